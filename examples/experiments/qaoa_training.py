"""QAOA's default training by depth: P(optimum) at p = 1..8 on two_robots_4x4, and the objectives compared.

Default training (:func:`simulate.layerwise.train_layerwise`): L-BFGS-B on the exact adjoint gradient, layer by
layer from p = 1 with INTERP and zero-layer warm starts, the linear ramp plus two seeded random starts at
p = 1, the Gibbs objective with ``eta = 5 / sigma``. Nothing is tuned per scenario.

Tables:

1. ``examples/two_robots_4x4.toml`` (issue #19's goal: P(optimum) >= 0.2 at some p <= 8): one training to
   p = 8, the kept run at each depth: the objective, ``<C>``, P(optimum), iterations, and the running totals of
   simulations, device objective estimates (a gradient = 1 + 4p estimates) and wall seconds.
2. The three objectives (``gibbs``, ``cvar`` with alpha 0.2, ``expectation``) with the same schedule on
   3x3 corner to corner (one robot), examples/paper_3x3.toml and two_robots_4x4, at p = 3 and p = 6.

Every row records its scenario (file), its options and the qcpp version (``results/qaoa_training.json``); the
circuit columns (qubits, depth, two-qubit depth of the compiled circuit at that p) are recomputed by
``tests/simulate/results_freshness_test.py``.

Outputs: ``results/qaoa_training.md``, ``results/qaoa_training.json``, ``figures/qaoa_training.png``.
Run: ``python examples/experiments/qaoa_training.py [--quick]``.
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import EXAMPLES, REPO, Table, command_line, parse, pyplot, save_figure, write_results

import qcpp
from gridcover.presets import default_scenario
from gridcover.scenario import Scenario, load_scenario, scenario_to_dict
from qcppio.atomic import write_text_atomic
from simulate.layerwise import DEFAULT_MAXITER, DEFAULT_RANDOM_STARTS, train_layerwise
from simulate.objectives import CVAR_ALPHA, GIBBS_SCALE, OBJECTIVES
from simulate.subspace import SubspaceQAOA

NAME = "qaoa_training"


def circuit_columns(scenario: Scenario, p: int) -> dict[str, int]:
    """Qubits, depth and two-qubit depth of the compiled circuit at depth ``p`` (the compiler's exact depth)."""
    from estimators.estimate import EstimateOptions, Point, estimate_point

    est = estimate_point(Point.from_scenario(scenario, p), EstimateOptions(depth="exact"))
    assert est.depth is not None
    return {"qubits": est.qubits, "depth": est.depth.depth, "two_qubit_depth": est.depth.two_qubit_depth}


def _source(path: Path | None) -> str:
    return "default_scenario(3, 3, 1)" if path is None else str(path.relative_to(REPO))


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    opts = parse(__doc__.splitlines()[0], argv)
    t_all = time.perf_counter()
    p_max = 3 if opts.quick else 8
    p_compare = (2,) if opts.quick else (3, 6)
    options = {"training": "layerwise", "optimizer": "L-BFGS-B", "maxiter": DEFAULT_MAXITER,
               "random_starts": DEFAULT_RANDOM_STARTS, "seed": 0, "gibbs_eta_sigma": GIBBS_SCALE,
               "cvar_alpha": CVAR_ALPHA}
    rows: list[dict[str, Any]] = []

    four = EXAMPLES / "two_robots_4x4.toml"
    s4 = load_scenario(four)
    q4 = SubspaceQAOA(s4)
    t0 = time.perf_counter()
    res = train_layerwise(q4, p_max, "gibbs", progress=lambda k, p: print(f"two_robots_4x4: p = {k} done "
                                                                          f"({time.perf_counter() - t0:.0f} s)",
                                                                          file=sys.stderr, flush=True))
    depth_table = Table(f"two_robots_4x4.toml ({q4.dimension:,} assignments, optimum {q4.optimum()[0]:g}): default "
                        "training, the kept run at each depth",
                        ["p", "Gibbs objective", "<C>", "P(optimum)", "iterations", "qubits", "depth", "2q depth"])
    for lv in res.levels:
        circ = circuit_columns(s4, lv.p)
        rows.append({"table": "by_depth", "scenario_file": _source(four), "scenario": scenario_to_dict(s4),
                     "objective": "gibbs", "options": options, "qcpp_version": qcpp.__version__, "p": lv.p,
                     "value": lv.value, "expectation": lv.expectation, "p_optimum": lv.p_optimum,
                     "iterations": len(lv.trace) - 1, **circ})
        depth_table.add(lv.p, lv.value, lv.expectation, lv.p_optimum, len(lv.trace) - 1, circ["qubits"],
                        circ["depth"], circ["two_qubit_depth"])
    totals = (f"Whole schedule to p = {p_max}: {res.runs} L-BFGS-B runs, {res.num_evaluations} simulations "
              f"({res.num_gradients} with gradient), {res.circuit_estimates} device objective estimates, "
              f"{res.seconds:.1f} s wall on the shared 2-core machine.")
    print(totals)

    compare = Table("The objectives compared (same schedule): P(optimum) of the kept run",
                    ["scenario", "assignments", "p", *OBJECTIVES])
    paper = EXAMPLES / "paper_3x3.toml"
    cases: list[tuple[Path | None, Scenario]] = [(None, default_scenario(3, 3, 1)), (paper, load_scenario(paper)),
                                                 (four, s4)]
    curves: dict[str, list[float]] = {}
    for path, s in cases:
        q = q4 if s is s4 else SubspaceQAOA(s)
        by_obj = {obj: train_layerwise(q, max(p_compare), obj) for obj in OBJECTIVES}
        if s is s4:
            curves = {obj: [lv.p_optimum for lv in r.levels] for obj, r in by_obj.items()}
        for p in p_compare:
            cells = []
            for obj in OBJECTIVES:
                lv = by_obj[obj].levels[p - 1]
                cells.append(lv.p_optimum)
                rows.append({"table": "objectives", "scenario_file": _source(path), "scenario": scenario_to_dict(s),
                             "objective": obj, "options": options, "qcpp_version": qcpp.__version__, "p": p,
                             "value": lv.value, "expectation": lv.expectation, "p_optimum": lv.p_optimum,
                             "iterations": len(lv.trace) - 1, **circuit_columns(s, p)})
            compare.add(_source(path), q.dimension, p, *cells)

    seconds = time.perf_counter() - t_all
    dump = {"qcpp_version": qcpp.__version__, "command": command_line(Path(__file__).name, opts),
            "seconds": seconds, "rows": rows}
    write_text_atomic(opts.results / f"{NAME}.json", json.dumps(dump, indent=1) + "\n")
    print(f"wrote {opts.results / f'{NAME}.json'}")
    notes = [f"qcpp {qcpp.__version__}; options of every row: {json.dumps(options, sort_keys=True)}.", totals,
             "Circuit columns: the compiler's exact depth of the compiled, lowered circuit at that p (all-to-all).",
             f"Whole script: {seconds:.0f} s."]
    write_results(opts, NAME, command_line(Path(__file__).name, opts), [depth_table, compare], notes)

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.0, 3.8))
    ax.plot([lv.p for lv in res.levels], [lv.p_optimum for lv in res.levels], "o-", label="gibbs (default), to p_max")
    for obj, ys in curves.items():
        if obj != "gibbs":
            ax.plot(range(1, len(ys) + 1), ys, "s--", label=obj)
    ax.axhline(0.2, color="grey", ls=":", lw=1, label="issue #19 goal 0.2")
    ax.set_yscale("log")
    ax.set_xlabel("QAOA layers p")
    ax.set_ylabel("P(optimum)")
    ax.set_title("two_robots_4x4: default layer-by-layer training", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(frameon=False, fontsize=8)
    fig.tight_layout()
    save_figure(fig, opts.figures / f"{NAME}.png")
    plt.close(fig)
    return {"rows": rows, "schedule": res}


if __name__ == "__main__":
    main()
