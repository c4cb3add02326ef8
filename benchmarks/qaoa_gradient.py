"""Time and memory of one exact QAOA training gradient, per scenario and depth p.

What the default training (:func:`qcpp.training.layerwise.train_layerwise`) computes at every L-BFGS-B step is
:meth:`qcpp.simulate.subspace.SubspaceQAOA.objective_and_gradient` of the Gibbs objective: one forward sweep, the
objective's weights, one adjoint backward sweep. This script times exactly that call, per scenario and p,
each scenario in a fresh child process (so its peak memory is its own), after one warm-up call that loads the
numba kernels.

Columns:

* ``build s``: the robots' bases, rotation pairs and the compact cost diagonal (wall, and CPU in parentheses);
* per ``p``: ``grad s`` wall (CPU) of one objective-and-gradient call, the smallest of ``--repeat`` calls
  (CPU seconds add the threads' time; on a shared machine wall time also counts waiting for a core, so CPU
  seconds are the steadier figure and ``CPU/wall`` says how much of the two cores the call got);
* ``traced MB``: the call's own peak of Python-visible allocations (``tracemalloc``, which numpy reports to):
  the state arrays and temporaries of the gradient alone;
* ``peak RSS MB``: the child's peak resident set so far (``ru_maxrss``, which only grows): for the 5x5 scenario
  this is set by the build (``qcpp.problem.cost.separable_cost``'s full-size pairwise temporaries).

Usage::

    python benchmarks/qaoa_gradient.py                        # 4x4/2 at p = 1..8, 5x5/2 at p = 1..5
    python benchmarks/qaoa_gradient.py --only two_robots_5x5 --p 5
    python benchmarks/qaoa_gradient.py --quick                # 4x4/2 only
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
import tracemalloc
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
SCENARIOS = {"two_robots_4x4": (REPO / "examples/two_robots_4x4.toml", 8),
             "two_robots_5x5": (REPO / "examples/two_robots_5x5.toml", 5)}
BIG = {"two_robots_5x5"}


def _peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB


def _clock() -> tuple[float, float]:
    return time.perf_counter(), time.process_time()


def run_child(name: str, depths: list[int], repeat: int) -> dict[str, Any]:
    """Measure one scenario in this process (called in a child)."""
    import numpy as np

    from qcpp.problem.scenario_io import load_scenario
    from qcpp.simulate.subspace import SubspaceQAOA
    from qcpp.training.objectives import make_objective
    from qcpp.training.training import cost_scale, initial_angles

    path, _ = SCENARIOS[name]
    s = load_scenario(path)
    w0, c0 = _clock()
    q = SubspaceQAOA(s)
    q.cost_levels()
    build = (time.perf_counter() - w0, time.process_time() - c0)
    build_rss = _peak_rss_mb()
    objective = make_objective("gibbs", cost_scale(q))
    q.objective_and_gradient(initial_angles(q, 1, "linear-ramp"), objective)  # load the numba kernels
    rows = []
    for p in depths:
        angles = initial_angles(q, p, "random", seed=p)
        best: tuple[float, float] | None = None
        traced = 0.0
        for _ in range(repeat):
            tracemalloc.start()
            w0, c0 = _clock()
            value, grad = q.objective_and_gradient(angles, objective)
            t = (time.perf_counter() - w0, time.process_time() - c0)
            traced = max(traced, tracemalloc.get_traced_memory()[1] / 2**20)
            tracemalloc.stop()
            assert np.isfinite(value) and np.all(np.isfinite(grad)) and grad.shape == (2 * p,)
            best = t if best is None or t[0] < best[0] else best
        assert best is not None
        rows.append({"p": p, "wall": best[0], "cpu": best[1], "traced_mb": traced, "rss_mb": _peak_rss_mb()})
    return {"name": name, "dims": "x".join(map(str, q.dims)), "dimension": q.dimension, "build": build,
            "build_rss_mb": build_rss, "rows": rows}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", choices=sorted(SCENARIOS), help="run only these scenarios")
    ap.add_argument("--p", type=int, nargs="*", help="depths (default: 1..8 for 4x4, 1..5 for 5x5)")
    ap.add_argument("--repeat", type=int, default=1, help="calls per depth; the fastest is reported (default 1)")
    ap.add_argument("--quick", action="store_true", help="skip the 73.8-million-amplitude 5x5 scenario")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.repeat < 1:
        ap.error("--repeat must be >= 1")
    if args.p is not None and any(p < 1 for p in args.p):
        ap.error("--p: every depth must be >= 1")
    if args.child:
        print(json.dumps(run_child(args.child, args.p, args.repeat)))
        return
    names = args.only or [n for n in SCENARIOS if not (args.quick and n in BIG)]
    header = (f"{'scenario':<15} {'dims':>10} {'assignments':>12} {'build s':>15} {'p':>2} {'grad s':>16} "
              f"{'CPU/wall':>8} {'traced MB':>9} {'peak RSS MB':>11}")
    print(header)
    print("-" * len(header), flush=True)
    for name in names:
        depths = args.p or list(range(1, SCENARIOS[name][1] + 1))
        print(f"{name}: measuring p = {', '.join(map(str, depths))} in a child process", file=sys.stderr, flush=True)
        out = subprocess.run([sys.executable, __file__, "--child", name, "--repeat", str(args.repeat), "--p",
                              *map(str, depths)], capture_output=True, text=True)
        if out.returncode:
            tail = out.stderr.strip().splitlines()[-1] if out.stderr.strip() else f"exit {out.returncode}"
            print(f"{name:<15} failed: {tail}")
            continue
        r = json.loads(out.stdout.strip().splitlines()[-1])
        build = f"{r['build'][0]:6.2f} ({r['build'][1]:6.2f})"
        for k, row in enumerate(r["rows"]):
            lead = (f"{r['name']:<15} {r['dims']:>10} {r['dimension']:>12,} {build:>15}" if k == 0
                    else " " * 55)
            print(f"{lead} {row['p']:>2} {row['wall']:7.2f} ({row['cpu']:6.2f}) {row['cpu'] / row['wall']:8.2f} "
                  f"{row['traced_mb']:9,.0f} {row['rss_mb']:11,.0f}", flush=True)
    print(f"grad: one Gibbs objective-and-gradient call of the default training, wall s (CPU s); "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at the end (other processes share the "
          "cores)")


if __name__ == "__main__":
    main()
