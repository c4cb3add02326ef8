"""Explorability: do SBF moves connect all feasible paths?

Free grids: for every start/goal pair on 3x3, 3x4 and 4x4 and the corner-to-corner pairs on 5x5, the paths
reachable from the initial path under the ``exact`` rule are exactly all feasible paths; the ``paper`` rule
restricted to moves that stay feasible connects them too. (Unordered pairs suffice: sbf_test shows the
rules and the feasible paths do not depend on the direction, and a connected move graph is connected from
any start.)

Hard obstacles: over every obstacle set of size 1 and 2 (and 3 on grids up to 3x4) and every start/goal
pair, the move graph can split into several components. The sweep is exhaustive up to the grid's
symmetries (mirror images and rotations have the same number of components, which
``test_component_count_is_symmetric`` checks on a seeded sample); no sampling.
"""

from __future__ import annotations

import functools
import itertools
import random
from dataclasses import dataclass
from pathlib import Path

import pytest

from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import Grid, Node, node_symmetries
from qcpp.problem.paths import enumerate_paths, initial_path, is_feasible
from qcpp.problem.sbf import move_components, reachable_paths, representatives, sbf_logic
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.problem.scenario_io import load_scenario

ROOT = Path(__file__).resolve().parents[2]
NOTES = ROOT / "docs" / "paper-notes.md"


def scenario(rows: int, cols: int, start: Node, goal: Node, obstacles: tuple[Node, ...] = (), mode: str = "soft"):
    return scenario_from_dict(
        {
            "grid": {"rows": rows, "cols": cols, "obstacles": [list(o) for o in obstacles]},
            "robots": [{"start": list(start), "goal": list(goal)}],
            "objective": {"obstacles": mode},
        }
    )


def free_pairs(rows: int, cols: int) -> list[tuple[Node, Node]]:
    if (rows, cols) == (5, 5):
        return [((0, 0), (4, 4)), ((0, 0), (0, 4))]  # diagonal corners, corners on one side
    return list(itertools.combinations(Grid(rows, cols).nodes, 2))


# ---------------------------------------------------------------- free grids


FREE_SIZES = [(3, 3), (3, 4), (4, 4), pytest.param(5, 5, marks=pytest.mark.heavy)]
"""Free grids swept over every start and goal; 5x5 (300 pairs) in the heavy run."""


@pytest.mark.slow
@pytest.mark.parametrize(("rows", "cols"), FREE_SIZES)
def test_exact_rule_reaches_every_path_from_the_initial_path(rows: int, cols: int) -> None:
    for start, goal in free_pairs(rows, cols):
        s = scenario(rows, cols, start, goal)
        paths = enumerate_paths(s, 0)
        reached = reachable_paths(s, 0, "exact")
        assert reached[0] == initial_path(s, 0)
        assert len(reached) == len(set(reached))
        assert set(reached) == set(paths), (start, goal)


@pytest.mark.slow
@pytest.mark.parametrize(("rows", "cols"), FREE_SIZES)
def test_paper_rule_restricted_to_feasible_moves_is_connected_too(rows: int, cols: int) -> None:
    for start, goal in free_pairs(rows, cols):
        comps = move_components(scenario(rows, cols, start, goal), 0, "paper")
        assert len(comps) == 1, (start, goal)


def test_reachable_from_any_start() -> None:
    """The move relation is symmetric, so any path reaches all the others (spot check from random paths)."""
    rng = random.Random(3)
    for start, goal in [((0, 0), (3, 3)), ((1, 1), (2, 2)), ((0, 1), (3, 1))]:
        s = scenario(4, 4, start, goal)
        paths = enumerate_paths(s, 0)
        for p in rng.sample(paths, 3):
            assert set(reachable_paths(s, 0, "exact", start=p)) == set(paths)


# ---------------------------------------------------------------- hard obstacles


Key = tuple[tuple[Node, ...], tuple[Node, ...]]


def images(rows: int, cols: int, obstacles: tuple[Node, ...], ends: tuple[Node, Node]) -> set[Key]:
    return {
        (tuple(sorted(map(f, obstacles))), tuple(sorted(map(f, ends)))) for f in node_symmetries(rows, cols)
    }


@dataclass(frozen=True)
class HardResult:
    rows: int
    cols: int
    obstacles: tuple[Node, ...]
    start: Node
    goal: Node
    orbit: int  # number of distinct scenarios this one stands for
    num_paths: int
    sizes: tuple[int, ...]  # component sizes, initial path's component first


SWEEP = {(2, 3): (1, 2, 3), (2, 4): (1, 2, 3), (3, 3): (1, 2, 3), (3, 4): (1, 2, 3), (4, 4): (1, 2)}


@functools.cache
def hard_sweep(rows: int, cols: int) -> tuple[HardResult, ...]:
    g = Grid(rows, cols)
    seen: set[Key] = set()
    out = []
    for k in SWEEP[(rows, cols)]:
        for obstacles in itertools.combinations(g.nodes, k):
            free = [n for n in g.nodes if n not in obstacles]
            for start, goal in itertools.combinations(free, 2):
                imgs = images(rows, cols, obstacles, (start, goal))
                if min(imgs) in seen:
                    continue
                seen.add(min(imgs))
                try:
                    s = scenario(rows, cols, start, goal, obstacles, "hard")
                except ScenarioError as exc:
                    assert exc.field == "robots[0].goal" and "cannot be reached" in exc.reason
                    continue
                out.append(HardResult(rows, cols, obstacles, start, goal, len(imgs), *_check_components(s)))
    return tuple(out)


def _check_components(s: Scenario) -> tuple[int, tuple[int, ...]]:
    """move_components partitions enumerate_paths; with several components, one representative each and BFS
    from each representative covers exactly its component."""
    paths = enumerate_paths(s, 0)
    comps = move_components(s, 0, "exact")
    flat = [p for c in comps for p in c]
    assert len(flat) == len(set(flat)) == len(paths)
    assert set(flat) == set(paths)
    assert initial_path(s, 0) in comps[0]
    if len(comps) > 1:
        reps = representatives(s, 0, "exact")
        assert len(reps) == len(comps)
        for rep, comp in zip(reps, comps, strict=True):
            assert rep == comp[0]
            assert set(reachable_paths(s, 0, "exact", start=rep)) == set(comp)
    return len(paths), tuple(len(c) for c in comps)


@pytest.mark.slow
@pytest.mark.parametrize(("rows", "cols"), list(SWEEP))
def test_hard_obstacle_components(rows: int, cols: int) -> None:
    results = hard_sweep(rows, cols)
    assert results
    scenarios = sum(r.orbit for r in results)
    multi = [r for r in results if len(r.sizes) > 1]
    worst = max(len(r.sizes) for r in results)
    example = max(results, key=lambda r: (len(r.sizes), -len(r.obstacles), -r.num_paths))
    print(
        f"\n{rows}x{cols} hard, obstacles {SWEEP[(rows, cols)]}: {scenarios} scenarios "
        f"({len(results)} up to symmetry), {sum(r.orbit for r in multi)} with >1 component, worst {worst}: "
        f"obstacles {example.obstacles} S {example.start} G {example.goal} components {example.sizes}"
    )
    if (rows, cols) == (3, 3):  # the only enclosed node of a 3x3 grid is its centre
        assert all(r.obstacles == ((1, 1),) for r in multi)
    if rows == 2:  # no node of a 2-row grid is enclosed: no splits there
        assert not multi


@pytest.mark.parametrize(("rows", "cols"), [(3, 4), pytest.param(4, 4, marks=pytest.mark.heavy)], ids=["3x4", "4x4"])
def test_component_count_is_symmetric(rows: int, cols: int) -> None:
    """Mirror images and rotations of a scenario have the same component sizes (this justifies the symmetry
    reduction of the sweep); checked on a seeded sample of the grid's scenarios."""
    rng = random.Random(2024)
    sweep = hard_sweep(rows, cols)
    sample = rng.sample(sweep, 25) + [r for r in sweep if len(r.sizes) > 2][:5]
    for r in sample:
        for f in node_symmetries(rows, cols)[1:]:
            obs = tuple(sorted(map(f, r.obstacles)))
            s = scenario(rows, cols, f(r.start), f(r.goal), obs, "hard")
            assert sorted(len(c) for c in move_components(s, 0, "exact")) == sorted(r.sizes)


def draw(grid: Grid, mask: int, start: Node, goal: Node, obstacles: tuple[Node, ...]) -> list[str]:
    """ASCII picture: ``S``/``G`` endpoints, ``X`` obstacles, ``o`` other nodes, ``---``/``|`` path edges."""
    lines = []
    for r in range(grid.rows):
        row = ""
        for c in range(grid.cols):
            n = (r, c)
            row += "S" if n == start else "G" if n == goal else "X" if n in obstacles else "o"
            if c + 1 < grid.cols:
                row += "---" if mask >> grid.edge_index(n, (r, c + 1)) & 1 else "   "
        lines.append(row)
        if r + 1 < grid.rows:
            lines.append("   ".join("|" if mask >> grid.edge_index((r, c), (r + 1, c)) & 1 else " "
                                    for c in range(grid.cols)).rstrip())
    return lines


def side_by_side(pictures: list[list[str]], gap: str = "      ") -> str:
    width = max(len(line) for p in pictures for line in p)
    return "\n".join(gap.join(p[i].ljust(width) for p in pictures).rstrip() for i in range(len(pictures[0])))


def test_smallest_split_is_documented() -> None:
    """The smallest scenario (grid size, then obstacles, then paths) whose move graph splits: every plaquette
    touches the single obstacle, so no move is possible and every path is its own component."""
    multi = [r for size in SWEEP for r in hard_sweep(*size) if len(r.sizes) > 1]
    r = min(multi, key=lambda r: (r.rows * r.cols, r.rows, len(r.obstacles), r.num_paths, r.obstacles, r.start))
    s = scenario(r.rows, r.cols, r.start, r.goal, r.obstacles, "hard")
    assert all(sbf_logic(s, 0, q).never for q in s.grid.plaquettes)
    assert r.sizes == (1,) * r.num_paths
    picture = side_by_side([draw(s.grid, p, r.start, r.goal, r.obstacles) for p in enumerate_paths(s, 0)])
    assert picture in NOTES.read_text(encoding="utf-8"), "\n" + picture


def test_bundled_hard_example_has_the_worst_case_split() -> None:
    """examples/obstacles_hard_4x4.toml: non-corner endpoints, initial path by the BFS fallback, and as
    many components as the worst case of the exhaustive 4x4 sweep."""
    s = load_scenario(ROOT / "examples" / "obstacles_hard_4x4.toml")
    rb = s.robots[0]
    corners = {(0, 0), (0, s.grid.cols - 1), (s.grid.rows - 1, 0), (s.grid.rows - 1, s.grid.cols - 1)}
    assert rb.start not in corners and rb.goal not in corners
    assert s.objective.obstacles == "hard"
    comps = move_components(s, 0, "exact")
    assert len(comps) == max(len(r.sizes) for r in hard_sweep(s.grid.rows, s.grid.cols))
    assert all(is_feasible(s, 0, p) for c in comps for p in c)
    # the paper's horizontal-then-vertical path would cross an obstacle, so the fallback was used
    (r0, c0), c1 = rb.start, rb.goal[1]
    paper_nodes = [(r0, c) for c in range(min(c0, c1), max(c0, c1) + 1)] + [
        (r, c1) for r in range(min(r0, rb.goal[0]), max(r0, rb.goal[0]) + 1)
    ]
    assert any(n in s.obstacle_set for n in paper_nodes)
