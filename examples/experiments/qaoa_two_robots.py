"""Beyond the paper: QAOA for two robots (4x4 and 5x5) on the subspace simulator, against simulated annealing.

For each scenario and depth p the angles are fitted three ways on the exact feasible-subspace state:

* ``<C>``: the usual QAOA objective, the expectation of the cost;
* ``CVaR``: the mean cost of the cheapest ``ALPHA = 0.2`` of the measurement distribution (Barkoutsos et al.,
  2020), which rewards weight on the best outcomes rather than a low average;
* ``max p_opt`` (4x4 only): the probability of the optimum itself, maximised. This needs the optimum, so it is
  no algorithm: it is a reference for how much weight any angles at that depth can put on the optimum (as
  far as a local optimiser from several starts finds).

Budgets (every fit keeps the best of its starts):

* 4x4 (178 x 178 = 31,684 assignments), p = 1..4: ``<C>`` by L-BFGS-B with exact adjoint gradients (100
  iterations) from the linear ramp and 5 random starts; CVaR and p_opt by COBYLA (200 evaluations) from the
  same 6 starts.
* 5x5 (8,590 x 8,590 = 73.8 million assignments; ~6-15 s per simulation here): p = 1 by a scan of beta_0 over
  10 values in [0, pi] (gamma_0 is irrelevant at p = 1: the initial state is a single basis state, so the first
  phase separator is a global phase); p = 2 by COBYLA with 12 evaluations per objective, from the best p = 1
  angles followed by the linear ramp's second-layer gamma and half that beta; p = 3, CVaR only, the same way
  from the p = 2 CVaR angles. No optimal assignment can carry amplitude below p = 3 here, whatever the angles
  (``qcpp.simulate.state_measures.layers_to_reach``), so p = 3 is the first depth at which p_opt can be non-zero.

Success at equal cost evaluations (see ``qcpp.simulate.success``): QAOA sampled ``S`` times from its trained
state succeeds with ``1 - (1 - p_opt)^S`` (training not counted); simulated annealing with an iteration
budget succeeds with its empirical rate over 50 seeds, plotted at its mean number of cost evaluations;
uniform sampling of feasible assignments succeeds with ``1 - (1 - n_opt/N)^S``.

Outputs: ``figures/qaoa_two_robots.png``, ``results/qaoa_two_robots.md`` and ``results/qaoa_two_robots.json``
(every row with its scenario, options and the qcpp version; ``tests/simulate/results_freshness_test.py``
recomputes the circuit columns and, on 4x4, the state's ``<C>`` and P(optimum) at the recorded angles).
Run: ``python examples/experiments/qaoa_two_robots.py [--quick]`` (full run: about 13 minutes on 2 cores).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Sequence
from concurrent.futures import Future, ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np
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

from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import dfs
from qcpp.simulate.annealing_runs import AnnealSuccess, anneal_success
from qcpp.simulate.state_measures import layers_to_reach, state_metrics, uniform_hit_probability
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.simulate.success import shots_for, success_probability
from qcpp.training.angle_fit import OBJECTIVES, AngleFit, fit_angles
from qcpp.training.training import initial_angles, interp_angles, train

NAME = "qaoa_two_robots"
ALPHA = 0.2
LARGE_EVALS = 12  # COBYLA evaluations per fit on 5x5 (~10-15 s each)
LABELS = {"expectation": "<C>", "cvar": f"CVaR_{ALPHA}", "p_optimum": "max p_opt (reference)"}


def main(argv: Sequence[str] | None = None) -> dict[str, object]:
    opts = parse(__doc__.splitlines()[0], argv)
    quick = opts.quick
    plan = {"two_robots_4x4": "full"} if quick else {"two_robots_4x4": "full", "two_robots_5x5": "budget"}
    budgets = [10, 100, 1000] if quick else [10, 30, 100, 300, 1000, 3000, 10000]
    seeds = list(range(opts.seed, opts.seed + (8 if quick else 50)))
    scenarios = {name: load_scenario(EXAMPLES / f"{name}.toml") for name in plan}
    optima = {name: dfs(s).cost.total for name, s in scenarios.items()}

    # simulated annealing runs in a second process while this one simulates QAOA (full mode)
    pool = None if quick else ProcessPoolExecutor(max_workers=1)
    pending: dict[str, Future[list[AnnealSuccess]] | list[AnnealSuccess]] = {}
    for name, s in scenarios.items():
        args = (s, budgets, seeds, optima[name])
        pending[name] = (pool.submit(anneal_success, *args, components="initial") if pool
                         else anneal_success(*args, components="initial"))

    fits: dict[str, dict[tuple[int, str], AngleFit]] = {}
    info: dict[str, dict[str, float]] = {}
    for name, s in scenarios.items():
        t0 = time.perf_counter()
        q = SubspaceQAOA(s)
        assert q.optimum()[0] == optima[name], "the subspace optimum differs from DFS"
        info[name] = {"dimension": q.dimension, "n_opt": len(q.optimum()[1]), "uniform": uniform_hit_probability(q),
                      "initial": float(q.cost_diagonal().reshape(-1)[0]), "build": time.perf_counter() - t0,
                      "reach": min(layers_to_reach(q, a) or 10**9 for a in q.optimal_assignments())}
        if plan[name] == "full":
            fits[name] = _fit_small(q, (1, 2) if quick else (1, 2, 3, 4), quick, opts.seed)
        else:
            fits[name] = _fit_large(q)
    sa = {name: (f.result() if isinstance(f, Future) else f) for name, f in pending.items()}
    if pool:
        pool.shutdown()

    tables = []
    for name in scenarios:
        d = info[name]
        t = Table(
            f"QAOA on {name} ({d['dimension']:,} assignments, optimum {optima[name]:g}, initial paths cost "
            f"{d['initial']:g}; an optimum can carry amplitude from p = {d['reach']} on)",
            ["p", "objective", "<C>", f"CVaR_{ALPHA}", "p_opt", "shots for 50%", "shots for 99%", "simulations",
             "seconds", "angles [g0, b0, ...]"],
        )
        for (p, obj), f in sorted(fits[name].items(), key=lambda kv: (kv[0][0], OBJECTIVES.index(kv[0][1]))):
            m = f.metrics
            t.add(p, LABELS[obj], m.expectation, m.cvar, m.p_optimum, _shots(m.p_optimum, 0.5),
                  _shots(m.p_optimum, 0.99), f.evaluations, f.seconds,
                  "[" + ", ".join(f"{a:.3f}" for a in f.angles) + "]")
        tables.append(t)
    for name in scenarios:
        pe_top, pc_top = _deepest(fits[name], "expectation"), _deepest(fits[name], "cvar")
        c = Table(
            f"{name}: probability of having seen an optimum after S cost evaluations",
            ["SA iterations", "S = SA evaluations (mean)", f"SA success ({len(seeds)} seeds) [95% CI]",
             f"QAOA <C>, p={pe_top}", f"QAOA CVaR, p={pc_top}", "uniform sampling"],
        )
        for r in sa[name]:
            lo, hi = r.interval()
            pe = fits[name][(pe_top, "expectation")].metrics.p_optimum
            pc = fits[name][(pc_top, "cvar")].metrics.p_optimum
            c.add(r.iterations, r.evaluations, f"{r.rate:.2f} [{lo:.2f}, {hi:.2f}]",
                  float(success_probability(pe, r.evaluations)), float(success_probability(pc, r.evaluations)),
                  float(success_probability(info[name]["uniform"], r.evaluations)))
        tables.append(c)
    notes = [
        "p_opt: exact probability of the optimal assignment(s) in the fitted state. shots for X%: fewest "
        "measurements of that state that see an optimum with probability X (inf: never).",
        "QAOA columns count only the S shots from the trained state; training is not counted (on hardware every "
        "expectation value in it costs many shots), so they are QAOA's most favourable reading.",
        "SA: qcpp.problem.solvers.anneal with the given iteration budget (schedule fitted to it), components='initial' "
        "(one move-graph component here); S = its Solution.evaluated (50 calibration moves included).",
        *(f"{n}: {info[n]['n_opt']:g} optimal assignment(s); uniform hit probability {info[n]['uniform']:.3g}; "
          f"subspace simulator built in {info[n]['build']:.1f} s." for n in scenarios),
    ]
    command = command_line(Path(__file__).name, opts)
    write_records(opts, NAME, command, _rows(scenarios, plan, fits, sa, quick, seeds))
    write_results(opts, NAME, command, tables, notes)
    _figure(opts, fits, sa, info, len(seeds))
    return {"fits": fits, "anneal": sa, "info": info, "optima": optima}


def _rows(scenarios, plan, fits, sa, quick: bool, seeds: list[int]) -> list[dict[str, object]]:  # type: ignore[no-untyped-def]
    """One record per fit (scenario, depth, objective) and per SA budget."""
    rows = []
    for name, s in scenarios.items():
        if plan[name] == "full":
            budget = {"schedule": "full", "starts": "linear ramp + " + ("1" if quick else "5") + " seeded random",
                      "maxiter": 30 if quick else 200, "<C>": "lbfgsb", "cvar, p_optimum": "cobyla"}
        else:
            budget = {"schedule": "budget", "p1": "beta scan, 10 values", "cobyla_evaluations": LARGE_EVALS}
        circuits = {p: circuit_columns(s, p) for p in sorted({p for p, _ in fits[name]})}
        for (p, obj), f in sorted(fits[name].items(), key=lambda kv: (kv[0][0], OBJECTIVES.index(kv[0][1]))):
            m = f.metrics
            rows.append(record(s, {**budget, "objective": obj, "alpha": ALPHA}, method="qaoa",
                               scenario_file=f"examples/{name}.toml", p=p, objective=obj, expectation=m.expectation,
                               cvar=m.cvar, p_opt=m.p_optimum, evaluations=f.evaluations, seconds=f.seconds,
                               angles=list(f.angles), **circuits[p]))
        for r in sa[name]:
            rows.append(record(s, {"iterations": r.iterations, "seeds": seeds, "components": "initial"},
                               method="anneal", scenario_file=f"examples/{name}.toml", runs=r.runs,
                               successes=r.successes, evaluations=r.evaluations, seconds=r.seconds))
    return rows


def _shots(p: float, target: float) -> float:
    n = shots_for(p, target) if p > 1e-15 else float("inf")
    return float(n) if n > 1e6 else n  # large counts print as 1.2e+10


def _deepest(fits: dict[tuple[int, str], AngleFit], objective: str) -> int:
    return max(p for p, o in fits if o == objective)


def _fit_small(q: SubspaceQAOA, layers: Sequence[int], quick: bool, seed: int) -> dict[tuple[int, str], AngleFit]:
    """All three objectives at every depth, best of the linear ramp and random starts."""
    n_random = 1 if quick else 5
    maxiter = 30 if quick else 200
    out = {}
    for p in layers:
        starts = [initial_angles(q, p, "linear-ramp")]
        starts += [initial_angles(q, p, "random", seed=seed + 1000 * p + k) for k in range(n_random)]
        runs = [train(q, p, "lbfgsb", init=x0, maxiter=maxiter // 2) for x0 in starts]
        out[(p, "expectation")] = AngleFit.from_training(q, runs, ALPHA)
        for obj in ("cvar", "p_optimum"):
            out[(p, obj)] = fit_angles(q, starts, obj, ALPHA, maxiter=maxiter)  # type: ignore[arg-type]
    return out


def _fit_large(q: SubspaceQAOA) -> dict[tuple[int, str], AngleFit]:
    """p = 1 by a beta scan, p = 2 by short COBYLA runs, p = 3 (CVaR only) likewise (see the module docstring)."""
    out = {}
    t0 = time.perf_counter()
    betas = np.linspace(0.0, np.pi, 10)
    scan = [state_metrics(q, [0.0, b], ALPHA) for b in betas]
    scan_s = time.perf_counter() - t0
    ramp = initial_angles(q, 3, "linear-ramp")
    for obj, key in (("expectation", lambda m: m.expectation), ("cvar", lambda m: m.cvar)):
        k = int(np.argmin([key(m) for m in scan]))
        x1 = [0.0, float(betas[k])]
        out[(1, obj)] = AngleFit(1, obj, ALPHA, tuple(x1), tuple(x1), key(scan[k]), scan[k],
                                 tuple(key(m) for m in scan), len(betas), 1, scan_s)
        x2 = interp_angles(x1)
        x2[2], x2[3] = ramp[2], x2[3] / 2
        out[(2, obj)] = fit_angles(q, [x2], obj, ALPHA, maxiter=LARGE_EVALS)  # type: ignore[arg-type]
    x3 = interp_angles(out[(2, "cvar")].angles)
    x3[4], x3[5] = ramp[4], x3[5] / 2
    out[(3, "cvar")] = fit_angles(q, [x3], "cvar", ALPHA, maxiter=LARGE_EVALS)
    return out


def _figure(opts, fits, sa, info, runs: int) -> None:  # type: ignore[no-untyped-def]
    plt = pyplot()
    names = list(fits)
    fig, axes = plt.subplots(len(names), 2, figsize=(12, 4.2 * len(names)), squeeze=False)
    colours = {"expectation": "tab:blue", "cvar": "tab:green", "p_optimum": "tab:purple"}
    floor = 1e-12
    for row, name in zip(axes, names):
        ax = row[0]
        for obj, colour in colours.items():
            pts = sorted((p, f.metrics.p_optimum) for (p, o), f in fits[name].items() if o == obj)
            if pts:
                ps, vals = zip(*pts)
                ax.plot(ps, np.maximum(vals, floor), "o-", color=colour, label=LABELS[obj])
        ax.axhline(info[name]["uniform"], color="grey", ls="--", label="uniform over feasible")
        reach = info[name]["reach"]
        if reach > 1:
            ax.axvspan(0.6, reach - 0.5, color="tab:red", alpha=0.08, label="p_opt = 0 for all angles (unreachable)")
        ax.set_yscale("log")
        ax.set_ylim(floor / 2, 1.5)
        depths = sorted({p for p, _ in fits[name]})
        ax.set_xticks(depths)
        ax.set_xlim(0.6, depths[-1] + 0.4)
        ax.set_xlabel("QAOA depth p")
        ax.set_ylabel(f"p_opt (values below {floor:g} drawn at {floor:g})")
        ax.set_title(f"{name}: probability of the optimum in the fitted state", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(frameon=False, fontsize=8, loc="center right")

        ax = row[1]
        xs = np.logspace(0, 5, 300)
        for obj, colour in colours.items():
            if any(o == obj for _, o in fits[name]):
                top = _deepest(fits[name], obj)
                pt = fits[name][(top, obj)].metrics.p_optimum
                ax.plot(xs, success_probability(pt, xs), color=colour,
                        label=f"QAOA {LABELS[obj]}, p={top} (p_opt {pt:.2g})")
        ax.plot(xs, success_probability(info[name]["uniform"], xs), color="grey", ls="--", label="uniform sampling")
        ev = [r.evaluations for r in sa[name]]
        rate = [r.rate for r in sa[name]]
        ci = np.array([r.interval() for r in sa[name]])
        ax.errorbar(ev, rate, yerr=[np.subtract(rate, ci[:, 0]), np.subtract(ci[:, 1], rate)], fmt="s",
                    color="tab:red", capsize=3, label=f"simulated annealing ({runs} seeds, 95% CI)")
        ax.set_xscale("log")
        ax.set_ylim(-0.03, 1.03)
        ax.set_xlabel("S = cost evaluations (QAOA: shots from the trained state, training not counted)")
        ax.set_ylabel("P(optimum seen)")
        ax.set_title(f"{name}: success at equal cost evaluations", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(frameon=False, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    fig.tight_layout()
    save_figure(fig, opts.figures / f"{NAME}.png")
    plt.close(fig)


if __name__ == "__main__":
    main()
