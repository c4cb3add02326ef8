"""Fused partial mixers (:mod:`qcpp.gadgets.junction`): exact costs, the same unitary, nothing left to Qiskit.

* ``test_every_junction_kind_reports_its_lowered_count``: every junction and rotation kind the compiler emits on
  a sweep of scenarios (grids 2x2..6x6 with 1..4 default robots, obstacles soft and hard, interior endpoints;
  both targets): reported cost == count of its own lowered gates (default and logical basis), at most the unfused
  leaves' count gate by gate, and fewer CNOTs somewhere.
* ``test_fused_layer_emits_the_partial_mixers_gates_in_order``: the pieces of a layer emit exactly the gates of
  its partial mixers, in order (so the high-level unitary is the unfused one).
* ``test_fused_lowered_mixer_equals_unfused_on_feasible_inputs``: the lowered fused layer and the partial mixers
  lowered one by one give the same state (1e-8) on every feasible assignment of small scenarios, ancillas clean.
* ``test_qiskit_o3_never_beats_our_lowering``: Qiskit's transpiler at optimization level 3 on our high-level
  circuit (the converter of ``benchmarks/mixer_cost.py``) finds no CX our lowering leaves.
"""

from __future__ import annotations

import itertools
import sys
from pathlib import Path

import pytest

from qcpp.gadgets.junction import MixerJunction, MixerRotation, RotationKind, mixer_pieces
from qcpp.gadgets.partial_mixer import ParityPartialMixer, partial_mixer
from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_circuit, qaoa_plan
from qcpp.problem.grid import Grid
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Objective, Robot, Scenario
from qcpp.simulate.sparse import simulate_sparse

from .gadgets_test import sweep_scenarios

TOL = 1e-8


def _lowered(gates: list, n: int, basis: frozenset[str] | None = None) -> Cost:
    c = Circuit([("q", n)], [Section("g", tuple(gates))])
    return Cost.count((lower(c) if basis is None else lower(c, basis)).gates)


def _layer(s: Scenario, target: str = "nisq") -> list[ParityPartialMixer]:
    out = []
    for r in range(s.num_robots):
        for q in s.grid.plaquettes:
            m = partial_mixer(s, r, q, 0.7, s.num_variables, "exact", target)  # type: ignore[arg-type]
            if m is not None:
                out.append(m)
    return out  # type: ignore[return-value]


def test_every_junction_kind_reports_its_lowered_count() -> None:
    seen: dict = {}
    for s, target in itertools.product(sweep_scenarios(), ("nisq", "ft")):
        mixers = _layer(s, target)
        width = s.num_variables + max((m.num_temps for m in mixers), default=0)
        for g in mixer_pieces(mixers):
            if g.kind not in seen:
                seen[g.kind] = (g, width)
    junctions = [g for g, _ in seen.values() if isinstance(g, MixerJunction)]
    assert len(junctions) >= 100
    assert {g.kind for g, _ in seen.values() if isinstance(g, MixerRotation)} == {
        RotationKind("mixer_rotation", "ccrx"),
        RotationKind("mixer_rotation", "crx"),
    }
    saved = []
    for g, width in seen.values():
        gates = g.emit()
        assert g.cost() == _lowered(gates, width), g.kind
        assert g.logical_cost() == _lowered(gates, width, LOGICAL_BASIS), g.kind
        if isinstance(g, MixerJunction):
            unfused = []
            if g.left is not None:
                unfused.append(Section("tail", tuple(g.left.parts()[2])))
            if g.right is not None:
                unfused.append(Section("head", tuple(g.right.parts()[0])))
            leaves = Cost.count(lower(Circuit([("q", width)], unfused)).gates).to_dict()
            assert all(leaves.get(name, 0) >= n for name, n in g.cost().items), g.kind  # fusing only removes
            saved.append(leaves.get("cx", 0) - g.cost().cx)
    assert any(saved)  # and somewhere it removes CNOTs


def test_fused_layer_emits_the_partial_mixers_gates_in_order() -> None:
    for s in [default_scenario(4, 4, 2), sweep_scenarios()[-1]]:
        mixers = _layer(s)
        assert [gate for g in mixer_pieces(mixers) for gate in g.emit()] == [gate for m in mixers for gate in m.emit()]


def _small_scenarios() -> list[Scenario]:
    g = Grid(3, 4)
    return [
        default_scenario(3, 3, 1),
        default_scenario(3, 3, 2),
        Scenario(g, (Robot((0, 0), (2, 3)),), ((1, 1),), Objective(obstacles="soft")),
        Scenario(g, (Robot((1, 0), (2, 3)),), ((1, 2),), Objective(obstacles="hard")),
    ]


@pytest.mark.parametrize("s", _small_scenarios(), ids=lambda s: f"{s.grid.rows}x{s.grid.cols}/{s.num_robots}")
def test_fused_lowered_mixer_equals_unfused_on_feasible_inputs(s: Scenario) -> None:
    plan = qaoa_plan(s, 1)
    n = plan.num_qubits
    regs = [("q", n)]
    fused = lower(Circuit(regs, [Section("m", tuple(g.emit())) for name, g in plan.sections() if name == "mixer_0"]))
    beta = Angle.symbol("beta_0")
    mixers = [partial_mixer(s, r, q, beta, s.num_variables) for r in range(s.num_robots) for q in s.grid.plaquettes]
    unfused = lower(Circuit(regs, [Section("m", tuple(m.emit())) for m in mixers if m is not None]))
    assert Cost.count(fused.gates).cx <= Cost.count(unfused.gates).cx
    bound = fused.bind({"beta_0": 0.83})
    ref = unfused.bind({"beta_0": 0.83})
    paths = [enumerate_paths(s, r) for r in range(s.num_robots)]
    for combo in itertools.islice(itertools.product(*paths), 40):
        start = 0
        for r, path in enumerate(combo):
            for k in range(s.num_variables):
                robot, e = s.variable_of(k)
                if robot == r and (path >> e) & 1:
                    start |= 1 << k
        got, want = simulate_sparse(bound, start), simulate_sparse(ref, start)
        assert all(k >> s.num_variables == 0 for k in got)  # every ancilla back in |0>
        for k in set(got) | set(want):
            assert abs(got.get(k, 0) - want.get(k, 0)) < TOL


def _qiskit_helpers():  # type: ignore[no-untyped-def]
    # the benchmark's own converter and transpile call, so that the test measures what the table prints
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    try:
        import mixer_cost
    finally:
        sys.path.pop(0)
    return mixer_cost


def _qiskit_cases() -> list[tuple[str, Scenario]]:
    g = Grid(5, 5)
    obstacles = ((1, 3), (2, 2))
    robots = (Robot((0, 0), (4, 4)), Robot((0, 4), (4, 0)))
    return [
        ("3x3/1", default_scenario(3, 3, 1)),
        ("4x4/2", default_scenario(4, 4, 2)),
        ("5x5/2 obst soft", Scenario(g, robots, obstacles)),
        ("5x5/2 obst hard", Scenario(g, robots, obstacles, Objective(obstacles="hard"))),
    ]


@pytest.mark.parametrize("label, s", _qiskit_cases(), ids=[c[0] for c in _qiskit_cases()])
def test_qiskit_o3_never_beats_our_lowering(label: str, s: Scenario) -> None:
    pytest.importorskip("qiskit")
    mixer_cost = _qiskit_helpers()
    high = qaoa_circuit(s, 1)
    ours = Cost.count(lower(high).gates).cx
    assert ours == qaoa_plan(s, 1).cost().cx
    theirs, _ = mixer_cost.qiskit_cx(high)
    assert theirs >= ours, (label, theirs, ours)


@pytest.mark.parametrize("target", ["nisq", "ft"])
def test_unfused_plan_reports_its_lowered_count_and_fusion_only_saves(target: str) -> None:
    s = _small_scenarios()[-1]
    fused = qaoa_plan(s, 2, PlanOptions(target=target))  # type: ignore[arg-type]
    unfused = qaoa_plan(s, 2, PlanOptions(target=target, fuse=False))  # type: ignore[arg-type]
    assert unfused.cost() == Cost.count(lower(unfused.circuit()).gates)
    assert fused.cost() == Cost.count(lower(fused.circuit()).gates)
    saved = unfused.cost().to_dict()
    for name, k in fused.cost().items:
        assert k <= saved.get(name, 0), name
    assert fused.cost().total < unfused.cost().total


@pytest.mark.parametrize("s", _small_scenarios()[1:], ids=lambda s: f"{s.grid.rows}x{s.grid.cols}/{s.num_robots}")
def test_fused_circuit_matches_the_subspace_simulator(s: Scenario) -> None:
    """The whole fused circuit (p = 2, lowered) against :class:`qcpp.simulate.subspace.SubspaceQAOA`, every feasible
    assignment, to 1e-8; every ancilla back in |0>."""
    from qcpp.simulate.validate import validate

    report = validate(s, p=2, backend="sparse", seed=11)
    assert report.passed and report.max_amplitude_error < TOL, report
