"""Gate costs as values: what a construction costs once lowered, without emitting its gates.

A :class:`Cost` is an immutable multiset of lowered gate names (``cx``, ``h``, ``rz``, ``t``, ...). Costs add
(``a + b``: one construction after another) and scale (``3 * a``: three copies), so the cost of a circuit is
the sum over its call graph of the costs of the gadgets it is made of (as Qualtran's bloqs count). Every
gadget of :mod:`qcpp.gadgets` reports a ``Cost`` and a test checks it against the count of its emitted,
lowered gates.

Derived figures follow :mod:`qcpp.estimators.counts`: ``cx``, ``single_qubit`` (every basis gate on one qubit),
``t`` (``t`` + ``tdg``), ``rotations`` (``rz``: arbitrary angles; Clifford and T phases are lowered to
``s``/``sdg``/``t``/``tdg`` instead, so every ``rz`` is a rotation a fault-tolerant machine must synthesise).

Example:
    >>> a = Cost.of(cx=3, h=2, t=2, tdg=2)
    >>> (2 * a + Cost.of(rz=1)).to_dict()
    {'cx': 6, 'h': 4, 'rz': 1, 't': 4, 'tdg': 4}
    >>> (a.cx, a.t, a.single_qubit, a.total)
    (3, 4, 6, 9)
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Literal

__all__ = ["ONE_QUBIT_NAMES", "TARGETS", "TWO_QUBIT_NAMES", "Cost", "Target"]

ONE_QUBIT_NAMES = frozenset({"x", "h", "rz", "t", "tdg", "s", "sdg", "rx", "ry"})
"""Gate names that act on one qubit."""

TWO_QUBIT_NAMES = frozenset({"cx", "cz", "crz", "cry", "crx", "rzz"})
"""Gate names that act on two qubits."""


@dataclass(frozen=True)
class Cost:
    """Gate counts by name; zero entries are dropped, names kept sorted.

    Attributes:
        items: ``(name, count)`` pairs, sorted by name, counts > 0.
    """

    items: tuple[tuple[str, int], ...] = ()

    @classmethod
    def of(cls, counts: Mapping[str, int] | None = None, **named: int) -> Cost:
        """Build from a mapping and/or keyword counts (``Cost.of(cx=2, rz=1)``).

        Args:
            counts: name -> count.
            **named: more name -> count pairs (added).
        """
        total: dict[str, int] = {}
        for src in (counts or {}), named:
            for k, v in src.items():
                if v < 0:
                    raise ValueError(f"negative count {v} for {k!r}")
                total[k] = total.get(k, 0) + int(v)
        return cls._of_valid(total)

    @classmethod
    def _of_valid(cls, total: Mapping[str, int]) -> Cost:
        """From counts known to be non-negative integers (sums of costs): sorted, zeros dropped."""
        return cls(tuple(sorted((k, v) for k, v in total.items() if v)))

    @classmethod
    def count(cls, gates: Iterable[tuple[object, ...]]) -> Cost:
        """The cost of an emitted gate list: one per gate, by name (the gate's first field).

        >>> from qcpp.ir.gates import cx, h
        >>> Cost.count([h(0), cx(0, 1), h(0)]).to_dict()
        {'cx': 1, 'h': 2}
        """
        return cls.of(Counter(g[0] for g in gates))  # type: ignore[misc]

    @classmethod
    def sum(cls, costs: Iterable[Cost]) -> Cost:
        """Add up many costs."""
        total: dict[str, int] = {}
        get = total.get
        for c in costs:
            for k, v in c.items:
                total[k] = get(k, 0) + v
        return cls._of_valid(total)

    def __add__(self, other: Cost) -> Cost:
        if not isinstance(other, Cost):
            return NotImplemented
        if not other.items:  # sums over a call graph add many empty parts
            return self
        if not self.items:
            return other
        return Cost.sum((self, other))

    def __mul__(self, k: int) -> Cost:
        if not isinstance(k, int) or isinstance(k, bool):
            return NotImplemented
        if k < 0:
            raise ValueError(f"cannot scale a cost by {k}")
        return Cost(tuple((n, v * k) for n, v in self.items)) if k else Cost()

    __rmul__ = __mul__

    def __getitem__(self, name: str) -> int:
        for n, v in self.items:
            if n == name:
                return v
        return 0

    def to_dict(self) -> dict[str, int]:
        """``{name: count}``, sorted by name."""
        return dict(self.items)

    @property
    def total(self) -> int:
        """All gates."""
        return sum(v for _, v in self.items)

    @property
    def cx(self) -> int:
        """CNOTs."""
        return self["cx"]

    @property
    def t(self) -> int:
        """``t`` + ``tdg``."""
        return self["t"] + self["tdg"]

    @property
    def rotations(self) -> int:
        """Arbitrary-angle ``rz`` gates."""
        return self["rz"]

    @property
    def single_qubit(self) -> int:
        """Gates on one qubit."""
        return sum(v for n, v in self.items if n in ONE_QUBIT_NAMES)

    @property
    def two_qubit(self) -> int:
        """Gates on two qubits."""
        return sum(v for n, v in self.items if n in TWO_QUBIT_NAMES)

    def __str__(self) -> str:
        return ", ".join(f"{n}: {v}" for n, v in self.items) or "nothing"


Target = Literal["nisq", "ft"]
"""What a construction is chosen for: ``nisq`` minimises CNOTs (arbitrary rotations are cheap), ``ft`` minimises
T gates and arbitrary rotations (each rotation costs a synthesised T sequence; ANDs are logical ANDs)."""

TARGETS: tuple[Target, ...] = ("nisq", "ft")
