"""The phase separator ``exp(-i gamma (C - c0))`` from the exact Ising Hamiltonian.

``C = c0 + sum_i h_i Z_i + sum_{i<j} J_ij Z_i Z_j`` is diagonal, so its exponential is a product of
``RZ(2 gamma h_i)`` on each qubit (``RZ(t) = exp(-i t Z / 2)``) and ``RZZ(2 gamma J_ij)`` on each coupled pair;
the constant ``c0`` is a global phase and emits nothing. Zero coefficients emit nothing either.

Order: the RZ gates by qubit, then the RZZ gates row-major by ``(i, j)``; all of them commute.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> from gridcover.hamiltonian import ising_hamiltonian
    >>> from circuitgen.angles import Angle
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
    >>> gates = phase_separator_gates(ising_hamiltonian(s), "gamma_0")
    >>> sorted({g.name for g in gates}), str(gates[0].params[0])
    (['rz', 'rzz'], '1.0*gamma_0')
"""

from __future__ import annotations

from gridcover.hamiltonian import IsingHamiltonian

from .angles import Angle
from .gates import Gate, rz, rzz

#: Coefficients smaller than this (absolute) are treated as zero: they only arise from float round-off.
COEFFICIENT_TOLERANCE = 1e-12


def phase_separator_gates(hamiltonian: IsingHamiltonian, gamma: str, data_offset: int = 0) -> list[Gate]:
    """RZ and RZZ gates implementing ``exp(-i gamma (C - c0))``.

    Args:
        hamiltonian: The Ising Hamiltonian (variable ``i`` on qubit ``data_offset + i``).
        gamma: Name of the layer's symbol, e.g. ``"gamma_0"``.
        data_offset: Qubit index of variable 0.

    Returns:
        The gate list (linear terms first).
    """
    tol = COEFFICIENT_TOLERANCE
    out = [rz(Angle.symbol(gamma, 2.0 * hi), data_offset + i) for i, hi in hamiltonian.linear_terms(tol)]
    out += [
        rzz(Angle.symbol(gamma, 2.0 * jij), data_offset + i, data_offset + j)
        for i, j, jij in hamiltonian.quadratic_terms(tol)
    ]
    return out
