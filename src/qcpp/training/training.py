"""Training QAOA angles on the exact feasible-subspace simulator.

``train(qaoa, p, optimizer=..., init=..., seed=..., maxiter=...)`` minimises ``E(angles) = <psi| C |psi>`` of a
:class:`~qcpp.simulate.subspace.SubspaceQAOA` over ``[gamma_0, beta_0, ..., gamma_{p-1}, beta_{p-1}]`` and returns
a :class:`TrainingResult` (deterministic given the seed: the simulator is exact).

Optimisers (``optimizer=``):

``nesterov`` (the paper's)
    Gradient descent with Nesterov momentum in PennyLane's form (``a <- m a + eta grad f(x - m a)``, ``x <- x - a``;
    ``eta = 0.1``, ``m = 0.9``) on the exact adjoint gradient of ``f = E / sigma`` (``normalize=True``) or ``E``.
    Runs exactly ``maxiter`` steps.
``cobyla`` / ``lbfgsb``
    ``scipy.optimize.minimize`` with ``COBYLA`` (derivative-free, ``maxiter`` bounds the evaluations) or
    ``L-BFGS-B`` (exact gradient).

Initial angles (``init=``; ``sigma`` is the standard deviation of the cost over the basis, so ``gamma * sigma`` is
the typical phase spread), or an explicit start vector:

``random``
    ``gamma_k ~ U[0, pi / sigma)``, ``beta_k ~ U[0, pi)`` (larger gammas mostly alias; beta in ``[0, pi)`` runs each
    SBF rotation ``exp(-i beta X / 2)`` from the identity to a full swap).
``linear-ramp``
    ``t_k = (k + 1/2) / p``, ``gamma_k = 0.75 t_k / sigma``, ``beta_k = 1.5 (1 - t_k)`` (the usual ramp, doubled
    because the SBF rotation is ``exp(-i beta X / 2)``).
``interp``
    INTERP (Zhou et al., PRX 10, 021067, 2020): ``p = 1`` from the linear ramp, then each depth from the
    interpolation (:func:`interp_angles`) of the optimum one below; the lower depths are kept in
    :attr:`TrainingResult.stages`.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.simulate.subspace import SubspaceQAOA
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> q = SubspaceQAOA(s)
    >>> res = train(q, p=1, optimizer="lbfgsb", init="linear-ramp", maxiter=30)
    >>> res.expectation < res.initial_expectation, len(res.angles)
    (True, 2)
    >>> masks, prob = most_probable(q, res.angles)
    >>> 0.0 < prob <= 1.0
    True
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field, replace
from typing import Any, Literal

import numpy as np
from scipy.optimize import minimize

from qcpp.simulate.subspace import SubspaceQAOA, split_angles
from qcpp.training.objectives import ObjectiveFn, ObjectiveName, make_objective

__all__ = [
    "INITS",
    "OPTIMIZERS",
    "TrainingResult",
    "check_at_least",
    "cost_scale",
    "initial_angles",
    "interp_angles",
    "most_probable",
    "train",
]

Optimizer = Literal["nesterov", "cobyla", "lbfgsb"]
Init = Literal["random", "linear-ramp", "interp"]
OPTIMIZERS: tuple[Optimizer, ...] = ("nesterov", "cobyla", "lbfgsb")
INITS: tuple[Init, ...] = ("random", "linear-ramp", "interp")

_RAMP = 0.75


@dataclass(frozen=True)
class TrainingResult:
    """The outcome of :func:`train`.

    Attributes:
        p: Number of QAOA layers.
        optimizer: ``nesterov``, ``cobyla`` or ``lbfgsb``.
        init: The initialisation strategy (``explicit`` for a given vector).
        seed: The seed (only ``random`` uses it).
        initial_angles: The starting angles ``[gamma_0, beta_0, ...]``.
        angles: The final angles.
        initial_expectation: ``E`` at the start.
        expectation: ``E`` at the final angles.
        initial_p_optimum: Probability of the optimal assignments at the start.
        p_optimum: Probability of the optimal assignments at the final angles.
        trace: ``E`` per iteration (see the module docstring for what an iteration is per optimiser).
        num_evaluations: Simulations of the state made by :func:`train` (each expectation with or without
            gradient, the start and the end included; summed over INTERP levels).
        num_gradients: Of those, the ones that also computed the gradient.
        seconds: Wall-clock time (INTERP: all levels).
        stages: For ``interp``: the results at ``p' = 1 .. p-1`` (each with its own ``stages`` empty).
        objective: The minimised objective's name (:mod:`qcpp.training.objectives`); ``trace`` holds its values.
        initial_value: The objective at the start.
        value: The objective at the final angles.
    """

    p: int
    optimizer: str
    init: str
    seed: int | None
    initial_angles: tuple[float, ...]
    angles: tuple[float, ...]
    initial_expectation: float
    expectation: float
    initial_p_optimum: float
    p_optimum: float
    trace: tuple[float, ...]
    num_evaluations: int
    num_gradients: int
    seconds: float
    stages: tuple[TrainingResult, ...] = field(default=())
    objective: str = "expectation"
    initial_value: float = float("nan")
    value: float = float("nan")

    def as_dict(self) -> dict[str, Any]:
        """A JSON-ready dict (tuples become lists, stages nested)."""
        return asdict(self)


def cost_scale(qaoa: SubspaceQAOA) -> float:
    """Standard deviation of the cost over the simulator's basis assignments (1.0 if the cost is constant).

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> cost_scale(SubspaceQAOA(s))   # both paths cost the same
        1.0
    """
    compact = qaoa.cost_levels()
    if compact is not None:
        values, levels = compact
        w = np.bincount(levels.reshape(-1), minlength=values.size).astype(float)
    else:
        values = qaoa.cost_diagonal().reshape(-1)
        w = np.ones(values.size)
    w /= w.sum()
    mean = float(np.dot(w, values))
    sd = float(np.sqrt(max(0.0, float(np.dot(w, (values - mean) ** 2)))))
    return sd if sd > 1e-12 * max(1.0, abs(mean)) else 1.0


def check_at_least(**bounds: tuple[int, int]) -> None:
    """Raise ``ValueError("NAME must be >= LOW, got VALUE")`` for the first ``NAME=(VALUE, LOW)`` below its bound.

    Example:
        >>> check_at_least(p=(2, 1), maxiter=(-1, 0))
        Traceback (most recent call last):
        ValueError: maxiter must be >= 0, got -1
    """
    for name, (value, low) in bounds.items():
        if value < low:
            raise ValueError(f"{name} must be >= {low}, got {value}")


def initial_angles(qaoa: SubspaceQAOA, p: int, init: Init = "linear-ramp", seed: int | None = None) -> np.ndarray:
    """Starting angles for ``random`` or ``linear-ramp`` (see the module docstring).

    ``interp`` needs an optimum at ``p - 1``; use :func:`interp_angles` or ``train(..., init="interp")``.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> initial_angles(SubspaceQAOA(s), 2).round(4).tolist()
        [0.1875, 1.125, 0.5625, 0.375]
    """
    check_at_least(p=(p, 1))
    sigma = cost_scale(qaoa)
    if init == "random":
        rng = np.random.default_rng(seed)
        gammas = rng.uniform(0.0, np.pi / sigma, p)
        betas = rng.uniform(0.0, np.pi, p)
    elif init == "linear-ramp":
        t = (np.arange(p) + 0.5) / p
        gammas = _RAMP * t / sigma
        betas = 2 * _RAMP * (1 - t)
    elif init == "interp":
        raise ValueError("init='interp' needs the optimum at p-1: use train(..., init='interp') or interp_angles")
    else:
        raise ValueError(f"unknown init {init!r} (expected one of {', '.join(INITS)})")
    return _join(gammas, betas)


def interp_angles(angles: Sequence[float] | np.ndarray) -> np.ndarray:
    """INTERP: angles for ``p + 1`` layers from angles for ``p`` (Zhou et al. 2020, eq. B1).

    ``v'_i = (i - 1)/p * v_{i-1} + (p - i + 1)/p * v_i`` for ``i = 1..p+1`` (1-based, ``v_0 = v_{p+1} = 0``),
    applied to the gammas and to the betas separately.

    Example:
        >>> interp_angles([0.2, 1.0]).tolist()
        [0.2, 1.0, 0.2, 1.0]
        >>> interp_angles([0.1, 0.9, 0.3, 0.5]).tolist()
        [0.1, 0.9, 0.2, 0.7, 0.3, 0.5]
    """
    gammas, betas = split_angles(angles)
    p = len(gammas)

    def up(v: np.ndarray) -> np.ndarray:
        padded = np.concatenate([[0.0], v, [0.0]])
        i = np.arange(1, p + 2)
        return (i - 1) / p * padded[i - 1] + (p - i + 1) / p * padded[i]

    return _join(up(gammas), up(betas))


def most_probable(qaoa: SubspaceQAOA, angles: Sequence[float] | np.ndarray) -> tuple[tuple[int, ...], float]:
    """The most probable assignment (one edge mask per robot) and its probability (first one on ties)."""
    probs = qaoa.probabilities(angles)
    k = int(np.argmax(probs))
    return qaoa.assignment(np.unravel_index(k, probs.shape)), float(probs.reshape(-1)[k])


def train(
    qaoa: SubspaceQAOA,
    p: int,
    optimizer: Optimizer = "nesterov",
    init: Init | Sequence[float] | np.ndarray = "linear-ramp",
    seed: int | None = None,
    maxiter: int = 100,
    step: float = 0.1,
    momentum: float = 0.9,
    normalize: bool = True,
    objective: ObjectiveName | ObjectiveFn = "expectation",
) -> TrainingResult:
    """Optimise the ``2p`` angles to minimise the expectation value.

    Args:
        p: Number of layers (>= 1).
        optimizer: ``nesterov`` (default), ``cobyla`` or ``lbfgsb``.
        init: ``linear-ramp`` (default), ``random``, ``interp``, or an explicit vector of ``2p`` angles.
        seed: Seed of the ``random`` initialisation.
        maxiter: Steps (``nesterov``), function evaluations (``cobyla``) or iterations (``lbfgsb``); with
            ``interp``, per level.
        step: Nesterov step size.
        momentum: Nesterov momentum.
        normalize: Nesterov descends on ``E / sigma`` (:func:`cost_scale`) instead of ``E``, so that the step
            means the same on every cost scale; with ``False`` (the paper's raw ``E``) a step of 0.1 overshoots
            on costs whose gradients are in the tens (e.g. ``examples/paper_3x3.toml``). The trace and results
            are in units of ``E`` either way.
        objective: What to minimise: ``expectation`` (default), ``cvar``, ``gibbs`` (with their defaults, see
            :func:`qcpp.training.objectives.make_objective`) or an objective object; the trace holds its values.

    Raises:
        ValueError: for an unknown optimiser or initialisation, ``p < 1``, or an explicit vector of the wrong
            length.
    """
    if optimizer not in OPTIMIZERS:
        raise ValueError(f"unknown optimizer {optimizer!r} (expected one of {', '.join(OPTIMIZERS)})")
    check_at_least(p=(p, 1), maxiter=(maxiter, 0))
    t0 = time.perf_counter()
    stages: tuple[TrainingResult, ...] = ()
    if isinstance(init, str):
        label = init
        if init == "interp":
            if p == 1:
                x0 = initial_angles(qaoa, 1, "linear-ramp")
            else:
                prev = train(qaoa, p - 1, optimizer, "interp", seed, maxiter, step, momentum, normalize, objective)
                stages = (*prev.stages, _replace_stages(prev))
                x0 = interp_angles(prev.angles)
        else:
            x0 = initial_angles(qaoa, p, init, seed)  # type: ignore[arg-type]
    else:
        label = "explicit"
        x0 = np.asarray(init, dtype=float).reshape(-1)
        if x0.size != 2 * p:
            raise ValueError(f"explicit init has {x0.size} angles, expected {2 * p}")
        split_angles(x0)
    obj = make_objective(objective, cost_scale(qaoa)) if isinstance(objective, str) else objective
    counter = _Counter(qaoa, obj)
    init_e, init_popt, init_f = counter.evaluate_with_popt(x0)
    if optimizer == "nesterov":
        scale = cost_scale(qaoa) if normalize else 1.0
        x, trace = _nesterov(counter, x0, init_f, maxiter, step / scale, momentum)
    elif optimizer == "cobyla":
        x, trace = _cobyla(counter, x0, init_f, maxiter)
    else:
        x, trace = _lbfgsb(counter, x0, init_f, maxiter)
    final_e, final_popt, final_f = counter.evaluate_with_popt(x)
    prior_evals = sum(s.num_evaluations for s in stages)
    prior_grads = sum(s.num_gradients for s in stages)
    return TrainingResult(
        p=p,
        optimizer=optimizer,
        init=label,
        seed=seed,
        initial_angles=tuple(float(v) for v in x0),
        angles=tuple(float(v) for v in x),
        initial_expectation=init_e,
        expectation=final_e,
        initial_p_optimum=init_popt,
        p_optimum=final_popt,
        trace=tuple(float(v) for v in trace),
        num_evaluations=counter.evaluations + prior_evals,
        num_gradients=counter.gradients + prior_grads,
        seconds=time.perf_counter() - t0,  # includes the lower INTERP levels
        stages=stages,
        objective=str(getattr(obj, "name", "custom")),
        initial_value=init_f,
        value=final_f,
    )


# ---------------------------------------------------------------- internals


def _join(gammas: np.ndarray, betas: np.ndarray) -> np.ndarray:
    out = np.empty(2 * len(gammas))
    out[0::2], out[1::2] = gammas, betas
    return out


def _replace_stages(r: TrainingResult) -> TrainingResult:
    """``r`` without its own stages and with its counts/seconds for its level only."""
    if not r.stages:
        return r
    return replace(r, num_evaluations=r.num_evaluations - sum(s.num_evaluations for s in r.stages),
                   num_gradients=r.num_gradients - sum(s.num_gradients for s in r.stages),
                   seconds=r.seconds - sum(s.seconds for s in r.stages), stages=())


class _Counter:
    """Counts simulations and memoises the last few values (scipy re-evaluates points)."""

    def __init__(self, qaoa: SubspaceQAOA, objective: ObjectiveFn) -> None:
        self.qaoa = qaoa
        self.objective = objective
        self.plain = getattr(objective, "name", None) == "expectation"  # <C> has its own faster kernels
        self.evaluations = 0
        self.gradients = 0
        self.memo: dict[bytes, float] = {}

    def value(self, x: np.ndarray) -> float:
        key = np.asarray(x, dtype=float).tobytes()
        if key not in self.memo:
            self.evaluations += 1
            if self.plain:
                self._remember(key, self.qaoa.expectation(x))
            else:
                psi = self.qaoa.state(x)
                self._remember(key, self._value_of(psi))
        return self.memo[key]

    def _value_of(self, psi: np.ndarray) -> float:
        values, _ = self.qaoa.cost_distribution_index()
        return float(self.objective(values, self.qaoa.level_probabilities(psi))[0])

    def value_and_gradient(self, x: np.ndarray) -> tuple[float, np.ndarray]:
        self.evaluations += 1
        self.gradients += 1
        if self.plain:
            e, g = self.qaoa.value_and_gradient(x)
        else:
            e, g = self.qaoa.objective_and_gradient(x, self.objective)
        self._remember(np.asarray(x, dtype=float).tobytes(), e)
        return e, g

    def evaluate_with_popt(self, x: np.ndarray) -> tuple[float, float, float]:
        """``(<C>, P(optimum), objective)`` from one simulation."""
        self.evaluations += 1
        psi = self.qaoa.state(x)
        e = self.qaoa.expectation_from_state(psi)
        return e, self.qaoa.p_optimum_from_state(psi), e if self.plain else self._value_of(psi)

    def _remember(self, key: bytes, e: float) -> None:
        if len(self.memo) > 64:
            self.memo.clear()
        self.memo[key] = e


def _nesterov(
    c: _Counter, x0: np.ndarray, e0: float, maxiter: int, step: float, momentum: float
) -> tuple[np.ndarray, list[float]]:
    x = x0.copy()
    a = np.zeros_like(x)
    trace = [e0]
    for _ in range(maxiter):
        _, g = c.value_and_gradient(x - momentum * a)
        a = momentum * a + step * g
        x = x - a
        trace.append(c.value(x))
    return x, trace


def _cobyla(c: _Counter, x0: np.ndarray, e0: float, maxiter: int) -> tuple[np.ndarray, list[float]]:
    trace: list[float] = []

    def fun(x: np.ndarray) -> float:
        e = c.value(x)
        trace.append(e)
        return e

    if maxiter == 0:
        return x0.copy(), [e0]
    res = minimize(fun, x0, method="COBYLA", options={"maxiter": maxiter, "rhobeg": 0.5})
    return np.asarray(res.x, dtype=float), trace


def _lbfgsb(c: _Counter, x0: np.ndarray, e0: float, maxiter: int) -> tuple[np.ndarray, list[float]]:
    trace = [e0]

    def callback(xk: np.ndarray) -> None:
        trace.append(c.value(xk))

    fg: Callable[[np.ndarray], tuple[float, np.ndarray]] = c.value_and_gradient
    if maxiter == 0:
        return x0.copy(), trace
    res = minimize(fg, x0, jac=True, method="L-BFGS-B", callback=callback, options={"maxiter": maxiter})
    return np.asarray(res.x, dtype=float), trace
