"""Tests for qcpp.ir.angles."""

from __future__ import annotations

import math
import pickle

import pytest
from hypothesis import given
from hypothesis import strategies as st

from qcpp.ir.angles import Angle, UnboundParameterError, format_angle, format_float, symbol_sort_key

finite = st.floats(allow_nan=False, allow_infinity=False, width=64)
small = st.floats(-1e6, 1e6, allow_nan=False)
names = st.sampled_from(["gamma_0", "beta_0", "gamma_1", "beta_1", "theta"])


@st.composite
def angles(draw: st.DrawFn) -> Angle:
    terms = draw(st.lists(st.tuples(names, small), max_size=3))
    return Angle(draw(small), terms)


def test_symbol_and_constant_parts() -> None:
    a = Angle.symbol("gamma_0", 2.5) + 0.1
    assert a.constant == 0.1
    assert a.terms == (("gamma_0", 2.5),)
    assert a.symbols == ("gamma_0",)
    assert not a.is_bound
    assert Angle(3.0).is_bound


def test_canonical_form_merges_and_drops_zero_terms() -> None:
    a = Angle(0.0, [("b", 1.0), ("a", 2.0), ("b", -1.0)])
    assert a.terms == (("a", 2.0),)
    assert Angle.symbol("x", 0.0).is_bound
    assert (Angle.symbol("x") - Angle.symbol("x")).is_bound
    assert Angle(1.0, {"a": 1.0, "b": 2.0}) == Angle(1.0, [("b", 2.0), ("a", 1.0)])


def test_arithmetic() -> None:
    g = Angle.symbol("gamma_0")
    b = Angle.symbol("beta_0")
    e = 2 * g - b / 2 + 1 - (-g)
    assert e.terms == (("beta_0", -0.5), ("gamma_0", 3.0))
    assert e.constant == 1.0
    assert (1 - g).terms == (("gamma_0", -1.0),)
    assert (1 - g).constant == 1.0
    assert (g * 0).is_bound
    assert +g is g
    assert g * Angle(2.0) == 2 * g
    assert g / Angle(2.0) == 0.5 * g


def test_nonaffine_operations_raise() -> None:
    g = Angle.symbol("gamma_0")
    with pytest.raises(TypeError):
        _ = g * g
    with pytest.raises(TypeError):
        _ = 1.0 / g  # type: ignore[operator]
    with pytest.raises(TypeError):
        _ = g + "x"  # type: ignore[operator]
    with pytest.raises(TypeError):
        _ = g * True


def test_invalid_symbol_names() -> None:
    for bad in ["", "1abc", "a-b", "a b"]:
        with pytest.raises(ValueError):
            Angle.symbol(bad)
    with pytest.raises(ValueError):
        Angle(0.0, [("no good", 1.0)])


def test_bind_partial_and_full() -> None:
    a = Angle.symbol("gamma_0", 2.0) + Angle.symbol("beta_0", 3.0) + 1.0
    partial = a.bind({"gamma_0": 0.5})
    assert partial.terms == (("beta_0", 3.0),)
    assert partial.constant == 2.0
    full = partial.bind({"beta_0": 1.0, "unused": 9.0})
    assert full.is_bound
    assert float(full) == 5.0
    assert a.bind({}) is a


def test_float_of_unbound_names_the_symbols() -> None:
    a = Angle.symbol("gamma_1") + Angle.symbol("beta_0")
    with pytest.raises(UnboundParameterError) as err:
        float(a)
    assert err.value.symbols == ("beta_0", "gamma_1")
    assert "beta_0" in str(err.value) and "gamma_1" in str(err.value)
    assert isinstance(err.value, ValueError)


def test_equality_and_hash_with_floats() -> None:
    assert Angle(0.5) == 0.5
    assert hash(Angle(0.5)) == hash(0.5)
    assert Angle.symbol("a") != 0.0
    assert len({Angle.symbol("a", 2.0), 2 * Angle.symbol("a")}) == 1


def test_immutable_and_picklable() -> None:
    a = Angle.symbol("gamma_0", 2.0) + 1
    with pytest.raises(AttributeError):
        a._const = 3.0  # type: ignore[misc]
    with pytest.raises(AttributeError):
        a.foo = 1  # type: ignore[attr-defined]
    assert pickle.loads(pickle.dumps(a)) == a


@given(angles(), angles(), small)
def test_arithmetic_agrees_with_numbers(a: Angle, b: Angle, f: float) -> None:
    values = {"gamma_0": 0.3, "beta_0": -1.7, "gamma_1": 2.0, "beta_1": 0.25, "theta": -0.5}

    def ev(x: Angle) -> float:
        return float(x.bind(values))

    tol = 1e-9 * (1 + abs(ev(a)) + abs(ev(b))) * (1 + abs(f))
    assert math.isclose(ev(a + b), ev(a) + ev(b), abs_tol=tol)
    assert math.isclose(ev(a - b), ev(a) - ev(b), abs_tol=tol)
    assert math.isclose(ev(a * f), ev(a) * f, abs_tol=tol)
    assert math.isclose(ev(-a), -ev(a), abs_tol=tol)
    assert a + b == b + a


def test_symbol_sort_key_orders_layers_then_gamma_before_beta() -> None:
    names_ = ["beta_1", "x", "gamma_1", "beta_0", "gamma_0", "gamma_10", "beta_2", "gamma_2", "alpha_0"]
    assert sorted(names_, key=symbol_sort_key) == [
        "gamma_0",
        "beta_0",
        "alpha_0",
        "gamma_1",
        "beta_1",
        "gamma_2",
        "beta_2",
        "gamma_10",
        "x",
    ]


@given(finite)
def test_format_float_round_trips_and_has_a_decimal_point(x: float) -> None:
    text = format_float(x)
    assert float(text) == x
    assert "." in text


def test_format_float_rejects_non_finite() -> None:
    for bad in [math.inf, -math.inf, math.nan]:
        with pytest.raises(ValueError):
            format_float(bad)


def test_format_angle() -> None:
    g = Angle.symbol("gamma_0")
    assert format_angle(2.5 * g + 0.1) == "2.5*gamma_0 + 0.1"
    assert format_angle(-g - 0.1) == "-gamma_0 - 0.1"
    assert format_angle(g - Angle.symbol("beta_0", 2.0)) == "-2.0*beta_0 + gamma_0"
    assert format_angle(Angle(0.0)) == "0.0"
    assert format_angle(1e-5, "qasm2") == "1.0e-05"
    assert format_angle(Angle(2.0), "qasm2") == "2.0"
    with pytest.raises(UnboundParameterError):
        format_angle(g, "qasm2")


@given(angles())
def test_format_angle_evaluates_back(a: Angle) -> None:
    values = {"gamma_0": 0.3, "beta_0": -1.7, "gamma_1": 2.0, "beta_1": 0.25, "theta": -0.5}
    text = format_angle(a, "qasm3")
    assert math.isclose(eval(text, {}, values), float(a.bind(values)), rel_tol=1e-12, abs_tol=1e-9)


