"""``qcpp compile --effort quick`` against the default ``full`` on the calibrated IBM devices, side by side in one run.

Run: ``python benchmarks/compile_effort.py [--devices ibm_fez ibm_torino] [CASE ...]`` (cases ``ROWSxCOLS/ROBOTS``
of the default scenarios; default ``3x3/1 3x4/1 3x3/2``). Per case and device, ``qcpp.compile(scenario, p=1,
device=DEVICE, bind=BIND, effort=E)`` for each effort, each in a fresh :class:`qcpp.RoutingContext` (nothing
shared between the two), the objective the device's default (ESP with idle decoherence on these snapshots).

The table gives, per effort, the CPU seconds of the call (this process's: SABRE's Rust passes run on the calling
thread with ``RAYON_NUM_THREADS=1``, which the script sets when unset, so CPU time counts all of the work), the
routed two-qubit gates and the ESP with idle decoherence, and, from the same compile's candidates, Qiskit O3's best
of its seeds by each figure (its routing as Qiskit wrote it, not the candidates that move it onto other qubits):
``quick`` drops only the choice of partial-mixer plans for the routing
(:data:`qcpp.routing.options.QUICK_ROUTING`), so it costs a fraction of the time and keeps Qiskit O3 as a
candidate (never worse than it by the figure chosen), for more two-qubit gates than ``full``.
"""

from __future__ import annotations

import argparse
import os
import re
import time
from typing import Any

from routing_verdict import BIND  # the verdict table's angles (this script's directory is on the path)

DEFAULT_CASES = ("3x3/1", "3x4/1", "3x3/2")
DEFAULT_DEVICES = ("ibm_fez", "ibm_torino")


def _row(case: str, device: str, effort: str) -> dict[str, Any]:
    import qcpp

    grid, robots = case.split("/")
    rows, cols = (int(v) for v in grid.split("x"))
    scenario = qcpp.grid_scenario(rows, cols, robots=int(robots))
    start = time.process_time()
    compiled = qcpp.compile(scenario, p=1, device=device, bind=BIND, effort=effort, context=qcpp.RoutingContext())
    seconds = time.process_time() - start
    routed = compiled.to_dict()["routed"]
    qiskit = [c for c in routed["candidates"] if re.fullmatch(r"qiskit O3 seed \d+", c["name"])]  # as Qiskit wrote it
    return {"case": case, "device": device, "effort": effort, "cpu_s": seconds, "twoq": routed["two_qubit"],
            "esp_idle": routed["esp_idle"], "o3_twoq": min(c["two_qubit"] for c in qiskit),
            "o3_esp_idle": max(c["esp_idle"] for c in qiskit)}  # fmt: skip


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cases", nargs="*", default=list(DEFAULT_CASES), help="ROWSxCOLS/ROBOTS (default scenarios)")
    parser.add_argument("--devices", nargs="+", default=list(DEFAULT_DEVICES), help="calibrated devices")
    args = parser.parse_args(argv)
    os.environ.setdefault("RAYON_NUM_THREADS", "1")
    import qcpp

    qcpp.compile(qcpp.grid_scenario(2, 2, robots=1), device=args.devices[0])  # imports and Qiskit's set-up, untimed
    print(f"`python benchmarks/compile_effort.py {' '.join(args.cases)} --devices {' '.join(args.devices)}`: "
          "qcpp.compile(..., effort=E), p = 1, angles bound, chosen by ESP with idle decoherence; CPU seconds of "
          "the call; Qiskit O3: its best of 3 seeds by each figure, from the same compile's candidates\n")  # fmt: skip
    print("| device | scenario | CPU s: full / quick | 2q: full / quick (Qiskit O3) | "
          "ESP idle: full / quick (Qiskit O3) |")
    print("|---|---|---:|---:|---:|")
    rows = []
    for device in args.devices:
        for case in args.cases:
            full, quick = (_row(case, device, effort) for effort in ("full", "quick"))
            rows += [full, quick]
            ratio = full["cpu_s"] / quick["cpu_s"]
            print(f"| {device} | {case} | {full['cpu_s']:.1f} / {quick['cpu_s']:.1f} = {ratio:.1f}x "
                  f"| {full['twoq']:,} / {quick['twoq']:,} ({full['o3_twoq']:,}) "
                  f"| {full['esp_idle']:.3g} / {quick['esp_idle']:.3g} ({full['o3_esp_idle']:.3g}) |",
                  flush=True)  # fmt: skip
    return rows


if __name__ == "__main__":
    main()
