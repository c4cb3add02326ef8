"""Diagonal phases from RZ and RZZ: the coupling construction, and the Pauli-Z form every phase gadget uses.

A diagonal polynomial ``f = k + sum_q l_q v_q + sum_{q,p} Q_qp v_q v_p`` over bits ``v_q`` held on qubits
(``v_q`` the qubit's value, or its complement when the qubit is listed as negated) is
``c0 + sum_q h_q Z_q + sum J_qp Z_q Z_p`` with ``v = (1 - s Z) / 2`` (``s = -1`` when negated)::

    c0 = k + sum l / 2 + sum Q / 4,   h_q = -s_q (l_q / 2 + sum_p Q_qp / 4),   J_qp = s_q s_p Q_qp / 4

so ``exp(-i gamma (f - c0))`` is ``RZ(2 gamma h_q)`` on each qubit and ``RZZ(2 gamma J_qp)`` on each pair
(:func:`ising_form`). :class:`IsingPhase` emits exactly that: rotations by qubit, then the couplings in the
given order. Lowered: 2 CX and one rotation per coupling, one rotation per linear term, nothing else
(the peephole pass finds nothing to cancel: consecutive couplings never share their qubit pair).

Example:
    >>> c0, h, J = ising_form({0: 1.0}, {(0, 1): 2.0})
    >>> c0, h, J
    (1.0, {0: -1.0, 1: -0.5}, {(0, 1): 0.5})
    >>> g = IsingPhase("gamma_0", tuple(h.items()), tuple((a, b, v) for (a, b), v in J.items()))
    >>> [str(x) for x in g.emit()]
    ['rz(-2.0*gamma_0) 0', 'rz(-gamma_0) 1', 'rzz(gamma_0) 0 1']
    >>> g.cost().to_dict()
    {'cx': 2, 'rz': 3}
"""

from __future__ import annotations

from collections.abc import Collection, Hashable, Mapping
from dataclasses import dataclass
from typing import NamedTuple, TypeVar

from qcpp.ir.angles import Angle
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate, rz, rzz

__all__ = ["COEFFICIENT_TOLERANCE", "IsingKind", "IsingPhase", "ising_cost", "ising_form"]

#: Coefficients smaller than this (absolute) are zero: they only arise from float round-off.
COEFFICIENT_TOLERANCE = 1e-12

K = TypeVar("K", bound=Hashable)


def ising_form(
    linear: Mapping[K, float],
    quadratic: Mapping[tuple[K, K], float],
    negated: Collection[K] = (),
    constant: float = 0.0,
) -> tuple[float, dict[K, float], dict[tuple[K, K], float]]:
    """The Pauli-Z form of a polynomial in bits (see the module docstring).

    Args:
        linear: ``l_q`` by bit key.
        quadratic: ``Q_qp`` by ordered key pair (the order is kept for emission; ``(q, q)`` not allowed).
        negated: Keys whose qubit holds the complement of the bit.
        constant: ``k``.

    Returns:
        ``(c0, h, J)``; ``h`` and ``J`` without coefficients below :data:`COEFFICIENT_TOLERANCE`, ``h`` in
        first-appearance order (linear keys first, then quadratic ones).
    """
    neg = set(negated)
    c0 = constant
    h: dict[K, float] = {}
    get = h.get
    for q, lq in linear.items():
        c0 += lq / 2
        h[q] = get(q, 0.0) - lq / 2
    J: dict[tuple[K, K], float] = {}
    for key, v in quadratic.items():  # keys are distinct: each is a new J entry
        q, p = key
        w = v / 4
        c0 += w
        h[q] = get(q, 0.0) - w
        h[p] = get(p, 0.0) - w
        J[key] = w if not neg or (q in neg) == (p in neg) else -w
    tol = COEFFICIENT_TOLERANCE
    h = {q: (-v if q in neg else v) for q, v in h.items() if abs(v) > tol}
    J = {k: v for k, v in J.items() if abs(v) > tol}
    return c0, h, J


def ising_cost(linear: int, couplings: int) -> Cost:
    """Lowered (and logical) cost of an :class:`IsingPhase` with these numbers of terms, by its kind.

    >>> ising_cost(3, 1).to_dict()
    {'cx': 2, 'rz': 4}
    """
    return Cost.of(cx=2 * couplings, rz=linear + couplings)


class IsingKind(NamedTuple):
    """Kind key of :class:`IsingPhase` (and of the plan's deferred data-qubit rotations): its term counts.

    Attributes:
        gadget: ``"ising"``.
        linear: RZ gates (linear terms).
        couplings: RZZ gates (couplings).
    """

    gadget: str
    linear: int
    couplings: int


@dataclass(frozen=True)
class IsingPhase:
    """``exp(-i gamma (sum h_q Z_q + sum J_qp Z_q Z_p))`` as RZ then RZZ gates.

    Attributes:
        gamma: Symbol name of the layer's angle.
        linear: ``(qubit, h)`` pairs, in emission order.
        couplings: ``(qubit, qubit, J)`` triples, in emission order.
    """

    gamma: str
    linear: tuple[tuple[int, float], ...]
    couplings: tuple[tuple[int, int, float], ...]

    @property
    def kind(self) -> IsingKind:
        return IsingKind("ising", len(self.linear), len(self.couplings))

    def cost(self) -> Cost:
        """2 CX and one rotation per coupling, one rotation per linear term (:func:`ising_cost`)."""
        return ising_cost(len(self.linear), len(self.couplings))

    def logical_cost(self) -> Cost:
        """The same (no AND in this construction)."""
        return self.cost()

    def needs(self) -> tuple[int, int]:
        """None: rotations only."""
        return 0, 0

    def emit(self) -> list[Gate]:
        """The RZ gates, then the RZZ gates."""
        g = self.gamma
        out = [rz(Angle.symbol(g, 2.0 * v), q) for q, v in self.linear]
        out += [rzz(Angle.symbol(g, 2.0 * v), a, b) for a, b, v in self.couplings]
        return out
