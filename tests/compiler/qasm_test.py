"""Tests for qcpp.lowering.qasm: Qiskit and pytket cross-checks, naming, parameters, atomic writes."""

from __future__ import annotations

import os
import re
from collections import Counter

import numpy as np
import pytest
import qiskit.qasm2 as qasm2
import qiskit.qasm3 as qasm3
from hypothesis import given, settings
from qiskit import QuantumCircuit, transpile
from qiskit.quantum_info import Operator, Statevector

from qcpp.ir import gates as G
from qcpp.ir.angles import Angle, UnboundParameterError
from qcpp.ir.circuit import Circuit, CircuitBuilder, Section
from qcpp.ir.gates import Gate, unitary
from qcpp.lowering.passes import lower
from qcpp.lowering.qasm import (
    CUSTOM_PREFIX,
    QASM_FORMS,
    ir_gate_name,
    iter_qasm,
    qasm_gate_name,
    to_qasm2,
    to_qasm3,
    write_qasm,
)
from qcpp.simulate.statevector import simulate_statevector
from qcpp.testing import circuits

VALUES = {"gamma_0": 0.37, "beta_0": -1.3, "gamma_1": 2.1}

# qelib1.inc as Qiskit reads it by default, plus everything its legacy mode adds
QISKIT_QELIB1 = {
    "u3", "u2", "u1", "cx", "id", "x", "y", "z", "h", "s", "sdg", "t", "tdg", "rx", "ry", "rz",
    "cz", "cy", "ch", "ccx", "crz", "cu1", "cu3", "U", "CX",
}  # fmt: skip
QISKIT_LEGACY = {ci.name for ci in qasm2.LEGACY_CUSTOM_INSTRUCTIONS}


def qiskit_counts(qc: QuantumCircuit) -> dict[str, int]:
    out: Counter[str] = Counter()
    for name, count in qc.count_ops().items():
        out[ir_gate_name(name)] += count
    return dict(out)


def all_gates_circuit() -> Circuit:
    b = CircuitBuilder([("data", 7)])
    b.append([G.h(q) for q in range(7)], section="initial_state")
    b.append(
        [
            G.x(0), G.t(1), G.tdg(2), G.s(3), G.sdg(4), G.rz(0.3, 5), G.rx(-0.4, 6), G.ry(1.1, 0),
            G.cx(0, 1), G.cz(1, 2), G.crz(0.7, 2, 3), G.cry(-0.8, 3, 4), G.rzz(0.9, 4, 5), G.crx(0.35, 5, 6),
            G.ccx(0, 1, 2), G.sbf(0.5, 0, 2, 4, 6), G.csbf(-0.6, 1, 0, 3, 5, 6),
        ],
        section="phase_0",
    )  # fmt: skip
    b.append(
        [
            G.mcx([0], 1, "0"), G.mcx([2, 3], 4, "10"), G.mcx([0, 1, 2], 3, "011"),
            G.mcx([0, 1, 2, 3, 4], 5), G.mcx([6, 5, 4, 3, 2, 1], 0, "101100"),
        ],
        section="mixer_0",
    )  # fmt: skip
    return b.build()


def check_against_qiskit(c: Circuit) -> None:
    ours = simulate_statevector(c, 0, VALUES)
    bound = c.bind(VALUES)
    expected_counts = bound.count_ops()
    for text, loaded in [
        (to_qasm2(bound), lambda s: qasm2.loads(s)),
        (to_qasm2(bound), lambda s: qasm2.loads(s, custom_instructions=qasm2.LEGACY_CUSTOM_INSTRUCTIONS)),
        (to_qasm2(bound), lambda s: qasm2.loads(s, strict=True)),
        (to_qasm3(bound), qasm3.loads),
    ]:
        qc = loaded(text)
        assert qc.num_qubits == c.num_qubits
        np.testing.assert_allclose(Statevector(qc).data, ours, atol=1e-9)  # exact phase
        assert qiskit_counts(qc) == expected_counts


def test_every_gate_against_qiskit_high_level_and_lowered() -> None:
    c = all_gates_circuit()
    check_against_qiskit(c)
    low = lower(c)
    check_against_qiskit(low)
    # lowered circuits use standard names only: Qiskit's raw count_ops match ours directly
    assert dict(qasm2.loads(to_qasm2(low)).count_ops()) == low.count_ops()
    assert dict(qasm3.loads(to_qasm3(low)).count_ops()) == low.count_ops()


@settings(max_examples=25, deadline=None)
@given(circuits(max_qubits=6, max_gates=8, max_controls=5, symbolic=True))
def test_random_circuits_against_qiskit(c: Circuit) -> None:
    check_against_qiskit(c)
    check_against_qiskit(lower(c))


def flattened(qc: QuantumCircuit) -> QuantumCircuit:
    """Inline the custom definitions (Qiskit's Operator on nested definitions is very slow)."""
    return transpile(qc, basis_gates=["cx", "ccx", "h", "x", "u1", "cu1", "p", "cp"], optimization_level=0)


@pytest.mark.parametrize("k", [3, 4, 5, 6])
def test_mcx_definitions_are_exact(k: int) -> None:
    rng = np.random.default_rng(k)
    for state in ["1" * k, "0" * k, "".join(rng.choice(["0", "1"], k))]:
        gate = G.mcx(list(range(k)), k, state)
        c = Circuit([("data", k + 1)], [Section("s", [gate])])
        for text, load in [(to_qasm2(c), qasm2.loads), (to_qasm3(c), qasm3.loads)]:
            np.testing.assert_allclose(Operator(flattened(load(text))).data, unitary(gate), atol=1e-9)


def test_mcx_definition_with_eight_controls() -> None:
    k, state = 8, "10110010"
    gate = G.mcx(list(range(k)), k, state)
    c = Circuit([("data", k + 1)], [Section("s", [gate])])
    fire = int(state[::-1], 2)
    inputs = [fire, fire | 1 << k, fire ^ 1, fire ^ 0b1000_0000, 0, 2 ** (k + 1) - 1]
    u = unitary(gate)
    for text, load in [(to_qasm2(c), qasm2.loads), (to_qasm3(c), qasm3.loads)]:
        qc = flattened(load(text))
        for i in inputs:
            out = Statevector.from_int(i, 2 ** (k + 1)).evolve(qc).data
            np.testing.assert_allclose(out, u[:, i], atol=1e-9)


def test_custom_names_never_collide_with_qiskit() -> None:
    c = all_gates_circuit()
    for text in [to_qasm2(c), to_qasm3(c)]:
        defined = re.findall(r"^gate (\w+)", text, flags=re.M)
        assert defined, "expected custom definitions"
        for name in defined:
            assert name.startswith(CUSTOM_PREFIX)
            assert name not in QISKIT_QELIB1 | QISKIT_LEGACY
        assert len(defined) == len(set(defined))


def test_only_used_definitions_are_emitted() -> None:
    c = Circuit([("data", 2)], [Section("s", [G.h(0), G.cx(0, 1)])])
    assert "gate " not in to_qasm2(c) and "gate " not in to_qasm3(c)
    assert "qcpp_cry" not in to_qasm3(Circuit([("data", 2)], [Section("s", [G.cry(0.1, 0, 1)])]))
    assert "gate qcpp_cry" in to_qasm2(Circuit([("data", 2)], [Section("s", [G.cry(0.1, 0, 1)])]))


def test_name_mapping() -> None:
    assert qasm_gate_name(G.rzz(0.1, 0, 1), 2) == "qcpp_rzz"
    assert qasm_gate_name(G.rzz(0.1, 0, 1), 3) == "qcpp_rzz"
    assert qasm_gate_name(G.mcx([0, 1, 2, 3], 4, "0110"), 2) == "qcpp_mcx4_0110"
    assert qasm_gate_name(G.mcx([0, 1, 2, 3], 4, "0110"), 3) == "negctrl @ ctrl(2) @ negctrl @ x"
    assert qasm_gate_name(G.mcx([0], 1, "0"), 3) == "negctrl @ x"
    assert qasm_gate_name(G.ccx(0, 1, 2), 2) == "ccx"
    for name in ["rzz", "cry", "crx", "sbf", "csbf", "mcx"]:
        assert ir_gate_name(f"{CUSTOM_PREFIX}{name}" if name != "mcx" else "qcpp_mcx3_111") == name
    assert qasm_gate_name(G.and_(0, 1, 2, "01"), 3) == "qcpp_and_01"
    assert qasm_gate_name(G.and_dg(0, 1, 2), 2) == "qcpp_and_dg_11"
    assert qasm_gate_name(G.crx(0.1, 0, 1), 3) == "crx" and qasm_gate_name(G.crx(0.1, 0, 1), 2) == "qcpp_crx"
    for state in ["00", "01", "10", "11"]:
        assert ir_gate_name(f"qcpp_and_{state}") == "and" and ir_gate_name(f"qcpp_and_dg_{state}") == "and_dg"


def test_layout_and_sections_in_text() -> None:
    c = all_gates_circuit()
    text = to_qasm3(c)
    assert "qubit[7] q;" in text
    assert re.findall(r"^// section (\w+)", text, flags=re.M) == ["initial_state", "phase_0", "mixer_0"]
    assert "qreg q[7];" in to_qasm2(c)
    # one statement per IR gate
    body = [ln for ln in to_qasm2(c).splitlines() if ln.endswith("];") and not ln.startswith("qreg")]
    assert len(body) == len(c)


def test_float_parameters_round_trip_exactly() -> None:
    thetas = [0.1, 1e-5, -2.5e-300, 1 / 3, 12345.678901234567, -0.0, 3e20]
    c = Circuit([("data", 1)], [Section("s", [G.rz(th, 0) for th in thetas])])
    for qc in [qasm2.loads(to_qasm2(c)), qasm3.loads(to_qasm3(c))]:
        assert [float(inst.operation.params[0]) for inst in qc.data] == thetas


def test_qasm2_unbound_symbols_raise() -> None:
    c = Circuit(
        [("data", 2)],
        [Section("s", [G.rzz(Angle.symbol("gamma_1"), 0, 1), G.rx(Angle.symbol("beta_0") + 1, 0)])],
    )
    with pytest.raises(UnboundParameterError) as err:
        to_qasm2(c)
    assert isinstance(err.value, ValueError)
    assert err.value.symbols == ("beta_0", "gamma_1")
    assert "beta_0" in str(err.value) and "gamma_1" in str(err.value)
    to_qasm2(c.bind({"gamma_1": 1.0, "beta_0": 2.0}))  # fine once bound


def test_qasm3_inputs_become_qiskit_parameters() -> None:
    g0, b0 = Angle.symbol("gamma_0"), Angle.symbol("beta_0")
    b = CircuitBuilder([("data", 3)])
    b.append([G.h(q) for q in range(3)], section="initial_state")
    b.append([G.rzz(2.5 * g0 + 0.1, 0, 1), G.rz(-g0, 2), G.crz(g0 - 0.5, 1, 2)], section="phase_0")
    b.append([G.rx(2 * b0, q) for q in range(3)] + [G.csbf(b0, 0, 1, 2, 3, 4)], section="mixer_0")
    b.add_register(("logic", 2))
    c = b.build()
    text = to_qasm3(c)
    assert "input float[64] gamma_0;" in text and "input float[64] beta_0;" in text
    assert text.index("gamma_0;") < text.index("beta_0;")
    assert "qcpp_rzz(2.5*gamma_0 + 0.1)" in text
    qc = qasm3.loads(text)
    assert sorted(p.name for p in qc.parameters) == ["beta_0", "gamma_0"]
    values = {"gamma_0": 0.4, "beta_0": -0.9}
    bound = qc.assign_parameters({p: values[p.name] for p in qc.parameters})
    np.testing.assert_allclose(Statevector(bound).data, simulate_statevector(c, 0, values), atol=1e-9)


def test_bad_symbol_names_are_rejected_for_qasm3() -> None:
    for bad in ["q", "pi", "input", "rz", "qcpp_x"]:
        c = Circuit([("data", 1)], [Section("s", [G.rz(Angle.symbol(bad), 0)])])
        with pytest.raises(ValueError):
            to_qasm3(c)


def test_iter_qasm_streams_and_validates_version() -> None:
    c = all_gates_circuit()
    chunks = list(iter_qasm(c, 3))
    assert len(chunks) > 1 and "".join(chunks) == to_qasm3(c)
    with pytest.raises(ValueError):
        iter_qasm(c, 4)  # type: ignore[arg-type]


def test_write_qasm_writes_whole_file(tmp_path) -> None:  # type: ignore[no-untyped-def]
    c = all_gates_circuit()
    path = tmp_path / "out.qasm"
    write_qasm(c, path, version=2)
    assert path.read_text() == to_qasm2(c)
    write_qasm(c, str(path), version=3)
    assert path.read_text() == to_qasm3(c)
    assert os.listdir(tmp_path) == ["out.qasm"]
    assert (path.stat().st_mode & 0o777) == 0o644


def failing_circuit() -> Circuit:
    """A circuit whose last section cannot be formatted (a NaN angle): fails mid-write."""
    big = [G.h(q % 5) for q in range(100_000)]
    return Circuit([("data", 5)], [Section("ok", big), Section("bad", [Gate("rz", (0,), (float("nan"),))])])


def test_write_qasm_failure_leaves_destination_untouched(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "out.qasm"
    path.write_text("previous content\n")
    with pytest.raises(ValueError, match="non-finite"):
        write_qasm(failing_circuit(), path, version=3)
    assert path.read_text() == "previous content\n"
    assert os.listdir(tmp_path) == ["out.qasm"]  # no temp file left behind


def test_write_qasm_failure_leaves_no_file(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "new.qasm"
    with pytest.raises(ValueError):
        write_qasm(failing_circuit(), path, version=2)
    assert os.listdir(tmp_path) == []
    unbound = Circuit([("data", 1)], [Section("s", [G.rz(Angle.symbol("gamma_0"), 0)])])
    with pytest.raises(UnboundParameterError):
        write_qasm(unbound, path, version=2)
    assert os.listdir(tmp_path) == []


# --- OpenQASM 3 modifiers, forms of every gate ----------------------------------------------------------------
def test_every_ir_gate_has_an_openqasm_form() -> None:
    """A new IR gate must get a form in QASM_FORMS (this fails until it does)."""
    missing = set(G.GATE_SPECS) - set(QASM_FORMS)
    assert not missing, f"gates without an OpenQASM form: {sorted(missing)}"


@pytest.mark.parametrize("version", [2, 3])
def test_unknown_gate_name_fails_loudly(version: int) -> None:
    c = Circuit([("data", 2)], [Section("s", [G.h(0), Gate("future_gate", (0, 1), (0.5,))])])
    with pytest.raises(ValueError, match="future_gate"):
        "".join(iter_qasm(c, version))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="future_gate"):
        qasm_gate_name(Gate("future_gate", (0, 1)), version)  # type: ignore[arg-type]


def test_qasm3_mcx_loads_as_one_qiskit_mcx_gate() -> None:
    from qiskit.circuit.library import CCXGate, CXGate, MCXGate

    gates = [G.mcx([0], 1, "0"), G.mcx([2, 3], 4, "10"), G.mcx([0, 1, 2], 3, "011"), G.mcx([0, 1, 2, 3, 4], 5)]
    gates.append(G.mcx([6, 5, 4, 3, 2, 1], 0, "101100"))
    text = to_qasm3(Circuit([("data", 7)], [Section("s", gates)]))
    assert "gate " not in text  # no definitions: the statements are standard OpenQASM 3
    assert "ctrl @ negctrl @ ctrl(2) @ negctrl(2) @ x q[6],q[5],q[4],q[3],q[2],q[1],q[0];" in text
    qc = qasm3.loads(text)
    assert len(qc.data) == len(gates)
    for inst, gate, cls in zip(qc.data, gates, [CXGate, CCXGate, MCXGate, MCXGate, MCXGate], strict=True):
        op = inst.operation
        assert isinstance(op, cls)
        assert [qc.find_bit(q).index for q in inst.qubits] == list(gate.qubits)
        # Qiskit's ctrl_state is an int whose bit i is control i; ours reads control 0 first
        assert op.ctrl_state == int((gate.ctrl_state or "1" * (len(gate.qubits) - 1))[::-1], 2)
        np.testing.assert_allclose(Operator(op).data, unitary(gate), atol=1e-12)
        assert ir_gate_name(op.name) == gate.name


def scenario_circuits(rows: int, cols: int, robots: int) -> tuple[Circuit, Circuit]:
    from qcpp.plan.compile import compile_scenario
    from qcpp.problem.presets import default_scenario

    s = default_scenario(rows, cols, robots)
    values = {"gamma_0": 0.37, "beta_0": -1.3}
    high = compile_scenario(s, 1, bindings=values).circuit
    low = compile_scenario(s, 1, lowered=True, bindings=values).circuit
    return high, low


QISKIT_BASIS = ["cx", "rz", "sx", "x"]


def qiskit_o3_cx(high: Circuit) -> tuple[QuantumCircuit, int]:
    out = transpile(qasm3.loads(to_qasm3(high)), basis_gates=QISKIT_BASIS, optimization_level=3, seed_transpiler=1)
    return out, out.count_ops().get("cx", 0)


def assert_qiskit_o3_within_one_percent(rows: int, cols: int, robots: int) -> None:
    high, low = scenario_circuits(rows, cols, robots)
    _, theirs = qiskit_o3_cx(high)
    ours = low.count_ops()["cx"]
    # a Qiskit user who loads our OpenQASM 3 pays at most 1% more CNOTs than our own lowering
    assert theirs <= 1.01 * ours, (theirs, ours)


def test_qiskit_o3_on_our_qasm3_is_within_one_percent_of_our_cx_3x3() -> None:
    assert_qiskit_o3_within_one_percent(3, 3, 1)


@pytest.mark.heavy
def test_qiskit_o3_on_our_qasm3_is_within_one_percent_of_our_cx_5x5() -> None:
    assert_qiskit_o3_within_one_percent(5, 5, 2)


def test_qiskit_o3_transpile_of_our_qasm3_prepares_our_state() -> None:
    """Qiskit's MCX syntheses may borrow untouched qubits as clean ancillas: right from |0...0> (our case)."""
    high, _ = scenario_circuits(2, 3, 1)
    out, _ = qiskit_o3_cx(high)
    theirs = Statevector(out)
    if out.layout is not None and out.layout.final_layout is not None:  # a permutation elided at the end
        perm = out.layout.final_index_layout()
        theirs = theirs.evolve(QuantumCircuit(len(perm)).compose(_inverse_permutation(perm)))
    ours = simulate_statevector(high)
    assert abs(np.vdot(theirs.data, ours)) == pytest.approx(1.0, abs=1e-9)  # equal up to a global phase


def _inverse_permutation(perm: list[int]) -> QuantumCircuit:
    from qiskit.circuit.library import PermutationGate

    qc = QuantumCircuit(len(perm))
    inv = [0] * len(perm)
    for i, j in enumerate(perm):
        inv[j] = i
    qc.append(PermutationGate(inv), range(len(perm)))
    return qc


# --- pytket reads the lowered OpenQASM 2 ---------------------------------------------------------------------
PYTKET_NAMES = {"CX": "cx", "H": "h", "X": "x", "Rz": "rz", "T": "t", "Tdg": "tdg", "S": "s", "Sdg": "sdg"}


def pytket_gates(text: str) -> tuple[int, list[Gate]]:
    """pytket's reading of an OpenQASM 2 text, translated back into IR gates (angles: half-turns * pi)."""
    from pytket.qasm import circuit_from_qasm_str

    tk = circuit_from_qasm_str(text)
    index = {q: i for i, q in enumerate(tk.qubits)}
    out = []
    for cmd in tk.get_commands():
        name = PYTKET_NAMES[cmd.op.type.name]
        params = tuple(float(p) * np.pi for p in cmd.op.params)
        out.append(Gate(name, tuple(index[q] for q in cmd.qubits), params))
    return tk.n_qubits, out


def test_pytket_reads_lowered_qasm2_with_same_counts_and_state() -> None:
    from pytket.qasm import circuit_from_qasm_str

    low = lower(all_gates_circuit())
    assert low.num_qubits <= 11  # pytket's own simulator stops at 11 qubits
    tk = circuit_from_qasm_str(to_qasm2(low))
    counts = Counter(PYTKET_NAMES[cmd.op.type.name] for cmd in tk.get_commands())
    assert dict(counts) == low.count_ops()
    n = low.num_qubits
    # pytket orders amplitudes with qubit 0 most significant; ours with qubit 0 least significant
    order = [int(f"{i:0{n}b}"[::-1], 2) for i in range(2**n)]
    np.testing.assert_allclose(tk.get_statevector()[order], simulate_statevector(low), atol=1e-9)  # exact phase


def test_pytket_reads_a_lowered_qaoa_circuit_gate_for_gate() -> None:
    _, low = scenario_circuits(2, 3, 1)
    n, gates = pytket_gates(to_qasm2(low))
    assert n == low.num_qubits
    assert dict(Counter(g.name for g in gates)) == low.count_ops()
    back = Circuit([("q", n)], [Section("s", gates)])
    np.testing.assert_allclose(simulate_statevector(back), simulate_statevector(low), atol=1e-9)


# --- and / and_dg: exact on a clean target (their contract) --------------------------------------------------
@pytest.mark.parametrize("state", ["00", "01", "10", "11"])
def test_and_definitions_are_exact_on_their_contract(state: str) -> None:
    """``and`` equals the IR permutation on inputs with a clean target; ``and_dg`` returns the AND to |0>."""
    fire = int(state[::-1], 2)  # controls q0, q1 matching the state (q0 the low bit)
    for gate in [G.and_(0, 1, 2, state), G.and_dg(0, 1, 2, state)]:
        c = Circuit([("data", 3)], [Section("s", [gate])])
        u = unitary(gate)
        for text, load in [(to_qasm2(c), qasm2.loads), (to_qasm3(c), qasm3.loads)]:
            got = Operator(load(text)).data
            for controls in range(4):
                target = int(controls == fire) if gate.name == "and_dg" else 0
                col = controls | target << 2
                np.testing.assert_allclose(got[:, col], u[:, col], atol=1e-12)  # exact, phase included


def test_and_compute_uncompute_against_qiskit() -> None:
    b = CircuitBuilder([("data", 4)])
    b.add_register(("logic", 2))
    b.append([G.h(0), G.ry(0.7, 1), G.h(2), G.ry(-1.1, 3)], section="initial_state")
    compute = [G.and_(0, 1, 4, "10"), G.and_(4, 2, 5, "01")]
    body = [G.crx(0.8, 5, 3), G.crz(-0.4, 4, 2), G.rzz(0.3, 5, 0)]
    uncompute = [G.and_dg(4, 2, 5, "01"), G.and_dg(0, 1, 4, "10")]
    b.append([*compute, *body, *uncompute], section="mixer_0")
    c = b.build()
    check_against_qiskit(c)
    check_against_qiskit(lower(c))
