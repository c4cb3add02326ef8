"""Time the README's test command with a CPU-bound job running beside it (its budget: 4 minutes on 2 cores).

Starts ``--hogs`` busy-looping Python processes, runs ``python -m pytest -n 2 --dist loadgroup -m "not heavy"`` (the
README's command) and prints its summary line, the wall time, the CPU time of the test run (every worker and subprocess
it waited for), the load averages before and after, and the wall time the same CPU work takes on a machine where
nothing else runs: the CPU time over the run's fair share of the cores beside the hogs. On a shared machine
the measured wall time depends on everyone else's jobs; the load averages say how busy it was.

Usage::

    python benchmarks/suite_under_load.py            # one CPU hog beside the suite
    python benchmarks/suite_under_load.py --hogs 0   # the suite alone
    python benchmarks/suite_under_load.py --cold     # as on a fresh install: numba compiles every kernel again

``--cold`` points numba's cache (``NUMBA_CACHE_DIR``) at an empty folder for the run, as the first run after
``pip install`` finds it: every worker that runs a numba kernel compiles it first (quimb's and qcpp's; the tests
that run quimb share one worker, see tests/conftest.py).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
WORKERS = 2
COMMAND = [sys.executable, "-m", "pytest", "-n", str(WORKERS), "--dist", "loadgroup", "-m", "not heavy", "-q",
           "-p", "no:randomly"]


def main(argv: list[str] | None = None) -> int:
    """Run the suite beside the hogs and print the figures (exit code: the test run's)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hogs", type=int, default=1, help="CPU-bound jobs beside the suite (default 1)")
    parser.add_argument("--cold", action="store_true", help="numba's kernel cache empty, as after pip install")
    args = parser.parse_args(argv)
    cores = os.cpu_count() or 1
    env = {**os.environ, "PYTHONPATH": str(REPO / "src"), "MPLBACKEND": "Agg"}
    if not args.cold:
        return _run(args, cores, env)
    with tempfile.TemporaryDirectory(prefix="numba-cache-") as empty:
        return _run(args, cores, {**env, "NUMBA_CACHE_DIR": empty})


def _run(args: argparse.Namespace, cores: int, env: dict[str, str]) -> int:
    """Run the suite in ``env`` beside ``args.hogs`` CPU hogs and print the figures."""
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
    print(f"beside it: {args.hogs} CPU-bound job(s); {cores} cores; numba's cache: "
          f"{'empty (as after pip install)' if args.cold else 'as found'}")
    print(f"result: {summary.strip('= ')}")
    print(f"wall: {wall:.0f} s; CPU of the test run: {cpu:.0f} s")
    print(f"load average (1, 5, 15 min) before: {', '.join(f'{x:.1f}' for x in load_before)}; "
          f"after: {', '.join(f'{x:.1f}' for x in load_after)}")
    print(f"the same CPU work with nothing else running but the hogs: {cpu / share:.0f} s "
          f"(CPU over a fair share of {share:.2f} cores)")
    return run.returncode


if __name__ == "__main__":
    sys.exit(main())
