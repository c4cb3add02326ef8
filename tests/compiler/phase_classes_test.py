"""Counting the phase separator by classes gives the plan's cost, logical cost, ancillas and gadget kinds."""

from __future__ import annotations

from collections import Counter
from typing import Any

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import lower
from qcpp.plan.call_graph import Deferred
from qcpp.plan.phase import phase_plan
from qcpp.plan.phase_choice import plan_score
from qcpp.plan.phase_classes import PhaseLayer, ising_count, phase_layer
from qcpp.problem.grid import Grid
from qcpp.problem.hamiltonian import ising_hamiltonian
from qcpp.problem.presets import default_scenario, max_default_robots
from qcpp.problem.scenario import Objective, Robot, Scenario, scenario_from_dict

TARGETS = ("nisq", "ft")
ALPHAS = [(1.0, 1.0, 1.0), (1.0, 0.5, 2.0), (2.0, 1.0, 0.0), (0.0, 1.0, 1.0), (1.0, 1.0, 0.25)]


def _summed(parts: list[tuple[Any, int]], logical: bool = False) -> Cost:
    return Cost.sum(n * (g.logical_cost() if logical else g.cost()) for g, n in parts)


def _same_as_plan(s: Scenario, target: str, optimize: str = "cx", budget: int | None = None) -> bool:
    """Whether the layer answered (``False``: it left the scenario to the plan); asserts it equals the plan."""
    layer = phase_layer(s, target, optimize=optimize, ancilla_budget=budget)
    if layer is None:
        return False
    plan = phase_plan(s, target=target, optimize=optimize, ancilla_budget=budget)  # type: ignore[arg-type]
    for logical in (False, True):  # the examples' own costs (a kind's cost is cached by its key)
        assert _summed([(k.example, n) for k, n in layer.kinds()], logical) == _summed(
            [(g, 1) for g in plan.gadgets("gamma")], logical
        )
    assert plan_score(layer.kinds(), target) == plan.score()  # type: ignore[arg-type]
    assert layer.num_ancillas == plan.num_ancillas
    kinds: Counter = Counter()
    for k, n in layer.kinds():
        kinds[k.key] += n
    assert kinds == Counter(g.kind for g in plan.gadgets("gamma"))
    return True


@pytest.mark.parametrize("target", TARGETS)
def test_representatives_emit_their_cost_on_the_layers_qubits(target: str) -> None:
    s = default_scenario(9, 7, 5)
    layer = phase_layer(s, target)
    assert layer is not None
    width = s.num_variables + layer.num_ancillas
    for k, _ in layer.kinds():
        g = k.example.build() if isinstance(k.example, Deferred) else k.example
        gates = g.emit()
        assert max(q for gate in gates for q in gate.qubits) < width
        assert Cost.count(lower(Circuit([("q", width)], [Section("s", tuple(gates))])).gates) == g.cost()


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("rows, cols", [(2, 9), (3, 3), (4, 7), (6, 6), (9, 8), (11, 11)])
def test_default_scenarios_equal_the_plan(rows: int, cols: int, target: str) -> None:
    answered = [_same_as_plan(default_scenario(rows, cols, k), target) for k in range(1, 9)
                if k <= max_default_robots(rows, cols)]  # fmt: skip
    if rows * cols >= 36:
        assert all(answered)  # only grids where the couplings alternative may win are left to the plan

def _random_robots(data: st.DataObject, rows: int, cols: int) -> list[Robot]:
    """1-4 robots with distinct random starts and distinct random goals (robots whose start is their goal dropped)."""
    nodes = [(r, c) for r in range(rows) for c in range(cols)]
    k = data.draw(st.integers(1, 4), label="robots")
    starts = data.draw(st.lists(st.sampled_from(nodes), min_size=k, max_size=k, unique=True), label="starts")
    goals = data.draw(st.lists(st.sampled_from(nodes), min_size=k, max_size=k, unique=True), label="goals")
    return [Robot(a, b) for a, b in zip(starts, goals) if a != b]


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_random_endpoints_and_objectives_equal_the_plan(data: st.DataObject) -> None:
    rows = data.draw(st.integers(2, 12), label="rows")
    cols = data.draw(st.integers(6, 12), label="cols")
    robots = _random_robots(data, rows, cols)
    objective = Objective(
        alpha=data.draw(st.sampled_from([(1.0, 1.0, 1.0), (1.0, 0.5, 2.0), (2.0, 1.0, 0.0), (1.0, 0.0, 1.0)])),
        balance=data.draw(st.sampled_from(["chain", "all-pairs"])),
        degree_target=data.draw(st.sampled_from(["exact", "paper"])),
        edge_length=data.draw(st.sampled_from([1.0, 2.5])),
    )
    if not robots:
        return
    s = Scenario(Grid(rows, cols), tuple(robots), objective=objective)
    for target in TARGETS:
        _same_as_plan(s, target)


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_random_scenarios_and_plan_options_equal_the_plan(data: st.DataObject) -> None:
    """The classes and the plan ask the same per-group decision (qcpp.plan.phase_choice) under every option a
    user can pass: a divergence in the choice of any class (visits, Hamming-weight merging, balance variant,
    ancilla budget) shows as a different cost, ancilla count or kind multiset."""
    rows = data.draw(st.integers(3, 9), label="rows")
    cols = data.draw(st.integers(3, 9), label="cols")
    robots = _random_robots(data, rows, cols)
    if not robots:
        return
    objective = Objective(
        alpha=data.draw(st.sampled_from([(1.0, 1.0, 1.0), (1.0, 0.5, 2.0), (2.0, 1.0, 0.0), (1.0, 0.0, 1.0)])),
        balance=data.draw(st.sampled_from(["chain", "all-pairs"])),
    )
    s = Scenario(Grid(rows, cols), tuple(robots), objective=objective)
    target = data.draw(st.sampled_from(TARGETS), label="target")
    optimize = data.draw(st.sampled_from(["cx", "depth"]), label="optimize")
    budget = data.draw(st.sampled_from([None, 0, 1, 2, 4, 8, 20, 60, 400]), label="budget")
    event(f"classes answered: {_same_as_plan(s, target, optimize, budget)}")


@pytest.mark.parametrize("target", TARGETS)
def test_budgets_and_depth_are_counted_where_the_choice_is_forced(target: str) -> None:
    big = default_scenario(10, 10, 3)
    need = phase_plan(big, target=target).num_ancillas  # type: ignore[arg-type]
    assert _same_as_plan(big, target, budget=need)  # the budget admits the cheapest plan: the classes answer
    assert _same_as_plan(big, target, budget=10 * need)
    assert not _same_as_plan(big, target, budget=50)  # the balance gets a smaller variant: the plan decides
    one = default_scenario(7, 6, 1)  # no visit group, no balance: the depth plan is the rotations
    assert _same_as_plan(one, target, optimize="depth")
    assert _same_as_plan(one, target, budget=0)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_ising_terms_by_classes_equal_the_hamiltonians(data: st.DataObject) -> None:
    """The whole-space phase separator counted by classes of nodes and edges (what the closed forms run with
    symbolic sides) has exactly the nonzero terms of the Ising Hamiltonian, for any endpoints and objective."""
    rows = data.draw(st.integers(2, 7), label="rows")
    cols = data.draw(st.integers(2, 7), label="cols")
    nodes = [(r, c) for r in range(rows) for c in range(cols)]
    k = data.draw(st.integers(1, min(4, len(nodes) // 2)), label="robots")
    starts = data.draw(st.lists(st.sampled_from(nodes), min_size=k, max_size=k, unique=True), label="starts")
    goals = data.draw(st.lists(st.sampled_from(nodes), min_size=k, max_size=k, unique=True), label="goals")
    robots = [Robot(a, b) for a, b in zip(starts, goals) if a != b]
    if not robots:
        return
    objective = Objective(
        alpha=data.draw(st.sampled_from(ALPHAS), label="alpha"),
        balance=data.draw(st.sampled_from(["chain", "all-pairs"])),
        degree_target=data.draw(st.sampled_from(["exact", "paper"])),
        edge_length=data.draw(st.sampled_from([1.0, 2.5])),
        free_weight=data.draw(st.sampled_from([-1.0, 0.0, 3.0])),
    )
    s = Scenario(Grid(rows, cols), tuple(robots), objective=objective)
    count, h = ising_count(s), ising_hamiltonian(s)
    assert count is not None
    assert (count.linear, count.couplings) == (len(list(h.linear_terms(1e-12))), h.num_quadratic_terms(1e-12))
    layer = phase_layer(s, representation="whole-space")
    plan = phase_plan(s, representation="whole-space")
    assert layer is not None
    assert _summed([(k.example, n) for k, n in layer.kinds()]) == _summed([(g, 1) for g in plan.gadgets("gamma")])
    assert [k.key for k, _ in layer.kinds()] == [g.kind for g in plan.gadgets("gamma")]


def test_left_to_the_plan() -> None:
    s = default_scenario(10, 10, 3)
    assert isinstance(phase_layer(s), PhaseLayer)
    assert isinstance(phase_layer(s, representation="whole-space"), PhaseLayer)
    for kwargs in ({"optimize": "depth"}, {"ancilla_budget": 50}):
        assert phase_layer(s, **kwargs) is None  # type: ignore[arg-type]
    obstacles = scenario_from_dict({"grid": {"rows": 6, "cols": 6, "obstacles": [[2, 2]]},
                                    "robots": [{"start": [0, 0], "goal": [5, 5]}]})  # fmt: skip
    assert phase_layer(obstacles) is None
    assert phase_layer(obstacles, representation="whole-space") is None


@pytest.mark.heavy
def test_every_default_scenario_up_to_16x16_equals_the_plan() -> None:
    """Every default scenario up to 10x10 with 1-8 robots (as many as fit), both targets; beyond, a fixed choice.

    Past 10 columns a larger grid adds more positions of the same classes (corner, edge, interior, a robot's
    neighbourhood), not new ones, and its 75 shapes cost over three times what all shapes up to 10x10 do, so for
    11-16 columns the rows are the thin strips (2, 3) and the near-square and square ones (``cols - 1``, ``cols``),
    with 1, 2, 3 and the most robots. Odd and even sizes both occur in each range.
    """
    for rows in range(2, 17):
        for cols in range(rows, 17):
            most = min(8, max_default_robots(rows, cols))
            robots = range(1, most + 1)
            if cols > 10:
                if rows not in (2, 3, cols - 1, cols):
                    continue
                robots = sorted({k for k in (1, 2, 3, most) if k <= most})
            for k in robots:
                for target in TARGETS:
                    _same_as_plan(default_scenario(rows, cols, k), target)
