"""Tests for qcpp.simulate.sparse: agreement with the dense simulator, big sparse circuits."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.ir import gates as G
from qcpp.ir.angles import Angle, UnboundParameterError
from qcpp.ir.circuit import Circuit, CircuitBuilder, Section
from qcpp.lowering.passes import lower
from qcpp.simulate.sparse import PRUNE_TOLERANCE, basis_from_bits, bits_of, simulate_sparse
from qcpp.simulate.statevector import simulate_statevector
from qcpp.testing import circuits

VALUES = {"gamma_0": 0.37, "beta_0": -1.3, "gamma_1": 2.1}


def dense(state: dict[int, complex], n: int) -> np.ndarray:
    v = np.zeros(2**n, dtype=complex)
    for k, a in state.items():
        v[k] = a
    return v


@settings(max_examples=80, deadline=None)
@given(circuits(max_qubits=6, max_gates=10, max_controls=5, symbolic=True), st.data())
def test_sparse_agrees_with_statevector(c: Circuit, data: st.DataObject) -> None:
    start = data.draw(st.integers(0, 2**c.num_qubits - 1))
    ours = dense(simulate_sparse(c, start, VALUES), c.num_qubits)
    np.testing.assert_allclose(ours, simulate_statevector(c, start, VALUES), atol=1e-9)


@settings(max_examples=20, deadline=None)
@given(circuits(max_qubits=5, max_gates=8, symbolic=True))
def test_sparse_agrees_on_superposition_input(c: Circuit) -> None:
    n = c.num_qubits
    init = {0: 0.6, 2**n - 1: 0.8j}
    ours = dense(simulate_sparse(c, init, VALUES), n)
    np.testing.assert_allclose(ours, simulate_statevector(c, dense(init, n), VALUES), atol=1e-9)


def test_hundreds_of_qubits() -> None:
    n = 400
    b = CircuitBuilder([("data", n)])
    b.append([G.x(0), G.x(1), G.x(2), G.x(3)], section="prep")
    b.append([G.mcx([0, 1, 2, 3], 399), G.cx(399, 200), G.mcx([0, 200, 5], 300, "110")], section="logic")
    b.append([G.rz(0.5, 300), G.rzz(0.25, 0, 399)], section="phase")
    c = lower(b.build())
    assert c.num_qubits == n + 2
    out = simulate_sparse(c, 0)
    ((key, amp),) = out.items()
    assert bits_of(key, [0, 1, 2, 3, 399, 200, 300, n, n + 1]) == (1, 1, 1, 1, 1, 1, 1, 0, 0)
    # rz(0.5) on |1>: e^{+0.25i}; rzz(0.25) on |11> (even parity): e^{-0.125i}
    np.testing.assert_allclose(amp, np.exp(0.25j) * np.exp(-0.125j))


def test_branching_and_pruning() -> None:
    c = Circuit([("data", 2)], [Section("s", [G.h(0), G.h(1), G.h(0)])])
    out = simulate_sparse(c, 0)
    assert set(out) == {0, 2}  # the |1> branch of qubit 0 cancels and is pruned
    np.testing.assert_allclose(sorted(abs(a) for a in out.values()), [2**-0.5] * 2)
    assert all(abs(a) >= PRUNE_TOLERANCE for a in out.values())


def test_helpers() -> None:
    assert basis_from_bits([]) == 0
    assert basis_from_bits([True, False, True, True]) == 13
    assert bits_of(13, [3, 2, 1, 0]) == (1, 1, 0, 1)
    assert basis_from_bits([0] * 299 + [1]) == 2**299


def test_errors() -> None:
    c = Circuit([("data", 2)], [Section("s", [G.rz(Angle.symbol("gamma_0"), 0)])])
    with pytest.raises(UnboundParameterError):
        simulate_sparse(c, 0)
    assert simulate_sparse(c, 1, {"gamma_0": 0.0}) == {1: 1}
    with pytest.raises(ValueError):
        simulate_sparse(c.bind({"gamma_0": 0.0}), 4)
