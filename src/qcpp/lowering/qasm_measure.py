"""Measurements appended to an OpenQASM text: one classical register ``meas``, bit ``i`` measuring a given qubit.

A file written by :mod:`qcpp.lowering.qasm` or a profile of :mod:`qcpp.lowering.qasm_profiles` ends its header with
the qubit register's declaration and ends with the last section's statements. :func:`with_measurements` adds the
classical register's declaration right after the qubit register's and the measurements after the last section, in
the syntax of the version (OpenQASM 3: ``bit[n] meas;`` and ``meas[i] = measure q[j];``, the same in every profile;
OpenQASM 2: ``creg meas[n];`` and ``measure q[j] -> meas[i];``). Nothing else of the text changes, so a file
without measurements is the writers' text byte for byte.

The register is named as Qiskit's ``measure_all`` names it: loaded by Qiskit (``qiskit.qasm3.loads``) and run by a
``SamplerV2``, the counts are ``result[0].data.meas.get_counts()``, keys with clbit 0 rightmost.

>>> from qcpp.ir.circuit import Circuit, Section
>>> from qcpp.ir.gates import h
>>> from qcpp.lowering.qasm import iter_qasm
>>> c = Circuit([("q", 3)], [Section("s", [h(2)])])
>>> print("".join(with_measurements(iter_qasm(c, 3), [2, 0], 3)), end="")
OPENQASM 3.0;
include "stdgates.inc";
qubit[3] q;
bit[2] meas;
// section s
h q[2];
// measure
meas[0] = measure q[2];
meas[1] = measure q[0];
>>> print("".join(with_measurements(iter_qasm(c, 2), [2], 2)), end="")
OPENQASM 2.0;
include "qelib1.inc";
qreg q[3];
creg meas[1];
// section s
h q[2];
// measure
measure q[2] -> meas[0];
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence

__all__ = ["MEASURE_REGISTER", "check_measured", "measure_text", "with_measurements"]

MEASURE_REGISTER = "meas"
"""The classical register's name (Qiskit's ``measure_all`` name; not a symbol name qcpp writes)."""


def check_measured(qubits: Sequence[int], num_qubits: int) -> tuple[int, ...]:
    """``qubits`` as a tuple, if they are distinct qubits of a register of ``num_qubits``, else ``ValueError``."""
    out = tuple(int(q) for q in qubits)
    if len(set(out)) != len(out) or any(not 0 <= q < num_qubits for q in out):
        raise ValueError(f"measured qubits must be distinct qubits below {num_qubits}, got {list(out)}")
    return out


def measure_text(qubits: Sequence[int], version: int) -> tuple[str, str]:
    """The declaration line and the measurement block (each ending in a newline) measuring ``qubits[i]`` into bit
    ``i`` of :data:`MEASURE_REGISTER`."""
    n, reg = len(qubits), MEASURE_REGISTER
    if version == 3:
        lines = [f"{reg}[{i}] = measure q[{q}];\n" for i, q in enumerate(qubits)]
        return f"bit[{n}] {reg};\n", "".join(["// measure\n", *lines])
    lines = [f"measure q[{q}] -> {reg}[{i}];\n" for i, q in enumerate(qubits)]
    return f"creg {reg}[{n}];\n", "".join(["// measure\n", *lines])


def with_measurements(chunks: Iterable[str], qubits: Sequence[int], version: int) -> Iterator[str]:
    """The chunks of an OpenQASM text (header first, as the writers give them) with the measurements of ``qubits``
    added (module docs); the chunks are passed through as they come."""
    declaration, block = measure_text(qubits, version)
    it = iter(chunks)
    head = next(it)
    if not head.endswith(" q;\n") and not head.endswith("];\n"):  # the writers end the header on the qubits
        raise ValueError("with_measurements: the first chunk is not an OpenQASM header ending in the qubit register")
    yield head + declaration
    yield from it
    yield block
