"""Noisy simulation of a routed circuit with the noise model of its device file (qiskit-aer, the extra ``noise``).

The check of the ESP model (:func:`qcpp.routing.native.esp`: a shot succeeds only when no gate and no read-out
fails): simulate the routed native circuit under a noise model built from the same device file and read
``P(optimum)``, the probability that the measured data register is an optimal assignment, beside
``ESP x P(optimum, ideal)``.

The noise model (:func:`device_noise_model`), per physical qubit and coupler of the device file:

* every native gate: its reported error ``e`` as an average gate infidelity, realised as in qiskit-aer's device
  models (``qiskit_aer.noise.device.basic_device_gate_errors``): thermal relaxation over the gate's duration (where
  the file has T1, T2 and durations) composed with the depolarising channel that brings the total to ``e``;
  ``rz`` is virtual (error 0, no duration);
* idling: where the file has durations and T1/T2, the circuit is scheduled ASAP (as
  :func:`qcpp.routing.native.duration_s`) and every wait of a qubit, up to the common read-out at the end, gets
  thermal relaxation for that time (:func:`noisy_circuit`);
* read-out: a symmetric bit flip of the file's read-out error on each measured data qubit.

Only the qubits the routed circuit touches are simulated (renumbered ``0..k-1``): up to
:data:`DENSITY_MATRIX_QUBITS` by aer's density-matrix method (``P(optimum)`` exact), up to
:data:`STATEVECTOR_QUBITS` by state-vector trajectories, beyond by its matrix-product-state method, both with
sampled noise (``shots`` trajectories; ``P(optimum)`` then carries a binomial error, :attr:`NoisyResult.stderr`).
Without noise every method gives the exact ``P(optimum)`` of the final state (aer's ``save_probabilities``; no
shots).

What a noisy run costs: each trajectory is a whole state-vector run of every gate and every error channel, so the
time grows as shots x operations x 2^qubits, and the noise takes away what makes ideal sampling cheap (one run,
then sampling the final state). The IBM files' qubits with T2 > T1 make thermal relaxation a Kraus channel that
aer cannot sample as a mixture of unitaries, which costs further passes over the state. The shots run in batches of
at most :data:`SHOT_BATCH`, fewer where a shot is predicted to take seconds (:func:`shot_batch`: a batch every
:data:`PROGRESS_SECONDS` or so; progress is reported after each), the batch from shot ``i`` seeded ``seed + i``: aer
seeds shot ``j`` of a run ``seed_simulator + j``, so the counts are those of one run of every shot. (aer's shot
branching, ``shot_branching_enable``, is not used: it can give different counts on runs with the same seed, and
the counts must follow from the seed.) :func:`noisy_need` predicts the peak
memory and time (:data:`SECONDS_PER_AMPLITUDE_OP` and its siblings; ``benchmarks/noisy_verdict.py --time``
prints the prediction beside the measured time); :func:`qcpp.simulate_noisy` refuses what it predicts to run for
hours.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import Gate
    >>> from qcpp.routing.native import to_native
    >>> from qcpp.routing.sabre import route
    >>> bell = Circuit([("data", 2)], [Section("s", [Gate("h", (0,), (), None), Gate("cx", (0, 1), (), None)])])
    >>> routed = to_native(route(bell, get_device("grid:2x2"), (0, 1)))
    >>> active_qubits(routed)
    (0, 1)
    >>> r = simulate_noisy(routed, [0b00, 0b11], noise=False)  # doctest: +SKIP
    >>> round(r.p_optimum, 9), r.method  # doctest: +SKIP
    (1.0, 'density_matrix')
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass
from typing import Any

from qcpp.errors import MissingExtraError
from qcpp.hardware.device import Device
from qcpp.problem.limits import Need
from qcpp.routing.native import one_qubit_name
from qcpp.routing.routed_circuit import RoutedCircuit

__all__ = [
    "BASE_BYTES",
    "DENSITY_MATRIX_QUBITS",
    "EXTRA",
    "IDEAL_SECONDS_PER_AMPLITUDE_OP",
    "METHODS",
    "MPS_SLOWDOWN",
    "PROGRESS_SECONDS",
    "SECONDS_PER_AMPLITUDE_OP",
    "SHOT_BATCH",
    "STATEVECTOR_QUBITS",
    "NoisyResult",
    "active_qubits",
    "default_method",
    "device_noise_model",
    "noisy_circuit",
    "noisy_need",
    "require_aer",
    "shot_batch",
    "simulate_noisy",
]

EXTRA = "noise"
"""The optional extra that installs qiskit-aer (``pip install 'qcpp[noise]'``)."""

DENSITY_MATRIX_QUBITS = 10
"""Active qubits up to which the density matrix is simulated (4^10 entries)."""

STATEVECTOR_QUBITS = 24
"""Active qubits up to which trajectories run on state vectors (2^24 amplitudes, 256 MiB); beyond, on MPS."""

METHODS = ("density_matrix", "statevector", "matrix_product_state")
"""aer's methods :func:`simulate_noisy` uses."""

PROGRESS_SECONDS = 30.0
"""About how long a batch of shots runs at most when shots are slow (:func:`shot_batch`)."""

SHOT_BATCH = 100
"""Shots per aer run of the sampled methods (progress is reported after each; the run from shot ``i`` is seeded
``seed + i``, so the counts equal one run's)."""

BASE_BYTES = 400_000_000
"""Peak of a process that has imported qiskit and qiskit-aer and built the noise model of a small circuit."""

SECONDS_PER_AMPLITUDE_OP = 6e-9
"""Seconds per amplitude, operation (gate of the routed circuit, or read-out) and shot of the state-vector
trajectories on one core, error channels included: the rate :func:`noisy_need` predicts with; the real rate
depends on the machine and its load (``benchmarks/noisy_verdict.py --time`` prints the prediction beside the
measured time)."""

MPS_SLOWDOWN = 40.0
"""How much slower the matrix-product-state trajectories are taken to run than the state-vector ones: their time
is predicted as the state vector's times this. A rough factor: the bond dimension, not the qubit count, sets
their cost, so it only keeps a prediction from calling a matrix-product-state run cheap."""

IDEAL_SECONDS_PER_AMPLITUDE_OP = 1e-9
"""Seconds per amplitude and operation of one ideal run (``noise=False``: gates fused, no error channels)."""


class NoisyBackendMissing(MissingExtraError):
    """qiskit-aer is not installed."""


def require_aer() -> Any:
    """The ``qiskit_aer`` module, or a one-line error naming the extra that installs it.

    Raises:
        NoisyBackendMissing: qiskit-aer is not installed.
    """
    try:
        import qiskit_aer
    except ImportError:
        raise NoisyBackendMissing(
            f"noisy simulation needs qiskit-aer: pip install 'qcpp[{EXTRA}]' (or pip install qiskit-aer)"
        ) from None
    return qiskit_aer


@dataclass(frozen=True)
class NoisyResult:
    """One noisy simulation.

    Attributes:
        p_optimum: probability that the measured data register is an optimal assignment.
        stderr: its standard error (0 for the exact density-matrix method).
        method: aer's method (:data:`METHODS`).
        qubits: active qubits simulated.
        shots: trajectories sampled (0: exact probabilities).
        noise: whether the device's noise was applied.
    """

    p_optimum: float
    stderr: float
    method: str
    qubits: int
    shots: int
    noise: bool


def active_qubits(routed: RoutedCircuit) -> tuple[int, ...]:
    """The physical qubits the routed circuit acts on or measures, ascending
    (:attr:`~qcpp.routing.routed_circuit.RoutedCircuit.active_qubits`)."""
    return routed.active_qubits


def default_method(qubits: int) -> str:
    """aer's method for ``qubits`` active qubits: density matrix up to :data:`DENSITY_MATRIX_QUBITS`, state
    vectors up to :data:`STATEVECTOR_QUBITS`, matrix product states beyond."""
    if qubits <= DENSITY_MATRIX_QUBITS:
        return "density_matrix"
    return "statevector" if qubits <= STATEVECTOR_QUBITS else "matrix_product_state"


def _workers(shots: int) -> int:
    """Shots aer runs at once: one per core this process may use."""
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    return max(1, min(cores, shots))


def shot_batch(routed: RoutedCircuit, shots: int, method: str) -> int:
    """Shots per aer run: :data:`SHOT_BATCH`, or fewer (a multiple of the cores, at least one per core) where a
    batch is predicted to run longer than :data:`PROGRESS_SECONDS`. The counts do not depend on it (aer seeds each
    shot), only how often progress is reported.

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> from qcpp.ir.circuit import Circuit, Section
        >>> from qcpp.ir.gates import Gate
        >>> from qcpp.routing.routed_circuit import RoutedCircuit
        >>> one = RoutedCircuit(Circuit([("q", 1)], [Section("s", [Gate("x", (0,), (), None)])]),
        ...                     get_device("grid:2x2"), (0,), (0,), 0, (0,))
        >>> shot_batch(one, 1000, "statevector")
        100
    """
    k = len(active_qubits(routed))
    per_shot = SECONDS_PER_AMPLITUDE_OP * (len(routed.circuit) + len(routed.measured)) * 2**k
    if method == "matrix_product_state":
        per_shot *= MPS_SLOWDOWN
    workers = _workers(shots)
    per_core = int(PROGRESS_SECONDS / per_shot) if per_shot > 0 else SHOT_BATCH  # shots one core runs in that time
    return max(workers, min(SHOT_BATCH, per_core * workers))


def noisy_need(routed: RoutedCircuit, *, noise: bool = True, shots: int = 2000, method: str | None = None) -> Need:
    """Predicted peak memory and wall time of :func:`simulate_noisy` (see the module docstring), from the active
    qubits ``k``, the routed circuit's operations ``g`` (gates and read-outs) and the shots: the density matrix
    ``16 * 4^k`` bytes (twice, while its probabilities are read) and ``g * 4^k`` amplitude operations once; state
    vectors ``16 * 2^k`` bytes per shot run in parallel (one per core) and ``shots * g * 2^k`` amplitude operations
    spread over the cores (one run of ``g * 2^k`` without noise); matrix product states as state vectors times
    :data:`MPS_SLOWDOWN`.

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> from qcpp.ir.circuit import Circuit, Section
        >>> from qcpp.ir.gates import Gate
        >>> from qcpp.routing.routed_circuit import RoutedCircuit
        >>> gates = [Gate("x", (q,), (), None) for q in range(22)] * 100
        >>> wide = RoutedCircuit(Circuit([("q", 22)], [Section("s", gates)]), get_device("grid:5x5"),
        ...                      tuple(range(22)), tuple(range(22)), 0, tuple(range(22)))
        >>> noisy_need(wide, shots=2000).seconds > 3600, noisy_need(wide, noise=False).seconds < 60
        (True, True)
    """
    k = len(active_qubits(routed))
    ops = len(routed.circuit) + len(routed.measured)
    chosen = method or default_method(k)
    if chosen == "density_matrix":
        what = f"a noisy simulation of {k} active qubits by density matrix ({ops:,} operations)"
        return Need(what, BASE_BYTES + 32 * 4**k, 1.0 + SECONDS_PER_AMPLITUDE_OP * ops * 4**k)
    if not noise:
        what = f"an ideal simulation of {k} active qubits by {chosen.replace('_', ' ')} ({ops:,} operations)"
        seconds = IDEAL_SECONDS_PER_AMPLITUDE_OP * ops * 2**k
        if chosen == "matrix_product_state":
            return Need(what, BASE_BYTES, 1.0 + seconds * MPS_SLOWDOWN)
        return Need(what, BASE_BYTES + 32 * 2**k, 1.0 + seconds)
    workers = _workers(min(shots, SHOT_BATCH))
    seconds = SECONDS_PER_AMPLITUDE_OP * shots * ops * 2**k / workers
    if chosen == "matrix_product_state":
        seconds *= MPS_SLOWDOWN
    what = (f"{shots:,} noisy trajectories of {k} active qubits by {chosen.replace('_', ' ')} "
            f"({ops:,} operations each)")  # fmt: skip
    if chosen == "matrix_product_state":  # its memory follows the bond dimension: not modelled
        return Need(what, BASE_BYTES, 1.0 + seconds)
    return Need(what, BASE_BYTES + 16 * 2**k * (workers + 1), 1.0 + seconds)


def _times(device: Device) -> tuple[list[float | None], list[float | None]] | None:
    if device.t1_s is None or device.t2_s is None:
        return None
    return list(device.t1_s), list(device.t2_s)


def device_noise_model(device: Device, qubits: Sequence[int], relaxation: bool = True) -> Any:
    """The aer ``NoiseModel`` of ``device`` on physical ``qubits``, renumbered ``0..len(qubits)-1``.

    Args:
        device: the device (its file's errors, durations and T1/T2).
        qubits: physical qubits, in the order of the simulated circuit's qubits.
        relaxation: add thermal relaxation during gates where T1/T2 and durations are known.

    Returns:
        A ``qiskit_aer.noise.NoiseModel`` with errors on ``cz``/``rzz``, ``sx``/``x``/``rx`` and ``measure``.
    """
    require_aer()
    from qiskit.circuit import Parameter
    from qiskit.circuit.library import CZGate, RXGate, RZZGate, SXGate, XGate
    from qiskit.circuit.measure import Measure
    from qiskit.transpiler import InstructionProperties, QubitProperties, Target
    from qiskit_aer.noise import NoiseModel
    from qiskit_aer.noise.device import basic_device_gate_errors, basic_device_readout_errors

    index = {p: i for i, p in enumerate(qubits)}
    times = _times(device) if relaxation else None
    props = [
        QubitProperties(t1=times[0][p], t2=times[1][p]) if times else QubitProperties() for p in qubits
    ]  # fmt: skip
    target = Target(num_qubits=len(qubits), qubit_properties=props)
    durations_1q = dict(device.duration_1q_s) if device.duration_1q_s is not None else {}
    gate_of = {"sx": SXGate(), "x": XGate(), "rx": RXGate(Parameter("theta"))}
    for name, errors in device.error_1q:
        if name not in gate_of:
            continue  # rz: virtual, error 0
        d = durations_1q.get(name)
        target.add_instruction(
            gate_of[name],
            {(index[p],): InstructionProperties(duration=d[p] if d else None, error=errors[p]) for p in qubits},
        )
    two = CZGate() if device.two_qubit_gate == "cz" else RZZGate(Parameter("theta"))
    pairs: dict[tuple[int, int], InstructionProperties] = {}
    for k, (a, b) in enumerate(device.coupling):
        if a in index and b in index:
            d2 = device.duration_2q_s[k] if device.duration_2q_s is not None else None
            prop = InstructionProperties(duration=d2, error=device.error_2q[k])
            pairs[(index[a], index[b])] = pairs[(index[b], index[a])] = prop
    if pairs:
        target.add_instruction(two, pairs)
    target.add_instruction(
        Measure(), {(index[p],): InstructionProperties(error=device.readout_error[p]) for p in qubits}
    )
    model = NoiseModel(basis_gates=["cz", "rzz", "rz", "sx", "x", "rx"])
    for name, qs, error in basic_device_gate_errors(target=target, thermal_relaxation=times is not None):
        model.add_quantum_error(error, name, qs, warnings=False)
    for qs, error in basic_device_readout_errors(target=target):
        model.add_readout_error(error, qs, warnings=False)
    return model


def _gate_duration(device: Device, g: tuple[Any, ...], edge: dict[tuple[int, int], int]) -> float:
    qs = g[1]
    if len(qs) == 2:
        return device.duration_2q_s[edge[qs]] if device.duration_2q_s is not None else 0.0
    if device.duration_1q_s is None:
        return 0.0
    d = dict(device.duration_1q_s).get(one_qubit_name(device, g))
    return d[qs[0]] if d else 0.0


def noisy_circuit(routed: RoutedCircuit, qubits: Sequence[int], idle: bool = True) -> Any:
    """The routed native circuit as a Qiskit circuit on ``qubits`` (renumbered), measured into the data bits.

    Classical bit ``i`` holds logical data qubit ``i`` (:attr:`RoutedCircuit.measured`) read at its final physical
    qubit. With ``idle`` (and T1/T2 and durations in the device file) every wait of a qubit in the ASAP schedule,
    up to the read-out of all at the end, gets a thermal-relaxation channel of that length.

    Raises:
        ValueError: a gate that is not native on the device.
    """
    require_aer()
    from qiskit import QuantumCircuit
    from qiskit_aer.noise import thermal_relaxation_error

    device = routed.device
    index = {p: i for i, p in enumerate(qubits)}
    times = _times(device) if idle and device.duration_2q_s is not None and device.duration_1q_s is not None else None
    edge = device.edge_index()
    qc = QuantumCircuit(len(qubits), len(routed.measured))
    free = [0.0] * len(qubits)

    def wait(i: int, until: float) -> None:
        gap = until - free[i]
        if times is not None and gap > 0:
            p = qubits[i]
            t1, t2 = times[0][p], times[1][p]
            t1 = math.inf if t1 is None else t1
            t2 = min(2 * t1, math.inf if t2 is None else t2)
            qc.append(thermal_relaxation_error(t1, t2, gap).to_instruction(), [i])
        free[i] = max(free[i], until)

    for g in routed.circuit.gates:
        name, qs, params = g[0], g[1], g[2]
        local = [index[q] for q in qs]
        start = max(free[i] for i in local)
        for i in local:
            wait(i, start)
        if len(qs) == 2:
            if name != device.two_qubit_gate:
                raise ValueError(f"noisy_circuit: {name} is not native on {device.name}")
            if name == "cz":
                qc.cz(*local)
            else:
                qc.rzz(float(params[0]), *local)
        elif name == "rz":
            qc.rz(float(params[0]), local[0])
        elif name == "x":
            qc.x(local[0])
        elif name == "rx":
            if one_qubit_name(device, g) == "sx" and abs(float(params[0]) - math.pi / 2) < 1e-12:
                qc.sx(local[0])
            else:
                qc.rx(float(params[0]), local[0])
        else:
            raise ValueError(f"noisy_circuit: {name} is not native on {device.name} (use to_native)")
        end = start + _gate_duration(device, g, edge)
        for i in local:
            free[i] = end
    last = max(free, default=0.0)
    for bit, lq in enumerate(routed.measured):
        i = index[routed.final_layout[lq]]
        wait(i, last)
        qc.measure(i, bit)
    return qc


def simulate_noisy(
    routed: RoutedCircuit,
    optimal: Collection[int],
    *,
    noise: bool = True,
    idle: bool = True,
    shots: int = 2000,
    seed: int = 0,
    method: str | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> NoisyResult:
    """``P(optimum)`` of a routed native circuit under its device's noise (see the module docstring).

    Args:
        routed: a routed circuit in the device's native gates (:func:`qcpp.routing.native.to_native`), angles bound.
        optimal: the optimal assignments as data-register integers (bit ``i`` = data qubit ``i``).
        noise: apply the device's noise (``False``: the ideal circuit's exact ``P(optimum)``, no shots).
        idle: with ``noise``, also the idle relaxation (``False``: gate and read-out errors only).
        shots: trajectories for the sampling methods (with ``noise``).
        seed: aer's seed (the batch of shots from shot ``i`` gets ``seed + i``: the counts of one
            run of every shot).
        method: one of :data:`METHODS` (default: by the active qubit count, :func:`default_method`).
        progress: called as ``progress(done, shots)`` after each run of sampled shots (with ``noise``, on the
            sampling methods; the exact methods run once and report nothing).

    Returns:
        The :class:`NoisyResult`.

    Raises:
        NoisyBackendMissing: qiskit-aer is not installed.
        ValueError: an unknown method, or a gate that is not native.
    """
    require_aer()
    from qiskit_aer import AerSimulator

    qubits = active_qubits(routed)
    n = len(qubits)
    chosen = method or default_method(n)
    if chosen not in METHODS:
        raise ValueError(f"unknown method {chosen!r} (expected one of {', '.join(METHODS)})")
    qc = noisy_circuit(routed, qubits, idle=noise and idle)
    model = device_noise_model(routed.device, qubits) if noise else None
    targets = set(optimal)
    if chosen == "density_matrix" or not noise:  # exact: the final state's probabilities, no sampling
        sim = AerSimulator(method=chosen, noise_model=model, seed_simulator=seed)
        exact = qc.remove_final_measurements(inplace=False)
        bits = [qc.find_bit(instr.qubits[0]).index for instr in qc.data if instr.operation.name == "measure"]
        if chosen == "density_matrix":
            exact.save_density_matrix()
            probs = sim.run(exact).result().data()["density_matrix"].probabilities(bits)
        else:
            exact.save_probabilities(bits)
            probs = sim.run(exact).result().data()["probabilities"]
        if noise and model is not None:
            probs = _apply_readout(probs, [routed.device.readout_error[routed.final_layout[lq]]
                                          for lq in routed.measured])  # fmt: skip
        p = float(sum(probs[k] for k in targets if k < len(probs)))
        return NoisyResult(min(1.0, max(0.0, p)), 0.0, chosen, n, 0, noise)
    sim = AerSimulator(method=chosen, noise_model=model)
    hits = 0
    size = shot_batch(routed, shots, chosen)
    for start in range(0, shots, size):
        batch = min(size, shots - start)
        counts = sim.run(qc, shots=batch, seed_simulator=seed + start).result().get_counts()
        hits += sum(c for key, c in counts.items() if int(key.replace(" ", ""), 2) in targets)
        if progress is not None:
            progress(start + batch, shots)
    p = hits / shots
    return NoisyResult(p, math.sqrt(max(p * (1 - p), 1.0 / shots) / shots), chosen, n, shots, noise)


def _apply_readout(probs: Any, errors: Sequence[float]) -> Any:
    """Apply independent symmetric read-out flips (bit ``i`` flips with ``errors[i]``) to a distribution."""
    import numpy as np

    p = np.asarray(probs, dtype=float).reshape([2] * len(errors))  # axis 0 = the highest bit
    for i, e in enumerate(errors):
        axis = len(errors) - 1 - i
        p = (1 - e) * p + e * np.flip(p, axis=axis)
    return p.reshape(-1)
