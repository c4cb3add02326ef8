"""Steepest descent over SBF moves from the initial paths: a cheap classical warm start.

:func:`local_search` starts from every robot's :func:`~qcpp.problem.paths.initial_path` and repeatedly takes the
single allowed SBF flip (one plaquette of one robot's path, :class:`~qcpp.problem.solvers.moves.MoveSpace`) that
lowers the total cost the most, until no flip lowers it: a local minimum of the move graph. Ties go to the
lowest robot, then the lowest plaquette. It is deterministic, has no parameters, and stops in at most
``(initial cost - optimum) / (smallest cost step)`` steps; each step scores every robot's allowed flips at once.

This is the warm start of the QAOA's ``local_search`` initial state (:mod:`qcpp.gadgets.initial_state`,
:mod:`qcpp.simulate.subspace`): the circuit prepares the descent's paths instead of the initial paths. It is a
heuristic, not a solver: it stops at the first local minimum, which can be far from the optimum.

Each step scores the flips of one robot against the other robots' fixed paths with the cost's own per-robot
decomposition (:func:`qcpp.problem.cost.separable_cost`, the one the subspace simulator uses), so a step costs a few
small matrix products per robot, with no quadratic form over all variables.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.problem.cost import cost
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> res = local_search(s)
    >>> res.initial_cost, res.cost, res.steps, res.cost == cost(s, res.paths)
    (12.0, -8.0, 2, True)
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from qcpp.problem.cost import cost, separable_cost
from qcpp.problem.paths import initial_path
from qcpp.problem.sbf import Rule
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers.moves import MoveSpace

__all__ = ["LocalSearch", "local_search", "steepest_descent"]


@dataclass(frozen=True)
class LocalSearch:
    """The outcome of :func:`local_search`.

    Attributes:
        paths: The local minimum: one edge mask per robot.
        cost: Its total cost.
        initial_cost: The initial paths' total cost.
        steps: Flips taken (each one robot, one plaquette).
        evaluated: Assignments scored (every allowed flip at every step, plus the start).
        trace: The cost after each step, the start first.
    """

    paths: tuple[int, ...]
    cost: float
    initial_cost: float
    steps: int
    evaluated: int
    seconds: float
    trace: tuple[float, ...]


@lru_cache(maxsize=16)  # deterministic; the simulator's bases ask once per robot and the QAOA solver's notes again
def local_search(scenario: Scenario, rule: Rule = "exact") -> LocalSearch:
    """Steepest descent over allowed SBF flips from the initial paths (see the module docstring).

    Args:
        rule: SBF rule deciding which flips are allowed (flips to infeasible paths are skipped).

    Pure memo: ``local_search.cache_clear()`` empties it."""
    t0 = time.perf_counter()
    start = tuple(initial_path(scenario, r) for r in range(scenario.num_robots))
    paths, trace, evaluated = steepest_descent(scenario, start, MoveSpace(scenario, rule, "initial"))
    return LocalSearch(paths, trace[-1], trace[0], len(trace) - 1, evaluated, time.perf_counter() - t0, trace)


def steepest_descent(
    scenario: Scenario, paths: tuple[int, ...], space: MoveSpace
) -> tuple[tuple[int, ...], tuple[float, ...], int]:
    """Steepest descent over ``space``'s allowed flips from ``paths`` (the rule of the module docstring); also
    the polish of :func:`qcpp.qubo.solve.solve_qubo`.

    Returns:
        The local minimum, the total cost after each step (the start's first) and the assignments scored.
    """
    current = cost(scenario, paths)
    trace = [current]
    evaluated = 1
    tol = 1e-9 * max(1.0, abs(current))
    while True:
        best: tuple[float, int, int] | None = None
        for r in range(scenario.num_robots):
            nbs = space.neighbours(r, paths[r])
            if not nbs:
                continue
            lists = [nbs if i == r else (p,) for i, p in enumerate(paths)]
            totals = separable_cost(scenario, lists).full_tensor().reshape(-1)
            evaluated += len(nbs)
            # first of the cheapest, lowest plaquette; ties within tol count as ties: the matrix products round
            # differently per candidate, and an argmin of exact ties would pick by rounding noise
            k = int(np.flatnonzero(totals <= totals.min() + tol)[0])
            if totals[k] < current - tol and (best is None or totals[k] < best[0] - tol):
                best = (float(totals[k]), r, nbs[k])
        if best is None:
            return paths, tuple(trace), evaluated
        current, r, mask = best
        paths = (*paths[:r], mask, *paths[r + 1:])
        trace.append(current)
