"""Derivative-free angle fits (COBYLA) to functions of the exact state, the probability of the optimum included.

:func:`fit_angles` fits QAOA angles to ``<C>``, ``CVaR_alpha`` or, as a reference that needs the optimum and so
is no algorithm, ``P(optimum)`` itself (the most any angles at that depth put on the optimum, as far as the
local optimiser finds). :meth:`AngleFit.from_training` reads gradient-based runs
(:func:`qcpp.training.training.train`) as a fit. The default training is
:func:`qcpp.training.layerwise.train_layerwise`. Example: at :func:`fit_angles`.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.optimize import minimize

from qcpp.simulate.state_measures import StateMetrics, cvar, state_metrics
from qcpp.simulate.subspace import SubspaceQAOA, split_angles
from qcpp.training.training import TrainingResult

__all__ = ["OBJECTIVES", "AngleFit", "fit_angles"]

Objective = Literal["expectation", "cvar", "p_optimum"]
OBJECTIVES: tuple[Objective, ...] = ("expectation", "cvar", "p_optimum")


@dataclass(frozen=True)
class AngleFit:
    """The outcome of :func:`fit_angles`.

    Attributes:
        objective: ``expectation``, ``cvar`` or ``p_optimum`` (the last maximised, the others minimised).
        alpha: CVaR tail mass (used only by ``cvar``).
        initial_angles: Start of the best restart.
        angles: Best angles found.
        value: The objective at ``angles`` (``p_optimum``: the probability, not its negative).
        metrics: :class:`StateMetrics` at ``angles``.
        trace: The objective at every evaluation of the best restart, in order.
        evaluations: Simulations over all restarts (the final metrics included).
        restarts: Number of starts tried.
    """

    p: int
    objective: str
    alpha: float
    initial_angles: tuple[float, ...]
    angles: tuple[float, ...]
    value: float
    metrics: StateMetrics
    trace: tuple[float, ...]
    evaluations: int
    restarts: int
    seconds: float

    @classmethod
    def from_training(cls, qaoa: SubspaceQAOA, runs: Sequence[TrainingResult], alpha: float = 0.2) -> AngleFit:
        """The best (lowest ``<C>``) of several :func:`qcpp.training.training.train` runs, as an ``expectation`` fit.

        ``evaluations`` and ``seconds`` add up over all runs (plus the one simulation for the metrics).

        Example:
            >>> from qcpp.problem.scenario import scenario_from_dict
            >>> from qcpp.training.training import train
            >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
            >>> q = SubspaceQAOA(s)
            >>> runs = [train(q, 1, "lbfgsb", init="random", seed=k, maxiter=20) for k in range(2)]
            >>> fit = AngleFit.from_training(q, runs)
            >>> fit.value == min(r.expectation for r in runs), fit.restarts
            (True, 2)
        """
        if not runs:
            raise ValueError("from_training needs at least one run")
        t0 = time.perf_counter()
        best = min(runs, key=lambda r: r.expectation)
        metrics = state_metrics(qaoa, best.angles, alpha)
        return cls(
            p=best.p,
            objective="expectation",
            alpha=alpha,
            initial_angles=best.initial_angles,
            angles=best.angles,
            value=best.expectation,
            metrics=metrics,
            trace=best.trace,
            evaluations=sum(r.num_evaluations for r in runs) + 1,
            restarts=len(runs),
            seconds=sum(r.seconds for r in runs) + time.perf_counter() - t0,
        )


def fit_angles(
    qaoa: SubspaceQAOA,
    starts: Sequence[Sequence[float]] | np.ndarray,
    objective: Objective = "cvar",
    alpha: float = 0.2,
    maxiter: int = 200,
    rhobeg: float = 0.5,
) -> AngleFit:
    """Fit QAOA angles to a function of the exact state with COBYLA, from each start; keep the best.

    Args:
        starts: One or more start vectors ``[gamma_0, beta_0, ...]`` (all the same length ``2p``).
        objective: ``expectation`` (``<C>``), ``cvar`` (``CVaR_alpha``, see :func:`cvar`) or ``p_optimum``
            (maximised; a reference only, it needs the optimum).
        alpha: CVaR tail mass.
        maxiter: COBYLA's evaluation budget per start.
        rhobeg: COBYLA's initial step (radians).

    Returns:
        The :class:`AngleFit` of the best point evaluated over all starts (lowest objective; highest for
        ``p_optimum``).

    Raises:
        ValueError: for an unknown objective, no starts, or starts of different or odd lengths.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
        >>> q = SubspaceQAOA(s)
        >>> fit = fit_angles(q, [[0.1, 0.3]], "p_optimum", maxiter=60)
        >>> fit.value > q.p_optimum([0.1, 0.3]), len(fit.angles)
        (True, 2)
    """
    if objective not in OBJECTIVES:
        raise ValueError(f"unknown objective {objective!r} (expected one of {', '.join(OBJECTIVES)})")
    x0s = [np.asarray(x, dtype=float).reshape(-1) for x in starts]
    if not x0s:
        raise ValueError("fit_angles needs at least one start")
    if len({x.size for x in x0s}) != 1:
        raise ValueError("all starts must have the same number of angles")
    for x in x0s:
        split_angles(x)
    sign = -1.0 if objective == "p_optimum" else 1.0
    t0 = time.perf_counter()
    evaluations = 0
    best: tuple[float, np.ndarray, np.ndarray, list[float]] | None = None
    for x0 in x0s:
        trace: list[float] = []
        seen: list[tuple[float, np.ndarray]] = []  # (signed value, x) of the best evaluation so far

        def fun(x: np.ndarray, trace: list[float] = trace, seen: list[tuple[float, np.ndarray]] = seen) -> float:
            nonlocal evaluations
            evaluations += 1
            psi = qaoa.state(x)
            if objective == "expectation":
                v = qaoa.expectation_from_state(psi)
            elif objective == "cvar":
                v = cvar(qaoa, psi, alpha)
            else:
                v = qaoa.p_optimum_from_state(psi)
            trace.append(v)
            if not seen or sign * v < seen[0][0]:
                seen[:] = [(sign * v, np.array(x, dtype=float))]
            return sign * v

        minimize(fun, x0, method="COBYLA", options={"maxiter": maxiter, "rhobeg": rhobeg})
        val, x = seen[0]  # the best point evaluated (COBYLA's last iterate need not be it on a short budget)
        if best is None or val < best[0]:
            best = (val, x, x0, trace)
    assert best is not None
    val, x, x0, trace = best
    metrics = state_metrics(qaoa, x, alpha)
    evaluations += 1
    return AngleFit(
        p=x.size // 2,
        objective=objective,
        alpha=alpha,
        initial_angles=tuple(float(v) for v in x0),
        angles=tuple(float(v) for v in x),
        value=sign * val,
        metrics=metrics,
        trace=tuple(trace),
        evaluations=evaluations,
        restarts=len(x0s),
        seconds=time.perf_counter() - t0,
    )
