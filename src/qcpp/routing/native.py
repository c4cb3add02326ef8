"""A routed circuit in the device's native gates, and its figures of merit: estimated success probability, duration.

:func:`to_native` rewrites a routed circuit into the device's native gates (exact up to a global phase):
``cx = h cz h`` and ``cz = rz(pi/2) rz(pi/2) rzz(-pi/2)`` (trapped ions); ``h = rz(pi/2) sx rz(pi/2)`` where
``sx`` is written ``rx(pi/2)`` (the IR has no ``sx``; the device's ``sx`` error and duration are charged for
it); ``t, tdg, s, sdg`` are ``rz`` of their angle; ``x`` stays ``x`` where native (``rx(pi)`` otherwise).

:func:`esp` is the estimated success probability: the product of ``(1 - error)`` over every gate of the
native circuit (per qubit / per coupling, from the device data) and of ``(1 - readout error)`` over the
measured qubits (the data qubits at their final positions), summed as logs (:func:`log_esp`: a circuit of
millions of gates has an ESP far below the smallest double, which :func:`esp` returns as ``0.0``). Idle
decoherence, crosstalk and leakage are not modelled there. :func:`duration_s` is the ASAP schedule's length with
the device's per-gate durations plus one readout, or ``None`` where the device publishes no durations.

:func:`esp_idle` multiplies :func:`esp` by an idle-decoherence factor (:data:`IDLE_MODEL`): in the same ASAP
schedule, a qubit's idle time ``t`` is the time between the start of its first timed gate and the end of its last
(for a measured qubit: the end of the schedule, when all are read out together) that its own gates do not fill.
Each idle qubit contributes the average gate fidelity of the amplitude- and phase-damping (thermal relaxation at
zero temperature) channel over ``t``, ``F = (3 + exp(-t/T1) + 2 exp(-t/T2)) / 6`` with ``T2`` capped at ``2 T1``
(the physical limit; some snapshots report more): the figure gate errors are reported in (``1 - F``, randomised
benchmarking), so gate and idle factors multiply alike. Before its first gate a qubit is in ``|0>`` (no decay);
after its last an ancilla is back in ``|0>``. Virtual gates (``rz``, duration 0) do not start or end the window.
Qubits whose T1 or T2 is unknown contribute 1; a device without durations or coherence times has no idle figure.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx
    >>> from qcpp.routing.sabre import route
    >>> routed = route(Circuit([("data", 2)], [Section("s", [cx(0, 1)])]), get_device("grid:1x2"), (0, 1))
    >>> sorted(to_native(routed).circuit.count_ops().items())
    [('cz', 1), ('rx', 2), ('rz', 4)]
    >>> 0 < esp(to_native(routed)) < 1
    True
    >>> esp_idle(to_native(routed)) is None  # the grid family's source publishes no T1 / T2
    True
"""

from __future__ import annotations

import math
from functools import cache

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cz, rx, rz, rzz
from qcpp.routing.routed_circuit import RoutedCircuit

__all__ = [
    "IDLE_MODEL", "RUNNABLE_ESP", "duration_s", "esp", "esp_figures", "esp_idle", "idle_fidelity", "idle_times_s",
    "log10_figure", "log_esp", "log_esp_idle", "native_gates", "one_qubit_name", "to_native",
]

IDLE_MODEL = (
    "idle decoherence: per qubit, the average fidelity (3 + exp(-t/T1) + 2 exp(-t/T2)) / 6 of amplitude and phase "
    "damping over its idle time t (T2 <= 2 T1) in the ASAP schedule with the device's gate durations, from its "
    "first to its last timed gate (measured qubits: to the readout at the end)"
)
"""The idle-decoherence model of :func:`esp_idle` (module docs)."""

RUNNABLE_ESP = 0.1
"""The verdict's bar (docs/guide/hardware.md): a routed circuit whose ESP is at least this (one shot in ten without
an error) is worth running; below it, noise dominates the samples."""

# --- native gates ------------------------------------------------------------------------------------------
_HALF_PI = math.pi / 2
_RZ_OF = {"t": math.pi / 4, "tdg": -math.pi / 4, "s": _HALF_PI, "sdg": -_HALF_PI}


def native_gates(g: Gate, twoq: str, native_x: bool) -> list[Gate]:
    """The native gates of one routed gate (module docs), given the device's two-qubit gate and whether ``x`` is
    native."""
    name, qs = g[0], g[1]
    if name == "cx":
        c, t = qs
        return [*native_gates(Gate("h", (t,), (), None), twoq, native_x), *_native_cz(c, t, twoq),
                *native_gates(Gate("h", (t,), (), None), twoq, native_x)]  # fmt: skip
    if name == "cz":
        return _native_cz(*qs, twoq)
    if name == "h":
        (q,) = qs
        return [rz(_HALF_PI, q), rx(_HALF_PI, q), rz(_HALF_PI, q)]
    if name in _RZ_OF:
        return [rz(_RZ_OF[name], qs[0])]
    if name == "x":
        return [g] if native_x else [rx(math.pi, qs[0])]
    if name in ("rz", "rx"):
        return [g]
    raise ValueError(f"to_native: no native form for gate {name!r}")


def _native_cz(a: int, b: int, twoq: str) -> list[Gate]:
    if twoq == "cz":
        return [cz(a, b)]
    return [rz(_HALF_PI, a), rz(_HALF_PI, b), rzz(-_HALF_PI, a, b)]  # CZ up to a global phase


def to_native(routed: RoutedCircuit) -> RoutedCircuit:
    """The routed circuit in the device's native gates (equal up to a global phase); see the module docs."""
    twoq = routed.device.two_qubit_gate
    native_x = "x" in routed.device.native_gates
    forms: dict[Gate, list[Gate]] = {}  # a routed circuit repeats its fixed gates (cx, h, ...): each form once
    sections = []
    for sec in routed.circuit.sections:
        gates: list[Gate] = []
        for g in sec.gates:
            if g[2]:  # angles: equal as numbers is not equal as written (an Angle, -0.0), so not memoised
                gates += native_gates(g, twoq, native_x)
                continue
            form = forms.get(g)
            if form is None:
                form = forms[g] = native_gates(g, twoq, native_x)
            gates += form
        sections.append(Section(sec.name, gates))
    circuit = Circuit(routed.circuit.registers, sections)
    return RoutedCircuit(circuit, routed.device, routed.initial_layout, routed.final_layout, routed.swaps,
                         routed.measured)  # fmt: skip


# --- figures of merit --------------------------------------------------------------------------------------
def one_qubit_name(device: Device, g: Gate) -> str:
    """The device gate a one-qubit IR gate stands for (``rx(+-pi/2)`` is ``sx`` where the device has ``sx``)."""
    name = g[0]
    if name == "rx" and "sx" in device.native_gates:
        return "sx"
    return name


def esp(routed: RoutedCircuit) -> float:
    """Estimated success probability of a native routed circuit (model in the module docs): ``exp`` of
    :func:`log_esp`, so ``0.0`` where the product is below the smallest double (about ``1e-308``, reached by a few
    hundred thousand gates); :func:`log_esp` keeps the figure there.

    Returns:
        ``prod (1 - e_gate) * prod_{measured} (1 - e_readout)``.

    Raises:
        ValueError: a gate the device has no error figure for.
    """
    return math.exp(log_esp(routed))


def log_esp(routed: RoutedCircuit) -> float:
    """Natural log of :func:`esp`, summed gate by gate in log space: finite however long the circuit (``-inf`` only
    where a gate or readout used has error 1).

    Returns:
        ``sum log(1 - e_gate) + sum_{measured} log(1 - e_readout)``.

    Raises:
        ValueError: a gate the device has no error figure for.
    """
    device = routed.device
    two_name = device.two_qubit_gate
    two, one = _log_fidelities(device)
    log = 0.0
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            if g[0] != two_name:
                raise ValueError(f"esp: {g[0]} is not native on {device.name} (use to_native)")
            log += two[qs]
        else:
            logs = one.get(g[0])
            if logs is None:
                raise ValueError(f"esp: {one_qubit_name(device, g)} is not native on {device.name} (use to_native)")
            log += logs[qs[0]]
    for lq in routed.measured:
        log += math.log1p(-device.readout_error[routed.final_layout[lq]])
    return log


@cache
def _log_fidelities(device: Device) -> tuple[dict[tuple[int, int], float], dict[str, tuple[float, ...]]]:
    """``log(1 - e)`` per coupler (both orders) and per one-qubit IR gate name and qubit (``-inf`` where
    ``e >= 1``; ``rx`` under the device gate :func:`one_qubit_name` gives it), the terms :func:`esp` adds. Pure
    memo: ``_log_fidelities.cache_clear()`` empties it."""

    def log1m(e: float) -> float:
        return math.log1p(-e) if e < 1 else -math.inf

    two = {pair: log1m(device.error_2q[i]) for pair, i in device.edge_index().items()}
    one = {name: tuple(log1m(e) for e in errors) for name, errors in device.error_1q}
    native_rx = one_qubit_name(device, rx(math.pi / 2, 0))
    if native_rx != "rx":
        one.pop("rx", None)  # rx is written as native_rx there: its own figure (if any) is not the one used
        if native_rx in one:
            one["rx"] = one[native_rx]
    return two, one


def duration_s(routed: RoutedCircuit) -> float | None:
    """ASAP schedule length of a native routed circuit plus one readout, in seconds (``None``: no durations)."""
    device = routed.device
    if device.duration_1q_s is None or device.duration_2q_s is None or device.readout_duration_s is None:
        return None
    one, two = _durations(device)
    d1 = dict(device.duration_1q_s)
    free = [0.0] * device.num_qubits
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            a, b = qs
            fa, fb = free[a], free[b]
            start = fb if fb > fa else fa  # max(fa, fb)
            free[a] = free[b] = start + two[qs]
        else:
            q = qs[0]
            durations = one.get(g[0])
            if durations is None:
                durations = d1[one_qubit_name(device, g)]  # a name without durations: raises
            d = durations[q]
            if d != 0:  # x + 0.0 is x: no time here is -0.0 (sums from +0.0)
                free[q] += d
    readout = max((device.readout_duration_s[routed.final_layout[lq]] for lq in routed.measured), default=0.0)
    return max(free, default=0.0) + readout


@cache
def _durations(device: Device) -> tuple[dict[str, tuple[float, ...]], dict[tuple[int, int], float]]:
    """Per one-qubit IR gate name its durations per qubit (``rx`` under the device gate :func:`one_qubit_name` gives
    it; a name the device has no durations for is missing), and per coupler (both orders) its two-qubit gate's
    duration: the figures :func:`duration_s` and :func:`_schedule` read. Pure memo; the device has durations."""
    d1 = dict(device.duration_1q_s or ())
    one = {name: d1[one_qubit_name(device, Gate(name, (0,), (), None))] for name in (*d1, "rx")
           if one_qubit_name(device, Gate(name, (0,), (), None)) in d1}  # fmt: skip
    durations_2q = device.duration_2q_s or ()
    two = {pair: durations_2q[i] for pair, i in device.edge_index().items()}
    return one, two


def _schedule(routed: RoutedCircuit) -> tuple[list[float], list[float | None], list[float]] | None:
    """ASAP schedule of a native routed circuit: per qubit the end of its last gate, the start of its first timed
    gate (``None``: none) and the time its own gates fill; ``None`` where the device publishes no durations."""
    device = routed.device
    if device.duration_1q_s is None or device.duration_2q_s is None:
        return None
    one, two = _durations(device)
    d1 = dict(device.duration_1q_s)
    n = device.num_qubits
    free, first, busy = [0.0] * n, [None] * n, [0.0] * n
    first_time: list[float | None] = first  # type: ignore[assignment]
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            a, b = qs
            fa, fb = free[a], free[b]
            start = fb if fb > fa else fa  # max(fa, fb)
            d = two[qs]
            free[a] = free[b] = start + d
            if d > 0:
                busy[a] += d
                if first_time[a] is None:
                    first_time[a] = start
                busy[b] += d
                if first_time[b] is None:
                    first_time[b] = start
        else:
            q = qs[0]
            durations = one.get(g[0])
            if durations is None:
                durations = d1[one_qubit_name(device, g)]  # a name without durations: raises
            d = durations[q]
            if d > 0:
                if first_time[q] is None:
                    first_time[q] = free[q]
                busy[q] += d
                free[q] += d
            elif d != 0:  # x + 0.0 is x: no time here is -0.0 (sums from +0.0)
                free[q] += d
    return free, first_time, busy


def idle_times_s(routed: RoutedCircuit) -> tuple[float, ...] | None:
    """Per physical qubit, its idle time in seconds in the ASAP schedule (module docs; ``None``: no durations).

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> from qcpp.ir.circuit import Circuit, Section
        >>> from qcpp.ir.gates import cz, rx
        >>> dev = get_device("ibm_fez")
        >>> c = Circuit([("q", dev.num_qubits)], [Section("s", [rx(1.0, 0), cz(0, 1), rx(1.0, 1), cz(0, 1)])])
        >>> t = idle_times_s(RoutedCircuit(c, dev, (0, 1), (0, 1), 0, (0,)))
        >>> math.isclose(t[0], dict(dev.duration_1q_s)["sx"][1])  # qubit 0 waits while qubit 1 has its sx
        True
        >>> t[1], t[2]  # qubit 1 is never idle between its first and last gate; qubit 2 has none
        (0.0, 0.0)
    """
    sched = _schedule(routed)
    if sched is None:
        return None
    free, first, busy = sched
    end = max(free, default=0.0)
    last = list(free)
    for lq in routed.measured:
        last[routed.final_layout[lq]] = end
    return tuple(0.0 if f is None else max(0.0, last[q] - f - busy[q]) for q, f in enumerate(first))


def idle_fidelity(t: float, t1: float, t2: float) -> float:
    """Average fidelity of amplitude and phase damping over ``t`` seconds (:data:`IDLE_MODEL`), ``T2 <= 2 T1``.

    >>> idle_fidelity(0.0, 1e-4, 1e-4), round(idle_fidelity(1e-4, 1e-4, 1e-4), 6)
    (1.0, 0.68394)
    """
    t2 = min(t2, 2 * t1)
    return (3 + math.exp(-t / t1) + 2 * math.exp(-t / t2)) / 6


def log10_figure(log: float | None) -> float | None:
    """A natural log (of an ESP) as a base-10 one for a row or a summary, rounded to 6 decimals (``None``: none, or
    ``-inf``, an ESP of exactly 0 that JSON cannot write as a number).

    >>> log10_figure(math.log(2.3e-226)), log10_figure(None), log10_figure(-math.inf)
    (-225.638272, None, None)
    """
    return None if log is None or math.isinf(log) else round(log / math.log(10), 6)


def esp_figures(routed: RoutedCircuit) -> dict[str, float | None]:
    """The ESP of a native routed circuit as a row or summary reports it: ``esp``, ``esp_idle`` (``None`` without
    T1 / T2) and both as base-10 logs (``log10_esp``, ``log10_esp_idle``: :func:`log10_figure`), from one pass
    each in log space.

    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx
    >>> from qcpp.routing.sabre import route
    >>> routed = to_native(route(Circuit([("data", 2)], [Section("s", [cx(0, 1)])]), get_device("ibm_fez"), (0, 1)))
    >>> f = esp_figures(routed)
    >>> f["esp"] == esp(routed), f["esp_idle"] == esp_idle(routed), f["log10_esp"] == log10_figure(log_esp(routed))
    (True, True, True)
    """
    gate_log = log_esp(routed)
    idle_log = log_esp_idle(routed, gate_log=gate_log)
    return {
        "esp": math.exp(gate_log),
        "esp_idle": None if idle_log is None else math.exp(idle_log),
        "log10_esp": log10_figure(gate_log),
        "log10_esp_idle": log10_figure(idle_log),
    }


def esp_idle(routed: RoutedCircuit, gate_esp: float | None = None) -> float | None:
    """:func:`esp` times the idle-decoherence factor of :data:`IDLE_MODEL` (``None``: the device has no durations or
    no T1 / T2); ``exp`` of :func:`log_esp_idle`.

    Args:
        routed: A native routed circuit.
        gate_esp: ``esp(routed)`` where the caller has it already (a pass over every gate saved); default: computed.
            Where it underflowed to ``0.0`` the gates' log is computed again, so the result is as
            :func:`log_esp_idle` makes it.
    """
    gate_log = math.log(gate_esp) if gate_esp is not None and gate_esp > 0 else None
    log = log_esp_idle(routed, gate_log=gate_log)
    return None if log is None else math.exp(log)


def log_esp_idle(routed: RoutedCircuit, gate_log: float | None = None) -> float | None:
    """Natural log of :func:`esp_idle`, summed in log space like :func:`log_esp` (``None``: the device has no
    durations or no T1 / T2).

    Args:
        routed: A native routed circuit.
        gate_log: ``log_esp(routed)`` where the caller has it already; default: computed.
    """
    device = routed.device
    if device.t1_s is None or device.t2_s is None:
        return None
    idle = idle_times_s(routed)
    if idle is None:
        return None
    log = log_esp(routed) if gate_log is None else gate_log
    for t, t1, t2 in zip(idle, device.t1_s, device.t2_s, strict=True):
        if t > 0 and t1 is not None and t2 is not None:
            log += math.log(idle_fidelity(t, t1, t2))
    return log
