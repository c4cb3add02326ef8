"""The circuit as a Cirq and a pytket object (qcpp.lowering.toolchains): the same unitary, global phase included,
as an independent conversion (Qiskit's), on random gate sequences and on compiled QAOA circuits; symbols kept."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import qcpp
from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, ccx, crx, cry, crz, csbf, mcx, rx, ry, rz, rzz, sbf
from qcpp.lowering.toolchains import DIRECT, to_cirq, to_pytket

cirq = pytest.importorskip("cirq")
pytket = pytest.importorskip("pytket")
qiskit_qi = pytest.importorskip("qiskit.quantum_info")

WIDTH = 5
ONE_QUBIT = ("x", "h", "t", "tdg", "s", "sdg")
TWO_QUBIT = ("cx", "cz")


@st.composite
def gates(draw: st.DrawFn) -> Gate:
    """One gate of any kind the converters write directly or decompose, on distinct qubits of ``WIDTH``."""
    kind = draw(st.sampled_from(["one", "two", "rot", "crot", "rzz", "ccx", "mcx", "sbf", "csbf"]))
    qs = draw(st.permutations(range(WIDTH)))
    theta = draw(st.floats(-2 * math.pi, 2 * math.pi, allow_nan=False))
    if kind == "one":
        return Gate(draw(st.sampled_from(ONE_QUBIT)), (qs[0],), (), None)
    if kind == "two":
        return Gate(draw(st.sampled_from(TWO_QUBIT)), (qs[0], qs[1]), (), None)
    if kind == "rot":
        return draw(st.sampled_from([rz, rx, ry]))(theta, qs[0])
    if kind == "crot":
        return draw(st.sampled_from([crz, cry, crx]))(theta, qs[0], qs[1])
    if kind == "rzz":
        return rzz(theta, qs[0], qs[1])
    if kind == "ccx":
        return ccx(qs[0], qs[1], qs[2])
    if kind == "mcx":
        k = draw(st.integers(1, 3))
        state = draw(st.text("01", min_size=k, max_size=k))
        return mcx(list(qs[:k]), qs[k], state)
    if kind == "sbf":
        return sbf(theta, *qs[:4])
    return csbf(theta, *qs[:5])


def _reference_unitary(circuit: Circuit) -> np.ndarray:
    """The unitary by qcpp's direct IR -> Qiskit conversion (``qcpp.simulate.equivalence.to_qiskit``), little
    endian."""
    from qcpp.simulate.equivalence import to_qiskit

    return qiskit_qi.Operator(to_qiskit(circuit)).data


def _little_endian(matrix_or_vector: np.ndarray, n: int) -> np.ndarray:
    """A big-endian (qubit 0 most significant) vector or matrix in Qiskit's little-endian order."""
    order = list(range(n - 1, -1, -1))
    if matrix_or_vector.ndim == 1:
        return matrix_or_vector.reshape([2] * n).transpose(order).reshape(-1)
    m = matrix_or_vector.reshape([2] * (2 * n))
    return m.transpose(order + [n + i for i in order]).reshape(2**n, 2**n)


def _cirq_unitary(circuit: Circuit) -> np.ndarray:
    n = circuit.num_qubits
    return _little_endian(to_cirq(circuit).unitary(qubit_order=cirq.LineQubit.range(n)), n)


def _pytket_unitary(circuit: Circuit) -> np.ndarray:
    return _little_endian(to_pytket(circuit).get_unitary(), circuit.num_qubits)


@settings(max_examples=60, deadline=None)
@given(st.lists(gates(), min_size=1, max_size=12))
def test_random_gate_sequences_have_the_reference_unitary_phase_included(sequence: list[Gate]) -> None:
    circuit = Circuit([("q", WIDTH)], [Section("s", sequence)])
    want = _reference_unitary(circuit)
    assert np.allclose(_cirq_unitary(circuit), want, atol=1e-9)
    assert np.allclose(_pytket_unitary(circuit), want, atol=1e-9)


def test_a_wrong_matrix_is_caught() -> None:
    """The comparison can fail: an extra T gate changes the unitary by a relative phase only."""
    base = Circuit([("q", 2)], [Section("s", [Gate("h", (0,), (), None), Gate("cx", (0, 1), (), None)])])
    other = Circuit([("q", 2)], [Section("s", [*base.gates, Gate("t", (1,), (), None)])])
    assert not np.allclose(_cirq_unitary(other), _reference_unitary(base), atol=1e-9)
    assert not np.allclose(_pytket_unitary(other), _reference_unitary(base), atol=1e-9)


def _state_reference(compiled: qcpp.Compiled) -> np.ndarray:
    """The state from |0...0> by Qiskit's reading of the OpenQASM 3 (``to_qiskit``), little endian."""
    return qiskit_qi.Statevector(compiled.to_qiskit()).data


def _cirq_state(compiled: qcpp.Compiled, resolver: dict[str, float] | None = None) -> np.ndarray:
    c = to_cirq(compiled.circuit)
    if resolver:
        c = cirq.resolve_parameters(c, cirq.ParamResolver(resolver))
    n = compiled.qubits
    vec = cirq.final_state_vector(c, qubit_order=cirq.LineQubit.range(n), dtype=np.complex128)
    return _little_endian(vec, n)


def _pytket_state(compiled: qcpp.Compiled, resolver: dict[str, float] | None = None) -> np.ndarray:
    import sympy

    c = to_pytket(compiled.circuit)
    if resolver:
        c.symbol_substitution({sympy.Symbol(k): v for k, v in resolver.items()})
    return _little_endian(c.get_statevector(), compiled.qubits)


ANGLES = {"gamma_0": 0.37, "beta_0": 1.21}


@pytest.mark.parametrize("lowered", [False, True])
@pytest.mark.parametrize(("rows", "cols", "robots"), [(2, 3, 1), (2, 2, 2)])
def test_compiled_qaoa_circuits_give_the_state_of_qiskits_reading(rows: int, cols: int, robots: int,
                                                                  lowered: bool) -> None:  # fmt: skip
    """High level (``and``, ``sbf``-like gadgets decomposed) and lowered (gate for gate), with clean ancillas."""
    s = qcpp.grid_scenario(rows, cols, robots=robots)
    bound = qcpp.compile(s, p=1, lowered=lowered, bind=ANGLES)
    want = _state_reference(bound)
    assert np.allclose(_cirq_state(bound), want, atol=1e-9)
    assert np.allclose(_pytket_state(bound), want, atol=1e-9)


def test_unbound_symbols_stay_symbols_and_resolve_to_the_bound_circuit() -> None:
    s = qcpp.grid_scenario(2, 3, robots=1)
    free = qcpp.compile(s, p=1, lowered=True)
    bound = qcpp.compile(s, p=1, lowered=True, bind=ANGLES)
    assert set(free.symbols) == set(ANGLES)
    assert cirq.parameter_names(free.to_cirq()) == set(ANGLES)
    assert {str(x) for x in free.to_pytket().free_symbols()} == set(ANGLES)
    want = _state_reference(bound)
    assert np.allclose(_cirq_state(free, ANGLES), want, atol=1e-9)
    assert np.allclose(_pytket_state(free, ANGLES), want, atol=1e-9)


def test_a_lowered_circuit_converts_gate_for_gate() -> None:
    c = qcpp.compile(qcpp.grid_scenario(3, 3, robots=1), p=1, lowered=True)
    counts = c.counts()
    assert set(counts) <= DIRECT
    assert len(list(c.to_cirq().all_operations())) == sum(counts.values())
    tk = c.to_pytket()
    assert tk.n_qubits == c.qubits and tk.n_gates == sum(counts.values())
    assert tk.n_gates_of_type(pytket.OpType.CX) == counts["cx"]


def test_a_routed_native_circuit_keeps_its_two_qubit_gates() -> None:
    c = qcpp.compile(qcpp.grid_scenario(2, 3, robots=1), p=1, device="ibm_fez", bind=ANGLES)
    twoq = sum(n for name, n in c.counts().items() if name in ("cz", "cx", "rzz"))
    assert twoq > 0
    assert sum(1 for op in c.to_cirq().all_operations() if len(op.qubits) == 2) == twoq
    tk = c.to_pytket()
    assert tk.n_qubits == c.qubits and tk.n_2qb_gates() == twoq


def test_angles_are_symbolic_expressions_of_the_symbols() -> None:
    g = Angle.symbol("gamma_0", 2.0) + 0.5
    c = Circuit([("q", 2)], [Section("s", [rzz(g, 0, 1), rz(-g, 1)])])
    (zz, z) = list(to_cirq(c).all_operations())
    assert cirq.parameter_names(zz) == {"gamma_0"} and cirq.parameter_names(z) == {"gamma_0"}
    resolved = cirq.resolve_parameters(to_cirq(c), {"gamma_0": 0.25})
    assert np.allclose(cirq.unitary(resolved), cirq.unitary(to_cirq(c.bind({"gamma_0": 0.25}))), atol=1e-12)


@pytest.mark.parametrize(("module", "method", "extra"),
                         [("cirq", "to_cirq", "cirq"), ("pytket", "to_pytket", "pytket")])  # fmt: skip
def test_without_the_toolchain_the_error_names_the_extra(monkeypatch: pytest.MonkeyPatch, module: str, method: str,
                                                         extra: str) -> None:  # fmt: skip
    monkeypatch.setitem(sys.modules, module, None)  # import raises ImportError
    c = qcpp.compile(qcpp.grid_scenario(2, 2, robots=1), p=1)
    with pytest.raises(ImportError, match=rf"^{method} needs .*pip install 'qcpp\[{extra}\]'$") as info:
        getattr(c, method)()
    # one refusal type for every missing extra, as qubo's and simulate_noisy's: a QcppError (one line in the CLI)
    assert isinstance(info.value, qcpp.QcppError) and "\n" not in str(info.value)
