"""From a scenario to a routed circuit on a device: compile, allocate, place, route, translate to native gates.

:func:`compile_for_device` is what ``qcpp compile --device NAME`` runs:

1. compile and lower with ``fuse=False`` (every partial mixer its own section, clean at both ends: needed by
   the local-ancilla pass, and the routed circuit's sections stay clean; the lowered count is 2-12 CX above
   the fused one on the default grids);
2. optionally give gadgets region-local ancillas (:func:`circuitgen.layout.localize_ancillas`,
   ``local_ancillas=True``; off by default: measured, it does not pay off yet, see ``benchmarks/routing.py``);
3. place (:func:`circuitgen.layout.place`), then refine the layout SABRE-style: route the two-qubit gates
   forward, then backward from the final layout, and start again from where the backward pass ends
   (``refine_rounds`` times); Qiskit's own ``SabreLayout`` is one more candidate (``layouts``); the layout whose
   routing needs the fewest SWAPs wins;
4. route with Qiskit's SABRE (:func:`circuitgen.routing.route`) and, unless ``lowered``, translate to the
   device's native gates (:func:`circuitgen.routing.to_native`).

Example:
    >>> from gridcover.presets import default_scenario
    >>> r = compile_for_device(default_scenario(3, 3, 1), p=1, device="grid", bindings={"gamma_0": 0.3})
    >>> r.routed.device.name, r.routed.circuit.num_qubits, r.logical_qubits
    ('grid:4x4', 16, 15)
    >>> sorted(r.routed.circuit.count_ops())
    ['cz', 'rx', 'rz']
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

from gridcover.scenario import Scenario

from .circuit import Circuit, Section
from .compile import CompileResult, compile_scenario
from .devices import Device, get_device
from .layout import localize_ancillas, place
from .options import DEFAULT_PLAN, PlanOptions
from .phase_locality import for_device
from .routing import RoutedCircuit, duration_s, esp, route, to_native

__all__ = ["DeviceCompileResult", "compile_for_device", "device_for"]


@dataclass(frozen=True)
class DeviceCompileResult:
    """A routed circuit and where it came from.

    Attributes:
        compiled: The unrouted lowered circuit (logical qubits).
        logical: The circuit routed (after the optional local-ancilla pass; logical qubits).
        routed: The routed circuit (native gates unless compiled ``lowered``).
        lowered: Whether the routed circuit keeps CX + one-qubit gates.
        seconds: Wall time of everything.
    """

    compiled: CompileResult
    logical: Circuit
    routed: RoutedCircuit
    lowered: bool
    seconds: float

    @property
    def logical_qubits(self) -> int:
        """Qubits of the logical circuit that was routed."""
        return self.logical.num_qubits

    def summary(self) -> dict[str, Any]:
        """JSON-ready: ``device``, ``initial_layout``, ``final_layout``, ``routed`` (gates, two-qubit count, swaps,
        ESP with its model, duration in seconds)."""
        r = self.routed
        native = r if not self.lowered else to_native(r)
        ops = r.circuit.count_ops()
        return {
            "device": r.device.summary(),
            "initial_layout": list(r.initial_layout),
            "final_layout": list(r.final_layout),
            "routed": {
                "router": "qiskit SabreSwap, our layout",
                "two_qubit": sum(v for k, v in ops.items() if k in ("cx", "cz", "rzz")),
                "swaps": r.swaps,
                "esp": esp(native),
                "esp_model": ESP_MODEL,
                "duration_s": duration_s(native),
            },
        }


ESP_MODEL = (
    "product of (1 - gate error) over every native gate and (1 - readout error) over the measured data qubits; "
    "device data, no idle decoherence or crosstalk"
)


def device_for(spec: str, qubits: int) -> Device:
    """The device named ``spec``; a family without a size gets its smallest member with ``qubits`` qubits."""
    return get_device(spec, min_qubits=qubits)


def _two_qubit_only(c: Circuit, reverse: bool = False) -> Circuit:
    gates = [g for g in c.gates if len(g[1]) == 2]
    if reverse:
        gates.reverse()
    return Circuit(c.registers, [Section("two_qubit", gates)])


def qiskit_sabre_layout(circuit: Circuit, device: Device, seed: int = 0) -> tuple[int, ...]:
    """Qiskit's ``SabreLayout`` (forward-backward SABRE from random starts) on the two-qubit gates."""
    from qiskit import QuantumCircuit
    from qiskit.transpiler import PassManager
    from qiskit.transpiler.passes import SabreLayout

    from .routing import coupling_map

    qc = QuantumCircuit(circuit.num_qubits)
    for g in circuit.gates:
        if len(g[1]) == 2:
            qc.cx(*g[1])
    pm = PassManager([SabreLayout(coupling_map(device), seed=seed, skip_routing=True)])
    pm.run(qc)
    layout = pm.property_set["layout"]
    return tuple(int(layout[q]) for q in qc.qubits)


LAYOUTS = ("ours", "qiskit")
"""Layout seeds :func:`best_layout` may try: our placement refined, and Qiskit's SabreLayout."""


def best_layout(
    circuit: Circuit,
    device: Device,
    refine_rounds: int = 3,
    seed: int = 0,
    layouts: tuple[str, ...] = LAYOUTS,
) -> tuple[int, ...]:
    """The layout of fewest routed SWAPs among: our placement and its forward-backward SABRE refinements
    (``"ours"``), and Qiskit's ``SabreLayout`` (``"qiskit"``)."""
    if device.is_all_to_all:
        return place(circuit, device)
    forward = _two_qubit_only(circuit)
    candidates: list[tuple[int, ...]] = []
    if "ours" in layouts:
        layout = place(circuit, device)
        candidates.append(layout)
        backward = _two_qubit_only(circuit, reverse=True)
        for _ in range(refine_rounds):
            ahead = route(forward, device, layout, seed=seed)
            layout = route(backward, device, ahead.final_layout, seed=seed).final_layout
            candidates.append(layout)
    if "qiskit" in layouts:
        candidates.append(qiskit_sabre_layout(circuit, device, seed))
    scored = [(route(forward, device, lay, seed=seed).swaps, i) for i, lay in enumerate(candidates)]
    return candidates[min(scored)[1]]


def compile_for_device(
    scenario: Scenario,
    p: int,
    device: str | Device,
    options: PlanOptions = DEFAULT_PLAN,
    *,
    lowered: bool = False,
    bindings: Mapping[str, float] | None = None,
    local_ancillas: bool = False,
    seed: int = 0,
    layouts: tuple[str, ...] = LAYOUTS,
) -> DeviceCompileResult:
    """Compile ``scenario`` and route it onto ``device`` (steps in the module docs).

    Args:
        scenario: The scenario.
        p: QAOA layers.
        device: A :class:`Device` or a name for :func:`circuitgen.devices.get_device` (a family without a size
            gets its smallest member that holds the circuit).
        options: How the circuit is built; routing always compiles it unfused (``fuse=False``: every partial
            mixer clean at both ends, so its ancillas can be placed and checked section by section).
        lowered: Keep CX + one-qubit gates (default: the device's native gates).
        bindings: Angle values (symbols may stay unbound).
        local_ancillas: Run :func:`circuitgen.layout.localize_ancillas` first.
        seed: SABRE's seed.
        layouts: Layout seeds to try (:func:`best_layout`).

    Returns:
        The :class:`DeviceCompileResult`.

    Raises:
        circuitgen.devices.DeviceError: an unknown device.
        ValueError: the device is too small.
    """
    start = time.perf_counter()
    options = for_device(options, device)  # phase_layout "auto": spatial on a device with a sparse coupling map
    compiled = compile_scenario(scenario, p, replace(options, fuse=False), lowered=True, bindings=bindings)
    circuit = compiled.circuit
    dev = device if isinstance(device, Device) else device_for(device, circuit.num_qubits)
    if circuit.num_qubits > dev.num_qubits:
        raise ValueError(f"the circuit needs {circuit.num_qubits} qubits; device {dev.name} has {dev.num_qubits}")
    if local_ancillas:
        circuit = localize_ancillas(circuit, scenario, dev.num_qubits - circuit.num_qubits)
    layout = best_layout(circuit, dev, seed=seed, layouts=layouts)
    routed = route(circuit, dev, layout, seed=seed, measured=range(scenario.num_variables))
    if not lowered:
        routed = to_native(routed)
    return DeviceCompileResult(compiled, circuit, routed, lowered, time.perf_counter() - start)
