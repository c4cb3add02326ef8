"""The routed bound of ``qcpp estimate --device`` before and after the layout bound, by size, in one run.

Run: ``python benchmarks/routed_bound.py [--sizes 10x10/4,16x16/8,20x20/8,30x30/8] [--compare 3x3/2,4x4/2]``.

Per size and device family (``grid``, ``heavy-hex``), on the device the estimate sizes for the row
(:func:`qcpp.pipeline.device_compile.layout_device`) and ``p`` = 3: the two-qubit count of the circuit the bound routes
(``circuit cx``: unfused, the device's phase layout), the previous bound (every two-qubit gate at the device's
diameter bound, the partial mixers' at :data:`qcpp.estimators.routed.MIXER_SPAN`; still the fallback where no layout
exists), the layout bound (every gate at its own distance in the geometric layout, :mod:`qcpp.estimators.layout_bound`)
with its wall seconds, and the ratios. The ``--compare`` sizes (``p`` = 1) add what ``qcpp compile --device``
routes exactly (its two-qubit count), which both bounds must exceed. The load average is printed (2 shared cores:
the seconds vary with it).
"""

from __future__ import annotations

import argparse
import os
import time
from dataclasses import replace

from qcpp.estimators import layout_bound, routed
from qcpp.pipeline.device_compile import compile_for_device, layout_device
from qcpp.pipeline.device_plan import device_plan_options
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.presets import default_scenario

DEVICES = ("grid", "heavy-hex")


def _sizes(text: str) -> list[tuple[int, int, int]]:
    out = []
    for spec in text.split(","):
        grid, robots = spec.split("/")
        rows, cols = grid.split("x")
        out.append((int(rows), int(cols), int(robots)))
    return out


def _row(shape: tuple[int, int, int], device: str, p: int, exact: bool) -> str:
    s = default_scenario(*shape)
    dev = layout_device(s, device)
    assert dev is not None
    plan = PlanOptions()
    cx = qaoa_plan(s, p, replace(device_plan_options(plan, dev), fuse=False)).cost().two_qubit
    real = layout_bound.layout_twoq_bound
    layout_bound.layout_twoq_bound = lambda *_a, **_k: None  # type: ignore[assignment]  # the previous bound
    try:
        before = routed._bound_of_compiled(s, p, plan, dev)["routed_twoq"]
    finally:
        layout_bound.layout_twoq_bound = real  # type: ignore[assignment]
    start = time.perf_counter()
    after = routed._bound_of_compiled(s, p, plan, dev)["routed_twoq"]
    seconds = time.perf_counter() - start
    compiled = "-"
    if exact:
        r = compile_for_device(s, p, device, lowered=True)
        n = sum(len(g[1]) == 2 for sec in r.routed.circuit.sections for g in sec.gates)
        compiled = f"{n:,} ({r.routed.device.name}) | {after / n:.2f}"
    else:
        compiled = "- | -"
    name = f"{shape[0]}x{shape[1]}/{shape[2]}"
    return (f"| {name} | {dev.name} | {p} | {cx:,} | {before:,} | {after:,} | {seconds:.1f} s | "
            f"{before / after:.1f} | {after / cx:.1f} | {compiled} |")  # fmt: skip


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="10x10/4,16x16/8,20x20/8,30x30/8")
    ap.add_argument("--compare", default="3x3/2,4x4/2")
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print()
    print("| size | device | p | circuit cx | previous bound | layout bound | layout bound time | previous / "
          "layout | layout / circuit cx | compile --device routes | layout / compile |")  # fmt: skip
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for shape in _sizes(args.compare) if args.compare else []:
        for device in DEVICES:
            print(_row(shape, device, 1, exact=True), flush=True)
    for shape in _sizes(args.sizes):
        for device in DEVICES:
            print(_row(shape, device, 3, exact=False), flush=True)


if __name__ == "__main__":
    main()
