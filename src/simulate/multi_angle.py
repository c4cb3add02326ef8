"""Multi-angle QAOA mixers (one beta per partial mixer and layer), trained on the mixer-only product state.

Multi-angle QAOA (Herrman et al. 2022, Sci. Rep. 12, 6781) gives every term of a layer its own angle. Here the
mixer's terms are the partial mixers, one per robot and plaquette: the compiled circuit with
``PlanOptions(angles="multi")`` has the symbol :func:`circuitgen.angles.mixer_symbol` ``(k, r, q)`` on
partial mixer ``(r, q)`` of layer ``k``, the same gates as the one-beta-per-layer circuit.

With every gamma 0 the state is the product over robots of small vectors (:mod:`simulate.mixer_warm`), so
the betas are trained cheaply: :func:`train_multi_angle` minimises an objective of the measured cost's
distribution (default: the Gibbs objective, the same as the full training's; it never looks up the optimum)
with L-BFGS-B on the exact gradient (one adjoint sweep per robot over its own vector), from the constant
betas of :data:`simulate.mixer_warm.MIXER_STARTS`, from the previous depth's best with a zero layer appended,
and from ``random_starts`` seeded uniform random betas, and keeps the run with the lowest objective.

The angle vector is layer-major, then robot, then plaquette ascending, over the *sites* of
:func:`mixer_sites`: the partial mixers whose flip is allowed on some path the mixer reaches (the compiled
circuit's other partial mixers act as the identity on every reachable state; :func:`bindings` sets them to 0).

What it finds (``docs/results/multi_angle.md``): with a beta at pi a partial mixer is a deterministic SBF flip,
at 0 the identity, so a multi-angle layer can apply any subset of the flips in plaquette order. On
two_robots_4x4 the trained circuit is such a sequence of flips onto the optimum; on two_robots_5x5 (p >= 4) a
robot's state spreads over several paths on the way and is interfered back onto the optimal one. Many starts
end on a worse local minimum, where the gradient vanishes; the random starts are what finds the optimum.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> from simulate.subspace import SubspaceQAOA
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3},
    ...                         "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}]})
    >>> q = SubspaceQAOA(s)
    >>> res = train_multi_angle(q, 1, random_starts=2)
    >>> len(res.betas) == len(mixer_sites(q)), res.value <= res.start_values[0]
    (True, True)
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from operator import itemgetter

import numpy as np

from circuitgen.angles import mixer_symbol
from circuitgen.options import PlanOptions
from circuitgen.qaoa import qaoa_plan
from simulate.mixer_warm import (
    MIXER_MAXITER,
    MIXER_STARTS,
    descend,
    optimal_indices,
    p_optimum_and_gradients,
    product_descent,
    product_objective,
    robot_states,
    robot_states_gradient,
)
from simulate.objectives import ObjectiveFn, ObjectiveName, make_objective
from simulate.subspace import SubspaceQAOA
from simulate.training import cost_scale

__all__ = [
    "MULTI_RANDOM_STARTS",
    "MultiAngleResult",
    "bindings",
    "mixer_sites",
    "most_probable_multi",
    "multi_robot_states",
    "multi_robot_states_gradient",
    "p_optimum_multi",
    "train_multi_angle",
    "train_multi_angle_layers",
]

MULTI_RANDOM_STARTS = 8
"""Seeded random starts of :func:`train_multi_angle` per depth."""


def mixer_sites(qaoa: SubspaceQAOA) -> tuple[tuple[int, int], ...]:
    """``(robot, plaquette index)`` of every partial mixer that rotates some reachable path, robot-major,
    plaquettes ascending: the order of one layer's betas."""
    return tuple((r, qi) for r, b in enumerate(qaoa.robot_bases) for qi, _, _ in b.pairs)


def _check(qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray, p: int) -> np.ndarray:
    x = np.asarray(betas, dtype=float).reshape(-1)
    n = len(mixer_sites(qaoa))
    if p < 0 or x.size != p * n:
        raise ValueError(f"expected {p} x {n} betas (layers x partial mixers), got {x.size}")
    if not np.all(np.isfinite(x)):
        raise ValueError("betas must be finite")
    return x


def multi_robot_states(qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray, p: int) -> list[np.ndarray]:
    """Per robot, its state after ``p`` multi-angle mixer layers with every gamma 0
    (:func:`simulate.mixer_warm.robot_states` of the betas as a ``(p, sites)`` array).

    Args:
        qaoa: The simulator.
        betas: ``p * len(mixer_sites(qaoa))`` betas, layer-major (see the module docstring).
        p: Number of layers.

    Returns:
        One complex vector per robot; their outer product is the circuit's state on the reachable basis.

    Raises:
        ValueError: for a wrong number of betas or a value that is not finite.
    """
    return robot_states(qaoa, _check(qaoa, betas, p).reshape(p, -1))


def multi_robot_states_gradient(
    qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray, p: int, weights: Sequence[np.ndarray]
) -> np.ndarray:
    """``d/dbetas sum_r <psi_r| diag(weights[r]) |psi_r>`` for :func:`multi_robot_states`, same layout as ``betas``
    (:func:`simulate.mixer_warm.robot_states_gradient`)."""
    return robot_states_gradient(qaoa, _check(qaoa, betas, p).reshape(p, -1), weights).reshape(-1)


def bindings(qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray, p: int) -> dict[str, float]:
    """The symbol values of the compiled multi-angle circuit (``PlanOptions(angles="multi")``) for ``betas``.

    Every gamma is 0, the sites' betas are ``betas``, and the compiled circuit's other partial mixers (the
    identity on the reachable states) get 0. The keys are exactly the circuit's
    :attr:`~circuitgen.qaoa.QaoaPlan.parameter_names`.

    Example:
        >>> from gridcover.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> bindings(SubspaceQAOA(s), [0.5], 1)
        {'gamma_0': 0.0, 'beta_r0_q0_0': 0.5}
    """
    x = _check(qaoa, betas, p)
    n = len(mixer_sites(qaoa))
    given = {mixer_symbol(k, r, q): float(x[k * n + m])
             for k in range(p) for m, (r, q) in enumerate(mixer_sites(qaoa))}  # fmt: skip
    plan = qaoa_plan(qaoa.scenario, p, PlanOptions(rule=qaoa.rule, initial=qaoa.initial, angles="multi"))
    return {name: given.get(name, 0.0) for name in plan.parameter_names}


@dataclass(frozen=True)
class MultiAngleResult:
    """The outcome of :func:`train_multi_angle` at one depth.

    Attributes:
        p: Number of layers.
        betas: The trained betas (layer-major; ``p * len(mixer_sites)``), every gamma 0.
        value: The objective at ``betas``.
        expectation: ``<C>`` there.
        start_values: The objective reached from each start, in the order tried (constant betas, the previous
            depth's best with a zero layer, then the random starts).
        evaluations: Objective evaluations (each with its gradient) at this depth, every start included.
        seconds: Wall time at this depth.
    """

    p: int
    betas: tuple[float, ...]
    value: float
    expectation: float
    start_values: tuple[float, ...]
    evaluations: int
    seconds: float

    @property
    def num_parameters(self) -> int:
        """Trained angles: one per partial mixer and layer."""
        return len(self.betas)


def train_multi_angle(
    qaoa: SubspaceQAOA,
    p: int,
    objective: ObjectiveName | ObjectiveFn = "gibbs",
    random_starts: int = MULTI_RANDOM_STARTS,
    seed: int = 0,
    maxiter: int = MIXER_MAXITER,
    previous: Sequence[float] | None = None,
) -> MultiAngleResult:
    """Train the multi-angle mixer-only betas of depth ``p`` (gammas 0) with L-BFGS-B from several starts.

    Args:
        qaoa: The simulator.
        p: Number of layers (>= 1).
        objective: ``gibbs`` (default), ``cvar``, ``expectation`` (with
            :func:`simulate.objectives.make_objective`'s defaults for this scenario) or an objective object.
        random_starts: Seeded uniform random starts in ``[0, 2 pi)`` (>= 0).
        seed: Seed of ``numpy.random.default_rng`` for them.
        maxiter: L-BFGS-B iterations per start.
        previous: The best betas of depth ``p - 1``: also start from them with a zero layer appended (the same
            state, so the result is never worse than depth ``p - 1``'s).

    Returns:
        The best run as a :class:`MultiAngleResult`.

    Raises:
        ValueError: ``p < 1``, negative ``random_starts`` or ``maxiter``, or ``previous`` of the wrong length.
    """
    if p < 1:
        raise ValueError(f"p must be >= 1, got {p}")
    if random_starts < 0 or maxiter < 0:
        raise ValueError(f"random_starts and maxiter must be >= 0, got {random_starts} and {maxiter}")
    obj = make_objective(objective, cost_scale(qaoa)) if isinstance(objective, str) else objective
    n = len(mixer_sites(qaoa))
    t0 = time.perf_counter()
    starts = [np.full(p * n, b) for b in MIXER_STARTS]
    if previous is not None:
        starts.append(np.append(_check(qaoa, previous, p - 1), np.zeros(n)))
    rng = np.random.default_rng(seed)
    starts += [rng.uniform(0.0, 2 * np.pi, p * n) for _ in range(random_starts)]
    fg = product_descent(qaoa, partial(product_objective, qaoa, objective=obj), (p, n))
    ends, evaluations = descend(fg, starts, maxiter)
    f, mean, x = min(ends, key=itemgetter(0))
    return MultiAngleResult(p, tuple(float(v) for v in x), f, mean, tuple(e[0] for e in ends), evaluations,
                            time.perf_counter() - t0)


def train_multi_angle_layers(
    qaoa: SubspaceQAOA,
    p: int,
    objective: ObjectiveName | ObjectiveFn = "gibbs",
    random_starts: int = MULTI_RANDOM_STARTS,
    seed: int = 0,
    maxiter: int = MIXER_MAXITER,
    progress: Callable[[int, int], None] | None = None,
) -> list[MultiAngleResult]:
    """:func:`train_multi_angle` at ``p = 1 .. p`` in turn, each depth also started from the one before.

    Depth ``k`` draws its random starts with seed ``seed + k``. Deterministic.

    Args:
        qaoa, objective, random_starts, maxiter: As in :func:`train_multi_angle`.
        p: The largest depth (>= 1).
        seed: Base seed.
        progress: Called as ``progress(k, p)`` after depth ``k``.

    Returns:
        One :class:`MultiAngleResult` per depth ``1 .. p``.
    """
    if p < 1:
        raise ValueError(f"p must be >= 1, got {p}")
    out: list[MultiAngleResult] = []
    for k in range(1, p + 1):
        out.append(train_multi_angle(qaoa, k, objective, random_starts, seed + k, maxiter,
                                     previous=out[-1].betas if out else None))
        if progress is not None:
            progress(k, p)
    return out


def most_probable_multi(
    qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray, p: int
) -> tuple[tuple[int, ...], float]:
    """The most probable assignment (edge masks) of the multi-angle mixer-only state and its probability.

    The state is a product, so it is every robot's most probable path.
    """
    probs = [v.real * v.real + v.imag * v.imag for v in multi_robot_states(qaoa, betas, p)]
    idx = tuple(int(np.argmax(pr)) for pr in probs)
    return qaoa.assignment(idx), float(np.prod([pr[i] for pr, i in zip(probs, idx)]))


def p_optimum_multi(qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray, p: int) -> float:
    """``P(optimum)`` of the multi-angle mixer-only state (uses :meth:`SubspaceQAOA.optimum`)."""
    probs = [v.real * v.real + v.imag * v.imag for v in multi_robot_states(qaoa, betas, p)]
    return p_optimum_and_gradients(probs, optimal_indices(qaoa))[0]
