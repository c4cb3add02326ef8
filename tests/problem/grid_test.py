"""Grid numbering: nodes, edges and plaquettes follow the documented stable order (they become qubit indices)."""

from __future__ import annotations

import dataclasses
import itertools

import networkx as nx
import pytest

from qcpp.problem.grid import Grid

SIZES = [(r, c) for r in range(1, 7) for c in range(1, 7)]


@pytest.mark.parametrize(("rows", "cols"), SIZES)
def test_nodes_are_row_major(rows: int, cols: int) -> None:
    g = Grid(rows, cols)
    assert g.num_nodes == rows * cols == len(g.nodes)
    k = 0
    for r in range(rows):
        for c in range(cols):
            assert g.nodes[k] == (r, c)
            assert g.node_index((r, c)) == k
            k += 1


@pytest.mark.parametrize(("rows", "cols"), SIZES)
def test_edge_order_and_count(rows: int, cols: int) -> None:
    g = Grid(rows, cols)
    expected = []
    for r in range(rows):
        for c in range(cols):
            if c + 1 < cols:
                expected.append(((r, c), (r, c + 1)))  # right edge first
            if r + 1 < rows:
                expected.append(((r, c), (r + 1, c)))  # then the down edge
    assert list(g.edges) == expected
    assert g.num_edges == len(g.edges) == rows * (cols - 1) + cols * (rows - 1)
    assert g.num_edges == nx.grid_2d_graph(rows, cols).number_of_edges()
    for i, (u, v) in enumerate(g.edges):
        assert u < v  # stored with the row-major-first node first
        assert g.edge_index(u, v) == g.edge_index(v, u) == i
        assert g.edge_nodes[i] == (g.node_index(u), g.node_index(v))


def test_edge_index_rejects_non_neighbours() -> None:
    g = Grid(3, 3)
    for u, v in [((0, 0), (1, 1)), ((0, 0), (0, 2)), ((0, 0), (0, 0)), ((2, 2), (2, 3))]:
        with pytest.raises(KeyError, match="no grid edge"):
            g.edge_index(u, v)


@pytest.mark.parametrize(("rows", "cols"), SIZES)
def test_incidence_and_neighbours(rows: int, cols: int) -> None:
    g = Grid(rows, cols)
    for node in g.nodes:
        r, c = node
        want = [(r - 1, c), (r, c - 1), (r, c + 1), (r + 1, c)]  # up, left, right, down
        want = [n for n in want if 0 <= n[0] < rows and 0 <= n[1] < cols]
        assert list(g.neighbours(node)) == want
        inc = g.incident_edges[g.node_index(node)]
        assert list(inc) == sorted(inc)
        assert sorted(inc) == sorted(g.edge_index(node, m) for m in want)
    assert all(g.contains(n) for n in g.nodes)
    assert not any(g.contains(n) for n in [(-1, 0), (0, -1), (rows, 0), (0, cols)])


@pytest.mark.parametrize(("rows", "cols"), SIZES)
def test_plaquettes(rows: int, cols: int) -> None:
    g = Grid(rows, cols)
    assert len(g.plaquettes) == (rows - 1) * (cols - 1)
    tops = [(r, c) for r in range(rows - 1) for c in range(cols - 1)]  # row-major by top-left corner
    for k, (q, (r, c)) in enumerate(zip(g.plaquettes, tops, strict=True)):
        assert q.index == k
        a, b, cc, d = (r, c), (r, c + 1), (r + 1, c + 1), (r + 1, c)  # clockwise from top-left
        assert q.corners == (a, b, cc, d)
        assert q.edges == (g.edge_index(a, b), g.edge_index(b, cc), g.edge_index(cc, d), g.edge_index(d, a))
        assert q.edge_mask == sum(1 << e for e in q.edges)
        assert q.edge_mask.bit_count() == 4
        for corner, outer, own in zip(q.corners, q.outer_edges, ((3, 0), (0, 1), (1, 2), (2, 3)), strict=True):
            # every outer edge touches its corner and is not an edge of the plaquette
            for e in outer:
                assert corner in g.edges[e]
                assert e not in q.edges
            assert list(outer) == sorted(outer)
            # the corner's two plaquette edges are the ones listed for it
            assert all(corner in g.edges[q.edges[i]] for i in own)
            # together: all edges at the corner
            assert sorted(outer + tuple(q.edges[i] for i in own)) == list(g.incident_edges[g.node_index(corner)])
            on_row_border = corner[0] in (0, rows - 1)
            on_col_border = corner[1] in (0, cols - 1)
            expected = 2 - on_row_border - on_col_border  # interior 2, boundary 1, grid corner 0
            assert len(outer) == expected


def test_plaquette_edges_cover_interior_edges_twice() -> None:
    """Each interior edge belongs to two plaquettes, each boundary edge to one (independent consistency check)."""
    for rows, cols in itertools.product(range(2, 6), repeat=2):
        g = Grid(rows, cols)
        count = [0] * g.num_edges
        for q in g.plaquettes:
            for e in q.edges:
                count[e] += 1
        for e, (u, v) in enumerate(g.edges):
            horizontal = u[0] == v[0]
            border = u[0] in (0, rows - 1) if horizontal else u[1] in (0, cols - 1)
            assert count[e] == (1 if border else 2)


def test_values_are_frozen() -> None:
    g = Grid(2, 2)
    with pytest.raises(dataclasses.FrozenInstanceError):
        g.rows = 3  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        g.plaquettes[0].index = 1  # type: ignore[misc]
    assert Grid(2, 3) == Grid(2, 3) and hash(Grid(2, 3)) == hash(Grid(2, 3))
