"""Circuits: a register layout plus gates grouped in named sections.

Design: a :class:`CircuitBuilder` appends gates (mutable, cheap), ``build()`` freezes it into
a :class:`Circuit`, whose registers and sections are tuples. Every operation on a ``Circuit``
(``compose``, ``inverse``, ``bind``, the lowering passes, ...) returns a new circuit, so a
finished circuit can be shared, cached and hashed by identity without defensive copies.

Layout: an ordered tuple of :class:`Register`; qubit index = register offset + index in the
register. By convention the first register is ``data`` (data qubit ``i`` is problem variable
``i``) and ancilla registers follow; the lowering passes add a ``work`` register at the end.

Sections: an ordered tuple of :class:`Section` (``"initial_state"``, ``"phase_0"``,
``"mixer_0"``, ...) so that counts can be broken down by section. Section names need not be
unique (``c.compose(c.inverse())`` repeats them); passes never move a gate across a section
boundary.

>>> from qcpp.ir.gates import h, rzz
>>> from qcpp.ir.angles import Angle
>>> b = CircuitBuilder([Register("data", 3)])
>>> b.append([h(q) for q in range(3)], section="initial_state")
>>> b.append(rzz(Angle.symbol("gamma_0", 2.0), 0, 1), section="phase_0")
>>> c = b.build()
>>> c.num_qubits, len(c), [s.name for s in c.sections], c.symbols
(3, 4, ['initial_state', 'phase_0'], ('gamma_0',))
>>> c.bind({"gamma_0": 0.25}).sections[1].gates[0].params
(0.5,)
"""

from __future__ import annotations

import itertools
import re
from collections import Counter
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from operator import itemgetter
from typing import overload

from qcpp.ir._perf import gc_paused
from qcpp.ir.angles import Angle, symbol_sort_key
from qcpp.ir.gates import GATE_SPECS, Gate

__all__ = ["Circuit", "CircuitBuilder", "Register", "Section"]

DEFAULT_SECTION = "main"
_NAME_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


@dataclass(frozen=True, slots=True)
class Register:
    """A named block of consecutive qubits.

    Attributes:
        name: identifier, unique within a layout.
        size: number of qubits (may be 0).

    >>> Register("data", 4)
    Register(name='data', size=4)
    """

    name: str
    size: int

    def __post_init__(self) -> None:
        if not _NAME_RE.match(self.name):
            raise ValueError(f"invalid register name {self.name!r}")
        if not isinstance(self.size, int) or self.size < 0:
            raise ValueError(f"register size must be a non-negative int, got {self.size!r}")


@dataclass(frozen=True, slots=True)
class Section:
    """A named, ordered run of gates.

    Attributes:
        name: section name, e.g. ``"phase_0"``.
        gates: the gates (any sequence is stored as a tuple).

    >>> from qcpp.ir.gates import x
    >>> Section("initial_state", [x(0)]).gates
    (Gate(name='x', qubits=(0,), params=(), ctrl_state=None),)
    """

    name: str
    gates: tuple[Gate, ...] = field(default=())

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not _NAME_RE.match(self.name):
            raise ValueError(f"invalid section name {self.name!r}: use an identifier such as 'phase_0'")
        if type(self.gates) is not tuple:
            object.__setattr__(self, "gates", tuple(self.gates))

    def __len__(self) -> int:
        return len(self.gates)


def _as_registers(registers: Iterable[Register | tuple[str, int]]) -> tuple[Register, ...]:
    regs = tuple(r if isinstance(r, Register) else Register(*r) for r in registers)
    names = [r.name for r in regs]
    if len(set(names)) != len(names):
        raise ValueError(f"duplicate register names in {names}")
    return regs


_qubits_of_gate = itemgetter(1)


def _check_qubits(gates: Sequence[Gate], num_qubits: int) -> None:
    """Range check with C-level iteration (the constructors already checked the rest)."""
    if not gates:
        return
    top = max(map(max, map(_qubits_of_gate, gates)))
    if top >= num_qubits:
        bad = next(g for g in gates if max(g[1]) >= num_qubits)
        raise ValueError(f"gate {bad} uses qubit {top} but the layout has {num_qubits} qubits")


class Circuit:
    """An immutable circuit: registers plus sections of gates.

    Build one with :class:`CircuitBuilder` (or pass sections directly). Cheap derived data
    (gate count, symbols) is computed once and cached.

    Args:
        registers: the layout, as :class:`Register` objects or ``(name, size)`` pairs.
        sections: the sections; gates are range-checked against the layout.

    >>> c = Circuit([Register("data", 2)])
    >>> c.num_qubits, len(c), list(c.qubits_of("data"))
    (2, 0, [0, 1])
    """

    __slots__ = ("_n_gates", "_registers", "_sections", "_symbols")

    def __init__(
        self,
        registers: Iterable[Register | tuple[str, int]],
        sections: Iterable[Section] = (),
    ) -> None:
        self._registers = _as_registers(registers)
        self._sections = tuple(sections)
        self._n_gates: int | None = None
        self._symbols: tuple[str, ...] | None = None
        n = self.num_qubits
        for sec in self._sections:
            if not isinstance(sec, Section):
                raise TypeError(f"expected Section, got {type(sec).__name__}")
            _check_qubits(sec.gates, n)

    @classmethod
    def _trusted(
        cls,
        registers: tuple[Register, ...],
        sections: tuple[Section, ...],
        symbols: tuple[str, ...] | None = None,
    ) -> Circuit:
        c = object.__new__(cls)
        c._registers = registers
        c._sections = sections
        c._n_gates = None
        c._symbols = symbols
        return c

    # --- layout -----------------------------------------------------------------------------
    @property
    def registers(self) -> tuple[Register, ...]:
        """The layout, in qubit order."""
        return self._registers

    @property
    def num_qubits(self) -> int:
        """Total number of qubits over all registers."""
        return sum(r.size for r in self._registers)

    def register(self, name: str) -> Register:
        """The register called ``name`` (``KeyError`` if absent)."""
        for r in self._registers:
            if r.name == name:
                return r
        raise KeyError(f"no register named {name!r}")

    def has_register(self, name: str) -> bool:
        """True if the layout has a register called ``name``."""
        return any(r.name == name for r in self._registers)

    def qubits_of(self, register: str) -> range:
        """Qubit indices of a register.

        Args:
            register: register name.

        Returns:
            ``range(offset, offset + size)``.
        """
        offset = 0
        for r in self._registers:
            if r.name == register:
                return range(offset, offset + r.size)
            offset += r.size
        raise KeyError(f"no register named {register!r}")

    # --- gates ------------------------------------------------------------------------------
    @property
    def sections(self) -> tuple[Section, ...]:
        """The sections, in order."""
        return self._sections

    @property
    def gates(self) -> Iterator[Gate]:
        """A fresh iterator over all gates, in order, across sections."""
        return itertools.chain.from_iterable(s.gates for s in self._sections)

    def __iter__(self) -> Iterator[Gate]:
        return self.gates

    def __len__(self) -> int:
        if self._n_gates is None:
            self._n_gates = sum(len(s.gates) for s in self._sections)
        return self._n_gates

    @property
    def symbols(self) -> tuple[str, ...]:
        """Unbound symbol names, ordered by :func:`qcpp.ir.angles.symbol_sort_key`
        (layer, then gamma before beta, then name: ``gamma_0, beta_0, gamma_1, ...``)."""
        if self._symbols is None:
            found: set[str] = set()
            seen: set[int] = set()  # ids of Angle objects already scanned (they are shared)
            for sec in self._sections:
                for g in sec.gates:
                    for p in g[2]:
                        if type(p) is Angle and id(p) not in seen:
                            seen.add(id(p))
                            found.update(name for name, _ in p.terms)
            self._symbols = tuple(sorted(found, key=symbol_sort_key))
        return self._symbols

    def count_ops(self) -> dict[str, int]:
        """Number of gates per gate name, most frequent first.

        >>> from qcpp.ir.gates import h
        >>> Circuit([("data", 2)], [Section("s", [h(0), h(1)])]).count_ops()
        {'h': 2}
        """
        return dict(Counter(map(itemgetter(0), self.gates)).most_common())

    # --- transformations --------------------------------------------------------------------
    def inverse(self) -> Circuit:
        """The inverse circuit: sections in reverse order, each reversed and gate-inverted.

        Section names are kept, so a per-section breakdown still refers to the same parts.
        """
        secs = tuple(
            Section(sec.name, tuple(g.inverse() for g in reversed(sec.gates))) for sec in reversed(self._sections)
        )
        return Circuit._trusted(self._registers, secs, self._symbols)

    def compose(self, other: Circuit) -> Circuit:
        """``self`` followed by ``other`` (sections concatenated, never merged).

        The layouts must be equal, or one must be a prefix of the other (the longer is kept).

        Args:
            other: circuit to run after this one.
        """
        a, b = self._registers, other._registers
        if a[: len(b)] == b:
            regs = a
        elif b[: len(a)] == a:
            regs = b
        else:
            raise ValueError(f"incompatible layouts {a} and {b}")
        return Circuit._trusted(regs, self._sections + other._sections)

    @gc_paused()
    def bind(self, mapping: Mapping[str, float]) -> Circuit:
        """Substitute symbol values; fully bound angles become plain floats.

        Args:
            mapping: symbol name -> value (extra names are ignored).

        Returns:
            The bound circuit (partially symbolic if ``mapping`` misses some symbols).
        """
        mapping = {k: float(v) for k, v in mapping.items()}
        new_gate = tuple.__new__
        secs = []
        for sec in self._sections:
            gates = list(sec.gates)
            for i, g in enumerate(gates):
                params = g[2]
                if not params:
                    continue
                p = params[0]
                if len(params) == 1 and type(p) is Angle:
                    terms = p._terms
                    if len(terms) == 1:  # the common case, inlined
                        value = mapping.get(terms[0][0])
                        if value is not None:
                            gates[i] = new_gate(Gate, (g[0], g[1], (p._const + terms[0][1] * value,), g[3]))
                        continue
                bound = g.bind(mapping)
                if bound is not g:
                    gates[i] = bound
            secs.append(Section(sec.name, tuple(gates)))
        remaining = None
        if self._symbols is not None:
            remaining = tuple(s for s in self._symbols if s not in mapping)
        return Circuit._trusted(self._registers, tuple(secs), remaining)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Circuit):
            return NotImplemented
        return self._registers == other._registers and self._sections == other._sections

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        regs = ", ".join(f"{r.name}[{r.size}]" for r in self._registers)
        secs = ", ".join(f"{s.name}:{len(s.gates)}" for s in self._sections)
        return f"Circuit(registers=[{regs}], sections=[{secs}])"


class CircuitBuilder:
    """Mutable accumulator of gates; :meth:`build` returns the frozen :class:`Circuit`.

    ``append(gates, section=name)`` adds to the current last section if it has that name,
    otherwise opens a new section; ``section=None`` means "the current section" (or
    ``"main"`` if there is none yet).

    Args:
        registers: initial layout.

    >>> from qcpp.ir.gates import cx, x
    >>> b = CircuitBuilder([("data", 2)])
    >>> b.append(x(0), section="prep")
    >>> b.append(cx(0, 1))
    >>> b.build().count_ops()
    {'x': 1, 'cx': 1}
    """

    __slots__ = ("_registers", "_sections")

    def __init__(self, registers: Iterable[Register | tuple[str, int]] = ()) -> None:
        self._registers = _as_registers(registers)
        self._sections: list[tuple[str, list[Gate]]] = []

    @property
    def num_qubits(self) -> int:
        """Total number of qubits in the current layout."""
        return sum(r.size for r in self._registers)

    def add_register(self, register: Register | tuple[str, int]) -> range:
        """Append a register to the layout.

        Returns:
            Its qubit indices.
        """
        start = self.num_qubits
        self._registers = _as_registers((*self._registers, register))
        return range(start, self.num_qubits)

    def qubits_of(self, register: str) -> range:
        """Qubit indices of a register of the current layout."""
        return Circuit._trusted(self._registers, ()).qubits_of(register)

    @overload
    def append(self, gates: Gate, section: str | None = None) -> None: ...
    @overload
    def append(self, gates: Iterable[Gate], section: str | None = None) -> None: ...

    def append(self, gates: Gate | Iterable[Gate], section: str | None = None) -> None:
        """Append one gate or an iterable of gates.

        Args:
            gates: a :class:`Gate` or an iterable of them.
            section: target section name (see the class docstring).
        """
        secs = self._sections
        if section is None:
            if not secs:
                secs.append((DEFAULT_SECTION, []))
        elif not secs or secs[-1][0] != section:
            if not _NAME_RE.match(section):
                raise ValueError(f"invalid section name {section!r}")
            secs.append((section, []))
        target = secs[-1][1]
        if isinstance(gates, Gate):
            if gates[0] not in GATE_SPECS:
                raise ValueError(f"unknown gate {gates[0]!r}")
            target.append(gates)
        else:
            start = len(target)
            target.extend(gates)
            for g in itertools.islice(target, start, None):
                if not isinstance(g, Gate) or g[0] not in GATE_SPECS:
                    del target[start:]
                    raise TypeError(f"expected a Gate with a known name, got {g!r}")

    @gc_paused()
    def build(self) -> Circuit:
        """Freeze into a :class:`Circuit` (gates are range-checked against the layout)."""
        n = self.num_qubits
        secs = []
        for name, gates in self._sections:
            _check_qubits(gates, n)
            secs.append(Section(name, tuple(gates)))
        return Circuit._trusted(self._registers, tuple(secs))
