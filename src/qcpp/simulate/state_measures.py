"""Functions of an exact QAOA state: the measured cost's distribution, CVaR, the optimum's probability, reach.

:func:`cost_distribution` is the distribution of the cost a measurement returns; :func:`cvar` the conditional
value at risk (mean cost of the cheapest ``alpha`` of the mass; Barkoutsos et al., Quantum 4, 256, 2020);
:func:`state_metrics` ``<C>``, ``CVaR`` and ``P(optimum)`` from one simulation; :func:`uniform_hit_probability`
the trivial baseline (one uniform draw from the feasible basis); :func:`layers_to_reach` the depth below which
an assignment's amplitude is exactly zero whatever the angles.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> q = SubspaceQAOA(s)
    >>> m = state_metrics(q, [0.0, 1.2], alpha=0.25)
    >>> m.cvar <= m.expectation, 0.0 < m.p_optimum < 1.0
    (True, True)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from qcpp.simulate.subspace import SubspaceQAOA

__all__ = ["StateMetrics", "cost_distribution", "cvar", "layers_to_reach", "state_metrics", "uniform_hit_probability"]


def _flat_state(qaoa: SubspaceQAOA, state: np.ndarray | Sequence[float]) -> np.ndarray:
    """The state array (``state`` itself if it has the simulator's shape, else the state at angles ``state``)."""
    arr = np.asarray(state)
    if np.iscomplexobj(arr) and arr.shape == qaoa.dims:
        return arr.reshape(-1)
    return qaoa.state(arr).reshape(-1)


def cost_distribution(qaoa: SubspaceQAOA, state: np.ndarray | Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """The distribution of the measured cost: sorted distinct cost values and their probabilities.

    Args:
        state: A state array of shape ``qaoa.dims`` (complex), or angles to simulate.

    Returns:
        ``(values, probabilities)``, ``values`` ascending and distinct (up to ``1e-12``), probabilities
        summing to the state's norm squared.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
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
        state: A state array of shape ``qaoa.dims`` (complex), or angles to simulate.
        alpha: Tail mass in ``(0, 1]``.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
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
        >>> from qcpp.problem.scenario import scenario_from_dict
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
        assignment: One edge mask per robot.
        max_layers: Give up after this many layers.

    Returns:
        The number of layers (0 if the assignment is in the initial support), or ``None`` if it is not
        reachable within ``max_layers`` (e.g. outside the basis).

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
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
