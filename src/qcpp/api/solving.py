"""``qcpp.solve``, ``qcpp.train_qaoa`` and ``qcpp.simulate_qaoa``: the solvers and simulators of ``qcpp solve`` and
``qcpp simulate``, with their checks.

Example:
    >>> from qcpp.api.scenarios import grid_scenario
    >>> s = grid_scenario(3, 3, robots=1)
    >>> solve(s, "cpsat").cost.total == solve(s, "dfs").cost.total
    True
    >>> round(simulate_qaoa(s, 1, angles=[0.0, 0.0]).amplitudes_held, 6)
    1.0
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from qcpp.api.checks import check_angles_arg, check_layers_arg, check_scenario_arg
from qcpp.api.progress import ProgressArg, check_progress_arg, reporting
from qcpp.api.scenarios import Scenario
from qcpp.errors import OptionError, check_choice, check_count
from qcpp.problem.limits import API_OVERRIDE
from qcpp.training.objectives import GIBBS_SCALE

if TYPE_CHECKING:
    from qcpp.problem.solvers import Solution
    from qcpp.training.evaluate import Evaluation
    from qcpp.training.qaoa_solver import QaoaSolution

__all__ = ["SOLVE_METHODS", "simulate_qaoa", "solve", "train_qaoa"]

SOLVE_METHODS: tuple[str, ...] = ("dfs", "cpsat", "anneal", "genetic", "qaoa", "qubo")
"""The methods of :func:`solve` (those of ``qcpp solve --method``)."""

_QAOA_DEFAULTS: dict[str, Any] = {
    "p": 1, "optimizer": "layerwise", "objective": "gibbs", "maxiter": 200, "initial": "initial_path",
    "mixer_warm": False, "restart_every_level": None, "gibbs_scale": GIBBS_SCALE,
}  # fmt: skip


def solve(
    scenario: Scenario,
    method: str = "cpsat",
    *,
    seed: int = 0,
    rule: str = "exact",
    time_limit: float | None = None,
    workers: int | None = None,
    iterations: int | None = None,
    generations: int | None = None,
    sampler: str | None = None,
    progress: ProgressArg = None,
    stop: Callable[[], bool] | None = None,
    **qaoa_options: Any,
) -> Solution:
    """Solve ``scenario`` with ``method`` (``qcpp solve --method``) and return its answer.

    Args:
        method: ``dfs`` (exhaustive), ``cpsat`` (OR-Tools CP-SAT, the optimum with a proof), ``anneal``,
            ``genetic``, ``qaoa`` (trained on the feasible-subspace simulator; :func:`train_qaoa`) or ``qubo``.
            The default is ``cpsat`` (a script gets the proven optimum); ``qcpp solve`` defaults to ``anneal``, the
            paper's heuristic (docs/guide/solve.md says why they differ).
        seed: Random seed (stochastic methods).
        rule: SBF rule of the local moves and of the QAOA mixer: ``exact`` or ``paper``.
        time_limit: ``cpsat``, ``anneal``, ``genetic``: seconds before the search stops with its best so far
            (default: ``cpsat`` until proven optimal, the others all their iterations). An answer cut short says
            so in ``stopped`` (``"time limit"``); ``cpsat``'s proof fields say how far from optimal it may be.
        workers: ``cpsat``: CP-SAT's search threads (default 1: the same answer on every run; more may answer
            differently from run to run).
        iterations: ``anneal``: iterations per restart (default 20,000).
        generations: ``genetic``: generations (default 40).
        sampler: ``qubo``: ``tabu`` (tabu search, one run per read; the default) or ``sa`` (simulated annealing,
            1,000 sweeps per read), 100 reads on the per-robot QUBO (:func:`qcpp.qubo.solve.solve_qubo`).
        progress: ``True`` for progress lines on stderr, or a function ``progress(done, total)``
            (:mod:`qcpp.api.progress`), as ``qcpp solve`` counts: ``dfs`` the assignments scored of all of them,
            ``cpsat`` each improving solution found (``total`` ``None``), ``anneal`` and ``genetic`` their
            iterations or generations, ``qaoa`` the levels trained (:func:`train_qaoa`), ``qubo`` its three
            steps (building the QUBO, sampling, polishing).
        stop: ``cpsat``, ``anneal``, ``genetic``: a function the search calls between its steps (from the thread
            that called ``solve``); once it returns ``True`` the search ends with its best so far, marked
            ``stopped == "interrupted"`` (what ``qcpp solve`` does on Ctrl-C). For example a
            ``threading.Event``'s ``is_set`` that another thread or a signal handler sets.
        **qaoa_options: ``qaoa`` only: the options of :func:`train_qaoa` (``p``, ``optimizer``, ...).

    Returns:
        The :class:`~qcpp.problem.solvers.Solution` (paths as edge masks per robot, cost and its parts;
        ``node_paths(scenario)`` gives each path's nodes, ``to_dict(scenario)`` the ``qcpp solve --json`` object
        of the same method and options, ``cpsat``'s proof and ``qaoa``'s training included: the command's
        ``scenario`` field aside, the same dict).

    Raises:
        qcpp.errors.OptionError: an unknown method or option, or an option of another method.
        qcpp.problem.solvers.exhaustive.DfsTooLargeError: ``dfs`` over the limits of ``qcpp solve -m dfs``.
    """
    s = check_scenario_arg(scenario)
    check_choice(method, SOLVE_METHODS, "method")
    check_choice(rule, ("exact", "paper"), "rule")
    check_count(seed, "seed", 0)
    if method != "qaoa" and qaoa_options:
        name = next(iter(qaoa_options))
        if name not in _QAOA_DEFAULTS:
            raise OptionError(name, f"unknown option of solve (qaoa's: {', '.join(_QAOA_DEFAULTS)})")
        raise OptionError(name, f"applies to method='qaoa' only (got method={method!r})")
    from qcpp.problem.solvers.stopping import TIME_LIMITED

    methods = ", ".join(repr(m) for m in TIME_LIMITED[:-1]) + f" or {TIME_LIMITED[-1]!r}"
    for name, given in (("time_limit", time_limit), ("stop", stop)):
        if given is not None and method not in TIME_LIMITED:
            raise OptionError(name, f"applies to method={methods} only (got method={method!r})")
    if time_limit is not None and (isinstance(time_limit, bool) or not isinstance(time_limit, (int, float))
                                   or not 0 < time_limit < math.inf):  # fmt: skip
        raise OptionError("time_limit", f"expected a positive number of seconds, got {time_limit!r}")
    if stop is not None and not callable(stop):
        raise OptionError("stop", f"expected a function stop() -> bool, got {type(stop).__name__}")
    for name, value, owner in (("workers", workers, "cpsat"), ("iterations", iterations, "anneal"),
                               ("generations", generations, "genetic")):  # fmt: skip
        if value is not None:
            if method != owner:
                raise OptionError(name, f"applies to method={owner!r} only (got method={method!r})")
            check_count(value, name, 1)
    sizes = {k: v for k, v in (("iterations", iterations), ("generations", generations)) if v is not None}
    if sampler is not None:
        if method != "qubo":
            raise OptionError("sampler", f"applies to method='qubo' only (got method={method!r})")
        check_choice(sampler, ("tabu", "sa"), "sampler")
    check_progress_arg(progress)
    if method == "qaoa":
        return train_qaoa(s, seed=seed, rule=rule, progress=progress, **qaoa_options).solution
    from qcpp.problem.cost_range import check_cost_range

    check_cost_range(s)
    task = f"solve {method} on {s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s)"
    unit = {"dfs": "assignments", "cpsat": "improving solutions", "anneal": "iterations",
            "genetic": "generations"}.get(method, "steps")  # fmt: skip
    if method == "dfs":  # within the limits of qcpp solve -m dfs (qcpp.allow_large() lifts them)
        from qcpp.problem.solvers.exhaustive import budgeted_dfs_paths, dfs

        paths = budgeted_dfs_paths(s)
        with reporting(progress, task, unit=unit) as bar:
            return dfs(s, paths=paths, progress=bar and bar.update)
    if method == "cpsat":
        from qcpp.problem.solvers import cpsat

        with reporting(progress, task, unit=unit) as bar:
            return cpsat(s, seed=seed, time_limit=time_limit, workers=workers or 1,
                         progress=bar and bar.update, stop=stop).solution  # fmt: skip
    if method == "qubo":
        from qcpp.qubo.solve import solve_qubo

        with reporting(progress, task, unit=unit) as bar:
            return solve_qubo(s, sampler=sampler or "tabu", seed=seed, rule=rule,  # type: ignore[arg-type]
                              progress=bar and bar.update).solution  # fmt: skip
    from qcpp.problem.solvers import SOLVERS

    limits = {"time_limit": time_limit, "stop": stop, **sizes} if method in ("anneal", "genetic") else {}
    with reporting(progress, task, unit=unit, deadline=time_limit) as bar:
        return SOLVERS[method](s, seed=seed, rule=rule, progress=bar and bar.update, **limits)  # type: ignore[arg-type]


def train_qaoa(
    scenario: Scenario,
    p: int = 1,
    *,
    optimizer: str = "layerwise",
    objective: str = "gibbs",
    maxiter: int = 200,
    initial: str = "initial_path",
    mixer_warm: bool = False,
    restart_every_level: bool | None = None,
    gibbs_scale: float = GIBBS_SCALE,
    seed: int = 0,
    rule: str = "exact",
    progress: ProgressArg = None,
) -> QaoaSolution:
    """Train a depth-``p`` QAOA on the exact feasible-subspace simulator and read off its most probable assignment
    (``qcpp solve --method qaoa``).

    Args:
        p: QAOA layers.
        optimizer: ``layerwise`` (L-BFGS-B for p = 1, 2, ... in turn, warm-started), ``multi-angle``, or one
            ``nesterov``, ``cobyla`` or ``lbfgsb`` run at depth ``p``.
        objective: ``gibbs``, ``cvar`` or ``expectation``.
        maxiter: Optimiser steps per run.
        initial: Initial state (:data:`qcpp.plan.options.INITIAL_STATES`).
        mixer_warm: ``layerwise``: also start every level from the mixer-only warm start.
        restart_every_level: ``layerwise``: also start every level ``p > 1`` from the linear ramp and two random
            angle sets (a level's warm starts cannot leave a basis state the level below ended on). ``None``
            (default): on for ``layerwise``, off for the single-run optimisers.
        gibbs_scale: ``gibbs``: the inverse temperature in units of ``1 / sigma`` (``sigma``: the cost's standard
            deviation over the basis). Larger values weigh the optimum's share of the probability more; the
            default (40) and the restarts are the schedule docs/ensembles.md measures.
        seed: Random seed of the initial angles.
        rule: SBF rule of the mixer.
        progress: ``True`` for progress lines on stderr, or a function ``progress(done, total)``
            (:mod:`qcpp.api.progress`): ``progress(0, p)`` before training and ``progress(k, p)`` once level ``k``
            is trained (``layerwise``; a single-run optimiser reports ``(0, 1)`` and ``(1, 1)``).

    Returns:
        The :class:`~qcpp.training.qaoa_solver.QaoaSolution` (``.solution``, ``.angles``, ``.probability``,
        ``.p_optimum``, ``.trace``).

    Raises:
        qcpp.errors.OptionError: a bad value, naming the option.
        qcpp.problem.errors.ScenarioError: weights whose phases the simulator cannot represent exactly.
        qcpp.problem.limits.SizeError: a feasible subspace whose state does not fit in half the available memory
            (inside ``qcpp.allow_large()`` nothing is refused).
    """
    from qcpp.plan.options import INITIAL_STATES
    from qcpp.problem.cost_range import check_phase_range
    from qcpp.simulate.guards import check_training_size
    from qcpp.training.objectives import OBJECTIVES
    from qcpp.training.qaoa_solver import QAOA_OPTIMIZERS, solve_qaoa

    s = check_scenario_arg(scenario)
    layers = check_layers_arg(p)
    check_choice(optimizer, QAOA_OPTIMIZERS, "optimizer")
    check_choice(objective, OBJECTIVES, "objective")
    check_choice(initial, INITIAL_STATES, "initial")
    check_choice(rule, ("exact", "paper"), "rule")
    check_count(maxiter, "maxiter", 1)
    check_count(seed, "seed", 0)
    if not isinstance(mixer_warm, bool):
        raise OptionError("mixer_warm", f"expected True or False, got {mixer_warm!r}")
    if mixer_warm and optimizer != "layerwise":
        raise OptionError("mixer_warm", f"applies to optimizer='layerwise' only (got optimizer={optimizer!r})")
    if restart_every_level is not None and not isinstance(restart_every_level, bool):
        raise OptionError("restart_every_level", f"expected True, False or None, got {restart_every_level!r}")
    if restart_every_level and optimizer != "layerwise":
        raise OptionError("restart_every_level",
                          f"applies to optimizer='layerwise' only (got optimizer={optimizer!r})")
    if isinstance(gibbs_scale, bool) or not isinstance(gibbs_scale, (int, float)) or not (
            0 < gibbs_scale < math.inf):
        raise OptionError("gibbs_scale", f"expected a positive finite number, got {gibbs_scale!r}")
    if gibbs_scale != GIBBS_SCALE and objective != "gibbs":
        raise OptionError("gibbs_scale", f"applies to objective='gibbs' only (got objective={objective!r})")
    check_progress_arg(progress)
    check_phase_range(s)
    check_training_size(s, "scenario", API_OVERRIDE, "use qcpp.solve(scenario, 'cpsat') or 'anneal'", p=layers)
    task = f"train_qaoa p={layers} on {s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s)"
    # a level costs more than the one below it: the share of levels done does not extrapolate to the time left
    with reporting(progress, task, unit="levels", time_left=False) as bar:
        return solve_qaoa(
            s, p=layers, optimizer=optimizer, objective=objective, maxiter=maxiter,  # type: ignore[arg-type]
            initial=initial, mixer_warm=mixer_warm, restart_every_level=restart_every_level,  # type: ignore[arg-type]
            gibbs_scale=float(gibbs_scale), seed=seed, rule=rule, progress=bar and bar.update,  # type: ignore[arg-type]
        )  # fmt: skip


def simulate_qaoa(
    scenario: Scenario,
    p: int = 1,
    *,
    angles: Sequence[float] | None = None,
    method: str = "subspace",
    seed: int = 0,
    rule: str = "exact",
    client: Any = None,
    initial: str = "initial_path",
) -> Evaluation:
    """Evaluate the QAOA state at given (or seeded random) angles (``qcpp simulate``).

    Args:
        p: QAOA layers.
        angles: ``2p`` angles ``[gamma_0, beta_0, gamma_1, beta_1, ...]``; ``None``: random from ``seed``.
        method: ``subspace`` (exact feasible-subspace simulator), ``statevector`` (the compiled circuit's dense
            state) or ``tensor`` (tensor network).
        seed: Seed of the random angles.
        rule: SBF rule of the mixer.
        initial: Initial state (:data:`qcpp.plan.options.INITIAL_STATES`), as in :func:`train_qaoa`: angles
            trained from a state are evaluated on that state.
        client: ``tensor`` only: a connected ``dask.distributed.Client``; contractions wider than the tensor
            backend's memory limit (2^27 entries) are sliced and their slices run on its cluster, as
            ``qcpp validate --dask`` does.

    Returns:
        The :class:`~qcpp.training.evaluate.Evaluation` (``expectation``, ``p_optimum``, ``amplitudes_held``, ...).

    Raises:
        qcpp.errors.OptionError: a bad value, naming the option (``angles`` of the wrong length or not finite;
            ``client`` with another method than ``tensor``).
        qcpp.problem.limits.SizeError: a feasible subspace over the limits of ``qcpp simulate`` (inside
            ``qcpp.allow_large()`` nothing is refused).
    """
    from qcpp.plan.options import INITIAL_STATES
    from qcpp.problem.cost_range import check_phase_range
    from qcpp.simulate.guards import check_simulation_size
    from qcpp.training.evaluate import METHODS, evaluate

    s = check_scenario_arg(scenario)
    layers = check_layers_arg(p)
    check_choice(method, METHODS, "method")
    check_choice(rule, ("exact", "paper"), "rule")
    check_choice(initial, INITIAL_STATES, "initial")
    check_count(seed, "seed", 0)
    if client is not None and method != "tensor":
        raise OptionError("client", f"only the tensor method runs on a dask cluster, got method={method!r}")
    values = check_angles_arg(angles, layers)
    check_phase_range(s)
    check_simulation_size(s, "scenario", API_OVERRIDE, p=layers, method=method)
    return evaluate(
        s, layers, method, angles=values, seed=None if values is not None else seed, rule=rule,  # type: ignore[arg-type]
        client=client, initial=initial,  # type: ignore[arg-type]
    )
