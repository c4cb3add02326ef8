"""Mixer-only warm start (gammas 0) for QAOA training, and how much P(optimum) the mixer alone can give, up to 5x5.

The goal: P(optimum) >= 0.05 on ``examples/two_robots_5x5.toml`` at some p <= 5; the single-start training
stays at beta = 0 there (``docs/results/qaoa_training.md``, table 5). The lever tried here: with every gamma 0
the state is a product over robots, so the betas can be trained cheaply per robot
(:func:`qcpp.training.mixer_only.train_mixer_only`, the Gibbs objective of the full cost on the product state;
it never looks at the optimum), and the full training can start from them.

For each scenario and p = 1..5 the table gives:

* **mixer-only (Gibbs)**: P(optimum) and ``<C>`` of the product state at the mixer-only trained betas;
* **then full training**: L-BFGS-B on the exact gradient (:func:`qcpp.training.training.train`, Gibbs, at most
  :data:`~qcpp.training.layerwise.DEFAULT_MAXITER` iterations) from those betas with the linear ramp's gammas, its
  P(optimum) and its largest ``|gamma|`` (scenarios of at most 100,000 assignments; one 5x5 gradient at p = 5
  takes 30-60 s on the shared machine, so not on two_robots_5x5);
* **single-start training**: :func:`qcpp.training.layerwise.train_layerwise` on ``STUDY_SCHEDULE`` (``_common.py``)
  from the initial paths, and the same with its
  option ``mixer_warm=True`` (every level also starts from the mixer-only betas with the ramp's gammas; 4x4
  scenarios);
* **mixer-only ceiling**: the largest P(optimum) found over mixer-only angles when maximising P(optimum)
  itself (:func:`qcpp.training.mixer_only.mixer_only_ceiling`, 60 seeded random starts per depth plus the previous
  depth's best). This diagnostic *uses the optimum*; it is not a method, it measures what any warm start with
  gammas 0 can give, so ``single-start / ceiling`` is the factor the phase separators add.

Every row records its scenario, options and the qcpp version; the circuit columns and (for at most 100,000
assignments) the states are recomputed by ``tests/simulate/results_freshness_test.py``. two_robots_5x5 states
are products of two 8,590-path robot vectors here, so no 73.8-million-amplitude state is built.

Outputs: ``results/mixer_warm_start.md``, ``results/mixer_warm_start.json``.
Run: ``python examples/experiments/mixer_warm_start.py [--quick]``.
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
    study_training,
    two_robot_cases,
    write_records,
    write_results,
)

import qcpp
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.layerwise import DEFAULT_MAXITER
from qcpp.training.mixer_only import (
    CEILING_STARTS,
    mixer_only_ceiling,
    product_objective,
    robot_states,
    train_mixer_only,
)
from qcpp.training.objectives import make_objective
from qcpp.training.training import initial_angles, train

NAME = "mixer_warm_start"
GOAL_5X5 = 0.05
FULL_TRAINING_MAX = 100_000
"""Scenarios of at most this many assignments also get the full training (a 5x5 gradient takes 30-60 s)."""


def _product_row(q: SubspaceQAOA, angles: Sequence[float]) -> dict[str, Any]:
    """``P(optimum)`` and ``<C>`` of a gammas-0 state from the robots' vectors (no full state)."""
    states = robot_states(q, [float(b) for b in angles[1::2]])
    probs = [v.real * v.real + v.imag * v.imag for v in states]
    _, mean, _ = product_objective(q, probs, make_objective("expectation"))
    p_opt = 0.0
    for k in q.optimum()[1]:
        idx = np.unravel_index(k, q.dims)
        p_opt += float(np.prod([pr[i] for pr, i in zip(probs, idx)]))
    return {"method": "qaoa", "angles": [float(a) for a in angles], "p_opt": p_opt, "expectation": mean}


def _state_row(q: SubspaceQAOA, angles: Sequence[float]) -> dict[str, Any]:
    psi = q.state(angles)
    return {"method": "qaoa", "angles": [float(a) for a in angles], "p_opt": q.p_optimum_from_state(psi),
            "expectation": q.expectation_from_state(psi)}


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    opts = parse(__doc__.splitlines()[0], argv)
    t_all = time.perf_counter()
    p_max = 2 if opts.quick else 5
    starts = 4 if opts.quick else CEILING_STARTS
    options = {"initial": "initial_path", "objective": "gibbs", **STUDY_SCHEDULE,
               "optimizer": "L-BFGS-B", "maxiter": DEFAULT_MAXITER, "ceiling_starts": starts, "seed": opts.seed}
    cases = two_robot_cases(opts.quick)
    table = Table(f"Mixer-only warm start (gammas 0) and the mixer-only ceiling, p = 1..{p_max}: P(optimum)",
                  ["scenario", "assignments", "p", "mixer-only (Gibbs)", "<C> mixer-only", "then full training",
                   "max abs(gamma) after", "single-start training", "single-start, mixer_warm=True",
                   "mixer-only ceiling (uses the optimum)",
                   "single-start / ceiling"])
    rows: list[dict[str, Any]] = []
    notes: list[str] = []
    out: dict[str, Any] = {}
    for source, s in cases:
        first_note = len(notes)
        t0 = time.perf_counter()
        q = SubspaceQAOA(s)
        obj = study_gibbs(q)
        warm = train_mixer_only(q, p_max, obj)
        ceiling = mixer_only_ceiling(q, p_max, starts=starts, seed=opts.seed)
        small = q.dimension <= FULL_TRAINING_MAX
        default = study_training(q, p_max) if small else None
        with_warm = study_training(q, p_max, mixer_warm=True) if small else None
        print(f"{source}: mixer-only and ceiling done ({time.perf_counter() - t0:.0f} s)", file=sys.stderr, flush=True)
        out[source] = {"warm": warm, "ceiling": ceiling, "default": default, "with_warm": with_warm}
        for p in range(1, p_max + 1):
            w, c = warm[p - 1], ceiling[p - 1]
            circ = circuit_columns(s, p)
            base = {"scenario_file": source, "p": p, **circ}
            wrow = _product_row(q, w.angles)
            crow = _product_row(q, c.angles)
            rows.append(record(s, {**options, "angles": "mixer_only"}, table="mixer_only", **base, **wrow,
                               value=w.value, evaluations=w.evaluations, seconds=w.seconds))
            rows.append(record(s, {**options, "angles": "mixer_only_ceiling"}, table="ceiling", **base, **crow))
            full_cell: Any = "-"
            gamma_cell: Any = "-"
            default_cell: Any = "-"
            warm_cell: Any = "-"
            ratio: Any = "-"
            if small and default is not None:
                x0 = np.array(w.angles)
                x0[0::2] = initial_angles(q, p, "linear-ramp")[0::2]
                run = train(q, p, "lbfgsb", init=x0, maxiter=DEFAULT_MAXITER, objective=obj)
                frow = _state_row(q, run.angles)
                rows.append(record(s, {**options, "angles": "mixer_only then full training"}, table="from_mixer",
                                   **base, **frow, value=run.value, iterations=len(run.trace) - 1))
                full_cell, gamma_cell = frow["p_opt"], float(np.max(np.abs(run.angles[0::2])))
                lv = default.levels[p - 1]
                drow = _state_row(q, lv.angles)
                rows.append(record(s, {**options, "angles": "single-start training"}, table="single_start", **base,
                                   **drow, value=lv.value))
                default_cell = drow["p_opt"]
                assert with_warm is not None
                lv = with_warm.levels[p - 1]
                mrow = _state_row(q, lv.angles)
                rows.append(record(s, {**options, "angles": "single-start training, mixer_warm=True"},
                                   table="single_start_mixer_warm", **base, **mrow, value=lv.value))
                warm_cell = mrow["p_opt"]
                ratio = drow["p_opt"] / crow["p_opt"] if crow["p_opt"] > 0 else "-"
            table.add(source, q.dimension, p, wrow["p_opt"], wrow["expectation"], full_cell, gamma_cell, default_cell,
                      warm_cell, crow["p_opt"], ratio)
        notes.append(f"{source} ({q.dimension:,} assignments, optimum {q.optimum()[0]:g}, "
                     f"{len(q.optimum()[1])} optimal): mixer-only training to p = {p_max} {warm[-1].evaluations} "
                     f"product-state evaluations with gradient, {warm[-1].seconds:.1f} s; ceiling "
                     f"{sum(c.seconds for c in ceiling):.1f} s; whole scenario {time.perf_counter() - t0:.0f} s.")
        if default is not None and with_warm is not None:
            notes.append(f"{source}: single-start training to p = {p_max}: {default.runs} L-BFGS-B runs, "
                         f"{default.num_evaluations} simulations, {default.circuit_estimates} device objective "
                         f"estimates, {default.seconds:.1f} s; with mixer_warm=True: {with_warm.runs} runs, "
                         f"{with_warm.num_evaluations} simulations + {with_warm.mixer_evaluations} product-state "
                         f"evaluations, {with_warm.circuit_estimates} estimates, {with_warm.seconds:.1f} s.")
        if not small:
            best = max(c.p_optimum for c in ceiling)
            notes.append(f"{source}: the best mixer-only P(optimum) found at p <= {p_max} is {best:.3g}; the goal "
                         f"{GOAL_5X5} needs the phase separators to multiply it by {GOAL_5X5 / best:.0f}.")
        print("\n".join(notes[first_note:]), flush=True)
    seconds = time.perf_counter() - t_all
    command = command_line(Path(__file__).name, opts)
    write_records(opts, NAME, command, rows, seconds=seconds)
    notes += [f"qcpp {qcpp.__version__}; options of every row: {json.dumps(options, sort_keys=True)}.",
              "Circuit columns (JSON): the compiler's exact depth of the compiled circuit at that p (all-to-all).",
              f"Whole script: {seconds:.0f} s on the shared 2-core machine."]
    write_results(opts, NAME, command, [table], notes)
    return {"rows": rows, **out, "repo": str(REPO)}


if __name__ == "__main__":
    main()
