"""A routed circuit in the device's native gates, and its figures of merit: estimated success probability, duration.

:func:`to_native` rewrites a routed circuit into the device's native gates (exact up to a global phase):
``cx = h cz h`` and ``cz = rz(pi/2) rz(pi/2) rzz(-pi/2)`` (trapped ions); ``h = rz(pi/2) sx rz(pi/2)`` where
``sx`` is written ``rx(pi/2)`` (the IR has no ``sx``; the device's ``sx`` error and duration are charged for
it); ``t, tdg, s, sdg`` are ``rz`` of their angle; ``x`` stays ``x`` where native (``rx(pi)`` otherwise).

:func:`esp` is the estimated success probability: the product of ``(1 - error)`` over every gate of the
native circuit (per qubit / per coupling, from the device data) and of ``(1 - readout error)`` over the
measured qubits (the data qubits at their final positions). Idle decoherence, crosstalk and leakage are not
modelled. :func:`duration_s` is the ASAP schedule's length with the device's per-gate durations plus one
readout, or ``None`` where the device publishes no durations.

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
"""

from __future__ import annotations

import math

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cz, rx, rz, rzz
from qcpp.routing.routed_circuit import RoutedCircuit

__all__ = ["duration_s", "esp", "native_gates", "one_qubit_name", "to_native"]

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
    sections = [
        Section(sec.name, [n for g in sec.gates for n in native_gates(g, twoq, native_x)])
        for sec in routed.circuit.sections
    ]
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
    """Estimated success probability of a native routed circuit (model in the module docs).

    Returns:
        ``prod (1 - e_gate) * prod_{measured} (1 - e_readout)``.

    Raises:
        ValueError: a gate the device has no error figure for.
    """
    device = routed.device
    e1 = dict(device.error_1q)
    edge = device.edge_index()
    log = 0.0
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            if g[0] != device.two_qubit_gate:
                raise ValueError(f"esp: {g[0]} is not native on {device.name} (use to_native)")
            e = device.error_2q[edge[qs]]
        else:
            name = one_qubit_name(device, g)
            if name not in e1:
                raise ValueError(f"esp: {name} is not native on {device.name} (use to_native)")
            e = e1[name][qs[0]]
        log += math.log1p(-e) if e < 1 else -math.inf
    for lq in routed.measured:
        log += math.log1p(-device.readout_error[routed.final_layout[lq]])
    return math.exp(log)


def duration_s(routed: RoutedCircuit) -> float | None:
    """ASAP schedule length of a native routed circuit plus one readout, in seconds (``None``: no durations)."""
    device = routed.device
    if device.duration_1q_s is None or device.duration_2q_s is None or device.readout_duration_s is None:
        return None
    d1 = dict(device.duration_1q_s)
    edge = device.edge_index()
    free = [0.0] * device.num_qubits
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            start = max(free[qs[0]], free[qs[1]])
            free[qs[0]] = free[qs[1]] = start + device.duration_2q_s[edge[qs]]
        else:
            q = qs[0]
            free[q] += d1[one_qubit_name(device, g)][q]
    readout = max((device.readout_duration_s[routed.final_layout[lq]] for lq in routed.measured), default=0.0)
    return max(free, default=0.0) + readout
