"""Routed two-qubit gates: ours vs Qiskit O3/SABRE on the same coupling map, in the same run.

Run: ``python benchmarks/routing.py [--quick] [--family grid|heavy-hex]`` (``--quick``: 3x3/1, 4x4/2 and the
obstacle scenarios but the 5x5 one; ``--family``: that device family's rows only; ``--scenario LABEL``: the rows whose
scenario label starts with LABEL, e.g. ``--scenario 4x4/2``);
``python benchmarks/routing.py --arrangements``: the medial layout's robot arrangements (``tile``, ``interleave``)
side by side on the multi-robot defaults, routed CX per part (phase separator, mixer) against the part's
unrouted CX (the compiled circuit's, before :mod:`qcpp.routing.bridge` relays far phases);
``python benchmarks/routing.py --cells [--quick] [--scenario LABEL]``: the heavy-hex cell layout
(:mod:`qcpp.layout.heavy_hex`) on every scenario (or those whose label starts with LABEL), routed CX per part the
same way, next to the greedy routing ``auto`` compares it with.

Per scenario (p = 1, angles bound) and device family, the device is what ``qcpp compile --device FAMILY`` picks:
``grid`` is sized for the medial layout (:func:`qcpp.pipeline.device_compile.medial_device`); ``heavy-hex`` is the
smallest lattice that holds the cell layout (:func:`qcpp.pipeline.device_compile.hex_device`) where compile keeps that
layout, else the smallest that holds the circuit (where ``auto`` found the greedy routing there cheaper). Columns:

* ``a2a cx``: the lowered circuit's CX (all-to-all, fused mixer; what ``qcpp compile --lowered`` writes);
* ``qiskit O3``: ``qiskit.transpile(optimization_level=3, seed_transpiler=0)`` of that circuit (read from our
  OpenQASM 2) onto the device's coupling map, basis ``cx`` + our one-qubit gates: its CX count and seconds;
* ``greedy``: :func:`qcpp.pipeline.device_compile.compile_for_device` with ``layout_method="greedy"`` (our greedy
  placement or Qiskit's SabreLayout, then one SABRE routing of the whole circuit): CX;
* ``compile``: what ``qcpp compile --device ... --lowered`` writes (``layout_method="auto"``: the geometric
  layout, ``medial``, on square grids and heavy-hex lattices, greedy elsewhere or where it routes cheaper on a
  small circuit): CX, seconds and the layout used;
* ``compile / O3`` (goal: <= 0.5 on a grid, <= 0.6 on heavy-hex) and ``compile / a2a`` (goal: <= 2 on a grid,
  <= 3 on heavy-hex);
* ``2q depth``: the routed circuit's two-qubit depth (ASAP), greedy and compile: windows that return home on
  disjoint qubits run side by side.
"""

from __future__ import annotations

import argparse
import time

from qcpp.api.scenarios import grid_scenario
from qcpp.estimators.counts import count_gates
from qcpp.hardware.device import Device, get_device
from qcpp.ir.circuit import Circuit
from qcpp.layout.medial import ARRANGEMENTS
from qcpp.lowering.qasm import to_qasm2
from qcpp.pipeline.device_compile import compile_for_device, medial_device
from qcpp.plan.compile import compile_scenario
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.problem.scenario_io import load_scenario
from qcpp.routing.context import RoutingContext
from qcpp.routing.routed_circuit import coupling_map

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
OBSTACLE = {
    "name": "3x4, hard obstacle, interior start",
    "grid": {"rows": 3, "cols": 4, "obstacles": [[0, 3]]},
    "robots": [{"start": [1, 1], "goal": [2, 3]}],
    "objective": {"obstacles": "hard"},
}

CONTEXT = RoutingContext()
"""The routing memos of this run: later rows find equal windows and the plans' searches routed already."""


def scenarios(quick: bool) -> list[tuple[str, Scenario]]:
    """The benchmark's scenarios."""
    out = [("3x3/1", default_scenario(3, 3, 1)), ("4x4/2", default_scenario(4, 4, 2))]
    if not quick:
        out += [("5x5/2", default_scenario(5, 5, 2)), ("6x6/3", default_scenario(6, 6, 3))]
    out += [
        ("obstacles_hard_4x4", load_scenario("examples/obstacles_hard_4x4.toml")),
        ("3x4 obstacle, interior", scenario_from_dict(OBSTACLE)),
        ("4x4/2, hard obstacle", grid_scenario(4, 4, robots=2, obstacles=[(1, 2)], hard_obstacles=True)),
    ]
    if not quick:
        out.append(("5x5/2, 2 hard obstacles", grid_scenario(5, 5, robots=2, obstacles=[(1, 3), (2, 2)],
                                                             hard_obstacles=True)))  # fmt: skip
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
    if family == "heavy-hex":  # what `qcpp compile --device heavy-hex` writes, and the others on its device
        start = time.perf_counter()
        compiled = compile_for_device(s, 1, family, lowered=True, bindings=BIND, context=CONTEXT)
        seconds = time.perf_counter() - start
        device = compiled.routed.device
    else:
        device = medial_device(s, family) or get_device(family, min_qubits=fused.num_qubits)
    o3, o3_s = qiskit_o3(fused, device)
    greedy = compile_for_device(s, 1, device, lowered=True, bindings=BIND, layout_method="greedy", context=CONTEXT)
    greedy_cx = greedy.routed.circuit.count_ops()["cx"]
    if family != "heavy-hex":
        start = time.perf_counter()
        compiled = compile_for_device(s, 1, device, lowered=True, bindings=BIND, context=CONTEXT)
        seconds = time.perf_counter() - start
    cx = compiled.routed.circuit.count_ops()["cx"]
    a2a = fused.count_ops()["cx"]
    depth = [count_gates(r.routed.circuit.gates, device.num_qubits).two_qubit_depth for r in (greedy, compiled)]
    return (
        f"| {label} | {fused.num_qubits} | {a2a:,} | {device.name} | {o3:,} ({o3_s:.1f} s) | {greedy_cx:,} "
        f"| {cx:,} ({seconds:.1f} s, {compiled.layout_method}) | {cx / o3:.2f} | {cx / a2a:.2f} "
        f"| {depth[0]:,} / {depth[1]:,} |"
    )


def _by_part(c: Circuit) -> dict[str, int]:
    part = {"phase": 0, "mixer": 0}
    for sec in c.sections:
        key = sec.name.split("_")[0]
        if key in part:
            part[key] += sum(len(g[1]) == 2 for g in sec.gates)
    return part


def arrangements() -> None:
    """Tile vs interleave: routed CX of the medial layout per part (phase separator, mixer) on the unsized
    ``grid``, next to the unrouted (all-to-all, unfused) CX of that part, as compiled (before relays)."""
    print("| scenario | arrangement | device | routed cx | phase: routed / a2a | mixer: routed / a2a |")
    print("|---|---|---|---:|---:|---:|")
    for label, s in (("4x4/2", default_scenario(4, 4, 2)), ("5x5/2", default_scenario(5, 5, 2)),
                     ("6x6/3", default_scenario(6, 6, 3))):  # fmt: skip
        for arrangement in ARRANGEMENTS:
            r = compile_for_device(s, 1, "grid", lowered=True, bindings=BIND, arrangement=arrangement, context=CONTEXT)
            routed, a2a = _by_part(r.routed.circuit), _by_part(r.compiled.circuit)
            cells = " | ".join(f"{routed[k]:,} / {a2a[k]:,} = {routed[k] / a2a[k]:.2f}" for k in ("phase", "mixer"))
            total = r.routed.circuit.count_ops()["cx"]
            print(f"| {label} | {arrangement} | {r.routed.device.name} | {total:,} | {cells} |", flush=True)


def cells(quick: bool, prefix: str = "") -> None:
    """The heavy-hex cell layout (``layout_method="medial"`` on the unsized ``heavy-hex``) on every scenario: routed
    CX per part against the part's unrouted CX, next to the greedy routing on the smallest lattice that holds the
    circuit (what ``auto`` compares on circuits of at most ``auto_compare_max_twoq`` two-qubit gates)."""
    print("| scenario | cells: device | cells cx | phase: routed / a2a | mixer: routed / a2a | greedy: device "
          "| greedy cx |")  # fmt: skip
    print("|---|---|---:|---:|---:|---|---:|")
    for label, s in scenarios(quick):
        if not label.startswith(prefix):
            continue
        r = compile_for_device(s, 1, "heavy-hex", lowered=True, bindings=BIND, layout_method="medial", context=CONTEXT)
        routed, a2a = _by_part(r.routed.circuit), _by_part(r.compiled.circuit)
        parts = " | ".join(
            f"{routed[k]:,} / {a2a[k]:,} = {routed[k] / a2a[k]:.2f}" if a2a[k] else "-" for k in ("phase", "mixer")
        )
        g = compile_for_device(s, 1, "heavy-hex", lowered=True, bindings=BIND, layout_method="greedy", context=CONTEXT)
        print(f"| {label} | {r.routed.device.name} | {r.routed.circuit.count_ops()['cx']:,} | {parts} "
              f"| {g.routed.device.name} | {g.routed.circuit.count_ops()['cx']:,} |", flush=True)  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer scenarios (module docs)")
    parser.add_argument("--family", choices=("grid", "heavy-hex"), help="that device family's rows only")
    parser.add_argument("--scenario", metavar="LABEL", default="", help="the rows whose label starts with LABEL")
    parser.add_argument("--arrangements", action="store_true", help="the medial layout's robot arrangements")
    parser.add_argument("--cells", action="store_true", help="the heavy-hex cell layout, routed CX per part")
    args = parser.parse_args()
    if args.arrangements:
        arrangements()
        return
    prefix = args.scenario
    if args.cells:
        cells(args.quick, prefix)
        return
    quick = args.quick
    families = ("grid", "heavy-hex") if args.family is None else (args.family,)
    print(
        "| scenario | qubits | a2a cx | device | qiskit O3 cx | greedy cx | compile cx | compile / O3 "
        "| compile / a2a | 2q depth: greedy / compile |"
    )
    print("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|")
    for label, s in scenarios(quick):
        if not label.startswith(prefix):
            continue
        for family in families:
            print(row(label, s, family), flush=True)


if __name__ == "__main__":
    main()
