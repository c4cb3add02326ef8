"""Speed and memory of the feasible-subspace QAOA simulator (:mod:`qcpp.simulate.subspace`).

Every scenario runs in a fresh child process so its peak resident memory (``ru_maxrss``) is its own. For each
one the table gives the state dimension, then wall-clock seconds (and CPU seconds of the process in
parentheses, which are less disturbed by other load on the machine) for

* ``build``: the robots' bases and rotation pairs plus the compact cost diagonal,
* ``E``: one expectation value at depth ``p``,
* ``grad``: one expectation value with its exact gradient (adjoint method),

and the process's peak resident memory (``ru_maxrss``, which only grows) after the build, after the expectation
and after the gradient. For two robots the build's peak comes from :func:`qcpp.problem.cost.separable_cost`'s
full-size pairwise temporaries; an expectation then holds the state (16 bytes per amplitude) plus one byte
of cost level per amplitude, a gradient two states.

Usage::

    python benchmarks/subspace_speed.py            # all scenarios, p = 1
    python benchmarks/subspace_speed.py --quick    # skip the 72-million-amplitude 5x5 case
    python benchmarks/subspace_speed.py --p 2 --only 4x4-two
    python benchmarks/subspace_speed.py --p 5 --only 5x5-example   # goal: gradient in < 30 s, < 4 GB
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

SCENARIOS: dict[str, dict[str, Any]] = {
    "3x3-one": {"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]},
    "5x5-one": {"grid": {"rows": 5, "cols": 5}, "robots": [{"start": [0, 0], "goal": [4, 4]}]},
    "4x4-two": {
        "grid": {"rows": 4, "cols": 4},
        "robots": [{"start": [0, 0], "goal": [3, 3]}, {"start": [0, 3], "goal": [3, 0]}],
    },
    "3x4-three": {
        "grid": {"rows": 3, "cols": 4},
        "robots": [
            {"start": [0, 0], "goal": [2, 3]},
            {"start": [0, 3], "goal": [2, 0]},
            {"start": [1, 0], "goal": [1, 3]},
        ],
    },
    "5x5-two": {
        "grid": {"rows": 5, "cols": 5},
        "robots": [{"start": [0, 0], "goal": [4, 4]}, {"start": [0, 4], "goal": [4, 0]}],
    },
    "5x5-example": "examples/two_robots_5x5.toml",
}
BIG = {"5x5-two", "5x5-example"}
REPO = Path(__file__).resolve().parents[1]


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB


def _timed(fn: Any) -> tuple[Any, float, float]:
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c


def run_one(name: str, p: int, kernels: str) -> dict[str, Any]:
    """Measure one scenario in this process (called in a child)."""
    from qcpp.problem.scenario import scenario_from_dict
    from qcpp.problem.scenario_io import load_scenario
    from qcpp.simulate.subspace import SubspaceQAOA

    spec = SCENARIOS[name]
    s = load_scenario(REPO / spec) if isinstance(spec, str) else scenario_from_dict(spec)
    angles = np.tile([0.1, 0.7], p)
    SubspaceQAOA(scenario_from_dict(SCENARIOS["4x4-two"]), kernels=kernels).gradient([0.1, 0.2])  # load the JIT

    def build() -> SubspaceQAOA:
        q = SubspaceQAOA(s, kernels=kernels)  # type: ignore[arg-type]
        q.cost_levels()
        return q

    q, bw, bc = _timed(build)
    build_mb = _peak_mb()
    e, ew, ec = _timed(lambda: q.expectation(angles))
    e_mb = _peak_mb()
    (e2, _), gw, gc = _timed(lambda: q.value_and_gradient(angles))
    g_mb = _peak_mb()
    assert abs(e - e2) <= 1e-9 * max(1.0, abs(e))
    return {
        "name": name,
        "dims": "x".join(map(str, q.dims)),
        "dimension": q.dimension,
        "p": p,
        "build": (bw, bc),
        "expectation": (ew, ec),
        "gradient": (gw, gc),
        "peak_build_mb": build_mb,
        "peak_e_mb": e_mb,
        "peak_grad_mb": g_mb,
        "energy": e,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--p", type=int, default=1, help="QAOA depth (default 1)")
    ap.add_argument("--quick", action="store_true", help="skip the 5x5 two-robot case")
    ap.add_argument("--only", nargs="*", choices=sorted(SCENARIOS), help="run only these scenarios")
    ap.add_argument("--kernels", choices=["auto", "numba", "blas"], default="auto", help="mixer kernels")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        print(json.dumps(run_one(args.child, args.p, args.kernels)))
        return
    names = args.only or [n for n in SCENARIOS if not (args.quick and n in BIG)]
    header = (
        f"{'scenario':<12} {'dims':>11} {'dimension':>11} {'p':>2} {'build s':>14} {'E s':>14} "
        f"{'grad s':>14} {'peak MB: build':>15} {'E':>6} {'grad':>6}"
    )
    print(header)
    print("-" * len(header))
    for name in names:
        out = subprocess.run(
            [sys.executable, __file__, "--child", name, "--p", str(args.p), "--kernels", args.kernels],
            capture_output=True, text=True,
        )
        if out.returncode:
            print(f"{name:<12} failed: {out.stderr.strip().splitlines()[-1] if out.stderr else out.returncode}")
            continue
        r = json.loads(out.stdout.strip().splitlines()[-1])

        def fmt(t: list[float]) -> str:
            return f"{t[0]:6.2f} ({t[1]:5.2f})"

        print(
            f"{r['name']:<12} {r['dims']:>11} {r['dimension']:>11,} {r['p']:>2} {fmt(r['build']):>14} "
            f"{fmt(r['expectation']):>14} {fmt(r['gradient']):>14} {r['peak_build_mb']:>15,.0f} "
            f"{r['peak_e_mb']:>6,.0f} {r['peak_grad_mb']:>6,.0f}",
            flush=True,
        )
    print("times: wall seconds (process CPU seconds, all threads); peak MB: the child's peak resident set after "
          f"each stage; kernels {args.kernels}; {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} "
          "at the end (other processes share the cores)")


if __name__ == "__main__":
    main()
