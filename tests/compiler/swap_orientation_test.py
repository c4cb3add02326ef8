"""SWAPs written the way round that lets their ``cx`` cancel (:mod:`qcpp.routing.swap_orientation`).

Evidence: on placement-search routings of the one-robot 3x3 and 2x3 circuits on heavy-hex:3, the oriented circuit
equals the routed one as an operator (statevector from random product states), keeps its gate and two-qubit counts
and layouts, and Qiskit's ``CommutativeCancellation`` removes at least as many ``cx`` from it; on one routing it removes
more. The doctest shows a SWAP turned round to meet a ``cx`` before it.
"""

from __future__ import annotations

import doctest
import importlib

import numpy as np
import pytest

from qcpp.hardware.device import get_device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import cx, rx, ry, t
from qcpp.layout.placement_search import search_route
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario
from qcpp.routing.qiskit_o3 import to_qiskit_lowered
from qcpp.routing.routed_circuit import RoutedCircuit
from qcpp.routing.swap_orientation import orient_swaps
from qcpp.simulate.statevector import simulate_statevector

BIND = {"gamma_0": 0.3, "beta_0": 0.7}


def test_doctests() -> None:
    result = doctest.testmod(importlib.import_module("qcpp.routing.swap_orientation"))
    assert result.failed == 0 and result.attempted > 0


def _cancelled(c: Circuit) -> int:
    from qiskit.transpiler import PassManager
    from qiskit.transpiler.passes import CommutativeCancellation

    return PassManager([CommutativeCancellation()]).run(to_qiskit_lowered(c)).count_ops().get("cx", 0)


def _used(routed: RoutedCircuit) -> list[int]:
    return sorted({q for g in routed.circuit.gates for q in g[1]} | set(routed.initial_layout))


def _compact(c: Circuit, used: list[int]) -> Circuit:
    index = {q: i for i, q in enumerate(used)}
    gates = [(g[0], tuple(index[q] for q in g[1]), g[2], g[3]) for g in c.gates]
    from qcpp.ir.gates import Gate

    return Circuit([("q", len(used))], [Section("s", [Gate(*g) for g in gates])])


@pytest.fixture(scope="module")
def routings() -> list[RoutedCircuit]:
    dev = get_device("heavy-hex:3")
    out = []
    for s in (default_scenario(3, 3, 1), default_scenario(2, 3, 1)):
        c = compile_scenario(s, 1, PlanOptions(fuse=False), lowered=True, bindings=BIND).circuit
        out.append(search_route(c, dev, layouts=4, seeds=2))
    return out


def test_same_operator_counts_and_layouts(routings: list[RoutedCircuit]) -> None:
    simulated = 0
    for routed in routings:
        oriented = orient_swaps(routed)
        assert oriented.initial_layout == routed.initial_layout and oriented.final_layout == routed.final_layout
        assert len(list(oriented.circuit.gates)) == len(list(routed.circuit.gates))
        assert oriented.circuit.count_ops() == routed.circuit.count_ops()
        assert [s.name for s in oriented.circuit.sections] == [s.name for s in routed.circuit.sections]
        used = _used(routed)
        if len(used) > 18:  # pragma: no cover - the statevector would be too large
            continue
        rng = np.random.default_rng(0)
        angles = rng.uniform(0, 3, size=(len(used), 2))
        prep = Section("prep", tuple(g for q in range(len(used)) for g in (ry(angles[q, 0], q), rx(angles[q, 1], q))))
        a, b = (_compact(r.circuit, used) for r in (routed, oriented))
        states = [simulate_statevector(Circuit(c.registers, [prep, *c.sections])) for c in (a, b)]
        assert np.allclose(states[0], states[1], atol=1e-9)
        simulated += routed.circuit != orient_swaps(routed).circuit
    assert simulated > 0  # the operator check ran on a routing that orientation changed


def test_cancellation_removes_at_least_as_many(routings: list[RoutedCircuit]) -> None:
    gains = []
    for routed in routings:
        before, after = _cancelled(routed.circuit), _cancelled(orient_swaps(routed).circuit)
        assert after <= before
        gains.append(before - after)
    assert max(gains) > 0


def test_a_swap_is_turned_to_meet_its_partner() -> None:
    c = Circuit([("q", 3)], [Section("s", [cx(1, 0), t(1), cx(0, 1), cx(1, 0), cx(0, 1)])])
    r = RoutedCircuit(c, get_device("grid:1x3"), (0, 1), (1, 0), 1, (0, 1))
    oriented = orient_swaps(r)
    assert [g[1] for g in oriented.circuit.gates if g[0] == "cx"] == [(1, 0), (1, 0), (0, 1), (1, 0)]
    assert _cancelled(oriented.circuit) == 2 and _cancelled(c) == 4
