"""QAOA as a solver: train on the subspace simulator, answer with the most probable assignment.

:func:`solve_qaoa` trains the angles and returns a :class:`QaoaSolution`: a regular
:class:`qcpp.problem.solvers.Solution` (method ``qaoa``; paths = the most probable assignment of the trained state;
``trace`` = the objective per iteration; ``evaluated`` = simulations made) plus that assignment's probability,
``p``, the angles and the training result. :func:`qaoa_method` adapts it to the
:class:`qcpp.problem.solvers.SolveMethod` signature so front ends can list it beside ``dfs``/``anneal``/``genetic``
(qcpp.problem itself never imports this module).

Training (``optimizer=``): ``layerwise`` (default, :func:`qcpp.training.layerwise.train_layerwise`); ``nesterov``,
``cobyla`` and ``lbfgsb``: one run of :func:`qcpp.training.training.train` at depth ``p`` from ``init``;
``multi-angle``: the multi-angle mixer-only circuit (``PlanOptions(angles="multi")``) trained by
:func:`qcpp.training.mixer_only.train_multi_angle_layers`, whose ``angles`` are the ``p x partial mixers`` betas and
``bindings`` the compiled circuit's symbol values. Every optimiser minimises ``objective``
(:mod:`qcpp.training.objectives`; default ``gibbs``).

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.problem.solvers import dfs
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1]]},
    ...                         "robots": [{"start": [0, 0], "goal": [0, 2]}]})   # examples/paper_3x3.toml
    >>> res = solve_qaoa(s, p=1, seed=0)
    >>> res.solution.method, res.solution.cost.total == dfs(s).cost.total, res.probability > 0.9
    ('qaoa', True, True)
    >>> {"probability", "p", "angles", "trace"} <= set(qaoa_to_dict(s, res))
    True
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Any

from qcpp.problem.cost import cost_parts
from qcpp.problem.sbf import Rule
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers import ProgressFn, Solution, SolveMethod, solution_to_dict
from qcpp.simulate.subspace import INITIAL_STATES, InitialState, SubspaceQAOA, angle_bindings
from qcpp.training.layerwise import (
    DEFAULT_MAXITER,
    DEFAULT_RANDOM_STARTS,
    SHOTS_PER_ESTIMATE,
    LayerwiseResult,
    train_layerwise,
)
from qcpp.training.mixer_only import (
    bindings,
    most_probable_multi,
    multi_robot_states,
    p_optimum_multi,
    product_objective,
    train_multi_angle_layers,
)
from qcpp.training.objectives import (
    GIBBS_SCALE,
    OBJECTIVES,
    Expectation,
    ObjectiveFn,
    ObjectiveName,
    make_objective,
)
from qcpp.training.training import INITS, OPTIMIZERS, Init, TrainingResult, cost_scale, most_probable, train

__all__ = [
    "QAOA_OPTIMIZERS", "SINGLE_START", "QaoaSolution", "qaoa_details", "qaoa_method", "qaoa_to_dict", "solve_qaoa",
]

QAOA_OPTIMIZERS: tuple[str, ...] = ("layerwise", "multi-angle", *OPTIMIZERS)
SINGLE_START: Mapping[str, Any] = MappingProxyType({"restart_every_level": False, "gibbs_scale": 5.0})
"""Options of :func:`solve_qaoa` (and ``qcpp.train_qaoa``) for the single-start schedule: levels ``p > 1`` start
from the level below only, the Gibbs objective at ``eta = 5 / sigma``. The studies of training variants use it as
their baseline; docs/ensembles.md measures the default against it."""


@dataclass(frozen=True)
class QaoaSolution:
    """A trained QAOA run read as a solver answer.

    Attributes:
        solution: The :class:`~qcpp.problem.solvers.Solution` (method ``qaoa``).
        probability: Probability of ``solution.paths`` in the trained state.
        p_optimum: Probability of the optimal assignments in the trained state.
        optimum: The optimal cost of the scenario (:meth:`qcpp.simulate.subspace.SubspaceQAOA.optimum`).
        training: The :class:`~qcpp.training.training.TrainingResult` of the answer's angles (layerwise: the run
            kept at the final depth).
        schedule: The :class:`~qcpp.training.layerwise.LayerwiseResult` (``None`` for a single run).
        initial: The initial state trained from.
        bindings: The trained angles as the compiled circuit's symbol values (``gamma_k``, ``beta_k``; the
            multi-angle circuit's own symbols for ``multi-angle``): ``qcpp.compile(scenario, p, rule=...,
            initial=..., bind=bindings)`` with the rule and initial state trained with is the trained circuit.
        estimates: ``multi-angle``: the device objective estimates of its training (a gradient by the
            parameter-shift rule = 1 + 2 x parameters estimates).
    """

    solution: Solution
    probability: float
    p_optimum: float
    optimum: float
    training: TrainingResult
    schedule: LayerwiseResult | None = None
    initial: str = "initial_path"
    bindings: dict[str, float] = field(default_factory=dict)
    estimates: int | None = None

    @property
    def optimizer(self) -> str:
        return "layerwise" if self.schedule is not None else self.training.optimizer

    @property
    def p(self) -> int:
        return self.training.p

    @property
    def angles(self) -> tuple[float, ...]:
        return self.training.angles

    @property
    def trace(self) -> tuple[float, ...]:
        """The objective per iteration (layerwise: the kept run of every level, concatenated)."""
        return self.schedule.trace if self.schedule is not None else self.training.trace

    @property
    def num_evaluations(self) -> int:
        return self.schedule.num_evaluations if self.schedule is not None else self.training.num_evaluations

    @property
    def circuit_estimates(self) -> int:
        """Objective estimates a device would need (see :class:`~qcpp.training.layerwise.LayerwiseResult`)."""
        if self.estimates is not None:
            return self.estimates
        if self.schedule is not None:
            return self.schedule.circuit_estimates
        t = self.training
        return t.num_evaluations + 4 * t.p * t.num_gradients

    @property
    def training_shots(self) -> int:
        """Shots a device would spend on the training: :attr:`circuit_estimates` x
        :data:`~qcpp.training.layerwise.SHOTS_PER_ESTIMATE` (an assumed shots per objective estimate), the
        ``training_shots`` of ``qcpp solve -m qaoa --json``."""
        return self.circuit_estimates * SHOTS_PER_ESTIMATE


def solve_qaoa(
    scenario: Scenario,
    *,
    p: int = 1,
    optimizer: str = "layerwise",
    objective: ObjectiveName = "gibbs",
    init: Init = "random",
    initial: InitialState = "initial_path",
    seed: int = 0,
    rule: Rule = "exact",
    maxiter: int = DEFAULT_MAXITER,
    random_starts: int = DEFAULT_RANDOM_STARTS,
    mixer_warm: bool = False,
    restart_every_level: bool | None = None,
    gibbs_scale: float = GIBBS_SCALE,
    progress: ProgressFn | None = None,
) -> QaoaSolution:
    """Train a depth-``p`` QAOA on the feasible-subspace simulator and read off the most probable assignment.

    Args:
        p: Layers (>= 1).
        optimizer: ``layerwise`` (default), or one run of ``nesterov``, ``cobyla`` or ``lbfgsb``.
        objective: ``gibbs`` (default), ``cvar`` or ``expectation``.
        init: Initial angles of a single run: ``random`` (from ``seed``), ``linear-ramp`` or ``interp``.
        initial: Initial state: ``initial_path`` (default), ``representatives``, ``local_search`` or
            ``local_search_mix`` (:data:`qcpp.gadgets.initial_state.INITIAL_STATES`).
        seed: Seed of the random initial angles.
        rule: SBF rule of the mixer.
        maxiter: Optimiser budget per run (see :func:`qcpp.training.training.train`).
        random_starts: ``layerwise``: random starts at ``p = 1`` beside the linear ramp.
        mixer_warm: ``layerwise``: also start every level from the mixer-only warm start
            (:mod:`qcpp.training.mixer_only`; an option, not the default).
        restart_every_level: ``layerwise``: also start every level ``p > 1`` from the linear ramp and
            ``random_starts`` random angles (:func:`qcpp.training.layerwise.train_layerwise`). ``None`` (default):
            on for ``layerwise``, off for the single-run optimisers.
        gibbs_scale: ``gibbs``: the inverse temperature ``eta = gibbs_scale / sigma`` (``sigma``: the cost scale,
            :func:`qcpp.training.training.cost_scale`). Larger values weigh the optimum's share of the
            probability more against near-optimal assignments.
        progress: Called as ``progress(0, p)`` before training and ``progress(k, p)`` after level ``k``
            (``progress(1, 1)`` for a single run).

    Raises:
        ValueError: unknown optimiser / objective / initialisation, ``p < 1``, negative ``maxiter``,
            ``mixer_warm`` or ``restart_every_level=True`` with another optimiser than ``layerwise``, a
            ``gibbs_scale`` that is not positive and finite or set with another objective, or a mixer the
            subspace simulator cannot represent (``NonUnitaryMixerError``).
    """
    if optimizer not in QAOA_OPTIMIZERS:
        raise ValueError(f"unknown optimizer {optimizer!r} (expected one of {', '.join(QAOA_OPTIMIZERS)})")
    if mixer_warm and optimizer != "layerwise":
        raise ValueError(f"mixer_warm applies to the layerwise optimizer only (got {optimizer!r})")
    if restart_every_level and optimizer != "layerwise":
        raise ValueError(f"restart_every_level applies to the layerwise optimizer only (got {optimizer!r})")
    if not (gibbs_scale > 0 and math.isfinite(gibbs_scale)):
        raise ValueError(f"gibbs_scale must be positive and finite, got {gibbs_scale}")
    if gibbs_scale != GIBBS_SCALE and objective != "gibbs":
        raise ValueError(f"gibbs_scale applies to the gibbs objective only (got {objective!r})")
    if objective not in OBJECTIVES:
        raise ValueError(f"unknown objective {objective!r} (expected one of {', '.join(OBJECTIVES)})")
    if init not in INITS:
        raise ValueError(f"unknown init {init!r} (expected one of {', '.join(INITS)})")
    if initial not in INITIAL_STATES:
        raise ValueError(f"unknown initial state {initial!r} (expected one of {', '.join(INITIAL_STATES)})")
    restarts = optimizer == "layerwise" if restart_every_level is None else restart_every_level
    t0 = time.perf_counter()
    q = SubspaceQAOA(scenario, rule=rule, initial=initial)
    # the default objective goes by name (the trainers build it); another temperature needs the cost scale
    obj: ObjectiveName | ObjectiveFn = (objective if gibbs_scale == GIBBS_SCALE
                                        else make_objective(objective, cost_scale(q), gibbs_scale=gibbs_scale))
    if optimizer == "multi-angle":
        return _solve_multi_angle(q, p, obj, initial, seed, maxiter, progress, t0)
    schedule = None
    if optimizer == "layerwise":
        if progress is not None:
            progress(0, p)
        schedule = train_layerwise(q, p, objective, random_starts=random_starts, seed=seed, maxiter=maxiter,
                                   gibbs_scale=gibbs_scale, mixer_warm=mixer_warm,
                                   restart_every_level=restarts, progress=progress)
        result = schedule.best
        how = f"layer by layer p = 1..{p} ({schedule.runs} L-BFGS-B runs)"
        if not restarts:
            how += ", levels p > 1 from the level below only"
        if mixer_warm:
            how += (f", every level also from the mixer-only warm start ({schedule.mixer_evaluations} product-state "
                    "evaluations)")
    else:
        if progress is not None:
            progress(0, 1)
        result = train(q, p, optimizer, init=init, seed=seed, maxiter=maxiter, objective=obj)  # type: ignore[arg-type]
        if progress is not None:
            progress(1, 1)
        how = f"{optimizer} from {init} angles, {len(result.trace) - 1} iteration(s)"
    masks, prob = most_probable(q, result.angles)
    best, _ = q.optimum()
    start = f"initial state {initial}"
    if initial in ("local_search", "local_search_mix"):
        from qcpp.problem.solvers.descent import local_search

        warm = local_search(scenario, rule)
        mixed = "; in superposition with the initial paths" if initial == "local_search_mix" else ""
        start += (f" (steepest descent over SBF moves: cost {warm.initial_cost:g} -> {warm.cost:g} in {warm.steps} "
                  f"step(s), {warm.seconds * 1e3:.1f} ms{mixed})")
    evaluations = schedule.num_evaluations if schedule is not None else result.num_evaluations
    estimates = (schedule.circuit_estimates if schedule is not None
                 else result.num_evaluations + 4 * p * result.num_gradients)
    solution = Solution(
        method="qaoa",
        paths=masks,
        cost=cost_parts(scenario, masks),
        seconds=time.perf_counter() - t0,
        evaluated=evaluations,
        trace=schedule.trace if schedule is not None else result.trace,
        seed=seed,
        rule=rule,
        notes=(
            f"p={p}, {start}, objective {result.objective}, {how}, {evaluations} simulation(s) of {q.dimension:,} "
            f"amplitudes; on a device: {estimates:,} objective estimates, {estimates * SHOTS_PER_ESTIMATE:,} shots "
            f"at {SHOTS_PER_ESTIMATE:,} per estimate",
            f"<C> {result.initial_expectation:.6g} at the starting angles -> {result.expectation:.6g} trained; the "
            "trained state reads an "
            f"optimal assignment (cost {best:g}) with probability {result.p_optimum:.4g}",
            *_unreached_optimum_note(q),
        ),
    )
    return _with_details(QaoaSolution(
        solution, prob, result.p_optimum, best, result, schedule, initial, angle_bindings(result.angles)
    ))


def _solve_multi_angle(
    q: SubspaceQAOA, p: int, objective: ObjectiveName | ObjectiveFn, initial: str, seed: int, maxiter: int,
    progress: ProgressFn | None, t0: float,
) -> QaoaSolution:
    """``optimizer="multi-angle"`` of :func:`solve_qaoa`."""
    if progress is not None:
        progress(0, p)
    levels = train_multi_angle_layers(q, p, objective, seed=seed, maxiter=maxiter, progress=progress)
    best = levels[-1]
    masks, prob = most_probable_multi(q, best.betas, p)
    optimum, _ = q.optimum()
    p_opt = p_optimum_multi(q, best.betas, p)
    start = p_optimum_multi(q, [0.0] * best.num_parameters, p)
    zero = [v.real * v.real + v.imag * v.imag for v in multi_robot_states(q, [0.0] * best.num_parameters, p)]
    start_mean = product_objective(q, zero, Expectation())[1]
    evaluations = sum(lv.evaluations for lv in levels)
    estimates = sum(lv.evaluations * (1 + 2 * lv.num_parameters) for lv in levels)
    trace = tuple(v for lv in levels for v in lv.start_values)
    seconds = time.perf_counter() - t0
    training = TrainingResult(
        p=p, optimizer="multi-angle", init="constant and random", seed=seed, initial_angles=(),
        angles=best.betas, initial_expectation=start_mean,
        expectation=best.expectation, initial_p_optimum=start, p_optimum=p_opt, trace=trace,
        num_evaluations=evaluations, num_gradients=evaluations, seconds=seconds,
        objective=str(getattr(objective, "name", objective)), value=best.value,
    )
    solution = Solution(
        method="qaoa",
        paths=masks,
        cost=cost_parts(q.scenario, masks),
        seconds=seconds,
        evaluated=evaluations,
        trace=trace,
        seed=seed,
        rule=q.rule,
        notes=(
            f"p={p}, initial state {initial}, multi-angle mixer-only (every gamma 0, {best.num_parameters} betas: one "
            f"per partial mixer and layer), objective {objective}, L-BFGS-B layer by layer p = 1..{p} from "
            f"{len(best.start_values)} starts per depth, {evaluations} product-state evaluations with gradient; on a "
            f"device: {estimates:,} objective estimates, {estimates * SHOTS_PER_ESTIMATE:,} shots at "
            f"{SHOTS_PER_ESTIMATE:,} per estimate",
            f"<C> {start_mean:.6g} -> {best.expectation:.6g}; the trained state reads an optimal assignment (cost "
            f"{optimum:g}) with probability {p_opt:.4g}",
            *_unreached_optimum_note(q),
        ),
    )
    return _with_details(QaoaSolution(solution, prob, p_opt, optimum, training, None, initial,
                                      bindings(q, best.betas, p), estimates))


def _unreached_optimum_note(q: SubspaceQAOA) -> tuple[str, ...]:
    """The note a QAOA answer adds where its initial state cannot reach the optimum (hard obstacles split a robot's
    paths into components SBF moves do not join, and the state starts in none that holds it), else nothing: where
    :meth:`~qcpp.simulate.subspace.SubspaceQAOA.optimum` finds no basis assignment of the optimal cost."""
    if len(q.optimum()[1]):
        return ()
    return (f"the initial state {q.initial} starts in none of the move-graph components that hold the optimum (hard "
            "obstacles split the paths; the mixer never joins them): P(optimum) is 0 at any angles; --initial "
            "representatives starts in every component",)  # fmt: skip


def qaoa_details(res: QaoaSolution) -> tuple[tuple[str, Any], ...]:
    """The JSON fields a QAOA answer adds to :func:`~qcpp.problem.solvers.solution_to_dict` (its
    ``Solution.details``, which :func:`solve_qaoa` sets): ``probability``, ``p_optimum``, ``p``, ``angles``,
    ``optimizer``, ``initial`` (the initial state), ``objective``, ``expectation``, ``trace`` (the objective),
    ``evaluations``, ``circuit_estimates``, ``training_shots`` (estimates x ``shots_per_estimate``, an assumed
    :data:`qcpp.training.layerwise.SHOTS_PER_ESTIMATE`), ``bindings`` (when there are any) and, for ``layerwise``,
    ``mixer_evaluations`` (the mixer-only warm start's product-state evaluations, 0 without it) and ``levels`` (per
    depth: ``p``, objective ``value``, ``expectation``, ``p_optimum``, ``iterations``)."""
    out: list[tuple[str, Any]] = [
        ("probability", res.probability),
        ("p_optimum", res.p_optimum),
        ("p", res.p),
        ("angles", list(res.angles)),
        ("optimizer", res.optimizer),
        ("initial", res.initial),
        ("objective", res.training.objective),
        ("expectation", res.training.expectation),
        ("trace", list(res.trace)),
        ("evaluations", res.num_evaluations),
        ("circuit_estimates", res.circuit_estimates),
        ("training_shots", res.training_shots),
        ("shots_per_estimate", SHOTS_PER_ESTIMATE),
    ]
    if res.bindings:
        out.append(("bindings", dict(res.bindings)))
    if res.schedule is not None:
        out.append(("mixer_evaluations", res.schedule.mixer_evaluations))
        out.append(("levels", [{"p": lv.p, "value": lv.value, "expectation": lv.expectation,
                                "p_optimum": lv.p_optimum, "iterations": len(lv.trace) - 1}
                               for lv in res.schedule.levels]))
    return tuple(out)


def _with_details(res: QaoaSolution) -> QaoaSolution:
    """``res`` whose solution carries :func:`qaoa_details`: ``qcpp.solve(s, "qaoa").to_dict(s)`` has them."""
    return replace(res, solution=replace(res.solution, details=qaoa_details(res)))


def qaoa_to_dict(scenario: Scenario, res: QaoaSolution) -> dict[str, Any]:
    """JSON-ready dict: :func:`~qcpp.problem.solvers.solution_to_dict` with the fields of :func:`qaoa_details`
    (``res.solution.to_dict(scenario)`` for an answer of :func:`solve_qaoa`)."""
    return solution_to_dict(scenario, replace(res.solution, details=qaoa_details(res)))


def qaoa_method(
    p: int = 1, optimizer: str = "layerwise", init: Init = "random", maxiter: int = DEFAULT_MAXITER,
    objective: ObjectiveName = "gibbs",
) -> SolveMethod:
    """:func:`solve_qaoa` with fixed settings, as a :class:`qcpp.problem.solvers.SolveMethod` (returns the
    ``Solution`` only).

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> qaoa_method(p=1, maxiter=5)(s, seed=0, rule="exact", progress=None).method
        'qaoa'
    """

    def method(scenario: Scenario, *, seed: int, rule: Rule, progress: ProgressFn | None) -> Solution:
        return solve_qaoa(
            scenario, p=p, optimizer=optimizer, init=init, seed=seed, rule=rule, maxiter=maxiter,
            objective=objective, progress=progress,
        ).solution

    return method
