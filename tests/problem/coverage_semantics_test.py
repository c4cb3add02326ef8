"""The cost's coverage and overlap are preferences, not constraints (docs/paper-notes.md, "Coverage, overlap and
collisions"): on the problem-model page's 4x5 field the exhaustive optimum leaves a free node unvisited and has the
two robots share edges."""

from __future__ import annotations

import qcpp


def test_the_optimum_need_not_cover_every_node_nor_keep_the_robots_apart() -> None:
    s = qcpp.grid_scenario(4, 5, robots=[((0, 0), (3, 4)), ((3, 0), (0, 4))], obstacles=[(1, 1), (2, 3)])
    best = qcpp.solve(s, "dfs")  # exhaustive: a proven optimum
    assert best.cost.total == qcpp.solve(s, "cpsat").cost.total == -2.0
    first, second = best.paths
    assert bin(first & second).count("1") >= 1  # edges driven by both robots
    visited = set().union(*(set(p) for p in best.node_paths(s)))
    free = {(r, c) for r in range(4) for c in range(5)} - set(s.obstacles)
    assert free - visited  # a free node no robot visits
    goal = s.robots[0].goal
    assert goal in best.node_paths(s)[1][1:-1]  # robot 1 drives through robot 0's goal
