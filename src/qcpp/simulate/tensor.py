"""Tensor-network simulation of compiled circuits (quimb + cotengra): amplitudes, projector probabilities, samples.

For circuits too wide for the dense simulator (20-40 qubits), one basis state at a time. :func:`to_quimb` converts
any :class:`~qcpp.ir.circuit.Circuit` into a ``quimb.tensor.Circuit``; :class:`TensorCircuit` wraps one bound
circuit (:meth:`~TensorCircuit.amplitude` ``<y|U|x>``, :meth:`~TensorCircuit.probability` of fixed values on some
qubits, :meth:`~TensorCircuit.sample`); :class:`MPSCircuit` answers the same from a matrix product state.

Conventions:

* A basis state is an ``int`` (bit ``i`` = qubit ``i``, as :mod:`qcpp.simulate.statevector`), a string whose
  character ``i`` is qubit ``i`` (quimb's order), or a sequence of 0/1 per qubit, qubit 0 first.
* Gates with a quimb native of the same matrix and qubit order map to it; ``mcx`` with more than two controls is
  quimb's controlled ``X`` (negative controls conjugated by ``X``); ``sbf``, ``csbf`` and mixed-polarity ``mcx`` up
  to :data:`RAW_MCX_MAX_QUBITS` qubits are raw matrices from :func:`qcpp.ir.gates.unitary` applied on the reversed
  qubit list (quimb reads a raw gate's first qubit as the most significant, ours as the least).
* Gates are added uncontracted (``gate_contract=False``: much faster to build, same amplitudes); quimb's
  controlled gates need a split mode and get ``'auto-split-gate'``.
* Amplitudes: ``U|x>`` is simplified once per bound circuit, then each amplitude fixes the outputs and contracts
  with a path from the shared :func:`~qcpp.simulate.contraction_paths.path_optimizer`, keyed by the network's
  structure, so one path search serves every bit string (and later processes, through its on-disk cache).
* Probabilities contract the closed network ``bra | ket`` with the fixed outputs on both sides (simplifying the
  open ket first turns outputs into hyper-indices and gives wrong norms). Every contraction is rehearsed first and
  refused beyond ``max_width`` (:class:`ContractionTooWideError`) rather than exhausting memory.
* Everything is contracted in complex128 (quimb's complex64 marginals are too coarse for validation).

Example:
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx, h, x
    >>> ghz = Circuit([("data", 3)], [Section("s", [h(0), cx(0, 1), cx(1, 2)])])
    >>> tc = TensorCircuit(ghz)
    >>> [round(abs(tc.amplitude(b)) ** 2, 12) for b in ("000", "111", "010")]
    [0.5, 0.5, 0.0]
    >>> round(tc.probability({0: 1}), 12), tc.num_qubits
    (0.5, 3)
    >>> round(TensorCircuit(ghz, psi0_bits="100").amplitude(0b111).real, 12)  # <111| U |q0=1>: (|000> - |111>)/√2
    -0.707106781187
"""

from __future__ import annotations

import copy
import math
import time
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from qcpp.errors import QcppError
from qcpp.io.caches import use_writable_numba_cache
from qcpp.ir.circuit import Circuit
from qcpp.ir.gates import Gate, controlled_x_pattern, unitary
from qcpp.simulate.contraction_paths import path_optimizer
from qcpp.simulate.statevector import bound_circuit

use_writable_numba_cache()  # quimb decorates its cache=True numba kernels when imported
with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # cotengra (which quimb imports) warns when the optional kahypar is missing
    import quimb.tensor as qtn

__all__ = [
    "DEFAULT_MAX_WIDTH",
    "RAW_MCX_MAX_QUBITS",
    "BasisState",
    "ContractionInfo",
    "ContractionTooWideError",
    "MPSCircuit",
    "TensorCircuit",
    "contract_sliced",
    "state_bits",
    "to_quimb",
]

BasisState = int | str | Sequence[int]
"""A computational basis state: ``int`` (bit i = qubit i), ``str`` (character i = qubit i) or 0/1 per qubit."""

DEFAULT_MAX_WIDTH = 27
"""Refuse contractions whose largest intermediate tensor has more than ``2**27`` entries (2 GiB of complex128)."""

RAW_MCX_MAX_QUBITS = 8
"""An ``mcx`` with mixed control polarity on at most this many qubits becomes one raw ``2^k x 2^k`` matrix."""

_NATIVE = {n: n.upper() for n in ("x", "h", "t", "tdg", "s", "sdg", "rx", "ry", "rz", "cx", "cz", "crz", "cry")}
_NATIVE |= {"rzz": "RZZ", "ccx": "CCX"}  # quimb gates of the same matrix and qubit order
_SIMPLIFY = "ADCRS"
_ATOL = 1e-12
_SIMPLIFY_DIAGONAL = "ADR"
"""Simplification with a 2^k-entry diagonal block in the network (column reduction and splitting on it are slow)."""


class ContractionTooWideError(QcppError):
    """A contraction would need an intermediate tensor larger than the allowed width (``2**width`` entries)."""


@dataclass(frozen=True)
class ContractionInfo:
    """Size of one contraction, found without running it.

    Attributes:
        width: log2 of the number of entries of the largest intermediate tensor (cotengra's ``W``).
        log10_flops: log10 of the estimated floating point operations (cotengra's ``C``).
        num_tensors: Tensors left after simplification.
        search_seconds: Wall time of simplification and path search (near 0 when the path was cached).
    """

    width: float
    log10_flops: float
    num_tensors: int
    search_seconds: float


# ------------------------------------------------------------------------------------------------ conversion


def state_bits(state: BasisState, num_qubits: int) -> tuple[int, ...]:
    """A basis state as one 0/1 per qubit, qubit 0 first.

    Args:
        state: ``int`` (bit i = qubit i), ``str`` of ``0``/``1`` (character i = qubit i) or a 0/1 sequence.
        num_qubits: Number of qubits.

    Returns:
        Tuple of ``num_qubits`` ints.

    Raises:
        ValueError: out of range, wrong length or not 0/1.

    Example:
        >>> state_bits(6, 3), state_bits("011", 3), state_bits([0, 1, 1], 3)
        ((0, 1, 1), (0, 1, 1), (0, 1, 1))
    """
    if isinstance(state, (int, np.integer)) and not isinstance(state, bool):
        k = int(state)
        if not 0 <= k < (1 << num_qubits):
            raise ValueError(f"basis index {k} out of range for {num_qubits} qubits")
        return tuple((k >> i) & 1 for i in range(num_qubits))
    bits = tuple(int(c) for c in state) if isinstance(state, str) else tuple(int(b) for b in state)
    if len(bits) != num_qubits:
        raise ValueError(f"basis state has {len(bits)} bits, expected {num_qubits}")
    if any(b not in (0, 1) for b in bits):
        raise ValueError(f"basis state bits must be 0 or 1, got {state!r}")
    return bits


def _apply(qc: Any, gate: Gate, split: str | None = "auto-split-gate") -> None:
    """Append ``gate`` to a quimb circuit; ``split`` is the contraction mode of controlled gates (``None``: the
    circuit's own, as for ``CircuitMPS``)."""
    name, qubits = gate[0], gate[1]
    native = _NATIVE.get(name)
    if native is not None:
        qc.apply_gate(native, *(float(p) for p in gate[2]), *qubits)
        return
    if name == "mcx":
        controls, state, target = controlled_x_pattern(gate)
        if "0" in state and len(qubits) <= RAW_MCX_MAX_QUBITS:
            qc.apply_gate_raw(unitary(gate), tuple(reversed(qubits)))
            return
        negative = [c for c, b in zip(controls, state) if b == "0"]
        for c in negative:
            qc.apply_gate("X", c)
        opts = {} if split is None else {"contract": split}
        qc.apply_gate("X", target, controls=list(controls), **opts)
        for c in negative:
            qc.apply_gate("X", c)
        return
    # sbf, csbf (and anything else in the spec table): the raw matrix, first listed qubit least significant
    qc.apply_gate_raw(unitary(gate), tuple(reversed(qubits)))


def to_quimb(
    circuit: Circuit,
    bindings: Mapping[str, float] | None = None,
    psi0_bits: BasisState | None = None,
) -> qtn.Circuit:
    """Convert a circuit into a quimb tensor-network circuit started from a basis state.

    Args:
        circuit: Any circuit (lowered basis or high-level gates).
        bindings: Symbol values, applied with :meth:`Circuit.bind` first.
        psi0_bits: Initial basis state (see :func:`state_bits`); default all zeros.

    Returns:
        A ``quimb.tensor.Circuit`` (qubit ``i`` is quimb's qubit ``i``; complex128 tensors).

    Raises:
        UnboundParameterError: if some symbol has no value.

    Example:
        >>> from qcpp.ir.circuit import Circuit, Section
        >>> from qcpp.ir.gates import mcx
        >>> c = Circuit([("data", 4)], [Section("s", [mcx([0, 1, 2], 3, "101")])])
        >>> qc = to_quimb(c, psi0_bits="1010")
        >>> round(float(abs(qc.amplitude("1011"))), 12)
        1.0
    """
    circuit = bound_circuit(circuit, bindings, "tensor-network simulation")
    n = circuit.num_qubits
    if n < 1:
        raise ValueError("the circuit has no qubits")
    bits = state_bits(psi0_bits if psi0_bits is not None else 0, n)
    psi0 = qtn.MPS_computational_state("".join(map(str, bits)), dtype="complex128")
    qc = qtn.Circuit(n, psi0=psi0, gate_contract=False)
    for gate in circuit.gates:
        _apply(qc, gate)
    return qc


# ------------------------------------------------------------------------------------------------ ancilla-clean blocks

MAX_BLOCK_DATA_QUBITS = 11
"""Largest block (data qubits) :func:`collapse_ancilla_blocks` turns into one dense operator (2^22 entries)."""


def _block_network(gates: Sequence[Gate], data: Sequence[int], ancillas: Sequence[int]) -> qtn.TensorNetwork:
    """A block's unitary as a tensor network on local qubits (``data`` first), its ancillas fixed to |0> on both
    sides; open indices ``k{i}`` (out) and ``b{i}`` (in) for data qubit ``i``."""
    local = {q: i for i, q in enumerate([*data, *ancillas])}
    qc = qtn.Circuit(len(local), gate_contract=False)
    for g in gates:
        _apply(qc, g._replace(qubits=tuple(local[q] for q in g[1])))
    uni = qc.get_uni()
    uni.isel_({f"{side}{i}": 0 for i in range(len(data), len(local)) for side in "kb"})
    return uni


def _block_operator(gates: Sequence[Gate], data: Sequence[int], ancillas: Sequence[int]) -> np.ndarray:
    """``(I ⊗ <0|) B (I ⊗ |0>)`` of a block of gates: the matrix on ``data`` (first qubit most significant)."""
    uni = _block_network(gates, data, ancillas)
    k = len(data)
    uni.astype_("complex128")
    outs, ins = [f"k{i}" for i in range(k)], [f"b{i}" for i in range(k)]
    return _contract_small(uni, [*outs, *ins]).to_dense(outs, ins)


def _contract_small(tn: Any, output_inds: Sequence[str]) -> Any:
    """``tn`` contracted to one tensor on a greedy path (small blocks: no search)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t = tn.contract(all, output_inds=output_inds, optimize="greedy")
    return t if isinstance(t, qtn.Tensor) else qtn.Tensor(np.asarray(t), inds=())


MAX_DIAGONAL_DATA_QUBITS = 24
"""Largest block (data qubits) :func:`collapse_ancilla_blocks` keeps as one diagonal (2^24 phases), e.g. the
phase separator's arithmetic on path-length registers, which computes into ``logic`` ancillas and uncomputes."""


def _block_diagonal(gates: Sequence[Gate], data: Sequence[int], ancillas: Sequence[int]) -> np.ndarray:
    """The diagonal ``<x, 0| B |x, 0>`` of a block over every data basis state ``x`` (first qubit most significant).

    Contracted with each data qubit's input and output joined by a COPY tensor, so only ``2^k`` entries are kept.
    If every entry has modulus 1 the block maps each ``|x, 0>`` to a phase times itself (``B`` is unitary): it is
    diagonal on the data and returns its ancillas to |0>.
    """
    uni = _block_network(gates, data, ancillas)
    k = len(data)
    for i in range(k):
        uni |= qtn.COPY_tensor(2, (f"k{i}", f"b{i}", f"x{i}"))
    uni.astype_("complex128")
    outs = [f"x{i}" for i in range(k)]
    uni.full_simplify_(seq=_SIMPLIFY, output_inds=outs, atol=_ATOL)
    return np.asarray(_contract_small(uni, outs).to_dense(outs)).reshape(-1)


def _operator_leak(op: np.ndarray) -> float:
    """``||T^dagger T - I||_2`` of a matrix, or of a diagonal given as its vector."""
    if op.ndim == 1:
        return float(np.max(np.abs(np.abs(op) ** 2 - 1.0), initial=0.0))
    return float(np.linalg.norm(op.conj().T @ op - np.eye(op.shape[0]), 2))


def collapse_ancilla_blocks(
    circuit: Circuit, ancillas: Sequence[int], atol: float = 1e-9, max_block_data_qubits: int = MAX_BLOCK_DATA_QUBITS
) -> list[tuple[tuple[int, ...], Gate | np.ndarray]] | None:
    """The circuit as operators on its data qubits alone, every block that uses ancillas contracted to one matrix.

    A section that touches an ancilla becomes ``T = (I ⊗ <0|) S (I ⊗ |0>)`` on the data qubits it touches (the
    following sections added until ``T`` is unitary). A unitary ``T`` proves that no amplitude leaks into dirty
    ancillas, so on inputs with clean ancillas the circuit equals the product of these operators, exactly, and
    the compute/uncompute pairs vanish before any path search. A block on more than
    ``max_block_data_qubits`` data qubits is kept as its diagonal ``<x, 0|S|x, 0>``, accepted only if every
    entry has modulus 1.

    Args:
        circuit: A bound circuit whose ancillas start in |0>.
        ancillas: The ancilla qubits (the rest are data, renumbered ``0..`` in order).
        atol: Tolerance of the unitarity check.
        max_block_data_qubits: Largest block kept as a dense operator (:data:`MAX_BLOCK_DATA_QUBITS`).

    Returns:
        ``[(data qubits, gate, matrix or diagonal vector), ...]`` in time order (qubits renumbered; a matrix or
        vector has its first qubit most significant, as quimb's raw gates), or ``None`` if some block would exceed
        :data:`MAX_DIAGONAL_DATA_QUBITS`, or ``max_block_data_qubits`` without being diagonal.

    Example:
        >>> from qcpp.ir.circuit import Circuit, Section
        >>> from qcpp.ir.gates import ccx, crx, h
        >>> c = Circuit([("d", 3), ("a", 1)], [Section("s", [h(0), ccx(0, 1, 3), crx(0.5, 3, 2), ccx(0, 1, 3)])])
        >>> [(qs, getattr(op, "shape", None)) for qs, op in collapse_ancilla_blocks(c, [3])]
        [((0, 1, 2), (8, 8))]
    """
    anc = set(ancillas)
    data_index = {q: i for i, q in enumerate(q for q in range(circuit.num_qubits) if q not in anc)}
    out: list[tuple[tuple[int, ...], Gate | np.ndarray]] = []
    sections = list(circuit.sections)
    i = 0
    while i < len(sections):
        gates = list(sections[i].gates)
        i += 1
        if not any(q in anc for g in gates for q in g[1]):
            out.extend((tuple(data_index[q] for q in g[1]), g) for g in gates)
            continue
        while True:
            touched = sorted({q for g in gates for q in g[1]})
            data = [q for q in touched if q not in anc]
            used = [q for q in touched if q in anc]
            if len(data) <= max_block_data_qubits:
                t = _block_operator(gates, data, used)
            elif len(data) <= MAX_DIAGONAL_DATA_QUBITS:
                t = _block_diagonal(gates, data, used)
            else:
                return None
            if _operator_leak(t) <= atol:
                break
            if i == len(sections):
                return None
            gates.extend(sections[i].gates)
            i += 1
        out.append((tuple(data_index[q] for q in data), t))
    return out


# ------------------------------------------------------------------------------------------------ simulation


def _projector(psi: Any, fix: Mapping[str, int], num_qubits: int) -> Any:
    """The closed network ``bra | ket`` of ``<psi| P |psi>``, ``P`` fixing the site indices ``fix`` on both sides
    (the other outputs joined; fixing before simplifying keeps the norms right)."""
    ket = qtn.TensorNetwork([t.copy() for t in psi.tensors])
    ket.isel_(fix)
    keep = {psi.site_ind(q) for q in range(num_qubits)} - set(fix)
    bra = ket.conj()
    bra.reindex_({ix: qtn.rand_uuid() for ix in bra.ind_map if ix not in keep})
    return qtn.TensorNetwork([*bra.tensors, *ket.tensors], virtual=True)


class TensorCircuit:
    """One bound circuit as a tensor network, with cached simplification and shared contraction paths.

    Args:
        bindings: Symbol values (the circuit must end up fully bound).
        psi0_bits: Initial basis state; default all zeros.
        optimizer: A cotengra path optimizer; default
            :func:`~qcpp.simulate.contraction_paths.path_optimizer` of ``cache_dir``.
        cache_dir: Path cache directory for the default optimizer (default
            :func:`~qcpp.simulate.contraction_paths.default_cache_dir`).
        max_width: Largest allowed contraction width (log2 of entries), see :class:`ContractionTooWideError`.
        client: A ``dask.distributed.Client`` (see :func:`qcpp.simulate.cluster.dask_client`): a contraction
            wider than ``max_width`` is then sliced by cotengra into pieces of at most ``2**max_width`` entries and
            the slices run on the cluster (:func:`contract_sliced`) instead of raising
            :class:`ContractionTooWideError`.
        ancillas: Qubits that start in |0> and that the circuit returns to |0> block by block (``logic``,
            ``work``): amplitudes are then contracted on the data qubits alone, each block that uses ancillas
            contracted first into one verified-unitary operator (:func:`collapse_ancilla_blocks`); an amplitude
            with an ancilla bit set is exactly 0. If a block cannot be collapsed, the full network is used.
        max_block_data_qubits: Widest ancilla block collapsed into a dense operator; wider ones are kept as their
            diagonal (:func:`collapse_ancilla_blocks`).

    Example:
        >>> from qcpp.ir.circuit import Circuit, Section
        >>> from qcpp.ir.gates import h, rz
        >>> tc = TensorCircuit(Circuit([("q", 1)], [Section("s", [h(0), rz(0.5, 0)])]))
        >>> np.round(tc.amplitudes([0, 1]) * np.sqrt(2), 6).tolist()
        [(0.968912-0.247404j), (0.968912+0.247404j)]
    """

    def __init__(
        self,
        circuit: Circuit,
        bindings: Mapping[str, float] | None = None,
        psi0_bits: BasisState | None = None,
        *,
        optimizer: Any = None,
        cache_dir: str | Path | None = None,
        max_width: float = DEFAULT_MAX_WIDTH,
        client: Any = None,
        ancillas: Sequence[int] = (),
        max_block_data_qubits: int = MAX_BLOCK_DATA_QUBITS,
    ) -> None:
        self.circuit = bound_circuit(circuit, bindings, "tensor-network simulation")
        self.max_block_data_qubits = max_block_data_qubits
        self.num_qubits = self.circuit.num_qubits
        self.psi0_bits = state_bits(psi0_bits if psi0_bits is not None else 0, self.num_qubits)
        self.quimb = to_quimb(self.circuit, psi0_bits=self.psi0_bits)
        self.optimizer = optimizer if optimizer is not None else path_optimizer(cache_dir)
        self.max_width = max_width
        self.client = client
        self.dask_contractions = 0  # contractions sliced and run on the dask cluster (the rest ran in-process)
        self.ancillas = tuple(sorted({int(q) for q in ancillas}))
        self._base: Any = None
        self._data_qubits: tuple[int, ...] | None = None  # set when the ancilla blocks were collapsed
        self.block_leak: float | None = None
        """After an amplitude on collapsed blocks: the sum over blocks of ``||T^dagger T - I||_2``, a bound on the
        probability that the circuit leaves some ancilla dirty (``None``: not collapsed)."""

    # -- networks ------------------------------------------------------------------------------------------

    def _collapsed_circuit(self) -> Any:
        """The data-only quimb circuit of :func:`collapse_ancilla_blocks`, or ``None``."""
        if not self.ancillas or any(self.psi0_bits[q] for q in self.ancillas):
            return None
        ops = collapse_ancilla_blocks(self.circuit, self.ancillas, max_block_data_qubits=self.max_block_data_qubits)
        if ops is None:
            return None
        anc = set(self.ancillas)
        data = tuple(q for q in range(self.num_qubits) if q not in anc)
        psi0 = qtn.MPS_computational_state("".join(str(self.psi0_bits[q]) for q in data), dtype="complex128")
        qc = qtn.Circuit(len(data), psi0=psi0, gate_contract=False)
        for qubits, op in ops:
            if isinstance(op, np.ndarray) and op.ndim == 1:
                # a diagonal stays one tensor on the current site indices (hyperedges), never a 2^k x 2^k matrix
                inds = [qc._psi.site_ind(q) for q in qubits]
                qc._psi |= qtn.Tensor(op.reshape((2,) * len(qubits)), inds=inds, tags=["DIAGONAL"])
            elif isinstance(op, np.ndarray):
                qc.apply_gate_raw(op, qubits)
            else:
                _apply(qc, op._replace(qubits=qubits))
        self._data_qubits = data
        self.block_leak = sum(_operator_leak(op) for _, op in ops if isinstance(op, np.ndarray))
        return qc

    def _base_state(self) -> Any:
        """``U|psi0>`` simplified once with every output index kept (copy before modifying)."""
        if self._base is None:
            qc = self._collapsed_circuit()
            seq = _SIMPLIFY_DIAGONAL if qc is not None and "DIAGONAL" in qc.psi.tag_map else _SIMPLIFY
            self._base = (qc if qc is not None else self.quimb).get_psi_simplified(seq=seq, atol=_ATOL)
        return self._base

    def _amplitude_network(self, state: BasisState) -> Any:
        """The closed network of ``<state|U|psi0>``, or ``None`` when it is exactly 0 (an ancilla bit set)."""
        bits = state_bits(state, self.num_qubits)
        base = self._base_state()
        if self._data_qubits is not None:
            if any(bits[q] for q in self.ancillas):
                return None
            bits = tuple(bits[q] for q in self._data_qubits)
        tn = base.copy()
        tn.isel_({tn.site_ind(i): b for i, b in enumerate(bits)})
        tn.astype_("complex128")
        return tn

    def _projector_network(self, fixed: Mapping[int, int]) -> Any:
        """Closed network ``<psi| P |psi>`` with ``P`` fixing ``qubit -> value``, simplified."""
        fix = self._check_fixed(fixed)
        psi = self.quimb.psi
        tn = _projector(psi, {psi.site_ind(q): b for q, b in fix.items()}, self.num_qubits)
        tn.full_simplify_(seq=_SIMPLIFY, atol=_ATOL, output_inds=(), equalize_norms=True)
        tn.astype_("complex128")
        return tn

    def _check_fixed(self, fixed: Mapping[int, int]) -> dict[int, int]:
        out: dict[int, int] = {}
        for q, b in fixed.items():
            q, b = int(q), int(b)
            if not 0 <= q < self.num_qubits:
                raise ValueError(f"qubit {q} out of range for {self.num_qubits} qubits")
            if b not in (0, 1):
                raise ValueError(f"qubit {q}: value must be 0 or 1, got {b}")
            out[q] = b
        return out

    def _tree(self, tn: Any, output_inds: Sequence[str] = ()) -> tuple[Any, ContractionInfo]:
        t0 = time.perf_counter()
        if tn.num_tensors <= 1:
            info = ContractionInfo(0.0, 0.0, tn.num_tensors, time.perf_counter() - t0)
            return None, info
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "Couldn't import kahypar" at every new search
            tree = tn.contraction_tree(output_inds=tuple(output_inds), optimize=self.optimizer)
        info = ContractionInfo(
            float(tree.contraction_width()),
            float(math.log10(max(float(tree.contraction_cost()), 1.0))),
            tn.num_tensors,
            time.perf_counter() - t0,
        )
        return tree, info

    def _contract(self, tn: Any) -> complex:
        if tn is None:
            return 0j
        tree, info = self._tree(tn)
        if info.width > self.max_width and self.client is not None:
            self.dask_contractions += 1
            return contract_sliced(tn, tree, target_size=2 ** int(self.max_width), client=self.client)
        if info.width > self.max_width:
            raise ContractionTooWideError(
                f"contraction width {info.width:g} exceeds max_width {self.max_width:g} "
                f"({self.num_qubits} qubits, {len(self.circuit)} gates): use a smaller circuit or fewer qubits"
            )
        value = tn.contract(all, output_inds=(), optimize=tree) if tree is not None else tn.contract(all)
        if isinstance(value, qtn.Tensor):
            value = value.data
        return complex(np.asarray(value).reshape(()))

    # -- amplitudes ----------------------------------------------------------------------------------------

    def amplitude(self, state: BasisState) -> complex:
        """``<state| U |psi0>``.

        Args:
            state: A basis state (see :func:`state_bits`).

        Raises:
            ContractionTooWideError: if the contraction exceeds ``max_width``.
        """
        return self._contract(self._amplitude_network(state))

    def amplitudes(self, states: Iterable[BasisState], open_qubits: Sequence[int] = ()) -> np.ndarray:
        """:meth:`amplitude` of each state (the contraction path is found once and reused).

        Args:
            open_qubits: Contract with these qubits' output indices left open: one contraction then gives the
                ``2**len(open_qubits)`` amplitudes of all states that agree on the other qubits (e.g. the last
                robot's data qubits: one contraction per assignment of the other robots). A group whose open
                contraction would exceed ``max_width`` falls back to one contraction per state.

        Returns:
            complex128 array, one entry per state.

        Example:
            >>> from qcpp.ir.circuit import Circuit, Section
            >>> from qcpp.ir.gates import cx, h
            >>> tc = TensorCircuit(Circuit([("q", 3)], [Section("s", [h(0), cx(0, 1), h(2)])]))
            >>> bool(np.allclose(tc.amplitudes([0, 3, 7, 4], open_qubits=[2]), tc.amplitudes([0, 3, 7, 4])))
            True
        """
        states = list(states)
        if not open_qubits:
            return np.array([self.amplitude(st) for st in states], dtype=np.complex128)
        opened = [int(q) for q in open_qubits]
        if set(opened) & set(self.ancillas) or len(set(opened)) != len(opened):
            raise ValueError(f"open_qubits must be distinct non-ancilla qubits, got {opened}")
        out = np.zeros(len(states), dtype=np.complex128)
        groups: dict[tuple[int, ...], list[tuple[int, tuple[int, ...]]]] = {}
        for k, st in enumerate(states):
            bits = state_bits(st, self.num_qubits)
            key = tuple(0 if q in opened else b for q, b in enumerate(bits))
            groups.setdefault(key, []).append((k, bits))
        for key, members in groups.items():
            block = self._open_block(key, opened)
            for k, bits in members:
                if block is None:
                    out[k] = self.amplitude(bits)
                elif not isinstance(block, str):
                    out[k] = block[tuple(bits[q] for q in opened)]
        return out

    def _open_block(self, key: tuple[int, ...], opened: list[int]) -> Any:
        """Amplitudes over the open qubits with the others fixed to ``key``: an array, ``'zero'`` (an ancilla bit
        is set), or ``None`` (too wide: contract state by state)."""
        base = self._base_state()
        where = {q: q for q in range(self.num_qubits)}
        if self._data_qubits is not None:
            if any(key[q] for q in self.ancillas):
                return "zero"
            where = {q: i for i, q in enumerate(self._data_qubits)}
        tn = base.copy()
        inds = [tn.site_ind(where[q]) for q in opened]
        # fix the other outputs by attaching basis vectors, not by selecting and simplifying again: the network
        # then has the same structure for every key and one cached path serves them all
        for q, b in enumerate(key):
            if q in where and q not in opened:
                tn.add_tensor(qtn.Tensor(np.eye(2, dtype=np.complex128)[b], inds=(tn.site_ind(where[q]),)))
        tn.astype_("complex128")
        tree, info = self._tree(tn, inds)
        if info.width > self.max_width:
            return None
        value = tn.contract(all, output_inds=inds, optimize=tree) if tree is not None else tn.contract(all)
        if isinstance(value, qtn.Tensor):
            return value.transpose(*inds).data
        return np.asarray(value).reshape((2,) * len(inds))

    def probability(self, fixed: Mapping[int, int]) -> float:
        """Probability that measuring the qubits in ``fixed`` gives those values, ``<psi| P |psi>``.

        Args:
            fixed: ``qubit -> 0 or 1``, e.g. ``{q: 0 for q in ancillas}`` for clean ancillas.

        Returns:
            The probability (real part of the contracted value).

        Raises:
            ContractionTooWideError: if the contraction exceeds ``max_width``.
        """
        return self._contract(self._projector_network(fixed)).real

    def zero_probability(self, qubits: Iterable[int]) -> float:
        """Probability that all of ``qubits`` are |0> (:meth:`probability` with zeros)."""
        return self.probability({q: 0 for q in qubits})

    def sample(self, shots: int, seed: int | None = None, group_size: int = 8) -> np.ndarray:
        """Measure every qubit ``shots`` times (quimb's lightcone marginal chain; small circuits).

        Args:
            shots: Number of samples (>= 0).
            seed: Seed for numpy's generator.
            group_size: Qubits per marginal in quimb's chain.

        Returns:
            uint8 array of shape ``(shots, num_qubits)``, column ``i`` = qubit ``i``.
        """
        if shots < 0:
            raise ValueError(f"shots must be >= 0, got {shots}")
        out = np.zeros((shots, self.num_qubits), dtype=np.uint8)
        if shots == 0:
            return out
        gen = self.quimb.sample(
            shots,
            seed=seed,
            group_size=group_size,
            optimize=self.optimizer,
            dtype="complex128",
            simplify_atol=_ATOL,
        )
        for k, b in enumerate(gen):
            out[k] = [int(c) for c in b]
        return out


# ------------------------------------------------------------------------------------------------ slicing, dask


def _slice_sum(tree: Any, arrays: Sequence[Any], start: int, stop: int) -> Any:
    """Sum of slices ``start .. stop-1`` of a sliced contraction tree (runs on a dask worker)."""
    # a private copy: the tree caches per-contraction state, and threads of one worker would share the object
    tree = copy.deepcopy(tree)
    total = None
    for i in range(start, stop):
        part = tree.contract_slice(arrays, i)
        total = part if total is None else total + part
    return total


def contract_sliced(
    tn: Any,
    tree: Any = None,
    *,
    target_size: int | None = None,
    target_slices: int | None = None,
    client: Any = None,
    chunk: int | None = None,
) -> complex:
    """Contract a closed tensor network to a scalar by cotengra slicing, the slices on a dask cluster if given.

    Every slice (some indices fixed) is an independent, smaller contraction and the result is their sum. With a
    ``dask.distributed.Client`` the arrays are scattered once and the slices submitted in chunks; without one
    they run in this process.

    Args:
        tn: A quimb ``TensorNetwork`` with no open index.
        tree: Its cotengra ``ContractionTree`` (default: found with
            :func:`~qcpp.simulate.contraction_paths.path_optimizer`).
        target_size: Largest intermediate tensor (entries) of a slice.
        target_slices: Or: at least this many slices.
        client: A ``dask.distributed.Client`` (``None``: in-process).
        chunk: Slices per dask task.

    Example:
        >>> import quimb.tensor as qtn
        >>> tn = qtn.TensorNetwork([qtn.rand_tensor([2, 2], ["a", "b"], seed=1), qtn.rand_tensor([2, 2], ["b", "a"])])
        >>> abs(contract_sliced(tn, target_slices=2) - tn.contract(all)) < 1e-12
        True
    """
    if tree is None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            tree = tn.contraction_tree(output_inds=(), optimize=path_optimizer())
    if target_size is None and target_slices is None:
        raise ValueError("give target_size or target_slices")
    sliced = tree.slice(target_size=target_size, target_slices=target_slices)
    arrays = [np.asarray(t.data, dtype=np.complex128) for t in tn.tensors]
    n = sliced.nslices
    if client is None:
        value = _slice_sum(sliced, arrays, 0, n)
    else:
        threads = max(1, sum(client.nthreads().values()))
        step = chunk or max(1, math.ceil(n / (4 * threads)))
        # hash=False: content keys can merge two different tensors into one (a wrong amplitude)
        remote = client.scatter(arrays, broadcast=True, hash=False)
        futures = [
            client.submit(_slice_sum, sliced, remote, i, min(i + step, n), pure=False) for i in range(0, n, step)
        ]
        value = sum(client.gather(futures))
    return complex(np.asarray(value).reshape(()))


class MPSCircuit:
    """A circuit simulated gate by gate as a matrix product state (quimb's ``CircuitMPS``), then queried.

    The whole state is kept, so every amplitude and every projector probability is cheap afterwards; the cost is
    in the bond dimension, which stays small while few basis states carry the amplitude. Singular values are truncated
    below ``cutoff`` (quimb's default relative squared-sum rule), so results are exact up to about ``cutoff`` per gate:
    an independent check of the exact contractions of :class:`TensorCircuit`, not a replacement.

    Args:
        bindings: Symbol values.
        psi0_bits: Initial basis state; default all zeros.
        layout: Site order, ``layout[site] = qubit`` (a permutation); default the identity. Putting qubits that
            interact with everything (ancillas) in the middle of the chain shortens the swap chains of non-local
            gates.
        cutoff: Singular value cutoff.
        bond_limit: Stop with :class:`ContractionTooWideError` once a bond exceeds this (the run time grows with
            the cube of the bond).

    Attributes:
        max_bond: Largest bond dimension seen after any gate.
        seconds: Wall time of the simulation.

    Example:
        >>> from qcpp.ir.circuit import Circuit, Section
        >>> from qcpp.ir.gates import cx, h
        >>> m = MPSCircuit(Circuit([("data", 3)], [Section("s", [h(0), cx(0, 2)])]), layout=[2, 0, 1])
        >>> round(abs(m.amplitude(0b101)) ** 2, 12), round(m.probability({1: 0}), 12), m.max_bond
        (0.5, 1.0, 2)
    """

    def __init__(
        self,
        circuit: Circuit,
        bindings: Mapping[str, float] | None = None,
        psi0_bits: BasisState | None = None,
        *,
        layout: Sequence[int] | None = None,
        cutoff: float = 1e-13,
        bond_limit: int | None = None,
    ) -> None:
        t0 = time.perf_counter()
        self.circuit = bound_circuit(circuit, bindings, "tensor-network simulation")
        n = self.num_qubits = self.circuit.num_qubits
        order = list(range(n)) if layout is None else [int(q) for q in layout]
        if sorted(order) != list(range(n)):
            raise ValueError(f"layout must be a permutation of range({n})")
        self.layout = tuple(order)
        self._site = {q: i for i, q in enumerate(order)}
        bits = state_bits(psi0_bits if psi0_bits is not None else 0, n)
        psi0 = qtn.MPS_computational_state("".join(str(bits[q]) for q in order), dtype="complex128")
        self.quimb = qtn.CircuitMPS(n, psi0=psi0, cutoff=cutoff, max_bond=None)
        self.max_bond = 1
        site = self._site
        for gate in self.circuit.gates:
            _apply(self.quimb, gate._replace(qubits=tuple(site[q] for q in gate[1])), split=None)
            if len(gate[1]) > 1:
                self.max_bond = max(self.max_bond, self.quimb.psi.max_bond())
                if bond_limit is not None and self.max_bond > bond_limit:
                    raise ContractionTooWideError(
                        f"MPS bond dimension {self.max_bond} exceeds bond_limit {bond_limit} "
                        f"(after {time.perf_counter() - t0:.0f} s)"
                    )
        self.seconds = time.perf_counter() - t0

    def _site_bits(self, state: BasisState) -> str:
        bits = state_bits(state, self.num_qubits)
        return "".join(str(bits[q]) for q in self.layout)

    def amplitude(self, state: BasisState) -> complex:
        """``<state| U |psi0>`` from the MPS."""
        return complex(self.quimb.amplitude(self._site_bits(state), optimize="greedy"))

    def amplitudes(self, states: Iterable[BasisState]) -> np.ndarray:
        """:meth:`amplitude` of each state, complex128 array."""
        return np.array([self.amplitude(s) for s in states], dtype=np.complex128)

    def probability(self, fixed: Mapping[int, int]) -> float:
        """Probability that the qubits in ``fixed`` (``qubit -> 0/1``) are measured with those values."""
        psi = self.quimb.psi
        fix: dict[str, int] = {}
        for q, b in fixed.items():
            if int(b) not in (0, 1) or int(q) not in self._site:
                raise ValueError(f"bad fixed value {q!r}: {b!r}")
            fix[psi.site_ind(self._site[int(q)])] = int(b)
        value = _projector(psi, fix, self.num_qubits).contract(all, output_inds=(), optimize="greedy")
        return float(np.real(value))

    def zero_probability(self, qubits: Iterable[int]) -> float:
        """Probability that all of ``qubits`` are |0>."""
        return self.probability({q: 0 for q in qubits})

