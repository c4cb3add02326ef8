"""A routed native circuit as Qiskit sees a circuit transpiled for the device: ``sx`` gates and the layouts.

The IR has no ``sx``: :func:`qcpp.routing.native.to_native` writes the device's ``sx`` as ``rx(pi/2)`` and charges
the device's ``sx`` error and duration for it. Loaded into Qiskit as written, such a circuit is not in an IBM
target's basis (``cz rz sx x``), and Qiskit's basis translation turns each ``rx(pi/2)`` into two ``sx`` pulses.
:func:`native_sx` writes each ``rx(pi/2)`` as ``sx`` with the global phase that keeps the unitary exactly equal
(``rx(pi/2) = e^{-i pi/4} sx``); :func:`attach_layout` records the routing's initial and final layouts on the
circuit as a Qiskit ``TranspileLayout``, so ``qc.layout.final_index_layout()`` says where each logical qubit ends.

Example:
    >>> import math
    >>> from qiskit import QuantumCircuit
    >>> from qiskit.quantum_info import Operator
    >>> qc = QuantumCircuit(2)
    >>> _ = qc.rx(math.pi / 2, 0)
    >>> _ = qc.cz(0, 1)
    >>> out, k = native_sx(qc)
    >>> dict(out.count_ops()), k, Operator(out) == Operator(qc)
    ({'sx': 1, 'cz': 1}, 1, True)
    >>> qc = attach_layout(QuantumCircuit(3), initial=[2, 0], final=[0, 1])
    >>> qc.layout.initial_index_layout(filter_ancillas=True), qc.layout.final_index_layout()
    ([2, 0], [0, 1])
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

__all__ = ["attach_layout", "native_sx"]

_HALF_PI = math.pi / 2


def native_sx(qc: Any) -> tuple[Any, int]:
    """``qc`` with every ``rx(pi/2)`` (angle exactly ``pi/2`` as a float) written ``sx``, the global phase lowered by
    ``pi/4`` per gate so the unitary is the same; and how many were rewritten. Other gates are kept as they are."""
    from qiskit.circuit import CircuitInstruction
    from qiskit.circuit.library import SXGate

    out = qc.copy_empty_like()
    sx = SXGate()
    k = 0
    for inst in qc.data:
        op = inst.operation
        if op.name == "rx" and isinstance(op.params[0], float) and op.params[0] == _HALF_PI:
            out._append(CircuitInstruction(sx, inst.qubits, ()))
            k += 1
        else:
            out._append(inst)
    out.global_phase = qc.global_phase - k * math.pi / 4
    return out, k


def attach_layout(qc: Any, initial: Sequence[int], final: Sequence[int]) -> Any:
    """``qc`` (on physical qubits) with a ``TranspileLayout`` recording that logical qubit ``i`` starts on physical
    qubit ``initial[i]`` and ends on ``final[i]``; returns ``qc``.

    The logical (virtual) circuit has ``len(initial)`` qubits; the other physical qubits are ancillas, which start
    and end in ``|0>`` wherever the routing moved them (they are paired in ascending order: any pairing describes
    the same circuit on inputs whose unused qubits are ``|0>``).
    """
    from qiskit.circuit import AncillaRegister, QuantumRegister
    from qiskit.transpiler import Layout, TranspileLayout

    n, m = qc.num_qubits, len(initial)
    if len(final) != m or len(set(initial)) != m or len(set(final)) != m:
        raise ValueError("attach_layout: initial and final must be equally long lists of distinct qubits")
    virtual = list(QuantumRegister(m, "q"))
    spare = [p for p in range(n) if p not in set(initial)]
    virtual += list(AncillaRegister(len(spare), "ancilla")) if spare else []
    starts = [*initial, *spare]
    ends = [*final, *(p for p in range(n) if p not in set(final))]
    out_qubits = list(qc.qubits)
    qc._layout = TranspileLayout(
        initial_layout=Layout({v: p for v, p in zip(virtual, starts, strict=True)}),
        input_qubit_mapping={v: i for i, v in enumerate(virtual)},
        final_layout=Layout({out_qubits[s]: e for s, e in zip(starts, ends, strict=True)}),
        _input_qubit_count=m,
        _output_qubit_list=out_qubits,
    )
    return qc
