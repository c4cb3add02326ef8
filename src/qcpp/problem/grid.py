"""The rectangular grid: nodes, stably numbered edges, and plaquettes (four-node sub-grids).

Numbering rules (stable: they never depend on dict or set order, and later become qubit indices):

* Node ``(row, col)`` has index ``row * cols + col`` (row-major).
* Edges are numbered by walking the nodes in row-major order and, at each node, taking first the edge to
  its right neighbour ``(row, col + 1)`` (if any), then the edge to its lower neighbour ``(row + 1, col)``
  (if any). An edge is stored as ``(u, v)`` with ``u`` the node that comes first in row-major order.
* Plaquettes are numbered row-major by their top-left corner. Corners run clockwise:
  ``a = (r, c)``, ``b = (r, c + 1)``, ``c = (r + 1, c + 1)``, ``d = (r + 1, c)``; the plaquette's edges are
  ``ab`` (top), ``bc`` (right), ``cd`` (bottom), ``da`` (left).

Example:
    >>> g = Grid(2, 3)
    >>> g.num_edges
    7
    >>> g.edges[:3]
    (((0, 0), (0, 1)), ((0, 0), (1, 0)), ((0, 1), (0, 2)))
    >>> g.plaquettes[1].corners
    ((0, 1), (0, 2), (1, 2), (1, 1))
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

Node = tuple[int, int]
Edge = tuple[Node, Node]


@dataclass(frozen=True)
class Plaquette:
    """A four-node sub-grid.

    Attributes:
        index: Row-major index of the plaquette (by its top-left corner).
        corners: ``(a, b, c, d)`` clockwise from the top-left corner.
        edges: Grid edge indices ``(ab, bc, cd, da)``.
        outer_edges: For each corner ``a, b, c, d`` in order, the grid edge indices incident to that corner
            that are not edges of this plaquette (0 to 2 of them, ascending).
    """

    index: int
    corners: tuple[Node, Node, Node, Node]
    edges: tuple[int, int, int, int]
    outer_edges: tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...], tuple[int, ...]]

    @property
    def edge_mask(self) -> int:
        """The plaquette's four edges as a bit mask over grid edge indices."""
        m = 0
        for e in self.edges:
            m |= 1 << e
        return m


@dataclass(frozen=True)
class Grid:
    """A ``rows x cols`` grid graph with 4-neighbour edges.

    Args:
        rows: Number of node rows (at least 1; scenarios require at least 2).
        cols: Number of node columns.
    """

    rows: int
    cols: int

    @property
    def num_nodes(self) -> int:
        return self.rows * self.cols

    @property
    def num_edges(self) -> int:
        return self.rows * (self.cols - 1) + self.cols * (self.rows - 1)

    def contains(self, node: Node) -> bool:
        """Whether ``node`` lies on the grid."""
        r, c = node
        return 0 <= r < self.rows and 0 <= c < self.cols

    def node_index(self, node: Node) -> int:
        """Row-major index of ``node``."""
        return node[0] * self.cols + node[1]

    @cached_property
    def nodes(self) -> tuple[Node, ...]:
        """All nodes in row-major order."""
        return tuple((r, c) for r in range(self.rows) for c in range(self.cols))

    @cached_property
    def edges(self) -> tuple[Edge, ...]:
        """All edges in the documented stable order (see the module docstring)."""
        out: list[Edge] = []
        for r in range(self.rows):
            for c in range(self.cols):
                if c + 1 < self.cols:
                    out.append(((r, c), (r, c + 1)))
                if r + 1 < self.rows:
                    out.append(((r, c), (r + 1, c)))
        return tuple(out)

    def edge_index(self, u: Node, v: Node) -> int:
        """Index of the edge between neighbouring nodes ``u`` and ``v`` (in either order).

        Raises:
            KeyError: if ``u`` and ``v`` are not 4-neighbours on this grid.
        """
        (r, c), (r2, c2) = (u, v) if u <= v else (v, u)
        right, down = r2 == r and c2 == c + 1, c2 == c and r2 == r + 1
        if not (right or down) or not (r >= 0 and c >= 0 and r2 < self.rows and c2 < self.cols):
            raise KeyError(f"no grid edge between {u} and {v} on a {self.rows}x{self.cols} grid")
        # the stable order: row-major nodes, each with its right edge then its down edge (no table to build)
        before = r * (2 * self.cols - 1) + c * (2 if r + 1 < self.rows else 1)
        return before if right else before + (1 if c + 1 < self.cols else 0)

    @cached_property
    def incident_edges(self) -> tuple[tuple[int, ...], ...]:
        """For each node index, the indices of the edges touching it (ascending)."""
        inc: list[list[int]] = [[] for _ in range(self.num_nodes)]
        for i, (u, v) in enumerate(self.edges):
            inc[self.node_index(u)].append(i)
            inc[self.node_index(v)].append(i)
        return tuple(tuple(x) for x in inc)

    def neighbours(self, node: Node) -> tuple[Node, ...]:
        """The 4-neighbours of ``node`` on the grid, in the order up, left, right, down."""
        r, c = node
        cand = ((r - 1, c), (r, c - 1), (r, c + 1), (r + 1, c))
        return tuple(n for n in cand if self.contains(n))

    @cached_property
    def plaquettes(self) -> tuple[Plaquette, ...]:
        """All plaquettes, row-major by top-left corner."""
        out = []
        for r in range(self.rows - 1):
            for c in range(self.cols - 1):
                a, b, cc, d = (r, c), (r, c + 1), (r + 1, c + 1), (r + 1, c)
                edges = (
                    self.edge_index(a, b),
                    self.edge_index(b, cc),
                    self.edge_index(cc, d),
                    self.edge_index(d, a),
                )
                own = set(edges)
                outer = tuple(
                    tuple(e for e in self.incident_edges[self.node_index(n)] if e not in own)
                    for n in (a, b, cc, d)
                )
                out.append(Plaquette(len(out), (a, b, cc, d), edges, outer))  # type: ignore[arg-type]
        return tuple(out)

    @cached_property
    def edge_sites(self) -> tuple[tuple[int, int], ...]:
        """For each edge index, its midpoint on the doubled lattice (node ``(r, c)`` at ``(2r, 2c)``): where a
        layout that keeps the grid's geometry puts the edge.

        >>> Grid(2, 2).edge_sites
        ((0, 1), (1, 0), (1, 2), (2, 1))
        """
        return tuple((r0 + r1, c0 + c1) for (r0, c0), (r1, c1) in self.edges)

    @cached_property
    def edge_nodes(self) -> tuple[tuple[int, int], ...]:
        """For each edge index, the pair of node indices it joins."""
        return tuple((self.node_index(u), self.node_index(v)) for u, v in self.edges)


def node_symmetries(rows: int, cols: int) -> list[Callable[[Node], Node]]:
    """The rotations and reflections that map a ``rows x cols`` grid onto itself, the identity first (4 on a
    rectangle, 8 on a square), as maps of ``(row, col)`` nodes.

    >>> [f((0, 1)) for f in node_symmetries(2, 3)]
    [(0, 1), (1, 1), (0, 1), (1, 1)]
    >>> len(node_symmetries(3, 3))
    8
    """
    maps: list[Callable[[Node], Node]] = [
        lambda n: n,
        lambda n: (rows - 1 - n[0], n[1]),
        lambda n: (n[0], cols - 1 - n[1]),
        lambda n: (rows - 1 - n[0], cols - 1 - n[1]),
    ]
    if rows == cols:
        maps += [
            lambda n: (n[1], n[0]),
            lambda n: (cols - 1 - n[1], rows - 1 - n[0]),
            lambda n: (n[1], rows - 1 - n[0]),
            lambda n: (cols - 1 - n[1], n[0]),
        ]
    return maps
