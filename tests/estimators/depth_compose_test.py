"""Exact depth by composing per-gadget transfer profiles == depths of the compiled circuit; carry over p; policy."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.estimators.crosscheck import crosscheck_cases, with_obstacles
from qcpp.estimators.depth import Depth, depths
from qcpp.estimators.depth_compose import (
    LayeredDepth,
    MatrixStep,
    anchored_profile,
    gadget_depth,
    lowered_gates,
    transfer_profile,
)
from qcpp.estimators.estimate import (
    EstimateOptions,
    _arithmetic_depth_bound,
    compiled_depth,
    depth_bound,
    estimate_depth,
    exact_depth,
    layer_costs,
)
from qcpp.gadgets.phase_sums import SumsKind
from qcpp.ir.circuit import Register
from qcpp.ir.cost import Cost
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.plan.phase_classes import phase_layer
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.errors import ScenarioError
from qcpp.problem.presets import default_scenario, max_default_robots
from qcpp.problem.scenario import Scenario, scenario_from_dict

OPTIONS = [
    PlanOptions(),
    PlanOptions(rule="paper"),
    PlanOptions(target="ft"),
    PlanOptions(phase="whole-space"),
    PlanOptions(optimize="depth"),
    PlanOptions(initial="representatives"),
    PlanOptions(ancilla_budget=0),
    PlanOptions(first_phase=False),  # the first layer without its phase separator: a frontier of its own
]


def _defaults(max_side: int, max_robots: int) -> list[Scenario]:
    return [
        default_scenario(r, c, k)
        for r in range(2, max_side + 1)
        for c in range(2, max_side + 1)
        for k in range(1, max_robots + 1)
        if k <= max_default_robots(r, c)
    ]


# --- the max-plus composition itself, on random gate lists -------------------------------------------------------
GATE = st.one_of(
    st.tuples(st.sampled_from(["h", "x", "rz", "t"]), st.integers(0, 5).map(lambda q: (q,))),
    st.lists(st.integers(0, 5), min_size=2, max_size=4, unique=True).map(lambda qs: ("cx" if len(qs) == 2 else "mcx",
                                                                                       tuple(qs))),
)  # fmt: skip


@settings(max_examples=100, deadline=None)
@given(st.lists(GATE, max_size=40), st.lists(st.integers(0, 40), max_size=4))
def test_composing_transfer_profiles_of_any_split_equals_depths(gates: list, cuts: list[int]) -> None:
    """Any cut of a gate list into consecutive pieces, each a transfer matrix on its own qubits, composes to the
    ASAP depths of the whole list."""
    n = 6
    bounds = sorted({0, len(gates), *(min(c, len(gates)) for c in cuts)})
    steps = []
    for a, b in zip(bounds, bounds[1:]):
        piece = gates[a:b]
        qubits = list(dict.fromkeys(q for g in piece for q in g[1]))
        idx = np.concatenate([np.asarray(qubits, dtype=np.intp) + t * n for t in range(3)])
        steps.append(MatrixStep(idx, transfer_profile(piece, qubits)))
    got = LayeredDepth(n, steps, []).depth(0)
    assert got == depths(gates, n)


def test_transfer_profile_of_a_small_gadget() -> None:
    m = transfer_profile([("h", (0,)), ("cx", (0, 1)), ("rz", (1,), (0.5,)), ("ccx", (1, 2, 3))], [0, 1, 2, 3])
    no = -(1 << 40)
    # all gates: h, cx, rz, ccx from qubit 0 to 1, 2, 3; qubit 0 is left after the cx; 2, 3 never reach it
    assert m[:4, :4].tolist() == [[2, 4, 4, 4], [1, 3, 3, 3], [no, 1, 1, 1], [no, 1, 1, 1]]
    # two-qubit gates: the cx adds a level, the ccx only synchronises its qubits
    assert m[4:8, 4:8].tolist() == [[1, 1, 1, 1], [1, 1, 1, 1], [no, 0, 0, 0], [no, 0, 0, 0]]
    # rotations: the rz on qubit 1, reached from qubits 0 and 1
    assert m[8:, 8:].tolist() == [[0, 1, 1, 1], [0, 1, 1, 1], [no, 0, 0, 0], [no, 0, 0, 0]]
    assert m[:4, 4:].max() == no  # the three depths do not mix


# --- exact by composition == compiled -----------------------------------------------------------------------------
@pytest.mark.parametrize("s", _defaults(4, 3), ids=lambda s: s.name)
def test_exact_depth_equals_the_compiled_circuit_small_defaults(s: Scenario) -> None:
    for p in (0, 1, 2):
        assert exact_depth(s, p) == compiled_depth(s, p)


@pytest.mark.parametrize("options", OPTIONS, ids=repr)
def test_exact_depth_equals_the_compiled_circuit_every_option(options: PlanOptions) -> None:
    scenarios = [default_scenario(3, 3, 1), default_scenario(3, 4, 2)]
    scenarios += [s for mode in ("soft", "hard") if (s := with_obstacles(default_scenario(4, 4, 2), mode))]
    for s in scenarios:
        for p in (0, 1, 2):
            assert exact_depth(s, p, options) == compiled_depth(s, p, options), (s.name, p)


@st.composite
def small_scenarios(draw: st.DrawFn) -> Scenario:
    rows, cols = draw(st.integers(2, 4)), draw(st.integers(2, 4))
    nodes = [(r, c) for r in range(rows) for c in range(cols)]
    obstacles = draw(st.lists(st.sampled_from(nodes), max_size=2, unique=True)) if rows * cols > 6 else []
    free = [n for n in nodes if n not in obstacles]
    k = draw(st.integers(1, min(3, len(free) // 2)))
    starts = draw(st.lists(st.sampled_from(free), min_size=k, max_size=k, unique=True))
    goals = draw(st.lists(st.sampled_from(free), min_size=k, max_size=k, unique=True))
    mode = draw(st.sampled_from(["soft", "hard"]))
    return scenario_from_dict(
        {
            "grid": {"rows": rows, "cols": cols, "obstacles": [list(o) for o in obstacles]},
            "robots": [{"start": list(a), "goal": list(b)} for a, b in zip(starts, goals)],
            "objective": {"obstacles": mode},
        }
    )


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(st.data())
def test_exact_depth_equals_the_compiled_circuit_random_scenarios(data: st.DataObject) -> None:
    try:
        s = data.draw(small_scenarios())
    except ScenarioError:
        return  # an infeasible random placement: nothing to compile
    options = data.draw(st.sampled_from(OPTIONS[:3]))
    p = data.draw(st.integers(1, 2))
    try:
        want = compiled_depth(s, p, options)
    except (ScenarioError, ValueError):
        return  # the compiler refuses it too (e.g. no feasible path)
    assert exact_depth(s, p, options) == want


def _everywhere() -> list[tuple[str, Scenario, int, PlanOptions]]:
    """Defaults 2x2..6x6 with 1..4 robots at p = 1..3 that the full cross-check does not compile: its cases
    (obstacles, hard mode, rules, targets, example files) have their exact depths, rotation depth included, checked
    against the compiled circuit by ``crosscheck`` in ``test_gadget_counts_equal_compiled_counts_everywhere``."""
    crosschecked = {(c.scenario, c.p, c.plan) for c in crosscheck_cases(full=True)}
    cases = [(f"{s.name} p{p}", s, p, DEFAULT_PLAN) for s in _defaults(6, 4) for p in (1, 2, 3)]
    return [case for case in cases if case[1:] not in crosschecked]


@pytest.mark.heavy
@pytest.mark.parametrize("part", range(3))
def test_exact_depth_equals_the_compiled_circuit_everywhere(part: int) -> None:
    """:func:`_everywhere`'s cases."""
    cases = _everywhere()[part::3]
    assert [label for label, s, p, o in cases if exact_depth(s, p, o) != compiled_depth(s, p, o)] == []


# --- the premise of the per-kind cache ------------------------------------------------------------------------------
@pytest.mark.parametrize("options", OPTIONS[:3], ids=repr)
def test_anchored_profiles_equal_each_gadgets_own(options: PlanOptions) -> None:
    """Gadgets of one kind have the same lowered gates up to their slot qubits: the cached profile of a kind is
    every gadget's own profile (on its slots), on every gadget of several scenarios."""
    scenarios = [default_scenario(r, c, k) for r, c, k in [(3, 3, 2), (4, 5, 3), (5, 4, 6)]]
    scenarios += [s for mode in ("soft", "hard") if (s := with_obstacles(default_scenario(5, 5, 2), mode))]
    checked = 0
    for s in scenarios:
        plan = qaoa_plan(s, 1, options)
        regs = tuple(plan.registers)
        for _, g in plan.sections():
            hit = anchored_profile(g, regs)
            if hit is None:
                continue
            qubits, matrix = hit
            assert np.array_equal(matrix, transfer_profile(lowered_gates(g, regs), qubits))
            checked += 1
    assert checked > 50


def test_gadget_depth_is_the_gadgets_own_depth() -> None:
    s = default_scenario(4, 4, 2)
    plan = qaoa_plan(s, 1)
    regs = tuple(plan.registers)
    n = sum(r.size for r in regs)
    for _, g in list(plan.sections())[:12]:
        assert gadget_depth(g, regs) == depths(lowered_gates(g, regs), n)


# --- carrying the frontier over p ----------------------------------------------------------------------------------
def test_frontier_carried_over_p_equals_a_fresh_computation() -> None:
    s = default_scenario(4, 3, 3)
    plan = qaoa_plan(s, 1)
    regs = tuple(plan.registers)
    carried = LayeredDepth.from_sections(plan.sections(), regs)
    in_turn = [carried.depth(p) for p in range(5)]
    for p in (4, 2, 0, 3):
        fresh = LayeredDepth.from_sections(plan.sections(), regs).depth(p)
        assert carried.depth(p) == fresh == in_turn[p] == compiled_depth(s, p)
    with pytest.raises(ValueError):
        carried.depth(-1)


def test_frontier_without_the_first_phase_separator_carries_the_first_layer_alone() -> None:
    s, options = default_scenario(4, 3, 2), PlanOptions(first_phase=False)
    plan = qaoa_plan(s, 2, options)  # layer 0 (no phase separator) and layer 1, which repeats
    carried = LayeredDepth.from_sections(plan.sections(), tuple(plan.registers))
    assert [carried.depth(p) for p in range(4)] == [compiled_depth(s, p, options) for p in range(4)]
    assert carried.depth(1) != compiled_depth(s, 1)  # the check can fail: with it, layer 0 is deeper


# --- the bound and the policy ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("options", OPTIONS, ids=repr)
def test_bound_is_above_exact_and_exact_at_p0(options: PlanOptions) -> None:
    scenarios = _defaults(4, 4)[::3] + [
        s for m in ("soft", "hard") if (s := with_obstacles(default_scenario(4, 4, 2), m))
    ]
    for s in scenarios:
        e0, b0 = exact_depth(s, 0, options), depth_bound(s, 0, options)
        assert (b0.depth, b0.two_qubit_depth, b0.rotation_depth) == (e0.depth, e0.two_qubit_depth, e0.rotation_depth)
        for p in (1, 3):
            e, b = exact_depth(s, p, options), depth_bound(s, p, options)
            assert b.kind == "bound"
            assert b.depth >= e.depth and b.two_qubit_depth >= e.two_qubit_depth
            assert b.rotation_depth >= e.rotation_depth


@pytest.mark.parametrize("rows, cols, robots", [(5, 5, 2), (7, 6, 4), (9, 9, 8)])
def test_arithmetic_bound_from_its_shape_is_above_the_gadgets_own_depth(rows: int, cols: int, robots: int) -> None:
    """The balance arithmetic's bound (its forms' trees side by side) holds for the gadget itself, and its halves and
    phase add up to its cost."""
    s = default_scenario(rows, cols, robots)
    layer = phase_layer(s)
    assert layer is not None
    balance = next(k.example for k, _ in layer.kinds() if isinstance(k.key, SumsKind))
    shape = balance.shape
    assert Cost.sum(c + u for c, u in shape.halves()) + shape.phase_cost() == shape.cost()
    gadget = balance.build()
    regs = (Register("q", s.num_variables + layer.num_ancillas),)
    own, bound = gadget_depth(gadget, regs), _arithmetic_depth_bound(shape)
    assert bound.depth >= own.depth and bound.two_qubit_depth >= own.two_qubit_depth
    assert bound.rotation_depth >= own.rotation_depth
    assert bound.depth < gadget.cost().total  # tighter than counting every gate


@pytest.mark.parametrize("rows, cols, robots", [(6, 6, 3), (7, 5, 4), (8, 8, 2), (5, 9, 6), (9, 9, 8)])
def test_bound_is_above_exact_on_larger_grids(rows: int, cols: int, robots: int) -> None:
    """Grids whose phase separator is counted by classes (its parts' own depths enter the bound)."""
    s = default_scenario(rows, cols, robots)
    for p in (1, 4):
        e, b = exact_depth(s, p), depth_bound(s, p)
        assert b.depth >= e.depth and b.two_qubit_depth >= e.two_qubit_depth
        assert b.rotation_depth >= e.rotation_depth


def test_auto_is_exact_up_to_the_budget_on_one_layer_whatever_p() -> None:
    s = default_scenario(4, 4, 2)
    size = layer_costs(s, DEFAULT_PLAN).cost(1).total
    for p in (1, 5, 40):
        at = estimate_depth(s, p, EstimateOptions(depth_budget=size))
        below = estimate_depth(s, p, EstimateOptions(depth_budget=size - 1))
        assert at == exact_depth(s, p) and at.kind == "exact"
        assert below == depth_bound(s, p) and below.kind == "bound"
    assert estimate_depth(s, 2, EstimateOptions(depth="none")) is None
    assert estimate_depth(s, 2, EstimateOptions(depth="exact", depth_budget=0)) == exact_depth(s, 2)


def test_depth_of_an_empty_circuit() -> None:
    assert LayeredDepth(0, [], []).depth(3) == Depth()


# --- every registered gadget example -------------------------------------------------------------------------------
def test_own_depth_of_every_registered_gadget_example_is_its_lowered_depth() -> None:
    from qcpp.lowering.passes import WORK_REGISTER
    from qcpp.plan.call_graph import Deferred, GadgetKind
    from qcpp.plan.gadget_examples import gadget_examples

    for label, g in gadget_examples():
        gadget = g.build() if isinstance(g, Deferred) else g
        kind = GadgetKind.of(gadget)
        top = max((q + 1 for gate in gadget.emit() for q in gate.qubits), default=1)
        regs = (Register("q", top), Register(WORK_REGISTER, kind.work)) if kind.work else (Register("q", top),)
        assert gadget_depth(gadget, regs) == depths(lowered_gates(gadget, regs), sum(r.size for r in regs)), label
