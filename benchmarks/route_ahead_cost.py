"""The memory that routing the large windows ahead costs: a heavy-hex compile with and without it, side by side.

Run: ``python benchmarks/route_ahead_cost.py [CASE ...]`` (cases ``ROWSxCOLS/ROBOTS`` of the default scenarios;
default ``5x5/2 8x8/3``). Per case, two fresh processes one after the other run
``compile_for_device(<default scenario>, 1, "heavy-hex", routing=replace(DEFAULT_ROUTING, route_ahead=...))``
(:mod:`qcpp.routing.prefetch`). Columns: the process's peak proportional set size (PSS: pages shared with the
forked copy count half to each) and the peak PSS of the process and its children together, sampled every 50 ms
from ``/proc`` (Linux), and the routed circuit's two-qubit gates (equal: the same circuit). The sampling slows the
compile (reading a process's page tables takes its memory lock), so times are left to
``benchmarks/hex_compile_speed.py``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time


def _pss_mb(pid: int) -> int:
    try:
        with open(f"/proc/{pid}/smaps_rollup") as f:
            return next(int(line.split()[1]) // 1024 for line in f if line.startswith("Pss:"))
    except (OSError, StopIteration):
        return 0


def _children(pid: int) -> list[int]:
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            return [int(v) for v in f.read().split()]
    except OSError:
        return []


def _worker(case: str, ahead: bool) -> None:
    from dataclasses import replace

    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.problem.presets import default_scenario
    from qcpp.routing.options import DEFAULT_ROUTING

    grid, robots = case.split("/")
    rows, cols = (int(v) for v in grid.split("x"))
    routing = replace(DEFAULT_ROUTING, route_ahead=ahead)
    out = compile_for_device(default_scenario(rows, cols, int(robots)), 1, "heavy-hex", routing=routing)
    twoq = sum(1 for g in out.routed.circuit.gates if len(g[1]) == 2)
    print(json.dumps({"twoq": twoq, "device": out.routed.device.name}))


def _measure(case: str, ahead: bool) -> dict[str, float]:
    proc = subprocess.Popen([sys.executable, __file__, "--worker", case, str(int(ahead))], stdout=subprocess.PIPE,
                            text=True)  # fmt: skip
    own = total = 0
    while proc.poll() is None:
        mine = _pss_mb(proc.pid)
        own, total = max(own, mine), max(total, mine + sum(_pss_mb(c) for c in _children(proc.pid)))
        time.sleep(0.05)
    assert proc.stdout is not None
    result = json.loads(proc.stdout.read().strip().splitlines()[-1])
    return {**result, "own": own, "total": total}


def main(argv: list[str]) -> int:
    if argv[:1] == ["--worker"]:
        _worker(argv[1], argv[2] == "1")
        return 0
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", default=["5x5/2", "8x8/3"], metavar="CASE",
                        help="ROWSxCOLS/ROBOTS of a default scenario (default 5x5/2 8x8/3)")
    argv = parser.parse_args(argv).cases
    print(f"{os.cpu_count()} cores, load average before: {os.getloadavg()[0]:.1f}")
    print()
    print("| case | device | routed ahead | peak PSS MB | with children MB | two-qubit gates |")
    print("|---|---|---|---:|---:|---:|")
    for case in argv:
        for ahead in (False, True):
            r = _measure(case, ahead)
            print(f"| {case} | {r['device']} | {'yes' if ahead else 'no'} | {r['own']:,.0f} | {r['total']:,.0f} | "
                  f"{r['twoq']:,.0f} |", flush=True)  # fmt: skip
    print()
    print(f"load average after: {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
