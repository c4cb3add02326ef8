"""Sparse basis-state simulator: the state is a ``dict {basis index: amplitude}``.

It runs circuits on hundreds of qubits as long as few amplitudes are non-zero (e.g. the
classical reversible parts of a circuit, or checking an mcx ladder on every basis input).
Permutation gates move keys, diagonal gates multiply amplitudes, and every other gate splits
each amplitude through its small unitary. Gate actions come from :mod:`qcpp.ir.gates`
(:func:`~qcpp.ir.gates.controlled_x_pattern`, :func:`~qcpp.ir.gates.diagonal`,
:func:`~qcpp.ir.gates.unitary`), exactly as in the dense simulator. Amplitudes with
``|a| < 1e-14`` are pruned after each splitting gate.

Convention: bit ``i`` of a basis index is qubit ``i`` (qubit 0 is the least significant).

>>> from qcpp.ir.circuit import Circuit, Section
>>> from qcpp.ir.gates import cx, x
>>> c = Circuit([("data", 300)], [Section("s", [x(0), cx(0, 299)])])
>>> simulate_sparse(c, 0) == {basis_from_bits([1] + [0] * 298 + [1]): 1}
True
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

from qcpp.ir.circuit import Circuit
from qcpp.ir.gates import GATE_SPECS, Gate, controlled_x_pattern, diagonal, unitary
from qcpp.simulate.statevector import bound_circuit

__all__ = ["PRUNE_TOLERANCE", "basis_from_bits", "bits_of", "simulate_sparse"]

PRUNE_TOLERANCE = 1e-14
"""Amplitudes smaller than this in modulus are dropped."""


def basis_from_bits(bits: Sequence[int | bool]) -> int:
    """Basis index whose qubit ``i`` is ``bits[i]``.

    Args:
        bits: one truth value per qubit, qubit 0 first.

    >>> basis_from_bits([1, 0, 1])
    5
    """
    index = 0
    for i, b in enumerate(bits):
        if b:
            index |= 1 << i
    return index


def bits_of(index: int, qubits: Iterable[int]) -> tuple[int, ...]:
    """Values of ``qubits`` in basis state ``index``.

    Args:
        index: basis index.
        qubits: qubit indices.

    Returns:
        One 0/1 per qubit, in the given order.

    >>> bits_of(5, [0, 1, 2])
    (1, 0, 1)
    """
    return tuple((index >> q) & 1 for q in qubits)


def _spread(local: int, qubits: Sequence[int]) -> int:
    out = 0
    for j, q in enumerate(qubits):
        if (local >> j) & 1:
            out |= 1 << q
    return out


def _local(index: int, qubits: Sequence[int]) -> int:
    out = 0
    for j, q in enumerate(qubits):
        out |= ((index >> q) & 1) << j
    return out


def _apply(state: dict[int, complex], gate: Gate) -> dict[int, complex]:
    name, qubits = gate[0], gate[1]
    spec = GATE_SPECS[name]
    if spec.permutation:
        controls, ctrl_state, target = controlled_x_pattern(gate)
        cmask = _spread((1 << len(controls)) - 1, controls)
        cval = _spread(int(ctrl_state[::-1], 2) if controls else 0, controls)
        tbit = 1 << target
        return {(k ^ tbit if (k & cmask) == cval else k): a for k, a in state.items()}
    if spec.diagonal:
        d = diagonal(gate).tolist()
        return {k: a * d[_local(k, qubits)] for k, a in state.items()}
    u = unitary(gate)
    dim = u.shape[0]
    spread = [_spread(o, qubits) for o in range(dim)]
    mask = spread[-1]
    # columns[l]: the non-zero (output offset, matrix entry) pairs of column l
    columns = [[(spread[o], complex(u[o, col])) for o in range(dim) if u[o, col] != 0] for col in range(dim)]
    out: dict[int, complex] = {}
    get = out.get
    for k, a in state.items():
        base = k & ~mask
        for off, m in columns[_local(k, qubits)]:
            key = base | off
            out[key] = get(key, 0) + m * a
    return {k: a for k, a in out.items() if abs(a) >= PRUNE_TOLERANCE}


def simulate_sparse(
    circuit: Circuit,
    initial: int | Mapping[int, complex] = 0,
    bindings: Mapping[str, float] | None = None,
) -> dict[int, complex]:
    """Run ``circuit`` on a sparse state.

    Args:
        circuit: any circuit (any gate level, any number of qubits).
        initial: a basis index, or a mapping ``{basis index: amplitude}``.
        bindings: symbol values, applied with :meth:`Circuit.bind` first.

    Returns:
        The final state as ``{basis index: amplitude}`` (pruned below 1e-14).

    Raises:
        UnboundParameterError: some symbol has no value.

    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import h
    >>> {k: round(abs(a) ** 2, 12) for k, a in simulate_sparse(Circuit([("d", 1)], [Section("s", [h(0)])])).items()}
    {0: 0.5, 1: 0.5}
    """
    circuit = bound_circuit(circuit, bindings)
    n = circuit.num_qubits
    if isinstance(initial, int):
        state: dict[int, complex] = {initial: 1.0 + 0j}
    else:
        state = {int(k): complex(a) for k, a in initial.items()}
    if any(k < 0 or k >> n for k in state):
        raise ValueError(f"initial basis index out of range for {n} qubits")
    for gate in circuit.gates:
        state = _apply(state, gate)
    return state
