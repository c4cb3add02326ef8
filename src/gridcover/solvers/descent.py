"""Steepest descent over SBF moves from the initial paths: a cheap classical warm start.

:func:`local_search` starts from every robot's :func:`~gridcover.paths.initial_path` and repeatedly takes the
single allowed SBF flip (one plaquette of one robot's path, :class:`~gridcover.solvers.moves.MoveSpace`) that
lowers the total cost the most, until no flip lowers it: a local minimum of the move graph. Ties go to the
lowest robot, then the lowest plaquette. It is deterministic, has no parameters, and stops in at most
``(initial cost - optimum) / (smallest cost step)`` steps; each step scores every robot's allowed flips at once.

This is the warm start of the QAOA's ``local_search`` initial state (:mod:`circuitgen.initial_state`,
:mod:`simulate.subspace`): the circuit prepares the descent's paths instead of the initial paths. It is a
heuristic, not a solver: it stops at the first local minimum (two_robots_5x5: cost -6 in 7 steps, the optimum
is -16).

Each step scores the flips of one robot against the other robots' fixed paths with the cost's own terms
(weights, path lengths, node degrees; :mod:`gridcover.cost`), so a step costs a few small matrix products per
robot, with no quadratic form over all variables.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> from gridcover.cost import cost
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> res = local_search(s)
    >>> res.initial_cost, res.cost, res.steps, res.cost == cost(s, res.paths)
    (12.0, -8.0, 2, True)
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from gridcover.cost import balanced_pairs, cost_parts_bits, incidence_matrix, robot_edge_vectors
from gridcover.paths import initial_path, paths_matrix
from gridcover.sbf import Rule
from gridcover.scenario import Scenario
from gridcover.solvers.moves import MoveSpace

__all__ = ["LocalSearch", "local_search"]


@dataclass(frozen=True)
class LocalSearch:
    """The outcome of :func:`local_search`.

    Attributes:
        paths: The local minimum: one edge mask per robot.
        cost: Its total cost.
        initial_cost: The initial paths' total cost.
        steps: Flips taken (each one robot, one plaquette).
        evaluated: Assignments scored (every allowed flip at every step, plus the start).
        seconds: Wall-clock time.
        trace: The cost after each step, the start first.
    """

    paths: tuple[int, ...]
    cost: float
    initial_cost: float
    steps: int
    evaluated: int
    seconds: float
    trace: tuple[float, ...]


class _Terms:
    """The cost split into the parts one robot's path contributes (see :mod:`gridcover.cost`)."""

    def __init__(self, scenario: Scenario, paths: tuple[int, ...]) -> None:
        self.s = scenario
        self.weights, self.lengths = robot_edge_vectors(scenario)
        self.incidence = incidence_matrix(scenario)
        t = scenario.degree_targets
        self.keep = ~np.isnan(t)
        self.targets = t[self.keep]
        self.alpha = scenario.objective.alpha
        self.pairs = balanced_pairs(scenario)
        bits = paths_matrix(scenario, paths)
        self.c1 = bits @ self.weights
        self.length = bits @ self.lengths
        self.degree = bits @ self.incidence  # (robots, nodes)

    def candidates(self, robot: int, masks: list[int]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Total costs with ``robot`` on each of ``masks`` (others fixed), and the candidates' terms."""
        bits = paths_matrix(self.s, masks)
        c1 = bits @ self.weights
        length = bits @ self.lengths
        degree = bits @ self.incidence
        total_c1 = self.c1.sum() - self.c1[robot] + c1
        c2 = np.zeros(len(masks))
        for r, q in self.pairs:
            lr = length if r == robot else self.length[r]
            lq = length if q == robot else self.length[q]
            c2 = c2 + (lr - lq) ** 2
        deg = self.degree.sum(axis=0) - self.degree[robot] + degree
        c3 = ((deg[:, self.keep] - self.targets) ** 2).sum(axis=1)
        a0, a1, a2 = self.alpha
        return a0 * total_c1 + a1 * c2 + a2 * c3, c1, length, degree

    def move(self, robot: int, c1: float, length: float, degree: np.ndarray) -> None:
        self.c1[robot], self.length[robot], self.degree[robot] = c1, length, degree


def local_search(scenario: Scenario, rule: Rule = "exact") -> LocalSearch:
    """Steepest descent over allowed SBF flips from the initial paths (see the module docstring).

    Args:
        scenario: The scenario.
        rule: SBF rule deciding which flips are allowed (flips to infeasible paths are skipped).

    Returns:
        The :class:`LocalSearch`.
    """
    t0 = time.perf_counter()
    space = MoveSpace(scenario, rule, "initial")
    paths = tuple(initial_path(scenario, r) for r in range(scenario.num_robots))
    terms = _Terms(scenario, paths)
    current = float(cost_parts_bits(scenario, paths_matrix(scenario, paths).reshape(-1))[3])
    trace = [current]
    evaluated = 1
    tol = 1e-9 * max(1.0, abs(current))
    while True:
        best: tuple[float, int, int, tuple[float, float, np.ndarray]] | None = None
        for r in range(scenario.num_robots):
            nbs = list(space.neighbours(r, paths[r]))
            if not nbs:
                continue
            totals, c1, length, degree = terms.candidates(r, nbs)
            evaluated += len(nbs)
            # first of the cheapest, lowest plaquette; ties within tol count as ties: the matrix products round
            # differently per candidate, and an argmin of exact ties would pick by rounding noise
            k = int(np.flatnonzero(totals <= totals.min() + tol)[0])
            if totals[k] < current - tol and (best is None or totals[k] < best[0] - tol):
                best = (float(totals[k]), r, nbs[k], (float(c1[k]), float(length[k]), degree[k]))
        if best is None:
            break
        current, r, mask, (c1_r, len_r, deg_r) = best
        paths = (*paths[:r], mask, *paths[r + 1:])
        terms.move(r, c1_r, len_r, deg_r)
        trace.append(current)
    return LocalSearch(paths, current, trace[0], len(trace) - 1, evaluated, time.perf_counter() - t0, tuple(trace))
