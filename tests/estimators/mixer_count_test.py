"""Signature counting gives the plan's mixer cost, logic width and work need, without building partial mixers."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from circuitgen.options import PlanOptions
from circuitgen.qaoa import qaoa_plan
from estimators.estimate import layer_costs, registers_for
from estimators.mixer_count import mixer_layer
from gridcover.presets import default_scenario, max_default_robots
from gridcover.scenario import Scenario, scenario_from_dict, scenario_to_dict
from tests.circuitgen.conftest import scenarios

OPTIONS = [("exact", "nisq"), ("exact", "ft"), ("paper", "nisq")]


def _check(rows: int, cols: int, robots: int, rule: str, target: str) -> None:
    s = default_scenario(rows, cols, robots)
    plan = qaoa_plan(s, 1, PlanOptions(rule=rule, target=target))  # type: ignore[arg-type]
    ml = mixer_layer(s, rule, target)
    assert ml.cost == plan.cost_by_section()["mixer"]
    assert ml.logical == plan.cost_by_section(logical=True)["mixer"]
    phase_ancillas = plan.phase_plan.num_ancillas if plan.phase_plan is not None else 0
    assert max(ml.logic_width, phase_ancillas) == plan.logic_width
    lc = layer_costs(s, PlanOptions(rule=rule, target=target))
    assert dict(lc.registers) == {r.name: r.size for r in plan.registers}
    assert lc.sections == plan.cost_by_section() and lc.logical == plan.cost_by_section(logical=True)
    p0 = qaoa_plan(s, 0, PlanOptions(rule=rule, target=target))  # type: ignore[arg-type]
    assert dict(registers_for(s, 0, PlanOptions(rule=rule, target=target))) == {r.name: r.size for r in p0.registers}


@pytest.mark.parametrize("rule, target", OPTIONS)
@pytest.mark.parametrize("rows, cols", [(2, 2), (2, 5), (3, 3), (4, 3), (5, 6)])
def test_signature_counts_equal_the_plan_sample(rows: int, cols: int, rule: str, target: str) -> None:
    for robots in (1, 2, 4, 5, 8):
        if robots <= max_default_robots(rows, cols):
            _check(rows, cols, robots, rule, target)


@pytest.mark.heavy
def test_signature_counts_equal_the_plan_everywhere() -> None:
    for rows in range(2, 9):
        for cols in range(2, 9):
            for robots in range(1, min(8, max_default_robots(rows, cols)) + 1):
                for rule, target in OPTIONS:
                    _check(rows, cols, robots, rule, target)


def test_interior_endpoints_from_a_file() -> None:
    d = scenario_to_dict(default_scenario(5, 6, 2))
    d["robots"] = [
        {"start": [2, 2], "goal": [3, 4]},
        {"start": [0, 3], "goal": [4, 1]},
        {"start": [1, 1], "goal": [2, 3]},
    ]
    s = scenario_from_dict(d)
    plan = qaoa_plan(s, 1)
    assert mixer_layer(s).cost == plan.cost_by_section()["mixer"]


def test_obstacles_are_refused() -> None:
    d = scenario_to_dict(default_scenario(4, 4, 1))
    d["grid"]["obstacles"] = [[1, 1]]
    with pytest.raises(ValueError):
        mixer_layer(scenario_from_dict(d))


@pytest.mark.parametrize("rows, cols, robots", [(3, 3, 1), (3, 4, 2)])
def test_representatives_initial_state_uses_the_plans_state_preparation(rows: int, cols: int, robots: int) -> None:
    s = default_scenario(rows, cols, robots)
    plan = qaoa_plan(s, 1, PlanOptions(initial="representatives"))
    lc = layer_costs(s, PlanOptions(initial="representatives"))
    assert lc.sections == plan.cost_by_section() and lc.logical == plan.cost_by_section(logical=True)
    assert dict(lc.registers) == {r.name: r.size for r in plan.registers}


@settings(max_examples=60, deadline=None)
@given(scenarios(max_side=7, max_robots=4, obstacles=False), st.sampled_from(["nisq", "ft"]))
def test_signature_counts_with_junctions_equal_the_plan_for_any_endpoints(s: Scenario, target: str) -> None:
    """Endpoints anywhere (interior, neighbouring, sharing rows): the junction pairs next to them are counted right."""
    plan = qaoa_plan(s, 0, PlanOptions(target=target))  # type: ignore[arg-type]
    ml = mixer_layer(s, "exact", target)
    assert ml.cost == plan.cost_by_section()["mixer"]
    assert ml.logical == plan.cost_by_section(logical=True)["mixer"]
