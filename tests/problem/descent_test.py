"""Steepest descent over SBF moves (qcpp.problem.solvers.descent): checked against the cost's own evaluator."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.problem.cost import cost
from qcpp.problem.paths import initial_path, is_feasible
from qcpp.problem.scenario import Scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers.descent import local_search
from qcpp.problem.solvers.moves import MoveSpace

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def reference_descent(s: Scenario) -> tuple[tuple[int, ...], float]:
    """The same descent written plainly: every neighbour scored by ``qcpp.problem.cost.cost``."""
    space = MoveSpace(s, "exact", "initial")
    paths = tuple(initial_path(s, r) for r in range(s.num_robots))
    current = cost(s, paths)
    tol = 1e-9 * max(1.0, abs(current))  # local_search's: costs equal within it are ties, the first one wins
    while True:
        best = None
        for r in range(s.num_robots):
            for nb in space.neighbours(r, paths[r]):
                cand = (*paths[:r], nb, *paths[r + 1:])
                c = cost(s, cand)
                if c < current - tol and (best is None or c < best[0] - tol):
                    best = (c, cand)
        if best is None:
            return paths, current
        current, paths = best


def check_local_minimum(s: Scenario) -> None:
    res = local_search(s)
    tol = 1e-9 * max(1.0, abs(res.initial_cost))
    assert res.initial_cost == pytest.approx(cost(s, [initial_path(s, r) for r in range(s.num_robots)]), abs=tol)
    assert res.cost == pytest.approx(cost(s, res.paths), abs=tol)
    assert res.steps == len(res.trace) - 1 and res.trace[0] == res.initial_cost and res.trace[-1] == res.cost
    assert all(b < a for a, b in zip(res.trace, res.trace[1:]))
    assert all(is_feasible(s, r, m) for r, m in enumerate(res.paths))
    space = MoveSpace(s, "exact", "initial")
    for r in range(s.num_robots):  # no single allowed flip improves it
        for nb in space.neighbours(r, res.paths[r]):
            assert cost(s, (*res.paths[:r], nb, *res.paths[r + 1:])) >= res.cost - tol
    assert res.cost == pytest.approx(reference_descent(s)[1], abs=tol)


@pytest.mark.parametrize("name", ["two_robots_4x4.toml", "two_robots_5x5.toml", "paper_3x3.toml",
                                  "obstacles_hard_4x4.toml"])
def test_examples_match_the_plain_descent(name: str) -> None:
    s = load_scenario(EXAMPLES / name)
    check_local_minimum(s)
    assert local_search(s).paths == reference_descent(s)[0]  # integer costs: the same tie-breaking


def test_five_by_five_stops_short_of_the_optimum() -> None:
    """two_robots_5x5: the warm start is a heuristic, not the answer (the optimum is -16, proven by dfs)."""
    res = local_search(load_scenario(EXAMPLES / "two_robots_5x5.toml"))
    assert (res.initial_cost, res.cost, res.steps) == (48.0, -6.0, 7)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_random_scenarios_end_in_a_local_minimum(random_scenarios, data) -> None:  # type: ignore[no-untyped-def]
    check_local_minimum(data.draw(random_scenarios(max_size=4, max_robots=3)))
