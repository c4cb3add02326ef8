"""Classical solvers: exhaustive search against a brute-force loop, the local searches against exhaustive
search, seeds, move-graph components, the registry and the JSON form."""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import numpy as np
import pytest

from qcpp.problem.cost import cost, cost_parts
from qcpp.problem.paths import enumerate_paths, initial_path, is_feasible, path_to_nodes
from qcpp.problem.sbf import move_components
from qcpp.problem.scenario import Scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import SOLVERS, anneal, dfs, genetic, solution_to_dict, solve

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def brute_force(s: Scenario) -> tuple[float, tuple[int, ...]]:
    """Minimum of cost() over every combination, first (lowest index tuple) minimiser."""
    lists = [enumerate_paths(s, r) for r in range(s.num_robots)]
    best, best_idx = math.inf, ()
    for idx in itertools.product(*(range(len(pl)) for pl in lists)):
        c = cost(s, [lists[r][i] for r, i in enumerate(idx)])
        if c < best:
            best, best_idx = c, idx
    return best, best_idx


def assert_feasible(s: Scenario, paths: tuple[int, ...]) -> None:
    assert len(paths) == s.num_robots
    for r, m in enumerate(paths):
        assert is_feasible(s, r, m)


# ----------------------------------------------------------------------------- dfs


TWO_ROBOTS_3X3 = [
    ([((0, 0), (2, 2)), ((2, 0), (0, 2))], [], "soft", {}),
    ([((0, 0), (2, 2)), ((0, 2), (2, 0))], [(1, 1)], "soft", {"balance": "all-pairs"}),
    ([((0, 0), (2, 2)), ((2, 0), (0, 2))], [(1, 1)], "hard", {}),
    ([((0, 0), (0, 2)), ((2, 2), (1, 0))], [(0, 1)], "soft", {"degree_target": "paper", "alpha": [2, 1, 3]}),
]
"""Two-robot 3x3 scenarios ``(robots, obstacles, obstacle mode, objective keys)``: open, a soft and a hard
obstacle, other balance and degree objectives (the exact solvers' sweeps: dfs here, CP-SAT in ``cpsat_test``)."""


@pytest.mark.parametrize(("robots", "obstacles", "mode", "objective"), TWO_ROBOTS_3X3)
def test_dfs_equals_brute_force_two_robots_3x3(build, robots, obstacles, mode, objective) -> None:
    s = build(3, 3, robots, obstacles, mode, **objective)
    best, idx = brute_force(s)
    sol = dfs(s)
    lists = [enumerate_paths(s, r) for r in range(s.num_robots)]
    assert sol.cost.total == pytest.approx(best, abs=1e-9)
    # integer weights: the tie-break (lowest index tuple) is exact too
    assert sol.paths == tuple(lists[r][i] for r, i in enumerate(idx))
    assert sol.cost == cost_parts(s, sol.paths)
    assert sol.paths_per_robot == tuple(len(pl) for pl in lists)
    assert sol.evaluated == math.prod(sol.paths_per_robot)
    assert_feasible(s, sol.paths)


def test_dfs_three_robots_and_chunking(build) -> None:
    s = build(2, 4, [((0, 0), (1, 3)), ((1, 0), (0, 3)), ((0, 1), (1, 2))], balance="all-pairs")
    best, idx = brute_force(s)
    whole = dfs(s)
    tiny = dfs(s, chunk_elements=3)  # blocks of one prefix row, so many blocks and gathered rows
    lists = [enumerate_paths(s, r) for r in range(3)]
    expected = tuple(lists[r][i] for r, i in enumerate(idx))
    assert whole.paths == tiny.paths == expected
    assert whole.cost.total == pytest.approx(best, abs=1e-9)
    assert whole.evaluated == tiny.evaluated == math.prod(len(pl) for pl in lists)


def test_dfs_random_weights_matches_brute_force(build) -> None:
    rng = np.random.default_rng(7)
    for _ in range(5):
        alpha = [float(x) for x in rng.uniform(0.1, 2.0, 3)]
        s = build(3, 3, [((0, 0), (2, 1)), ((1, 2), (2, 0))], [(1, 1)], "soft", alpha=alpha,
                  obstacle_weight=float(rng.uniform(0, 3)), free_weight=float(rng.uniform(-3, 0)))
        best, _ = brute_force(s)
        assert dfs(s).cost.total == pytest.approx(best, abs=1e-9)


def test_dfs_rejects_bad_chunk(build) -> None:
    with pytest.raises(ValueError, match="chunk_elements"):
        dfs(build(2, 2, [((0, 0), (1, 1))]), chunk_elements=0)


# ----------------------------------------------------------------------------- local searches vs dfs


@pytest.fixture(scope="module", params=["paper_3x3.toml", "two_robots_4x4.toml"])
def example(request) -> tuple[Scenario, float]:  # type: ignore[no-untyped-def]
    s = load_scenario(EXAMPLES / request.param)
    return s, dfs(s).cost.total


@pytest.mark.parametrize("search", [anneal, genetic], ids=["anneal", "genetic"])
def test_local_search_defaults_find_the_dfs_optimum(example, search) -> None:
    s, optimum = example
    sol = search(s)
    assert sol.cost.total == pytest.approx(optimum)
    assert sol.cost == cost_parts(s, sol.paths)
    assert_feasible(s, sol.paths)


@pytest.mark.parametrize("method", ["anneal", "genetic"])
def test_paper_rule_keeps_paths_feasible(method) -> None:
    s = load_scenario(EXAMPLES / "two_robots_4x4.toml")
    sol = solve(s, method, seed=1, rule="paper")
    assert sol.rule == "paper"
    assert_feasible(s, sol.paths)
    assert sol.cost.total >= dfs(s).cost.total - 1e-9


# ----------------------------------------------------------------------------- seeds and traces


def test_seeds_reproduce_traces_exactly(build) -> None:
    s = build(4, 4, [((0, 0), (3, 3)), ((3, 0), (0, 3))], [(1, 2)])
    a1, a2 = anneal(s, seed=11, iterations=3000), anneal(s, seed=11, iterations=3000)
    assert a1.trace == a2.trace and a1.paths == a2.paths and a1.evaluated == a2.evaluated
    g1, g2 = genetic(s, seed=11, generations=8), genetic(s, seed=11, generations=8)
    assert g1.trace == g2.trace and g1.paths == g2.paths and g1.evaluated == g2.evaluated
    # the seed matters: another seed gives another run (its calibration walk, its proposals)
    other = anneal(s, seed=12, iterations=3000)
    assert (other.trace, other.evaluated, other.notes) != (a1.trace, a1.evaluated, a1.notes)


def test_traces_are_best_so_far(build) -> None:
    s = build(4, 4, [((0, 0), (3, 3)), ((3, 0), (0, 3))], [(1, 2)])
    for sol, n in ((anneal(s, seed=3, iterations=2000, cycles=4), 2000), (genetic(s, seed=3, generations=6), 6)):
        assert len(sol.trace) == n
        assert all(b <= a for a, b in zip(sol.trace, sol.trace[1:]))
        assert sol.trace[-1] == pytest.approx(sol.cost.total)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"iterations": 0}, "iterations"),
        ({"t0": 0.0}, "t0"),
        ({"cooling": 1.5}, "cooling"),
        ({"cycles": 0}, "cycles"),
        ({"iterations": 5}, "cycles"),  # the default 10 cycles do not fit in 5 iterations
        ({"rule": "fast"}, "rule"),
        ({"components": "some"}, "component"),
    ],
)
def test_anneal_rejects_bad_settings(build, kwargs, match) -> None:
    with pytest.raises(ValueError, match=match):
        anneal(build(2, 2, [((0, 0), (1, 1))]), **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"population": 0}, "population"),
        ({"generations": 0}, "generations"),
        ({"crossover": -0.1}, "crossover"),
        ({"mutation": "some"}, "mutation"),
        ({"selection": "roulette"}, "selection"),
        ({"elite": 500}, "elite"),
    ],
)
def test_genetic_rejects_bad_settings(build, kwargs, match) -> None:
    with pytest.raises(ValueError, match=match):
        genetic(build(2, 2, [((0, 0), (1, 1))]), **kwargs)


def test_genetic_random_mutation_and_tournament_selection(example) -> None:
    s, optimum = example
    sol = genetic(s, seed=2, mutation="random", selection="tournament", population=32, generations=60)
    assert_feasible(s, sol.paths)
    assert sol.cost.total >= optimum - 1e-9


# ----------------------------------------------------------------------------- move-graph components


def test_hard_obstacle_example_has_several_components_and_all_are_visited() -> None:
    s = load_scenario(EXAMPLES / "obstacles_hard_4x4.toml")
    n_comp = len(move_components(s, 0, "exact"))
    assert n_comp > 1
    optimum = dfs(s).cost.total
    for sol in (anneal(s, seed=0, iterations=2000), genetic(s, seed=0, generations=10)):
        assert sol.num_components == (n_comp,)
        assert sol.components_visited == (tuple(range(n_comp)),)
        assert sol.cost.total == pytest.approx(optimum)
    only_initial = anneal(s, seed=0, iterations=2000, components="initial")
    assert only_initial.components_visited == ((0,),) and only_initial.num_components == ()
    assert any("not analysed" in n for n in only_initial.notes)


def test_optimum_outside_the_initial_component_is_found(build) -> None:
    # hard centre obstacle on 3x3: from (0,0) to (0,2) the paths are the two-edge one over the top (the
    # initial path) and the six-edge detour round the bottom; no SBF move joins them
    s = build(3, 3, [((0, 0), (0, 2))], [(1, 1)], "hard")
    comps = move_components(s, 0, "exact")
    assert [len(c) for c in comps] == [1, 1] and comps[0] == [initial_path(s, 0)]
    optimum = dfs(s)
    assert optimum.paths != (initial_path(s, 0),)  # the detour covers more free nodes: cheaper
    for method in (anneal, genetic):
        stuck = method(s, seed=0, components="initial")
        assert stuck.paths == (initial_path(s, 0),) and stuck.cost.total > optimum.cost.total
        found = method(s, seed=0)
        assert found.paths == optimum.paths and found.components_visited == ((0, 1),)


def test_restarts_cover_every_combination_of_representatives(build) -> None:
    # two robots, each with two components: 4 restarts, trace = iterations x 4
    s = build(3, 3, [((0, 0), (0, 2)), ((2, 2), (2, 0))], [(1, 1)], "hard")
    sol = anneal(s, seed=0, iterations=50)
    assert sol.num_components == (2, 2)
    assert len(sol.trace) == 50 * 4
    assert sol.components_visited == ((0, 1), (0, 1))
    assert sol.cost.total == pytest.approx(dfs(s).cost.total)


# ----------------------------------------------------------------------------- registry and JSON


def test_registry_and_solve() -> None:
    s = load_scenario(EXAMPLES / "paper_3x3.toml")
    assert set(SOLVERS) == {"dfs", "anneal", "genetic", "cpsat"}
    calls: list[tuple[int, int]] = []
    sol = solve(s, "dfs", progress=lambda done, total: calls.append((done, total)))
    assert sol.method == "dfs" and calls and calls[-1][0] == calls[-1][1] == sol.evaluated
    with pytest.raises(ValueError, match="unknown method"):
        solve(s, "qaoa-not-yet")


def test_solution_to_dict_walks_paths_start_to_goal() -> None:
    s = load_scenario(EXAMPLES / "two_robots_4x4.toml")
    sol = dfs(s)
    d = json.loads(json.dumps(solution_to_dict(s, sol)))
    assert d["method"] == "dfs" and d["cost"] == sol.cost.total
    assert d["cost_parts"] == {"c1": sol.cost.c1, "c2": sol.cost.c2, "c3": sol.cost.c3}
    assert d["evaluated"] == sol.evaluated and d["paths_per_robot"] == list(sol.paths_per_robot)
    for r, (nodes, rb) in enumerate(zip(d["paths"], s.robots)):
        assert tuple(nodes[0]) == rb.start and tuple(nodes[-1]) == rb.goal
        assert [tuple(n) for n in nodes] == path_to_nodes(s.grid, sol.paths[r], rb.start)
