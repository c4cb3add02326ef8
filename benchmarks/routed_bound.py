"""The routed two-qubit count of ``qcpp estimate --device`` by each of its paths, side by side, per row.

Run: ``python benchmarks/routed_bound.py [--compare 3x3/1,3x3/2,4x4/2] [--sizes 30x30/1,10x10/4,30x30/8]``.

Per row (size/robots) and device (``grid``, ``heavy-hex``, ``ibm_fez``; the unsized families sized as the estimate
sizes them, :func:`qcpp.pipeline.device_compile.layout_device`): the path the estimate takes (its ``routed_model``),
the two-qubit count of the circuit compile routes before routing (``circuit cx``), then each path's routed
two-qubit count with its wall seconds: ``compile`` (``qcpp compile --device``, exact; the ``--compare`` rows, p = 1),
the window-class sum (:func:`qcpp.estimators.window_classes.routed_sum`, exact where it answers: square grids of at
most ``WHOLE_DEVICE_MAX_QUBITS`` qubits, within the estimate's whole-device budget; ``-`` elsewhere) and the bound
(:func:`qcpp.estimators.layout_bound.layout_twoq_bound`: the geometric layout where the device holds it, else a
breadth-first ball). The ``--sizes`` rows are at p = 3 and skip compile. The load average is printed (shared
cores: the seconds vary with it).
"""

from __future__ import annotations

import argparse
import os
import time
from dataclasses import replace

from qcpp.estimators import routed
from qcpp.estimators.window_classes import WHOLE_DEVICE_MAX_QUBITS, routed_sum
from qcpp.hardware.device import get_device
from qcpp.pipeline.device_compile import compile_for_device, layout_device
from qcpp.pipeline.device_plan import device_plan_options
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.presets import default_scenario
from qcpp.routing.context import RoutingContext

DEVICES = ("grid", "heavy-hex", "ibm_fez")


def _sizes(text: str) -> list[tuple[int, int, int]]:
    out = []
    for spec in text.split(","):
        grid, robots = spec.split("/")
        rows, cols = grid.split("x")
        out.append((int(rows), int(cols), int(robots)))
    return out


def _timed(run):  # type: ignore[no-untyped-def]
    start = time.perf_counter()
    value = run()
    return value, time.perf_counter() - start


def _row(shape: tuple[int, int, int], device: str, p: int, exact: bool) -> str | None:
    s = default_scenario(*shape)
    plan = PlanOptions()
    laid = qaoa_plan(s, p, replace(device_plan_options(plan, device), fuse=False))
    sized = device in ("grid", "heavy-hex")
    dev = layout_device(s, device) if sized else get_device(device, min_qubits=laid.num_qubits)
    if dev is None or dev.num_qubits < laid.num_qubits:
        return None
    fused = qaoa_plan(s, p, plan).cost()
    path = "compile" if fused.total <= routed.EXACT_MAX_GATES else "window sum or bound"
    compiled = "-"
    if exact:
        r, sec = _timed(lambda: compile_for_device(s, p, device, plan, lowered=True, context=RoutingContext()))
        n = sum(len(g[1]) == 2 for g in r.routed.circuit.gates)
        compiled = f"{n:,} ({r.routed.device.name}, {r.layout_method}, {sec:.0f} s)"
    context = RoutingContext()
    summed, sec = None, 0.0
    if device == "grid" and dev.num_qubits <= WHOLE_DEVICE_MAX_QUBITS:  # as the estimate asks it
        summed, sec = _timed(lambda: routed_sum(s, p, plan, device, whole_device_work=routed.WINDOW_SUM_WORK,
                                                context=context))  # fmt: skip
    window = "-" if summed is None else f"{summed.two_qubit:,} ({sec:.1f} s)"
    if path != "compile":  # the estimate's own choice (its classes known already: no routing again)
        path = "window sum" if routed._window_sum(s, p, plan, device, None, context) is not None else "bound"
    bound, sec = _timed(lambda: routed._bound_of_compiled(s, p, plan, dev, sized))
    kind = "layout" if bound["routed_model"] == routed.LAYOUT_BOUND_MODEL else "ball"
    name = f"{shape[0]}x{shape[1]}/{shape[2]}"
    return (f"| {name} | {bound['device']} | {p} | {path} | {laid.cost().two_qubit:,} | {compiled} | {window} | "
            f"{bound['routed_twoq']:,} ({kind}, {sec:.1f} s) |")  # fmt: skip


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--compare", default="3x3/1,3x3/2,4x4/2")
    ap.add_argument("--sizes", default="30x30/1,10x10/4,30x30/8")
    ap.add_argument("--devices", default=",".join(DEVICES))
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print()
    print("| size | device | p | estimate takes | circuit cx | compile | window sum | bound |")
    print("|---|---|---:|---|---:|---:|---:|---:|")
    rows = [(shape, 1, True) for shape in _sizes(args.compare)] if args.compare else []
    rows += [(shape, 3, False) for shape in _sizes(args.sizes)] if args.sizes else []
    for shape, p, exact in rows:
        for device in args.devices.split(","):
            line = _row(shape, device, p, exact)
            if line is not None:
                print(line, flush=True)


if __name__ == "__main__":
    main()
