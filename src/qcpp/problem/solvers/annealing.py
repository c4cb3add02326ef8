"""Simulated annealing with SBF moves (the paper's SA baseline).

State: one feasible path per robot, starting from the initial paths. Each iteration proposes a random
*allowed* SBF flip: a uniformly random robot among those that can move, then a uniformly random plaquette
among those its SBF rule allows (:meth:`~qcpp.problem.solvers.moves.MoveSpace.random_flip`). The proposal is
accepted by the Metropolis rule (always if the cost does not rise, else with probability
``exp(-delta / T)``) and the temperature cools geometrically, ``T_k = t0 * cooling**k``. A run of
``iterations`` is split into ``cycles`` annealing cycles (default 10): each reheats to ``t0`` and restarts
from the best state of the run so far (reheating escapes local minima that one long cycle stays in).

``time_limit`` (seconds) and ``stop`` (a caller's request, e.g. Ctrl-C) end the search early with the best state so
far (:mod:`qcpp.problem.solvers.stopping`); without them the run is unchanged.

Defaults: 20,000 iterations; ``t0`` the mean absolute cost change of a 50-move random walk from the start;
``cooling`` lowers the temperature 1000-fold over one cycle. ``evaluated`` counts every cost lookup.

When a robot's feasible paths split into several move-graph components (hard obstacles, the ``paper`` rule),
the annealer **restarts from every combination of component representatives**, each run with the full
``iterations``; the trace is the global best-so-far over the runs, concatenated.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> sol = anneal(s, seed=1, iterations=500)
    >>> from qcpp.problem.solvers.exhaustive import dfs
    >>> sol.cost == dfs(s).cost, len(sol.trace)
    (True, 500)
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from qcpp.problem.sbf import Rule
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers.moves import ComponentMode, CostCache, MoveSpace, search_solution, search_start
from qcpp.problem.solvers.result import ProgressFn, Solution
from qcpp.problem.solvers.stopping import Clock, StopFn, stop_check, stopped_note

CALIBRATION_MOVES = 50
DEFAULT_CYCLES = 10
FINAL_TEMPERATURE_RATIO = 1e-3


def anneal(
    scenario: Scenario,
    *,
    seed: int = 0,
    iterations: int = 20000,
    t0: float | None = None,
    cooling: float | None = None,
    cycles: int = DEFAULT_CYCLES,
    rule: Rule = "exact",
    components: ComponentMode = "auto",
    progress: ProgressFn | None = None,
    time_limit: float | None = None,
    stop: StopFn | None = None,
    clock: Clock = time.perf_counter,
) -> Solution:
    """Simulated annealing over feasible paths with SBF moves (see the module docstring).

    Args:
        seed: Seed of ``numpy.random.default_rng``; the same seed gives the same trace.
        iterations: Iterations per restart (one proposal each).
        t0: Initial temperature (``None``: calibrated from random moves).
        cooling: Geometric factor per iteration in ``(0, 1]`` (``None``: ``1e-3 ** (1 / cycle length)``).
        cycles: Annealing cycles per restart (at most ``iterations``); each reheats to ``t0`` from the run's
            best state and lasts ``iterations / cycles`` iterations.
        rule: SBF rule deciding the allowed moves (``exact`` or ``paper``).
        components: Move-graph component handling: ``all``, ``initial`` or ``auto``
            (see :mod:`qcpp.problem.solvers.moves`).
        progress: Called as ``progress(done, total)`` in iterations, every 1% or so.
        time_limit: Seconds after which the search stops with the best assignment so far (``None``: none; the
            clock starts before the move space is built). The same seed gives the same trace up to where it stops.
        stop: Asked before every iteration; once it returns ``True`` the search stops the same way (the command
            line's Ctrl-C).
        clock: The clock ``time_limit`` is measured on (tests pass a fake one).

    Returns:
        The best assignment seen, with ``trace``, ``seed``, ``rule`` and the component fields filled in; a
        search that stopped early says why in ``stopped`` and how far it got in a note.

    Raises:
        ValueError: on a non-positive ``iterations`` or ``t0``, a ``cooling`` outside ``(0, 1]``, ``cycles``
            outside ``1 .. iterations``, a ``time_limit`` that is not a positive number, or an unknown rule /
            component mode.
        ScenarioError: weights outside :mod:`qcpp.problem.cost_range`'s range.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 0], "goal": [1, 2]}]})
        >>> anneal(s, seed=3, iterations=200).trace == anneal(s, seed=3, iterations=200).trace
        True
    """
    if iterations < 1:
        raise ValueError(f"iterations must be positive, got {iterations}")
    if t0 is not None and not t0 > 0:
        raise ValueError(f"t0 must be positive, got {t0}")
    if not 1 <= cycles <= iterations:
        raise ValueError(f"cycles must be between 1 and iterations ({iterations}), got {cycles}")
    if cooling is None:
        cooling = FINAL_TEMPERATURE_RATIO ** (1.0 / (iterations // cycles))
    if not 0 < cooling <= 1:
        raise ValueError(f"cooling must be in (0, 1], got {cooling}")
    check = stop_check(time_limit, stop, clock)
    t_start, rng, space, cost = search_start(scenario, seed, rule, components)
    starts = space.starts()
    if t0 is None:
        t0 = _calibrate(space, cost, starts[0], rng)

    best: tuple[int, ...] = starts[0]
    best_cost = cost(best)
    trace: list[float] = []
    total = iterations * len(starts)
    step = max(1, total // 100)
    cycle_len = [iterations // cycles + (1 if i < iterations % cycles else 0) for i in range(cycles)]
    stopped: str | None = None
    for start in starts:
        if stopped:
            break
        cur, cur_cost = start, cost(start)
        run_best, run_best_cost = cur, cur_cost
        space.visit(cur)
        for n_it in cycle_len:
            if stopped:
                break
            # each cycle reheats to t0 and continues from this run's best state
            cur, cur_cost, temp = run_best, run_best_cost, t0
            for _ in range(n_it):
                if check is not None and (stopped := check()):
                    break
                cand = space.random_flip(cur, rng)
                if cand is not None:
                    c = cost(cand)
                    delta = c - cur_cost
                    if delta <= 0 or rng.random() < math.exp(-delta / temp):
                        cur, cur_cost = cand, c
                        space.visit(cur)
                        if cur_cost < run_best_cost:
                            run_best, run_best_cost = cur, cur_cost
                if run_best_cost < best_cost:
                    best, best_cost = run_best, run_best_cost
                trace.append(best_cost)
                temp *= cooling
                if progress is not None and len(trace) % step == 0:
                    progress(len(trace), total)

    notes = [f"{len(starts)} restart(s) (one per combination of component representatives)", *space.notes()]
    notes.append(f"t0={t0:.6g}, cooling={cooling:.6g}, {len(cost)} distinct assignments scored")
    if stopped:
        notes.append(stopped_note(stopped, len(trace), total, "iterations", time_limit))
    sol = search_solution("anneal", best, t_start, cost, trace, space, seed, notes)
    return replace(sol, stopped=stopped) if stopped else sol


def _calibrate(space: MoveSpace, cost: CostCache, start: tuple[int, ...], rng: np.random.Generator) -> float:
    """Mean absolute cost change of a short random walk of allowed moves (1.0 if it never changes)."""
    deltas = []
    cur, cur_cost = start, cost(start)
    for _ in range(CALIBRATION_MOVES):
        cand = space.random_flip(cur, rng)
        if cand is None:
            break
        c = cost(cand)
        deltas.append(abs(c - cur_cost))
        cur, cur_cost = cand, c
    mean = float(np.mean(deltas)) if deltas else 0.0
    return mean if mean > 0 else 1.0
