"""The speed goals of hardware-aware compilation and estimates, timed as a user runs them (fresh processes, wall
time and the child's CPU time, and the machine's load average first).

Run: ``python benchmarks/routing_speed.py``. Prints one table row per command, with the routed figures it reports
and how they were obtained (``routed_kind``: ``exact`` = what ``qcpp compile --device`` writes, or ``bound``):

* ``qcpp estimate --grid 30x30 --robots 8 -p 3 --device heavy-hex --json`` (goal: under 10 s);
* ``qcpp estimate --grid 30x30 --robots 8 -p 3 --device grid --json`` (goal: under 10 s);
* ``qcpp estimate --grid 30x30 --robots 1 -p 3 --device grid --json`` (no goal: the window sum exact at a real
  size, where every window is local);
* ``qcpp estimate --grid 2x50 --robots 1 --device grid --json`` (goal: seconds; a long strip, whose square medial
  grid is 99x99) and ``qcpp estimate --grid 8x8 --robots 3 --device heavy-hex --json`` (no goal beyond progress
  inside the row: compiled exactly, the cells' plan choice for 147 partial mixers), two shapes that are slow to
  route (a long strip on a square lattice, many robots compiled exactly);
* ``qcpp compile <6x6, 3 robots> --device grid --bind ... --qasm FILE --json`` (goal: under 30 s), and the same
  on ``heavy-hex`` for 4x4 with 2 robots and 6x6 with 3 (no goal: timed because the cells' plan choice
  makes them the slowest compiles), each with the routed two-qubit count, the device and the layout it reports.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import scenario_to_dict


def timed(args: list[str]) -> tuple[str, str]:
    """``"wall s (CPU s)"`` and standard output of ``python -m qcpp ARGS`` (CPU: user + system of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "qcpp", *args], capture_output=True, text=True, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    return f"{wall:.1f} s ({cpu:.1f} s)", out.stdout


ESTIMATES = (
    ("30x30", "8", "3", "heavy-hex", "10 s"),
    ("30x30", "8", "3", "grid", "10 s"),
    ("30x30", "1", "3", "grid", "-"),
    ("2x50", "1", "1", "grid", "10 s"),
    ("8x8", "3", "1", "heavy-hex", "-"),
)

COMPILES = (
    ((6, 6, 3), "grid", "30 s"),
    ((4, 4, 2), "heavy-hex", "-"),
    ((6, 6, 3), "heavy-hex", "-"),
)
"""``qcpp compile`` rows: (rows, cols, robots) of the default scenario, device family, goal."""


def main() -> None:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print()
    print("| command | goal | wall (CPU) time | routed_kind | routed_depth_kind | result |")
    print("|---|---:|---:|---|---|---|")
    for grid, robots, p, device, goal in ESTIMATES:
        args = ["estimate", "--grid", grid, "--robots", robots, "-p", p, "--device", device, "--json"]
        seconds, out = timed(args)
        (row,) = json.loads(out)
        print(
            f"| `qcpp {' '.join(args)}` | {goal} | {seconds} | {row['routed_kind']} | "
            f"{row['routed_depth_kind']} | {row['device']}, routed_twoq {row['routed_twoq']:,} "
            f"(all-to-all {row['cx']:,}), esp {row['esp']:.3g} |",
            flush=True,
        )
    for (rows, cols, robots), device, goal in COMPILES:
        with tempfile.TemporaryDirectory() as tmp:
            scen = Path(tmp) / f"default_{rows}x{cols}_{robots}.json"
            scen.write_text(json.dumps(scenario_to_dict(default_scenario(rows, cols, robots))))
            qasm = Path(tmp) / "routed.qasm"
            args = ["compile", str(scen), "--device", device, "--bind", "gamma_0=0.3", "beta_0=0.7", "--qasm",
                    str(qasm)]  # fmt: skip
            seconds, out = timed([*args, "--json"])
        summary = json.loads(out)
        routed = summary["routed"]
        print(
            f"| `qcpp compile <default {rows}x{cols}/{robots}> --device {device} --qasm FILE --json` | {goal} | "
            f"{seconds} | exact | exact | {summary['device']['name']}, layout {routed['layout']}, "
            f"{routed['two_qubit']:,} two-qubit gates |",
            flush=True,
        )


if __name__ == "__main__":
    main()
