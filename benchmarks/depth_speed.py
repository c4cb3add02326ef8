"""Speed of the depths of ``qcpp estimate``: exact by composition, the bound, and the depth part of the big sweep.

Run: ``python benchmarks/depth_speed.py [--table-only | --sweep-only | --cli] [--stride N] [--budget GATES]``
(one process, so one core; ``--budget`` replaces the default ``--depth-budget`` in the sweep; the table takes
about a minute, the sweep three to four). Prints two tables (``--cli``: a third instead of the second: the whole
sweep through ``qcpp estimate`` with the default depth policy and with ``--depth none``, wall clock, CPU seconds
and peak memory, about two minutes; ``--cli --sweep-only``: that table alone):

1. per scenario (default scenarios, default options): lowered gates of the state preparation plus one layer
   (what ``--depth-budget`` compares), the seconds to build the exact composition (plan the phase separator,
   emit and lower the non-anchored gadgets, look up the anchored ones), to propagate p = 1..5 (carried from p to
   p + 1), to compile the circuit and layer it (the reference, :func:`qcpp.estimators.estimate.compiled_depth`, only
   where it is small),
   the bound's seconds, and exact depth / bound at p = 5;
2. the depth part of ``qcpp estimate --grid 2x2..40x40 --robots 1..8 -p 1..5`` (60,840 requested rows) under
   the default policy (``depth="auto"``), in sweep order: for each scenario the counts are computed first and NOT
   timed (they are cached per scenario, as in the sweep), then :func:`qcpp.estimators.estimate.estimate_depth` is timed
   for its five points. Every scenario that may be exact (its mixer alone within the budget) is timed; of the
   others (certainly bounds, about 0.3 ms each) every ``N``-th grid (row-major, default ``N`` = 13), scaled by
   ``N``.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import subprocess
import sys
import time
from pathlib import Path

from qcpp.estimators.estimate import (
    DEFAULT_OPTIONS,
    compiled_depth,
    depth_bound,
    estimate_depth,
    layer_costs,
    layered_depth,
)
from qcpp.plan.mixer_classes import mixer_part
from qcpp.plan.options import DEFAULT_PLAN
from qcpp.problem.presets import default_scenario, max_default_robots

SCENARIOS = [(4, 4, 2), (6, 6, 2), (8, 8, 4), (12, 12, 8), (20, 20, 4), (30, 30, 8), (40, 40, 8)]
COMPILE_LIMIT = 400_000  # compile the reference only up to this many lowered gates at p = 5


def per_scenario() -> None:
    print("| scenario | gates (prep + 1 layer) | exact: build | exact: p=1..5 | compile p=5 | bound | "
          "depth p=5 exact / bound |")  # fmt: skip
    print("|---|---:|---:|---:|---:|---:|---|")
    for r, c, k in SCENARIOS:
        s = default_scenario(r, c, k)
        lc = layer_costs(s, DEFAULT_PLAN)
        t = time.perf_counter()
        ld = layered_depth(s, DEFAULT_PLAN)
        build = time.perf_counter() - t
        t = time.perf_counter()
        exact = [ld.depth(p) for p in range(1, 6)][-1]
        layers = time.perf_counter() - t
        t = time.perf_counter()
        bound = depth_bound(s, 5, DEFAULT_PLAN)
        tb = time.perf_counter() - t
        comp = "-"
        if lc.cost(5).total <= COMPILE_LIMIT:
            t = time.perf_counter()
            ref = compiled_depth(s, 5, DEFAULT_PLAN)
            comp = f"{time.perf_counter() - t:.2f} s" + ("" if ref == exact else " MISMATCH")
        ratio = f"{exact.depth:,} / {bound.depth:,} ({bound.depth / exact.depth:.2f}x)"
        print(f"| {r}x{c} / {k} | {lc.cost(1).total:,} | {build:.3f} s | {layers:.3f} s | {comp} | "
              f"{tb * 1e3:.1f} ms | {ratio} |")  # fmt: skip


def sweep_depth(stride: int, budget: int) -> None:
    options = dataclasses.replace(DEFAULT_OPTIONS, depth_budget=budget)
    t_exact = t_sampled = 0.0
    rows = {"exact": 0, "bound": 0}
    sampled_rows = 0
    for index, (r, c) in enumerate((r, c) for r in range(2, 41) for c in range(2, 41)):
        for k in range(1, 9):
            if k > max_default_robots(r, c):
                continue
            s = default_scenario(r, c, k)
            # one layer has at least the mixer's gates: above the budget, the point is certainly a bound
            candidate = sum(n * k.cost().total for k, n in mixer_part(s).kinds) <= budget
            if not candidate and index % stride:
                continue
            lc = layer_costs(s, DEFAULT_PLAN)  # the counts: not timed
            t = time.perf_counter()
            ds = [estimate_depth(s, p, options, lc) for p in range(1, 6)]
            dt = time.perf_counter() - t
            if candidate:
                t_exact += dt
                for d in ds:
                    rows[d.kind] += 1  # type: ignore[union-attr]
            else:
                t_sampled += dt
                sampled_rows += len(ds)
    print()
    print(f"| depth part of the 2x2..40x40 / 1..8 / p=1..5 sweep (budget {budget:,}) | value |")
    print("|---|---:|")
    print(f"| scenarios whose mixer alone has at most {budget:,} gates: every one, timed | "
          f"{t_exact:.1f} s ({rows['exact']:,} exact rows, {rows['bound']:,} bound) |")  # fmt: skip
    print(f"| all others (bound): every {stride}th grid timed ({sampled_rows:,} rows), x {stride} | "
          f"{t_sampled * stride:.1f} s |")  # fmt: skip
    print(f"| total, one core | {t_exact + t_sampled * stride:.0f} s |")


def cli_sweep() -> None:
    """The whole sweep through the CLI, with the default depth policy and without depth (wall clock, peak RSS)."""
    root = Path(__file__).resolve().parents[1]
    env = {**os.environ, "PYTHONPATH": str(root / "src") + os.pathsep + os.environ.get("PYTHONPATH", "")}
    args = ["estimate", "--grid", "2x2..40x40", "--robots", "1..8", "-p", "1..5", "--format", "csv"]
    print()
    print(f"load average before (1, 5, 15 min): {', '.join(f'{x:.1f}' for x in os.getloadavg())}")
    print("| `qcpp estimate --grid 2x2..40x40 --robots 1..8 -p 1..5 --format csv` | wall | CPU | peak RSS | rows | "
          "exact |")  # fmt: skip
    print("|---|---:|---:|---:|---:|---:|")
    for extra in ([], ["--depth", "none"]):
        cmd = ["/usr/bin/time", "-f", "%U %S %M", sys.executable, "-m", "qcpp", *args, *extra]
        t = time.perf_counter()
        done = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=root, check=True)
        wall = time.perf_counter() - t
        user, system, rss_kb = done.stderr.strip().splitlines()[-1].split()
        cpu = float(user) + float(system)  # the machine is shared: CPU seconds are the figure that load moves least
        rss_gb = int(rss_kb) * 1024 / 1e9
        lines = done.stdout.splitlines()
        col = lines[0].split(",").index("depth_kind")
        exact = sum(1 for line in lines[1:] if line.split(",")[col] == "exact")
        print(f"| {' '.join(extra) or '(default: --depth auto)'} | {wall:.0f} s | {cpu:.0f} s | {rss_gb:.2f} GB | "
              f"{len(lines) - 1:,} | {exact:,} |")  # fmt: skip
    print(f"load average after (1, 5, 15 min): {', '.join(f'{x:.1f}' for x in os.getloadavg())}")


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--table-only", action="store_true", help="the per-scenario table alone")
    parser.add_argument("--sweep-only", action="store_true", help="the sweep table alone")
    parser.add_argument("--cli", action="store_true", help="the sweep through qcpp estimate instead")
    parser.add_argument("--stride", type=int, default=13, help="time every N-th certain-bound grid (default 13)")
    parser.add_argument("--budget", type=int, default=DEFAULT_OPTIONS.depth_budget, help="the sweep's depth budget")
    args = parser.parse_args(argv)
    if not args.sweep_only:
        per_scenario()
    if not args.table_only and not args.cli:
        sweep_depth(args.stride, args.budget)
    if args.cli:
        cli_sweep()
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
