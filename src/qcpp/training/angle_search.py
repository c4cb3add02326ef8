"""The most probability any angles put on the optimum, by an expensive search: a reference for the training.

The default training (:func:`qcpp.training.layerwise.train_layerwise`) minimises an objective that does not know
the optimum. Whether a low ``P(optimum)`` is the training's fault or the ansatz's shows only against the best
``P(optimum)`` the same circuit reaches at the same depth. :func:`search_p_optimum` looks for it directly, with
the optimum known (so it is no algorithm, only a yardstick), at every depth ``p = 1 .. P``:

* **local runs**: L-BFGS-B on ``-P(optimum)`` with its exact adjoint gradient
  (:meth:`qcpp.simulate.subspace.SubspaceQAOA.p_optimum_and_gradient`), at most ``budget.maxiter`` iterations,
  from every start of the level: the given warm angles (e.g. the default training's at that depth), the best
  angles of depth ``p - 1`` with a zero layer appended (the same state, so the best found never decreases with
  ``p``) and their INTERP extension, and ``budget.random_starts`` seeded random angles;
* **basin hopping** (monotonic): ``budget.hops`` times, the best angles so far perturbed by a normal step
  (``budget.step`` radians on the betas, ``budget.step / sigma`` on the gammas, ``sigma`` the cost scale) and
  optimised locally; a better result replaces the best.

Once a level reaches ``1 - budget.tolerance`` (the ceiling, up to the tolerance) the deeper levels search no
more: they take the same state with zero layers appended (``start = "reached"``, no evaluations). Every
simulation is counted (:attr:`SearchLevel.evaluations`). The search is deterministic given ``seed``.

**The ansatz's ceiling.** What the search finds is a lower bound on the ceiling ``max_angles P(optimum)`` at
depth ``p``. An upper bound holds whatever the angles: below :attr:`SearchLevel.reach_layers` layers
(:func:`qcpp.simulate.state_measures.layers_to_reach`, the fewest layers after which some optimal assignment can
carry amplitude at all) the ceiling is exactly 0; from there on this module bounds it by 1 only.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.simulate.subspace import SubspaceQAOA
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1]]},
    ...                         "robots": [{"start": [0, 0], "goal": [0, 2]}]})
    >>> levels = search_p_optimum(SubspaceQAOA(s), 2, budget=SearchBudget(random_starts=2, hops=1, maxiter=30))
    >>> [lv.p for lv in levels], levels[1].p_optimum >= levels[0].p_optimum, levels[0].ceiling_upper
    ([1, 2], True, 1.0)
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from qcpp.simulate.state_measures import layers_to_reach
from qcpp.simulate.subspace import SubspaceQAOA, split_angles
from qcpp.training.training import check_at_least, cost_scale, initial_angles, interp_angles

__all__ = ["SearchBudget", "SearchLevel", "search_p_optimum"]


@dataclass(frozen=True)
class SearchBudget:
    """How hard :func:`search_p_optimum` looks at each depth.

    Attributes:
        random_starts: Seeded random starts (besides the warm ones).
        hops: Basin-hopping steps from the best angles.
        maxiter: L-BFGS-B iterations per local run.
        step: Basin-hopping step (radians on the betas; divided by the cost scale on the gammas).
        tolerance: A level whose best is at least ``1 - tolerance`` ends the search (the ceiling is reached).
    """

    random_starts: int = 6
    hops: int = 4
    maxiter: int = 60
    step: float = 0.6
    tolerance: float = 1e-3

    def runs(self, warm: int) -> int:
        """Local runs per level with ``warm`` warm starts (the two from the level below included)."""
        return warm + self.random_starts + self.hops


@dataclass(frozen=True)
class SearchLevel:
    """The best found at one depth.

    Attributes:
        p: Layers.
        p_optimum: The best ``P(optimum)`` found (a lower bound on the ansatz's ceiling at ``p``).
        angles: Angles that give it.
        start: Which start led to it: ``warm``, ``previous``, ``interp``, ``random``, ``hop``, or ``reached``
            (a level below reached the ceiling; these are its angles with zero layers appended).
        runs: Local runs made at this level.
        evaluations: Simulations (each with its gradient) at this level.
        seconds: Wall-clock time of the level.
        reach_layers: Fewest layers after which an optimal assignment can carry amplitude (``None``: never).
    """

    p: int
    p_optimum: float
    angles: tuple[float, ...]
    start: str
    runs: int
    evaluations: int
    seconds: float
    reach_layers: int | None

    @property
    def ceiling_upper(self) -> float:
        """An upper bound on ``max_angles P(optimum)`` at this depth: 0 below :attr:`reach_layers`, else 1."""
        return 1.0 if self.reach_layers is not None and self.p >= self.reach_layers else 0.0


def search_p_optimum(
    qaoa: SubspaceQAOA,
    p: int,
    *,
    warm: Sequence[Sequence[float]] = (),
    budget: SearchBudget = SearchBudget(),
    seed: int = 0,
) -> tuple[SearchLevel, ...]:
    """The best ``P(optimum)`` found at every depth ``1 .. p`` (see the module docstring).

    Args:
        p: The largest depth (>= 1).
        warm: Optional warm angles per depth, ``warm[k]`` with ``2 (k + 1)`` values (fewer than ``p`` entries:
            the deeper levels have none).
        budget: Starts, hops and iterations per level.
        seed: Seed of the random starts and hops.

    Raises:
        ValueError: ``p < 1``, a negative budget, or warm angles of the wrong length.
    """
    check_at_least(p=(p, 1), random_starts=(budget.random_starts, 0), hops=(budget.hops, 0),
                   maxiter=(budget.maxiter, 1))
    for k, x in enumerate(warm[:p]):
        if len(x) != 2 * (k + 1):
            raise ValueError(f"warm[{k}] needs {2 * (k + 1)} angles, got {len(x)}")
    sigma = cost_scale(qaoa)
    reach = min((r for r in (layers_to_reach(qaoa, a) for a in qaoa.optimal_assignments()) if r is not None),
                default=None)
    rng = np.random.default_rng([seed, p])
    levels: list[SearchLevel] = []
    for level in range(1, p + 1):
        t0 = time.perf_counter()
        evaluations = 0
        if levels and levels[-1].p_optimum >= 1 - budget.tolerance:
            angles = (*levels[-1].angles, 0.0, 0.0)
            levels.append(SearchLevel(level, qaoa.p_optimum(angles), angles, "reached", 0, 1,
                                      time.perf_counter() - t0, reach))
            continue

        def local(x0: np.ndarray) -> tuple[float, np.ndarray]:
            nonlocal evaluations
            v, x, n = _local_max(qaoa, x0, budget.maxiter)
            evaluations += n
            return v, x

        starts: list[tuple[str, np.ndarray]] = []
        if level <= len(warm):
            starts.append(("warm", np.asarray(warm[level - 1], dtype=float)))
        if levels:
            prev = np.asarray(levels[-1].angles)
            starts += [("previous", np.concatenate([prev, [0.0, 0.0]])), ("interp", interp_angles(prev))]
        seeds = rng.integers(0, 2**31, size=budget.random_starts)
        starts += [("random", initial_angles(qaoa, level, "random", seed=int(s))) for s in seeds]
        top = (-1.0, np.zeros(2 * level), "")
        for label, x0 in starts:
            v, x = local(x0)
            if v > top[0]:
                top = (v, x, label)
        scale = np.tile([budget.step / sigma, budget.step], level)
        for _ in range(budget.hops):
            v, x = local(top[1] + scale * rng.standard_normal(2 * level))
            if v > top[0]:
                top = (v, x, "hop")
        split_angles(top[1])
        levels.append(SearchLevel(level, float(top[0]), tuple(float(a) for a in top[1]), top[2],
                                  len(starts) + budget.hops, evaluations, time.perf_counter() - t0, reach))
    return tuple(levels)


def _local_max(qaoa: SubspaceQAOA, x0: np.ndarray, maxiter: int) -> tuple[float, np.ndarray, int]:
    """L-BFGS-B on ``-P(optimum)`` from ``x0``: the best point evaluated, its value and the evaluations made."""
    best: list[tuple[float, np.ndarray]] = []

    def fun(x: np.ndarray) -> tuple[float, np.ndarray]:
        v, g = qaoa.p_optimum_and_gradient(x)
        if not best or v > best[0][0]:
            best[:] = [(v, np.array(x, dtype=float))]
        return -v, -g

    res = minimize(fun, x0, jac=True, method="L-BFGS-B", options={"maxiter": maxiter})
    return best[0][0], best[0][1], int(res.nfev)
