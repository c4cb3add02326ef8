"""QAOA as a solver: train on the subspace simulator, answer with the most probable assignment.

:func:`solve_qaoa` trains the angles (:func:`simulate.training.train`) and returns a :class:`QaoaSolution`:
a regular :class:`gridcover.solvers.Solution` (method ``qaoa``; paths = the most probable assignment of the
trained state; ``trace`` = the training's ``<C>`` per iteration; ``evaluated`` = simulations made in
training) plus the QAOA-specific numbers (that assignment's probability, ``p``, the angles, the training
result). :func:`qaoa_method` adapts it to the uniform :class:`gridcover.solvers.SolveMethod` signature so
front ends can list it beside ``dfs``/``anneal``/``genetic``; gridcover itself never imports this module.

Initial angles: seeded random (``init="random"``, :func:`simulate.training.initial_angles`) by default, so
``seed`` means what it means for the other stochastic solvers; ``linear-ramp`` and ``interp`` are available.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> from gridcover.solvers import dfs
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1]]},
    ...                         "robots": [{"start": [0, 0], "goal": [0, 2]}]})   # examples/paper_3x3.toml
    >>> res = solve_qaoa(s, p=1, seed=0)
    >>> res.solution.method, res.solution.cost.total == dfs(s).cost.total, res.probability > 0.9
    ('qaoa', True, True)
    >>> {"probability", "p", "angles", "trace"} <= set(qaoa_to_dict(s, res))
    True
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

from gridcover.cost import cost_parts
from gridcover.sbf import Rule
from gridcover.scenario import Scenario
from gridcover.solvers import ProgressFn, Solution, SolveMethod, solution_to_dict
from simulate.subspace import SubspaceQAOA
from simulate.training import INITS, OPTIMIZERS, Init, Optimizer, TrainingResult, most_probable, train

__all__ = ["QaoaSolution", "qaoa_method", "qaoa_to_dict", "solve_qaoa"]


@dataclass(frozen=True)
class QaoaSolution:
    """A trained QAOA run read as a solver answer.

    Attributes:
        solution: The :class:`~gridcover.solvers.Solution` (method ``qaoa``).
        probability: Probability of ``solution.paths`` in the trained state.
        p_optimum: Probability of the optimal assignments in the trained state.
        optimum: The optimal cost over the simulator's basis.
        training: The full :class:`~simulate.training.TrainingResult`.
    """

    solution: Solution
    probability: float
    p_optimum: float
    optimum: float
    training: TrainingResult

    @property
    def p(self) -> int:
        return self.training.p

    @property
    def angles(self) -> tuple[float, ...]:
        return self.training.angles

    @property
    def trace(self) -> tuple[float, ...]:
        return self.training.trace


def solve_qaoa(
    scenario: Scenario,
    *,
    p: int = 1,
    optimizer: Optimizer = "nesterov",
    init: Init = "random",
    seed: int = 0,
    rule: Rule = "exact",
    maxiter: int = 100,
    progress: ProgressFn | None = None,
) -> QaoaSolution:
    """Train a depth-``p`` QAOA on the feasible-subspace simulator and read off the most probable assignment.

    Args:
        scenario: The scenario.
        p: Layers (>= 1).
        optimizer: ``nesterov`` (the paper's, step 0.1 on the normalised objective), ``cobyla`` or ``lbfgsb``.
        init: Initial angles: ``random`` (from ``seed``), ``linear-ramp`` or ``interp``.
        seed: Seed of the random initial angles.
        rule: SBF rule of the mixer.
        maxiter: Optimiser budget (see :func:`simulate.training.train`).
        progress: Called as ``progress(0, 1)`` before and ``progress(1, 1)`` after training.

    Returns:
        The :class:`QaoaSolution`.

    Raises:
        ValueError: unknown optimiser / initialisation, ``p < 1``, negative ``maxiter``, or a mixer the subspace
            simulator cannot represent (``NonUnitaryMixerError``).
    """
    if optimizer not in OPTIMIZERS:
        raise ValueError(f"unknown optimizer {optimizer!r} (expected one of {', '.join(OPTIMIZERS)})")
    if init not in INITS:
        raise ValueError(f"unknown init {init!r} (expected one of {', '.join(INITS)})")
    t0 = time.perf_counter()
    if progress is not None:
        progress(0, 1)
    q = SubspaceQAOA(scenario, rule=rule)
    result = train(q, p, optimizer, init=init, seed=seed, maxiter=maxiter)
    masks, prob = most_probable(q, result.angles)
    if progress is not None:
        progress(1, 1)
    best, _ = q.optimum()
    solution = Solution(
        method="qaoa",
        paths=masks,
        cost=cost_parts(scenario, masks),
        seconds=time.perf_counter() - t0,
        evaluated=result.num_evaluations,
        trace=result.trace,
        seed=seed,
        rule=rule,
        notes=(
            f"p={p}, {optimizer} from {init} angles, {len(result.trace) - 1} iteration(s), "
            f"{result.num_evaluations} simulation(s) of {q.dimension:,} amplitudes",
            f"<C> {result.initial_expectation:.6g} -> {result.expectation:.6g}; the trained state reads an "
            f"optimal assignment (cost {best:g}) with probability {result.p_optimum:.4g}",
        ),
    )
    return QaoaSolution(solution, prob, result.p_optimum, best, result)


def qaoa_to_dict(scenario: Scenario, res: QaoaSolution) -> dict[str, Any]:
    """JSON-ready dict: :func:`~gridcover.solvers.solution_to_dict` (without its trace) plus ``probability``,
    ``p_optimum``, ``p``, ``angles``, ``optimizer`` and ``trace``."""
    out = solution_to_dict(scenario, res.solution, include_trace=False)
    out.update(
        probability=res.probability,
        p_optimum=res.p_optimum,
        p=res.p,
        angles=list(res.angles),
        optimizer=res.training.optimizer,
        trace=list(res.trace),
    )
    return out


def qaoa_method(
    p: int = 1, optimizer: Optimizer = "nesterov", init: Init = "random", maxiter: int = 100
) -> SolveMethod:
    """:func:`solve_qaoa` with fixed settings, as a :class:`gridcover.solvers.SolveMethod` (returns the
    ``Solution`` only).

    Example:
        >>> from gridcover.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> qaoa_method(p=1, maxiter=5)(s, seed=0, rule="exact", progress=None).method
        'qaoa'
    """

    def method(scenario: Scenario, *, seed: int, rule: Rule, progress: ProgressFn | None) -> Solution:
        return solve_qaoa(
            scenario, p=p, optimizer=optimizer, init=init, seed=seed, rule=rule, maxiter=maxiter, progress=progress
        ).solution

    return method
