"""Tests for qcpp.simulate.statevector against an independent dense reference."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from qcpp.ir import gates as G
from qcpp.ir.angles import Angle, UnboundParameterError
from qcpp.ir.circuit import Circuit, CircuitBuilder, Section
from qcpp.ir.gates import Gate, unitary
from qcpp.lowering.passes import lower
from qcpp.simulate.statevector import circuit_unitary, simulate_statevector
from qcpp.testing import circuits

VALUES = {"gamma_0": 0.37, "beta_0": -1.3, "gamma_1": 2.1}


def embed(gate: Gate, n: int) -> np.ndarray:
    """Full 2^n matrix of ``gate`` by explicit index arithmetic (reference implementation)."""
    u = unitary(gate)
    qs = gate.qubits
    dim = 2**n
    full = np.zeros((dim, dim), dtype=complex)
    for col in range(dim):
        local_in = sum(((col >> q) & 1) << j for j, q in enumerate(qs))
        rest = col & ~sum(1 << q for q in qs)
        for local_out in range(len(u)):
            row = rest | sum(((local_out >> j) & 1) << q for j, q in enumerate(qs))
            full[row, col] += u[local_out, local_in]
    return full


def reference_unitary(c: Circuit) -> np.ndarray:
    m = np.eye(2**c.num_qubits, dtype=complex)
    for g in c.bind(VALUES).gates:
        m = embed(g, c.num_qubits) @ m
    return m


@settings(max_examples=50, deadline=None)
@given(circuits(max_qubits=5, max_gates=6, symbolic=True))
def test_matches_reference(c: Circuit) -> None:
    ref = reference_unitary(c)
    np.testing.assert_allclose(circuit_unitary(c, VALUES), ref, atol=1e-9)
    psi0 = np.random.default_rng(1).normal(size=2**c.num_qubits) + 0j
    psi0 /= np.linalg.norm(psi0)
    np.testing.assert_allclose(simulate_statevector(c, psi0, VALUES), ref @ psi0, atol=1e-9)
    np.testing.assert_allclose(
        simulate_statevector(c, 3 % 2**c.num_qubits, VALUES), ref[:, 3 % 2**c.num_qubits], atol=1e-9
    )


def test_basis_convention_qubit0_is_least_significant() -> None:
    c = Circuit([("data", 3)], [Section("s", [G.x(0), G.x(2)])])
    psi = simulate_statevector(c)
    assert psi[0b101] == 1 and np.count_nonzero(psi) == 1
    psi = simulate_statevector(Circuit([("data", 3)], [Section("s", [G.cx(1, 0)])]), 0b010)
    assert psi[0b011] == 1


def test_every_gate_on_scattered_qubits() -> None:
    n = 7
    gates = [
        G.x(5), G.h(6), G.t(0), G.rx(0.3, 4), G.cx(6, 1), G.cz(0, 5), G.crz(0.5, 3, 0), G.cry(0.2, 6, 2),
        G.rzz(0.9, 5, 1), G.ccx(6, 0, 3), G.mcx([1, 6, 3], 0, "010"), G.sbf(0.4, 6, 0, 3, 2),
        G.csbf(-0.7, 2, 5, 0, 6, 4), G.ry(-1.0, 6), G.sdg(3), G.s(1), G.tdg(2),
    ]  # fmt: skip
    c = Circuit([("data", n)], [Section("s", gates)])
    np.testing.assert_allclose(circuit_unitary(c), reference_unitary(c), atol=1e-12)


def test_fused_runs_on_one_and_two_qubits() -> None:
    # runs the simulator fuses (same one or two qubits, gates in both qubit orders), split by ccx
    gates = [
        G.cx(3, 1), G.rz(0.4, 1), G.cx(3, 1), G.crz(0.2, 1, 3), G.rzz(0.3, 1, 3), G.t(3),  # diagonal
        G.ccx(0, 1, 2),
        G.cz(2, 0), G.cx(0, 2), G.rz(-1.0, 2), G.cx(0, 2), G.crz(0.7, 0, 2),  # diagonal
        G.ccx(1, 2, 3),
        G.h(1), G.x(1), G.rx(0.1, 1), G.s(1),  # one qubit
        G.ccx(0, 1, 3),
        G.cry(0.5, 3, 1), G.h(1), G.h(1), G.cx(1, 3),  # dense: applied gate by gate
    ]  # fmt: skip
    c = Circuit([("data", 4)], [Section("s", gates)])
    np.testing.assert_allclose(circuit_unitary(c), reference_unitary(c), atol=1e-12)


def test_initial_state_validation() -> None:
    c = Circuit([("data", 2)], [Section("s", [G.h(0)])])
    with pytest.raises(ValueError):
        simulate_statevector(c, 4)
    with pytest.raises(ValueError):
        simulate_statevector(c, np.ones(3))
    out = simulate_statevector(c, np.array([0, 1, 0, 0]))
    np.testing.assert_allclose(out, [2**-0.5, -(2**-0.5), 0, 0])


def test_bindings_and_unbound_error() -> None:
    c = Circuit([("data", 1)], [Section("s", [G.rx(Angle.symbol("beta_0", 2.0), 0)])])
    with pytest.raises(UnboundParameterError, match="beta_0"):
        simulate_statevector(c)
    with pytest.raises(UnboundParameterError):
        circuit_unitary(c)
    np.testing.assert_allclose(simulate_statevector(c, 0, {"beta_0": np.pi / 2}), [0, -1j], atol=1e-12)


def test_unitary_size_limit() -> None:
    with pytest.raises(ValueError):
        circuit_unitary(Circuit([("data", 15)]))


def test_twenty_qubits() -> None:
    rng = np.random.default_rng(0)
    n = 18
    b = CircuitBuilder([("data", n)])
    b.append([G.h(q) for q in range(n)], section="initial_state")
    for _ in range(20):
        a, c = rng.choice(n, 2, replace=False).tolist()
        b.append(G.rzz(rng.uniform(-1, 1), a, c), section="phase_0")
    for _ in range(5):
        qs = rng.choice(n, 5, replace=False).tolist()
        b.append(G.mcx(qs[:4], qs[4], "1010"), section="mixer_0")
        b.append(G.rx(0.3, qs[4]))
    high = b.build()
    low = lower(high)
    assert low.num_qubits == 20 and len(low) > 200
    psi = simulate_statevector(low)
    assert abs(np.linalg.norm(psi) - 1) < 1e-9
    # the work qubits (the two high bits) end in |0>, and the data part matches the high level
    np.testing.assert_allclose(psi[2**n :], 0, atol=1e-9)
    np.testing.assert_allclose(psi[: 2**n], simulate_statevector(high), atol=1e-9)
