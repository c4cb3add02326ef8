"""The paper's two-robot experiment: simulated annealing finds the exhaustive-search optimum on 4x4 and 5x5.

For each scenario: exhaustive search (DFS, the exact optimum), one simulated-annealing run with the default
settings (20,000 iterations, 10 reheating cycles, SBF moves under the exact rule), and the same annealer from
20 seeds for its success rate and the spread of its cost curve. The script asserts that the headline run
reaches the DFS optimum (the same assignment, or another one of equal cost where the optimum is not unique).

The seed sweep passes ``components="initial"``: on these obstacle-free-of-walls grids every robot's feasible
paths form a single move-graph component, so this only skips the component analysis (the script checks that
the headline run's trace is identical either way).

Outputs: ``figures/annealing_<scenario>_paths.png`` (both robots' paths), ``figures/annealing_cost.png``
(SA cost curves), ``results/annealing_two_robots.md`` and ``results/annealing_two_robots.json`` (every row with
its scenario, options and the qcpp version; ``tests/simulate/results_freshness_test.py`` recomputes the 4x4 DFS
and the seeded SA run).

Run: ``python examples/experiments/annealing_two_robots.py [--quick]``
"""

from __future__ import annotations

import re
import sys
from collections.abc import Sequence
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np
from _common import EXAMPLES, Table, command_line, parse, pyplot, record, save_figure, write_records, write_results

from qcpp.cli.render import plot_paths, render_ascii
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import anneal, dfs

NAME = "annealing_two_robots"


def main(argv: Sequence[str] | None = None) -> dict[str, object]:
    opts = parse(__doc__.splitlines()[0], argv)
    files = ("two_robots_4x4",) if opts.quick else ("two_robots_4x4", "two_robots_5x5")
    iterations = 2000 if opts.quick else 20000
    seeds = list(range(opts.seed, opts.seed + (5 if opts.quick else 20)))

    timing = Table(
        "Exhaustive search (DFS) against simulated annealing (SA), two robots",
        ["scenario", "paths per robot", "assignments", "optimal assignments", "DFS cost", "DFS s",
         f"SA cost (seed {opts.seed})", "SA = DFS assignment", "SA s", "SA evaluations", "SA distinct scored",
         f"SA optimal in {len(seeds)} seeds", "SA s (mean over seeds)"],
    )
    curves, art, out, rows = {}, [], {}, []
    for name in files:
        s = load_scenario(EXAMPLES / f"{name}.toml")
        exact = dfs(s)
        sa = anneal(s, seed=opts.seed, iterations=iterations)
        assert sa.cost.total == exact.cost.total, f"{name}: annealing missed the DFS optimum"
        runs = [anneal(s, seed=k, iterations=iterations, components="initial") for k in seeds]
        assert runs[0].trace == sa.trace, "components='initial' changed the search"
        wins = sum(r.cost.total == exact.cost.total for r in runs)
        n_opt = _note_number(exact.notes, r"(\d+) optimal assignment")
        distinct = _note_number(sa.notes, r"(\d+) distinct assignments scored")
        timing.add(name, "x".join(map(str, exact.paths_per_robot)), exact.evaluated, n_opt, exact.cost.total,
                   exact.seconds, sa.cost.total, sa.paths == exact.paths, sa.seconds, sa.evaluated, distinct,
                   f"{wins}/{len(runs)}", float(np.mean([r.seconds for r in runs])))
        curves[name] = (sa, runs, exact.cost.total)
        art += [f"{name}: SA (seed {opts.seed}) paths, cost {sa.cost.total:g} "
                f"(c1 {sa.cost.c1:g}, c2 {sa.cost.c2:g}, c3 {sa.cost.c3:g}):", "", "```",
                render_ascii(s, sa.paths, legend=False), "```", ""]
        title = f"{s.name}: SA result, cost {sa.cost.total:g} (= DFS optimum)"
        print(f"wrote {plot_paths(s, sa.paths, opts.figures / f'annealing_{name}_paths.png', title=title)}")
        out[name] = {"dfs": exact, "anneal": sa, "runs": runs, "optimal_assignments": n_opt}
        rows += [
            record(s, {}, method="dfs", scenario_file=f"examples/{name}.toml", cost=exact.cost.total,
                   evaluated=exact.evaluated, paths_per_robot=list(exact.paths_per_robot),
                   optimal_assignments=_int(n_opt),
                   paths=list(exact.paths), seconds=exact.seconds),
            record(s, {"seed": opts.seed, "iterations": iterations}, method="anneal",
                   scenario_file=f"examples/{name}.toml", cost=sa.cost.total, evaluated=sa.evaluated,
                   distinct_scored=_int(distinct), paths=list(sa.paths), same_as_dfs=sa.paths == exact.paths,
                   seconds=sa.seconds),
            record(s, {"seeds": seeds, "iterations": iterations, "components": "initial"}, method="anneal_seeds",
                   scenario_file=f"examples/{name}.toml", costs=[r.cost.total for r in runs], successes=wins,
                   mean_seconds=float(np.mean([r.seconds for r in runs]))),
        ]
    print("\n".join(art))
    notes = [
        "DFS scores every combination of the robots' feasible paths with numpy (qcpp.problem.solvers.dfs); "
        "its time includes enumerating the paths.",
        "SA evaluations = cost look-ups (Solution.evaluated: 20,000 iterations + 50 calibration moves + 3); "
        "distinct scored = different assignments among them.",
        "Where several assignments share the optimal cost (mirror images), SA may return another one than DFS; "
        "'SA = DFS assignment' says whether it is the very same.",
    ]
    command = command_line(Path(__file__).name, opts)
    write_records(opts, NAME, command, rows)
    write_results(opts, NAME, command, [timing], notes, "\n".join(art))
    _figure(opts, curves)
    return out


def _note_number(notes: Sequence[str], pattern: str) -> str:
    """A number the solver reported in its notes (``?`` if the note is absent)."""
    for n in notes:
        m = re.search(pattern, n)
        if m:
            return m.group(1)
    return "?"


def _int(text: str) -> int | None:
    return int(text) if text.isdigit() else None


def _figure(opts, curves) -> None:  # type: ignore[no-untyped-def]
    plt = pyplot()
    fig, axes = plt.subplots(1, len(curves), figsize=(5.6 * len(curves), 3.8), squeeze=False)
    for ax, (name, (sa, runs, best)) in zip(axes[0], curves.items()):
        traces = np.array([r.trace for r in runs])
        xs = np.arange(1, traces.shape[1] + 1)
        lo, med, hi = np.percentile(traces, [10, 50, 90], axis=0)
        ax.fill_between(xs, lo, hi, step="post", alpha=0.25, color="tab:blue",
                        label=f"10-90% of {len(runs)} seeds")
        ax.step(xs, med, where="post", color="tab:blue", lw=1.2, ls="--", label="median")
        ax.step(xs, sa.trace, where="post", color="tab:orange", lw=1.8, label=f"seed {sa.seed}")
        ax.axhline(best, color="black", ls=":", lw=1.2, label=f"DFS optimum {best:g}")
        ax.set_xscale("log")
        ax.set_xlabel("SA iteration")
        ax.set_ylabel("best cost so far")
        ax.set_title(f"SA cost plot, {name}", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(frameon=False, fontsize=8)
    fig.tight_layout()
    save_figure(fig, opts.figures / "annealing_cost.png")
    plt.close(fig)


if __name__ == "__main__":
    main()
