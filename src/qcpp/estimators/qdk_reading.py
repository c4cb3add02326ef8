"""The QDK resource estimator's own reading of a qcpp circuit, term by term, beside qcpp's logical counts.

``qcpp estimate --physical`` hands the QDK estimator logical counts it computes itself
(:attr:`qcpp.estimators.estimate.Estimate.logical_counts`); the QDK can also read the OpenQASM that ``qcpp compile``
writes and count for itself (``qdk.openqasm.estimate``). The physical figures (code distance, T factories, physical
qubits, runtime) are one function of the seven logical counts in both cases (Beverland et al. 2022,
arXiv:2211.07629: ``2Q + ceil(sqrt(8Q)) + 1`` logical qubits with layout overhead,
``M + R + T + 3 (CCZ + CCiX) + t_rot * rotation depth`` logical cycles, ``T + 4 (CCZ + CCiX) + t_rot * R``
T states), so every difference between the two estimates is a difference of counts. This module reads the QDK's
counts (:func:`qdk_read`) and gives it two texts of one circuit:

* the file as written (``qcpp compile --bind``): OpenQASM gate definitions cannot measure, so an AND uncompute is
  written unitarily (4 T) and nothing is measured; the QDK counts every AND as 4 explicit T gates;
* the logical-AND reading (:func:`logical_and_qasm`), the model qcpp's counts assume
  (:mod:`qcpp.estimators.fault_tolerant`): an AND is a ``ccx`` onto its clean target (the QDK's CCZ, which its
  formulas charge exactly as a CCiX: 4 T states, 3 cycles), an AND uncompute is Gidney's measurement-based one
  (``h``, measure, a classically controlled ``cz``, ``reset``: one measurement, no T) and the data register is
  read out at the end.

With the logical-AND reading the QDK's counts equal qcpp's in every term but the rotation depth, which the two
define differently (:func:`asap_rotation_depth` is the QDK's rule, in Python): the QDK layers ASAP with every T
gate taking a layer on its qubit and counts the layers that hold a rotation; qcpp
(:mod:`qcpp.estimators.depth`) counts the longest chain of dependent rotations, T gates and Cliffords ordering
but not separating them. A chain of ``k`` dependent rotations takes ``k`` distinct ASAP layers, so the QDK's figure
is never below qcpp's; qcpp's is the fewest rotation layers any schedule needs and is reached (rotations grouped
by their chain length, every T gate run between the layers of the rotations before and after it), so it is the
figure the PSSPC layout's parallel synthesis runs.

Why the legacy entry point: ``qdk.openqasm.estimate`` is the estimator ``qcpp estimate --physical`` uses
(``qdk.estimator.LogicalCounts.estimate``, the same Beverland et al. model), so the two readings differ only by
their counts. qdk 1.33 marks it deprecated in favour of ``qdk.qre``, which reads OpenQASM too
(``qdk.qre.application.OpenQASMApplication``) and models the same qubit (``GateBased(error_rate=1e-3,
gate_time=50, measurement_time=100)``) and surface code under ``max_error=1e-3``, but is another estimator: it
returns a Pareto frontier over code distances and factory designs, composes the error budget over every operation,
and builds other T factories (round-based distillation, Litinski 2019). None of its estimates equals the legacy
one, so a comparison through it would measure the estimators, not the counts (``benchmarks/qre_v3_check.py``
prints both). :func:`qdk_read` therefore keeps the legacy call and silences only its deprecation warning. When a
qdk release removes ``qdk.openqasm.estimate``, :func:`qdk_read` raises :class:`ImportError` naming it;
``benchmarks/ft_vs_qdk.py`` and the tests of this module need an older qdk then, and ``qcpp estimate
--physical`` needs ``qdk.estimator`` (the same legacy estimator, not yet marked deprecated in 1.33) kept too.

Example:
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import Gate
    >>> gates = [Gate("t", (0,), (), None), Gate("rz", (0,), (0.3,), None), Gate("rz", (1,), (0.2,), None)]
    >>> asap_rotation_depth(gates, 2)  # the T pushes the first rotation to a second layer
    2
    >>> print(logical_and_qasm(Circuit([("data", 2), ("logic", 1)], [Section("s", [
    ...     Gate("and", (0, 1, 2), (), "10"), Gate("and_dg", (0, 1, 2), (), "10")])])))
    OPENQASM 3.0;
    include "stdgates.inc";
    qubit[3] q;
    bit m;
    x q[1];
    ccx q[0],q[1],q[2];
    x q[1];
    x q[1];
    h q[2];
    m = measure q[2];
    if (m) cz q[0],q[1];
    reset q[2];
    x q[1];
    measure q[0];
    measure q[1];
    <BLANKLINE>
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from qcpp.estimators.physical import (
    DEFAULT_ERROR_BUDGET,
    DEFAULT_QEC_SCHEME,
    DEFAULT_QUBIT_MODEL,
    LogicalCounts,
    PhysicalEstimate,
    estimator_params,
    physical_from_result,
)
from qcpp.ir.angles import format_float
from qcpp.ir.circuit import Circuit
from qcpp.lowering.passes import LOGICAL_BASIS

__all__ = ["LEGACY_QRE_WARNING", "QdkReading", "asap_rotation_depth", "logical_and_qasm", "qdk_read"]

LEGACY_QRE_WARNING = "This version of QRE is deprecated"
"""The start of the DeprecationWarning qdk (1.33) gives on every call of its legacy estimator; :func:`qdk_read`
silences that warning and no other."""

_CLIFFORD_1Q = frozenset({"h", "s", "sdg", "x", "y", "z", "sx"})
_QUARTER = math.pi / 4


@dataclass(frozen=True)
class QdkReading:
    """The QDK's counts of an OpenQASM text and its physical estimate from them.

    Attributes:
        counts: the logical counts the QDK's tracer found.
        physical: its physical estimate (same model fields as :func:`qcpp.estimators.physical.physical_estimate`).
        logical_qubits: logical qubits with the PSSPC layout overhead (``algorithmicLogicalQubits``).
        t_per_rotation: T states per rotation the estimator chose (``numTsPerRotation``; 0 without rotations).
    """

    counts: LogicalCounts
    physical: PhysicalEstimate
    logical_qubits: int
    t_per_rotation: int


def qdk_read(
    source: str,
    qubit_model: str = DEFAULT_QUBIT_MODEL,
    qec_scheme: str = DEFAULT_QEC_SCHEME,
    error_budget: float = DEFAULT_ERROR_BUDGET,
) -> QdkReading:
    """Let the QDK resource estimator read an OpenQASM 3 text (every angle bound) and estimate it.

    The estimator is the legacy one (``qdk.openqasm.estimate``), the one ``qcpp estimate --physical`` hands its
    counts to, so the two estimates differ by their counts alone (see the module docstring for why ``qdk.qre``
    cannot stand in). Its deprecation warning (qdk 1.33) is silenced for this call only; any other warning passes.

    Args:
        source: OpenQASM 3 text.
        qubit_model, qec_scheme, error_budget: the model, as :func:`qcpp.estimators.physical.physical_estimate`.

    Returns:
        The :class:`QdkReading`.

    Raises:
        ImportError: the installed qdk has no ``qdk.openqasm.estimate`` (removed after its deprecation).
    """
    import warnings

    from qdk import openqasm

    legacy = getattr(openqasm, "estimate", None)
    if legacy is None:
        raise ImportError("qdk_read needs qdk.openqasm.estimate, the legacy QDK resource estimator, which this "
                          "qdk no longer has (qdk 1.33 has it)")
    params = estimator_params(qubit_model, qec_scheme, error_budget)
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=LEGACY_QRE_WARNING, category=DeprecationWarning)
        res = legacy(source, params)
    counts = LogicalCounts.from_qdk(res["logicalCounts"])
    bd = res["physicalCounts"]["breakdown"]
    return QdkReading(
        counts=counts,
        physical=physical_from_result(res, qubit_model, qec_scheme, error_budget),
        logical_qubits=int(bd["algorithmicLogicalQubits"]),
        t_per_rotation=int(bd.get("numTsPerRotation") or 0),
    )


def _is_quarter_turn(theta: float) -> tuple[bool, bool]:
    """(a multiple of pi/4, an odd multiple) within the QDK's tolerance."""
    k = round(theta / _QUARTER)
    return abs(k * _QUARTER - theta) <= 2.220446049250313e-16, k % 2 == 1


def asap_rotation_depth(gates: Iterable[tuple[Any, ...]], num_qubits: int) -> int:
    """The rotation depth by the QDK tracer's rule (``resource_estimator/src/counts.rs`` of microsoft/qsharp).

    ASAP layers shared by all qubits: a ``t``/``tdg`` and an arbitrary ``rz`` each take the next layer on their
    qubit (an ``rz`` of an odd multiple of pi/4 is a T, of an even one a Clifford), a ``ccx`` takes the next layer
    on its three qubits, a two-qubit Clifford aligns its two qubits to the later of them without a layer of its
    own, one-qubit Cliffords take none. The result is the number of layers that hold a rotation.

    Args:
        gates: gate tuples ``(name, qubits, params, ...)`` with bound angles (names of the lowered and logical
            bases; ``and``/``and_dg`` are not read).
        num_qubits: one more than the largest qubit index.

    Returns:
        The number of layers holding a rotation.

    Raises:
        ValueError: a gate this rule does not read.
    """
    level = [0] * num_qubits
    rotation_layers: set[int] = set()
    for g in gates:
        name, qs = g[0], g[1]
        if name == "rz":
            quarter, odd = _is_quarter_turn(float(g[2][0]))
            if quarter and not odd:
                continue
            q = qs[0]
            if not quarter:
                rotation_layers.add(level[q])
            level[q] += 1
        elif name in ("t", "tdg"):
            level[qs[0]] += 1
        elif name in ("cx", "cz", "swap"):
            a, b = qs
            level[a] = level[b] = max(level[a], level[b])
        elif name == "ccx":
            top = max(level[q] for q in qs) + 1
            for q in qs:
                level[q] = top
        elif name not in _CLIFFORD_1Q:
            raise ValueError(f"asap_rotation_depth: gate {name!r} is not read by this rule")
    return len(rotation_layers)


def _flips(g: tuple[Any, ...]) -> list[str]:
    state = g[3] or "11"
    return [f"x q[{c}];" for c, bit in zip(g[1][:2], state, strict=True) if bit == "0"]


def logical_and_qasm(circuit: Circuit) -> str:
    """OpenQASM 3 of a bound circuit in the logical-AND model, for the QDK to read (see the module docstring).

    Args:
        circuit: a bound circuit in :data:`qcpp.lowering.passes.LOGICAL_BASIS` (``lower(c, basis=LOGICAL_BASIS)``);
            its ``data`` register (if any) is measured at the end.

    Returns:
        The text: ``and`` as ``ccx`` (X on its '0' controls around it), ``and_dg`` as ``h``, ``measure``, a
        classically controlled ``cz`` and ``reset``, every other gate as its standard OpenQASM 3 gate.

    Raises:
        ValueError: a gate outside :data:`~qcpp.lowering.passes.LOGICAL_BASIS`, or an unbound angle.
    """
    lines = ["OPENQASM 3.0;", 'include "stdgates.inc";', f"qubit[{circuit.num_qubits}] q;", "bit m;"]
    append = lines.append
    for g in circuit.gates:
        name, qs, params = g[0], g[1], g[2]
        if name not in LOGICAL_BASIS:
            raise ValueError(f"logical_and_qasm: gate {name!r} is not in the logical basis (lower the circuit first)")
        if name in ("and", "and_dg"):
            a, b, t = qs
            flips = _flips(g)
            lines.extend(flips)
            if name == "and":
                append(f"ccx q[{a}],q[{b}],q[{t}];")
            else:
                lines.extend((f"h q[{t}];", f"m = measure q[{t}];", f"if (m) cz q[{a}],q[{b}];", f"reset q[{t}];"))
            lines.extend(flips)
            continue
        if any(type(p) is not float for p in params):
            raise ValueError(f"logical_and_qasm: gate {name!r} has an unbound angle (bind the circuit first)")
        head = f"{name}({','.join(format_float(p) for p in params)})" if params else name
        append(f"{head} {','.join(f'q[{q}]' for q in qs)};")
    if circuit.has_register("data"):
        lines.extend(f"measure q[{q}];" for q in circuit.qubits_of("data"))
    return "\n".join(lines) + "\n"
