"""Dense numpy statevector simulator for any :class:`~qcpp.ir.circuit.Circuit`.

Convention (Qiskit's ``Statevector``): bit ``i`` of a basis index is qubit ``i``, so qubit 0
is the least significant bit. Gate actions come from :mod:`qcpp.ir.gates`: permutation
gates through :func:`~qcpp.ir.gates.controlled_x_pattern` (a slice swap), diagonal gates
through :func:`~qcpp.ir.gates.diagonal` (a broadcast multiply), all others through
:func:`~qcpp.ir.gates.unitary` (a tensor contraction on the gate's axes). The sparse
simulator uses the same three functions, so the two cannot silently disagree. Runs of gates
confined to one or two qubits are multiplied together first (from the same matrices) when
the product is diagonal or acts on one qubit, e.g. a lowered ``rzz`` (cx, rz, cx) costs one
pass over the state instead of three.

Practical limits: ~26 qubits for :func:`simulate_statevector` (1 GiB of amplitudes),
~12 qubits for :func:`circuit_unitary`.

>>> from qcpp.ir.circuit import Circuit, Section
>>> from qcpp.ir.gates import cx, h
>>> bell = Circuit([("data", 2)], [Section("s", [h(0), cx(0, 1)])])
>>> np.round(simulate_statevector(bell), 6).tolist()
[(0.707107+0j), 0j, 0j, (0.707107+0j)]
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from qcpp.ir.angles import UnboundParameterError
from qcpp.ir.circuit import Circuit
from qcpp.ir.gates import GATE_SPECS, Gate, controlled_x_pattern, diagonal, unitary

__all__ = ["MAX_STATEVECTOR_QUBITS", "MAX_UNITARY_QUBITS", "circuit_unitary", "simulate_statevector"]

MAX_STATEVECTOR_QUBITS = 26
"""The dense simulator holds ``2**n`` complex amplitudes: 26 qubits are 1 GiB (callers refuse beyond it)."""
MAX_UNITARY_QUBITS = 14
"""Refuse :func:`circuit_unitary` beyond this many qubits (4**14 amplitudes = 4 GiB)."""


def bound_circuit(circuit: Circuit, bindings: Mapping[str, float] | None, context: str = "simulation") -> Circuit:
    """``circuit`` with ``bindings`` applied; raises :class:`UnboundParameterError` if a symbol is left."""
    if bindings:
        circuit = circuit.bind(bindings)
    if circuit.symbols:
        raise UnboundParameterError(circuit.symbols, context)
    return circuit


def _apply_permutation(psi: np.ndarray, gate: Gate, n: int) -> np.ndarray:
    controls, state, target = controlled_x_pattern(gate)
    idx: list[int | slice] = [slice(None)] * (n + 1)
    for c, bit in zip(controls, state, strict=True):
        idx[n - 1 - c] = 1 if bit == "1" else 0
    ax = n - 1 - target
    idx[ax] = 0
    i0 = tuple(idx)
    idx[ax] = 1
    i1 = tuple(idx)
    tmp = psi[i0].copy()
    psi[i0] = psi[i1]
    psi[i1] = tmp
    return psi


def _apply_diagonal(psi: np.ndarray, qubits: Sequence[int], d: np.ndarray, n: int) -> np.ndarray:
    k = len(qubits)
    if k == 1:
        view = psi.reshape(-1, 2, psi.size >> (n - qubits[0]))
        d0, d1 = d.tolist()
        if d0 != 1:
            view[:, 0, :] *= d0
        view[:, 1, :] *= d1
        return psi
    dt = d.reshape((2,) * k)  # axis a <-> local bit k-1-a <-> qubits[k-1-a]
    order = sorted(range(k), key=lambda j: -qubits[j])  # local bits in psi-axis order
    dt = dt.transpose([k - 1 - j for j in order])
    shape = [1] * (n + 1)
    for j in order:
        shape[n - 1 - qubits[j]] = 2
    psi *= dt.reshape(shape)
    return psi


def _apply_matrix(psi: np.ndarray, qubits: Sequence[int], u: np.ndarray, n: int) -> np.ndarray:
    k = len(qubits)
    if k == 1:
        # view psi as (A, 2, C), the gate's axis in the middle (C includes the batch axis)
        c = psi.size >> (n - qubits[0])
        view = psi.reshape(-1, 2, c)
        if c >= 16:  # long contiguous rows: one batched GEMM
            return np.matmul(u, view).reshape(psi.shape)
        # short rows: matmul would loop over tiny blocks; update the two halves in place
        a0, a1 = view[:, 0, :], view[:, 1, :]
        top = u[0, 0] * a0
        top += u[0, 1] * a1
        a1 *= u[1, 1]
        a1 += u[1, 0] * a0
        a0[...] = top
        return psi
    ut = u.reshape((2,) * (2 * k))
    axes = [n - 1 - qubits[j] for j in range(k - 1, -1, -1)]  # psi axes of local bits k-1..0
    out = np.tensordot(ut, psi, axes=(list(range(k, 2 * k)), axes))
    return np.ascontiguousarray(np.moveaxis(out, list(range(k)), axes))


def _apply(psi: np.ndarray, gate: Gate, n: int) -> np.ndarray:
    """Apply ``gate`` to ``psi`` of shape ``(2,)*n + (batch,)``; axis of qubit q is n-1-q."""
    spec = GATE_SPECS[gate[0]]
    if spec.permutation:
        return _apply_permutation(psi, gate, n)
    if spec.diagonal:
        return _apply_diagonal(psi, gate[1], diagonal(gate), n)
    return _apply_matrix(psi, gate[1], unitary(gate), n)


_SWAP = np.eye(4)[[0, 2, 1, 3]]


def _embed(gate: Gate, block: tuple[int, ...]) -> np.ndarray:
    """Matrix of ``gate`` on the qubits ``block`` (one or two; block[0] is the low bit)."""
    u = unitary(gate)
    qubits = gate[1]
    if len(block) == 1:
        return u
    if len(qubits) == 2:
        return u if qubits == block else _SWAP @ u @ _SWAP
    return np.kron(np.eye(2), u) if qubits[0] == block[0] else np.kron(u, np.eye(2))


def _flush(psi: np.ndarray, block: tuple[int, ...], gates: list[Gate], n: int) -> np.ndarray:
    """Apply a run of gates confined to one or two qubits, fused when that saves passes."""
    if len(gates) == 1:
        return _apply(psi, gates[0], n)
    m = _embed(gates[0], block)
    for g in gates[1:]:
        m = _embed(g, block) @ m
    d = np.diag(m)
    if np.count_nonzero(m) == np.count_nonzero(d):  # e.g. cx rz cx: one multiply, not 3 passes
        return _apply_diagonal(psi, block, d.copy(), n)
    if len(block) == 1:
        return _apply_matrix(psi, block, m, n)
    # a dense 4x4 costs more than a few cheap gates: apply them one by one
    for g in gates:
        psi = _apply(psi, g, n)
    return psi


def _run(circuit: Circuit, psi: np.ndarray) -> np.ndarray:
    """Apply all gates, fusing runs of gates that stay on the same one or two qubits."""
    n = circuit.num_qubits
    block: tuple[int, ...] = ()
    pending: list[Gate] = []
    for gate in circuit.gates:
        qubits = gate[1]
        if len(qubits) <= 2:
            union = block + tuple(q for q in qubits if q not in block)
            if len(union) <= 2:
                block = union
                pending.append(gate)
                continue
        if pending:
            psi = _flush(psi, block, pending, n)
        if len(qubits) <= 2:
            block, pending = tuple(qubits), [gate]
        else:
            block, pending = (), []
            psi = _apply(psi, gate, n)
    if pending:
        psi = _flush(psi, block, pending, n)
    return psi


def simulate_statevector(
    circuit: Circuit,
    initial: int | np.ndarray = 0,
    bindings: Mapping[str, float] | None = None,
) -> np.ndarray:
    """Final statevector of ``circuit``.

    Args:
        circuit: any circuit (any gate level), at most ~26 qubits.
        initial: a basis-state index, or a vector of length ``2**num_qubits``.
        bindings: symbol values, applied with :meth:`Circuit.bind` first.

    Returns:
        Complex vector of length ``2**num_qubits`` (index bit i = qubit i).

    Raises:
        UnboundParameterError: some symbol has no value.

    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import x
    >>> simulate_statevector(Circuit([("data", 2)], [Section("s", [x(1)])])).argmax()
    np.int64(2)
    """
    circuit = bound_circuit(circuit, bindings)
    n = circuit.num_qubits
    dim = 1 << n
    if isinstance(initial, (int, np.integer)):
        if not 0 <= initial < dim:
            raise ValueError(f"basis index {initial} out of range for {n} qubits")
        psi = np.zeros(dim, dtype=complex)
        psi[int(initial)] = 1.0
    else:
        psi = np.array(initial, dtype=complex).reshape(-1)
        if psi.shape != (dim,):
            raise ValueError(f"initial state has {psi.size} amplitudes, expected {dim}")
    psi = _run(circuit, psi.reshape((2,) * n + (1,)))
    return psi.reshape(dim)


def circuit_unitary(circuit: Circuit, bindings: Mapping[str, float] | None = None) -> np.ndarray:
    """Matrix of the whole circuit (column ``j`` = image of basis state ``j``).

    Args:
        circuit: a circuit with at most :data:`MAX_UNITARY_QUBITS` qubits (~12 is fast).
        bindings: symbol values.

    Returns:
        ``2**n x 2**n`` complex array.

    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cz, h
    >>> u = circuit_unitary(Circuit([("data", 2)], [Section("s", [h(1), cz(0, 1), h(1)])]))
    >>> np.round(u.real, 12).astype(int).tolist()  # = cx(0, 1)
    [[1, 0, 0, 0], [0, 0, 0, 1], [0, 0, 1, 0], [0, 1, 0, 0]]
    """
    circuit = bound_circuit(circuit, bindings)
    n = circuit.num_qubits
    if n > MAX_UNITARY_QUBITS:
        raise ValueError(f"{n} qubits is too many for a dense unitary")
    dim = 1 << n
    psi = np.eye(dim, dtype=complex).reshape((2,) * n + (dim,))
    return _run(circuit, psi).reshape(dim, dim)
