"""Cold-cache timing of the resource-estimate sweep: every grid 2x2..10x10, 1-4 robots, p = 1.

Run: ``python benchmarks/estimate_sweep.py [GRIDS] [ROBOTS] [JOBS]`` (defaults ``2x2..10x10 1..4`` and all cores).
Uses a fresh temporary cache directory, so nothing is read from an earlier run. Prints the wall-clock time of the
whole sweep, the time summed over points for each stage (build = ``qaoa_circuit``, lower = ``lower``,
count = ``estimators.counts.count`` plus the high-level count, fault_tolerant = the Clifford+T estimate), the
slowest points, and a warm-cache rerun. Target: the whole table under a minute on 2 cores.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time

from estimators.sweep import grid_points, parse_grid_range, parse_int_range, sweep


def main(argv: list[str]) -> int:
    grids = parse_grid_range(argv[0] if argv else "2x2..10x10")
    robots = parse_int_range(argv[1] if len(argv) > 1 else "1..4", "robots", 1, 4)
    jobs = int(argv[2]) if len(argv) > 2 else (os.cpu_count() or 1)
    points = grid_points(grids, robots, [1])
    with tempfile.TemporaryDirectory() as cache:
        t0 = time.perf_counter()
        cpu0 = os.times()
        results = sweep(points, jobs=jobs, cache=cache, progress=sys.stderr.isatty())
        wall = time.perf_counter() - t0
        cpu1 = os.times()
        t1 = time.perf_counter()
        sweep(points, jobs=jobs, cache=cache, progress=False)
        warm = time.perf_counter() - t1
    stages = ("build", "lower", "count", "fault_tolerant")
    totals = {s: sum(r.timings[s] for r in results) for s in stages}
    child_cpu = (cpu1.children_user + cpu1.children_system) - (cpu0.children_user + cpu0.children_system)
    gates = sum(r.counts.size for r in results)
    print(f"points: {len(points)}  jobs: {jobs}  cores: {os.cpu_count()}  lowered gates: {gates:,}")
    print(f"{'stage':<16}{'CPU seconds (sum over points)':>32}{'share':>8}")
    total = sum(totals.values())
    for s in stages:
        print(f"{s:<16}{totals[s]:>32.1f}{totals[s] / total:>8.0%}")
    print(f"{'all stages':<16}{total:>32.1f}")
    print(f"cold sweep wall clock: {wall:.1f} s   (CPU of the worker processes: {child_cpu:.1f} s)")
    print(f"idle-machine estimate, worker CPU / jobs: {child_cpu / jobs:.1f} s")
    print(f"warm sweep wall clock (all cached): {warm:.2f} s")
    print(f"load average at the end: {os.getloadavg()[0]:.1f}")
    print("slowest points:")
    for r in sorted(results, key=lambda r: -sum(r.timings.values()))[:5]:
        parts = "  ".join(f"{s} {r.timings[s]:.2f}" for s in stages)
        print(f"  {r.point.label:<14} {r.counts.size:>9,} gates  {parts}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
