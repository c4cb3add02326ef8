"""Gate value type, gate constructors, the gate spec table and each gate's action.

A :class:`Gate` is a ``NamedTuple`` subclass ``(name, qubits, params, ctrl_state)``: lowered
circuits hold millions of gates, and a NamedTuple is about twice as cheap to create as a frozen
slotted dataclass. Like any tuple it compares equal to a plain tuple with the same fields; do
not rely on that.

Qubit order convention (the Qiskit one): in every local matrix or vector of this module the
first listed qubit of a gate is the least significant bit of the local basis index.

Gate conventions:

====== ============================================================================
x h    Pauli X, Hadamard
t tdg  diag(1, e^{±iπ/4});  s sdg: diag(1, ±i)
rz     RZ(θ) = diag(e^{-iθ/2}, e^{iθ/2})
rx ry  RX(θ) = exp(-iθX/2), RY(θ) = exp(-iθY/2)
cx cz  controlled X (control first), controlled Z
crz    controlled RZ (Qiskit's ``crz``), control first
cry    controlled RY, control first
rzz    RZZ(θ) = exp(-iθ Z⊗Z/2)
ccx    Toffoli, controls first
and    AND into a clean target: X on the last qubit if both controls match ``ctrl_state``
       (a permutation, like ``ccx``); lowered to a 3-CX relative-phase Toffoli plus ``sdg``,
       which is exact only when the target starts in |0> (the gadget's contract)
and_dg the uncompute of ``and`` (same permutation; lowered to the exact inverse of ``and``'s
       lowering, so it returns a target holding the AND to |0>)
crx    controlled RX, control first
mcx    X on the last qubit, controlled by all others; ``ctrl_state[i]`` is the
       required value of ``qubits[i]`` ('1' = control on |1>, '0' = on |0>).
       Note: reading order, *not* Qiskit's little-endian ``ctrl_state`` integer.
sbf    SBF(θ) = exp(-iθ X⊗X⊗X⊗X/2) on four qubits
csbf   SBF(θ) on qubits[1:5] controlled by qubits[0]
====== ============================================================================

>>> g = rzz(0.5, 3, 4)
>>> g.name, g.qubits, g.params
('rzz', (3, 4), (0.5,))
>>> g.inverse().params
(-0.5,)
>>> mcx([0, 1], 2)  # normalised
Gate(name='ccx', qubits=(0, 1, 2), params=(), ctrl_state=None)
>>> unitary(cx(0, 1)).real.astype(int).tolist()  # q0 is the low bit
[[1, 0, 0, 0], [0, 0, 0, 1], [0, 0, 1, 0], [0, 1, 0, 0]]
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from numbers import Real
from types import MappingProxyType
from typing import NamedTuple

import numpy as np

from qcpp.ir.angles import Angle, Param

__all__ = [
    "GATE_SPECS",
    "Gate",
    "GateSpec",
    "and_",
    "and_dg",
    "ccx",
    "controlled_x_pattern",
    "crx",
    "cry",
    "crz",
    "csbf",
    "cx",
    "cz",
    "diagonal",
    "h",
    "mcx",
    "rx",
    "ry",
    "rz",
    "rzz",
    "s",
    "sbf",
    "sdg",
    "t",
    "tdg",
    "unitary",
    "x",
]


@dataclass(frozen=True, slots=True)
class GateSpec:
    """Static facts about one gate name.

    Attributes:
        name: gate name.
        num_qubits: number of qubits, or ``None`` if variadic (``mcx``: controls + target).
        num_params: number of angle parameters.
        inverse: ``"self"`` (self-inverse), ``"negate"`` (same gate, negated parameters), or
            the name of the inverse gate (``t`` -> ``tdg``).
        diagonal: the matrix is diagonal in the computational basis (see :func:`diagonal`).
        permutation: a (multi-)controlled X, i.e. a basis-state permutation
            (see :func:`controlled_x_pattern`).
    """

    name: str
    num_qubits: int | None
    num_params: int
    inverse: str
    diagonal: bool = False
    permutation: bool = False


_SPEC_LIST = (
    GateSpec("x", 1, 0, "self", permutation=True),
    GateSpec("h", 1, 0, "self"),
    GateSpec("t", 1, 0, "tdg", diagonal=True),
    GateSpec("tdg", 1, 0, "t", diagonal=True),
    GateSpec("s", 1, 0, "sdg", diagonal=True),
    GateSpec("sdg", 1, 0, "s", diagonal=True),
    GateSpec("rz", 1, 1, "negate", diagonal=True),
    GateSpec("rx", 1, 1, "negate"),
    GateSpec("ry", 1, 1, "negate"),
    GateSpec("cx", 2, 0, "self", permutation=True),
    GateSpec("cz", 2, 0, "self", diagonal=True),
    GateSpec("crz", 2, 1, "negate", diagonal=True),
    GateSpec("cry", 2, 1, "negate"),
    GateSpec("rzz", 2, 1, "negate", diagonal=True),
    GateSpec("ccx", 3, 0, "self", permutation=True),
    GateSpec("and", 3, 0, "and_dg", permutation=True),
    GateSpec("and_dg", 3, 0, "and", permutation=True),
    GateSpec("crx", 2, 1, "negate"),
    GateSpec("mcx", None, 0, "self", permutation=True),
    GateSpec("sbf", 4, 1, "negate"),
    GateSpec("csbf", 5, 1, "negate"),
)

GATE_SPECS: Mapping[str, GateSpec] = MappingProxyType({s.name: s for s in _SPEC_LIST})
"""Gate name -> :class:`GateSpec`, the single table every pass and simulator consults."""

_INVERSE_NAME = {s.name: (s.name if s.inverse in ("self", "negate") else s.inverse) for s in _SPEC_LIST}
_NEGATE = frozenset(s.name for s in _SPEC_LIST if s.inverse == "negate")


class Gate(NamedTuple):
    """One gate application: an immutable value type (a ``NamedTuple``, see module docs).

    Prefer the constructor functions (:func:`rz`, :func:`mcx`, ...), which validate and
    normalise; ``Gate(...)`` itself does not check anything.

    Attributes:
        name: a key of :data:`GATE_SPECS`.
        qubits: the qubits, in the gate's own order (controls first, target last).
        params: angles (``float | Angle``).
        ctrl_state: ``mcx`` only: one ``'0'``/``'1'`` per control, in ``qubits`` order.

    >>> Gate("h", (0,)) == h(0)
    True
    """

    name: str
    qubits: tuple[int, ...]
    params: tuple[Param, ...] = ()
    ctrl_state: str | None = None

    @property
    def spec(self) -> GateSpec:
        """The :class:`GateSpec` of this gate's name."""
        return GATE_SPECS[self.name]

    @property
    def num_qubits(self) -> int:
        """Number of qubits the gate acts on."""
        return len(self.qubits)

    def inverse(self) -> Gate:
        """The inverse gate (from the ``inverse`` rule of the spec table).

        >>> t(0).inverse().name, rx(0.3, 0).inverse().params
        ('tdg', (-0.3,))
        """
        name = self[0]
        if name in _NEGATE:
            return _new(Gate, (name, self[1], tuple(-p for p in self[2]), self[3]))
        inv = _INVERSE_NAME[name]
        if inv == name:
            return self
        return _new(Gate, (inv, self[1], self[2], self[3]))

    def bind(self, mapping: Mapping[str, float]) -> Gate:
        """Substitute symbol values; fully bound angles become floats.

        Args:
            mapping: symbol name -> value.

        Returns:
            The gate with bound parameters (``self`` if nothing changed).

        >>> rz(Angle.symbol("gamma_0", 2.0), 0).bind({"gamma_0": 0.25}).params
        (0.5,)
        """
        params = self[2]
        if not params:
            return self
        new = tuple(_bind_param(p, mapping) for p in params)
        if all(a is b for a, b in zip(new, params, strict=True)):
            return self
        return _new(Gate, (self[0], self[1], new, self[3]))

    def __str__(self) -> str:
        ps = f"({', '.join(str(p) for p in self.params)})" if self.params else ""
        cs = f"[{self.ctrl_state}]" if self.ctrl_state is not None else ""
        return f"{self.name}{cs}{ps} {' '.join(map(str, self.qubits))}"


_new = tuple.__new__


def _bind_param(p: Param, mapping: Mapping[str, float]) -> Param:
    if isinstance(p, Angle):
        b = p.bind(mapping)
        return b.constant if b.is_bound else b
    return p


# --- constructors ---------------------------------------------------------------------------
def _param(theta: object) -> Param:
    if type(theta) is float or type(theta) is Angle or isinstance(theta, Angle):
        return theta  # type: ignore[return-value]
    if isinstance(theta, bool) or not isinstance(theta, Real):
        raise TypeError(f"angle must be a real number or an Angle, got {theta!r}")
    return float(theta)


def _distinct(*qubits: int) -> tuple[int, ...]:
    for q in qubits:
        if type(q) is not int and (isinstance(q, bool) or not isinstance(q, (int, np.integer))):
            raise TypeError(f"qubit index must be an int, got {q!r}")
        if q < 0:
            raise ValueError(f"negative qubit index {q}")
    if len(set(qubits)) != len(qubits):
        raise ValueError(f"repeated qubit in {qubits}")
    return tuple(int(q) for q in qubits)


# Fast paths for the common case (plain non-negative distinct ints); _distinct reports errors.
def _q1(q: int) -> tuple[int]:
    if type(q) is int and q >= 0:
        return (q,)
    return _distinct(q)  # type: ignore[return-value]


def _q2(a: int, b: int) -> tuple[int, int]:
    if type(a) is int and type(b) is int and a != b and a >= 0 and b >= 0:
        return (a, b)
    return _distinct(a, b)  # type: ignore[return-value]


def x(q: int) -> Gate:
    """Pauli X on ``q``.

    >>> x(0)
    Gate(name='x', qubits=(0,), params=(), ctrl_state=None)
    """
    return _new(Gate, ("x", _q1(q), (), None))


def h(q: int) -> Gate:
    """Hadamard on ``q``."""
    return _new(Gate, ("h", _q1(q), (), None))


def t(q: int) -> Gate:
    """T = diag(1, e^{iπ/4}) on ``q``."""
    return _new(Gate, ("t", _q1(q), (), None))


def tdg(q: int) -> Gate:
    """T† on ``q``."""
    return _new(Gate, ("tdg", _q1(q), (), None))


def s(q: int) -> Gate:
    """S = diag(1, i) on ``q``."""
    return _new(Gate, ("s", _q1(q), (), None))


def sdg(q: int) -> Gate:
    """S† on ``q``."""
    return _new(Gate, ("sdg", _q1(q), (), None))


def rz(theta: Param, q: int) -> Gate:
    """RZ(θ) = diag(e^{-iθ/2}, e^{iθ/2}) on ``q``.

    Args:
        theta: angle (number or :class:`Angle`).
        q: qubit.

    >>> rz(Angle.symbol("gamma_0"), 2)
    Gate(name='rz', qubits=(2,), params=(Angle('gamma_0'),), ctrl_state=None)
    """
    return _new(Gate, ("rz", _q1(q), (_param(theta),), None))


def rx(theta: Param, q: int) -> Gate:
    """RX(θ) = exp(-iθX/2) on ``q``."""
    return _new(Gate, ("rx", _q1(q), (_param(theta),), None))


def ry(theta: Param, q: int) -> Gate:
    """RY(θ) = exp(-iθY/2) on ``q``."""
    return _new(Gate, ("ry", _q1(q), (_param(theta),), None))


def cx(c: int, t: int) -> Gate:
    """CNOT with control ``c`` and target ``t``."""
    return _new(Gate, ("cx", _q2(c, t), (), None))


def cz(a: int, b: int) -> Gate:
    """Controlled Z (symmetric)."""
    return _new(Gate, ("cz", _q2(a, b), (), None))


def crz(theta: Param, c: int, t: int) -> Gate:
    """RZ(θ) on ``t`` controlled by ``c`` (Qiskit's ``crz``)."""
    return _new(Gate, ("crz", _q2(c, t), (_param(theta),), None))


def cry(theta: Param, c: int, t: int) -> Gate:
    """RY(θ) on ``t`` controlled by ``c``."""
    return _new(Gate, ("cry", _q2(c, t), (_param(theta),), None))


def rzz(theta: Param, a: int, b: int) -> Gate:
    """RZZ(θ) = exp(-iθ Z_a Z_b / 2).

    >>> rzz(0.1, 0, 1).spec.diagonal
    True
    """
    return _new(Gate, ("rzz", _q2(a, b), (_param(theta),), None))


def ccx(a: int, b: int, t: int) -> Gate:
    """Toffoli: X on ``t`` if ``a`` and ``b`` are both 1."""
    return _new(Gate, ("ccx", _distinct(a, b, t), (), None))


def and_(a: int, b: int, target: int, ctrl_state: str = "11") -> Gate:
    """AND of two controls into a clean ``target`` (see the module table; uncompute with :func:`and_dg`).

    Args:
        a, b: controls.
        target: a qubit in |0> (the lowering is exact only then).
        ctrl_state: required values of ``a``, ``b`` (``'1'``: on |1>).

    >>> and_(0, 1, 2, "10")
    Gate(name='and', qubits=(0, 1, 2), params=(), ctrl_state='10')
    """
    if len(ctrl_state) != 2 or ctrl_state.strip("01"):
        raise ValueError(f"ctrl_state {ctrl_state!r} must be 2 characters of '0'/'1'")
    return _new(Gate, ("and", _distinct(a, b, target), (), ctrl_state))


def and_dg(a: int, b: int, target: int, ctrl_state: str = "11") -> Gate:
    """Uncompute of :func:`and_` (the same arguments)."""
    return and_(a, b, target, ctrl_state).inverse()


def crx(theta: Param, c: int, t: int) -> Gate:
    """Controlled RX(θ), control first."""
    return _new(Gate, ("crx", _q2(c, t), (_param(theta),), None))


def mcx(controls: Sequence[int], target: int, ctrl_state: str | None = None) -> Gate:
    """Multi-controlled X, normalised to the smallest equivalent gate name.

    Args:
        controls: control qubits (any number, including none).
        target: target qubit.
        ctrl_state: one ``'0'``/``'1'`` per control in ``controls`` order (``'1'``: fire on
            |1>); ``None`` means all ``'1'``.

    Returns:
        ``x`` for no control, ``cx``/``ccx`` for one/two positive controls, otherwise an
        ``mcx`` gate carrying an explicit ``ctrl_state``.

    >>> mcx([], 3).name, mcx([1], 0).name, mcx([1], 0, "0").name
    ('x', 'cx', 'mcx')
    >>> mcx([0, 1, 2], 3, "101").ctrl_state
    '101'
    """
    qubits = _distinct(*controls, target)
    k = len(qubits) - 1
    if ctrl_state is None:
        ctrl_state = "1" * k
    elif len(ctrl_state) != k or ctrl_state.strip("01"):
        raise ValueError(f"ctrl_state {ctrl_state!r} must be {k} characters of '0'/'1'")
    if k == 0:
        return _new(Gate, ("x", qubits, (), None))
    if ctrl_state == "1":
        return _new(Gate, ("cx", qubits, (), None))
    if ctrl_state == "11":
        return _new(Gate, ("ccx", qubits, (), None))
    return _new(Gate, ("mcx", qubits, (), ctrl_state))


def sbf(theta: Param, a: int, b: int, c: int, d: int) -> Gate:
    """SBF(θ) = exp(-iθ X_a X_b X_c X_d / 2)."""
    return _new(Gate, ("sbf", _distinct(a, b, c, d), (_param(theta),), None))


def csbf(theta: Param, ctrl: int, a: int, b: int, c: int, d: int) -> Gate:
    """SBF(θ) on ``a, b, c, d`` controlled by ``ctrl`` (``ctrl`` is listed first)."""
    return _new(Gate, ("csbf", _distinct(ctrl, a, b, c, d), (_param(theta),), None))


# --- action ---------------------------------------------------------------------------------
def controlled_x_pattern(gate: Gate) -> tuple[tuple[int, ...], str, int]:
    """Controls, required control values and target of a permutation gate.

    Every permutation gate of the set (``x``, ``cx``, ``ccx``, ``mcx``, ``and``, ``and_dg``) is an X on the target
    conditioned on each control having the given value.

    Args:
        gate: a gate whose spec has ``permutation=True``.

    Returns:
        ``(controls, ctrl_state, target)``.

    >>> controlled_x_pattern(mcx([4, 2], 0, "01"))
    ((4, 2), '01', 0)
    """
    name, qubits, _, state = gate
    if not GATE_SPECS[name].permutation:
        raise ValueError(f"{name} is not a permutation gate")
    controls = qubits[:-1]
    return controls, state if state is not None else "1" * len(controls), qubits[-1]


def _angle(gate: Gate) -> float:
    return float(gate[2][0])


_T = cmath.exp(0.25j * math.pi)
_FIXED_DIAGONALS = {
    "t": (1.0, _T),
    "tdg": (1.0, _T.conjugate()),
    "s": (1.0, 1j),
    "sdg": (1.0, -1j),
    "cz": (1.0, 1.0, 1.0, -1.0),
}


def diagonal(gate: Gate) -> np.ndarray:
    """Diagonal of a diagonal gate's matrix, indexed by the local basis index.

    Args:
        gate: a gate whose spec has ``diagonal=True``; parameters must be bound.

    Returns:
        Complex vector of length ``2**num_qubits``.

    >>> np.round(diagonal(rzz(math.pi, 0, 1)), 12).tolist()
    [-1j, 1j, 1j, -1j]
    """
    name = gate[0]
    fixed = _FIXED_DIAGONALS.get(name)
    if fixed is not None:
        return np.array(fixed, dtype=complex)
    if name in ("rz", "rzz", "crz"):
        half = 0.5 * _angle(gate)
        m, p = cmath.exp(-1j * half), cmath.exp(1j * half)
        if name == "rz":
            return np.array((m, p))
        if name == "rzz":
            return np.array((m, p, p, m))
        return np.array((1.0, m, 1.0, p))
    raise ValueError(f"{name} is not a diagonal gate")


_H = np.array([[1, 1], [1, -1]], dtype=complex) / math.sqrt(2)


def _rx(theta: float) -> np.ndarray:
    c, s_ = math.cos(theta / 2), math.sin(theta / 2)
    return np.array([[c, -1j * s_], [-1j * s_, c]])


def _ry(theta: float) -> np.ndarray:
    c, s_ = math.cos(theta / 2), math.sin(theta / 2)
    return np.array([[c, -s_], [s_, c]], dtype=complex)


def _sbf(theta: float) -> np.ndarray:
    # exp(-iθ/2 X⊗4) = cos(θ/2) I - i sin(θ/2) X⊗4, and X⊗4 maps index i to i ^ 0b1111.
    m = math.cos(theta / 2) * np.eye(16, dtype=complex)
    m[np.arange(16) ^ 15, np.arange(16)] = -1j * math.sin(theta / 2)
    return m


def _controlled(u: np.ndarray) -> np.ndarray:
    """Control on the local least significant bit (the first listed qubit)."""
    dim = u.shape[0]
    out = np.zeros((2 * dim, 2 * dim), dtype=complex)
    out[0::2, 0::2] = np.eye(dim)
    out[1::2, 1::2] = u
    return out


@lru_cache(maxsize=64)
def _permutation_matrix(k: int, state: str) -> np.ndarray:
    """Pure memo: ``_permutation_matrix.cache_clear()`` empties it."""
    dim = 1 << (k + 1)
    want = sum(1 << i for i, c in enumerate(state) if c == "1")
    cmask = (1 << k) - 1
    tbit = 1 << k
    perm = [(i ^ tbit) if (i & cmask) == want else i for i in range(dim)]
    m = np.zeros((dim, dim), dtype=complex)
    m[perm, np.arange(dim)] = 1.0
    m.setflags(write=False)
    return m


def unitary(gate: Gate) -> np.ndarray:
    """Matrix of ``gate`` on its own qubits (first listed qubit = least significant bit).

    Permutation gates are built from :func:`controlled_x_pattern` and diagonal gates from
    :func:`diagonal`, so the simulators (which use those directly) cannot disagree with it.

    Args:
        gate: any gate with bound parameters.

    Returns:
        A ``2**n x 2**n`` complex array (a fresh, writable copy).

    Raises:
        UnboundParameterError: a parameter is still symbolic.

    >>> np.allclose(unitary(ry(0.3, 0)) @ unitary(ry(-0.3, 0)), np.eye(2))
    True
    """
    name = gate[0]
    spec = GATE_SPECS[name]
    if spec.permutation:
        controls, state, _ = controlled_x_pattern(gate)
        return _permutation_matrix(len(controls), state).copy()
    if spec.diagonal:
        return np.diag(diagonal(gate))
    if name == "h":
        return _H.copy()
    if name == "rx":
        return _rx(_angle(gate))
    if name == "ry":
        return _ry(_angle(gate))
    if name == "cry":
        return _controlled(_ry(_angle(gate)))
    if name == "crx":
        return _controlled(_rx(_angle(gate)))
    if name == "sbf":
        return _sbf(_angle(gate))
    if name == "csbf":
        return _controlled(_sbf(_angle(gate)))
    raise ValueError(f"no matrix known for gate {name!r}")
