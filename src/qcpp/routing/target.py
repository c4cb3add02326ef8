"""A device as Qiskit's ``Target``: its couplings, native gates, per-qubit and per-coupler errors and durations,
readout errors and coherence times, so Qiskit's noise-aware passes (``VF2Layout``, ``VF2PostLayout``, the
``transpile`` presets) see the calibration our device file holds.

Built from the device file alone (not from qiskit-ibm-runtime, which is not a dependency): the native two-qubit
gate on every coupler in both directions with that coupler's error and duration, each one-qubit native gate per
qubit (``rz`` virtual: error 0, duration 0), ``measure`` with the readout error and duration, and per-qubit
``QubitProperties(t1, t2)`` where the device has them.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> t = device_target(get_device("ibm_fez"))
    >>> t.num_qubits, sorted(t.operation_names)
    (156, ['cz', 'measure', 'rz', 'sx', 'x'])
    >>> t["cz"][(0, 1)].error == t["cz"][(1, 0)].error == get_device("ibm_fez").error_2q[0]
    True
"""

from __future__ import annotations

from functools import cache
from typing import Any

from qcpp.hardware.device import Device

__all__ = ["device_target"]


def _gate(name: str) -> Any:
    from qiskit.circuit import Parameter
    from qiskit.circuit.library import CZGate, RXGate, RZGate, RZZGate, SXGate, XGate

    theta = Parameter("theta")
    gates = {"cz": CZGate(), "sx": SXGate(), "x": XGate(), "rz": RZGate(theta), "rx": RXGate(theta),
             "rzz": RZZGate(theta)}  # fmt: skip
    if name not in gates:
        raise ValueError(f"device_target: no Qiskit gate for native gate {name!r}")
    return gates[name]


@cache
def device_target(device: Device) -> Any:
    """The ``qiskit.transpiler.Target`` of ``device`` (module docs); memoised per device (a frozen value)."""
    from qiskit.circuit import Measure
    from qiskit.providers import QubitProperties
    from qiskit.transpiler import InstructionProperties, Target

    n = device.num_qubits
    props = None
    if device.t1_s is not None or device.t2_s is not None:
        t1 = device.t1_s or (None,) * n
        t2 = device.t2_s or (None,) * n
        props = [QubitProperties(t1=t1[q], t2=t2[q]) for q in range(n)]
    target = Target(description=device.name, num_qubits=n, qubit_properties=props)
    d2 = device.duration_2q_s
    twoq: dict[tuple[int, ...], Any] = {}
    for i, (a, b) in enumerate(device.coupling):
        p = InstructionProperties(error=device.error_2q[i], duration=None if d2 is None else d2[i])
        twoq[(a, b)] = twoq[(b, a)] = p
    target.add_instruction(_gate(device.two_qubit_gate), twoq)
    d1 = dict(device.duration_1q_s) if device.duration_1q_s is not None else {}
    for name, errors in device.error_1q:
        durations = d1.get(name)
        target.add_instruction(_gate(name), {
            (q,): InstructionProperties(error=errors[q], duration=None if durations is None else durations[q])
            for q in range(n)
        })  # fmt: skip
    ro = device.readout_duration_s
    target.add_instruction(Measure(), {
        (q,): InstructionProperties(error=device.readout_error[q], duration=None if ro is None else ro[q])
        for q in range(n)
    })  # fmt: skip
    return target
