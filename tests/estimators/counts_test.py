"""Exact counts: hand-derived tiny circuits, random circuits against Qiskit, and emitted OpenQASM 2 read by Qiskit."""

from __future__ import annotations

import json
import math

import pytest
import qiskit.qasm2
from hypothesis import given, settings
from hypothesis import strategies as st
from qiskit import QuantumCircuit

from qcpp.estimators.counts import count, count_gates
from qcpp.ir.circuit import Circuit, CircuitBuilder, Register, Section
from qcpp.ir.gates import ccx, cx, h, rz, t, tdg, x
from qcpp.lowering.passes import lower
from qcpp.lowering.qasm import ir_gate_name, to_qasm2
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.presets import default_scenario


def two_qubit_depth(qc: QuantumCircuit) -> int:
    return qc.depth(filter_function=lambda i: i.operation.num_qubits == 2)


# --- by hand ---------------------------------------------------------------------------------------------------
def test_tiny_circuit_by_hand() -> None:
    # q0: h . cx(0,1) . . ccx . . ; q1: . cx(0,1) cx(1,2) ccx ; q2: t . cx(1,2) ccx
    b = CircuitBuilder([Register("data", 2), Register("work", 1)])
    b.append([h(0), t(2), cx(0, 1), cx(1, 2), ccx(0, 1, 2), tdg(0)], section="s")
    rc = count(b.build())
    # layers: {h0, t2} -> cx01 -> cx12 -> ccx -> tdg0: depth 5
    assert rc.depth == 5
    # two-qubit layers: cx01 -> cx12 (shares q1); the ccx adds nothing (not 2-qubit): 2
    assert rc.two_qubit_depth == 2
    assert (rc.qubits, rc.data_qubits, rc.ancillas) == (3, 2, 1)
    assert rc.ops == {"ccx": 1, "cx": 2, "h": 1, "t": 1, "tdg": 1}
    assert (rc.size, rc.single_qubit, rc.two_qubit, rc.multi_qubit, rc.cx, rc.t) == (6, 3, 2, 1, 2, 2)


def test_three_qubit_gate_synchronises_two_qubit_levels_like_qiskit() -> None:
    # cx(0,1) puts q0,q1 at 2q-level 1; ccx(0,1,2) lifts q2 to 1 without adding; cx(2,3) is then at level 2.
    gates = [cx(0, 1), ccx(0, 1, 2), cx(2, 3)]
    gc = count_gates(gates, 4)
    assert gc.two_qubit_depth == 2
    assert gc.depth == 3


def test_parallel_gates_share_a_layer() -> None:
    gates = [h(q) for q in range(4)] + [cx(0, 1), cx(2, 3)] + [x(q) for q in range(4)]
    gc = count_gates(gates, 4)
    assert (gc.depth, gc.two_qubit_depth, gc.size) == (3, 1, 10)


def test_sections_with_the_same_name_merge_and_depth_is_per_name() -> None:
    secs = [Section("mixer_0", [x(0), cx(0, 1)]), Section("phase_1", [x(1), x(1)]), Section("mixer_0", [cx(0, 1)])]
    rc = count(Circuit([("data", 2)], secs))
    assert list(rc.sections) == ["mixer_0", "phase_1"]
    mixer = rc.sections["mixer_0"]
    assert mixer.ops == {"cx": 2, "x": 1}
    # mixer_0 gates alone: x0 -> cx -> cx: depth 3, two-qubit depth 2
    assert (mixer.depth, mixer.two_qubit_depth) == (3, 2)
    # whole circuit: x0 -> cx -> x1 -> x1 -> cx: depth 5
    assert rc.depth == 5
    assert rc.sections["phase_1"].depth == 2
    assert sum(s.size for s in rc.sections.values()) == rc.size


def test_empty_circuit_and_no_data_register() -> None:
    rc = count(Circuit([("logic", 3)]))
    assert (rc.qubits, rc.data_qubits, rc.ancillas, rc.depth, rc.size, rc.sections) == (3, 0, 3, 0, 0, {})


def test_to_dict_is_json_ready() -> None:
    rc = count(lower(qaoa_circuit(default_scenario(2, 3, 2), 1)))
    d = json.loads(json.dumps(rc.to_dict()))
    assert d["sections"]["phase_0"] == rc.sections["phase_0"].to_dict()
    assert {k: d[k] for k in ("qubits", "cx", "depth")} == {"qubits": rc.qubits, "cx": rc.cx, "depth": rc.depth}


# --- random circuits against Qiskit's own counting ---------------------------------------------------------------
N = 5
_gate = st.one_of(
    st.tuples(st.sampled_from(["h", "x", "t", "rz"]), st.lists(st.integers(0, N - 1), min_size=1, max_size=1)),
    st.tuples(st.just("cx"), st.lists(st.integers(0, N - 1), min_size=2, max_size=2, unique=True)),
    st.tuples(st.just("ccx"), st.lists(st.integers(0, N - 1), min_size=3, max_size=3, unique=True)),
)


@settings(max_examples=60, deadline=None)
@given(st.lists(_gate, max_size=40))
def test_random_circuits_match_qiskit(spec: list[tuple[str, list[int]]]) -> None:
    qc = QuantumCircuit(N)
    gates = []
    for name, qs in spec:
        if name == "rz":
            qc.rz(0.3, qs[0])
            gates.append(rz(0.3, qs[0]))
        else:
            getattr(qc, name)(*qs)
            gates.append({"h": h, "x": x, "t": t, "cx": cx, "ccx": ccx}[name](*qs))
    gc = count_gates(gates, N)
    assert gc.depth == qc.depth()
    assert gc.two_qubit_depth == two_qubit_depth(qc)
    assert dict(gc.ops) == dict(sorted(qc.count_ops().items()))


# --- emitted OpenQASM 2 read back by Qiskit ----------------------------------------------------------------------
CASES = [(3, 3, 1, True), (2, 3, 2, True), (2, 3, 2, False), (3, 3, 1, False)]


@pytest.mark.parametrize(("rows", "cols", "robots", "lowered"), CASES)
def test_counts_equal_qiskits_on_emitted_qasm2(rows: int, cols: int, robots: int, lowered: bool) -> None:
    circ = qaoa_circuit(default_scenario(rows, cols, robots), 1)
    if lowered:
        circ = lower(circ)
    circ = circ.bind({"gamma_0": 0.37, "beta_0": math.pi / 5})
    qc = qiskit.qasm2.loads(to_qasm2(circ))
    rc = count(circ)
    ops: dict[str, int] = {}
    for name, k in qc.count_ops().items():
        ops[ir_gate_name(name)] = ops.get(ir_gate_name(name), 0) + k
    assert dict(rc.ops) == dict(sorted(ops.items()))
    assert rc.depth == qc.depth()
    assert rc.two_qubit_depth == two_qubit_depth(qc)
    assert rc.qubits == qc.num_qubits
    assert rc.size == qc.size()
    assert rc.cx == qc.count_ops().get("cx", 0)


@pytest.mark.parametrize("section", ["initial_state", "phase_0", "mixer_0"])
def test_section_depth_equals_qiskit_depth_of_that_section_alone(section: str) -> None:
    low = lower(qaoa_circuit(default_scenario(3, 3, 1), 1)).bind({"gamma_0": 0.2, "beta_0": 0.4})
    only = Circuit(low.registers, [s for s in low.sections if s.name == section])
    qc = qiskit.qasm2.loads(to_qasm2(only))
    sec = count(low).sections[section]
    assert sec.depth == qc.depth()
    assert sec.two_qubit_depth == two_qubit_depth(qc)
    assert sec.size == qc.size()
