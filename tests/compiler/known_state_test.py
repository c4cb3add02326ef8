"""A routed circuit simplified for the all-|0> start (:mod:`qcpp.routing.known_state`).

Evidence: on random circuits of ``cx``, ``x``, ``h``, ``rx``, ``rz``, ``s``, ``t``, ``cz``, ``rzz`` and SWAPs
(hypothesis) and on placement-search routings of the one-robot 2x3 and 3x3 circuits on heavy-hex:3, the simplified
circuit prepares the same state from |0...0> as the input (statevector), keeps the layouts and section names and has
no more ``cx``; on the routings it removes many (the robots' start is a basis state). A circuit with a superposition
on every control keeps every ``cx``, and the doctests show a SWAP into |0> losing its third ``cx``.
"""

from __future__ import annotations

import doctest
import importlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.hardware.device import get_device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cx, cz, h, rx, rz, rzz, t, x
from qcpp.ir.gates import s as s_gate
from qcpp.layout.placement_search import search_route
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario
from qcpp.routing.known_state import from_zero
from qcpp.routing.routed_circuit import RoutedCircuit
from qcpp.simulate.statevector import simulate_statevector

BIND = {"gamma_0": 0.3, "beta_0": 0.7}


def test_doctests() -> None:
    result = doctest.testmod(importlib.import_module("qcpp.routing.known_state"))
    assert result.failed == 0 and result.attempted > 0


def _routed(gates: list[Gate], n: int) -> RoutedCircuit:
    c = Circuit([("q", n)], [Section("s", gates)])
    return RoutedCircuit(c, get_device("grid:1x2" if n == 2 else f"grid:1x{n}"), tuple(range(n)), tuple(range(n)), 0,
                         tuple(range(n)))  # fmt: skip


def _cx_count(c: Circuit) -> int:
    return sum(1 for g in c.gates if g[0] == "cx")


_N = 4
_gate = st.one_of(
    st.tuples(st.sampled_from(["x", "h", "t", "s", "rz", "rx"]), st.integers(0, _N - 1)),
    st.tuples(st.sampled_from(["cx", "swap", "cz", "rzz"]), st.integers(0, _N - 1), st.integers(1, _N - 1)),
)


def _build(spec: list[tuple]) -> list[Gate]:
    """The gates of ``spec``: every kind :func:`from_zero` tells apart (``x``; one-qubit diagonal ``t``, ``s``,
    ``rz``; other one-qubit ``h``, ``rx``; ``cx`` and SWAPs of three; two-qubit diagonal ``cz``, ``rzz``)."""
    gates: list[Gate] = []
    for item in spec:
        name, a = item[0], item[1]
        if len(item) == 3:
            b = (a + item[2]) % _N
            two = {"cx": [cx(a, b)], "swap": [cx(a, b), cx(b, a), cx(a, b)], "cz": [cz(a, b)],
                   "rzz": [rzz(0.61, a, b)]}  # fmt: skip
            gates += two[name]
        else:
            one = {"x": x(a), "h": h(a), "t": t(a), "s": s_gate(a), "rz": rz(0.37, a), "rx": rx(0.83, a)}
            gates.append(one[name])
    return gates


@settings(max_examples=300, deadline=None)
@given(st.lists(_gate, max_size=30))
def test_same_state_from_zero_and_never_more_cx(spec: list[tuple]) -> None:
    r = _routed(_build(spec), _N)
    z = from_zero(r)
    assert z.initial_layout == r.initial_layout and z.final_layout == r.final_layout and z.swaps == r.swaps
    assert _cx_count(z.circuit) <= _cx_count(r.circuit)
    assert np.allclose(simulate_statevector(z.circuit), simulate_statevector(r.circuit), atol=1e-9)


def test_controls_in_superposition_keep_every_cx() -> None:
    gates = [h(0), h(1), h(2), cx(0, 1), cx(1, 2), cx(2, 0), cx(0, 1)]
    r = _routed(gates, 3)
    assert from_zero(r) is r


def test_a_cx_on_a_basis_state_control_becomes_x_or_goes() -> None:
    r = _routed([x(0), cx(0, 1), cx(2, 1), h(2), cx(1, 2)], 3)
    assert [(g[0], g[1]) for g in from_zero(r).circuit.gates] == [("x", (0,)), ("x", (1,)), ("h", (2,)),
                                                                   ("x", (2,))]  # fmt: skip


@pytest.mark.parametrize(
    ("gates", "last"),
    [
        # cx 0 1 onto |0> relates x1 = x0; an x on either side flips the relation, so cx 1 0 leaves 0 in |1>
        ([h(0), cx(0, 1), x(0), cx(1, 0), cx(0, 3)], ("x", (3,))),
        ([h(0), cx(0, 1), x(1), cx(1, 0), cx(0, 3)], ("x", (3,))),
        # the relation goes when 1 changes otherwise (cx 2 1 from a superposition; h on 1) or 0 does (h on 0)
        ([h(0), cx(0, 1), h(2), cx(2, 1), cx(1, 0), cx(0, 3)], ("cx", (0, 3))),
        ([h(0), cx(0, 1), h(1), cx(1, 0), cx(0, 3)], ("cx", (0, 3))),
        ([h(0), cx(0, 1), h(0), cx(1, 0), cx(0, 3)], ("cx", (0, 3))),
    ],
)
def test_a_relation_between_two_qubits_holds_while_neither_changes_otherwise(
    gates: list[Gate], last: tuple[str, tuple[int, ...]]
) -> None:
    """The relations the random circuits rarely build and then break: a stale one would drop the last ``cx``."""
    r = _routed(gates, 4)
    z = from_zero(r)
    *_, final = z.circuit.gates
    assert (final[0], final[1]) == last
    assert np.allclose(simulate_statevector(z.circuit), simulate_statevector(r.circuit), atol=1e-9)

@pytest.fixture(scope="module")
def routings() -> list[RoutedCircuit]:
    dev = get_device("heavy-hex:3")
    out = []
    for s in (default_scenario(2, 3, 1), default_scenario(3, 3, 1)):
        c = compile_scenario(s, 1, PlanOptions(fuse=False), lowered=True, bindings=BIND).circuit
        out.append(search_route(c, dev, layouts=4, seeds=2))
    return out


def _used(routed: RoutedCircuit) -> list[int]:
    return sorted({q for g in routed.circuit.gates for q in g[1]} | set(routed.initial_layout))


def _compact(c: Circuit, used: list[int]) -> Circuit:
    index = {q: i for i, q in enumerate(used)}
    return Circuit([("q", len(used))], [Section("s", [Gate(g[0], tuple(index[q] for q in g[1]), g[2], g[3])
                                                      for g in c.gates])])  # fmt: skip


def test_routings_of_the_qaoa_circuit_lose_many_cx_and_keep_their_state(routings: list[RoutedCircuit]) -> None:
    simulated = 0
    for routed in routings:
        z = from_zero(routed)
        assert [s.name for s in z.circuit.sections] == [s.name for s in routed.circuit.sections]
        assert _cx_count(z.circuit) <= 0.9 * _cx_count(routed.circuit)
        used = _used(routed)
        if len(used) > 18:  # pragma: no cover - the statevector would be too large
            continue
        a, b = (simulate_statevector(_compact(c, used)) for c in (routed.circuit, z.circuit))
        assert np.allclose(a, b, atol=1e-9)
        simulated += 1
    assert simulated > 0
