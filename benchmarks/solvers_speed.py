"""Speed of the classical solvers (:mod:`qcpp.problem.solvers`) and how often the local searches find the optimum.

Two tables:

* ``dfs`` and ``cpsat`` side by side: exhaustive search -- paths per robot, assignments scored, wall-clock
  seconds, and the process's peak resident memory after the run (``ru_maxrss`` only grows; for two robots on
  5x5 it is dominated by :func:`qcpp.problem.cost.separable_cost`'s full pairwise matrix and its temporaries) --
  and CP-SAT (:func:`qcpp.problem.solvers.cpsat`, one worker): seconds to the proven optimum, when it first found
  it, and its cost (checked equal to DFS's);
* ``anneal`` / ``genetic`` with default settings over several seeds: mean seconds, the cost of seed 0, and in
  how many seeds the exhaustive optimum was found.

Usage::

    python benchmarks/solvers_speed.py              # 5 seeds
    python benchmarks/solvers_speed.py --seeds 20
    python benchmarks/solvers_speed.py --quick      # skip the 5x5 cases
"""

from __future__ import annotations

import argparse
import math
import resource
import time
from pathlib import Path

from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import anneal, cpsat, dfs, genetic

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB


def _scenarios(quick: bool) -> list[tuple[str, Scenario]]:
    out = [
        ("paper_3x3.toml (1 robot)", load_scenario(EXAMPLES / "paper_3x3.toml")),
        ("two_robots_4x4.toml", load_scenario(EXAMPLES / "two_robots_4x4.toml")),
        ("obstacles_hard_4x4.toml (1 robot)", load_scenario(EXAMPLES / "obstacles_hard_4x4.toml")),
    ]
    if not quick:
        out += [
            ("two_robots_5x5.toml", load_scenario(EXAMPLES / "two_robots_5x5.toml")),
            ("5x5 corner-to-corner, 2 robots", default_scenario(5, 5, 2)),
        ]
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seeds", type=int, default=5, help="seeds per local search (default 5)")
    parser.add_argument("--quick", action="store_true", help="skip the 5x5 cases")
    args = parser.parse_args()

    optimum: dict[str, float] = {}
    print("dfs (exhaustive) and cpsat (CP-SAT, 1 worker, proven optimum)")
    print(f"{'scenario':36} {'paths/robot':>14} {'assignments':>14} {'dfs s':>8} {'peak MB':>8} {'cost':>7} "
          f"{'cpsat s':>8} {'found at':>8} {'proven':>6}")
    for name, s in _scenarios(args.quick):
        t = time.perf_counter()
        sol = dfs(s)
        sec = time.perf_counter() - t
        optimum[name] = sol.cost.total
        peak = _peak_mb()
        exact = cpsat(s)
        assert math.isclose(exact.solution.cost.total, sol.cost.total, abs_tol=1e-9), name
        found = exact.time_to_cost(sol.cost.total)
        ppr = " x ".join(str(n) for n in sol.paths_per_robot)
        print(f"{name:36} {ppr:>14} {sol.evaluated:>14,} {sec:>8.2f} {peak:>8.0f} {sol.cost.total:>7g} "
              f"{exact.solution.seconds:>8.2f} {found if found is None else round(found, 2)!s:>8} "
              f"{'yes' if exact.proven_optimal else 'no':>6}", flush=True)

    print()
    print(f"anneal / genetic (defaults), seeds 0..{args.seeds - 1}")
    print(f"{'scenario':36} {'method':8} {'mean s':>7} {'max s':>7} {'cost(seed 0)':>12} {'optimum':>8} "
          f"{'found':>7} {'evaluated':>10}")
    for name, s in _scenarios(args.quick):
        if s.num_robots < 2:
            continue
        for method in (anneal, genetic):
            secs, found, first = [], 0, None
            for seed in range(args.seeds):
                sol = method(s, seed=seed)
                secs.append(sol.seconds)
                found += math.isclose(sol.cost.total, optimum[name], abs_tol=1e-9)
                first = first or sol
            assert first is not None
            print(f"{name:36} {method.__name__:8} {sum(secs) / len(secs):>7.2f} {max(secs):>7.2f} "
                  f"{first.cost.total:>12g} {optimum[name]:>8g} {found:>3}/{args.seeds:<3} {first.evaluated:>10,}",
                  flush=True)


if __name__ == "__main__":
    main()
