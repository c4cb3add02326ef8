"""The default QAOA training: layer by layer with warm starts, several starts, exact gradients.

:func:`train_layerwise` trains ``p = 1, 2, ..., P`` in turn with L-BFGS-B on the exact adjoint gradient
(:meth:`qcpp.simulate.subspace.SubspaceQAOA.objective_and_gradient`) of a chosen objective
(:mod:`qcpp.training.objectives`; default ``gibbs``). Starts:

* ``p = 1``: the linear ramp (:func:`qcpp.training.training.initial_angles`) and ``random_starts`` seeded random
  angles;
* ``p > 1``: from the best angles at ``p - 1``, (a) their INTERP extension (Zhou et al., PRX 10, 021067,
  2020; :func:`qcpp.training.training.interp_angles`) and (b) the same angles with a zero layer appended, which
  reproduces the ``p - 1`` state exactly, so the objective at ``p`` is never worse than at ``p - 1``.

With ``restart_every_level=True`` (the default) every level ``p > 1`` also starts from the linear ramp at depth
``p`` and from ``random_starts`` seeded random angles (seeds ``seed + 1000 p + k``): the best angles at ``p - 1``
are often a basis state (``beta`` at 0 or ``pi`` leaves the initial path in place or swaps it onto another path),
where every objective is stationary in the new layer, so the two warm starts above cannot leave it.

With ``mixer_warm=True`` every level also starts from the mixer-only warm start
(:func:`qcpp.training.mixer_only.train_mixer_only`) with the linear ramp's gammas (not 0, where every objective is
stationary in them).

At every level the best run (lowest objective) is kept and warm-starts the next. Every simulation is counted;
:meth:`LayerwiseResult.circuit_estimates` converts them to a device's objective estimates (a central-difference
gradient costs ``2 * 2p``: the parameter-shift rule does not apply as is because every angle drives many gates),
:meth:`LayerwiseResult.shots` multiplies by the shots per estimate.

Defaults (objective ``gibbs`` with ``eta = 40 / sigma``, the linear ramp and 2 random starts at every level, at
most 200 L-BFGS-B iterations per run) are the same for every scenario: nothing is tuned per instance.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.simulate.subspace import SubspaceQAOA
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1]]},
    ...                         "robots": [{"start": [0, 0], "goal": [0, 2]}]})
    >>> res = train_layerwise(SubspaceQAOA(s), 2)
    >>> [lv.p for lv in res.levels], res.p_optimum > 0.9, res.runs
    ([1, 2], True, 8)
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.mixer_only import train_mixer_only
from qcpp.training.objectives import CVAR_ALPHA, GIBBS_SCALE, ObjectiveName, make_objective
from qcpp.training.training import TrainingResult, check_at_least, cost_scale, initial_angles, interp_angles, train

__all__ = [
    "DEFAULT_MAXITER",
    "DEFAULT_OBJECTIVE",
    "DEFAULT_RANDOM_STARTS",
    "SHOTS_PER_ESTIMATE",
    "LayerwiseResult",
    "extend_angles",
    "train_layerwise",
]

DEFAULT_OBJECTIVE: ObjectiveName = "gibbs"
DEFAULT_RANDOM_STARTS = 2
DEFAULT_MAXITER = 200
SHOTS_PER_ESTIMATE = 1000
"""Assumed shots per objective estimate on a device (standard error about ``sigma / 30`` for ``<C>``)."""


def extend_angles(angles: np.ndarray | tuple[float, ...]) -> np.ndarray:
    """``angles`` with a zero layer ``(gamma, beta) = (0, 0)`` appended: the same state at ``p + 1``.

    Example:
        >>> extend_angles((0.1, 0.2)).tolist()
        [0.1, 0.2, 0.0, 0.0]
    """
    return np.concatenate([np.asarray(angles, dtype=float), [0.0, 0.0]])


@dataclass(frozen=True)
class LayerwiseResult:
    """The outcome of :func:`train_layerwise`.

    Attributes:
        objective: The objective's name.
        levels: The best run at each ``p = 1 .. P`` (a :class:`~qcpp.training.training.TrainingResult`).
        runs: Optimiser runs made over all levels and starts.
        num_evaluations: Simulations over all runs (with or without gradient).
        num_gradients: Of those, the ones that also computed the gradient.
        circuit_estimates: Objective estimates a device would need for the same optimiser path: one per
            value, ``1 + 4p`` per gradient (central differences over the ``2p`` angles, ``p`` the run's depth).
        seconds: Wall-clock time of the whole schedule.
        mixer_evaluations: Product-state objective evaluations (each with its gradient) of the mixer-only warm
            start (``mixer_warm=True``; 0 otherwise); each is counted in :attr:`circuit_estimates` as
            ``1 + 2p`` estimates of the mixer-only circuit (central differences over its ``p`` betas).
        level_estimates: :attr:`circuit_estimates` accumulated up to and including each level (the training a
            run stopped at that depth would have needed; the last entry is :attr:`circuit_estimates`).
    """

    objective: str
    levels: tuple[TrainingResult, ...]
    runs: int
    num_evaluations: int
    num_gradients: int
    circuit_estimates: int
    seconds: float
    mixer_evaluations: int = 0
    level_estimates: tuple[int, ...] = ()

    @property
    def best(self) -> TrainingResult:
        """The run at the largest ``p``."""
        return self.levels[-1]

    @property
    def p(self) -> int:
        return self.best.p

    @property
    def angles(self) -> tuple[float, ...]:
        return self.best.angles

    @property
    def p_optimum(self) -> float:
        return self.best.p_optimum

    @property
    def trace(self) -> tuple[float, ...]:
        """The objective per iteration of the kept run at every level, levels concatenated."""
        return tuple(v for lv in self.levels for v in lv.trace)

    def shots(self, shots_per_estimate: int = SHOTS_PER_ESTIMATE) -> int:
        """Device shots for training: :attr:`circuit_estimates` times ``shots_per_estimate``."""
        return self.circuit_estimates * shots_per_estimate

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready: the counts, the per-level summaries (angles, objective, ``<C>``, ``P(optimum)``)."""
        return {
            "objective": self.objective,
            "p": self.p,
            "runs": self.runs,
            "num_evaluations": self.num_evaluations,
            "num_gradients": self.num_gradients,
            "circuit_estimates": self.circuit_estimates,
            "seconds": self.seconds,
            "mixer_evaluations": self.mixer_evaluations,
            "level_estimates": list(self.level_estimates),
            "levels": [
                {k: v for k, v in asdict(lv).items() if k not in ("stages", "trace", "initial_angles")}
                | {"iterations": len(lv.trace) - 1}
                for lv in self.levels
            ],
        }


def train_layerwise(
    qaoa: SubspaceQAOA,
    p: int,
    objective: ObjectiveName = DEFAULT_OBJECTIVE,
    *,
    random_starts: int = DEFAULT_RANDOM_STARTS,
    seed: int = 0,
    maxiter: int = DEFAULT_MAXITER,
    alpha: float = CVAR_ALPHA,
    eta: float | None = None,
    gibbs_scale: float = GIBBS_SCALE,
    mixer_warm: bool = False,
    restart_every_level: bool = True,
    progress: Callable[[int, int], None] | None = None,
) -> LayerwiseResult:
    """Train ``p = 1 .. p`` layer by layer (see the module docstring).

    Args:
        p: The final number of layers (>= 1).
        objective: ``gibbs`` (default), ``cvar`` or ``expectation``.
        random_starts: Seeded random starts at ``p = 1`` beside the linear ramp (>= 0).
        seed: Seed of the random starts (start ``k`` uses ``seed + k``).
        maxiter: L-BFGS-B iterations per run.
        alpha: CVaR tail mass (``cvar``).
        eta: Gibbs inverse temperature (``gibbs``); default ``gibbs_scale / sigma``.
        gibbs_scale: Gibbs inverse temperature in units of ``1 / sigma`` when ``eta`` is not given (default
            ``GIBBS_SCALE``, 40).
        mixer_warm: Also start every level from the mixer-only warm start (see the module docstring).
        restart_every_level: Also start every level ``p > 1`` from the linear ramp and ``random_starts`` random
            angles (default; see the module docstring).
        progress: Called as ``progress(level, p)`` after each level.

    Raises:
        ValueError: ``p < 1``, ``random_starts < 0``, a negative ``maxiter``, or a bad objective parameter.
    """
    check_at_least(p=(p, 1), random_starts=(random_starts, 0), maxiter=(maxiter, 0))
    t0 = time.perf_counter()
    obj = make_objective(objective, cost_scale(qaoa), alpha=alpha, eta=eta, gibbs_scale=gibbs_scale)
    levels: list[TrainingResult] = []
    level_estimates: list[int] = []
    runs = evaluations = gradients = estimates = mixer_evaluations = 0
    warm = train_mixer_only(qaoa, p, obj) if mixer_warm else []
    for level in range(1, p + 1):
        if level == 1:
            starts = [initial_angles(qaoa, 1, "linear-ramp")]
            starts += [initial_angles(qaoa, 1, "random", seed=seed + k) for k in range(random_starts)]
        else:
            prev = np.array(levels[-1].angles)
            starts = [interp_angles(prev), extend_angles(prev)]
            if restart_every_level:
                starts.append(initial_angles(qaoa, level, "linear-ramp"))
                starts += [initial_angles(qaoa, level, "random", seed=seed + 1000 * level + k)
                           for k in range(random_starts)]
        if warm:
            x0 = initial_angles(qaoa, level, "linear-ramp")
            x0[1::2] = warm[level - 1].betas
            starts.append(x0)
            count = warm[level - 1].evaluations - (warm[level - 2].evaluations if level > 1 else 0)
            mixer_evaluations += count
            estimates += count * (1 + 2 * level)
        best: TrainingResult | None = None
        for x0 in starts:
            run = train(qaoa, level, "lbfgsb", init=x0, maxiter=maxiter, objective=obj)
            runs += 1
            evaluations += run.num_evaluations
            gradients += run.num_gradients
            estimates += run.num_evaluations + 4 * level * run.num_gradients
            if best is None or run.value < best.value:
                best = run
        assert best is not None
        levels.append(best)
        level_estimates.append(estimates)
        if progress is not None:
            progress(level, p)
    return LayerwiseResult(obj.name, tuple(levels), runs, evaluations, gradients, estimates, time.perf_counter() - t0,
                           mixer_evaluations, tuple(level_estimates))
