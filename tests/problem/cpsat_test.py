"""The CP-SAT solver: the same optimum as exhaustive search (fixed sweeps and hypothesis scenarios), feasible paths,
bounds at a time limit, exact integer scaling of the weights, and the registry entry."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.problem.cost import cost_parts
from qcpp.problem.paths import enumerate_paths, is_feasible
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import SOLVERS, CpSatResult, cpsat, dfs, solve
from qcpp.problem.solvers.cpsat import exact_rational, scenario_symmetries

from .solvers_test import TWO_ROBOTS_3X3

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def check_against_dfs(s: Scenario, **options: Any) -> CpSatResult:
    """CP-SAT proves DFS's optimum and returns feasible paths whose re-scored cost is that optimum."""
    res = cpsat(s, **options)
    best = dfs(s).cost.total
    tol = 1e-9 * max(1.0, abs(best))
    assert res.proven_optimal and res.status == "OPTIMAL"
    assert res.solution.cost.total == pytest.approx(best, abs=tol)
    assert res.bound == pytest.approx(best, abs=tol) and res.gap == 0.0
    assert res.solution.cost == cost_parts(s, res.solution.paths)
    for r, m in enumerate(res.solution.paths):
        assert is_feasible(s, r, m)
    # improvements are in time order, each better than the last, ending at the optimum
    times = [t for t, _ in res.improvements]
    values = [v for _, v in res.improvements]
    assert times == sorted(times) and values == sorted(values, reverse=True)
    assert values[-1] == pytest.approx(best, abs=1e-6 * max(1.0, abs(best)))
    assert res.time_to_cost(best) is not None and res.time_to_cost(best - 1.0) is None
    return res


# ----------------------------------------------------------------------------- the dfs test sweeps


@pytest.mark.parametrize(
    ("robots", "obstacles", "mode", "objective"),
    [
        *TWO_ROBOTS_3X3,
        # negative alphas: the balance square as an exact product, the degree term as a table
        ([((0, 0), (2, 2)), ((2, 0), (0, 2))], [(1, 1)], "soft", {"alpha": [1, -0.5, -0.25]}),
        ([((0, 0), (2, 1)), ((1, 2), (2, 0))], [(1, 1)], "soft",
         {"alpha": [0.7, 1.3, 0.9], "obstacle_weight": 2.5, "free_weight": -1.75}),
    ],
)
def test_equals_dfs_two_robots_3x3(build, robots, obstacles, mode, objective) -> None:
    check_against_dfs(build(3, 3, robots, obstacles, mode, **objective))


def test_equals_dfs_three_robots(build) -> None:
    check_against_dfs(build(2, 4, [((0, 0), (1, 3)), ((1, 0), (0, 3)), ((0, 1), (1, 2))], balance="all-pairs"))
    check_against_dfs(build(3, 3, [((0, 0), (2, 2)), ((2, 0), (0, 2)), ((1, 1), (0, 1))], [(1, 2)], "soft"))


def test_equals_dfs_with_edge_lengths(build) -> None:
    lengths = [[[0, 0], [0, 1], 2.5], [[1, 1], [2, 1], 0.75]]
    check_against_dfs(build(3, 3, [((0, 0), (2, 2)), ((0, 2), (2, 0))], edge_lengths=lengths))
    # many integer length steps: the balance square as a product instead of chords
    check_against_dfs(build(3, 3, [((0, 0), (2, 2)), ((0, 2), (2, 0))], edge_length=1.001))


@pytest.mark.parametrize("name", ["paper_3x3.toml", "two_robots_4x4.toml", "obstacles_hard_4x4.toml"])
def test_equals_dfs_on_the_examples(name: str) -> None:
    check_against_dfs(load_scenario(EXAMPLES / name))


@pytest.mark.heavy
def test_equals_dfs_two_robots_5x5() -> None:
    res = check_against_dfs(load_scenario(EXAMPLES / "two_robots_5x5.toml"))
    assert res.solution.cost.total == -16.0


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_equals_dfs_on_random_scenarios(random_scenarios, data) -> None:  # type: ignore[no-untyped-def]
    s = data.draw(random_scenarios(max_size=4, max_robots=3))
    if math.prod(len(enumerate_paths(s, r)) for r in range(s.num_robots)) > 50_000:
        return  # exhaustive search would be slow; every other scenario is checked
    check_against_dfs(s, symmetry_breaking=data.draw(st.booleans(), label="symmetry_breaking"))


@pytest.mark.parametrize(("n", "robots", "symmetries"), [(3, 1, 3), (3, 2, 7), (3, 3, 0), (4, 2, 7), (4, 3, 0)])
def test_default_placements_with_and_without_symmetry_breaking(n: int, robots: int, symmetries: int) -> None:
    # corner to opposite corner: two robots' paths must cross (the crossing cut); one robot keeps its diagonal
    # (3 symmetries), two robots are swapped by the others (7); the third robot has the second's endpoints,
    # which makes the robot permutation ambiguous, so no symmetry is used
    s = default_scenario(n, n, robots)
    assert len(scenario_symmetries(s)) == symmetries
    a, b = check_against_dfs(s), check_against_dfs(s, symmetry_breaking=True)
    assert a.solution.cost.total == b.solution.cost.total


@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_symmetries_preserve_the_cost(random_scenarios, data) -> None:  # type: ignore[no-untyped-def]
    s = data.draw(random_scenarios(max_size=4, max_robots=3))
    lists = [enumerate_paths(s, r) for r in range(s.num_robots)]
    masks = [data.draw(st.sampled_from(pl)) for pl in lists]
    for perm, emap in scenario_symmetries(s):
        image = [0] * s.num_robots
        for r, m in enumerate(masks):
            image[perm[r]] = sum(1 << emap[e] for e in range(s.grid.num_edges) if (m >> e) & 1)
        assert all(is_feasible(s, r, m) for r, m in enumerate(image))
        assert cost_parts(s, image).total == pytest.approx(cost_parts(s, masks).total, abs=1e-9)


# ----------------------------------------------------------------------------- time limit, bound, registry


def test_time_limit_returns_feasible_paths_and_a_valid_bound() -> None:
    s = default_scenario(8, 8, 2)
    res = cpsat(s, time_limit=1.0)
    # how far 1 s gets depends on the machine and its load: every outcome must be reported consistently
    assert res.status in ("OPTIMAL", "FEASIBLE", "UNKNOWN")
    assert res.proven_optimal == (res.status == "OPTIMAL")
    if res.proven_optimal:
        assert res.bound == res.solution.cost.total
    assert res.bound <= res.solution.cost.total and res.gap == res.solution.cost.total - res.bound
    for r, m in enumerate(res.solution.paths):
        assert is_feasible(s, r, m)
    assert res.solution.cost == cost_parts(s, res.solution.paths)


def test_bound_is_below_the_optimum() -> None:
    # whatever the limit stops, the bound never exceeds the optimum (-16, exhaustive search: docs/experiments.md)
    s = load_scenario(EXAMPLES / "two_robots_5x5.toml")
    for limit in (0.05, 0.3, 0.6):
        res = cpsat(s, time_limit=limit)
        assert res.bound <= -16.0 <= res.solution.cost.total
        assert res.proven_optimal == (res.bound == res.solution.cost.total)


def test_registry_and_solve(build) -> None:
    s = build(3, 3, [((0, 0), (2, 2))])
    assert "cpsat" in SOLVERS
    sol = solve(s, "cpsat", seed=4)
    assert sol.method == "cpsat" and sol.seed == 4 and sol.cost.total == dfs(s).cost.total
    assert sol.trace and sol.evaluated == len(sol.trace)


def test_bad_arguments(build) -> None:
    s = build(2, 2, [((0, 0), (1, 1))])
    with pytest.raises(ValueError, match="time_limit"):
        cpsat(s, time_limit=0)
    with pytest.raises(ValueError, match="workers"):
        cpsat(s, workers=0)


# ----------------------------------------------------------------------------- exact integer objective


def test_exact_rational() -> None:
    assert exact_rational(0.1) == Fraction(1, 10) and exact_rational(-2.5) == Fraction(-5, 2)
    assert exact_rational(1 / 3) == Fraction(1, 3) and exact_rational(3.0) == 3
    with pytest.raises(ValueError, match="rational"):
        exact_rational(0.1 + 0.2)  # 0.30000000000000004: no short fraction is exactly this float
    with pytest.raises(ValueError, match="rational"):
        exact_rational(math.pi)


def test_weights_that_cannot_be_scaled_exactly_are_refused(build) -> None:
    s = build(3, 3, [((0, 0), (2, 2))], alpha=[0.1 + 0.2, 1, 1])
    with pytest.raises(ValueError, match=r"0\.30000000000000004"):
        cpsat(s)


def test_scale_is_the_common_denominator(build) -> None:
    s = build(3, 3, [((0, 0), (2, 2)), ((2, 0), (0, 2))], alpha=[0.5, 0.25, 1], free_weight=-1.5,
              edge_length=1 / 3)
    res = check_against_dfs(s)
    # a0*w: 1/2 * 3/2 -> 4; a1 * (1/3)^2 (one length step is 1/3) -> 36
    assert res.scale == 36
