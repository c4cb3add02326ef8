"""Shared strategies for circuit tests: random scenarios with random feasible paths."""

from __future__ import annotations

from hypothesis import strategies as st

from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import Grid
from qcpp.problem.scenario import Objective, Robot, Scenario


@st.composite
def scenarios(
    draw: st.DrawFn, max_side: int = 5, max_robots: int = 1, obstacles: bool = True
) -> Scenario:
    """A random valid scenario: sizes 2..max_side, random obstacles (soft or hard), random endpoints."""
    rows = draw(st.integers(2, max_side))
    cols = draw(st.integers(2, max_side))
    grid = Grid(rows, cols)
    nodes = list(grid.nodes)
    n_obs = draw(st.integers(0, min(3, len(nodes) - 2))) if obstacles else 0
    obs = sorted(draw(st.lists(st.sampled_from(nodes), min_size=n_obs, max_size=n_obs, unique=True)))
    free = [n for n in nodes if n not in obs]
    k = draw(st.integers(1, min(max_robots, len(free))))
    robots = []
    used_starts: set[tuple[int, int]] = set()
    for _ in range(k):
        start = draw(st.sampled_from([n for n in free if n not in used_starts]))
        goal = draw(st.sampled_from([n for n in free if n != start]))
        used_starts.add(start)
        robots.append(Robot(start, goal))
    mode = draw(st.sampled_from(["soft", "hard"]))
    try:
        s = Scenario(grid, tuple(robots), tuple(obs), Objective(obstacles=mode))
    except ScenarioError:  # unreachable goal in hard mode: fall back to soft
        s = Scenario(grid, tuple(robots), tuple(obs), Objective(obstacles="soft"))
    return s
