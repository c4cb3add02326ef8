"""The degree term of a node that several robots can pass: ``coefficient * sum_{a<b} y_a y_b`` on visit bits.

On a feasible assignment a robot uses 0 or 2 of its edges at a node it does not start or end at, so
"robot ``a`` visits the node" is the bit ``y_a`` = OR of all but one of its edges there
(:class:`qcpp.problem.feasible_cost.VisitGroup`). The gadget

1. computes each ``y_a``: with two usable edges ``y_a`` *is* the first edge's qubit (no gate); with three,
   ``NOT y = AND(NOT e0, NOT e1)`` into a clean ancilla (X on the two edges, one AND); with four,
   ``NOT y = AND(AND(NOT e0, NOT e1), NOT e2)`` into two clean ancillas (X on three edges, two ANDs);
2. applies ``exp(-i gamma (coefficient sum_{a<b} y_a y_b - c0))`` as RZ on every visit bit and RZZ on every
   pair (:func:`~qcpp.gadgets.phase_ising.ising_form`, complemented bits handled by sign);
3. uncomputes with the mirror (``and_dg``, X): ancillas return to |0> on every input, not only feasible ones.

With ``products`` (chosen for the fault-tolerant target) the gadget also computes ``z_ab = AND(y_a, y_b)`` for
every pair into clean ancillas and phases ``coefficient * sum z_ab`` with one RZ per pair: ``C(m, 2)`` more ANDs
(4 T each, the uncompute free) buy ``m`` fewer rotations (30 T each) and no RZZ.

Cost with ``m`` visitors of which ``m3`` have three and ``m4`` four usable edges:
``CX = 6 m3 + 12 m4 + 2 C(m, 2)``, rotations ``m + C(m, 2)``, ANDs ``m3 + 2 m4`` (4 T each in the
fault-tolerant view; their uncompute 0 T). The coupling alternative (expand ``y_a y_b`` into the
``|E_a| |E_b|`` products of edge bits) costs ``2 |E_a| |E_b|`` CX per pair.

Example:
    >>> g = VisitPhase("gamma_0", 8.0, ((0, 1, 2, 3), (4, 5)), (6, 7))
    >>> g.cost().cx, g.cost().rotations, g.logical_cost()["and"]
    (14, 3, 2)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

from qcpp.gadgets.phase_ising import IsingPhase, ising_form
from qcpp.gadgets.pricing import PricedByKind
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate, and_, x

__all__ = ["AND_COST", "AND_DG_COST", "VisitPhase", "VisitsKind", "visit_ancillas", "with_ands"]


def _visit_costs(sizes: tuple[int, ...], products: bool, nonzero: bool) -> tuple[Cost, Cost]:
    """``(cost, logical cost)`` of a :class:`VisitPhase`: they depend on its kind only (so :meth:`VisitPhase.cost`
    looks them up per kind in :data:`~qcpp.gadgets.pricing.COSTS`; a 30x30 plan prices thousands of nodes)."""
    g = VisitPhase("g", 1.0 if nonzero else 0.0, tuple(tuple(range(k)) for k in sizes), (), products)
    ands, xs = g._counts()
    ph = g.phase()[1].cost()
    return with_ands(ands, Cost.of(x=xs) + ph)

AND_COST = Cost.of(cx=3, h=2, t=2, tdg=2, sdg=1)
"""Lowered ``and``."""
AND_DG_COST = Cost.of(cx=3, h=2, t=2, tdg=2, s=1)
"""Lowered ``and_dg``."""


def with_ands(ands: int, rest: Cost) -> tuple[Cost, Cost]:
    """``(lowered, logical)`` cost of ``ands`` ANDs with their ``and_dg`` mirrors, plus ``rest`` (no AND in it).

    >>> with_ands(1, Cost.of(cx=2))[0].cx, with_ands(1, Cost.of(cx=2))[1].to_dict()
    (8, {'and': 1, 'and_dg': 1, 'cx': 2})
    """
    return ands * (AND_COST + AND_DG_COST) + rest, Cost.of({"and": ands, "and_dg": ands}) + rest


def visit_ancillas(sizes: tuple[int, ...], products: bool = False) -> int:
    """Clean ancillas :class:`VisitPhase` needs for visitors with these numbers of usable edges."""
    m = len(sizes)
    return sum({2: 0, 3: 1, 4: 2}[k] for k in sizes) + (m * (m - 1) // 2 if products else 0)


class VisitsKind(NamedTuple):
    """Kind key of :class:`VisitPhase`: equal kinds, equal gates and costs up to qubit names.

    Attributes:
        gadget: ``"visits"``.
        sizes: per visitor, its usable edges at the node (2 to 4).
        products: the pairwise products are computed into ancillas (the fault-tolerant choice).
        rotates: the coefficient is nonzero (a zero coefficient emits no rotation).
    """

    gadget: str
    sizes: tuple[int, ...]
    products: bool
    rotates: bool


@dataclass(frozen=True)
class VisitPhase(PricedByKind):
    """Compute visit bits, phase their pairwise products, uncompute (see the module docstring).

    Attributes:
        gamma: Symbol name of the layer's angle.
        coefficient: The factor of ``sum_{a<b} y_a y_b``.
        visitors: Per visitor, the qubits of its usable edges at the node (2 to 4).
        ancillas: Clean ancillas (at least :func:`visit_ancillas` of the sizes).
    """

    gamma: str
    coefficient: float
    visitors: tuple[tuple[int, ...], ...]
    ancillas: tuple[int, ...]
    products: bool = False

    @property
    def kind(self) -> VisitsKind:
        """The visitors' edge counts, ``products`` and whether the coefficient is nonzero."""
        return VisitsKind("visits", tuple(len(v) for v in self.visitors), self.products, self.coefficient != 0)

    def needs(self) -> tuple[int, int]:
        """The clean ancillas of :func:`visit_ancillas`, no work ancillas."""
        return visit_ancillas(tuple(len(v) for v in self.visitors), self.products), 0

    def _layout(self) -> tuple[list[Gate], list[tuple[int, bool]]]:
        """The compute gates and, per visitor, ``(qubit, holds the complement)``."""
        gates: list[Gate] = []
        bits: list[tuple[int, bool]] = []
        anc = iter(self.ancillas)
        for edges in self.visitors:
            k = len(edges)
            if k == 2:
                bits.append((edges[0], False))
            elif k == 3:
                t = next(anc)
                gates += [x(edges[0]), x(edges[1]), and_(edges[0], edges[1], t)]
                bits.append((t, True))
            elif k == 4:
                t1, t2 = next(anc), next(anc)
                gates += [x(edges[0]), x(edges[1]), x(edges[2]), and_(edges[0], edges[1], t1), and_(t1, edges[2], t2)]
                bits.append((t2, True))
            else:
                raise ValueError(f"a visitor has {k} usable edges; 2 to 4 are possible on a grid")
        return gates, bits

    def _products_layout(self) -> tuple[list[Gate], list[int]]:
        """Visit bits made positive (X on the complemented ones), then one AND per pair into clean ancillas."""
        gates, bits = self._layout()
        used = sum(1 for q, neg in bits if neg) + sum(1 for v in self.visitors if len(v) == 4)
        anc = iter(self.ancillas[used:])
        gates += [x(q) for q, neg in bits if neg]
        zs: list[int] = []
        for a in range(len(bits)):
            for b in range(a + 1, len(bits)):
                z = next(anc)
                gates.append(and_(bits[a][0], bits[b][0], z))
                zs.append(z)
        return gates, zs

    def phase(self, labels: list[tuple[int, bool]] | None = None) -> tuple[float, IsingPhase]:
        """``(c0, the RZ/RZZ gadget)`` of ``coefficient * sum y_a y_b`` on the visit bits (or, with
        :attr:`products`, of ``coefficient * sum z_ab`` on the pair ANDs: one RZ each)."""
        if self.products:
            m = len(self.visitors)
            zs = [z for z, _ in labels] if labels is not None else list(range(m * (m - 1) // 2))
            c0, h, _ = ising_form(dict.fromkeys(zs, self.coefficient), {})
            return c0, IsingPhase(self.gamma, tuple(h.items()), ())
        bits = labels if labels is not None else [(i, len(v) > 2) for i, v in enumerate(self.visitors)]
        quad = {(bits[a][0], bits[b][0]): self.coefficient for a in range(len(bits)) for b in range(a + 1, len(bits))}
        c0, h, j = ising_form({}, quad, negated=[q for q, neg in bits if neg])
        return c0, IsingPhase(self.gamma, tuple(h.items()), tuple((a, b, v) for (a, b), v in j.items()))

    @property
    def constant(self) -> float:
        """``c0``: the gadget applies ``exp(-i gamma (value - c0))``."""
        return self.phase()[0]

    def _counts(self) -> tuple[int, int]:
        m = len(self.visitors)
        m3 = sum(1 for v in self.visitors if len(v) == 3)
        m4 = sum(1 for v in self.visitors if len(v) == 4)
        ands = m3 + 2 * m4
        xs = 4 * m3 + 6 * m4
        if self.products:
            ands += m * (m - 1) // 2
            xs += 2 * (m3 + m4)
        return ands, xs

    def _kind_costs(self) -> tuple[Cost, Cost]:
        return _visit_costs(tuple(len(v) for v in self.visitors), self.products, self.coefficient != 0)

    def emit(self) -> list[Gate]:
        if self.products:
            compute, zs = self._products_layout()
            _, ph = self.phase([(z, False) for z in zs])
        else:
            compute, bits = self._layout()
            _, ph = self.phase(bits)
        return [*compute, *ph.emit(), *(g.inverse() for g in reversed(compute))]
