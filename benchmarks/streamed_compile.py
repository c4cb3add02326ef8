"""Streamed ``qcpp compile --qasm``: peak memory against ``p``, and the guard's prediction against the real run.

Run: ``python benchmarks/streamed_compile.py [--grid 8x8] [--robots 4] [--layers 1,4,16]``.

Each row runs ``qcpp compile --grid G --robots K -p P --lowered --qasm FILE`` in a child process (GNU ``time`` for
its peak resident memory and CPU seconds) and prints the lowered gates written, the wall and CPU seconds, the
rate (gates per CPU second), the peak memory, the file's size, and what the size guard predicted
(:func:`qcpp.estimators.guard.compile_need`: memory and seconds, from
:data:`~qcpp.estimators.guard.BYTES_PER_GATE` and :data:`~qcpp.estimators.guard.GATES_PER_SECOND`). The guard is
meant to over-predict both: a streamed compile holds one layer, so its peak should not grow with ``p``, and the
rate should stay above ``GATES_PER_SECOND`` on a loaded 2-core machine. The load average is printed before and
after.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from qcpp.estimators.guard import GATES_PER_SECOND, compile_need, predict_size
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario

ROOT = Path(__file__).resolve().parents[1]


def _compile(rows: int, cols: int, robots: int, p: int, out: Path) -> tuple[float, float, float]:
    """Wall seconds, CPU seconds and peak RSS (MB) of one streamed compile in a child process."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src") + os.pathsep + os.environ.get("PYTHONPATH", "")}
    cmd = ["/usr/bin/time", "-f", "%M %U %S", sys.executable, "-m", "qcpp", "compile", "--grid", f"{rows}x{cols}",
           "--robots", str(robots), "-p", str(p), "--lowered", "--qasm", str(out)]  # fmt: skip
    start = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT, check=True)
    wall = time.perf_counter() - start
    rss, user, system = proc.stderr.strip().splitlines()[-1].split()
    return wall, float(user) + float(system), int(rss) * 1.024 / 1000


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--grid", default="8x8", help="ROWSxCOLS (default 8x8)")
    parser.add_argument("--robots", type=int, default=4, help="robots in the default placement (default 4)")
    parser.add_argument("--layers", default="1,4,16", help="comma list of p (default 1,4,16)")
    args = parser.parse_args()
    rows, cols = (int(v) for v in args.grid.lower().split("x"))
    scenario = default_scenario(rows, cols, args.robots)
    print(f"load average before: {os.getloadavg()[0]:.1f}; GATES_PER_SECOND = {GATES_PER_SECOND:,}")
    print("| scenario | p | lowered gates | wall s | CPU s | gates / CPU s | peak MB | file MB "
          "| guard: MB | guard: s |")  # fmt: skip
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for p in (int(v) for v in args.layers.split(",")):
            out = Path(tmp) / f"p{p}.qasm"
            wall, cpu, peak = _compile(rows, cols, args.robots, p, out)
            gates = predict_size(scenario, p, PlanOptions()).gates
            need = compile_need(scenario, p, PlanOptions(), streamed=True)
            print(f"| {rows}x{cols}/{args.robots} | {p} | {gates:,} | {wall:.1f} | {cpu:.1f} | {gates / cpu:,.0f} "
                  f"| {peak:.0f} | {out.stat().st_size / 1e6:.0f} | {need.bytes / 1e6:.0f} | {need.seconds:.0f} |",
                  flush=True)  # fmt: skip
            out.unlink()
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
