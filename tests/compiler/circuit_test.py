"""Tests for qcpp.ir.circuit: layout, sections, builder, transformations."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, CircuitBuilder, Register, Section
from qcpp.ir.gates import Gate, ccx, cx, h, mcx, rx, rz, rzz, t, x
from qcpp.simulate.statevector import circuit_unitary
from qcpp.testing import circuits

G0, B0, G1, B1 = (Angle.symbol(n) for n in ("gamma_0", "beta_0", "gamma_1", "beta_1"))


def small_circuit() -> Circuit:
    b = CircuitBuilder([Register("data", 3), Register("anc", 1)])
    b.append([h(q) for q in range(3)], section="initial_state")
    b.append(rzz(2 * G0, 0, 1), section="phase_0")
    b.append(rz(G0, 2))
    b.append(rx(B0, 0), section="mixer_0")
    b.append(rzz(G1 + 0.5, 1, 2), section="phase_1")
    b.append(rx(2 * B1, 3), section="mixer_1")
    return b.build()


def test_layout() -> None:
    c = small_circuit()
    assert c.num_qubits == 4
    assert c.qubits_of("data") == range(0, 3)
    assert c.qubits_of("anc") == range(3, 4)
    assert c.register("anc") == Register("anc", 1)
    assert c.has_register("data") and not c.has_register("work")
    with pytest.raises(KeyError):
        c.qubits_of("work")


def test_register_validation() -> None:
    with pytest.raises(ValueError):
        Register("bad name", 1)
    with pytest.raises(ValueError):
        Register("data", -1)
    with pytest.raises(ValueError):
        Circuit([("data", 1), ("data", 2)])


def test_builder_sections() -> None:
    c = small_circuit()
    assert [s.name for s in c.sections] == ["initial_state", "phase_0", "mixer_0", "phase_1", "mixer_1"]
    assert [len(s) for s in c.sections] == [3, 2, 1, 1, 1]
    assert all(type(s.gates) is tuple for s in c.sections)
    assert len(c) == 8
    assert list(c.gates) == [g for s in c.sections for g in s.gates]
    assert list(c) == list(c.gates)


def test_builder_default_section_and_reopening() -> None:
    b = CircuitBuilder([("data", 2)])
    b.append(h(0))
    b.append(x(1), section="a")
    b.append(x(0), section="main")  # a later section may reuse a name
    c = b.build()
    assert [s.name for s in c.sections] == ["main", "a", "main"]
    assert [(s.name, [g.name for g in s.gates]) for s in c.sections] == [("main", ["h"]), ("a", ["x"]), ("main", ["x"])]


def test_builder_rejects_bad_input() -> None:
    b = CircuitBuilder([("data", 2)])
    with pytest.raises(TypeError):
        b.append([h(0), "h 1"])  # type: ignore[list-item]
    with pytest.raises(ValueError):
        b.append(Gate("foo", (0,)))
    with pytest.raises(ValueError):
        b.append(h(0), section="not a name")
    b.append(h(0), section="s")
    assert len(b.build()) == 1  # the rejected batch left nothing behind
    b.append(cx(0, 2))
    with pytest.raises(ValueError, match="qubit 2"):
        b.build()


def test_builder_grows_layout() -> None:
    b = CircuitBuilder([("data", 2)])
    anc = b.add_register(("anc", 2))
    assert anc == range(2, 4) and b.num_qubits == 4 and b.qubits_of("anc") == anc
    b.append(ccx(0, 1, 3), section="s")
    c = b.build()
    assert len(c) == 1 and c.num_qubits == 4 and c.sections[0].name == "s"


def test_section_names_are_identifiers() -> None:
    with pytest.raises(ValueError):
        Section("phase 0\nh q[0];", [])
    assert Section("mixer_0").gates == ()


def test_circuit_constructor_checks() -> None:
    with pytest.raises(ValueError):
        Circuit([("data", 1)], [Section("s", [cx(0, 1)])])
    with pytest.raises(TypeError):
        Circuit([("data", 1)], [("s", [h(0)])])  # type: ignore[list-item]
    with pytest.raises(ValueError):
        Circuit([("data", 1)], []).compose(Circuit([("data", 3)], [Section("s", [h(2)])]))


def test_symbols_sorted_by_layer_then_gamma_before_beta() -> None:
    assert small_circuit().symbols == ("gamma_0", "beta_0", "gamma_1", "beta_1")


def test_bind() -> None:
    c = small_circuit()
    partial = c.bind({"gamma_0": 0.25, "beta_1": 1.0})
    assert partial.symbols == ("beta_0", "gamma_1")
    assert partial.sections[1].gates[0].params == (0.5,)
    assert type(partial.sections[1].gates[0].params[0]) is float
    full = partial.bind({"beta_0": 2, "gamma_1": 0.5})
    assert full.symbols == ()
    assert [g.params for g in full.gates if g.params] == [(0.5,), (0.25,), (2.0,), (1.0,), (2.0,)]
    assert c.symbols == ("gamma_0", "beta_0", "gamma_1", "beta_1")  # original untouched
    # a fresh circuit (no cached symbols) agrees
    assert Circuit(full.registers, full.sections).symbols == ()


def test_count_ops() -> None:
    c = small_circuit()
    assert c.count_ops() == {"h": 3, "rzz": 2, "rx": 2, "rz": 1}


def test_inverse_reverses_sections_and_gates() -> None:
    c = Circuit([("data", 2)], [Section("a", [h(0), t(1)]), Section("b", [cx(0, 1)])])
    inv = c.inverse()
    assert [s.name for s in inv.sections] == ["b", "a"]
    assert list(inv.gates) == [cx(0, 1), t(1).inverse(), h(0)]
    assert inv.inverse() == c


def test_compose_layouts() -> None:
    a = Circuit([("data", 2)], [Section("a", [h(0)])])
    b = Circuit([("data", 2), ("anc", 1)], [Section("b", [cx(1, 2)])])
    ab = a.compose(b)
    assert ab.registers == b.registers and [s.name for s in ab.sections] == ["a", "b"]
    assert b.compose(a).registers == b.registers
    with pytest.raises(ValueError):
        a.compose(Circuit([("other", 2)]))


def test_equality_and_repr() -> None:
    assert small_circuit() == small_circuit()
    assert small_circuit() != small_circuit().bind({"gamma_0": 1.0})
    assert "data[3]" in repr(small_circuit())
    with pytest.raises(TypeError):
        hash(small_circuit())


def test_mcx_in_circuit_keeps_ctrl_state() -> None:
    c = Circuit([("data", 4)], [Section("m", [mcx([0, 1, 2], 3, "010")])])
    assert next(c.gates).ctrl_state == "010"


@settings(max_examples=40, deadline=None)
@given(circuits(max_qubits=4, max_gates=8, symbolic=True))
def test_inverse_composed_with_circuit_is_identity(c: Circuit) -> None:
    values = {"gamma_0": 0.3, "beta_0": -1.1, "gamma_1": 0.7}
    u = circuit_unitary(c.compose(c.inverse()), values)
    np.testing.assert_allclose(u, np.eye(2**c.num_qubits), atol=1e-9)
