"""The call graph counted by classes (open grids) equals the call graph of the planned gadgets, kind by kind;
its sums equal the lowered circuit's counts; registers and kinds' needs agree."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.gadgets.pricing import COSTS
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.call_graph import CallGraph, GadgetKind
from qcpp.plan.mixer_classes import mixer_part
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.presets import default_scenario, max_default_robots
from qcpp.problem.scenario import Scenario, scenario_from_dict, scenario_to_dict
from tests.compiler.conftest import scenarios

OPTIONS = [
    PlanOptions(),
    PlanOptions(target="ft"),
    PlanOptions(rule="paper"),
    PlanOptions(fuse=False),
    PlanOptions(phase="whole-space"),
]


def _keys(graph: CallGraph) -> dict[str, dict[object, int]]:
    return {part: {k.key: n for k, n in kinds.items()} for part, kinds in graph.parts.items()}


def _check(s: Scenario, options: PlanOptions, p: int = 1) -> None:
    plan = qaoa_plan(s, p, options)
    by_classes, listed = plan.call_graph(), plan.call_graph(by_classes=False)
    assert _keys(by_classes) == _keys(listed)
    assert (by_classes.logic_width, by_classes.work_width) == (listed.logic_width, listed.work_width)
    for part in ("initial_state", "phase", "mixer"):
        for kind, _ in by_classes.parts[part].items():
            assert kind.temporaries <= by_classes.logic_width and kind.work <= by_classes.work_width
    _assert_named_keys(by_classes)
    _assert_named_keys(listed)


def _assert_named_keys(graph: CallGraph) -> None:
    """Every kind key is a named tuple whose first field ``gadget`` names the gadget: read by name, not position."""
    for kinds in graph.parts.values():
        for kind in kinds:
            fields = getattr(type(kind.key), "_fields", ())
            assert fields[:1] == ("gadget",) and isinstance(kind.key.gadget, str), kind.key


@pytest.mark.parametrize("options", OPTIONS, ids=lambda o: f"{o.rule}/{o.target}/{o.initial}/fuse={o.fuse}")
@pytest.mark.parametrize("rows, cols", [(2, 2), (2, 5), (3, 3), (4, 3), (5, 6), (7, 7)])
def test_classes_list_the_planned_kinds_default_scenarios(rows: int, cols: int, options: PlanOptions) -> None:
    for robots in (1, 2, 4, 5, 8):
        if robots <= max_default_robots(rows, cols):
            _check(default_scenario(rows, cols, robots), options)


@pytest.mark.heavy
def test_classes_list_the_planned_kinds_everywhere() -> None:
    """Every grid from 2x2 to 8x8 (both orientations), each of :data:`OPTIONS`; every robot count (up to 8, as many
    as fit) on grids up to 5x5, and 1, 2, 3 and the most robots on the larger ones.

    A robot beyond the third adds more pairs of the kinds three robots already have (balance, shared nodes), and
    the listed call graph's cost grows with the robots: counts 4 to 7 on grids past 5x5 were over half this sweep.
    """
    for rows in range(2, 9):
        for cols in range(2, 9):
            most = min(8, max_default_robots(rows, cols))
            counts = range(1, most + 1) if max(rows, cols) <= 5 else sorted({k for k in (1, 2, 3, most) if k <= most})
            for robots in counts:
                for options in OPTIONS:
                    _check(default_scenario(rows, cols, robots), options)


@pytest.mark.parametrize("layout", ["spatial", "medial"])
def test_placed_phase_kinds_are_named(layout: str) -> None:
    s = scenario_from_dict({**scenario_to_dict(default_scenario(4, 4, 2)), "grid": {"rows": 4, "cols": 4,
                                                                                    "obstacles": [[1, 2]]}})
    _assert_named_keys(qaoa_plan(s, 1, PlanOptions(phase_layout=layout)).call_graph())


@pytest.mark.parametrize("rows, cols, robots", [(3, 3, 1), (3, 4, 2)])
def test_representatives_initial_state(rows: int, cols: int, robots: int) -> None:
    _check(default_scenario(rows, cols, robots), PlanOptions(initial="representatives"))


def test_interior_endpoints_and_p0() -> None:
    d = scenario_to_dict(default_scenario(5, 6, 2))
    d["robots"] = [
        {"start": [2, 2], "goal": [3, 4]},
        {"start": [0, 3], "goal": [4, 1]},
        {"start": [1, 1], "goal": [2, 3]},
    ]
    s = scenario_from_dict(d)
    for p in (0, 1):
        _check(s, PlanOptions(), p)
    assert qaoa_plan(s, 0).call_graph().parts["phase"] == {}


@settings(max_examples=60, deadline=None)
@given(scenarios(max_side=7, max_robots=4, obstacles=False), st.sampled_from(["nisq", "ft"]))
def test_classes_list_the_planned_kinds_for_any_endpoints(s: Scenario, target: str) -> None:
    """Endpoints anywhere (interior, neighbouring, sharing rows): the junction pairs next to them are counted right."""
    _check(s, PlanOptions(target=target))  # type: ignore[arg-type]
    _check(s, PlanOptions(target=target, phase="whole-space"))  # type: ignore[arg-type]


@pytest.mark.parametrize("options", [PlanOptions(), PlanOptions(phase="whole-space"), PlanOptions(rule="paper")])
def test_the_call_graph_sums_to_the_lowered_circuits_counts(options: PlanOptions) -> None:
    robots = [{"start": [0, 0], "goal": [3, 3]}, {"start": [1, 1], "goal": [3, 0]}]
    s = scenario_from_dict({"grid": {"rows": 4, "cols": 4, "obstacles": [[1, 2]]}, "robots": robots})
    plan = qaoa_plan(s, 2, options)
    circuit = plan.circuit()
    graph = plan.call_graph()
    assert graph.cost(2) == Cost.count(lower(circuit).gates)
    assert graph.cost(2, logical=True) == Cost.count(lower(circuit, LOGICAL_BASIS).gates)
    assert {r.name: r.size for r in lower(circuit).registers} == {r.name: r.size for r in plan.registers}


def test_mixer_classes_refuse_obstacles() -> None:
    d = scenario_to_dict(default_scenario(4, 4, 1))
    d["grid"]["obstacles"] = [[1, 1]]
    with pytest.raises(ValueError):
        mixer_part(scenario_from_dict(d))


def test_kinds_compare_by_key_and_costs_come_from_the_cache() -> None:
    s = default_scenario(4, 4, 2)
    kinds = list(qaoa_plan(s, 1).call_graph().parts["mixer"])
    a = kinds[0]
    twin = GadgetKind(a.key, a.example)
    assert twin == a and hash(twin) == hash(a) and {a: 1}[twin] == 1
    COSTS.clear()
    assert len(COSTS) == 0
    assert twin.cost() == a.example.cost() and len(COSTS) == 1


def test_gadgets_priced_per_kind_and_depth_facts_share_the_one_cache() -> None:
    from qcpp.estimators.depth_compose import gadget_depth, known_depth
    from qcpp.gadgets.junction import MixerJunction
    from qcpp.gadgets.phase_visits import VisitPhase

    plan = qaoa_plan(default_scenario(4, 4, 2), 1)
    found = {}
    for _, g in plan.sections():
        if isinstance(g, MixerJunction | VisitPhase):
            found.setdefault(type(g), g)
    assert set(found) == {MixerJunction, VisitPhase}

    def never() -> tuple[Cost, Cost]:
        raise AssertionError("priced twice")

    COSTS.clear()
    for g in found.values():
        assert (g.cost(), g.logical_cost()) == COSTS.costs(g.kind, never)  # priced once, under its kind key
        assert known_depth(g) is None
        d = gadget_depth(g, tuple(plan.registers))
        assert known_depth(g) == d  # the own depth is remembered per kind in the same cache
    assert len(COSTS.table("own depth")) == 2
    COSTS.clear()
    assert len(COSTS) == 0 and all(known_depth(g) is None for g in found.values())


def test_mixer_class_representatives_live_in_the_one_cache() -> None:
    COSTS.clear()
    before = mixer_part(default_scenario(5, 4, 2), "exact", "nisq", True, None)
    assert all(len(COSTS.table(t)) > 0 for t in ("mixer representative", "mixer kinds", "mixer junction"))
    COSTS.clear()
    assert len(COSTS) == 0
    mixer_part.cache_clear()
    assert mixer_part(default_scenario(5, 4, 2), "exact", "nisq", True, None) == before  # rebuilt, equal kinds
