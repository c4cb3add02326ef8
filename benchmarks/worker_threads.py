"""Wall and CPU time of tests run on pytest-xdist workers, with Qiskit's Rust thread pool at one thread per worker
(what ``tests/conftest.py`` sets) and at its default (one thread per core).

Each xdist worker already keeps a core busy; Qiskit's Rust passes (SABRE layout and routing, the O3 passes) add a
rayon thread pool per process whose threads then compete with the other worker for the same cores. Both settings
give the same results (SABRE's trials are seeded; only who runs them differs); this script measures what the
competition costs. The runs alternate (default, one thread, default, ...) so that a change of the machine's load
hits both; the load averages are printed.

Usage::

    python benchmarks/worker_threads.py                 # the heavy device-routing tests below, twice each
    python benchmarks/worker_threads.py --repeats 1 tests/compiler/noise_aware_test.py
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
WORKERS = 2
DEFAULT_TESTS = ("tests/compiler/noise_aware_test.py", "tests/compiler/routing_qcec_test.py",
                 "tests/cli/device_cli_test.py")  # fmt: skip
"""Heavy tests whose time is mostly routing on calibrated IBM devices (Qiskit's SABRE and O3 passes)."""

SETTINGS = (("0", "default (one per core)"), ("1", "1 per worker"))
"""``RAYON_NUM_THREADS`` values (0: rayon's default, which ``tests/conftest.py`` leaves alone) and their labels."""


def _run(tests: list[str], threads: str) -> tuple[float, float, str]:
    """Wall seconds, CPU seconds (every worker and subprocess) and the summary line of one test run."""
    env = {**os.environ, "PYTHONPATH": str(REPO / "src"), "MPLBACKEND": "Agg", "RAYON_NUM_THREADS": threads}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    run = subprocess.run([sys.executable, "-m", "pytest", "-n", str(WORKERS), "-m", "heavy or not heavy", "-q",
                          "-p", "no:randomly", *tests], cwd=REPO, env=env, capture_output=True, text=True,
                         check=False)  # fmt: skip
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    summary = next((line for line in reversed(run.stdout.splitlines()) if " in " in line), "(no summary line)")
    if run.returncode != 0:
        raise SystemExit(f"the test run failed ({summary.strip('= ')}):\n{run.stdout[-2000:]}")
    return wall, cpu, summary.strip("= ")


def main(argv: list[str] | None = None) -> int:
    """Run the tests under each setting, alternating, and print one row per run and the medians."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tests", nargs="*", default=list(DEFAULT_TESTS), help="pytest selections (default: above)")
    parser.add_argument("--repeats", type=int, default=2, help="runs per setting (default 2)")
    args = parser.parse_args(argv)
    print(f"python -m pytest -n {WORKERS} {' '.join(args.tests)}; {os.cpu_count()} cores; "
          f"load average before: {', '.join(f'{x:.1f}' for x in os.getloadavg())}")
    print()
    print("| rust threads | run | wall s | CPU s | tests |")
    print("|---|---:|---:|---:|---|")
    walls: dict[str, list[float]] = {value: [] for value, _ in SETTINGS}
    cpus: dict[str, list[float]] = {value: [] for value, _ in SETTINGS}
    for k in range(args.repeats):
        for value, label in SETTINGS:
            wall, cpu, summary = _run(args.tests, value)
            walls[value].append(wall)
            cpus[value].append(cpu)
            print(f"| {label} | {k + 1} | {wall:.1f} | {cpu:.1f} | {summary} |", flush=True)
    print()
    for value, label in SETTINGS:
        print(f"{label}: median wall {statistics.median(walls[value]):.1f} s, "
              f"median CPU {statistics.median(cpus[value]):.1f} s")
    print(f"load average after: {', '.join(f'{x:.1f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
