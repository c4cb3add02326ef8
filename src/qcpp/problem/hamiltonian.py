"""The exact diagonal Ising (Pauli-Z) form of the cost.

Substituting ``x_i = (1 - Z_i) / 2`` into the quadratic cost (:func:`qcpp.problem.cost.quadratic_cost`)
gives ``C = c0 + sum_i h_i Z_i + sum_{i<j} J_ij Z_i Z_j`` with, for
``cost = k + sum_i l_i x_i + sum_{i<j} q_ij x_i x_j``::

    c0   = k + sum_i l_i / 2 + sum_{i<j} q_ij / 4
    h_i  = -l_i / 2 - sum_{j != i} q_ij / 4
    J_ij = q_ij / 4

The paper writes ``x = 1 - Z`` (dropping the 1/2), which doubles linear terms and quadruples quadratic
ones; see ``docs/paper-notes.md``. Variables are indexed as in :mod:`qcpp.problem.scenario`.

Example:
    >>> import numpy as np
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
    >>> H = ising_hamiltonian(s)
    >>> H.num_qubits, H.evaluate(np.array([1, 0, 1, 0]))   # the path (0,0)-(0,1)-(1,1)
    (4, 2.0)
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from qcpp.problem.cost import QuadraticCost, quadratic_cost
from qcpp.problem.scenario import Scenario


@dataclass(frozen=True, eq=False)
class IsingHamiltonian:
    """``C = c0 + sum_i h_i Z_i + sum_{i<j} J_ij Z_i Z_j``.

    Attributes:
        c0: Constant (identity) coefficient.
        h: ``(n,)`` linear coefficients.
        J: ``(n, n)`` strictly upper-triangular quadratic coefficients.
    """

    c0: float
    h: np.ndarray
    J: np.ndarray

    @property
    def num_qubits(self) -> int:
        return len(self.h)

    def linear_terms(self, tol: float = 0.0) -> Iterator[tuple[int, float]]:
        """``(i, h_i)`` for every ``|h_i| > tol``, ascending ``i``."""
        for i in np.flatnonzero(np.abs(self.h) > tol):
            yield int(i), float(self.h[i])

    def quadratic_terms(self, tol: float = 0.0) -> Iterator[tuple[int, int, float]]:
        """``(i, j, J_ij)`` for every ``|J_ij| > tol``, row-major (``i < j``)."""
        ii, jj = np.nonzero(np.abs(self.J) > tol)
        vals = self.J[ii, jj]
        yield from zip(ii.tolist(), jj.tolist(), vals.tolist(), strict=True)

    def num_quadratic_terms(self, tol: float = 0.0) -> int:
        return int(np.count_nonzero(np.abs(self.J) > tol))

    def evaluate(self, bits: np.ndarray) -> np.ndarray | float:
        """Energy of computational basis states given as 0/1 bits (``Z = 1 - 2x``): one row or ``(N, n)``."""
        z = 1.0 - 2.0 * np.asarray(bits, dtype=float)
        val = self.c0 + z @ self.h + np.einsum("...i,ij,...j->...", z, self.J, z)
        return float(val) if np.ndim(val) == 0 else val


def ising_from_quadratic(q: QuadraticCost) -> IsingHamiltonian:
    """Convert ``k + l.x + sum_{i<j} q_ij x_i x_j`` to Pauli-Z form (see the module docstring)."""
    sym = q.quad + q.quad.T
    c0 = q.const + q.linear.sum() / 2 + q.quad.sum() / 4
    h = -q.linear / 2 - sym.sum(axis=1) / 4
    return IsingHamiltonian(float(c0), h, q.quad / 4)


def ising_hamiltonian(scenario: Scenario) -> IsingHamiltonian:
    """The exact Ising Hamiltonian of the scenario's cost, built with numpy."""
    return ising_from_quadratic(quadratic_cost(scenario))
