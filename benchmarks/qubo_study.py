"""QUBO for annealers: feasibility and success against the penalty P, reads and time, against CP-SAT and SBF annealing.

For every scenario (default corner-to-corner robots, no obstacles, 3x3..6x6, 1..3 robots):

* CP-SAT's optimum (``qcpp.problem.solvers.cpsat``, proven unless ``--cpsat-limit`` stops it: marked ``*``);
* the ``paper`` QUBO and the ``per-robot`` QUBO at ``P = rule / 4, rule / 2, rule`` (the rule:
  ``qcpp.qubo.model.penalty_rule``), each sampled by dwave-samplers' simulated annealing (``sa``: ``--reads`` reads,
  1000 sweeps) and tabu search (``tabu``: ``--reads`` reads, one tabu run each). Per run: % of reads feasible as
  sampled, % repairable (right degrees: a path plus cycles; the cycles dropped), % of reads at the optimum after
  repair and before any polishing, the best repaired read, the answer after SBF polishing (steepest descent from
  up to 100 best distinct repaired reads, i.e. all of them at 100 reads) and the wall time;
* qcpp's own SBF simulated annealing (``qcpp.problem.solvers.anneal``, default 20,000 iterations): how many of
  ``--seeds`` seeds reach the optimum, and the mean time.

A third table varies the sampler's effort (reads, tabu runs per read, SA sweeps per read) on the two-robot
5x5 and 6x6 scenarios at the rule's P, over ``--seeds`` seeds: how often a read (before polishing) and the
polished answer reach the optimum, and the time.

A fourth table (``--only sweeps`` prints it alone) asks how often a single read reaches the optimum on seeded
random instances with obstacles (``qcpp.ensemble``, density 0.1, seed 0; ``--sweep-cells``, ``--sweep-instances``):
simulated annealing at 100, 1,000 and 10,000 sweeps per read against tabu search (one run per read), 100 reads at
the rule's P, the instance's index as the sampler's seed. Per cell and sampler: the median [quartiles] over the
instances of the % of reads at CP-SAT's optimum after repair and before polishing, on how many instances at least
one read was, on how many the polished answer was, and the median time per run.

Prints markdown tables: every run and the effort sweep (docs/qubo.md), a per-scenario summary (the README) and
the sweeps table (docs/qubo.md).

Run:  PYTHONPATH=src python benchmarks/qubo_study.py            (about 15 minutes on the 2-core machine, and the
                                                                sweeps table's 6 more)
      PYTHONPATH=src python benchmarks/qubo_study.py --sizes 3,4 --robots 1,2   (a quick look)
      PYTHONPATH=src python benchmarks/qubo_study.py --only sweeps               (the sweeps table alone)
"""

from __future__ import annotations

import argparse
import sys
import time

from qcpp.problem.presets import default_scenario
from qcpp.problem.solvers import anneal, cpsat
from qcpp.problem.solvers.moves import CostCache
from qcpp.qubo.model import paper_bqm, penalty_rule
from qcpp.qubo.solve import drop_cycles, sample_bqm, solve_qubo

TOL = 1e-9


def _paper_run(s, sampler: str, reads: int, seed: int, opt: float) -> dict:  # type: ignore[no-untyped-def]
    """The paper form: sample, decode, repair (no polishing needed to show the point)."""
    from qcpp.problem.paths import is_feasible
    from qcpp.qubo.model import decode_edges

    m = paper_bqm(s)
    t0 = time.perf_counter()
    bits, energies = sample_bqm(m, sampler=sampler, reads=reads, seed=seed)  # type: ignore[arg-type]
    cost = CostCache(s)
    feas = rep = at_opt = 0
    best = None
    for row in bits:
        masks = decode_edges(s, m, row)
        feas += all(is_feasible(s, r, mk) for r, mk in enumerate(masks))
        fixed = tuple(drop_cycles(s, r, mk) for r, mk in enumerate(masks))
        if all(f is not None for f in fixed):
            rep += 1
            c = cost(fixed)  # type: ignore[arg-type]
            at_opt += abs(c - opt) <= TOL
            best = c if best is None else min(best, c)
    return {"feasible": feas, "repairable": rep, "at_opt": at_opt, "best_read": best, "final": None,
            "lowest_energy": float(energies.min()), "seconds": time.perf_counter() - t0, "reads": len(bits)}


def _per_robot_run(s, penalty: float, sampler: str, reads: int, seed: int, opt: float) -> dict:  # type: ignore[no-untyped-def]
    t0 = time.perf_counter()
    run = solve_qubo(s, penalty=penalty, sampler=sampler, reads=reads, seed=seed)  # type: ignore[arg-type]
    secs = time.perf_counter() - t0
    # reads at the optimum before polishing: at_best counts reads at the answer's cost, which is the optimum
    # only when the answer is optimal
    final = run.solution.cost.total
    at_opt = run.at_best if abs(final - opt) <= TOL else 0
    return {"feasible": run.feasible, "repairable": run.repairable, "at_opt": at_opt, "best_read": run.best_read_cost,
            "final": final, "lowest_energy": run.lowest_energy, "seconds": secs, "reads": run.reads}


EFFORTS = [
    ("tabu", 10, 0, "1 run"),
    ("tabu", 100, 0, "1 run"),
    ("tabu", 10, 5, "6 runs"),
    ("tabu", 100, 2, "3 runs"),
    ("sa", 100, 100, "100 sweeps"),
    ("sa", 100, 1000, "1000 sweeps"),
    ("sa", 100, 10000, "10000 sweeps"),
    ("sa", 1000, 1000, "1000 sweeps"),
]


def _effort(args: argparse.Namespace, optima: dict[str, float]) -> list[str]:
    out = []
    for name in [x for x in args.effort.split(",") if x]:
        n, k = int(name.split("x")[0]), int(name.split("/")[1])
        s = default_scenario(n, n, k)
        opt = optima.get(name)
        if opt is None:
            opt = cpsat(s, time_limit=args.cpsat_limit).solution.cost.total
        p = penalty_rule(s).penalty
        for sampler, reads, effort, label in EFFORTS:
            print(f"{name}: effort {sampler} {reads} x {label} ...", file=sys.stderr, flush=True)
            raw = polished = 0
            secs = 0.0
            for seed in range(args.seeds):
                kw = {"tabu_restarts": effort} if sampler == "tabu" else {"sweeps": effort}
                t0 = time.perf_counter()
                run = solve_qubo(s, penalty=p, sampler=sampler, reads=reads, seed=seed, **kw)  # type: ignore[arg-type]
                secs += time.perf_counter() - t0
                raw += run.best_read_cost is not None and abs(run.best_read_cost - opt) <= TOL
                polished += abs(run.solution.cost.total - opt) <= TOL
            out.append(f"| {name} | {sampler} | {reads} | {label} | {raw}/{args.seeds} | {polished}/{args.seeds} | "
                       f"{secs / args.seeds:.1f} |")
    return out


SWEEPS = [("sa", 100, "100 sweeps"), ("sa", 1000, "1000 sweeps"), ("sa", 10000, "10000 sweeps"),
          ("tabu", 0, "1 run")]


def _quartiles(values: list[float]) -> str:
    import numpy as np

    q1, med, q3 = np.percentile(values, [25, 50, 75])
    return f"{med:.0f} [{q1:.0f}, {q3:.0f}]"


def _sweeps(args: argparse.Namespace) -> list[str]:
    """The sweeps table: % of reads at the optimum per instance of seeded random cells, SA by sweeps against tabu."""
    import statistics

    from qcpp.problem.ensembles import ensemble

    out = []
    for cell in [x for x in args.sweep_cells.split(",") if x]:
        size, k = cell.split("/")
        rows_, cols_ = (int(v) for v in size.split("x"))
        instances = ensemble(rows_, cols_, int(k), 0.1, count=args.sweep_instances, seed=0)
        stats: dict[str, list[tuple[float, bool, bool, float]]] = {label: [] for _, _, label in SWEEPS}
        for i, s in enumerate(instances):
            ex = cpsat(s, time_limit=args.cpsat_limit)
            opt = ex.solution.cost.total
            p = penalty_rule(s).penalty
            for sampler, sweeps, label in SWEEPS:
                print(f"{cell} #{i}: {sampler} {label} ...", file=sys.stderr, flush=True)
                kw = {"sweeps": sweeps} if sampler == "sa" else {}
                t0 = time.perf_counter()
                run = solve_qubo(s, penalty=p, sampler=sampler, reads=args.reads, seed=i, **kw)  # type: ignore[arg-type]
                secs = time.perf_counter() - t0
                polished = abs(run.solution.cost.total - opt) <= TOL
                at_opt = run.at_best if polished else 0
                stats[label].append((100 * at_opt / run.reads, at_opt > 0, polished, secs))
        n = len(instances)
        for sampler, _, label in SWEEPS:
            rs = stats[label]
            out.append(f"| {cell} | {sampler} | {label} | {_quartiles([r[0] for r in rs])} | "
                       f"{sum(r[1] for r in rs)}/{n} | {sum(r[2] for r in rs)}/{n} | "
                       f"{statistics.median(r[3] for r in rs):.1f} |")
    return out


def _print_sweeps(args: argparse.Namespace) -> None:
    t0 = time.perf_counter()
    rows = _sweeps(args)
    if rows:
        print(f"\nSweeps (random instances: qcpp.ensemble, density 0.1, seed 0, {args.sweep_instances} per cell; "
              f"per-robot form at the rule's P, {args.reads} reads per run; % of reads at the optimum after repair, "
              "before polishing: median [quartiles] over the instances)\n")
        print("| cell | sampler | effort per read | reads at optimum % | instances with a read at optimum | "
              "polished at optimum | s per run (median) |")
        print("|---|---|---|---|---:|---:|---:|")
        print("\n".join(rows))
        print(f"\nSweeps table: {time.perf_counter() - t0:.0f} s wall, {time.process_time() / 60:.1f} CPU minutes "
              "in this process.")


def _pct(k: int, n: int) -> str:
    return f"{100 * k / n:.0f}"


def _fmt(v: float | None) -> str:
    return "-" if v is None else f"{v:g}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="3,4,5,6", help="grid sides (n x n)")
    ap.add_argument("--robots", default="1,2,3", help="robot counts")
    ap.add_argument("--reads", type=int, default=100)
    ap.add_argument("--seeds", type=int, default=3, help="SBF annealing seeds")
    ap.add_argument("--cpsat-limit", type=float, default=240.0, help="CP-SAT seconds per scenario")
    ap.add_argument("--effort", default="5x5/2,6x6/2", help="scenarios of the effort sweep ('' for none)")
    ap.add_argument("--sweep-cells", default="4x5/2,5x5/2",
                    help="random cells ROWSxCOLS/ROBOTS of the sweeps table ('' for none)")
    ap.add_argument("--sweep-instances", type=int, default=20, help="instances per cell of the sweeps table")
    ap.add_argument("--only", choices=("sweeps",), help="print only this table")
    args = ap.parse_args()
    if args.only == "sweeps":
        _print_sweeps(args)
        return
    sizes = [int(x) for x in args.sizes.split(",")]
    robots = [int(x) for x in args.robots.split(",")]
    rows, summary = [], []
    optima: dict[str, float] = {}
    for n in sizes:
        for k in robots:
            s = default_scenario(n, n, k)
            name = f"{n}x{n}/{k}"
            print(f"{name}: CP-SAT ...", file=sys.stderr, flush=True)
            t0 = time.perf_counter()
            ex = cpsat(s, time_limit=args.cpsat_limit)
            cp_s = time.perf_counter() - t0
            opt = ex.solution.cost.total
            optima[name] = opt
            opt_txt = f"{opt:g}" + ("" if ex.proven_optimal else "*")
            rule = penalty_rule(s)
            sbf_hits, sbf_t = 0, 0.0
            for seed in range(args.seeds):
                t0 = time.perf_counter()
                sol = anneal(s, seed=seed)
                sbf_t += time.perf_counter() - t0
                sbf_hits += abs(sol.cost.total - opt) <= TOL
            per_scen: dict[tuple[str, str], dict] = {}
            configs = [("paper", None)] + [("per-robot", f) for f in (0.25, 0.5, 1.0)]
            for form, factor in configs:
                for sampler in ("sa", "tabu"):
                    print(f"{name}: {form} {factor or ''} {sampler} ...", file=sys.stderr, flush=True)
                    if form == "paper":
                        r = _paper_run(s, sampler, args.reads, 0, opt)
                        p_txt = "-"
                    else:
                        p = rule.penalty * factor  # type: ignore[operator]
                        r = _per_robot_run(s, p, sampler, args.reads, 0, opt)
                        p_txt = f"{p:g}" + (" (rule)" if factor == 1.0 else "")
                    per_scen[(form + str(factor), sampler)] = r
                    nr = r["reads"]
                    rows.append(
                        f"| {name} | {form} | {p_txt} | {sampler} | {_pct(r['feasible'], nr)} | "
                        f"{_pct(r['repairable'], nr)} | {_pct(r['at_opt'], nr)} | {_fmt(r['best_read'])} | "
                        f"{_fmt(r['final'])} | {opt_txt} | {r['lowest_energy']:g} | {r['seconds']:.1f} |"
                    )
            nv = s.num_variables
            tabu, sa = per_scen[("per-robot1.0", "tabu")], per_scen[("per-robot1.0", "sa")]
            paper_feas = max(per_scen[("paperNone", "sa")]["feasible"], per_scen[("paperNone", "tabu")]["feasible"])
            summary.append(
                f"| {name} | {nv} | {opt_txt} ({cp_s:.1f} s) | {rule.penalty:g} | "
                f"{_pct(paper_feas, args.reads)} | "
                f"{_pct(sa['feasible'], sa['reads'])} / {_pct(sa['repairable'], sa['reads'])} / "
                f"{_pct(sa['at_opt'], sa['reads'])} | {_fmt(sa['final'])} | "
                f"{_pct(tabu['feasible'], tabu['reads'])} / {_pct(tabu['repairable'], tabu['reads'])} / "
                f"{_pct(tabu['at_opt'], tabu['reads'])} | {_fmt(tabu['final'])} ({tabu['seconds']:.1f} s) | "
                f"{sbf_hits}/{args.seeds} ({sbf_t / args.seeds:.1f} s) |"
            )
    print(f"Every run ({args.reads} reads each; % of reads; * = CP-SAT not proven in {args.cpsat_limit:g} s)\n")
    print("| scenario | form | P | sampler | feasible % | repairable % | at optimum % | best read | polished | "
          "optimum | lowest energy | s |")
    print("|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    print("\n".join(rows))
    effort_rows = _effort(args, optima)
    if effort_rows:
        print(f"\nEffort (per-robot form at the rule's P; {args.seeds} seeds; read = a repaired read at the optimum "
              "before polishing, polished = the answer at the optimum; time per run)\n")
        print("| scenario | sampler | reads | effort per read | read at optimum | polished at optimum | s |")
        print("|---|---|---:|---|---:|---:|---:|")
        print("\n".join(effort_rows))
    print(f"\nSummary (per-robot form at the rule's P; feasible / repairable / at-optimum % of {args.reads} reads)\n")
    print("| scenario | edge vars | CP-SAT optimum | P (rule) | paper form feasible % | SA per-robot | SA polished | "
          "tabu per-robot | tabu polished | SBF anneal at optimum |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    print("\n".join(summary))
    _print_sweeps(args)


if __name__ == "__main__":
    main()
