"""qcpp.problem.cost_range: every numeric field, every solver: one ScenarioError naming the field outside the range,
a clean run (no warnings, no MODEL_INVALID) at the edge of it."""

from __future__ import annotations

import math
import warnings
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.problem.cost import cost_parts
from qcpp.problem.cost_range import (
    COST_LIMIT,
    MIN_WEIGHT,
    check_cost_range,
    cost_bound,
    largest_allowed,
    weight_fields,
)
from qcpp.problem.errors import ScenarioError
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.problem.solvers import anneal, cpsat, dfs, genetic

BASE: dict[str, Any] = {
    "grid": {"rows": 3, "cols": 3, "obstacles": [[1, 1]]},
    "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}],
    "objective": {"edge_lengths": [[[0, 0], [0, 1], 2.0]]},
}
FIELDS = [f.name for f in weight_fields(scenario_from_dict(BASE))]
SOLVERS = {
    "dfs": dfs,
    "anneal": lambda s: anneal(s, iterations=300),
    "genetic": lambda s: genetic(s, generations=3),
    "cpsat": lambda s: cpsat(s).solution,
}


def _with(name: str, value: float) -> Scenario:
    d = {**BASE, "objective": {**BASE["objective"]}}
    ob = d["objective"]
    key = name.split(".", 1)[1]
    if key.startswith("alpha["):
        alpha = [1.0, 1.0, 1.0]
        alpha[int(key[6])] = value
        ob["alpha"] = alpha
    elif key.startswith("edge_lengths["):
        ob["edge_lengths"] = [[[0, 0], [0, 1], value]]
    else:
        ob[key] = value
    return scenario_from_dict(d)


def _solve(method: str, s: Scenario) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no RuntimeWarning may leak
        SOLVERS[method](s)


def test_every_field_is_listed() -> None:
    assert FIELDS == [
        "objective.alpha[0]", "objective.alpha[1]", "objective.alpha[2]", "objective.obstacle_weight",
        "objective.free_weight", "objective.edge_length", "objective.edge_lengths[0]",
    ]


def test_bound_holds_on_every_assignment() -> None:
    """cost_bound is an upper bound of |cost| over every combination of simple paths (exhaustively)."""
    for name in FIELDS:
        s = _with(name, -7.5 if "length" not in name else 7.5)
        bound = cost_bound(s)
        worst = max(
            abs(cost_parts(s, [a, b]).total) for a in enumerate_paths(s, 0) for b in enumerate_paths(s, 1)
        )
        assert worst <= bound


@pytest.mark.parametrize("name", FIELDS)
@pytest.mark.parametrize("sign", [1.0, -1.0])
@pytest.mark.parametrize("magnitude", [1e9, 1e17, 1e200, 1e308])
def test_too_large_names_the_field_everywhere(name: str, sign: float, magnitude: float) -> None:
    if "length" in name and sign < 0:
        pytest.skip("lengths are positive (refused by the scenario itself)")
    if "length" not in name and magnitude < 1e16:
        pytest.skip("linear weights of 1e9 are well inside the range (the cost reaches 1e11)")
    s = _with(name, sign * magnitude)
    for method in SOLVERS:
        with pytest.raises(ScenarioError) as exc:
            _solve(method, s)
        assert exc.value.field == name
        assert "too large" in exc.value.reason and "<=" in exc.value.reason
        assert "\n" not in str(exc.value)


@pytest.mark.parametrize("name", FIELDS)
@pytest.mark.parametrize("value", [1e-7, 1e-200, 5e-324])
def test_too_small_names_the_field(name: str, value: float) -> None:
    s = _with(name, value)
    for method in SOLVERS:
        with pytest.raises(ScenarioError) as exc:
            _solve(method, s)
        assert exc.value.field == name
        assert f"{MIN_WEIGHT:g}" in exc.value.reason


@pytest.mark.parametrize("name", FIELDS)
def test_the_edge_of_the_range_solves_cleanly(name: str) -> None:
    """At the largest allowed value (a round number just below it) every solver runs, without warnings;
    twice that is refused."""
    base = _with(name, 1.0)
    most = largest_allowed(base, name)
    assert 0 < most < math.inf
    edge = float(f"{most:.2e}") if float(f"{most:.2e}") <= most else float(f"{most * 0.99:.2e}")
    s = _with(name, edge)
    check_cost_range(s)
    assert cost_bound(s) <= COST_LIMIT
    for method in SOLVERS:
        _solve(method, s)
    with pytest.raises(ScenarioError):
        check_cost_range(_with(name, 2 * most))


def test_cpsat_range_is_scaled_by_the_common_denominator() -> None:
    """A cost inside the float range whose integer form (times the denominators) is not: cpsat alone refuses."""
    s = scenario_from_dict({**BASE, "objective": {"alpha": [1.0, 1e15, 1.0], "edge_length": 1 / 3}})
    check_cost_range(s)
    SOLVERS["dfs"](s)
    with pytest.raises(ScenarioError) as exc:
        SOLVERS["cpsat"](s)
    assert "cpsat" in exc.value.reason and exc.value.field.startswith("objective.")


def test_cpsat_names_a_weight_without_a_short_fraction() -> None:
    s = _with("objective.free_weight", 0.1 + 0.2)
    with pytest.raises(ScenarioError) as exc:
        SOLVERS["cpsat"](s)
    assert exc.value.field == "objective.free_weight"


@pytest.mark.parametrize("objective, field", [
    ({"alpha": [1.0, 1e300, 1.0]}, "objective.alpha[1]"),  # one robot: no balance term to weigh
    ({"edge_length": 1e9}, "objective.edge_length"),  # one robot: lengths never enter the cost
    ({"obstacle_weight": -1e200}, "objective.obstacle_weight"),  # no obstacles
])
def test_fields_the_cost_does_not_use_are_still_held_to_their_cap(objective: dict[str, Any], field: str) -> None:
    s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}],
                            "objective": objective})
    for method in SOLVERS:
        with pytest.raises(ScenarioError) as exc:
            _solve(method, s)
        assert exc.value.field == field and "any scenario" in exc.value.reason


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_bound_holds_on_random_scenarios(data: st.DataObject, scenario_dict_strategy: Any) -> None:
    """Soft and hard obstacles, both balance and degree modes, any signs: no assignment of simple paths costs
    more (in magnitude) than cost_bound."""
    import itertools

    s = scenario_from_dict(data.draw(scenario_dict_strategy(max_size=3, max_robots=2)))
    paths = [enumerate_paths(s, r) for r in range(s.num_robots)]
    worst = max(abs(cost_parts(s, list(combo)).total) for combo in itertools.product(*paths))
    assert worst <= cost_bound(s) * (1 + 1e-12)
