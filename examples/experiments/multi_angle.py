"""Multi-angle QAOA mixers (one beta per partial mixer and layer, gammas 0): P(optimum) at p = 1..5, up to 5x5.

The goal: P(optimum) >= 0.05 on ``examples/two_robots_5x5.toml`` at some p <= 5. With one beta per layer
even the mixer-only ceiling is 1.64e-4 there at p = 5 (``docs/results/mixer_warm_start.md``). The lever tried
here is multi-angle QAOA (Herrman et al. 2022, Sci. Rep. 12, 6781): every partial mixer (robot, plaquette) gets
its own beta in every layer, the circuit ``PlanOptions(angles="multi")`` (the same gates as the default one).

For each scenario and p = 1..5 the table gives:

* **trained (Gibbs)**: :func:`qcpp.training.mixer_only.train_multi_angle` with every gamma 0 (the state is then a
  product over robots): L-BFGS-B on the exact gradient of the Gibbs objective of the measured cost (``eta = 5 /
  sigma``, ``STUDY_SCHEDULE`` of ``_common.py``) from the 3 constant starts, the previous depth's best with a zero
  layer appended, and 8 seeded random starts; the run with the lowest objective is kept (the training never looks
  up the optimum). Its P(optimum), ``<C>``, the probability of its most probable assignment (1 when the state is
  one basis state), how many of the starts ended within 0.01 of the kept objective value, the parameters, the objective
  evaluations (each with its gradient, every start included), the device objective estimates they would take
  (a gradient by the parameter-shift rule = 1 + 2 x parameters estimates) and the wall time;
* **on the way**: following the trained circuit one partial mixer at a time, the most paths one robot's state
  spreads over (probability above 1e-6) and the smallest probability of its most probable path (1 path and 1:
  a classical sequence of flips; more: superpositions that the later mixers interfere back);
* **multi-angle ceiling**: the largest P(optimum) found over multi-angle mixer-only betas when maximising
  P(optimum) itself, from the trained betas, the previous depth's ceiling with a zero layer and 4 seeded random
  starts. This diagnostic *uses the optimum*; it is not a method.

Every row records its scenario, options and the qcpp version; ``tests/simulate/results_freshness_test.py``
recomputes the circuit columns and, for at most 100,000 assignments, P(optimum) and ``<C>`` from the recorded
betas.

Outputs: ``results/multi_angle.md``, ``results/multi_angle.json``.
Run: ``python examples/experiments/multi_angle.py [--quick]``.
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
    REPO,
    STUDY_SCHEDULE,
    Table,
    circuit_columns,
    command_line,
    parse,
    record,
    study_gibbs,
    two_robot_cases,
    write_records,
    write_results,
)

import qcpp
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.mixer_only import (
    MIXER_MAXITER,
    MIXER_STARTS,
    MULTI_RANDOM_STARTS,
    best_p_optimum,
    mixer_sites,
    multi_robot_states,
    optimal_indices,
    p_optimum_and_gradients,
    product_objective,
    train_multi_angle,
)
from qcpp.training.objectives import make_objective

NAME = "multi_angle"
GOAL_5X5 = 0.05
CEILING_RANDOM = 4


def _probs(states: Sequence[np.ndarray]) -> list[np.ndarray]:
    return [v.real * v.real + v.imag * v.imag for v in states]


def _row(q: SubspaceQAOA, betas: Sequence[float], p: int) -> dict[str, Any]:
    """P(optimum) and ``<C>`` of the product state at ``betas`` (no full state)."""
    probs = _probs(multi_robot_states(q, betas, p))
    _, mean, _ = product_objective(q, probs, make_objective("expectation"))
    return {"method": "qaoa_multi_angle", "betas": [float(b) for b in betas],
            "p_opt": p_optimum_and_gradients(probs, optimal_indices(q))[0], "expectation": mean,
            "p_most_probable": float(np.prod([pr.max() for pr in probs]))}


def _walk(q: SubspaceQAOA, betas: Sequence[float], p: int) -> tuple[int, float]:
    """Along the circuit, one partial mixer at a time: the most paths one robot's state spreads over (probability
    above 1e-6) and the smallest probability of its most probable path. ``(1, 1.0)``: every step is a basis state
    (the circuit is a classical sequence of flips); larger: a superposition on the way."""
    x = np.asarray(betas, dtype=float)
    n = len(mixer_sites(q))
    widest, lowest, first = 1, 1.0, 0
    for b in q.robot_bases:
        v = b.initial.astype(np.complex128)
        for k in range(p):
            for m, (_, i, j) in enumerate(b.pairs):
                c, s = np.cos(x[k * n + first + m] / 2), -1j * np.sin(x[k * n + first + m] / 2)
                vi, vj = v[i], v[j]
                v[i], v[j] = c * vi + s * vj, s * vi + c * vj
                pr = v.real * v.real + v.imag * v.imag
                widest, lowest = max(widest, int(np.count_nonzero(pr > 1e-6))), min(lowest, float(pr.max()))
        first += len(b.pairs)
    return widest, lowest


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    opts = parse(__doc__.splitlines()[0], argv)
    t_all = time.perf_counter()
    p_max = 2 if opts.quick else 5
    random_starts = 2 if opts.quick else MULTI_RANDOM_STARTS
    options = {"initial": "initial_path", "angles": "multi", "gammas": 0, "objective": "gibbs",
               "gibbs_eta_sigma": STUDY_SCHEDULE["gibbs_eta_sigma"], "optimizer": "L-BFGS-B", "maxiter": MIXER_MAXITER,
               "constant_starts": list(MIXER_STARTS), "random_starts": random_starts, "seed": opts.seed}
    cases = two_robot_cases(opts.quick)
    table = Table(f"Multi-angle mixer-only QAOA (one beta per partial mixer and layer, gammas 0), p = 1..{p_max}",
                  ["scenario", "assignments", "p", "parameters", "P(optimum), trained (Gibbs)", "<C>",
                   "P(most probable assignment)", "starts ending there (within 0.01)", "evaluations",
                   "device estimates", "seconds", "on the way: most paths per robot",
                   "on the way: least P(most probable path)", "multi-angle ceiling (uses the optimum)"])
    rows: list[dict[str, Any]] = []
    notes: list[str] = []
    out: dict[str, Any] = {}
    for source, s in cases:
        t0 = time.perf_counter()
        q = SubspaceQAOA(s)
        objective = study_gibbs(q)
        sites = len(mixer_sites(q))
        rng = np.random.default_rng(opts.seed + 1)
        trained, ceilings = [], []
        prev: tuple[float, ...] | None = None
        prev_ceiling: np.ndarray | None = None
        for p in range(1, p_max + 1):
            res = train_multi_angle(q, p, objective, random_starts=random_starts, seed=opts.seed + p,
                                    previous=prev)
            prev = res.betas
            trow = _row(q, res.betas, p)
            x0s = [np.asarray(res.betas)] + [rng.uniform(0.0, 2 * np.pi, p * sites) for _ in range(CEILING_RANDOM)]
            if prev_ceiling is not None:
                x0s.insert(1, np.append(prev_ceiling, np.zeros(sites)))
            prev_ceiling, ceiling = best_p_optimum(q, (p, sites), x0s, maxiter=500)
            trained.append(res)
            ceilings.append(ceiling)
            there = sum(abs(v - res.value) <= 0.01 for v in res.start_values)
            widest, lowest = _walk(q, res.betas, p)
            trow.update(walk_most_paths=widest, walk_least_max_probability=lowest)
            estimates = res.evaluations * (1 + 2 * res.num_parameters)
            base = {"scenario_file": source, "p": p, **circuit_columns(s, p)}
            rows.append(record(s, options, table="trained", **base, **trow, value=res.value,
                               parameters=res.num_parameters, start_values=list(res.start_values),
                               evaluations=res.evaluations, device_estimates=estimates, seconds=res.seconds))
            rows.append(record(s, {**options, "ceiling_random_starts": CEILING_RANDOM}, table="ceiling", **base,
                               **_row(q, prev_ceiling, p)))
            table.add(source, q.dimension, p, res.num_parameters, trow["p_opt"], trow["expectation"],
                      trow["p_most_probable"], f"{there} of {len(res.start_values)}", res.evaluations, estimates,
                      round(res.seconds, 1), widest, lowest,
                      ceiling)
            print(f"{source} p = {p}: P(optimum) {trow['p_opt']:.4g}, ceiling {ceiling:.4g}, "
                  f"{res.evaluations} evaluations, {res.seconds:.1f} s", file=sys.stderr, flush=True)
        out[source] = {"trained": trained, "ceilings": ceilings}
        best = max(range(p_max), key=lambda k: rows[-2 * (p_max - k)]["p_opt"])
        value, p_opt = trained[best].value, rows[-2 * (p_max - best)]["p_opt"]
        notes.append(f"{source} ({q.dimension:,} assignments, optimum {q.optimum()[0]:g}, {len(q.optimum()[1])} "
                     f"optimal, {sites} partial mixers that act on reachable paths): best trained P(optimum) "
                     f"{p_opt:.4g} at p = {best + 1} (Gibbs objective {value:.4g}); training to p = {p_max} "
                     f"{sum(r.evaluations for r in trained)} product-state evaluations with gradient, "
                     f"{sum(r.seconds for r in trained):.1f} s; whole scenario {time.perf_counter() - t0:.0f} s.")
        print(notes[-1], flush=True)
    seconds = time.perf_counter() - t_all
    command = command_line(Path(__file__).name, opts)
    write_records(opts, NAME, command, rows, seconds=seconds)
    notes += [f"qcpp {qcpp.__version__}; options of every row: {json.dumps(options, sort_keys=True)}.",
              "Random starts: seed + p for the training, seed + 1 (one stream per scenario) for the ceiling.",
              "Circuit columns (JSON): the compiler's exact depth of the compiled circuit at that p (all-to-all); "
              "the multi-angle circuit has the same gates, only its symbols differ.",
              f"Whole script: {seconds:.0f} s on the shared 2-core machine."]
    write_results(opts, NAME, command, [table], notes)
    return {"rows": rows, **out, "repo": str(REPO)}


if __name__ == "__main__":
    main()
