"""Pricing per gadget kind: one process-wide cache of what is known per kind key, and the mixin that uses it.

Gadgets of equal :attr:`~qcpp.gadgets.Gadget.kind` have equal costs, so a cost is computed once per kind and
looked up by the key afterwards (:data:`COSTS`). The estimators keep their other per-kind facts (depth profiles,
own depth, depth bounds) as named tables of the same cache, so :meth:`CostCache.clear` forgets everything known
per kind at once. The call graph (:class:`qcpp.plan.call_graph.GadgetKind`) reads its kinds' costs from here;
gadget classes whose cost depends on their kind only price themselves here through :class:`PricedByKind`.

Example:
    >>> from qcpp.gadgets.phase_ising import IsingPhase
    >>> g = IsingPhase("gamma", ((0, 1.0),), ())
    >>> COSTS.costs(g.kind, lambda: (g.cost(), g.logical_cost()))[0] == g.cost()
    True
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Any

from qcpp.ir.cost import Cost

__all__ = ["COSTS", "CostCache", "PricedByKind"]


class CostCache:
    """What is known per kind key, computed once: named tables, the costs one of them (see the module docstring).

    Example:
        >>> from qcpp.gadgets.phase_ising import IsingPhase
        >>> g = IsingPhase("gamma", ((0, 1.0),), ())
        >>> cache = CostCache()
        >>> cache.costs(g.kind, lambda: (g.cost(), g.logical_cost())) == (g.cost(), g.logical_cost()), len(cache)
        (True, 1)
        >>> cache.remember("own depth", g.kind, 1); cache.table("own depth")[g.kind], len(cache)
        (1, 2)
    """

    def __init__(self, limit: int = 1 << 16) -> None:
        self._tables: dict[str, dict[Hashable, Any]] = {}
        self._limits: dict[str, int] = {}
        self._costs = self.table("costs", limit)  # a long sweep meets few kinds; a bound keeps memory flat anyway

    def costs(self, key: Hashable, compute: Callable[[], tuple[Cost, Cost]]) -> tuple[Cost, Cost]:
        """``(cost, logical cost)`` of the kind ``key``, from ``compute()`` the first time (a
        :class:`~qcpp.plan.call_graph.GadgetKind` asks its example; a gadget class that prices itself per kind,
        itself)."""
        hit = self._costs.get(key)
        if hit is None:
            hit = compute()
            self.remember("costs", key, hit)
        return hit

    def table(self, name: str, limit: int = 1 << 12) -> dict[Hashable, Any]:
        """The table ``name`` (per kind key; created empty with at most ``limit`` entries on first use). Read it
        directly (one dictionary look-up on a hot path); write with :meth:`remember`."""
        if name not in self._tables:
            self._tables[name], self._limits[name] = {}, limit
        return self._tables[name]

    def remember(self, name: str, key: Hashable, value: Any) -> None:
        """Store ``value`` for ``key`` in the table ``name`` (which starts again when full: a bound on memory)."""
        table = self.table(name)
        if len(table) >= self._limits[name]:
            table.clear()
        table[key] = value

    def clear(self) -> None:
        """Forget everything (tests that count work); the tables stay the same objects."""
        for table in self._tables.values():
            table.clear()

    def __len__(self) -> int:
        return sum(len(t) for t in self._tables.values())


COSTS = CostCache()
"""The process-wide cost cache of gadget kinds (:class:`~qcpp.plan.call_graph.GadgetKind` and :class:`PricedByKind`)."""


class PricedByKind:
    """Mixin of a gadget class whose cost depends on its :attr:`kind` only: it prices itself (``_kind_costs() ->
    (cost, logical cost)``) once per kind in :data:`COSTS`."""

    kind: Hashable

    def _kind_costs(self) -> tuple[Cost, Cost]:
        raise NotImplementedError

    def cost(self) -> Cost:
        """Lowered cost (computed once per kind)."""
        return COSTS.costs(self.kind, self._kind_costs)[0]

    def logical_cost(self) -> Cost:
        """Cost with ANDs and Toffolis kept whole (computed once per kind)."""
        return COSTS.costs(self.kind, self._kind_costs)[1]
