"""A circuit as another toolchain's Python object: a ``cirq.Circuit`` or a ``pytket.Circuit``, its symbols kept.

OpenQASM carries a circuit to any client (:mod:`qcpp.lowering.qasm_profiles`); these converters hand the circuit
to Cirq and pytket as objects, with qcpp's unbound angles as the toolchain's own symbolic parameters (sympy
symbols of the same names: ``gamma_0``, ``beta_0``, ...), so a sweep over the angles needs no export per value.

**Gate for gate** where the toolchain has the gate (:data:`DIRECT`: ``x h t tdg s sdg rz rx ry cx cz crz cry rzz
ccx`` and ``mcx``, a multi-controlled X with its control values); every other gate (``and``, ``and_dg``, ``crx``,
``sbf``, ``csbf``) is written as the exact decomposition qcpp's own lowering uses
(:func:`qcpp.lowering.passes.decompose_gate`; for ``and``/``and_dg`` the relative-phase Toffoli, exact on a clean
target as the IR's contract says), so a lowered circuit converts one gate to one operation. Each gate has the
matrix of :mod:`qcpp.ir.gates`, global phase included (``rz(θ) = exp(-iθZ/2)``, pytket's angles in half-turns:
``Rz(θ/π)``; ``rzz(θ) = exp(-iθZZ/2)`` is Cirq's ``ZZPowGate(exponent=θ/π, global_shift=-1/2)`` and pytket's
``ZZPhase(θ/π)``). ``tests/compiler/toolchains_test.py`` compares the unitaries of random gate sequences with an
independent conversion (:func:`qcpp.simulate.equivalence.to_qiskit`) and the states of compiled circuits with
Qiskit's reading of their OpenQASM 3, global phase included. Qubit ``i`` is
``cirq.LineQubit(i)`` and pytket's ``q[i]``; Cirq's circuit holds only the qubits its operations touch (pass
``qubit_order=cirq.LineQubit.range(n)`` to its simulators), pytket's all ``n``.

Cirq and pytket are optional (``pip install 'qcpp[cirq]'``, ``'qcpp[pytket]'``); without them the converters raise
:class:`qcpp.errors.MissingExtraError` (a ``QcppError`` and an ``ImportError``) naming the extra.

Example:
    >>> from qcpp.ir.angles import Angle
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx, h, rzz
    >>> c = Circuit([("data", 2)], [Section("s", [h(0), cx(0, 1), rzz(Angle.symbol("gamma_0", 2.0), 0, 1)])])
    >>> print(to_pytket(c).get_commands())
    [H q[0];, CX q[0], q[1];, ZZPhase(2.0*gamma_0/pi) q[0], q[1];]
    >>> import cirq
    >>> sorted(cirq.parameter_names(to_cirq(c)))
    ['gamma_0']
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from typing import Any

from qcpp.errors import MissingExtraError, missing_extra
from qcpp.ir.angles import Angle, Param
from qcpp.ir.circuit import Circuit
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import decompose_gate

__all__ = ["DIRECT", "to_cirq", "to_pytket"]

DIRECT = frozenset({"x", "h", "t", "tdg", "s", "sdg", "rz", "rx", "ry", "cx", "cz", "crz", "cry", "rzz", "ccx", "mcx"})
"""Gates both converters write as one operation; any other is written as its decomposition."""


def _flat(circuit: Circuit) -> Iterator[Gate]:
    """The gates of ``circuit`` in order, each gate outside :data:`DIRECT` replaced by its exact decomposition."""
    for gate in circuit.gates:
        yield from _expanded(gate)


def _expanded(gate: Gate) -> Iterator[Gate]:
    if gate[0] in DIRECT:
        yield gate
        return
    for sub in decompose_gate(gate):
        yield from _expanded(sub)


def _angle(value: Param, half_turns: bool = False) -> Any:
    """``value`` in radians (or half-turns: divided by pi) as a float, or as a sympy expression of its symbols if
    unbound."""
    if not isinstance(value, Angle) or value.is_bound:
        return float(value) / math.pi if half_turns else float(value)
    import sympy

    expr = sympy.Float(value.constant) + sum(sympy.Float(c) * sympy.Symbol(name) for name, c in value.terms)
    return expr / sympy.pi if half_turns else expr


def _missing(what: str, package: str, exc: ImportError) -> MissingExtraError:
    return missing_extra(what, package, package.split("-")[0], exc.name)


def to_cirq(circuit: Circuit) -> Any:
    """``circuit`` as a ``cirq.Circuit`` (module docs: qubit ``i`` is ``cirq.LineQubit(i)``; unbound angles are
    sympy symbols of the same names).

    Args:
        circuit: Any circuit of qcpp (high level, lowered, or routed in a device's native gates).

    Returns:
        The ``cirq.Circuit``, its operations in the order of ``circuit``'s gates (decompositions in place).

    Raises:
        qcpp.errors.MissingExtraError: Cirq is not installed (also an ``ImportError``).
    """
    try:
        import cirq
    except ImportError as exc:
        raise _missing("to_cirq", "cirq-core", exc) from None

    q = cirq.LineQubit.range(circuit.num_qubits)
    fixed: dict[str, Callable[..., Any]] = {
        "x": cirq.X, "h": cirq.H, "t": cirq.T, "tdg": cirq.T**-1, "s": cirq.S, "sdg": cirq.S**-1, "cx": cirq.CNOT,
        "cz": cirq.CZ, "ccx": cirq.CCX,
    }  # fmt: skip
    ops = []
    for name, qubits, params, ctrl_state in _flat(circuit):
        on = [q[i] for i in qubits]
        if name in fixed:
            ops.append(fixed[name](*on))
        elif name in ("rz", "rx", "ry"):
            ops.append(getattr(cirq, name)(_angle(params[0]))(*on))
        elif name in ("crz", "cry"):
            ops.append(getattr(cirq, name[1:])(_angle(params[0])).controlled()(*on))
        elif name == "rzz":
            ops.append(cirq.ZZPowGate(exponent=_angle(params[0], half_turns=True), global_shift=-0.5)(*on))
        else:  # mcx: controls first, the target last
            values = [int(v) for v in (ctrl_state or "1" * (len(on) - 1))]
            ops.append(cirq.X(on[-1]).controlled_by(*on[:-1], control_values=values))
    return cirq.Circuit(ops)


def to_pytket(circuit: Circuit) -> Any:
    """``circuit`` as a ``pytket.Circuit`` on ``circuit.num_qubits`` qubits (module docs: angles in half-turns;
    unbound angles are sympy symbols of the same names).

    Args:
        circuit: Any circuit of qcpp (high level, lowered, or routed in a device's native gates).

    Returns:
        The ``pytket.Circuit``, its commands in the order of ``circuit``'s gates (decompositions in place; a
        multi-controlled X with a control on ``|0>`` is conjugated by X on that control).

    Raises:
        qcpp.errors.MissingExtraError: pytket is not installed (also an ``ImportError``).
    """
    try:
        import pytket
        from pytket import OpType
    except ImportError as exc:
        raise _missing("to_pytket", "pytket", exc) from None

    out = pytket.Circuit(circuit.num_qubits)
    fixed = {"x": OpType.X, "h": OpType.H, "t": OpType.T, "tdg": OpType.Tdg, "s": OpType.S, "sdg": OpType.Sdg,
             "cx": OpType.CX, "cz": OpType.CZ, "ccx": OpType.CCX}  # fmt: skip
    rotations = {"rz": OpType.Rz, "rx": OpType.Rx, "ry": OpType.Ry, "crz": OpType.CRz, "cry": OpType.CRy,
                 "rzz": OpType.ZZPhase}  # fmt: skip
    for name, qubits, params, ctrl_state in _flat(circuit):
        if name in fixed:
            out.add_gate(fixed[name], list(qubits))
        elif name in rotations:
            out.add_gate(rotations[name], [_angle(params[0], half_turns=True)], list(qubits))
        else:  # mcx: X on every control on |0>, the controlled X, X again
            zeros = [c for c, v in zip(qubits[:-1], ctrl_state or "", strict=False) if v == "0"]
            for c in zeros:
                out.X(c)
            out.add_gate(OpType.CnX, list(qubits))
            for c in zeros:
                out.X(c)
    return out
