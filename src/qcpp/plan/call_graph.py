"""The QAOA circuit as a call graph: per part a multiset of gadget kinds (Qualtran's ``build_call_graph``).

A :class:`GadgetKind` is what a gadget costs, not where it sits: its key (:attr:`Gadget.kind
<qcpp.gadgets.Gadget.kind>`: equal keys, equal gates up to qubit names), its costs, the ``logic``
temporaries and ``work`` ancillas it needs, and an example gadget for whatever needs gates (depth profiles).
Kinds compare and hash by key only, so a kind counted by classes on one scenario equals the kind the compiler
emits on another. A :class:`CallGraph` (:meth:`qcpp.plan.qaoa.QaoaPlan.call_graph`) holds each part's kinds with
their multiplicities and the shared registers' widths; every count the estimators report is a sum over it.

Everything known per kind (its costs; the estimators' per-kind depth facts as named tables) is looked up by the
kind's key in one explicit cache, :data:`qcpp.gadgets.pricing.COSTS`. The other memos hold other concepts:
per-scenario results (at most :data:`SCENARIOS_KEPT` scenarios each), geometry (local pictures), per-shape decisions of
:mod:`qcpp.plan.phase_choice`, constructions keyed by their inputs (the partial mixers' searched plans,
``depth_compose``'s transfer matrices per gate structure), leaf gate costs and the symbolic formula tables.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.plan.qaoa import qaoa_plan
    >>> graph = qaoa_plan(default_scenario(3, 3, 1), 1).call_graph()
    >>> sorted(graph.parts), graph.cost_by_part()["initial_state"].to_dict()
    (['initial_state', 'mixer', 'phase'], {'x': 4})
    >>> graph.cost(1) == qaoa_plan(default_scenario(3, 3, 1), 1).cost()
    True
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Hashable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from qcpp.gadgets import Gadget
from qcpp.gadgets.pricing import COSTS
from qcpp.ir.cost import Cost

__all__ = ["PARTS", "SCENARIOS_KEPT", "CallGraph", "Deferred", "GadgetKind"]

PARTS: tuple[str, ...] = ("initial_state", "phase", "mixer")
"""The parts of a QAOA circuit: the state preparation once, then ``p`` times the phase separator (``p - 1`` times
without the first: :attr:`CallGraph.first_phase`) and the mixer."""


SCENARIOS_KEPT = 8
"""How many scenarios each per-scenario memo keeps: a sweep asks ``p = 1..P`` of one scenario in a row, and a kept
scenario keeps its plan and its grid's tables alive (megabytes each at 40x40)."""


class _HashedKey:
    """A kind key with its hash computed once (the cache's key: it holds no example, so no gadget stays alive)."""

    __slots__ = ("hash", "key")

    def __init__(self, key: Hashable) -> None:
        self.key, self.hash = key, hash(key)

    def __hash__(self) -> int:
        return self.hash

    def __eq__(self, other: object) -> bool:  # equal to its plain key too: a gadget prices itself by plain key
        if isinstance(other, _HashedKey):
            return self.hash == other.hash and self.key == other.key
        return self.key == other


@dataclass(frozen=True, eq=False)
class GadgetKind:
    """One kind of gadget: its cost and needs, no qubits (see the module docstring).

    Attributes:
        key: the kind key (:attr:`Gadget.kind <qcpp.gadgets.Gadget.kind>`).
        example: a gadget of this kind (for gates: depth profiles, routing).
        temporaries: clean ``logic`` ancillas it uses.
        work: ``work`` ancillas the lowering of its multi-controlled X gates adds.
    """

    key: Hashable
    example: Gadget = field(repr=False)
    temporaries: int = 0
    work: int = 0

    @classmethod
    def of(cls, gadget: Gadget) -> GadgetKind:
        """The kind of a gadget (its needs read from the gadget: :meth:`Gadget.needs <qcpp.gadgets.Gadget.needs>`)."""
        temporaries, work = gadget.needs()
        return cls(gadget.kind, gadget, temporaries, work)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_hashed", _HashedKey(self.key))  # keys can be long tuples: hash them once

    def costs(self) -> tuple[Cost, Cost]:
        """``(lowered cost, logical cost)``: from :data:`~qcpp.gadgets.pricing.COSTS`, or a :class:`Deferred`
        example's own (its key is one scenario's: no entry)."""
        if isinstance(self.example, Deferred):
            return self.example.lowered, self.example.logical
        return COSTS.costs(self._hashed, self._priced)  # type: ignore[attr-defined]

    def cost(self) -> Cost:
        """Lowered cost."""
        return self.costs()[0]

    def logical_cost(self) -> Cost:
        """Cost with ANDs and Toffolis kept whole."""
        return self.costs()[1]

    @property
    def cache_key(self) -> Hashable:
        """The key (hashed once, holding no example) by which :data:`~qcpp.gadgets.pricing.COSTS` and its tables
        know this kind."""
        return self._hashed  # type: ignore[attr-defined,no-any-return]

    def _priced(self) -> tuple[Cost, Cost]:
        return self.example.cost(), self.example.logical_cost()

    def __eq__(self, other: object) -> bool:
        return self is other or (isinstance(other, GadgetKind) and self.key == other.key)

    def __hash__(self) -> int:
        return self._hashed.hash  # type: ignore[attr-defined,no-any-return]


@dataclass(frozen=True, eq=False)
class Deferred:
    """A gadget known by its kind and cost, built only when its gates are asked for (a counted kind whose example
    would take ``O(variables)`` to build: the data-qubit rotations, the balance arithmetic).

    Attributes:
        kind, lowered, logical, num_ancillas: the built gadget's kind key, costs and clean ancillas.
        build: builds the gadget (placed on qubits).
        shape: the balance's :class:`~qcpp.gadgets.phase_sums.SumsShape` (what its cost depends on), else
            ``None``.
    """

    kind: Hashable
    lowered: Cost
    logical: Cost
    build: Callable[[], Gadget]
    shape: Any = None
    num_ancillas: int = 0

    def cost(self) -> Cost:
        """Lowered cost."""
        return self.lowered

    def logical_cost(self) -> Cost:
        """Logical cost."""
        return self.logical

    def needs(self) -> tuple[int, int]:
        """``(num_ancillas, 0)``: the built gadget's clean ancillas, no work ancillas."""
        return self.num_ancillas, 0

    def emit(self) -> Sequence[Any]:
        """The built gadget's gates."""
        return self.build().emit()


@dataclass(frozen=True)
class CallGraph:
    """Per part, the gadget kinds of the circuit and how many of each (see the module docstring).

    Attributes:
        parts: ``{part: {kind: multiplicity}}`` for :data:`PARTS` (``phase`` and ``mixer``: one layer; ``phase``
            is one phase separator's kinds also where the plan's circuit has none: ``first_phase=False`` at
            ``p = 1``).
        logic_width, work_width: the shared clean ``logic`` register and the ``work`` register the lowering adds
            (of the plan's own ``p``).
        first_phase: whether the first layer has its phase separator
            (:attr:`qcpp.plan.options.PlanOptions.first_phase`): ``p`` layers hold ``p`` phase separators, or
            ``p - 1``.
    """

    parts: Mapping[str, Mapping[GadgetKind, int]]
    logic_width: int
    work_width: int
    first_phase: bool = True

    @classmethod
    def build(
        cls,
        parts: Mapping[str, Iterable[tuple[GadgetKind, int]]],
        logic_width: int,
        work_width: int,
        first_phase: bool = True,
    ) -> CallGraph:
        """Merge ``(kind, multiplicity)`` pairs per part (equal kinds add up; zero multiplicities are dropped)."""
        merged: dict[str, Mapping[GadgetKind, int]] = {}
        for name in PARTS:
            counts: Counter[GadgetKind] = Counter()
            for kind, n in parts.get(name, ()):
                counts[kind] += n
            merged[name] = {k: n for k, n in counts.items() if n}
        return cls(merged, logic_width, work_width, first_phase)

    def cost_by_part(self, logical: bool = False) -> dict[str, Cost]:
        """Lowered (or logical) cost per part: ``initial_state``, one layer's ``phase`` and ``mixer``."""
        return dict(self._sums[logical][0])

    def cost(self, p: int, logical: bool = False) -> Cost:
        """Cost of the circuit with ``p`` layers: state preparation + ``p`` x (phase separator + mixer), less one
        phase separator without the first (:attr:`first_phase`)."""
        hit = self._totals.get((p, logical))
        if hit is None:  # an estimate asks each p more than once
            parts, layer = self._sums[logical]
            if self.first_phase or not p:
                hit = parts["initial_state"] + p * layer
            else:
                hit = parts["initial_state"] + p * parts["mixer"] + (p - 1) * parts["phase"]
            self._totals[p, logical] = hit
        return hit

    @cached_property
    def _totals(self) -> dict[tuple[int, bool], Cost]:
        return {}

    @cached_property
    def _sums(self) -> tuple[tuple[dict[str, Cost], Cost], ...]:
        """``(per part, one layer)`` lowered, then logical (summed once: a sweep asks for every ``p``)."""
        out = []
        for logical in (False, True):
            parts = {}
            for name, kinds in self.parts.items():
                total: Counter[str] = Counter()
                for kind, n in kinds.items():
                    for gate, k in (kind.logical_cost() if logical else kind.cost()).items:
                        total[gate] += n * k
                parts[name] = Cost.of(total)
            out.append((parts, parts["phase"] + parts["mixer"]))
        return tuple(out)

    def kinds(self) -> Iterable[tuple[str, GadgetKind, int]]:
        """``(part, kind, multiplicity)`` for every kind."""
        for name, kinds in self.parts.items():
            for kind, n in kinds.items():
                yield name, kind, n
