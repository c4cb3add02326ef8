"""Gadgets: constructions that emit their gates *and* know their lowered cost without emitting them.

A gadget is a small frozen value (a dataclass) bound to its qubits and angles. Every gadget kind implements
the :class:`Gadget` protocol:

* ``emit()`` - the gadget's gates in the high-level IR (:mod:`qcpp.ir.gates`), in time order;
* ``cost()`` - the :class:`~qcpp.ir.cost.Cost` of those gates after :func:`qcpp.lowering.passes.lower`,
  computed from the gadget's parameters alone (a closed form or a sum over the gadgets it calls), never by
  emitting. Invariant (tested for every kind the compiler emits):
  ``cost() == Cost.count(lower(<circuit of emit()>))``;
* ``logical_cost()`` - the same for ``lower(..., basis=LOGICAL_BASIS)``: ``and``/``and_dg``/``ccx`` kept whole,
  which is what the fault-tolerant view prices (an AND costs 4 T, its uncompute a measurement and no T);
* ``kind`` - a hashable key: two gadgets with equal kinds have equal costs. Estimates sum
  ``cost(kind) * multiplicity`` over a circuit's call graph and never materialise a gate list;
* ``needs()`` - ``(logic temporaries, work ancillas)``: the clean ancillas the gadget uses and the ``work``
  ancillas the lowering of its multi-controlled X gates adds. Equal kinds have equal needs, so the call graph
  (:class:`qcpp.plan.call_graph.GadgetKind`) records them per kind.

Example:
    >>> from qcpp.gadgets import Gadget
    >>> Gadget.__name__
    'Gadget'
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from typing import Protocol, runtime_checkable

from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate

__all__ = ["Gadget"]


@runtime_checkable
class Gadget(Protocol):
    """What every construction offers (see the package docstring)."""

    @property
    def kind(self) -> Hashable:
        """Key that determines the cost."""
        ...

    def cost(self) -> Cost:
        """Lowered cost, without emitting."""
        ...

    def logical_cost(self) -> Cost:
        """Cost with ``and``/``and_dg``/``ccx`` kept whole, without emitting."""
        ...

    def needs(self) -> tuple[int, int]:
        """``(logic temporaries, work ancillas)`` the gadget's gates and their lowering use."""
        ...

    def emit(self) -> Sequence[Gate]:
        """High-level gates, in time order."""
        ...
