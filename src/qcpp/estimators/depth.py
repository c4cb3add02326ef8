"""Depths of a lowered gate sequence: all gates, two-qubit gates only, and arbitrary rotations only.

* ``depth``: ASAP layering, every gate one layer on its qubits (Qiskit's ``depth()``);
* ``two_qubit_depth``: two-qubit gates add a layer, other gates add nothing but a gate on three or more qubits
  synchronises its qubits (Qiskit's ``depth(filter_function=...)``, as :mod:`qcpp.estimators.counts`);
* ``rotation_depth``: the same with ``rz`` (an arbitrary rotation in a lowered circuit) as the only gate that
  adds a layer and every multi-qubit gate synchronising: the number of rotation layers, the
  ``rotationDepth`` input of the physical estimator (:mod:`qcpp.estimators.physical`).

A :class:`Depth` is ``exact`` (computed on the gates) or a ``bound``: ``+`` (sequential composition) gives a
bound unless one side is empty, ASAP layering only shortening a concatenation.

Example:
    >>> d = depths([("h", (0,)), ("cx", (0, 1)), ("rz", (1,), (0.1,)), ("rz", (0,), (0.2,)), ("cx", (0, 1))], 2)
    >>> d.depth, d.two_qubit_depth, d.rotation_depth, d.kind
    (4, 2, 1, 'exact')
    >>> (d + d).depth, (d + d).kind
    (8, 'bound')
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any, Literal

__all__ = ["Depth", "DepthKind", "advance", "depths"]

DepthKind = Literal["exact", "bound"]


@dataclass(frozen=True)
class Depth:
    """The three depths of the module docstring, and whether they are ``exact`` or a ``bound``."""

    depth: int = 0
    two_qubit_depth: int = 0
    rotation_depth: int = 0
    kind: DepthKind = "exact"

    def __add__(self, other: Depth) -> Depth:
        if not isinstance(other, Depth):
            return NotImplemented
        if other == Depth():
            return self
        if self == Depth():
            return other
        return Depth(
            self.depth + other.depth,
            self.two_qubit_depth + other.two_qubit_depth,
            self.rotation_depth + other.rotation_depth,
            "bound",
        )

    def __mul__(self, k: int) -> Depth:
        if not isinstance(k, int) or k < 0:
            return NotImplemented
        if k == 0:
            return Depth()
        if k == 1:
            return self
        return Depth(self.depth * k, self.two_qubit_depth * k, self.rotation_depth * k, "bound")

    __rmul__ = __mul__


def advance(
    gates: Iterable[tuple[Any, ...]], lv: list[int], l2: list[int], lr: list[int] | None = None
) -> None:
    """The one ASAP loop: advance the per-qubit levels over ``gates``, in place.

    Args:
        gates: gate tuples ``(name, qubits, ...)``.
        lv, l2, lr: levels of ``depth``, ``two_qubit_depth`` and (if given) ``rotation_depth``.
    """
    for g in gates:
        qs = g[1]
        n = len(qs)
        if n == 1:
            q = qs[0]
            lv[q] += 1
            if lr is not None and g[0] == "rz":
                lr[q] += 1
        elif n == 2:
            a, b = qs
            x, y = lv[a], lv[b]
            lv[a] = lv[b] = (x if x > y else y) + 1
            x, y = l2[a], l2[b]
            l2[a] = l2[b] = (x if x > y else y) + 1
            if lr is not None:
                x, y = lr[a], lr[b]
                lr[a] = lr[b] = x if x > y else y
        elif n:
            m = max([lv[q] for q in qs]) + 1
            m2 = max([l2[q] for q in qs])
            for q in qs:
                lv[q] = m
                l2[q] = m2
            if lr is not None:
                mr = max([lr[q] for q in qs])
                for q in qs:
                    lr[q] = mr


def depths(gates: Iterable[tuple[Any, ...]], num_qubits: int) -> Depth:
    """The three ASAP depths of ``gates`` (see the module docstring).

    Args:
        gates: gate tuples ``(name, qubits, ...)``.
        num_qubits: one more than the largest qubit index.

    Returns:
        An ``exact`` :class:`Depth`.
    """
    lv, l2, lr = [0] * num_qubits, [0] * num_qubits, [0] * num_qubits
    advance(gates, lv, l2, lr)
    return Depth(max(lv, default=0), max(l2, default=0), max(lr, default=0), "exact")
