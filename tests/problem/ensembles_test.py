"""Random ensembles: every instance feasible (by exhaustive search), the draw a function of the seed alone."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.errors import QcppError
from qcpp.problem.ensembles import ensemble, obstacle_count, random_scenario
from qcpp.problem.errors import ScenarioError
from qcpp.problem.scenario import scenario_from_dict, scenario_to_dict
from qcpp.problem.solvers import dfs

cells = st.tuples(
    st.integers(2, 4), st.integers(2, 4), st.integers(1, 2), st.sampled_from([0.0, 0.1, 0.2, 0.3]),
    st.sampled_from(["soft", "hard"]),
)
seeds = st.integers(0, 2**32 - 1)


def _fits(rows: int, cols: int, robots: int, density: float) -> bool:
    return round(density * rows * cols) + 2 * robots <= rows * cols


@settings(max_examples=15, deadline=None)
@given(cells, seeds, st.integers(0, 50))
def test_every_instance_is_feasible_and_as_asked(cell: tuple, seed: int, index: int) -> None:
    rows, cols, robots, density, mode = cell
    if not _fits(rows, cols, robots, density):
        field = "robots" if 2 * robots > rows * cols else "density"  # the obstacles' fault only when they cause it
        with pytest.raises(ScenarioError, match=f"^{field}: "):
            random_scenario(rows, cols, robots, density, seed=seed, index=index, obstacles=mode)
        return
    s = random_scenario(rows, cols, robots, density, seed=seed, index=index, obstacles=mode)
    assert (s.grid.rows, s.grid.cols, s.num_robots, s.objective.obstacles) == (rows, cols, robots, mode)
    assert len(s.obstacles) == obstacle_count(rows, cols, robots, density)
    ends = [n for rb in s.robots for n in (rb.start, rb.goal)]
    assert len(set(ends)) == 2 * robots and not set(ends) & set(s.obstacles)
    sol = dfs(s)  # exhaustive search finds an assignment: every robot has a path
    assert sol.evaluated >= 1 and math.isfinite(sol.cost.total)
    assert scenario_from_dict(scenario_to_dict(s)) == s


@settings(max_examples=10, deadline=None)
@given(cells, seeds)
def test_a_seed_names_the_same_instances(cell: tuple, seed: int) -> None:
    rows, cols, robots, density, mode = cell
    if not _fits(rows, cols, robots, density):
        return
    a = ensemble(rows, cols, robots, density, count=3, seed=seed, obstacles=mode)
    assert a == ensemble(rows, cols, robots, density, count=3, seed=seed, obstacles=mode)
    assert a == ensemble(rows, cols, robots, density, count=5, seed=seed, obstacles=mode)[:3]
    assert a[2] == random_scenario(rows, cols, robots, density, seed=seed, index=2, obstacles=mode)


@settings(max_examples=10, deadline=None)
@given(st.tuples(st.integers(3, 4), st.integers(3, 4), st.integers(1, 2), st.sampled_from([0.0, 0.1, 0.2])),
       seeds, seeds)
def test_different_seeds_draw_different_ensembles(cell: tuple, seed: int, other: int) -> None:
    rows, cols, robots, density = cell
    if seed == other:
        return
    # eight instances of at least 3x3 grids: equal ensembles would need eight collisions among >= 72 draws each
    a = ensemble(rows, cols, robots, density, count=8, seed=seed)
    b = ensemble(rows, cols, robots, density, count=8, seed=other)
    assert [scenario_to_dict(s) | {"name": ""} for s in a] != [scenario_to_dict(s) | {"name": ""} for s in b]


def test_instances_of_one_ensemble_vary() -> None:
    a = ensemble(4, 4, 2, 0.1, count=30, seed=0)
    assert len({(s.robots, s.obstacles) for s in a}) >= 25


def test_hard_obstacles_never_cut_a_robot_off() -> None:
    # a dense 3x3 grid: many draws wall a robot in, and those are redrawn
    for i in range(20):
        s = random_scenario(3, 3, 1, 0.45, seed=0, index=i, obstacles="hard")
        assert len(s.obstacles) == 4 and dfs(s).evaluated >= 1


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [({"rows": 1}, "rows"), ({"robots": 0}, "robots"), ({"density": 1.0}, "density"), ({"density": -0.1}, "density"),
     ({"seed": -1}, "seed"), ({"index": 1.5}, "index"), ({"obstacles": "wall"}, "obstacles"),
     ({"robots": 5}, "robots"), ({"robots": 4, "density": 0.2}, "density")],
)
def test_bad_arguments_name_their_field(kwargs: dict, field: str) -> None:
    args = {"rows": 3, "cols": 3, "robots": 1, "density": 0.1} | kwargs
    with pytest.raises(ScenarioError) as err:
        random_scenario(args.pop("rows"), args.pop("cols"), args.pop("robots"), args.pop("density"), **args)
    assert err.value.field == field and isinstance(err.value, (QcppError, ValueError))


def test_count_must_be_positive() -> None:
    with pytest.raises(ScenarioError, match="count"):
        ensemble(3, 3, 1, count=0)


def test_too_many_robots_name_robots_and_too_many_obstacles_name_density() -> None:
    import qcpp

    with pytest.raises(qcpp.ScenarioError) as robots:
        qcpp.random_scenario(3, 3, robots=9)
    assert str(robots.value) == "robots: 9 robots need 18 distinct endpoints, a 3x3 grid has 9 nodes"
    with pytest.raises(qcpp.ScenarioError) as density:
        qcpp.random_scenario(3, 3, robots=4, density=0.2)  # 8 endpoints fit on 9 nodes; 2 obstacles do not
    assert str(density.value) == "density: 2 obstacles and 8 endpoints do not fit on the 9 nodes of a 3x3 grid"
