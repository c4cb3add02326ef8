"""The first phase separator acts on the initial state: on a basis state it is a global phase.

With a basis-state initial state (``initial_path``, the paper's single initial path per robot, and
``local_search``), ``exp(-i gamma_0 C)`` multiplies the state by ``exp(-i gamma_0 C(x0))``: no measurement can see
``gamma_0``, at any depth, and the first phase separator's gates change nothing observable. A superposition of
paths of different costs (``local_search_mix``) does see it: the negative control that shows the check can fail.
docs/paper-notes.md ("The first phase separator") says what this means for the paper's circuit and for the counts.
"""

from __future__ import annotations

import numpy as np
import pytest
from qiskit.quantum_info import Statevector

import qcpp

FIELD = qcpp.grid_scenario(3, 3, robots=[((0, 0), (2, 2))])
"""One robot across a 3x3 grid: its initial and descent paths differ in cost (12 edges, small enough to simulate)."""


def _overlap(initial: str, p: int) -> float:
    """``|<psi(gamma_0 = 0.3)|psi(gamma_0 = 1.7)>|`` of the compiled circuit, the other angles fixed."""

    def state(gamma_0: float) -> np.ndarray:
        bind = {"gamma_0": gamma_0, "beta_0": 0.8, **({"gamma_1": 0.5, "beta_1": 0.4} if p == 2 else {})}
        return Statevector(qcpp.compile(FIELD, p, bind=bind, initial=initial).to_qiskit()).data

    return float(abs(np.vdot(state(0.3), state(1.7))))


@pytest.mark.parametrize(("initial", "p"), [("initial_path", 2), ("local_search", 1)])
def test_gamma_0_is_a_global_phase_on_a_basis_state(initial: str, p: int) -> None:
    assert _overlap(initial, p) == pytest.approx(1.0, abs=1e-9)


def test_a_superposition_of_paths_sees_gamma_0() -> None:
    assert _overlap("local_search_mix", 1) < 0.5
