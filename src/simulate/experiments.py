"""Measures for comparing QAOA with classical local search at an equal number of cost evaluations.

The question the experiments ask is "how likely is a method to have *seen* an optimal assignment after ``S``
cost evaluations?" (an evaluation = one assignment whose cost is computed classically).

**QAOA with S shots.** Measuring a trained QAOA state once returns an assignment, optimal with probability
``p_opt`` (:meth:`~simulate.subspace.SubspaceQAOA.p_optimum`); its cost is then evaluated. ``S`` independent
shots find an optimum with probability ``1 - (1 - p_opt)^S`` (:func:`success_probability`). This counts
only the shots taken from the *trained* state: training (which on hardware needs many shots per
expectation value) is left out, so it is the most favourable count for QAOA.

**Simulated annealing with S evaluations.** :func:`anneal_success` runs
:func:`gridcover.solvers.anneal` with a given iteration budget (its schedule fitted to that budget) from
many seeds; a run succeeds if its best assignment is optimal. The evaluations of a run are the annealer's
own ``Solution.evaluated`` (every cost look-up, its temperature calibration included); the success
probability is the empirical rate with a Wilson score interval (:func:`wilson_interval`).

**Uniform sampling** (the trivial baseline): ``S`` assignments drawn uniformly from the feasible basis
succeed with ``1 - (1 - n_opt / N)^S`` (:func:`uniform_hit_probability`).

Besides ``<C>``, QAOA angles can be fitted to other functions of the exact state (:func:`fit_angles`,
derivative-free COBYLA): the conditional value at risk ``CVaR_alpha`` (mean cost of the cheapest ``alpha``
probability mass; Barkoutsos et al., Quantum 4, 256, 2020; :func:`cvar`) and, as a reference that needs the
optimum and so is no algorithm, ``p_opt`` itself (the most any angles at that depth can put on the optimum,
as far as the local optimiser finds). :func:`layers_to_reach` gives the depth below which an assignment's
amplitude is exactly zero whatever the angles.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> from simulate.subspace import SubspaceQAOA
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> q = SubspaceQAOA(s)
    >>> m = state_metrics(q, [0.0, 1.2], alpha=0.25)
    >>> m.cvar <= m.expectation, 0.0 < m.p_optimum < 1.0
    (True, True)
    >>> round(float(success_probability(0.5, 3)), 6), shots_for(0.5, 0.99)
    (0.875, 7)
"""

from __future__ import annotations

import inspect
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.optimize import minimize

from gridcover.scenario import Scenario
from gridcover.solvers import anneal
from simulate.subspace import SubspaceQAOA, split_angles
from simulate.training import TrainingResult

__all__ = [
    "OBJECTIVES",
    "AngleFit",
    "AnnealSuccess",
    "StateMetrics",
    "anneal_success",
    "cost_distribution",
    "cvar",
    "fit_angles",
    "layers_to_reach",
    "shots_for",
    "state_metrics",
    "success_probability",
    "uniform_hit_probability",
    "wilson_interval",
]

_ANNEAL_PARAMS = inspect.signature(anneal).parameters

Objective = Literal["expectation", "cvar", "p_optimum"]
OBJECTIVES: tuple[Objective, ...] = ("expectation", "cvar", "p_optimum")


def success_probability(p_hit: float | np.ndarray, shots: int | np.ndarray) -> np.ndarray:
    """Probability that ``shots`` independent draws, each a hit with probability ``p_hit``, hit at least once.

    ``1 - (1 - p_hit)^shots``, computed as ``-expm1(shots * log1p(-p_hit))`` so that tiny ``p_hit`` keep
    their precision. Broadcasts over both arguments.

    Args:
        p_hit: Per-draw hit probability in ``[0, 1]``.
        shots: Number of draws (>= 0).

    Returns:
        The probability (float array; 0-d for scalar input).

    Raises:
        ValueError: if ``p_hit`` is outside ``[0, 1]`` or ``shots`` is negative.

    Example:
        >>> success_probability([0.0, 0.1, 1.0], 2).round(4).tolist()
        [0.0, 0.19, 1.0]
    """
    p = np.asarray(p_hit, dtype=float)
    s = np.asarray(shots, dtype=float)
    if np.any((p < 0) | (p > 1)) or np.any(~np.isfinite(p)):
        raise ValueError(f"p_hit must be in [0, 1], got {p_hit}")
    if np.any(s < 0):
        raise ValueError(f"shots must be >= 0, got {shots}")
    with np.errstate(divide="ignore", invalid="ignore"):
        out = -np.expm1(s * np.log1p(-p))
    return np.where(p >= 1, np.where(s > 0, 1.0, 0.0), out)


def shots_for(p_hit: float, target: float = 0.99) -> float:
    """Fewest draws that reach success probability ``target`` (``inf`` if ``p_hit == 0``).

    Example:
        >>> shots_for(0.1, 0.5), shots_for(1.0), shots_for(0.0)
        (7, 1, inf)
    """
    if not 0 <= p_hit <= 1:
        raise ValueError(f"p_hit must be in [0, 1], got {p_hit}")
    if not 0 < target < 1:
        raise ValueError(f"target must be in (0, 1), got {target}")
    if p_hit == 0:
        return math.inf
    if p_hit == 1:
        return 1
    n = math.ceil(math.log1p(-target) / math.log1p(-p_hit))
    # guard against rounding in the logarithms: the smallest n with 1 - (1-p)^n >= target
    while n > 1 and float(success_probability(p_hit, n - 1)) >= target:
        n -= 1
    while float(success_probability(p_hit, n)) < target:
        n += 1
    return n


def wilson_interval(successes: int, trials: int, z: float = 1.96) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion (default 95%).

    Example:
        >>> lo, hi = wilson_interval(50, 50)
        >>> round(lo, 3), hi
        (0.929, 1.0)
    """
    if trials < 1 or not 0 <= successes <= trials:
        raise ValueError(f"need 0 <= successes <= trials and trials >= 1, got {successes}/{trials}")
    phat = successes / trials
    den = 1 + z * z / trials
    centre = (phat + z * z / (2 * trials)) / den
    half = z * math.sqrt(phat * (1 - phat) / trials + z * z / (4 * trials * trials)) / den
    lo = 0.0 if successes == 0 else max(0.0, centre - half)  # the exact ends, free of rounding
    hi = 1.0 if successes == trials else min(1.0, centre + half)
    return lo, hi


# ---------------------------------------------------------------- functions of the QAOA state


def _flat_state(qaoa: SubspaceQAOA, state: np.ndarray | Sequence[float]) -> np.ndarray:
    """The state array (``state`` itself if it has the simulator's shape, else the state at angles ``state``)."""
    arr = np.asarray(state)
    if np.iscomplexobj(arr) and arr.shape == qaoa.dims:
        return arr.reshape(-1)
    return qaoa.state(arr).reshape(-1)


def cost_distribution(qaoa: SubspaceQAOA, state: np.ndarray | Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """The distribution of the measured cost: sorted distinct cost values and their probabilities.

    Args:
        qaoa: The simulator.
        state: A state array of shape ``qaoa.dims`` (complex), or angles to simulate.

    Returns:
        ``(values, probabilities)``, ``values`` ascending and distinct (up to ``1e-12``), probabilities
        summing to the state's norm squared.

    Example:
        >>> from gridcover.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 0], "goal": [1, 2]}]})
        >>> q = SubspaceQAOA(s)
        >>> v, w = cost_distribution(q, [])   # p = 0: all weight on the initial path
        >>> len(v), float(w.sum())
        (1, 1.0)
    """
    flat = _flat_state(qaoa, state)
    probs = flat.real * flat.real + flat.imag * flat.imag
    compact = qaoa.cost_levels()
    if compact is not None:
        values, levels = compact
        w = np.bincount(levels.reshape(-1), weights=probs, minlength=values.size)
        keep = w > 0
        return values[keep].copy(), w[keep]
    diag = qaoa.cost_diagonal().reshape(-1)
    order = np.argsort(diag, kind="stable")
    d, w = diag[order], probs[order]
    starts = np.flatnonzero(np.concatenate([[True], np.diff(d) > 1e-12 * np.maximum(1.0, np.abs(d[1:]))]))
    sums = np.add.reduceat(w, starts)
    keep = sums > 0
    return d[starts][keep], sums[keep]


def cvar(qaoa: SubspaceQAOA, state: np.ndarray | Sequence[float], alpha: float) -> float:
    """Conditional value at risk: the mean cost of the cheapest ``alpha`` of the measurement distribution.

    ``CVaR_1`` is ``<C>``; as ``alpha -> 0`` it tends to the cheapest cost with non-zero probability. The
    boundary level is taken fractionally, so the value is exact (not a sample estimate).

    Args:
        qaoa: The simulator.
        state: A state array of shape ``qaoa.dims`` (complex), or angles to simulate.
        alpha: Tail mass in ``(0, 1]``.

    Example:
        >>> from gridcover.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
        >>> q = SubspaceQAOA(s)
        >>> abs(cvar(q, [0.1, 0.7], 1.0) - q.expectation([0.1, 0.7])) < 1e-9
        True
    """
    if not 0 < alpha <= 1:
        raise ValueError(f"alpha must be in (0, 1], got {alpha}")
    values, w = cost_distribution(qaoa, state)
    w = w / w.sum()
    before = np.cumsum(w) - w
    take = np.clip(alpha - before, 0.0, w)
    return float(np.dot(take, values) / take.sum())


@dataclass(frozen=True)
class StateMetrics:
    """``<C>``, ``CVaR_alpha`` and ``p_opt`` of one QAOA state (one simulation)."""

    expectation: float
    cvar: float
    p_optimum: float
    alpha: float


def state_metrics(qaoa: SubspaceQAOA, angles: Sequence[float] | np.ndarray, alpha: float = 0.2) -> StateMetrics:
    """Simulate once and return :class:`StateMetrics` (see the module example)."""
    psi = qaoa.state(angles)
    return StateMetrics(
        expectation=qaoa.expectation_from_state(psi),
        cvar=cvar(qaoa, psi, alpha),
        p_optimum=qaoa.p_optimum_from_state(psi),
        alpha=alpha,
    )


def uniform_hit_probability(qaoa: SubspaceQAOA) -> float:
    """Fraction of the feasible basis assignments that are optimal (one uniform draw's hit probability).

    With the exact rule and connected move graphs the basis is every feasible assignment.

    Example:
        >>> from gridcover.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
        >>> uniform_hit_probability(SubspaceQAOA(s)) == 2 / 12   # two Hamiltonian paths among 12
        True
    """
    n_feasible = math.prod(int(f.sum()) for f in qaoa.feasible)
    return len(qaoa.optimum()[1]) / n_feasible


def layers_to_reach(qaoa: SubspaceQAOA, assignment: Sequence[int], max_layers: int = 1000) -> int | None:
    """Fewest QAOA layers after which ``assignment`` can carry amplitude at all.

    The support of the state grows by a fixed rule whatever the angles: the phase separator is diagonal, and
    each partial mixer (in the circuit's order: plaquettes ascending, per robot) can move amplitude across
    its pairs only. Each robot's support is propagated through one layer's ordered partial mixers until it
    holds the robot's path; the assignment needs the largest of these counts. Below that depth the
    amplitude is exactly zero for every choice of angles; from it on it is non-zero for generic angles
    (accidental cancellations aside).

    Args:
        qaoa: The simulator.
        assignment: One edge mask per robot.
        max_layers: Give up after this many layers.

    Returns:
        The number of layers (0 if the assignment is in the initial support), or ``None`` if it is not
        reachable within ``max_layers`` (e.g. outside the basis).

    Example:
        >>> from gridcover.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1]]},
        ...                         "robots": [{"start": [0, 0], "goal": [0, 2]}]})
        >>> q = SubspaceQAOA(s)
        >>> layers_to_reach(q, q.optimal_assignments()[0]), layers_to_reach(q, q.assignment((0,)))
        (1, 0)
    """
    worst = 0
    for basis, mask in zip(qaoa.robot_bases, assignment, strict=True):
        try:
            target = basis.index(mask)
        except KeyError:
            return None
        support = basis.initial > 0
        layers = 0
        while not support[target]:
            if layers == max_layers:
                return None
            before = support.copy()
            for _, ii, jj in basis.pairs:
                both = support[ii] | support[jj]
                support[ii] = both
                support[jj] = both
            layers += 1
            if np.array_equal(before, support):  # closed: the target is not reachable
                return None
        worst = max(worst, layers)
    return worst


@dataclass(frozen=True)
class AngleFit:
    """The outcome of :func:`fit_angles`.

    Attributes:
        p: Layers.
        objective: ``expectation``, ``cvar`` or ``p_optimum`` (the last maximised, the others minimised).
        alpha: CVaR tail mass (used only by ``cvar``).
        initial_angles: Start of the best restart.
        angles: Best angles found.
        value: The objective at ``angles`` (``p_optimum``: the probability, not its negative).
        metrics: :class:`StateMetrics` at ``angles``.
        trace: The objective at every evaluation of the best restart, in order.
        evaluations: Simulations over all restarts (the final metrics included).
        restarts: Number of starts tried.
        seconds: Wall-clock time.
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
        """The best (lowest ``<C>``) of several :func:`simulate.training.train` runs, as an ``expectation`` fit.

        ``evaluations`` and ``seconds`` add up over all runs (plus the one simulation for the metrics).

        Example:
            >>> from gridcover.scenario import scenario_from_dict
            >>> from simulate.training import train
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
        qaoa: The simulator.
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
        >>> from gridcover.scenario import scenario_from_dict
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


# ---------------------------------------------------------------- simulated annealing at a budget


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
    """Run :func:`gridcover.solvers.anneal` at each iteration budget from each seed; count optimal results.

    Args:
        scenario: The scenario.
        budgets: Iteration budgets (each >= 1; ``cycles`` is lowered to the budget when it would exceed it).
        seeds: Seeds (one run per seed and budget).
        optimum: The optimal total cost (e.g. from :func:`gridcover.solvers.dfs`).
        tol: A run succeeds if its cost is at most ``optimum + tol * max(1, |optimum|)``.
        **anneal_options: Passed on to ``anneal`` (e.g. ``components="initial"``, ``rule``).

    Returns:
        One :class:`AnnealSuccess` per budget, in the given order.

    Example:
        >>> from gridcover.scenario import scenario_from_dict
        >>> from gridcover.solvers import dfs
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
