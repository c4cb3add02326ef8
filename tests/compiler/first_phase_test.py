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


# --- the plan option that omits it: PlanOptions(first_phase=False), --skip-first-phase -----------------------------

SMALL = {
    "3x3/1 initial_path": (FIELD, "initial_path"),
    "3x3/1 local_search": (FIELD, "local_search"),
    "2x3/2 initial_path": (qcpp.grid_scenario(2, 3, robots=2), "initial_path"),
    "2x3/2 representatives": (qcpp.grid_scenario(2, 3, robots=2), "representatives"),  # one component each
}
"""Small scenarios whose start is a basis state (the sparse simulator holds their states exactly)."""

ANGLES = [(0.3, 0.8, 0.5, 0.4), (1.7, -0.6, 2.2, 1.1), (-0.9, 2.5, 0.05, -1.3)]


def _bindings(angles: tuple[float, ...], p: int) -> dict[str, float]:
    return dict(zip(["gamma_0", "beta_0", "gamma_1", "beta_1"][: 2 * p], angles, strict=False))


def _sparse_state(circuit: object, bindings: dict[str, float]) -> dict[int, complex]:
    from qcpp.simulate.sparse import simulate_sparse

    return simulate_sparse(circuit, 0, bindings)  # type: ignore[arg-type]


def _overlap_of(a: dict[int, complex], b: dict[int, complex]) -> float:
    """``|<a|b>|`` of two normalised sparse states: 1 exactly when they are equal up to a global phase."""
    return abs(sum(a[k].conjugate() * b.get(k, 0) for k in a))


@pytest.mark.parametrize("angles", ANGLES, ids=["a", "b", "c"])
@pytest.mark.parametrize("p", [1, 2])
@pytest.mark.parametrize("case", list(SMALL))
def test_without_the_first_phase_separator_the_state_is_the_same(case: str, p: int, angles: tuple) -> None:
    s, initial = SMALL[case]
    bind = _bindings(angles, p)  # gamma_0 bound too: a name with no gate binds as before
    with_it = _sparse_state(qcpp.compile(s, p, initial=initial, lowered=True).circuit, bind)
    without = qcpp.compile(s, p, initial=initial, lowered=True, first_phase=False).circuit
    assert "gamma_0" not in without.symbols and not any(sec.name == "phase_0" for sec in without.sections)
    assert _overlap_of(with_it, _sparse_state(without, bind)) == pytest.approx(1.0, abs=1e-9)


def test_a_superposition_start_is_refused() -> None:
    with pytest.raises(qcpp.OptionError, match=r"^first_phase: .*local_search_mix"):
        qcpp.compile(FIELD, 1, initial="local_search_mix", first_phase=False)
    with pytest.raises(qcpp.OptionError, match=r"^first_phase: .*local_search_mix"):
        qcpp.estimate(FIELD, 1, initial="local_search_mix", first_phase=False)


def test_leaving_out_the_first_phase_separator_of_a_superposition_changes_the_state() -> None:
    """The negative control: the sections ``phase_0`` taken out of the ``local_search_mix`` circuit by hand (what
    the option would do, were it not refused) give another state, so the check above can fail."""
    from qcpp.ir.circuit import Circuit

    full = qcpp.compile(FIELD, 1, initial="local_search_mix", lowered=True).circuit
    cut = Circuit(full.registers, [sec for sec in full.sections if sec.name != "phase_0"])
    bind = _bindings(ANGLES[0], 1)
    assert _overlap_of(_sparse_state(full, bind), _sparse_state(cut, bind)) < 0.99


@pytest.mark.parametrize("case", ["3x3/1 local_search", "2x3/2 initial_path"])
def test_the_subspace_simulator_gives_the_state_of_the_circuit_without_it(case: str) -> None:
    """The feasible-subspace simulator applies every phase separator; the circuit without the first one differs
    from its state by a global phase only."""
    from qcpp.simulate.subspace import SubspaceQAOA

    s, initial = SMALL[case]
    angles = ANGLES[1]
    circuit = qcpp.compile(s, 2, initial=initial, lowered=True, first_phase=False).circuit
    mine = SubspaceQAOA(s, initial=initial).state_dict(list(angles), key="index")  # type: ignore[arg-type]
    assert _overlap_of(_sparse_state(circuit, _bindings(angles, 2)), mine) == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("method", ["state", "gadgets"])
def test_feasibility_is_verified_without_the_first_phase_separator(method: str) -> None:
    from qcpp.plan.options import PlanOptions
    from qcpp.verification import verify

    s = qcpp.grid_scenario(2, 3, robots=2)
    report = verify(s, 2, "exact", method, 20, 0, options=PlanOptions(first_phase=False))  # type: ignore[arg-type]
    assert report.holds
