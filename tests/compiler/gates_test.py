"""Tests for qcpp.ir.gates: constructors, spec table, inverse, matrices (against Qiskit)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from qiskit import QuantumCircuit
from qiskit.circuit.library import UnitaryGate
from qiskit.quantum_info import Operator, Pauli

from qcpp.ir import gates as G
from qcpp.ir.angles import Angle, UnboundParameterError
from qcpp.ir.gates import GATE_SPECS, Gate, controlled_x_pattern, diagonal, unitary
from qcpp.testing import gates as random_gates


def qiskit_matrix(gate: Gate) -> np.ndarray:
    """Matrix of ``gate`` built with Qiskit's own gates on qubits 0..n-1 in the given order."""
    n = len(gate.qubits)
    qc = QuantumCircuit(n)
    qs = list(range(n))
    name = gate.name
    theta = float(gate.params[0]) if gate.params else 0.0
    if name in ("x", "h", "t", "tdg", "s", "sdg"):
        getattr(qc, name)(0)
    elif name in ("rz", "rx", "ry"):
        getattr(qc, name)(theta, 0)
    elif name in ("cx", "cz"):
        getattr(qc, name)(0, 1)
    elif name in ("crz", "cry", "crx", "rzz"):
        getattr(qc, name)(theta, 0, 1)
    elif name == "ccx":
        qc.ccx(0, 1, 2)
    elif name in ("mcx", "and", "and_dg"):
        # Qiskit's ctrl_state string is big-endian (last char = first control); ours is not
        qc.mcx(qs[:-1], n - 1, ctrl_state=gate.ctrl_state[::-1])
    elif name == "sbf":
        qc.append(_pauli_rotation("XXXX", theta), qs)
    elif name == "csbf":
        qc.append(_pauli_rotation("XXXX", theta).control(1), qs)
    else:  # pragma: no cover
        raise AssertionError(name)
    return Operator(qc).data


def _pauli_rotation(label: str, theta: float) -> UnitaryGate:
    """exp(-iθP/2) from Qiskit's Pauli matrix."""
    p = Pauli(label).to_matrix()
    return UnitaryGate(math.cos(theta / 2) * np.eye(len(p)) - 1j * math.sin(theta / 2) * p)


ONE_OF_EACH = [
    G.x(0), G.h(0), G.t(0), G.tdg(0), G.s(0), G.sdg(0),
    G.rz(0.7, 0), G.rx(-1.1, 0), G.ry(2.3, 0),
    G.cx(0, 1), G.cz(0, 1), G.crz(0.9, 0, 1), G.cry(-0.4, 0, 1), G.crx(0.5, 0, 1), G.rzz(1.3, 0, 1),
    G.and_(0, 1, 2, "10"), G.and_dg(0, 1, 2, "01"),
    G.ccx(0, 1, 2), G.mcx([0], 1, "0"), G.mcx([0, 1], 2, "01"), G.mcx([0, 1, 2], 3, "110"),
    G.mcx([0, 1, 2, 3], 4, "1111"), G.sbf(0.6, 0, 1, 2, 3), G.csbf(-1.2, 0, 1, 2, 3, 4),
]  # fmt: skip


def test_table_covers_every_constructor() -> None:
    assert {g.name for g in ONE_OF_EACH} == set(GATE_SPECS)


@pytest.mark.parametrize("gate", ONE_OF_EACH, ids=lambda g: str(g))
def test_unitary_matches_qiskit_exactly(gate: Gate) -> None:
    np.testing.assert_allclose(unitary(gate), qiskit_matrix(gate), atol=1e-12)


@pytest.mark.parametrize("gate", ONE_OF_EACH, ids=lambda g: str(g))
def test_spec_flags_match_the_matrix(gate: Gate) -> None:
    u = unitary(gate)
    spec = gate.spec
    assert u.shape == (2 ** len(gate.qubits),) * 2
    np.testing.assert_allclose(u @ u.conj().T, np.eye(len(u)), atol=1e-12)
    off_diagonal = u - np.diag(np.diag(u))
    assert spec.diagonal == bool(np.allclose(off_diagonal, 0))
    is_permutation = bool(np.all(np.isin(u, [0, 1])) and np.allclose(np.abs(u).sum(axis=0), 1))
    assert spec.permutation == is_permutation
    if spec.diagonal:
        np.testing.assert_allclose(diagonal(gate), np.diag(u))
    assert spec.num_params == len(gate.params)
    if spec.num_qubits is not None:
        assert spec.num_qubits == len(gate.qubits)


@pytest.mark.parametrize("gate", ONE_OF_EACH, ids=lambda g: str(g))
def test_inverse_rule(gate: Gate) -> None:
    inv = gate.inverse()
    np.testing.assert_allclose(unitary(inv) @ unitary(gate), np.eye(2 ** len(gate.qubits)), atol=1e-12)
    assert inv.inverse() == gate


@given(random_gates(6, symbolic=True))
def test_inverse_of_random_gates(gate: Gate) -> None:
    bound = gate.bind({"gamma_0": 0.3, "beta_0": -0.7, "gamma_1": 1.1})
    inv = gate.inverse().bind({"gamma_0": 0.3, "beta_0": -0.7, "gamma_1": 1.1})
    np.testing.assert_allclose(unitary(inv) @ unitary(bound), np.eye(2 ** len(gate.qubits)), atol=1e-12)


def test_qubit_order_convention() -> None:
    # cx(1, 0): control is local bit 0 (listed first), so |control=1, target=0> = index 1 -> 3
    u = unitary(G.cx(1, 0))
    assert u[3, 1] == 1 and u[1, 3] == 1 and u[0, 0] == 1 and u[2, 2] == 1
    # crz acts on |c=1>: local indices 1 and 3
    np.testing.assert_allclose(np.diag(unitary(G.crz(math.pi, 0, 1))), [1, -1j, 1, 1j], atol=1e-15)


def test_mcx_normalisation() -> None:
    assert G.mcx([], 3) == G.x(3)
    assert G.mcx([], 3, "") == G.x(3)
    assert G.mcx([1], 0) == G.cx(1, 0)
    assert G.mcx([1, 2], 0) == G.ccx(1, 2, 0)
    assert G.mcx([1, 2], 0, "10").name == "mcx"
    assert G.mcx([1], 0, "0").name == "mcx"
    g = G.mcx([1, 2, 3], 0)
    assert g.name == "mcx" and g.ctrl_state == "111" and g.qubits == (1, 2, 3, 0)
    assert controlled_x_pattern(g) == ((1, 2, 3), "111", 0)
    assert controlled_x_pattern(G.x(4)) == ((), "", 4)
    with pytest.raises(ValueError):
        controlled_x_pattern(G.h(0))


@pytest.mark.parametrize(
    "call",
    [
        lambda: G.mcx([0, 1], 2, "1"),
        lambda: G.mcx([0, 1], 2, "12"),
        lambda: G.mcx([0, 0], 2),
        lambda: G.cx(1, 1),
        lambda: G.ccx(0, 1, 0),
        lambda: G.sbf(0.1, 0, 1, 2, 2),
        lambda: G.h(-1),
    ],
)
def test_constructor_validation_value_errors(call) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(ValueError):
        call()


def test_constructor_validation_type_errors() -> None:
    with pytest.raises(TypeError):
        G.h(1.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        G.cx(True, 2)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        G.rz(True, 0)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        G.rz("0.5", 0)  # type: ignore[arg-type]


def test_numpy_ints_and_int_angles_are_normalised() -> None:
    g = G.rz(1, np.int64(3))  # type: ignore[arg-type]
    assert g.qubits == (3,) and type(g.qubits[0]) is int
    assert g.params == (1.0,) and type(g.params[0]) is float


def test_value_semantics() -> None:
    a = G.rzz(Angle.symbol("gamma_0", 2.0), 0, 1)
    b = G.rzz(2 * Angle.symbol("gamma_0"), 0, 1)
    assert a == b and hash(a) == hash(b)
    assert len({G.h(0), G.h(0), G.h(1)}) == 2
    with pytest.raises(AttributeError):
        a.name = "rz"  # type: ignore[misc]
    assert str(G.mcx([0, 1, 2], 3, "101")) == "mcx[101] 0 1 2 3"
    assert str(G.rz(2 * Angle.symbol("gamma_0") + 0.5, 4)) == "rz(2.0*gamma_0 + 0.5) 4"


def test_bind_converts_bound_angles_to_float() -> None:
    g = G.crz(Angle.symbol("beta_0", 2.0) + 0.5, 0, 1)
    assert g.bind({"gamma_0": 1.0}) is g
    bound = g.bind({"beta_0": 0.25})
    assert bound.params == (1.0,) and type(bound.params[0]) is float
    assert G.h(0).bind({"beta_0": 1.0}) == G.h(0)


def test_unitary_needs_bound_parameters() -> None:
    with pytest.raises(UnboundParameterError):
        unitary(G.rx(Angle.symbol("beta_0"), 0))
    with pytest.raises(UnboundParameterError):
        diagonal(G.rz(Angle.symbol("beta_0"), 0))


@pytest.mark.parametrize("k", range(1, 6))
def test_mcx_unitary_every_polarity(k: int) -> None:
    for state in itertools.product("01", repeat=k):
        g = G.mcx(list(range(k)), k, "".join(state))
        u = unitary(g)
        for col in range(2**k * 2):
            controls_match = all(((col >> i) & 1) == int(b) for i, b in enumerate(state))
            expected = col ^ (1 << k) if controls_match else col
            assert u[expected, col] == 1


@given(st.integers(0, 40), st.integers(0, 40))
def test_two_qubit_fast_path_validation(a: int, b: int) -> None:
    if a == b:
        with pytest.raises(ValueError):
            G.rzz(0.1, a, b)
    else:
        assert G.rzz(0.1, a, b).qubits == (a, b)
