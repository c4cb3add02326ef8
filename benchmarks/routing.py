"""Routed two-qubit gates: ours vs Qiskit O3/SABRE on the same coupling map, in the same run.

Run: ``python benchmarks/routing.py [--quick]`` (``--quick``: 3x3/1, 4x4/2 and the obstacle scenarios only).

Per scenario (p = 1, angles bound) and device family (the smallest square grid and the smallest heavy-hex that
hold the circuit), columns:

* ``a2a cx``: the lowered circuit's CX (all-to-all, fused mixer; what ``qcpp compile --lowered`` writes);
* ``qiskit O3``: ``qiskit.transpile(optimization_level=3, seed_transpiler=0)`` of that circuit (read from our
  OpenQASM 2) onto the device's coupling map, basis ``cx`` + our one-qubit gates: its CX count and seconds;
* ``ours layout``: our placement refined forward-backward (:func:`circuitgen.hardware.best_layout` with
  ``layouts=("ours",)``), routed by SABRE: CX (SWAPs as 3 CX) of the unfused lowered circuit;
* ``local anc``: the same with region-local ancillas (:func:`circuitgen.layout.localize_ancillas`);
* ``compile``: what ``qcpp compile --device ... --lowered`` writes (the better of our layout and Qiskit's
  SabreLayout, then SABRE): CX and seconds;
* ``compile / O3``: the goal is <= 0.5 on a grid and <= 0.6 on heavy-hex.
"""

from __future__ import annotations

import sys
import time

from circuitgen.circuit import Circuit
from circuitgen.compile import compile_scenario
from circuitgen.devices import Device, get_device
from circuitgen.hardware import best_layout, compile_for_device
from circuitgen.layout import localize_ancillas
from circuitgen.options import PlanOptions
from circuitgen.qasm import to_qasm2
from circuitgen.routing import coupling_map, route
from gridcover.presets import default_scenario
from gridcover.scenario import Scenario, load_scenario, scenario_from_dict

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
OBSTACLE = {
    "name": "3x4, hard obstacle, interior start",
    "grid": {"rows": 3, "cols": 4, "obstacles": [[0, 3]]},
    "robots": [{"start": [1, 1], "goal": [2, 3]}],
    "objective": {"obstacles": "hard"},
}


def scenarios(quick: bool) -> list[tuple[str, Scenario]]:
    """The benchmark's scenarios."""
    out = [("3x3/1", default_scenario(3, 3, 1)), ("4x4/2", default_scenario(4, 4, 2))]
    if not quick:
        out += [("5x5/2", default_scenario(5, 5, 2)), ("6x6/3", default_scenario(6, 6, 3))]
    out += [
        ("obstacles_hard_4x4", load_scenario("examples/obstacles_hard_4x4.toml")),
        ("3x4 obstacle, interior", scenario_from_dict(OBSTACLE)),
    ]
    return out


def qiskit_o3(circuit: Circuit, device: Device) -> tuple[int, float]:
    """Qiskit O3's routed CX count and seconds."""
    from qiskit import qasm2, transpile

    start = time.perf_counter()
    qc = qasm2.loads(to_qasm2(circuit))
    basis = ["cx", "h", "rz", "t", "tdg", "s", "sdg", "x"]
    out = transpile(qc, coupling_map=coupling_map(device), optimization_level=3, seed_transpiler=0, basis_gates=basis)
    return out.count_ops().get("cx", 0), time.perf_counter() - start


def row(label: str, s: Scenario, family: str) -> str:
    """One table row."""
    fused = compile_scenario(s, 1, lowered=True, bindings=BIND).circuit
    unfused = compile_scenario(s, 1, PlanOptions(fuse=False), lowered=True, bindings=BIND).circuit
    device = get_device(family, min_qubits=fused.num_qubits)
    o3, o3_s = qiskit_o3(fused, device)
    ours = route(unfused, device, best_layout(unfused, device, layouts=("ours",))).circuit.count_ops()["cx"]
    local = localize_ancillas(unfused, s, device.num_qubits - unfused.num_qubits)
    local_cx = "-"
    if local.num_qubits > unfused.num_qubits:
        local_cx = str(route(local, device, best_layout(local, device, layouts=("ours",))).circuit.count_ops()["cx"])
    start = time.perf_counter()
    compiled = compile_for_device(s, 1, device, lowered=True, bindings=BIND)
    seconds = time.perf_counter() - start
    cx = compiled.routed.circuit.count_ops()["cx"]
    return (
        f"| {label} | {fused.num_qubits} | {fused.count_ops()['cx']:,} | {device.name} | {o3:,} ({o3_s:.1f} s) "
        f"| {ours:,} | {local_cx} | {cx:,} ({seconds:.1f} s) | {cx / o3:.2f} |"
    )


def main() -> None:
    quick = "--quick" in sys.argv
    print(
        "| scenario | qubits | a2a cx | device | qiskit O3 cx | ours layout cx | local anc cx | compile cx "
        "| compile / O3 |"
    )
    print("|---|---:|---:|---|---:|---:|---:|---:|---:|")
    for label, s in scenarios(quick):
        for family in ("grid", "heavy-hex"):
            print(row(label, s, family), flush=True)


if __name__ == "__main__":
    main()
