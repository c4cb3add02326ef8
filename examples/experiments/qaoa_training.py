"""QAOA's layer-by-layer training by depth: P(optimum) at p = 1..8 on two_robots_4x4, objectives, warm starts, 5x5.

The training (:func:`qcpp.training.layerwise.train_layerwise`) on the single-start schedule (``STUDY_SCHEDULE`` of
``_common.py``): L-BFGS-B on the exact adjoint gradient, layer by layer from p = 1 with INTERP and zero-layer warm
starts only, the linear ramp plus two seeded random starts at p = 1, the Gibbs objective with ``eta = 5 / sigma``.
Nothing is tuned per scenario.

Tables:

1. ``examples/two_robots_4x4.toml`` (the goal: P(optimum) >= 0.2 at some p <= 8): one training to
   p = 8, the kept run at each depth: the objective, ``<C>``, P(optimum), iterations, and the running totals of
   simulations, device objective estimates (a gradient = 1 + 4p estimates) and wall seconds.
2. The three objectives (``gibbs``, ``cvar`` with alpha 0.2, ``expectation``) with the same schedule on
   3x3 corner to corner (one robot), examples/paper_3x3.toml and two_robots_4x4, at p = 3 and p = 6.
3. Initial states compared with the same training to p = 5: the paper's ``initial_path`` against the
   classical warm start ``local_search`` (:func:`qcpp.problem.solvers.descent.local_search`, steepest descent over
   SBF moves) and ``local_search_mix`` (per robot the initial and the descent path in equal superposition), on
   the scenarios of this script where the descent does not already end on the optimum (the open 4x4 with two
   robots; on two_robots_4x4 it does, which the notes say).
4. ``examples/two_robots_5x5.toml`` (73.8 million assignments) at p = 1..5 without training: the angles of
   table 1 at the same p, gammas scaled by ``sigma_4x4 / sigma_5x5`` (parameter transfer), from the
   ``initial_path`` and ``local_search`` states, and table 3's ``local_search_mix`` angles of the open 4x4 (gammas
   scaled the same way) from ``local_search_mix``; the notes give the warm start's cost, time and distance to
   the optimum in SBF moves and in mixer layers (:func:`qcpp.simulate.state_measures.layers_to_reach`).
5. ``examples/two_robots_5x5.toml``, the training to p = 5 from ``local_search_mix`` (the 5x5
   goal: P(optimum) >= 0.05 at some p <= 5), the kept run at each depth with its iterations and time.

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

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import (
    EXAMPLES,
    REPO,
    STUDY_SCHEDULE,
    Table,
    command_line,
    parse,
    pyplot,
    save_figure,
    study_training,
    write_results,
)

import qcpp
from qcpp.io.atomic import write_text_atomic
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_to_dict
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers.descent import local_search
from qcpp.simulate.state_measures import layers_to_reach
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.layerwise import DEFAULT_MAXITER, DEFAULT_RANDOM_STARTS
from qcpp.training.objectives import CVAR_ALPHA, OBJECTIVES
from qcpp.training.training import cost_scale

NAME = "qaoa_training"


def circuit_columns(scenario: Scenario, p: int, initial: str = "initial_path") -> dict[str, int]:
    """Qubits, depth and two-qubit depth of the compiled circuit at depth ``p`` (the compiler's exact depth)."""
    from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
    from qcpp.plan.options import PlanOptions

    plan = PlanOptions(initial=initial)  # type: ignore[arg-type]
    est = estimate_point(Point.from_scenario(scenario, p), EstimateOptions(plan=plan, depth="exact"))
    assert est.depth is not None
    return {"qubits": est.qubits, "depth": est.depth.depth, "two_qubit_depth": est.depth.two_qubit_depth}


def _source(path: Path | str | None) -> str:
    if isinstance(path, str):
        return path
    return "default_scenario(3, 3, 1)" if path is None else str(path.relative_to(REPO))


def _state_row(q: SubspaceQAOA, angles: Sequence[float]) -> dict[str, Any]:
    """What the freshness test recomputes from a row: the angles, ``P(optimum)`` and ``<C>`` of that state."""
    psi = q.state(angles)
    return {"method": "qaoa", "angles": [float(a) for a in angles], "p_opt": q.p_optimum_from_state(psi),
            "expectation": q.expectation_from_state(psi)}


def moves_to_optimum(q: SubspaceQAOA, start: Sequence[int]) -> int:
    """Fewest SBF moves from the assignment ``start`` to an optimal one: the sum over robots of the breadth-first
    distance in the robot's move graph (a move changes one robot's path), the nearest optimum taken."""
    per_robot = []
    for b, m in zip(q.robot_bases, start):
        nbrs: list[list[int]] = [[] for _ in range(b.size)]
        for _, i, j in b.pairs:
            for a, c in zip(i.tolist(), j.tolist()):
                nbrs[a].append(c)
                nbrs[c].append(a)
        dist = np.full(b.size, -1)
        dist[b.index(m)] = 0
        frontier = [b.index(m)]
        while frontier:
            nxt = []
            for u in frontier:
                for v in nbrs[u]:
                    if dist[v] < 0:
                        dist[v] = dist[u] + 1
                        nxt.append(v)
            frontier = nxt
        per_robot.append(dist)
    return min(sum(int(d[i]) for d, i in zip(per_robot, q.index_of(opt))) for opt in q.optimal_assignments())


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    opts = parse(__doc__.splitlines()[0], argv)
    t_all = time.perf_counter()
    p_max = 3 if opts.quick else 8
    p_compare = (2,) if opts.quick else (3, 6)
    options = {"training": "layerwise", "optimizer": "L-BFGS-B", "maxiter": DEFAULT_MAXITER,
               "random_starts": DEFAULT_RANDOM_STARTS, "seed": 0, **STUDY_SCHEDULE,
               "cvar_alpha": CVAR_ALPHA}
    rows: list[dict[str, Any]] = []

    four = EXAMPLES / "two_robots_4x4.toml"
    s4 = load_scenario(four)
    q4 = SubspaceQAOA(s4)
    t0 = time.perf_counter()
    res = study_training(q4, p_max, "gibbs", progress=lambda k, p: print(f"two_robots_4x4: p = {k} done "
                                                                          f"({time.perf_counter() - t0:.0f} s)",
                                                                          file=sys.stderr, flush=True))
    depth_table = Table(f"two_robots_4x4.toml ({q4.dimension:,} assignments, optimum {q4.optimum()[0]:g}): "
                        "single-start training, the kept run at each depth",
                        ["p", "Gibbs objective", "<C>", "P(optimum)", "iterations", "qubits", "depth", "2q depth"])
    for lv in res.levels:
        circ = circuit_columns(s4, lv.p)
        rows.append({"table": "by_depth", "scenario_file": _source(four), "scenario": scenario_to_dict(s4),
                     "objective": "gibbs", "options": options, "qcpp_version": qcpp.__version__, "p": lv.p,
                     "value": lv.value, **_state_row(q4, lv.angles), "iterations": len(lv.trace) - 1, **circ})
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
        by_obj = {obj: study_training(q, max(p_compare), obj) for obj in OBJECTIVES}
        if s is s4:
            curves = {obj: [lv.p_optimum for lv in r.levels] for obj, r in by_obj.items()}
        for p in p_compare:
            cells = []
            for obj in OBJECTIVES:
                lv = by_obj[obj].levels[p - 1]
                cells.append(lv.p_optimum)
                rows.append({"table": "objectives", "scenario_file": _source(path), "scenario": scenario_to_dict(s),
                             "objective": obj, "options": options, "qcpp_version": qcpp.__version__, "p": p,
                             "value": lv.value, **_state_row(q, lv.angles), "iterations": len(lv.trace) - 1,
                             **circuit_columns(s, p)})
            compare.add(_source(path), q.dimension, p, *cells)

    # 3. initial states compared: the warm start where the descent does not already end on the optimum
    p_warm = 2 if opts.quick else 5
    warm_options = {**options, "objective": "gibbs"}
    warm_inits = ("initial_path", "local_search", "local_search_mix")
    warm_table = Table(f"Initial states compared (single-start training to p = {p_warm}): P(optimum) of the kept run",
                       ["scenario", "assignments", "descent cost", "optimum", "p", *warm_inits])
    warm_notes = []
    mix_source: tuple[SubspaceQAOA, Any] | None = None  # the open 4x4's local_search_mix training, for table 4
    for path, s in ((four, s4), ("default_scenario(4, 4, 2)", default_scenario(4, 4, 2))):
        warm = local_search(s)
        q = q4 if s is s4 else SubspaceQAOA(s)
        best = q.optimum()[0]
        if warm.cost <= best + 1e-9:
            warm_notes.append(f"{_source(path)}: the local_search warm start (steepest descent over SBF moves, cost "
                              f"{warm.initial_cost:g} -> {warm.cost:g} in {warm.steps} steps, "
                              f"{warm.seconds * 1e3:.1f} ms) already ends on the optimum: P(optimum) = 1 at p = 0 "
                              f"(local_search_mix: {SubspaceQAOA(s, initial='local_search_mix').p_optimum([]):.4g} at "
                              "p = 0), so this scenario says nothing about QAOA from them.")
            continue
        by_init = {}
        for initial in warm_inits:
            qi = q if initial == "initial_path" else SubspaceQAOA(s, initial=initial)  # type: ignore[arg-type]
            by_init[initial] = (qi, study_training(qi, p_warm, "gibbs"))
        mix_source = by_init["local_search_mix"]
        for p in range(1, p_warm + 1):
            cells = []
            for initial, (qi, r) in by_init.items():
                lv = r.levels[p - 1]
                cells.append(lv.p_optimum)
                rows.append({"table": "initial_states", "scenario_file": _source(path), "scenario": scenario_to_dict(s),
                             "objective": "gibbs", "options": {**warm_options, "initial": initial},
                             "qcpp_version": qcpp.__version__, "p": p, "value": lv.value, **_state_row(qi, lv.angles),
                             "iterations": len(lv.trace) - 1})
            warm_table.add(_source(path), q.dimension, warm.cost, best, p, *cells)
        print(f"{_source(path)}: descent {warm.initial_cost:g} -> {warm.cost:g}, optimum {best:g}", file=sys.stderr)

    # 4. two_robots_5x5: angles transferred from table 1 (and table 3's mix), no training there
    tables = [depth_table, compare, warm_table]
    five_notes = []
    if not opts.quick:
        assert mix_source is not None
        five = EXAMPLES / "two_robots_5x5.toml"
        s5 = load_scenario(five)
        warm5 = local_search(s5)
        q5 = {initial: SubspaceQAOA(s5, initial=initial) for initial in warm_inits}  # type: ignore[arg-type]
        best5 = q5["initial_path"].optimum()[0]
        sigma5 = cost_scale(q5["initial_path"])
        scale = cost_scale(q4) / sigma5
        mix_scale = cost_scale(mix_source[0]) / sigma5
        five_table = Table(f"two_robots_5x5.toml ({q5['initial_path'].dimension:,} assignments, optimum {best5:g}): "
                           f"table 1's angles at the same p, gammas x {scale:.4g} (sigma_4x4 / sigma_5x5), and for "
                           f"local_search_mix table 3's open-4x4 local_search_mix angles, gammas x {mix_scale:.4g}; no "
                           "training", ["p", *(f"{k} {i}" for i in warm_inits for k in ("P(optimum)", "<C>")),
                                        "qubits", "depth (initial_path)", "2q depth"])
        for lv in res.levels[:5]:
            circ = circuit_columns(s5, lv.p)
            cells = []
            for initial, q in q5.items():
                source = mix_source[1].levels[lv.p - 1] if initial == "local_search_mix" else lv
                x = np.array(source.angles)
                x[0::2] *= mix_scale if initial == "local_search_mix" else scale
                where = ("default_scenario(4, 4, 2) initial_states local_search_mix" if initial == "local_search_mix"
                         else "two_robots_4x4 by_depth")
                circ_i = circuit_columns(s5, lv.p, initial)
                t0 = time.perf_counter()
                st = _state_row(q, x)
                print(f"two_robots_5x5 p = {lv.p} {initial}: P(optimum) {st['p_opt']:.4g} "
                      f"({time.perf_counter() - t0:.0f} s)", file=sys.stderr, flush=True)
                cells += [st["p_opt"], st["expectation"]]
                ratio = mix_scale if initial == "local_search_mix" else scale
                rows.append({"table": "five_by_five_transfer", "scenario_file": _source(five),
                             "scenario": scenario_to_dict(s5), "objective": "gibbs",
                             "options": {**options, "initial": initial, "angles": f"{where}, gamma x "
                                         f"sigma ratio {ratio!r}"}, "qcpp_version": qcpp.__version__, "p": lv.p,
                             **st, **circ_i})
            five_table.add(lv.p, *cells, circ["qubits"], circ["depth"], circ["two_qubit_depth"])
        tables.append(five_table)

        # 5. two_robots_5x5: the single-start training from local_search_mix, p = 1..5
        qm = q5["local_search_mix"]
        t0 = time.perf_counter()
        res5 = study_training(qm, 5, "gibbs", progress=lambda k, p: print(
            f"two_robots_5x5 local_search_mix: p = {k} done ({time.perf_counter() - t0:.0f} s)", file=sys.stderr,
            flush=True))
        trained_table = Table(f"two_robots_5x5.toml: single-start training to p = 5 from local_search_mix "
                              f"(P(optimum) = {qm.p_optimum([]):.4g} at p = 0, <C> = {qm.expectation([]):.4g}), "
                              "the kept run at each depth",
                              ["p", "Gibbs objective", "<C>", "P(optimum)", "beta", "iterations", "simulations",
                               "qubits", "depth", "2q depth"])
        for lv in res5.levels:
            circ = circuit_columns(s5, lv.p, "local_search_mix")
            rows.append({"table": "five_by_five_trained", "scenario_file": _source(five),
                         "scenario": scenario_to_dict(s5), "objective": "gibbs",
                         "options": {**options, "initial": "local_search_mix"}, "qcpp_version": qcpp.__version__,
                         "p": lv.p, "value": lv.value, "method": "qaoa", "angles": [float(a) for a in lv.angles],
                         "p_opt": lv.p_optimum, "expectation": lv.expectation, "iterations": len(lv.trace) - 1,
                         "simulations": lv.num_evaluations, **circ})
            trained_table.add(lv.p, lv.value, lv.expectation, lv.p_optimum,
                              " ".join(f"{b:.3g}" for b in lv.angles[1::2]), len(lv.trace) - 1, lv.num_evaluations,
                              circ["qubits"], circ["depth"], circ["two_qubit_depth"])
        tables.append(trained_table)
        five_notes.append(f"two_robots_5x5 single-start training from local_search_mix to p = 5: {res5.runs} "
                          f"L-BFGS-B runs, {res5.num_evaluations} simulations ({res5.num_gradients} with gradient), "
                          f"{res5.seconds:.0f} s wall; best P(optimum) {max(lv.p_optimum for lv in res5.levels):.4g}.")
        print(five_notes[-1])
        start_paths = tuple(q5["initial_path"].bases[r][0] for r in range(s5.num_robots))
        m0, m1 = (moves_to_optimum(q5["initial_path"], a) for a in (start_paths, warm5.paths))
        l0, l1, l2 = (min(layers_to_reach(q, a) or 10**9 for a in q.optimal_assignments()) for q in q5.values())
        five_notes.append(f"two_robots_5x5 warm start (local_search): cost {warm5.initial_cost:g} -> {warm5.cost:g} in "
                          f"{warm5.steps} steps ({warm5.evaluated} assignments scored, {warm5.seconds * 1e3:.1f} ms); "
                          f"the nearest optimum (cost {best5:g}) is {m1} SBF moves and {l1} mixer layers away "
                          f"(from the initial paths: {m0} moves, {l0} layers; from local_search_mix: {l2} layers).")
        print(five_notes[-1])

    seconds = time.perf_counter() - t_all
    dump = {"qcpp_version": qcpp.__version__, "command": command_line(Path(__file__).name, opts),
            "seconds": seconds, "rows": rows}
    write_text_atomic(opts.results / f"{NAME}.json", json.dumps(dump, indent=1) + "\n")
    print(f"wrote {opts.results / f'{NAME}.json'}")
    notes = [f"qcpp {qcpp.__version__}; options of every row: {json.dumps(options, sort_keys=True)}.", totals,
             *warm_notes, *five_notes,
             "Circuit columns: the compiler's exact depth of the compiled, lowered circuit at that p (all-to-all).",
             f"Whole script: {seconds:.0f} s."]
    write_results(opts, NAME, command_line(Path(__file__).name, opts), tables, notes)

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.0, 3.8))
    ax.plot([lv.p for lv in res.levels], [lv.p_optimum for lv in res.levels], "o-", label="gibbs, to p_max")
    for obj, ys in curves.items():
        if obj != "gibbs":
            ax.plot(range(1, len(ys) + 1), ys, "s--", label=obj)
    ax.axhline(0.2, color="grey", ls=":", lw=1, label="goal 0.2")
    ax.set_yscale("log")
    ax.set_xlabel("QAOA layers p")
    ax.set_ylabel("P(optimum)")
    ax.set_title("two_robots_4x4: single-start layer-by-layer training", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(frameon=False, fontsize=8)
    fig.tight_layout()
    save_figure(fig, opts.figures / f"{NAME}.png")
    plt.close(fig)
    return {"rows": rows, "schedule": res}


if __name__ == "__main__":
    main()
