"""``qcpp.RoutingContext``: routing calls that share one answer from it what they routed before, with the same
result as without it."""

from __future__ import annotations

import pytest

import qcpp
from qcpp.routing.context import RoutingContext

S = qcpp.grid_scenario(2, 2, robots=1)


@pytest.mark.heavy  # compiles 2x2/1 on ibm_fez twice with every candidate (~8 CPU-s)
def test_an_estimate_after_a_compile_in_one_context_is_the_estimate_alone_and_routes_nothing_again() -> None:
    context = qcpp.RoutingContext()
    compiled = qcpp.compile(S, device="ibm_fez", context=context)
    assert len(context.compiles) == 1
    searched = dict(context.placements)
    shared = qcpp.estimate(S, device="ibm_fez", context=context)
    assert len(context.compiles) == 1 and context.placements == searched  # the compile itself was answered
    alone = qcpp.estimate(S, device="ibm_fez")
    assert shared.to_dict() == alone.to_dict()
    assert shared.routed_twoq == compiled.counts()["cz"]
    again = qcpp.compile(S, device="ibm_fez", context=context)
    assert again.circuit == compiled.circuit and again.initial_layout == compiled.initial_layout


@pytest.mark.heavy  # two compiles on ibm_fez (~3 CPU-s)
def test_a_different_call_is_compiled_afresh() -> None:
    context = qcpp.RoutingContext()
    a = qcpp.compile(S, device="ibm_fez", context=context, optimize_for="twoq")
    b = qcpp.compile(S, device="ibm_fez", context=context, bind={"gamma_0": 0.3, "beta_0": 0.7})
    assert len(context.compiles) == 2
    assert a.symbols and not b.symbols


def test_the_latest_compiles_are_kept_and_none_where_asked() -> None:
    context = RoutingContext(compiles_kept=2)
    for key in "abc":
        context.keep_compile(key, key.upper())
    assert list(context.compiles) == ["b", "c"]
    context.keep_compile("b", "B")  # kept again: now the latest
    context.keep_compile("d", "D")
    assert list(context.compiles) == ["b", "d"]
    none = RoutingContext(compiles_kept=0)
    none.keep_compile("a", "A")
    assert none.compiles == {}
    context.clear()
    assert context.compiles == {}


@pytest.mark.parametrize("call", [qcpp.compile, qcpp.estimate])
def test_a_context_that_is_not_one_is_refused_by_name(call: object) -> None:
    with pytest.raises(qcpp.OptionError, match=r"^context: expected a qcpp.RoutingContext or None, got dict$"):
        call(S, device="ibm_fez", context={})  # type: ignore[operator]


@pytest.mark.parametrize("call", [qcpp.compile, qcpp.estimate])
def test_a_context_without_a_device_is_refused_by_name(call: object) -> None:
    with pytest.raises(qcpp.OptionError, match=r"^context: applies with a device only \(no device given\)$"):
        call(S, context=qcpp.RoutingContext())  # type: ignore[operator]
