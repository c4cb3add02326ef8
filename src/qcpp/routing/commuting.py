"""A run of commuting two-qubit phases routed in any order: qubits move until every pair has met once.

The register phase of the balance arithmetic (:class:`qcpp.gadgets.phase_sums.SumsPhase`) and an Ising phase are
runs of *blocks* ``cx a b; <diagonal one-qubit gates>; cx a b``, each a diagonal operator (an ``rzz`` when the
gate between is an ``rz`` on ``b``), with diagonal one-qubit gates between them. Diagonal operators commute, so
the blocks may run in any order, while SABRE routes them in the order written. :func:`commuting_blocks` finds
such a run in a window's middle (:func:`qcpp.routing.windows.route_window`); :func:`route_blocks` routes it as a
commutation-aware greedy: run every block whose two qubits are adjacent, then make the SWAP that most lowers the
sum of the remaining blocks' distances (a SWAP right after a block on the same pair first: the two fuse,
:func:`qcpp.routing.sabre.window_cx`); where no SWAP lowers it, move one qubit of the nearest block along a
shortest path until that block runs. Every greedy step lowers a non-negative integer and every other step ends
with a block run, so the route is finite. The window router keeps whichever of SABRE's and this route gives the
whole window fewer CX (:attr:`qcpp.routing.options.RoutingOptions.commuting_phases`).

Example:
    >>> from qcpp.ir.gates import cx, h, rz
    >>> gates = [h(0), cx(0, 1), rz(0.1, 1), cx(0, 1), cx(0, 2), rz(0.2, 2), cx(0, 2)]
    >>> commuting_blocks(gates, 0)
    ((1, 3), (4, 6))
    >>> line = [[1], [0, 2], [1, 3], [2]]  # qubits 0 - 1 - 2 - 3; the blocks join (0, 3), (1, 2), (0, 1)
    >>> route_blocks([(0, 3), (1, 2), (0, 1)], line)
    [('gate', 2), ('gate', 3), ('gate', 4), ('gate', 5), ('swap', (0, 1)), ('swap', (1, 2)), ('gate', 0), ('gate', 1)]
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Sequence

from qcpp.ir.gates import Gate

__all__ = ["commuting_blocks", "graph_distances", "route_blocks"]


def commuting_blocks(gates: Sequence[Gate], compute: int) -> tuple[tuple[int, int], ...] | None:
    """The blocks of a window's commuting middle: between its first and last ``compute`` two-qubit gates (its
    compute and uncompute, :func:`qcpp.routing.windows.mirror_length`), every two-qubit gate is a ``cx`` whose
    next two-qubit gate is the same ``cx`` (a block), and every one-qubit gate after the first block's first ``cx``
    and before the last block's last ``cx`` is diagonal.

    Args:
        gates: A window's gates (one-qubit and two-qubit).
        compute: Two-qubit gates of its compute (and of its uncompute).

    Returns:
        Each block's two gate indices in ``gates``, in order; ``None`` if the middle is not such a run (or empty).
    """
    twoq = [i for i, g in enumerate(gates) if len(g[1]) == 2]
    twoq = twoq[compute : len(twoq) - compute]
    if not twoq or len(twoq) % 2:
        return None
    blocks = tuple(zip(twoq[::2], twoq[1::2], strict=True))
    for i, j in blocks:
        if gates[i][0] != "cx" or gates[j][0] != "cx" or gates[i][1] != gates[j][1]:
            return None
    if any(not g.spec.diagonal for g in gates[blocks[0][0] : blocks[-1][1]] if len(g[1]) == 1):
        return None
    return blocks


def _shortest_step(neighbours: Sequence[Sequence[int]], source: int, target: int) -> int:
    """A neighbour of ``source`` on a shortest path to ``target``: the one through which a breadth-first search from
    ``target`` (neighbours in the graph's order) first reaches ``source``."""
    back = {target: target}
    todo = deque([target])
    while todo:  # breadth first from the target, so a neighbour's label says how far it is
        p = todo.popleft()
        for r in neighbours[p]:
            if r not in back:
                back[r] = p
                todo.append(r)
        if source in back:
            break
    return back[source]


def route_blocks(
    pairs: Sequence[tuple[int, int]],
    neighbours: Sequence[Sequence[int]],
    dist: Sequence[Sequence[int]] | None = None,
) -> list[tuple]:
    """Route commuting blocks on a connected graph (module docs): each block runs once, when its qubits are adjacent.

    Args:
        pairs: Each block's two qubits, as the graph nodes where they start.
        neighbours: The graph, as each node's neighbours.
        dist: Its all-pairs distances (:func:`graph_distances`), if already known.

    Returns:
        Events in order: ``("gate", 2 j)`` and ``("gate", 2 j + 1)`` run block ``j`` (its two ``cx``, on the nodes
        its qubits are on then), ``("swap", (u, v))`` exchanges the contents of adjacent nodes ``u < v``. Ties
        between SWAPs go to the lowest-numbered nodes, so the route depends only on ``pairs`` and the graph.
    """
    dist = graph_distances(neighbours) if dist is None else dist
    state = _Blocks(pairs, neighbours, dist)
    events: list[tuple] = []
    ran = state.adjacent(range(len(pairs)))
    chase: int | None = None  # a block whose first qubit is moving towards its second
    while True:
        for j in ran:
            events += [("gate", 2 * j), ("gate", 2 * j + 1)]
            state.run(j)
            chase = None if chase == j else chase
        if not state.left:
            return events
        best = None
        if chase is None:
            last = None
            if ran:  # a SWAP on the pair of the block run last fuses with it
                u, v = state.at[pairs[ran[-1]][0]], state.at[pairs[ran[-1]][1]]
                last = (min(u, v), max(u, v))
            best = state.best_swap(last)
            if best is None:
                chase = min(state.left, key=lambda j: (dist[state.at[pairs[j][0]]][state.at[pairs[j][1]]], j))
        if best is None:
            a, b = pairs[chase]  # type: ignore[index]
            p = state.at[a]
            r = _shortest_step(neighbours, p, state.at[b])
            best = (min(p, r), max(p, r))
        events.append(("swap", best))
        ran = state.adjacent(sorted({j for q in state.swap(*best) for j in state.blocks[q]}))


class _Blocks:
    """The blocks left and where their qubits are, with each qubit's summed distance to its partners kept for the
    nodes it could move to (its node and the node's neighbours), updated as qubits move and blocks run."""

    def __init__(self, pairs: Sequence[tuple[int, int]], neighbours: Sequence[Sequence[int]],
                 dist: Sequence[Sequence[int]]) -> None:  # fmt: skip
        self.pairs = pairs
        self.neighbours = neighbours
        self.dist = dist
        self.at: dict[int, int] = {}  # qubit (named by its start node) -> node now
        self.holder: dict[int, int] = {}  # node -> qubit of a block on it
        self.blocks: dict[int, list[int]] = {}  # qubit -> its blocks left
        for j, (a, b) in enumerate(pairs):
            for q in (a, b):
                self.at[q] = self.holder[q] = q
                self.blocks.setdefault(q, []).append(j)
        self.left = set(range(len(pairs)))
        self.near: dict[int, dict[int, int]] = {q: self._near(q) for q in self.blocks}

    def _partners(self, q: int) -> list[int]:
        pairs = self.pairs
        return [pairs[j][1] if pairs[j][0] == q else pairs[j][0] for j in self.blocks[q]]

    def _near(self, q: int) -> dict[int, int]:
        """Per node ``q`` could move to, the sum of its distances to its partners' nodes from there."""
        p = self.at[q]
        where = [self.at[o] for o in self._partners(q)]
        dist = self.dist
        return {r: sum(dist[r][x] for x in where) for r in (p, *self.neighbours[p])}

    def adjacent(self, candidates: Iterable[int]) -> list[int]:
        """The blocks of ``candidates`` left whose qubits are adjacent, in order."""
        at, dist, pairs = self.at, self.dist, self.pairs
        return [j for j in candidates if j in self.left and dist[at[pairs[j][0]]][at[pairs[j][1]]] == 1]

    def run(self, j: int) -> None:
        """Block ``j`` has run: it leaves its qubits' partners and their summed distances."""
        a, b = self.pairs[j]
        self.left.discard(j)
        for q, o in ((a, b), (b, a)):
            self.blocks[q].remove(j)
            x = self.at[o]
            near = self.near[q]
            for r in near:
                near[r] -= self.dist[r][x]

    def best_swap(self, fused: tuple[int, int] | None) -> tuple[int, int] | None:
        """The SWAP that most lowers the remaining blocks' summed distances (a SWAP on ``fused`` first among equals,
        then the lowest-numbered nodes), or ``None`` if none lowers it."""
        best: tuple[int, bool, int, int] | None = None
        holder, near = self.holder, self.near
        for q in sorted(q for q, js in self.blocks.items() if js):
            p = self.at[q]
            mine = near[q]
            for r in self.neighbours[p]:
                delta = mine[r] - mine[p]
                h = holder.get(r)
                if h is not None:
                    theirs = near[h]
                    delta += theirs[p] - theirs[r]
                u, v = (p, r) if p < r else (r, p)
                key = (delta, (u, v) != fused, u, v)
                if best is None or key < best:
                    best = key
        return None if best is None or best[0] >= 0 else (best[2], best[3])

    def swap(self, u: int, v: int) -> tuple[int, ...]:
        """Exchange the contents of nodes ``u`` and ``v``; the qubits of blocks that moved."""
        holder, at, dist = self.holder, self.at, self.dist
        moved = tuple(q for q in (holder.get(u), holder.get(v)) if q is not None)
        a, b = holder.pop(u, None), holder.pop(v, None)
        if a is not None:
            at[a], holder[v] = v, a
        if b is not None:
            at[b], holder[u] = u, b
        for q in moved:
            old, new = (u, v) if at[q] == v else (v, u)
            for o in self._partners(q):
                if o not in moved:
                    near = self.near[o]
                    for r in near:
                        near[r] += dist[r][new] - dist[r][old]
        for q in moved:
            self.near[q] = self._near(q)
        return moved


def graph_distances(neighbours: Sequence[Sequence[int]]) -> list[list[int]]:
    """All-pairs distances of a graph (SciPy's unweighted shortest paths, as
    :func:`qcpp.hardware.device.distances`), as lists of ints for fast indexing; ``len(neighbours)`` between
    components.

    >>> graph_distances([[1], [0, 2], [1]])
    [[0, 1, 2], [1, 0, 1], [2, 1, 0]]
    """
    import numpy as np
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import shortest_path

    n = len(neighbours)
    rows = [p for p in range(n) for _ in neighbours[p]]
    cols = [r for p in range(n) for r in neighbours[p]]
    graph = csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    dist = shortest_path(graph, directed=False, unweighted=True)
    dist[np.isinf(dist)] = n
    return dist.astype(int).tolist()  # type: ignore[no-any-return]
