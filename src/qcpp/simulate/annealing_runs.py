"""Simulated annealing at a fixed iteration budget over many seeds: the success rate and its interval.

A run succeeds if its best assignment is optimal. The evaluations of a run are the annealer's own
``Solution.evaluated`` (every cost look-up, its temperature calibration included); the success probability
is the empirical rate with a Wilson score interval (:func:`qcpp.simulate.success.wilson_interval`). Example: at
:func:`anneal_success`.
"""

from __future__ import annotations

import inspect
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers import anneal
from qcpp.simulate.success import wilson_interval

__all__ = ["AnnealSuccess", "anneal_success"]

_ANNEAL_PARAMS = inspect.signature(anneal).parameters


@dataclass(frozen=True)
class AnnealSuccess:
    """Simulated annealing's success rate at one iteration budget over many seeds.

    Attributes:
        iterations: Iterations per run (the schedule cools over exactly these).
        runs: Number of seeds.
        successes: Runs whose best assignment is optimal.
        evaluations: Mean cost evaluations per run (``Solution.evaluated``).
        max_evaluations: The largest over the runs.
        seconds: Mean wall-clock time per run.
    """

    iterations: int
    runs: int
    successes: int
    evaluations: float
    max_evaluations: int
    seconds: float

    @property
    def rate(self) -> float:
        """Empirical success probability."""
        return self.successes / self.runs

    def interval(self, z: float = 1.96) -> tuple[float, float]:
        """Wilson interval of :attr:`rate`."""
        return wilson_interval(self.successes, self.runs, z)


def anneal_success(
    scenario: Scenario,
    budgets: Sequence[int],
    seeds: Sequence[int],
    optimum: float,
    tol: float = 1e-9,
    **anneal_options: object,
) -> list[AnnealSuccess]:
    """Run :func:`qcpp.problem.solvers.anneal` at each iteration budget from each seed; count optimal results.

    Args:
        budgets: Iteration budgets (each >= 1; ``cycles`` is lowered to the budget when it would exceed it).
        seeds: Seeds (one run per seed and budget).
        optimum: The optimal total cost (e.g. from :func:`qcpp.problem.solvers.dfs`).
        tol: A run succeeds if its cost is at most ``optimum + tol * max(1, |optimum|)``.
        **anneal_options: Passed on to ``anneal`` (e.g. ``components="initial"``, ``rule``).

    Returns:
        One :class:`AnnealSuccess` per budget, in the given order.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> from qcpp.problem.solvers import dfs
        >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
        >>> [r.rate for r in anneal_success(s, [200], range(5), dfs(s).cost.total)]
        [1.0]
    """
    if not seeds:
        raise ValueError("anneal_success needs at least one seed")
    bar = optimum + tol * max(1.0, abs(optimum))
    out = []
    for budget in budgets:
        if budget < 1:
            raise ValueError(f"iteration budgets must be >= 1, got {budget}")
        opts = dict(anneal_options)
        if "cycles" in _ANNEAL_PARAMS:  # reheating cycles cannot outnumber the iterations
            cycles = opts.get("cycles", _ANNEAL_PARAMS["cycles"].default)
            opts["cycles"] = min(int(cycles), budget)  # type: ignore[call-overload]
        wins, evals, secs = 0, [], 0.0
        for seed in seeds:
            sol = anneal(scenario, seed=int(seed), iterations=int(budget), **opts)  # type: ignore[arg-type]
            wins += sol.cost.total <= bar
            evals.append(sol.evaluated)
            secs += sol.seconds
        out.append(
            AnnealSuccess(
                iterations=int(budget),
                runs=len(seeds),
                successes=wins,
                evaluations=float(np.mean(evals)),
                max_evaluations=int(max(evals)),
                seconds=secs / len(seeds),
            )
        )
    return out
