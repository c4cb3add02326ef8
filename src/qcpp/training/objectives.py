"""Training objectives: functions of the measured cost's distribution, with their derivatives.

A QAOA state measured in the computational basis returns an assignment whose cost ``C`` has a distribution
``w_v = P(C = v)`` over the cost table ``v`` (:meth:`qcpp.simulate.subspace.SubspaceQAOA.cost_distribution_index`).
Each objective here is a function ``F(v, w)`` to *minimise*, returned together with ``dF/dw``, so that
:meth:`~qcpp.simulate.subspace.SubspaceQAOA.objective_and_gradient` gives its exact gradient in the angles by one
adjoint sweep. All are in units of the cost:

``expectation``
    ``<C> = sum_v w_v v``. Rewards every improvement equally; on rugged landscapes it settles for a state
    spread over many mediocre assignments.
``cvar``
    ``CVaR_alpha``: the mean cost of the cheapest ``alpha`` of the probability mass (Barkoutsos et al.,
    Quantum 4, 256, 2020), the boundary level taken fractionally. It stops rewarding once ``alpha`` of the
    mass sits on the optimum, so it caps ``P(optimum)`` near ``alpha``.
``gibbs``
    ``-(1/eta) log <exp(-eta C)>`` (Li et al., PRR 2, 023074, 2020, up to the factor ``1/eta`` that keeps the
    units of cost): the free energy at inverse temperature ``eta``. It tends to ``<C>`` as ``eta -> 0`` and to
    the cheapest cost with any weight as ``eta -> inf``; in between it keeps rewarding weight on the cheapest
    costs however much is there. Default ``eta``: ``GIBBS_SCALE / sigma`` with ``sigma`` the standard
    deviation of the cost over all basis assignments (:func:`qcpp.training.training.cost_scale`), so the default
    needs no tuning to a scenario's cost units.

Example:
    >>> import numpy as np
    >>> v, w = np.array([0.0, 1.0, 5.0]), np.array([0.1, 0.5, 0.4])
    >>> [round(make_objective(n, sigma=1.0)(v, w)[0], 4) for n in OBJECTIVES]
    [2.5, 0.5, 0.0576]
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np

__all__ = ["CVAR_ALPHA", "GIBBS_SCALE", "OBJECTIVES", "CVaR", "Expectation", "Gibbs", "ObjectiveName", "make_objective"]

ObjectiveName = Literal["expectation", "cvar", "gibbs"]
OBJECTIVES: tuple[ObjectiveName, ...] = ("expectation", "cvar", "gibbs")
CVAR_ALPHA = 0.2
"""Default CVaR tail mass."""
GIBBS_SCALE = 40.0
"""Default Gibbs inverse temperature in units of ``1 / sigma`` (see the module docstring). Cold enough that a
state spread over the optimum and its neighbours scores better than one sure near-optimal assignment
(docs/ensembles.md measures it against ``5``)."""

ObjectiveFn = Callable[[np.ndarray, np.ndarray], tuple[float, np.ndarray]]


@dataclass(frozen=True)
class Expectation:
    """``<C>``; ``dF/dw_v = v``.

    Example:
        >>> import numpy as np
        >>> Expectation()(np.array([1.0, 3.0]), np.array([0.5, 0.5]))[0]
        2.0
    """

    name: str = "expectation"

    def __call__(self, values: np.ndarray, probs: np.ndarray) -> tuple[float, np.ndarray]:
        return float(np.dot(values, probs)), np.asarray(values, dtype=float)


@dataclass(frozen=True)
class CVaR:
    """``CVaR_alpha``: the mean of the cheapest ``alpha`` of the mass.

    With ``b`` the boundary level (the first whose cumulative mass reaches ``alpha``),
    ``F = (sum_{v<b} w_v v + (alpha - sum_{v<b} w_v) b) / alpha``, so ``dF/dw_v = (v - b) / alpha`` below the
    boundary and 0 from it on (a one-sided derivative where the boundary moves).

    Example:
        >>> import numpy as np
        >>> f, g = CVaR(0.5)(np.array([0.0, 2.0, 4.0]), np.array([0.25, 0.5, 0.25]))
        >>> f, g.tolist()
        (1.0, [-4.0, 0.0, 0.0])
    """

    alpha: float = CVAR_ALPHA
    name: str = "cvar"

    def __post_init__(self) -> None:
        if not 0 < self.alpha <= 1:
            raise ValueError(f"CVaR alpha must be in (0, 1], got {self.alpha}")

    def __call__(self, values: np.ndarray, probs: np.ndarray) -> tuple[float, np.ndarray]:
        w = np.asarray(probs, dtype=float)
        before = np.cumsum(w) - w
        b = int(min(np.searchsorted(np.cumsum(w), self.alpha * (1 - 1e-12)), w.size - 1))
        take = np.clip(self.alpha - before, 0.0, w)
        value = float(np.dot(take, values) / self.alpha)
        grad = np.zeros(w.size)
        grad[:b] = (values[:b] - values[b]) / self.alpha
        return value, grad


@dataclass(frozen=True)
class Gibbs:
    """``-(1/eta) log sum_v w_v exp(-eta v)``, evaluated shifted by the cheapest cost for stability.

    Example:
        >>> import numpy as np
        >>> f, g = Gibbs(1.0)(np.array([0.0, 10.0]), np.array([0.5, 0.5]))
        >>> round(f, 4), round(float(g[0]), 4)
        (0.6931, -1.9999)
    """

    eta: float
    name: str = "gibbs"

    def __post_init__(self) -> None:
        if not (self.eta > 0 and np.isfinite(self.eta)):
            raise ValueError(f"Gibbs eta must be positive and finite, got {self.eta}")

    def __call__(self, values: np.ndarray, probs: np.ndarray) -> tuple[float, np.ndarray]:
        w = np.asarray(probs, dtype=float)
        v0 = float(values.min())
        boltz = np.exp(-self.eta * (values - v0))
        z = float(np.dot(w, boltz))
        return v0 - float(np.log(z)) / self.eta, -boltz / (self.eta * z)


def make_objective(
    name: ObjectiveName, sigma: float = 1.0, alpha: float = CVAR_ALPHA, eta: float | None = None,
    gibbs_scale: float = GIBBS_SCALE,
) -> Expectation | CVaR | Gibbs:
    """The objective called ``name`` with its defaults.

    Args:
        name: ``expectation``, ``cvar`` or ``gibbs``.
        sigma: The cost scale (standard deviation over the basis) that sets the default Gibbs ``eta``.
        alpha: CVaR tail mass.
        eta: Gibbs inverse temperature; default ``gibbs_scale / sigma``.
        gibbs_scale: Gibbs inverse temperature in units of ``1 / sigma`` when ``eta`` is not given.

    Raises:
        ValueError: for an unknown name or out-of-range parameter.

    Example:
        >>> make_objective("gibbs", sigma=10.0)
        Gibbs(eta=4.0, name='gibbs')
    """
    if name == "expectation":
        return Expectation()
    if name == "cvar":
        return CVaR(alpha)
    if name == "gibbs":
        return Gibbs(gibbs_scale / sigma if eta is None else eta)
    raise ValueError(f"unknown objective {name!r} (expected one of {', '.join(OBJECTIVES)})")
