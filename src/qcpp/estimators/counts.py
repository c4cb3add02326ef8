"""Exact resource counts of a circuit: qubits, gates per name, T count, depth and two-qubit depth.

:func:`count` reads any :class:`~qcpp.ir.circuit.Circuit`'s own gate tuples, high level or lowered: the very
gate list :mod:`qcpp.lowering.qasm` writes, so the numbers equal what a reader of the emitted file counts. The
definitions are Qiskit's (``tests/estimators/counts_test.py`` checks them against
``qiskit.qasm2.loads(to_qasm2(c))``): ``qubits`` is ``num_qubits`` (``data_qubits`` the ``data`` register,
``ancillas`` the rest), ``ops`` is ``count_ops()``, ``depth`` is ``depth()`` and ``two_qubit_depth`` is
``depth(filter_function=lambda i: i.operation.num_qubits == 2)`` (:func:`qcpp.estimators.depth.advance`).

Sections sharing a name (``initial_state``, ``phase_k``, ``mixer_k``, ...) are added up, and their depth is the
ASAP depth of all their gates, in circuit order, taken alone (``sections["mixer_k"]`` is the whole mixer layer
``k``). Section depths do not add up to the circuit's: ASAP layering lets a later section start early.

Example:
    >>> from qcpp.ir.circuit import CircuitBuilder
    >>> from qcpp.ir.gates import cx, h, t
    >>> b = CircuitBuilder([("data", 2), ("work", 1)])
    >>> b.append([h(0), cx(0, 1), t(2)], section="s")
    >>> rc = count(b.build())
    >>> rc.qubits, rc.data_qubits, rc.ancillas, rc.cx, rc.t, rc.depth, rc.two_qubit_depth
    (3, 2, 1, 1, 1, 2, 1)
    >>> rc.sections["s"].ops
    {'cx': 1, 'h': 1, 't': 1}
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from operator import itemgetter
from typing import Any

from qcpp.estimators.depth import advance
from qcpp.ir.circuit import Circuit
from qcpp.ir.gates import GATE_SPECS

__all__ = ["GateCount", "ResourceCount", "count", "count_gates"]

DATA_REGISTER = "data"
_T_NAMES = ("t", "tdg")


@dataclass(frozen=True)
class GateCount:
    """Gate statistics of a gate sequence (a whole circuit or the sections sharing one name).

    Attributes:
        ops: gates per name, sorted by name.
        size: all gates.
        single_qubit, two_qubit, multi_qubit: gates on one, two, three or more qubits.
        cx: ``cx`` gates.
        t: ``t`` plus ``tdg`` gates.
        depth, two_qubit_depth: see the module docstring.
    """

    ops: Mapping[str, int] = field(default_factory=dict)
    size: int = 0
    single_qubit: int = 0
    two_qubit: int = 0
    multi_qubit: int = 0
    cx: int = 0
    t: int = 0
    depth: int = 0
    two_qubit_depth: int = 0

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field (mappings as dicts, tuples as lists, sections nested)."""
        return {k: _plain(getattr(self, k)) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class ResourceCount(GateCount):
    """Exact resources of one circuit: qubits, the :class:`GateCount` fields, and a per-section breakdown.

    Attributes:
        qubits, data_qubits, ancillas: see the module docstring.
        registers: ``(name, size)`` of every register, in layout order.
        sections: section name -> :class:`GateCount`, in order of first appearance.
    """

    qubits: int = 0
    data_qubits: int = 0
    ancillas: int = 0
    registers: tuple[tuple[str, int], ...] = ()
    sections: Mapping[str, GateCount] = field(default_factory=dict)


def _plain(value: Any) -> Any:
    if isinstance(value, GateCount):
        return value.to_dict()
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    return [_plain(v) for v in value] if isinstance(value, tuple) else value


def _arity(ops: Counter[str], gates: Iterable[tuple[Any, ...]]) -> Counter[int]:
    """Gates per number of qubits: from the spec table, looking at single gates only for variadic names."""
    arity: Counter[int] = Counter()
    variadic = set()
    for name, k in ops.items():
        spec = GATE_SPECS.get(name)
        if spec is None or spec.num_qubits is None:
            variadic.add(name)
        else:
            arity[spec.num_qubits] += k
    if variadic:
        arity.update(len(g[1]) for g in gates if g[0] in variadic)
    return arity


def _stats(ops: Counter[str], arity: Counter[int], depth: int, depth2: int) -> GateCount:
    return GateCount(
        ops=dict(sorted(ops.items())),
        size=sum(ops.values()),
        single_qubit=arity.get(1, 0),
        two_qubit=arity.get(2, 0),
        multi_qubit=sum(v for k, v in arity.items() if k >= 3),
        cx=ops.get("cx", 0),
        t=sum(ops.get(n, 0) for n in _T_NAMES),
        depth=depth,
        two_qubit_depth=depth2,
    )


def count_gates(gates: Iterable[tuple[Any, ...]], num_qubits: int) -> GateCount:
    """:class:`GateCount` of a plain gate sequence.

    Args:
        gates: gate tuples ``(name, qubits, ...)`` (:class:`~qcpp.ir.gates.Gate` or plain tuples).
        num_qubits: one more than the largest qubit index used.

    >>> count_gates([("h", (0,)), ("cx", (0, 1)), ("ccx", (0, 1, 2)), ("cx", (1, 2))], 3).two_qubit_depth
    2
    """
    gates = list(gates)
    lv, l2 = [0] * num_qubits, [0] * num_qubits
    advance(gates, lv, l2)
    ops = Counter(map(itemgetter(0), gates))
    return _stats(ops, _arity(ops, gates), max(lv, default=0), max(l2, default=0))


def count(circuit: Circuit) -> ResourceCount:
    """Count the resources of ``circuit`` (see the module docstring).

    Args:
        circuit: any circuit; symbolic angles are fine.

    >>> from qcpp.ir.circuit import CircuitBuilder
    >>> from qcpp.ir.gates import cx, x
    >>> b = CircuitBuilder([("data", 2)])
    >>> b.append([x(0), cx(0, 1)], section="mixer_0")
    >>> b.append([x(1)], section="phase_1")
    >>> b.append([cx(0, 1)], section="mixer_0")
    >>> rc = count(b.build())
    >>> rc.depth, rc.sections["mixer_0"].ops, rc.sections["mixer_0"].depth
    (4, {'cx': 2, 'x': 1}, 3)
    """
    n = circuit.num_qubits
    lv, l2 = [0] * n, [0] * n
    per_name: dict[str, tuple[Counter[str], Counter[int], list[int], list[int]]] = {}
    for sec in circuit.sections:
        gates = sec.gates
        acc = per_name.get(sec.name)
        if acc is None:
            acc = per_name[sec.name] = (Counter(), Counter(), [0] * n, [0] * n)
        sec_ops = Counter(map(itemgetter(0), gates))
        acc[0].update(sec_ops)
        acc[1].update(_arity(sec_ops, gates))
        advance(gates, lv, l2)  # the whole circuit's levels, then this section name's own
        advance(gates, acc[2], acc[3])
    ops: Counter[str] = Counter()
    arity: Counter[int] = Counter()
    sections: dict[str, GateCount] = {}
    for name, (s_ops, s_arity, s_lv, s_l2) in per_name.items():
        ops.update(s_ops)
        arity.update(s_arity)
        sections[name] = _stats(s_ops, s_arity, max(s_lv, default=0), max(s_l2, default=0))
    total = _stats(ops, arity, max(lv, default=0), max(l2, default=0))
    registers = tuple((r.name, r.size) for r in circuit.registers)
    data = sum(size for name, size in registers if name == DATA_REGISTER)
    return ResourceCount(
        **{k: getattr(total, k) for k in GateCount.__dataclass_fields__},
        qubits=n,
        data_qubits=data,
        ancillas=n - data,
        registers=registers,
        sections=sections,
    )
