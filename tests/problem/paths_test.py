"""Paths as edge masks: enumeration against networkx, feasibility, node sequences, initial and shortest paths,
bit-vector conversions."""

from __future__ import annotations

import itertools
import random
from typing import Any

import networkx as nx
import numpy as np
import pytest

from qcpp.problem.grid import Grid, Node
from qcpp.problem.paths import (
    assignment_bits,
    assignment_from_bits,
    edges_of,
    enumerate_paths,
    initial_path,
    is_feasible,
    mask_from_bits,
    path_bits,
    path_from_nodes,
    path_to_nodes,
    paths_matrix,
    shortest_path,
)


def nx_paths(rows: int, cols: int, start: Node, goal: Node, blocked: tuple[Node, ...] = ()) -> list[list[Node]]:
    """All simple start-goal node sequences by networkx (the independent reference)."""
    graph = nx.grid_2d_graph(rows, cols)
    graph.remove_nodes_from(blocked)
    return [list(map(tuple, p)) for p in nx.all_simple_paths(graph, start, goal)]


def mask_of(grid: Grid, nodes: list[Node]) -> int:
    """Edge mask of a node sequence, via the grid's edge numbering only."""
    return sum(1 << grid.edge_index(u, v) for u, v in zip(nodes, nodes[1:]))


CASES = [
    # (rows, cols, start, goal, obstacles, mode)
    (2, 2, (0, 0), (1, 1), (), "soft"),
    (2, 3, (0, 1), (1, 1), (), "soft"),
    (3, 3, (0, 0), (2, 2), (), "soft"),
    (3, 3, (1, 1), (0, 1), (), "soft"),
    (3, 4, (1, 1), (1, 2), (), "soft"),
    (3, 4, (0, 2), (2, 1), (), "soft"),
    (4, 4, (0, 0), (3, 3), (), "soft"),
    (4, 4, (1, 2), (2, 1), (), "soft"),
    (4, 5, (2, 2), (0, 4), (), "soft"),
    (3, 3, (0, 0), (2, 2), ((1, 1),), "soft"),  # soft obstacles do not remove paths
    (3, 3, (0, 0), (2, 2), ((1, 1),), "hard"),
    (3, 4, (0, 0), (2, 3), ((1, 1), (1, 2)), "hard"),
    (4, 4, (1, 2), (3, 1), ((1, 1), (3, 0)), "hard"),
    (4, 4, (0, 1), (3, 2), ((1, 1), (2, 2), (1, 2)), "hard"),
    (5, 4, (4, 0), (0, 3), ((2, 1), (2, 2)), "hard"),
]


@pytest.mark.parametrize(("rows", "cols", "start", "goal", "obstacles", "mode"), CASES)
def test_enumerate_paths_matches_networkx(
    build: Any, rows: int, cols: int, start: Node, goal: Node, obstacles: tuple[Node, ...], mode: str
) -> None:
    s = build(rows, cols, [(start, goal)], obstacles, mode=mode)
    got = enumerate_paths(s, 0)
    ref = nx_paths(rows, cols, start, goal, obstacles if mode == "hard" else ())
    assert len(got) == len(ref)
    assert len(set(got)) == len(got)  # no duplicates
    assert set(got) == {mask_of(s.grid, p) for p in ref}
    for m in got:
        assert is_feasible(s, 0, m)
        nodes = path_to_nodes(s.grid, m, start)
        assert nodes[0] == start and nodes[-1] == goal
        assert path_from_nodes(s.grid, nodes) == m
    assert got == enumerate_paths(s, 0)  # deterministic


def test_enumeration_order_is_dfs_up_left_right_down(build: Any) -> None:
    """The documented order: depth-first, neighbours tried up, left, right, down (checked by a recursive DFS)."""
    s = build(3, 4, [((1, 1), (2, 3))])
    g = s.grid
    out: list[int] = []

    def dfs(node: Node, visited: list[Node], mask: int) -> None:
        for m in g.neighbours(node):  # up, left, right, down (tested in grid_test)
            if m in visited:
                continue
            e = 1 << g.edge_index(node, m)
            if m == (2, 3):
                out.append(mask | e)
            else:
                dfs(m, [*visited, m], mask | e)

    dfs((1, 1), [(1, 1)], 0)
    assert enumerate_paths(s, 0) == out


@pytest.mark.parametrize(("rows", "cols"), [(2, 2), (2, 3), (3, 2)])
def test_is_feasible_on_every_mask(build: Any, rows: int, cols: int) -> None:
    """Exhaustive: over all 2^E edge subsets and every start/goal pair, feasible == a networkx simple path."""
    g = Grid(rows, cols)
    for start, goal in itertools.permutations(g.nodes, 2):
        s = build(rows, cols, [(start, goal)])
        want = {mask_of(g, p) for p in nx_paths(rows, cols, start, goal)}
        for m in range(1 << g.num_edges):
            assert is_feasible(s, 0, m) == (m in want), (start, goal, edges_of(m))


def test_is_feasible_on_every_mask_3x3_hard(build: Any) -> None:
    g = Grid(3, 3)
    for obstacles, start, goal in [(((1, 1),), (0, 0), (2, 2)), (((0, 1),), (0, 0), (0, 2)), ((), (1, 0), (1, 2))]:
        s = build(3, 3, [(start, goal)], obstacles, mode="hard")
        want = {mask_of(g, p) for p in nx_paths(3, 3, start, goal, obstacles)}
        for m in range(1 << g.num_edges):
            assert is_feasible(s, 0, m) == (m in want)


def test_is_feasible_rejects_hand_made_cases(build: Any) -> None:
    s = build(3, 3, [((0, 0), (2, 2))])
    g = s.grid
    good = mask_of(g, [(0, 0), (0, 1), (0, 2), (1, 2), (2, 2)])
    assert is_feasible(s, 0, good)
    bad = {
        "empty": 0,
        "branch": good | mask_of(g, [(0, 1), (1, 1)]),
        "loop attached": mask_of(g, [(0, 0), (0, 1), (1, 1), (1, 0), (0, 0)]) | mask_of(g, [(1, 1), (2, 1), (2, 2)]),
        "disconnected cycle": mask_of(g, [(0, 0), (1, 0), (2, 0), (2, 1), (2, 2)])
        | mask_of(g, [(0, 1), (0, 2), (1, 2), (1, 1), (0, 1)]),
        "wrong end": mask_of(g, [(0, 0), (0, 1), (0, 2), (1, 2)]),
        "wrong start": mask_of(g, [(0, 1), (0, 2), (1, 2), (2, 2)]),
        "overshoot past the goal": mask_of(g, [(0, 0), (0, 1), (1, 1), (2, 1), (2, 2), (1, 2)]),
        "through the start": mask_of(g, [(1, 0), (0, 0), (0, 1), (0, 2), (1, 2), (2, 2)]),
        "two pieces": mask_of(g, [(0, 0), (0, 1)]) | mask_of(g, [(2, 1), (2, 2)]),
    }
    for name, m in bad.items():
        assert not is_feasible(s, 0, m), name
    hard = build(3, 3, [((0, 0), (2, 2))], [(0, 1)], mode="hard")
    assert not is_feasible(hard, 0, good)  # crosses the hard obstacle
    soft = build(3, 3, [((0, 0), (2, 2))], [(0, 1)], mode="soft")
    assert is_feasible(soft, 0, good)  # soft obstacles only cost


def test_path_to_nodes_rejects_non_paths() -> None:
    g = Grid(3, 3)
    cases = [
        (0, (0, 0), "no edges"),
        (mask_of(g, [(0, 0), (0, 1)]), (2, 2), "does not have exactly one"),
        (mask_of(g, [(1, 0), (1, 1), (1, 2)]) | mask_of(g, [(1, 1), (0, 1)]), (1, 0), "path edges"),
        (mask_of(g, [(0, 0), (0, 1)]) | mask_of(g, [(2, 1), (2, 2)]), (0, 0), "connected"),
        (mask_of(g, [(0, 0), (0, 1), (1, 1), (1, 0), (0, 0)]), (0, 0), "does not have exactly one"),
    ]
    for m, start, msg in cases:
        with pytest.raises(ValueError, match=msg):
            path_to_nodes(g, m, start)
    with pytest.raises(ValueError, match="no grid edge"):
        path_from_nodes(g, [(0, 0), (1, 1)])


def test_node_sequence_round_trip() -> None:
    g = Grid(4, 4)
    for start, goal in [((0, 0), (3, 3)), ((1, 1), (2, 2)), ((0, 2), (3, 1))]:
        for p in nx_paths(4, 4, start, goal):
            m = path_from_nodes(g, p)
            assert m == mask_of(g, p) and m.bit_count() == len(p) - 1
            assert path_to_nodes(g, m, start) == p
            assert path_to_nodes(g, m, goal) == p[::-1]
            assert edges_of(m) == sorted(g.edge_index(u, v) for u, v in zip(p, p[1:]))


def _sign(x: int) -> int:
    return (x > 0) - (x < 0)


@pytest.mark.parametrize(("rows", "cols"), [(2, 2), (3, 4), (4, 3), (5, 5)])
def test_initial_path_is_horizontal_then_vertical(build: Any, rows: int, cols: int) -> None:
    g = Grid(rows, cols)
    for start, goal in itertools.permutations(g.nodes, 2):
        s = build(rows, cols, [(start, goal)])
        nodes = path_to_nodes(g, initial_path(s, 0), start)
        # expected: walk the start's row to the goal's column, then the goal's column to the goal's row
        want = [start]
        while want[-1][1] != goal[1]:
            want.append((start[0], want[-1][1] + _sign(goal[1] - start[1])))
        while want[-1][0] != goal[0]:
            want.append((want[-1][0] + _sign(goal[0] - start[0]), goal[1]))
        assert nodes == want


def test_initial_path_ignores_soft_obstacles_and_falls_back_in_hard_mode(build: Any) -> None:
    start, goal, obstacles = (0, 0), (2, 3), [(0, 2)]
    want = [(0, 0), (0, 1), (0, 2), (0, 3), (1, 3), (2, 3)]
    soft = build(3, 4, [(start, goal)], obstacles, mode="soft")
    assert path_to_nodes(soft.grid, initial_path(soft, 0), start) == want
    hard = build(3, 4, [(start, goal)], obstacles, mode="hard")
    p = initial_path(hard, 0)
    assert is_feasible(hard, 0, p)
    assert (0, 2) not in path_to_nodes(hard.grid, p, start)
    graph = nx.grid_2d_graph(3, 4)
    graph.remove_nodes_from(obstacles)
    assert p.bit_count() == nx.shortest_path_length(graph, start, goal)
    # hard mode keeps the paper's path when it is not blocked
    clear = build(3, 4, [(start, goal)], [(2, 0)], mode="hard")
    assert path_to_nodes(clear.grid, initial_path(clear, 0), start) == want


def test_initial_and_shortest_paths_in_hard_mode_exhaustive(build: Any) -> None:
    """Every single-obstacle hard 3x4 scenario: the initial path is feasible and, when the paper's path is
    blocked, a shortest one."""
    g = Grid(3, 4)
    for ob in g.nodes:
        graph = nx.grid_2d_graph(3, 4)
        graph.remove_node(ob)
        free = [n for n in g.nodes if n != ob]
        for start, goal in itertools.permutations(free, 2):
            s = build(3, 4, [(start, goal)], [ob], mode="hard")
            dist = nx.shortest_path_length(graph, start, goal)
            p, q = initial_path(s, 0), shortest_path(s, 0)
            assert is_feasible(s, 0, p) and is_feasible(s, 0, q)
            assert q.bit_count() == dist
            paper = mask_of(g, _paper_nodes(start, goal))
            if ob in _paper_nodes(start, goal):
                assert p == q
            else:
                assert p == paper


def _paper_nodes(start: Node, goal: Node) -> list[Node]:
    nodes = [start]
    while nodes[-1][1] != goal[1]:
        nodes.append((start[0], nodes[-1][1] + _sign(goal[1] - start[1])))
    while nodes[-1][0] != goal[0]:
        nodes.append((nodes[-1][0] + _sign(goal[0] - start[0]), goal[1]))
    return nodes


def test_bit_vectors(build: Any) -> None:
    rng = random.Random(7)
    for mode in ("soft", "hard"):
        s = build(10, 10, [((0, 0), (9, 9)), ((0, 9), (9, 0))], [(4, 4), (5, 6)], mode=mode)
        ve = s.variable_edges
        masks = [sum(1 << e for e in ve if rng.random() < 0.4) for _ in range(20)]
        mat = paths_matrix(s, masks)
        assert mat.shape == (20, len(ve)) and mat.dtype == np.uint8
        for m, row in zip(masks, mat, strict=True):
            want = [(m >> e) & 1 for e in ve]  # the grid has 180 edges: well past one 64-bit word
            assert row.tolist() == want
            assert path_bits(s, m).tolist() == want
            assert mask_from_bits(s, row) == m
        assert paths_matrix(s, []).shape == (0, len(ve))
        bits = assignment_bits(s, masks[:2])
        assert bits.tolist() == mat[0].tolist() + mat[1].tolist()
        assert assignment_from_bits(s, bits) == tuple(masks[:2])
        with pytest.raises(ValueError, match="expected 2 paths"):
            assignment_bits(s, masks[:1])
