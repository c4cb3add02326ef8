"""Phase separator, initial states and the assembled QAOA circuit, checked by simulation."""

from __future__ import annotations

import cmath
import math
import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.gadgets.initial_state import initial_state_gates, superposition_gates
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.lowering.passes import lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.phase import phase_separator_gates
from qcpp.plan.qaoa import qaoa_circuit, qaoa_plan, qubit_map
from qcpp.problem.cost import cost
from qcpp.problem.grid import Grid
from qcpp.problem.hamiltonian import ising_hamiltonian
from qcpp.problem.paths import assignment_bits, enumerate_paths, initial_path, mask_from_bits
from qcpp.problem.sbf import representatives
from qcpp.problem.scenario import Objective, Robot, Scenario
from qcpp.simulate.sparse import basis_from_bits, simulate_sparse
from qcpp.simulate.statevector import simulate_statevector

from .conftest import scenarios

TOL = 1e-9


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    s=scenarios(max_side=4, max_robots=3),
    gamma=st.floats(-3, 3, allow_nan=False),
    seed=st.integers(0, 2**32 - 1),
    lowered=st.booleans(),
)
def test_phase_separator_multiplies_each_basis_state_by_its_cost_phase(
    s: Scenario, gamma: float, seed: int, lowered: bool
) -> None:
    h = ising_hamiltonian(s)
    c = Circuit([Register("data", s.num_variables)], [Section("phase_0", phase_separator_gates(h, "gamma_0"))])
    c = c.bind({"gamma_0": gamma})
    if lowered:
        c = lower(c)
    rng = random.Random(seed)
    for _ in range(3):
        bits = [rng.randrange(2) for _ in range(s.num_variables)]
        out = simulate_sparse(c, basis_from_bits(bits))
        v = s.edges_per_robot
        masks = [mask_from_bits(s, bits[r * v : (r + 1) * v]) for r in range(s.num_robots)]
        expected = cmath.exp(-1j * gamma * (cost(s, masks) - h.c0))
        assert list(out) == [basis_from_bits(bits)]
        assert abs(out[basis_from_bits(bits)] - expected) < 1e-8


def test_phase_separator_omits_zero_coefficients() -> None:
    s = Scenario(Grid(3, 3), (Robot((0, 0), (2, 2)), Robot((0, 2), (2, 0))))
    h = ising_hamiltonian(s)
    gates = phase_separator_gates(h, "gamma_0")
    n_rz = int(np.count_nonzero(np.abs(h.h) > 1e-12))
    n_rzz = int(np.count_nonzero(np.abs(h.J) > 1e-12))
    assert [g.name for g in gates].count("rz") == n_rz
    assert [g.name for g in gates].count("rzz") == n_rzz
    assert n_rzz < s.num_variables * (s.num_variables - 1) // 2  # some couplings cancel exactly


@settings(max_examples=40, deadline=None)
@given(
    strings=st.lists(st.integers(0, 2**6 - 1), min_size=1, max_size=9, unique=True),
)
def test_superposition_prepares_the_uniform_state_on_the_given_strings(strings: list[int]) -> None:
    n = 6
    gates = superposition_gates(strings, list(range(n)), ancilla=n)
    c = Circuit([Register("data", n), Register("logic", 1)], [Section("initial_state", gates)])
    for circuit in (c, lower(c)):
        psi = simulate_statevector(circuit)
        expected = np.zeros(2 ** circuit.num_qubits, dtype=complex)
        expected[strings] = 1 / math.sqrt(len(strings))
        assert np.allclose(psi, expected, atol=TOL)


def test_initial_path_state_is_the_basis_state_of_the_initial_paths() -> None:
    s = Scenario(Grid(3, 4), (Robot((0, 0), (2, 3)), Robot((2, 1), (0, 2))))
    c = Circuit([Register("data", s.num_variables)], [Section("initial_state", initial_state_gates(s))])
    out = simulate_sparse(c, 0)
    expected = basis_from_bits(list(assignment_bits(s, [initial_path(s, 0), initial_path(s, 1)])))
    assert out == {expected: 1}


def test_representatives_initial_state_covers_every_component() -> None:
    # hard obstacles that split the moves into several components on a small grid, if any exist
    found = None
    for obs in [((1, 1),), ((0, 1), (2, 1)), ((1, 0), (1, 2)), ((1, 1), (2, 2))]:
        for a in Grid(3, 4).nodes:
            for b in Grid(3, 4).nodes:
                if a >= b or a in obs or b in obs:
                    continue
                try:
                    s = Scenario(Grid(3, 4), (Robot(a, b),), tuple(sorted(obs)), Objective(obstacles="hard"))
                except Exception:
                    continue
                if len(representatives(s, 0)) > 1:
                    found = s
                    break
            if found:
                break
        if found:
            break
    s = found or Scenario(Grid(3, 3), (Robot((0, 0), (2, 2)),))
    reps = representatives(s, 0)
    c = qaoa_circuit(s, 0, PlanOptions(initial="representatives"))
    out = simulate_sparse(lower(c), 0)
    expected = {basis_from_bits(list(assignment_bits(s, [m]))): 1 / math.sqrt(len(reps)) for m in reps}
    assert out.keys() == expected.keys()
    assert all(abs(out[k] - v) < TOL for k, v in expected.items())


def test_qaoa_circuit_layout_and_symbols() -> None:
    s = Scenario(Grid(3, 3), (Robot((0, 0), (2, 2)),), ((1, 1),))
    c = qaoa_circuit(s, 3)
    assert c.symbols == ("gamma_0", "beta_0", "gamma_1", "beta_1", "gamma_2", "beta_2")
    names = [sec.name for sec in c.sections]
    assert names[0] == "initial_state"
    assert [n for n in dict.fromkeys(names)] == [
        "initial_state", "phase_0", "mixer_0", "phase_1", "mixer_1", "phase_2", "mixer_2",
    ]
    qm = qubit_map(s, lower(c).num_qubits)
    assert len(qm.data) == s.num_variables == 12
    assert qm.data[0] == (0, 0)
    assert list(qm.ancillas) == list(range(12, lower(c).num_qubits))
    with pytest.raises(ValueError, match="non-negative"):
        qaoa_circuit(s, -1)


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(s=scenarios(max_side=3, max_robots=2), p=st.integers(1, 2), angles=st.sampled_from(["layer", "multi"]))
def test_every_symbol_of_the_circuit_is_a_parameter_name(s: Scenario, p: int, angles: str) -> None:
    # compile --bind checks names against parameter_names alone, so no gate may carry an angle it does not list
    plan = qaoa_plan(s, p, PlanOptions(angles=angles))
    assert set(plan.circuit().symbols) <= set(plan.parameter_names)
    assert len(set(plan.parameter_names)) == len(plan.parameter_names)
    plan.check_bindings(plan.parameter_names)
    with pytest.raises(ValueError, match="unknown symbol"):
        plan.check_bindings(["gamma_99"])


def test_whole_lowered_circuit_stays_feasible_with_clean_ancillas() -> None:
    s = Scenario(Grid(3, 3), (Robot((0, 0), (2, 2)),), ((1, 1),))
    c = lower(qaoa_circuit(s, 2)).bind({"gamma_0": 0.3, "beta_0": 1.1, "gamma_1": -0.4, "beta_1": 0.6})
    psi = simulate_statevector(c)
    feasible = {basis_from_bits(list(assignment_bits(s, [m]))) for m in enumerate_paths(s, 0)}
    held = sum(abs(psi[i]) ** 2 for i in feasible)
    assert abs(held - 1) < 1e-9
    assert abs(np.linalg.norm(psi) - 1) < 1e-9
