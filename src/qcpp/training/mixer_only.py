"""Mixer-only QAOA (every gamma 0), where the state is a product over robots: the warm start and multi-angle.

With ``gamma_k = 0`` the phase separators are the identity and each robot's partial mixers act on its own axis,
so the state is the product of per-robot vectors of the robot's basis size (thousands of paths rather than
millions of assignments). The measured cost's distribution of that product is still the full one,
``w_v = sum_{x: C(x) = v} prod_r |psi_r(x_r)|^2``, computed in one pass over the cost levels
(:func:`product_objective`); one adjoint sweep per robot turns its derivative into the betas' gradient
(:func:`robot_states_gradient`). The objectives are the full training's (default ``gibbs``): training never
looks up the optimum.

The betas come in two shapes, one kernel (:func:`robot_states`) for both:

* **One beta per layer** (the warm start, :func:`train_mixer_only`). Every objective of the measured cost is even
  in the gammas and in the betas, so its gradient vanishes at ``beta = 0`` and at ``gamma = 0``: a layer-by-layer
  training can stay stuck there. The warm start finds betas that spread each robot over its paths towards cheap
  assignments, and the full training starts its gammas elsewhere
  (:func:`qcpp.training.layerwise.train_layerwise` with ``mixer_warm=True``). :func:`mixer_only_ceiling` is a
  diagnostic: the best ``P(optimum)`` over these angles, found by maximising it directly (it uses the optimum).
* **One beta per partial mixer and layer** (multi-angle QAOA, Herrman et al. 2022, Sci. Rep. 12, 6781:
  :func:`train_multi_angle`). The circuit compiled with ``PlanOptions(angles="multi")`` has the symbol
  :func:`qcpp.ir.angles.mixer_symbol` ``(k, r, q)`` on partial mixer ``(r, q)`` of layer ``k``. The angle vector
  is layer-major, then robot, then plaquette, over the *sites* of :func:`mixer_sites` (the partial mixers whose
  flip is allowed on some reachable path; :func:`bindings` sets the others to 0). A beta at pi is a deterministic
  flip and 0 the identity, so a layer can apply any subset of the flips; many starts end in a worse local
  minimum, and the random starts are what finds the optimum.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.simulate.subspace import SubspaceQAOA
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3},
    ...                         "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}]})
    >>> q = SubspaceQAOA(s)
    >>> w = train_mixer_only(q, 2)[-1]   # one result per depth 1..2
    >>> len(w.betas), w.value < w.initial_value
    (2, True)
    >>> import numpy as np   # the product state is the simulator's state at gammas 0
    >>> full = q.probabilities([0.0, w.betas[0], 0.0, w.betas[1]])
    >>> bool(np.allclose(full, np.multiply.outer(*(abs(v) ** 2 for v in robot_states(q, w.betas)))))
    True
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
from scipy.optimize import minimize

from qcpp.ir.angles import mixer_symbol
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.simulate import subspace_kernels
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.objectives import ObjectiveFn, ObjectiveName, make_objective
from qcpp.training.training import check_at_least, cost_scale

__all__ = [
    "CEILING_STARTS",
    "MIXER_MAXITER",
    "MIXER_STARTS",
    "MULTI_RANDOM_STARTS",
    "MixerCeiling",
    "MixerWarmStart",
    "MultiAngleResult",
    "best_p_optimum",
    "bindings",
    "gammas_zero_angles",
    "mixer_only_ceiling",
    "mixer_sites",
    "most_probable_multi",
    "multi_robot_states",
    "multi_robot_states_gradient",
    "optimal_indices",
    "p_optimum_and_gradients",
    "p_optimum_multi",
    "product_objective",
    "robot_states",
    "robot_states_gradient",
    "train_mixer_only",
    "train_multi_angle",
    "train_multi_angle_layers",
]

MIXER_MAXITER = 100
"""L-BFGS-B iterations per mixer-only run."""
MIXER_STARTS = (0.5, 1.5, 2.5)
"""Constant betas the mixer-only training starts from at ``p = 1`` (deterministic)."""
CEILING_STARTS = 60
"""Seeded random starts of :func:`mixer_only_ceiling` per depth."""
MULTI_RANDOM_STARTS = 8
"""Seeded random starts of :func:`train_multi_angle` per depth."""

_ROWS = 1 << 10  # rows of the first robot's axis per chunk of the product pass


def gammas_zero_angles(betas: Sequence[float]) -> tuple[float, ...]:
    """The QAOA angles ``[0, beta_0, 0, beta_1, ...]`` of one beta per layer with every gamma 0.

    Args:
        betas: One beta per layer.

    Returns:
        The interleaved angles, ``2 len(betas)`` values.

    Example:
        >>> gammas_zero_angles([0.5, 1.5])
        (0.0, 0.5, 0.0, 1.5)
    """
    return tuple(v for b in betas for v in (0.0, float(b)))


@dataclass(frozen=True)
class MixerWarmStart:
    """The outcome of :func:`train_mixer_only` at one depth.

    Attributes:
        betas: The trained betas (the gammas are all 0).
        initial_value: The objective at the start of the kept run.
        value: The objective of the product state at ``betas``.
        expectation: ``<C>`` of that state.
        evaluations: Objective evaluations (each with its gradient) over every run up to this depth.
        seconds: Wall time over every run up to this depth.
    """

    p: int
    betas: tuple[float, ...]
    initial_value: float
    value: float
    expectation: float
    evaluations: int
    seconds: float

    @property
    def angles(self) -> tuple[float, ...]:
        """``[0, beta_0, 0, beta_1, ...]``: the QAOA angles of this product state."""
        return gammas_zero_angles(self.betas)


def _site_betas(qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray) -> np.ndarray:
    """``betas`` as a ``(p, sites)`` array: a 2-D array as it is, one beta per layer tied over every site."""
    x = np.asarray(betas, dtype=float)
    return x if x.ndim == 2 else np.repeat(x[:, None], sum(len(b.pairs) for b in qaoa.robot_bases), axis=1)


def _rotate(v: np.ndarray, i: np.ndarray, j: np.ndarray, beta: float, sign: float) -> None:
    c, s = np.cos(beta / 2), sign * 1j * np.sin(beta / 2)
    vi, vj = v[i], v[j]
    v[i], v[j] = c * vi + s * vj, s * vi + c * vj


def robot_states(qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray) -> list[np.ndarray]:
    """Per robot, its state after the mixer layers with every gamma 0: ``prod_k U_r(beta_k) psi_r(0)``.

    Args:
        qaoa: The simulator (its bases, initial amplitudes and rotation pairs are used).
        betas: One beta per layer, or a ``(p, sites)`` array with one beta per partial mixer of
            :func:`mixer_sites` and layer (multi-angle; one per layer is that with tied betas).

    Returns:
        One complex vector per robot (length the robot's basis size); their outer product is
        ``qaoa.state([0, beta_0, 0, beta_1, ...])``.
    """
    x, out, at = _site_betas(qaoa, betas), [], 0
    for b in qaoa.robot_bases:
        v = b.initial.astype(np.complex128)
        for row in x:
            for m, (_, i, j) in enumerate(b.pairs):
                _rotate(v, i, j, float(row[at + m]), -1.0)
        out.append(v)
        at += len(b.pairs)
    return out


def robot_states_gradient(
    qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray, weights: Sequence[np.ndarray]
) -> np.ndarray:
    """``d/dbetas sum_r <psi_r| diag(weights[r]) |psi_r>`` for :func:`robot_states` (adjoint sweep per robot).

    Args:
        betas: As in :func:`robot_states`.
        weights: Per robot, a real weight per basis path (``dF/d|psi_r|^2`` of an objective ``F``).

    Returns:
        One derivative per beta, shaped as ``betas``; a tied beta's is the sum over its sites.
    """
    x = _site_betas(qaoa, betas)
    grad, at = np.zeros(x.shape), 0
    for r, (b, psi) in enumerate(zip(qaoa.robot_bases, robot_states(qaoa, x))):
        lam = np.asarray(weights[r], dtype=float) * psi
        for k in range(len(x) - 1, -1, -1):
            for m in range(len(b.pairs) - 1, -1, -1):
                _, i, j = b.pairs[m]
                # the generator of exp(-i beta X / 2) on the pair is X / 2: dE/dbeta = Im <lam|X|psi>
                grad[k, at + m] = float(np.sum(np.conj(lam[i]) * psi[j] + np.conj(lam[j]) * psi[i]).imag)
                _rotate(psi, i, j, float(x[k, at + m]), 1.0)
                _rotate(lam, i, j, float(x[k, at + m]), 1.0)
        at += len(b.pairs)
    if np.ndim(betas) == 2:
        return grad
    tied, at = np.zeros(len(x)), 0
    for b in qaoa.robot_bases:  # the order of the sweeps above, which fixes the rounding
        for m in range(at + len(b.pairs) - 1, at - 1, -1):
            tied += grad[:, m]
        at += len(b.pairs)
    return tied


def product_objective(
    qaoa: SubspaceQAOA, probs: Sequence[np.ndarray], objective: ObjectiveFn
) -> tuple[float, float, list[np.ndarray]]:
    """An objective of the measured cost for the product distribution ``prod_r probs[r]``, and its derivatives.

    Args:
        qaoa: The simulator (its cost levels: :meth:`~qcpp.simulate.subspace.SubspaceQAOA.cost_distribution_index`).
        probs: Per robot, a probability per basis path.
        objective: ``objective(values, level_probabilities) -> (F, dF/dlevel_probabilities)``.

    Returns:
        ``(F, <C>, grads)`` with ``grads[r] = dF/dprobs[r]`` (same length as ``probs[r]``).

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> from qcpp.training.objectives import Expectation
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3},
        ...                         "robots": [{"start": [0, 0], "goal": [1, 2]}, {"start": [1, 0], "goal": [0, 2]}]})
        >>> q = SubspaceQAOA(s)
        >>> pr = [np.full(n, 1.0 / n) for n in q.dims]
        >>> f, mean, g = product_objective(q, pr, Expectation())
        >>> bool(np.isclose(f, q.cost_diagonal().mean())), bool(np.isclose(f, mean))
        (True, True)
    """
    values, index = qaoa.cost_distribution_index()
    if len(probs) == 2 and subspace_kernels.AVAILABLE and index.dtype in (np.uint8, np.uint16):
        p0, p1 = (np.asarray(p, dtype=float) for p in probs)
        weight = subspace_kernels.pair_level_weights(index, p0, p1, values.size)
        value, dw = objective(values, weight)
        g0, g1 = subspace_kernels.pair_weight_gradients(index, np.asarray(dw, dtype=float), p0, p1)
        return float(value), float(np.dot(weight, values)), [g0, g1]
    n0 = index.shape[0]
    rest = np.ones(())
    for p in probs[1:]:
        rest = np.multiply.outer(rest, np.asarray(p, dtype=float))
    rest = rest.reshape(-1)
    levels = index.reshape(n0, -1)
    p0 = np.asarray(probs[0], dtype=float)
    weight = np.zeros(values.size)
    for a in range(0, n0, _ROWS):
        blk = levels[a : a + _ROWS]
        w = np.multiply.outer(p0[a : a + _ROWS], rest)
        weight += np.bincount(blk.reshape(-1), weights=w.reshape(-1), minlength=values.size)
    value, dw = objective(values, weight)
    dw = np.asarray(dw, dtype=float)
    g0 = np.empty(n0)
    grest = np.zeros(rest.size)
    for a in range(0, n0, _ROWS):
        table = dw[levels[a : a + _ROWS]]
        g0[a : a + _ROWS] = table @ rest
        grest += p0[a : a + _ROWS] @ table
    grads = [g0]
    dims = [len(p) for p in probs[1:]]
    if dims:
        gr = grest.reshape(dims)
        for r in range(len(dims)):
            other = gr
            for s in range(len(dims) - 1, -1, -1):  # contract the other robots' axes with their probabilities
                if s != r:
                    other = np.tensordot(other, np.asarray(probs[s + 1], dtype=float), axes=([s], [0]))
            grads.append(np.asarray(other, dtype=float).reshape(-1))
    return float(value), float(np.dot(weight, values)), grads


_Measure = Callable[[list[np.ndarray]], tuple[float, float, list[np.ndarray]]]
"""``measure(probs) -> (F, <C> or another number to report, dF/dprobs)`` of the robots' path probabilities."""
_Descent = Callable[[np.ndarray], tuple[float, float, np.ndarray]]
"""``fg(x) -> (F, <C>, dF/dx)`` over a flat angle vector, for :func:`_descend`."""


def _product_descent(qaoa: SubspaceQAOA, measure: _Measure, shape: tuple[int, ...]) -> _Descent:
    """``measure`` of the product state at betas ``x.reshape(shape)`` (:func:`robot_states`) and its gradient;
    ``shape`` is ``(p,)`` for one beta per layer, ``(p, sites)`` for multi-angle."""

    def fg(x: np.ndarray) -> tuple[float, float, np.ndarray]:
        betas = np.asarray(x, dtype=float).reshape(shape)
        value, mean, grads = measure([v.real * v.real + v.imag * v.imag for v in robot_states(qaoa, betas)])
        return value, mean, robot_states_gradient(qaoa, betas, grads).reshape(-1)

    return fg


def _descend(
    fg: _Descent, starts: Sequence[np.ndarray], maxiter: int | None = None
) -> tuple[list[tuple[float, float, np.ndarray]], int]:
    """L-BFGS-B on ``fg`` from each of ``starts``: where each run ends, ``(F, <C>, x)``, and the evaluations."""
    seen: dict[bytes, tuple[float, float]] = {}
    calls = 0

    def f_and_g(x: np.ndarray) -> tuple[float, np.ndarray]:
        nonlocal calls
        calls += 1
        f, mean, g = fg(x)
        seen[np.asarray(x, dtype=float).tobytes()] = (f, mean)
        return f, g

    ends = []
    for x0 in starts:
        opts = {} if maxiter is None else {"maxiter": maxiter}
        x = np.asarray(minimize(f_and_g, x0, jac=True, method="L-BFGS-B", options=opts).x, dtype=float)
        if x.tobytes() not in seen:
            f_and_g(x)
        ends.append((*seen[x.tobytes()], x))
    return ends, calls


def train_mixer_only(
    qaoa: SubspaceQAOA,
    p: int,
    objective: ObjectiveName | ObjectiveFn = "gibbs",
    maxiter: int = MIXER_MAXITER,
) -> list[MixerWarmStart]:
    """Train the betas of ``p = 1 .. p`` mixer-only layers (gammas 0), layer by layer, with L-BFGS-B.

    ``p = 1`` starts from each of :data:`MIXER_STARTS`; every later depth from the best betas of the depth
    before with one more layer, as a copy of the last beta and as 0 (the same state, so never worse), and keeps
    the better run. Deterministic.

    Args:
        p: The largest depth (>= 1).
        objective: ``gibbs`` (default), ``cvar``, ``expectation`` (with :func:`qcpp.training.objectives.make_objective`
            defaults for this scenario) or an objective object.
        maxiter: L-BFGS-B iterations per run.

    Returns:
        One :class:`MixerWarmStart` per depth ``1 .. p``.

    Raises:
        ValueError: ``p < 1`` or a negative ``maxiter``.
    """
    check_at_least(p=(p, 1), maxiter=(maxiter, 0))
    obj = make_objective(objective, cost_scale(qaoa)) if isinstance(objective, str) else objective
    t0 = time.perf_counter()
    evaluations = 0
    out: list[MixerWarmStart] = []
    for level in range(1, p + 1):
        if level == 1:
            starts = [np.array([b]) for b in MIXER_STARTS]
        else:
            prev = np.array(out[-1].betas)
            starts = [np.append(prev, prev[-1]), np.append(prev, 0.0)]
        fg = _product_descent(qaoa, partial(product_objective, qaoa, objective=obj), (level,))
        firsts = [fg(x0)[0] for x0 in starts]
        ends, calls = _descend(fg, starts, maxiter)
        evaluations += len(starts) + calls
        value, mean, x = min(ends, key=itemgetter(0))
        first = firsts[[e[0] for e in ends].index(value)]
        out.append(MixerWarmStart(level, tuple(float(b) for b in x), first, value, mean, evaluations,
                                  time.perf_counter() - t0))
    return out


@dataclass(frozen=True)
class MixerCeiling:
    """The best ``P(optimum)`` found over mixer-only angles at one depth (:func:`mixer_only_ceiling`).

    Attributes:
        betas: The betas that reach it (gammas 0).
        p_optimum: ``P(optimum)`` of the product state at ``betas``.
        starts: Random starts tried.
        seconds: Wall time for this depth.
    """

    p: int
    betas: tuple[float, ...]
    p_optimum: float
    starts: int
    seconds: float

    @property
    def angles(self) -> tuple[float, ...]:
        """``[0, beta_0, 0, beta_1, ...]``."""
        return gammas_zero_angles(self.betas)


def p_optimum_and_gradients(
    probs: Sequence[np.ndarray], optima: Sequence[Sequence[int]]
) -> tuple[float, list[np.ndarray]]:
    """``sum_o prod_r probs[r][o_r]`` over the optimal assignments ``o`` (array indices) and its derivatives.

    Args:
        probs: Per robot, a probability per basis path.
        optima: The optimal assignments as per-robot indices.

    Returns:
        ``(P(optimum), grads)`` with ``grads[r] = dP/dprobs[r]``.
    """
    total = 0.0
    grads = [np.zeros(len(p)) for p in probs]
    for o in optima:
        parts = [float(p[i]) for p, i in zip(probs, o)]
        total += float(np.prod(parts))
        for r, i in enumerate(o):
            grads[r][i] += float(np.prod(parts[:r] + parts[r + 1 :]))
    return total, grads


def optimal_indices(qaoa: SubspaceQAOA) -> list[tuple[int, ...]]:
    """The optimal assignments (:meth:`~qcpp.simulate.subspace.SubspaceQAOA.optimum`) as per-robot basis indices."""
    return [tuple(int(i) for i in np.unravel_index(k, qaoa.dims)) for k in qaoa.optimum()[1]]


def best_p_optimum(
    qaoa: SubspaceQAOA, shape: tuple[int, ...], x0s: Sequence[np.ndarray], maxiter: int | None = None
) -> tuple[np.ndarray, float]:
    """The largest ``P(optimum)`` of the product state that L-BFGS-B finds on its exact gradient (uses the optimum).

    Args:
        shape: Of the betas: ``(p,)`` for one beta per layer, ``(p, sites)`` for multi-angle (:func:`robot_states`).
        x0s: Flat start vectors.
        maxiter: L-BFGS-B iterations per start (``None``: scipy's default).

    Returns:
        ``(betas, P(optimum))`` (flat betas), the first start if no run improves on it.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
        >>> q = SubspaceQAOA(s)
        >>> x, best = best_p_optimum(q, (1, len(mixer_sites(q))), [np.full(len(mixer_sites(q)), 0.3)])
        >>> best > p_optimum_multi(q, np.full(len(mixer_sites(q)), 0.3), 1)
        True
    """
    optima = optimal_indices(qaoa)

    def minus_p_optimum(probs: list[np.ndarray]) -> tuple[float, float, list[np.ndarray]]:
        value, grads = p_optimum_and_gradients(probs, optima)
        return -value, value, [-g for g in grads]

    fg = _product_descent(qaoa, minus_p_optimum, shape)
    first = -fg(x0s[0])[0]
    value, _, x = min(_descend(fg, x0s, maxiter)[0], key=itemgetter(0))
    return (x, -value) if -value > first else (np.asarray(x0s[0], dtype=float), first)


def mixer_only_ceiling(
    qaoa: SubspaceQAOA, p: int, starts: int = CEILING_STARTS, seed: int = 0
) -> list[MixerCeiling]:
    """The largest ``P(optimum)`` found over mixer-only angles (gammas 0) at depths ``1 .. p``: a diagnostic.

    Unlike :func:`train_mixer_only` this *uses the optimum* (:meth:`~qcpp.simulate.subspace.SubspaceQAOA.optimum`):
    it maximises the probability of the optimal assignments directly, by L-BFGS-B on the exact gradient, at
    each depth from ``starts`` seeded uniform random betas in ``[0, 2 pi)`` and from the best betas of the depth
    before with a zero layer appended (so the result never decreases with depth). It is not a solver; it says
    what a warm start with gammas 0 can give at best (the best found, a lower bound on the true maximum), so
    that the phase separators' share of a trained ``P(optimum)`` can be read off.

    Args:
        p: The largest depth (>= 1).
        starts: Random starts per depth (>= 1).
        seed: Seed of ``numpy.random.default_rng``.

    Returns:
        One :class:`MixerCeiling` per depth ``1 .. p``.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
        >>> c = mixer_only_ceiling(SubspaceQAOA(s), 2, starts=5)
        >>> c[0].p_optimum <= c[1].p_optimum <= 1.0, len(c[1].angles)
        (True, 4)
    """
    check_at_least(p=(p, 1), starts=(starts, 1))
    rng = np.random.default_rng(seed)
    out: list[MixerCeiling] = []
    for level in range(1, p + 1):
        t0 = time.perf_counter()
        x0s = [rng.uniform(0.0, 2 * np.pi, level) for _ in range(starts)]
        if out:
            x0s.insert(0, np.append(out[-1].betas, 0.0))
        best_x, best = best_p_optimum(qaoa, (level,), x0s)
        out.append(MixerCeiling(level, tuple(float(b) for b in best_x), best, starts, time.perf_counter() - t0))
    return out


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
    (:func:`robot_states` of the betas as a ``(p, sites)`` array).

    Args:
        betas: ``p * len(mixer_sites(qaoa))`` betas, layer-major (see the module docstring).

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
    (:func:`robot_states_gradient`)."""
    return robot_states_gradient(qaoa, _check(qaoa, betas, p).reshape(p, -1), weights).reshape(-1)


def bindings(qaoa: SubspaceQAOA, betas: Sequence[float] | np.ndarray, p: int) -> dict[str, float]:
    """The symbol values of the compiled multi-angle circuit (``PlanOptions(angles="multi")``) for ``betas``.

    Every gamma is 0, the sites' betas are ``betas``, and the compiled circuit's other partial mixers (the
    identity on the reachable states) get 0. The keys are exactly the circuit's
    :attr:`~qcpp.plan.qaoa.QaoaPlan.parameter_names`.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
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
        p: Number of layers (>= 1).
        objective: ``gibbs`` (default), ``cvar``, ``expectation`` (with
            :func:`qcpp.training.objectives.make_objective`'s defaults for this scenario) or an objective object.
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
    check_at_least(p=(p, 1), random_starts=(random_starts, 0), maxiter=(maxiter, 0))
    obj = make_objective(objective, cost_scale(qaoa)) if isinstance(objective, str) else objective
    n = len(mixer_sites(qaoa))
    t0 = time.perf_counter()
    starts = [np.full(p * n, b) for b in MIXER_STARTS]
    if previous is not None:
        starts.append(np.append(_check(qaoa, previous, p - 1), np.zeros(n)))
    rng = np.random.default_rng(seed)
    starts += [rng.uniform(0.0, 2 * np.pi, p * n) for _ in range(random_starts)]
    fg = _product_descent(qaoa, partial(product_objective, qaoa, objective=obj), (p, n))
    ends, evaluations = _descend(fg, starts, maxiter)
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
    check_at_least(p=(p, 1))
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
