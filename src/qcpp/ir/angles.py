"""Affine symbolic angles: ``constant + sum(coefficient * symbol)``.

Gate parameters are ``float | Angle``. :class:`Angle` is deliberately tiny (two slots, tuples
only, no sympy) because a QAOA phase separator creates hundreds of thousands of them.

Symbols are plain strings such as ``"gamma_0"``; :func:`symbol_sort_key` gives the documented
circuit-wide order (by layer, then gamma before beta, then name).

>>> g = Angle.symbol("gamma_0", 2.5)
>>> a = g + 0.1
>>> a
Angle('2.5*gamma_0 + 0.1')
>>> a.symbols
('gamma_0',)
>>> float(a.bind({"gamma_0": 2.0}))
5.1
>>> format_angle(-a, "qasm3")
'-2.5*gamma_0 - 0.1'
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from functools import lru_cache
from numbers import Real
from typing import Literal, TypeAlias

from qcpp.errors import QcppError

__all__ = [
    "Angle",
    "Param",
    "UnboundParameterError",
    "format_angle",
    "format_float",
    "mixer_symbol",
    "symbol_sort_key",
]


class UnboundParameterError(QcppError):
    """A numeric value was needed but some symbols have no value.

    Args:
        symbols: The unbound symbol names.
        context: What needed the numbers (``OpenQASM 2 has no symbolic parameters``), in parentheses.
        hint: How to give them, ending the message (the command line's ``give them with --bind NAME=VALUE``).

    Attributes:
        symbols: the unbound symbol names, in :func:`symbol_sort_key` order.
        context: as given.
        hint: as given.
    """

    def __init__(self, symbols: Iterable[str], context: str = "", hint: str = "bind them first") -> None:
        self.symbols: tuple[str, ...] = tuple(sorted(set(symbols), key=symbol_sort_key))
        self.context = context
        self.hint = hint
        where = f" ({context})" if context else ""
        super().__init__(f"unbound symbols{where}: {', '.join(self.symbols)}; {hint}")

    def __reduce__(self) -> tuple[type[UnboundParameterError], tuple[tuple[str, ...], str, str]]:
        # picklable with its arguments, so that it crosses process-pool boundaries intact
        return (type(self), (self.symbols, self.context, self.hint))


Terms: TypeAlias = tuple[tuple[str, float], ...]

_SYMBOL_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_LAYER_RE = re.compile(r"^(.*?)_(\d+)$")
_KIND_ORDER = {"gamma": 0, "beta": 1}


@lru_cache(maxsize=1 << 12)
def _is_symbol_name(name: str) -> bool:
    """Whether ``name`` is an identifier (pure memo: a circuit names few symbols many times;
    ``_is_symbol_name.cache_clear()`` empties it)."""
    return _SYMBOL_RE.match(name) is not None


def symbol_sort_key(name: str) -> tuple[int, int, int, str]:
    """Sort key for symbol names: ``(layer, kind, name)``.

    The layer is the trailing ``_<int>`` of the name; within a layer ``gamma`` comes before
    ``beta`` (the QAOA application order: phase separator, then mixer), then any other prefix
    alphabetically. Names without a trailing layer number sort after all layered names.

    Args:
        name: a symbol name.

    Returns:
        A tuple usable as a ``sorted`` key.

    >>> sorted(["beta_1", "gamma_1", "beta_0", "t", "gamma_0", "gamma_10"], key=symbol_sort_key)
    ['gamma_0', 'beta_0', 'gamma_1', 'beta_1', 'gamma_10', 't']
    """
    m = _LAYER_RE.match(name)
    if m is None:
        return (1, 0, 0, name)
    kind = m.group(1)
    if kind.startswith("beta_r"):  # a multi-angle partial-mixer beta (mixer_symbol)
        kind = "beta"
    return (0, int(m.group(2)), _KIND_ORDER.get(kind, 2), name)


def mixer_symbol(layer: int, robot: int, plaquette: int) -> str:
    """The symbol of one partial mixer's beta in layer ``layer`` of a multi-angle circuit.

    ``PlanOptions(angles="multi")`` gives every partial mixer (robot, plaquette) its own beta per layer
    (multi-angle QAOA, Herrman et al. 2022) instead of the layer's ``beta_k``. The layer stays the trailing
    number, so :func:`symbol_sort_key` orders the symbols by layer, gamma first, then the betas.

    Args:
        layer: QAOA layer ``k``.
        plaquette: Plaquette index (row-major, :attr:`qcpp.problem.grid.Plaquette.index`).

    Returns:
        ``beta_r{robot}_q{plaquette}_{layer}``.

    >>> mixer_symbol(2, 0, 5)
    'beta_r0_q5_2'
    >>> sorted(["beta_r1_q0_0", "gamma_1", "beta_r0_q3_0", "gamma_0"], key=symbol_sort_key)
    ['gamma_0', 'beta_r0_q3_0', 'beta_r1_q0_0', 'gamma_1']
    """
    return f"beta_r{robot}_q{plaquette}_{layer}"


def _check_number(x: object) -> float:
    if type(x) is float:
        return x  # type: ignore[return-value]
    if isinstance(x, Real) and not isinstance(x, bool):
        return float(x)
    raise TypeError(f"expected a real number, got {type(x).__name__}")


class Angle:
    """Immutable affine angle ``constant + sum(coeff_i * symbol_i)``.

    Terms are stored as a tuple of ``(symbol, coefficient)`` pairs sorted by symbol name with
    no zero coefficients, so equal angles have equal representations (and hashes). A bound
    angle (no terms) compares equal to the float of its constant.

    Args:
        constant: the constant part.
        terms: ``(symbol, coefficient)`` pairs or a mapping; duplicates are summed.

    >>> Angle(0.5) == 0.5
    True
    >>> (Angle.symbol("beta_0") * 2 - Angle.symbol("beta_0")).terms
    (('beta_0', 1.0),)
    >>> float(Angle.symbol("beta_0"))
    Traceback (most recent call last):
    ...
    qcpp.ir.angles.UnboundParameterError: unbound symbols: beta_0; bind them first
    """

    __slots__ = ("_const", "_terms")
    _const: float
    _terms: Terms

    def __init__(self, constant: float = 0.0, terms: Iterable[tuple[str, float]] | Mapping[str, float] = ()) -> None:
        items = terms.items() if isinstance(terms, Mapping) else terms
        acc: dict[str, float] = {}
        for name, coeff in items:
            if not isinstance(name, str) or not _SYMBOL_RE.match(name):
                raise ValueError(f"invalid symbol name {name!r}")
            acc[name] = acc.get(name, 0.0) + _check_number(coeff)
        _set_const(self, _check_number(constant))
        _set_terms(self, tuple(sorted((k, v) for k, v in acc.items() if v != 0.0)))

    @classmethod
    def symbol(cls, name: str, coeff: float = 1.0) -> Angle:
        """``coeff * name``.

        Args:
            name: symbol name (an identifier, e.g. ``"gamma_0"``).
            coeff: its coefficient.

        >>> Angle.symbol("gamma_0", 0.5)
        Angle('0.5*gamma_0')
        """
        if not isinstance(name, str) or not _is_symbol_name(name):
            raise ValueError(f"invalid symbol name {name!r}")
        if type(coeff) is not float:
            coeff = _check_number(coeff)
        return _make(0.0, ((name, coeff),) if coeff != 0.0 else ())

    @property
    def constant(self) -> float:
        """The constant part."""
        return self._const

    @property
    def terms(self) -> Terms:
        """``(symbol, coefficient)`` pairs, sorted by symbol name, no zero coefficients."""
        return self._terms

    @property
    def symbols(self) -> tuple[str, ...]:
        """Names of the symbols this angle depends on."""
        return tuple(name for name, _ in self._terms)

    @property
    def is_bound(self) -> bool:
        """True if the angle has no symbols left (it is a plain number)."""
        return not self._terms

    def bind(self, mapping: Mapping[str, float]) -> Angle:
        """Substitute values for the symbols found in ``mapping``; others stay symbolic.

        Args:
            mapping: symbol name -> value.

        Returns:
            A new angle (``self`` if nothing was substituted).

        >>> (Angle.symbol("a") + Angle.symbol("b", 2.0)).bind({"a": 1.0})
        Angle('2.0*b + 1.0')
        """
        const = self._const
        rest: list[tuple[str, float]] = []
        for name, coeff in self._terms:
            value = mapping.get(name)
            if value is None:
                rest.append((name, coeff))
            else:
                const += coeff * _check_number(value)
        if len(rest) == len(self._terms):
            return self
        return _make(const, tuple(rest))

    def __float__(self) -> float:
        if self._terms:
            raise UnboundParameterError(self.symbols)
        return self._const

    # --- arithmetic -------------------------------------------------------------------------
    def __add__(self, other: object) -> Angle:
        if isinstance(other, Angle):
            return _make(self._const + other._const, _merge(self._terms, other._terms, 1.0))
        try:
            value = _check_number(other)
        except TypeError:
            return NotImplemented
        return _make(self._const + value, self._terms)

    __radd__ = __add__

    def __sub__(self, other: object) -> Angle:
        if isinstance(other, Angle):
            return _make(self._const - other._const, _merge(self._terms, other._terms, -1.0))
        try:
            value = _check_number(other)
        except TypeError:
            return NotImplemented
        return _make(self._const - value, self._terms)

    def __rsub__(self, other: object) -> Angle:
        try:
            value = _check_number(other)
        except TypeError:
            return NotImplemented
        return _make(value - self._const, _scale(self._terms, -1.0))

    def __neg__(self) -> Angle:
        return _make(-self._const, _scale(self._terms, -1.0))

    def __pos__(self) -> Angle:
        return self

    def __mul__(self, other: object) -> Angle:
        if isinstance(other, Angle):
            if other.is_bound:
                return self * other._const
            if self.is_bound:
                return other * self._const
            raise TypeError("product of two symbolic angles is not affine")
        try:
            f = _check_number(other)
        except TypeError:
            return NotImplemented
        if f == 0.0:
            return _make(0.0, ())
        return _make(self._const * f, _scale(self._terms, f))

    __rmul__ = __mul__

    def __truediv__(self, other: object) -> Angle:
        if isinstance(other, Angle):
            if not other.is_bound:
                raise TypeError("division by a symbolic angle is not affine")
            other = other._const
        try:
            f = _check_number(other)
        except TypeError:
            return NotImplemented
        return _make(self._const / f, tuple((n, c / f) for n, c in self._terms))

    # --- value semantics --------------------------------------------------------------------
    def __eq__(self, other: object) -> bool:
        if isinstance(other, Angle):
            return self._const == other._const and self._terms == other._terms
        if isinstance(other, Real):
            return not self._terms and self._const == other
        return NotImplemented

    def __hash__(self) -> int:
        if not self._terms:
            return hash(self._const)
        return hash((self._const, self._terms))

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError("Angle is immutable")

    def __delattr__(self, name: str) -> None:
        raise AttributeError("Angle is immutable")

    def __reduce__(self) -> tuple[object, ...]:
        return (Angle, (self._const, self._terms))

    def __repr__(self) -> str:
        return f"Angle({format_angle(self, 'qasm3')!r})"

    def __str__(self) -> str:
        return format_angle(self, "qasm3")


_set_const = Angle._const.__set__  # type: ignore[attr-defined]
_set_terms = Angle._terms.__set__  # type: ignore[attr-defined]
_new_object = object.__new__


def _make(const: float, terms: Terms) -> Angle:
    """Trusted constructor: ``terms`` must already be canonical."""
    a = _new_object(Angle)
    _set_const(a, const)
    _set_terms(a, terms)
    return a


def _scale(terms: Terms, f: float) -> Terms:
    if len(terms) == 1:
        name, coeff = terms[0]
        return ((name, coeff * f),)
    return tuple((n, c * f) for n, c in terms)


def _merge(a: Terms, b: Terms, sign: float) -> Terms:
    if not b:
        return a
    if not a:
        return b if sign == 1.0 else _scale(b, -1.0)
    if len(a) == 1 and len(b) == 1 and a[0][0] == b[0][0]:
        coeff = a[0][1] + sign * b[0][1]
        return ((a[0][0], coeff),) if coeff != 0.0 else ()
    acc = dict(a)
    for name, coeff in b:
        acc[name] = acc.get(name, 0.0) + sign * coeff
    return tuple(sorted((k, v) for k, v in acc.items() if v != 0.0))


Param: TypeAlias = float | Angle
"""A gate parameter: a number or an affine symbolic :class:`Angle`."""


def format_float(x: float) -> str:
    """Shortest round-trip decimal text of ``x`` that is a valid OpenQASM 2 and 3 real literal.

    ``repr`` is exact (it round-trips to the same float); a ``.0`` is inserted where needed
    because OpenQASM 2 real literals require a decimal point.

    Args:
        x: a finite float.

    >>> format_float(0.1), format_float(1e-5), format_float(-2.0)
    ('0.1', '1.0e-05', '-2.0')
    """
    s = repr(x) if type(x) is float else repr(float(x))
    if "." not in s:
        if "e" in s:
            return s.replace("e", ".0e")
        raise ValueError(f"cannot write non-finite angle {s} to OpenQASM")
    return s


def format_angle(value: float | Angle, style: Literal["qasm2", "qasm3"] = "qasm3") -> str:
    """Text of a gate parameter for OpenQASM.

    Args:
        value: a number or an :class:`Angle`.
        style: ``"qasm2"`` needs a bound value (numbers only); ``"qasm3"`` writes symbols as
            an affine expression, e.g. ``2.5*gamma_0 + 0.1``.

    Raises:
        UnboundParameterError: ``style="qasm2"`` and the angle has symbols.

    >>> format_angle(Angle.symbol("gamma_0", -1.0) + Angle.symbol("beta_0"), "qasm3")
    'beta_0 - gamma_0'
    >>> format_angle(0.25, "qasm2")
    '0.25'
    """
    if type(value) is float:
        return format_float(value)
    if not isinstance(value, Angle):
        return format_float(_check_number(value))
    if not value._terms:
        return format_float(value._const)
    if style == "qasm2":
        raise UnboundParameterError(value.symbols, "OpenQASM 2 has no symbolic parameters")
    if len(value._terms) == 1 and value._const == 0.0:  # fast path: c*name
        name, coeff = value._terms[0]
        if coeff == 1.0:
            return name
        if coeff == -1.0:
            return "-" + name
        return f"{format_float(coeff)}*{name}"
    parts: list[str] = []
    for i, (name, coeff) in enumerate(value._terms):
        mag = abs(coeff)
        body = name if mag == 1.0 else f"{format_float(mag)}*{name}"
        if i == 0:
            parts.append(body if coeff > 0 else "-" + body)
        else:
            parts.append((" + " if coeff > 0 else " - ") + body)
    const = value._const
    if const != 0.0:
        parts.append((" + " if const > 0 else " - ") + format_float(abs(const)))
    return "".join(parts)
