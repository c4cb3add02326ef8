"""Node visit terms in batches: the pair products of several nodes phased together by Hamming-weight phasing.

With ``products`` (the fault-tolerant choice) a node's visit gadget (:class:`~qcpp.gadgets.phase_visits.VisitPhase`)
computes ``z_ab = AND(y_a, y_b)`` for every pair of robots that can pass it and applies one ``RZ`` per ``z``, all
at the angle ``2 gamma coefficient``. Nodes of the grid mostly share that coefficient, so a batch of ``K`` nodes

1. computes every node's visit bits and pair products into its own clean ancillas, node after node: ``y_a`` is
   the first edge's qubit (two usable edges), ``OR(e0, e1) = e0 XOR e1 XOR AND(e0, e1)`` into a clean ancilla
   (three: one AND and 2 CX), or the OR of that and ``e2`` (four: two ANDs and 4 CX); then
   ``z_ab = AND(y_a, y_b)``. The edges are only ever controls (the single node's gadget flips them with X around
   its ANDs instead): an edge meets two nodes, and every node of the batch must read it as it is;
2. phases ``coefficient * sum z`` over all of them at once with Hamming-weight phasing
   (:class:`~qcpp.gadgets.phase_sums.SumsPhase` with one unit-weight form and ``M = 0``: a popcount of the ``n``
   products, then one rotation per bit of the count, ``floor(log2 n) + 1`` rotations instead of ``n``);
3. uncomputes the nodes in reverse order: every ancilla returns to |0> on every input.

A batch's nodes share no edge (the plan takes nodes of one checkerboard colour), so their compute halves act on
disjoint qubits and run side by side.

With ``m`` visitors of which ``m3`` have three and ``m4`` four usable edges, each node costs ``m3 + 2 m4 +
C(m, 2)`` ANDs and ``2 (2 m3 + 4 m4)`` CX (compute and mirror). Each rotation saved costs about one AND of the
popcount, so on the ``ft`` model (rotation 30 T, AND 4 T) a batch of ``n`` products saves about
``26 (n - log2 n)`` T. It holds every node's ancillas at once, so the plan sizes batches to the ancillas the phase
separator has anyway (:func:`qcpp.plan.phase_choice.visit_batches`).

Example:
    >>> g = VisitBatch("gamma_0", 8.0, (((0, 1), (2, 3), (4, 5)), ((6, 7), (8, 9), (10, 11))), tuple(range(12, 24)))
    >>> from qcpp.gadgets.phase_visits import VisitPhase
    >>> g.cost().rotations, 2 * VisitPhase("g", 8.0, ((0, 1), (2, 3), (4, 5)), (), True).cost().rotations
    (3, 6)
    >>> g.needs()[0] <= 12
    True
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from itertools import accumulate
from typing import NamedTuple

from qcpp.gadgets.phase_sums import SumsPhase
from qcpp.gadgets.phase_visits import visit_ancillas, with_ands
from qcpp.gadgets.pricing import PricedByKind
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate, and_, cx

__all__ = ["VisitBatch", "VisitBatchKind", "visit_batch_ancillas"]


def _hamming(n: int, coefficient: float, ancillas: tuple[int, ...] = ()) -> SumsPhase:
    """Hamming-weight phasing of ``coefficient * (sum of n bits)`` on qubits ``0 .. n - 1``."""
    return SumsPhase("gamma", (tuple((q, 1) for q in range(n)),), ((0.0,),), (coefficient,), ancillas)


def visit_batch_ancillas(sizes: tuple[int, ...], nodes: int) -> int:
    """Clean ancillas of a :class:`VisitBatch` of ``nodes`` nodes whose visitors have these numbers of usable
    edges: every node's visit bits and pair products, then the popcount of all products.

    >>> visit_batch_ancillas((2, 2), 1), visit_batch_ancillas((4, 4, 4, 4), 3)
    (1, 58)
    """
    m = len(sizes)
    products = nodes * (m * (m - 1) // 2)
    return nodes * visit_ancillas(sizes, True) + _hamming(products, 1.0).num_ancillas


class VisitBatchKind(NamedTuple):
    """Kind key of :class:`VisitBatch`: equal kinds, equal gates and costs up to qubit names.

    Attributes:
        gadget: ``"visit_batch"``.
        sizes: per visitor, its usable edges at each node (every node of a batch has the same).
        nodes: nodes in the batch.
        coefficient: the factor of every node's ``sum_{a<b} y_a y_b`` (the popcount's phase depends on it).
    """

    gadget: str
    sizes: tuple[int, ...]
    nodes: int
    coefficient: float


@dataclass(frozen=True)
class VisitBatch(PricedByKind):
    """Compute the visit bits and pair products of several nodes, phase all products at once, uncompute.

    Attributes:
        gamma: Symbol name of the layer's angle.
        coefficient: The factor of each node's ``sum_{a<b} y_a y_b`` (nonzero).
        nodes: Per node, per visitor, the qubits of its usable edges there (2 to 4); every node has the same
            numbers of usable edges per visitor, and no two nodes share an edge (so their halves run side by
            side, and the gadget's depth is its kind's).
        ancillas: Clean ancillas (at least :func:`visit_batch_ancillas` of them).
    """

    gamma: str
    coefficient: float
    nodes: tuple[tuple[tuple[int, ...], ...], ...]
    ancillas: tuple[int, ...]

    def __post_init__(self) -> None:
        if len({tuple(len(v) for v in node) for node in self.nodes}) != 1:
            raise ValueError("a visit batch needs at least one node, all with the same visitor sizes")
        edges = [q for node in self.nodes for v in node for q in v]
        if len(set(edges)) != len(edges):
            raise ValueError("the nodes of a visit batch must share no edge (take nodes of one checkerboard colour)")

    @classmethod
    def of_kind(cls, sizes: tuple[int, ...], nodes: int, coefficient: float) -> VisitBatch:
        """A batch of ``nodes`` nodes on abstract qubits (node ``i``'s edges after node ``i - 1``'s), no ancillas:
        what a kind costs.

        >>> VisitBatch.of_kind((2, 3), 2, 8.0).nodes
        (((0, 1), (2, 3, 4)), ((5, 6), (7, 8, 9)))
        """
        width = sum(sizes)
        node = tuple(tuple(range(end - k, end)) for k, end in zip(sizes, accumulate(sizes), strict=True))
        return cls("gamma", coefficient, tuple(tuple(tuple(i * width + q for q in v) for v in node)
                                               for i in range(nodes)), ())  # fmt: skip

    @property
    def _sizes(self) -> tuple[int, ...]:
        return tuple(len(v) for v in self.nodes[0])

    @property
    def kind(self) -> VisitBatchKind:
        """The visitors' edge counts, the number of nodes and the coefficient."""
        return VisitBatchKind("visit_batch", self._sizes, len(self.nodes), self.coefficient)

    def needs(self) -> tuple[int, int]:
        """The clean ancillas of :func:`visit_batch_ancillas`, no work ancillas."""
        return visit_batch_ancillas(self._sizes, len(self.nodes)), 0

    def _node(self, visitors: tuple[tuple[int, ...], ...], ancillas: Iterator[int]) -> tuple[list[Gate], list[int]]:
        """One node's compute gates (edges as controls only) and its pair products' qubits."""
        gates: list[Gate] = []
        bits: list[int] = []
        for edges in visitors:
            y = edges[0]
            for e in edges[1 : len(edges) - 1]:  # y = OR(y, e): AND into a clean ancilla, then both CX
                t = next(ancillas)
                gates += [and_(y, e, t), cx(y, t), cx(e, t)]
                y = t
            bits.append(y)
        products = []
        for a in range(len(bits)):
            for b in range(a + 1, len(bits)):
                z = next(ancillas)
                gates.append(and_(bits[a], bits[b], z))
                products.append(z)
        return gates, products

    def _phase(self, products: list[int]) -> SumsPhase:
        rest = self.ancillas[len(self.nodes) * visit_ancillas(self._sizes, True) :]
        return SumsPhase(self.gamma, (tuple((z, 1) for z in products),), ((0.0,),), (self.coefficient,), rest)

    def hamming(self) -> SumsPhase:
        """The phase on the pair products (Hamming-weight phasing), on abstract qubits: its kind and costs."""
        m = len(self._sizes)
        return _hamming(len(self.nodes) * (m * (m - 1) // 2), self.coefficient)

    @property
    def constant(self) -> float:
        """``c0``: the gadget applies ``exp(-i gamma (coefficient * sum z - c0))``."""
        return self.hamming().constant

    def node_costs(self) -> tuple[Cost, Cost]:
        """``(lowered, logical)`` cost of the nodes' compute halves and mirrors (all but the phase)."""
        m = len(self._sizes)
        ors = sum(k - 2 for k in self._sizes)  # ORs of two bits: one AND and 2 CX each
        ands, cxs = ors + m * (m - 1) // 2, 2 * 2 * ors
        return with_ands(len(self.nodes) * ands, Cost.of(cx=len(self.nodes) * cxs))

    def _kind_costs(self) -> tuple[Cost, Cost]:
        nodes, hw = self.node_costs(), self.hamming()
        return nodes[0] + hw.cost(), nodes[1] + hw.logical_cost()

    def emit(self) -> list[Gate]:
        compute: list[Gate] = []
        products: list[int] = []
        ancillas = iter(self.ancillas)
        for node in self.nodes:
            gates, zs = self._node(node, ancillas)
            compute += gates
            products += zs
        return [*compute, *self._phase(products).emit(), *(g.inverse() for g in reversed(compute))]
