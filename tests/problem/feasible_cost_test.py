"""The feasible-subspace cost representation equals the cost on every feasible assignment.

Exhaustive over a sweep of small scenarios (every feasible assignment, sampled where the product is big),
hypothesis over random scenarios up to 5x5 with obstacles and non-default weights, and the structural claims
(dead edges are never used, visit groups hold 2-4 edges per visitor, one robot has no quadratic part).
"""

from __future__ import annotations

import itertools
import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.problem.cost import cost_parts_bits
from qcpp.problem.feasible_cost import feasible_cost, live_edges
from qcpp.problem.paths import enumerate_paths, path_bits
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario

from .conftest import make_scenario

TOL = 1e-8


def sweep() -> list[Scenario]:
    """The sweep shared with ``tests/compiler/phase_test.py``: grids up to 4x4, 1-3 robots, both obstacle
    modes, both balance modes, both degree-target modes, non-default weights and lengths."""
    out = [default_scenario(r, c, k) for r, c, k in [(2, 2, 1), (3, 3, 1), (3, 3, 2), (3, 4, 2), (4, 4, 2), (4, 4, 3)]]
    robots3 = [((0, 0), (3, 3)), ((0, 3), (3, 0)), ((1, 2), (3, 3))]
    for mode in ("soft", "hard"):
        out.append(make_scenario(4, 4, robots3, obstacles=[(1, 1), (2, 3)], mode=mode, alpha=[0.7, 1.3, 2.1],
                                 balance="all-pairs", obstacle_weight=2.5, free_weight=-0.5))  # fmt: skip
        out.append(make_scenario(3, 4, [((0, 0), (2, 3)), ((2, 0), (0, 3))], obstacles=[(1, 2)],
                                 mode=mode, degree_target="paper", edge_length=2.0,
                                 edge_lengths=[[[0, 0], [0, 1], 3.0]]))  # fmt: skip
    out.append(make_scenario(3, 3, [((1, 1), (0, 0)), ((0, 2), (2, 0))], edge_lengths=[[[1, 1], [1, 2], 0.37]]))
    out.append(make_scenario(4, 3, [((0, 0), (3, 2)), ((3, 0), (3, 2)), ((0, 2), (1, 1))], balance="all-pairs"))
    return out


def feasible_rows(s: Scenario, limit: int = 3000, seed: int = 0) -> np.ndarray:
    """Bit rows of feasible assignments: all of them, or ``limit`` random ones when there are more."""
    pl = [enumerate_paths(s, r) for r in range(s.num_robots)]
    total = int(np.prod([len(p) for p in pl]))
    if total <= limit:
        combos = list(itertools.product(*pl))
    else:
        rng = random.Random(seed)
        combos = [tuple(rng.choice(p) for p in pl) for _ in range(limit)]
    return np.array([np.concatenate([path_bits(s, m) for m in c]) for c in combos])


def _id(s: Scenario) -> str:
    return f"{s.grid.rows}x{s.grid.cols}-{s.num_robots}-{s.objective.obstacles}"


@pytest.mark.parametrize("s", sweep(), ids=_id)
def test_equals_cost_on_feasible_assignments(s: Scenario) -> None:
    x = feasible_rows(s)
    f = feasible_cost(s)
    np.testing.assert_allclose(f.evaluate(x), cost_parts_bits(s, x)[:, 3], atol=TOL, rtol=0)


@pytest.mark.parametrize("s", sweep()[:6], ids=_id)
def test_dead_variables_are_never_used(s: Scenario) -> None:
    x = feasible_rows(s)
    dead = sorted(feasible_cost(s).dead)
    assert not x[:, dead].any()


def test_docstring_examples() -> None:
    import doctest

    import qcpp.problem.feasible_cost as mod

    result = doctest.testmod(mod)
    assert result.attempted > 0 and result.failed == 0


def test_one_robot_is_linear_and_visit_groups_have_two_to_four_edges() -> None:
    assert not feasible_cost(default_scenario(4, 4, 1)).visits
    f = feasible_cost(default_scenario(4, 4, 3))
    assert f.visits and all(2 <= len(v) <= 4 for g in f.visits for v in g.visitors)
    # integer lengths: the balance group is arithmetic-ready
    assert f.sums and f.sums[0].integral


def test_live_edges_drop_dead_ends() -> None:
    # hard obstacle at (0, 1) leaves node (0, 0)'s only other edge a dead end for a robot not ending there
    s = make_scenario(3, 3, [((1, 0), (2, 2))], obstacles=[(0, 1)], mode="hard")
    live = live_edges(s, 0)
    assert live[0] == []


def test_non_integer_lengths_stay_real() -> None:
    s = make_scenario(3, 3, [((0, 0), (2, 2)), ((0, 2), (2, 0))], edge_lengths=[[[0, 0], [0, 1], 2**0.5]])
    f = feasible_cost(s)
    assert not f.sums[0].integral
    x = feasible_rows(s)
    np.testing.assert_allclose(f.evaluate(x), cost_parts_bits(s, x)[:, 3], atol=TOL, rtol=0)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_random_scenarios(random_scenarios, data) -> None:  # type: ignore[no-untyped-def]
    s = data.draw(random_scenarios(max_size=5, max_robots=3))
    if any(not enumerate_paths(s, r) for r in range(s.num_robots)):
        return
    x = feasible_rows(s, limit=300, seed=1)
    f = feasible_cost(s)
    scale = max(1.0, float(np.abs(cost_parts_bits(s, x)[:, 3]).max()))
    np.testing.assert_allclose(f.evaluate(x), cost_parts_bits(s, x)[:, 3], atol=1e-9 * scale, rtol=0)
