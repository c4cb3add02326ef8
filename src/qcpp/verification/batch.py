"""Many basis inputs through one circuit at once: a sparse state per input, held in flat numpy arrays.

The feasibility checks run a gate list on every input of a set (every feasible assignment, every local input of a
gadget) and look at each input's output on its own. :class:`Batch` holds all of them together: entry ``i`` is the
amplitude ``amps[i]`` of basis state ``keys[i]`` in the output of input ``owners[i]``. A permutation gate moves
keys, a diagonal gate multiplies amplitudes, any other gate splits every entry through its small unitary and
entries of one input on one key are summed; amplitudes below :data:`PRUNE` are dropped. The gate actions come
from :mod:`qcpp.ir.gates` (as in :mod:`qcpp.simulate.sparse`, one input at a time), so neither can disagree
with the IR. Keys are ``int64``: at most :data:`MAX_QUBITS` qubits.

Convention: bit ``i`` of a key is qubit ``i``.

Example:
    >>> from qcpp.ir.gates import cx, h
    >>> b = Batch.of_inputs([0, 1]).run([h(0), cx(0, 1)])
    >>> sorted((int(o), int(k), round(float(abs(a)) ** 2, 6)) for o, k, a in zip(b.owners, b.keys, b.amps))
    [(0, 0, 0.5), (0, 3, 0.5), (1, 0, 0.5), (1, 3, 0.5)]
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from qcpp.ir.gates import GATE_SPECS, Gate, controlled_x_pattern, diagonal, unitary

__all__ = ["MAX_QUBITS", "PRUNE", "Batch"]

MAX_QUBITS = 62
"""Widest register a :class:`Batch` holds (keys are signed 64-bit integers)."""

PRUNE = 1e-14
"""Amplitudes smaller than this in modulus are dropped after each splitting gate."""


def _mask(qubits: Iterable[int]) -> int:
    out = 0
    for q in qubits:
        out |= 1 << q
    return out


def _local(keys: np.ndarray, qubits: Sequence[int]) -> np.ndarray:
    """Each key's bits on ``qubits`` as a local index (qubit ``qubits[j]`` is bit ``j``)."""
    out = np.zeros(len(keys), dtype=np.int64)
    for j, q in enumerate(qubits):
        out |= ((keys >> q) & 1) << j
    return out


@dataclass(frozen=True)
class Batch:
    """Sparse states of many inputs (see the module docstring).

    Attributes:
        owners: per entry, the input it belongs to (``int64``).
        keys: per entry, its basis state (``int64``).
        amps: per entry, its amplitude (``complex128``).
    """

    owners: np.ndarray
    keys: np.ndarray
    amps: np.ndarray

    @classmethod
    def of_inputs(cls, keys: Sequence[int] | np.ndarray) -> Batch:
        """Input ``i`` is the basis state ``keys[i]`` with amplitude 1."""
        k = np.asarray(keys, dtype=np.int64)
        return cls(np.arange(len(k), dtype=np.int64), k.copy(), np.ones(len(k), dtype=np.complex128))

    def __len__(self) -> int:
        return len(self.keys)

    def run(self, gates: Iterable[Gate]) -> Batch:
        """The batch after ``gates`` (bound: no symbolic angle; qubits below :data:`MAX_QUBITS`)."""
        owners, keys, amps = self.owners, self.keys, self.amps
        for gate in gates:
            owners, keys, amps = _apply(owners, keys, amps, gate)
        return Batch(owners, keys, amps)

    def of_input(self, owner: int) -> dict[int, complex]:
        """Input ``owner``'s output as ``{key: amplitude}``."""
        pick = self.owners == owner
        return {int(k): complex(a) for k, a in zip(self.keys[pick], self.amps[pick])}


def _apply(
    owners: np.ndarray, keys: np.ndarray, amps: np.ndarray, gate: Gate
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    name, qubits = gate[0], gate[1]
    if max(qubits) >= MAX_QUBITS:
        raise ValueError(f"qubit {max(qubits)} is beyond the {MAX_QUBITS} a batch holds")
    spec = GATE_SPECS[name]
    if spec.permutation:
        controls, state, target = controlled_x_pattern(gate)
        cmask = _mask(controls)
        cval = _mask(c for c, bit in zip(controls, state, strict=True) if bit == "1")
        hit = (keys & cmask) == cval
        return owners, np.where(hit, keys ^ (1 << target), keys), amps
    if spec.diagonal:
        d = np.asarray(diagonal(gate), dtype=np.complex128)
        return owners, keys, amps * d[_local(keys, qubits)]
    u = np.asarray(unitary(gate), dtype=np.complex128)
    dim = u.shape[0]
    offsets = np.array([_mask(q for j, q in enumerate(qubits) if (o >> j) & 1) for o in range(dim)], dtype=np.int64)
    local = _local(keys, qubits)
    base = keys & ~np.int64(_mask(qubits))
    new_owners, new_keys, new_amps = [], [], []
    for o in range(dim):
        a = u[o, local] * amps
        keep = a != 0
        new_owners.append(owners[keep])
        new_keys.append(base[keep] | offsets[o])
        new_amps.append(a[keep])
    owners, keys, amps = np.concatenate(new_owners), np.concatenate(new_keys), np.concatenate(new_amps)
    if len(local) and (local == local[0]).all():  # every entry had the same bits here: no two outputs coincide
        keep = np.abs(amps) >= PRUNE
        return owners[keep], keys[keep], amps[keep]
    return _combine(owners, keys, amps)


def _combine(owners: np.ndarray, keys: np.ndarray, amps: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Sum the entries of one input on one key; drop the small ones."""
    if len(keys) == 0:
        return owners, keys, amps
    width = int(keys.max()).bit_length()
    if int(owners.max()).bit_length() + width <= 62:  # one int64 sort key: several times faster than lexsort
        order = np.argsort((owners << width) | keys)
    else:
        order = np.lexsort((keys, owners))
    owners, keys, amps = owners[order], keys[order], amps[order]
    start = np.ones(len(keys), dtype=bool)
    start[1:] = (owners[1:] != owners[:-1]) | (keys[1:] != keys[:-1])
    idx = np.flatnonzero(start)
    summed = np.add.reduceat(amps, idx)
    keep = np.abs(summed) >= PRUNE
    return owners[idx][keep], keys[idx][keep], summed[keep]
