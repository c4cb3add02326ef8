"""The paper's QAOA experiment: one robot on a 3x3 grid, p = 1..3, against exhaustive search and annealing.

Trains the constrained-mixer QAOA on the exact feasible-subspace simulator with Nesterov momentum, step 0.1
(the paper's optimiser and step), from the deterministic linear-ramp start, twice per p:

* on ``E / sigma`` (``train``'s default ``normalize=True``; ``sigma`` = the cost's standard deviation over the
  feasible paths), the run whose results are reported and asserted;
* on the raw ``E`` (``normalize=False``, the paper's literal objective), drawn for comparison.

At every p the most probable path must be the exhaustive-search (DFS) optimum and the simulated-annealing
result; the script asserts this. Outputs: ``figures/qaoa_3x3_cost.png`` (training traces),
``figures/qaoa_3x3_initial.png`` and ``figures/qaoa_3x3_optimum.png`` (the paper's "initial state and optimal
path"), ``results/qaoa_3x3.md`` and ``results/qaoa_3x3.json`` (every row with its scenario, options and the qcpp
version; ``tests/simulate/results_freshness_test.py`` recomputes the circuit columns, DFS, the seeded SA run
and P(optimum) at the recorded angles).

Run: ``python examples/experiments/qaoa_3x3.py [--quick]``
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import (
    EXAMPLES,
    Table,
    circuit_columns,
    command_line,
    parse,
    pyplot,
    record,
    save_figure,
    write_records,
    write_results,
)

from qcpp.cli.render import plot_paths, render_ascii
from qcpp.problem.paths import initial_path, path_to_nodes
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import anneal, dfs
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.training import cost_scale, most_probable, train

NAME = "qaoa_3x3"
STEP = 0.1  # the paper's Nesterov step


def main(argv: Sequence[str] | None = None) -> dict[str, object]:
    opts = parse(__doc__.splitlines()[0], argv)
    layers = (1, 2) if opts.quick else (1, 2, 3)
    maxiter = 15 if opts.quick else 100
    s = load_scenario(EXAMPLES / "paper_3x3.toml")
    start = s.robots[0].start

    exact = dfs(s)
    sa_iterations = 2000 if opts.quick else 20000
    sa = anneal(s, seed=opts.seed, iterations=sa_iterations)
    assert sa.cost.total == exact.cost.total and sa.paths == exact.paths, "annealing missed the DFS optimum"
    q = SubspaceQAOA(s)
    sigma = cost_scale(q)

    results, raw = {}, {}
    for p in layers:
        results[p] = train(q, p, "nesterov", init="linear-ramp", maxiter=maxiter, step=STEP, normalize=True)
        raw[p] = train(q, p, "nesterov", init="linear-ramp", maxiter=maxiter, step=STEP, normalize=False)

    table = Table(
        f"QAOA on {s.name}: Nesterov, step {STEP} on E/sigma (sigma = {sigma:.4g}), linear-ramp start, "
        f"{maxiter} steps",
        ["p", "E start", "E final", "p_opt", "most probable path", "its probability", "= DFS = SA",
         "E final (raw E, paper's literal)", "p_opt (raw E)", "angles [g0, b0, ...]"],
    )
    found = {}
    for p in layers:
        r = results[p]
        masks, prob = most_probable(q, r.angles)
        found[p] = masks
        ok = masks == exact.paths == sa.paths
        table.add(p, r.initial_expectation, r.expectation, r.p_optimum, _nodes(s, masks[0], start), prob, ok,
                  raw[p].expectation, raw[p].p_optimum, "[" + ", ".join(f"{a:.3f}" for a in r.angles) + "]")
    summary = Table(
        "Classical baselines",
        ["method", "cost", "path", "evaluated", "seconds"],
    )
    summary.add("DFS (exhaustive)", exact.cost.total, _nodes(s, exact.paths[0], start), exact.evaluated, exact.seconds)
    summary.add(f"SA (seed {opts.seed})", sa.cost.total, _nodes(s, sa.paths[0], start), sa.evaluated, sa.seconds)

    init = (initial_path(s, 0),)
    art = [
        "Initial path (the QAOA initial state):", "", "```", render_ascii(s, init, legend=False), "```", "",
        "Optimal path (DFS = SA = most probable QAOA outcome at every p):", "", "```",
        render_ascii(s, exact.paths, legend=False), "```", "",
    ]
    print("\n".join(art))
    notes = [
        f"{q.dimension} feasible paths; the optimum (cost {exact.cost.total:g}) is unique.",
        "p_opt = probability of the optimal path in the trained state (exact, no sampling).",
        "The initial state is one basis state (the initial path), so gamma_0 only adds a global phase: at p = 1 "
        "the mixer angle alone moves the weight; the ordered partial mixers at beta near pi act as a chain of "
        "SBF swaps that carries the initial path to the optimum four moves away.",
        f"Raw E (normalize=False): the gradients are in the tens (cost spread sigma = {sigma:.3g}), so step 0.1 "
        "overshoots and the trace oscillates (the figure's dashed lines); E/sigma makes the step scale-free.",
    ]
    command = command_line(Path(__file__).name, opts)
    rows = []
    for p in layers:
        circuit = circuit_columns(s, p)
        for normalize, runs in ((True, results), (False, raw)):
            r = runs[p]
            options = {"optimizer": "nesterov", "step": STEP, "init": "linear-ramp", "maxiter": maxiter,
                       "normalize": normalize}
            rows.append(record(s, options, method="qaoa", p=p, e_start=r.initial_expectation, e_final=r.expectation,
                               p_opt=r.p_optimum, angles=list(r.angles), **circuit,
                               most_probable=list(found[p]) if normalize else None))
    rows.append(record(s, {}, method="dfs", cost=exact.cost.total, evaluated=exact.evaluated,
                       paths=list(exact.paths), seconds=exact.seconds))
    rows.append(record(s, {"seed": opts.seed, "iterations": sa_iterations},
                       method="anneal", cost=sa.cost.total, evaluated=sa.evaluated, paths=list(sa.paths),
                       seconds=sa.seconds))
    write_records(opts, NAME, command, rows)
    write_results(opts, NAME, command, [table, summary], notes, "\n".join(art))
    _figures(opts, s, results, raw, exact.cost.total, init, exact.paths)
    for p in layers:
        assert found[p] == exact.paths, f"p={p}: the most probable path is not the DFS optimum"
    return {"results": results, "raw": raw, "dfs": exact, "anneal": sa, "most_probable": found}


def _nodes(s: object, mask: int, start: tuple[int, int]) -> str:
    return "-".join(f"{r}{c}" for r, c in path_to_nodes(s.grid, mask, start))  # type: ignore[attr-defined]


def _figures(opts, s, results, raw, optimum, init, best) -> None:  # type: ignore[no-untyped-def]
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, runs, label in ((axes[0], results, "Nesterov on E/sigma (reported)"),
                            (axes[1], raw, "Nesterov on raw E (paper's literal objective)")):
        for p, r in runs.items():
            ax.plot(range(len(r.trace)), r.trace, lw=1.8, ls="-" if runs is results else "--", label=f"p = {p}")
        ax.axhline(optimum, color="black", ls=":", lw=1.2, label=f"optimum {optimum:g}")
        ax.set_xlabel("Nesterov step")
        ax.set_title(f"{label}, step {STEP}", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right", framealpha=0.95)
    axes[0].set_ylabel("expectation <C>")
    fig.suptitle(f"QAOA cost curves, {s.name}", fontsize=11)
    fig.tight_layout()
    save_figure(fig, opts.figures / f"{NAME}_cost.png")
    plt.close(fig)
    for tag, paths, title in (("initial", init, "Initial state (initial path)"),
                              ("optimum", best, "Optimal path: QAOA (p = 1..3) = DFS = SA")):
        print(f"wrote {plot_paths(s, paths, opts.figures / f'{NAME}_{tag}.png', title=title)}")


if __name__ == "__main__":
    main()
