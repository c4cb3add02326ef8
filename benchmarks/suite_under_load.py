"""Time the README's test command with a CPU-bound job running beside it (its budget: 4 minutes on 2 cores).

Starts ``--hogs`` busy-looping Python processes, runs ``python -m pytest -n 2 -m "not heavy"`` (the README's
command) and prints its summary line, the wall time, the CPU time of the test run (every worker and subprocess
it waited for), the load averages before and after, and the wall time the same CPU work takes on a machine where
nothing else runs: the CPU time over the run's fair share of the cores beside the hogs. On a shared machine
the measured wall time depends on everyone else's jobs; the load averages say how busy it was.

Usage::

    python benchmarks/suite_under_load.py            # one CPU hog beside the suite
    python benchmarks/suite_under_load.py --hogs 0   # the suite alone
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
WORKERS = 2
COMMAND = [sys.executable, "-m", "pytest", "-n", str(WORKERS), "-m", "not heavy", "-q", "-p", "no:randomly"]


def main(argv: list[str] | None = None) -> int:
    """Run the suite beside the hogs and print the figures (exit code: the test run's)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hogs", type=int, default=1, help="CPU-bound jobs beside the suite (default 1)")
    args = parser.parse_args(argv)
    cores = os.cpu_count() or 1
    env = {**os.environ, "PYTHONPATH": str(REPO / "src"), "MPLBACKEND": "Agg"}
    hogs = [subprocess.Popen([sys.executable, "-c", "while 1: pass"]) for _ in range(args.hogs)]
    load_before = os.getloadavg()
    start = time.monotonic()
    try:
        run = subprocess.run(COMMAND, cwd=REPO, env=env, capture_output=True, text=True, check=False)
        wall = time.monotonic() - start
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)  # the test run only: the hogs are not reaped yet
        cpu = usage.ru_utime + usage.ru_stime
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()
    load_after = os.getloadavg()
    summary = next((line for line in reversed(run.stdout.splitlines()) if " in " in line), "(no summary line)")
    share = min(WORKERS, cores * WORKERS / (WORKERS + args.hogs))
    print(f"command: {' '.join(['python', *COMMAND[1:]])}")
    print(f"beside it: {args.hogs} CPU-bound job(s); {cores} cores")
    print(f"result: {summary.strip('= ')}")
    print(f"wall: {wall:.0f} s; CPU of the test run: {cpu:.0f} s")
    print(f"load average (1, 5, 15 min) before: {', '.join(f'{x:.1f}' for x in load_before)}; "
          f"after: {', '.join(f'{x:.1f}' for x in load_after)}")
    print(f"the same CPU work with nothing else running but the hogs: {cpu / share:.0f} s "
          f"(CPU over a fair share of {share:.2f} cores)")
    return run.returncode


if __name__ == "__main__":
    sys.exit(main())
