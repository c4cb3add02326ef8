"""OpenQASM 3 export profiles (:mod:`qcpp.lowering.qasm_profiles`) against the clients that install beside qcpp.

The same unitary in every profile: each profile's text, given the meaning of its gate names (Qiskit's stdgates for
``portable``; Braket's names defined from them for ``braket``), simulates in Qiskit to qcpp's own state. Which client
loads which profile unchanged: pyqasm and the reference parser every profile (pyqasm bound only), Cirq and the QDK
the default one only (they need ``include "stdgates.inc"``, which Braket and PennyLane reject; those two run in
``benchmarks/qasm_clients.py``, in their own environments).
"""

from __future__ import annotations

import warnings
from functools import cache

import numpy as np
import pytest

from qcpp.api.compiling import Compiled
from qcpp.api.compiling import compile as qcpp_compile
from qcpp.api.scenarios import grid_scenario
from qcpp.errors import OptionError
from qcpp.ir import gates as g
from qcpp.ir.circuit import Circuit, Section
from qcpp.lowering.qasm import to_qasm3
from qcpp.lowering.qasm_profiles import (
    PROFILES,
    QasmProfileError,
    iter_qasm_profile,
    iter_qasm_profile_body,
    to_qasm3_profile,
)
from qcpp.simulate.statevector import simulate_statevector

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
OTHER = tuple(p for p in PROFILES if p != "default")
# the meaning of Braket's names in stdgates terms (Braket's documentation): lets Qiskit read a braket-profile file
BRAKET_NAMES = (
    "gate cnot a, b { cx a, b; }\ngate ccnot a, b, c { ccx a, b, c; }\ngate si a { sdg a; }\ngate ti a { tdg a; }\n"
)
SMALL = ((2, 4, 1), (2, 2, 2))  # 11 and 8 qubits: the default test run
SCENARIOS = ((3, 3, 1), (2, 3, 2))  # 15 and 16 qubits, heavy (3x3 with two robots has 27: 2 GiB per state)


@cache
def compiled(rows: int, cols: int, robots: int, lowered: bool, bound: bool) -> Compiled:
    return qcpp_compile(grid_scenario(rows, cols, robots=robots), lowered=lowered, bind=BIND if bound else None)


@cache
def reference(rows: int, cols: int, robots: int, lowered: bool) -> np.ndarray:
    return simulate_statevector(compiled(rows, cols, robots, lowered, True).circuit)


def fidelity(a: np.ndarray, b: np.ndarray) -> float:
    return float(abs(np.vdot(a, b)) ** 2 / (np.vdot(a, a).real * np.vdot(b, b).real))


def with_meaning(text: str, profile: str) -> str:
    """The text with the include (and Braket's names) it leaves out, so that Qiskit can read it."""
    head, rest = text.split("\n", 1)
    assert head == "OPENQASM 3.0;"
    prelude = 'include "stdgates.inc";\n' + (BRAKET_NAMES if profile == "braket" else "")
    return f"{head}\n{prelude}{rest}"


def qiskit_state(text: str) -> np.ndarray:
    import qiskit.qasm3
    from qiskit.quantum_info import Statevector

    return np.asarray(Statevector(qiskit.qasm3.loads(text)).data)


def big_endian_to_qcpp(state: np.ndarray, n: int) -> np.ndarray:
    return np.asarray(state).reshape([2] * n).transpose(list(range(n))[::-1]).reshape(-1)


# --- the text of each profile ------------------------------------------------------------------------------------
def test_default_profile_is_the_faithful_text() -> None:
    c = compiled(2, 4, 1, False, False)
    assert c.to_qasm(profile="default") == c.to_qasm() == to_qasm3(c.circuit)
    assert to_qasm3_profile(c.circuit, "default") == to_qasm3(c.circuit)


@pytest.mark.parametrize("profile", OTHER)
def test_other_profiles_leave_out_the_include_definitions_and_modifiers(profile: str) -> None:
    text = compiled(2, 4, 1, False, False).to_qasm(profile=profile)
    assert "include" not in text and "\ngate " not in text and "@" not in text
    assert text.startswith("OPENQASM 3.0;\ninput float[64] gamma_0;\ninput float[64] beta_0;\nqubit[11] q;\n")
    words = {line.split()[0].split("(")[0] for line in text.splitlines()[4:] if line and not line.startswith("//")}
    allowed = {"portable": {"x", "z", "h", "s", "t", "rx", "ry", "rz", "cz"}}.get(
        profile, {"x", "h", "s", "t", "si", "ti", "rx", "ry", "rz", "cz", "cnot", "ccnot"}
    )
    assert words <= allowed, words - allowed


@pytest.mark.parametrize("profile", PROFILES)
def test_the_body_of_sections_handed_out_one_at_a_time_is_the_text_after_the_header(profile: str) -> None:
    c = compiled(2, 4, 1, True, False)
    chunks = list(iter_qasm_profile(c.circuit, 3, profile))
    body = iter_qasm_profile_body(iter(c.circuit.sections), c.circuit.num_qubits, 3, profile)
    assert len(c.circuit.sections) > 1
    assert "".join(body) == "".join(chunks[1:])


def every_gate() -> Circuit:
    """Every IR gate kind (an AND onto a clean target, its uncompute with the target holding the AND)."""
    gates: list[g.Gate] = [
        g.h(0), g.x(1), g.ry(0.4, 2), g.rx(-0.3, 3), g.rz(0.2, 4), g.s(0), g.sdg(1), g.t(2), g.tdg(3), g.cx(0, 1),
        g.cz(1, 2), g.crz(0.5, 2, 3), g.cry(0.6, 3, 4), g.crx(0.7, 4, 0), g.ccx(0, 1, 2), g.rzz(0.8, 1, 3),
        g.sbf(0.9, 0, 1, 2, 3), g.csbf(1.1, 4, 0, 1, 2, 3), g.mcx([0], 4, "0"), g.mcx([1, 2], 0, "01"), g.h(4),
        g.and_(0, 1, 5, "10"), g.rz(0.3, 5), g.and_dg(0, 1, 5, "10"), g.ry(1.3, 5),
    ]  # fmt: skip
    return Circuit([("data", 6)], [Section("all", gates)])


@pytest.mark.parametrize("profile", PROFILES)
def test_every_gate_kind_simulates_to_qcpps_state(profile: str) -> None:
    circuit = every_gate()
    text = with_meaning(to_qasm3_profile(circuit, profile), profile) if profile != "default" else to_qasm3(circuit)
    assert fidelity(simulate_statevector(circuit), qiskit_state(text)) == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("profile", OTHER)
@pytest.mark.parametrize("lowered", [False, True])
@pytest.mark.parametrize(
    "shape",
    [*SMALL, *(pytest.param(s, marks=pytest.mark.heavy) for s in SCENARIOS)],
    ids=lambda s: f"{s[0]}x{s[1]}_{s[2]}",
)
def test_scenario_profiles_simulate_to_qcpps_state(shape: tuple[int, int, int], lowered: bool, profile: str) -> None:
    text = compiled(*shape, lowered, True).to_qasm(profile=profile)
    assert fidelity(reference(*shape, lowered), qiskit_state(with_meaning(text, profile))) == pytest.approx(
        1.0, abs=1e-9
    )


def test_the_state_check_can_fail() -> None:
    text = compiled(2, 4, 1, True, True).to_qasm(profile="portable")
    lines = text.splitlines()
    i = next(k for k in range(len(lines) - 1) if lines[k].startswith("z ") and lines[k + 1].startswith("s "))
    wrong = "\n".join(lines[:i] + lines[i + 1 :]) + "\n"  # one sdg written as s
    assert fidelity(reference(2, 4, 1, True), qiskit_state(with_meaning(wrong, "portable"))) < 0.999


def test_a_mcx_with_three_controls_has_no_profile_form() -> None:
    c = Circuit([("data", 4)], [Section("s", [g.mcx([0, 1, 2], 3, "101")])])
    for profile in OTHER:
        with pytest.raises(QasmProfileError, match=r"multi-controlled X with 3 controls.*--lowered"):
            to_qasm3_profile(c, profile)
    assert "ctrl" in to_qasm3_profile(c, "default")


# --- the clients beside qcpp -------------------------------------------------------------------------------------
@pytest.mark.parametrize("profile", PROFILES)
def test_pyqasm_validates_and_unrolls_every_bound_profile(profile: str) -> None:
    import pyqasm

    for lowered in (False, True):
        module = pyqasm.loads(compiled(2, 4, 1, lowered, True).to_qasm(profile=profile))
        module.validate()
        module.unroll()


@pytest.mark.parametrize("profile", PROFILES)
def test_pyqasm_refuses_inputs_as_gate_arguments(profile: str) -> None:
    """Why the docs say pyqasm needs bound files: it rejects every profile's unbound ``input``."""
    import pyqasm

    module = pyqasm.loads(compiled(2, 4, 1, False, False).to_qasm(profile=profile))
    with pytest.raises(Exception, match="Invalid parameter"):
        module.validate()


@pytest.mark.parametrize("profile", PROFILES)
@pytest.mark.parametrize("bound", [True, False])
def test_the_reference_parser_parses_every_profile(profile: str, bound: bool) -> None:
    import openqasm3

    program = openqasm3.parse(compiled(2, 4, 1, False, bound).to_qasm(profile=profile))
    assert len(program.statements) > 50


def cirq_state(text: str, n: int, resolver: dict[str, float] | None = None) -> np.ndarray:
    import cirq
    from cirq.contrib.qasm_import import circuit_from_qasm

    order = [cirq.NamedQubit(f"q_{i}") for i in range(n)]
    result = cirq.Simulator(dtype=np.complex128).simulate(
        circuit_from_qasm(text), param_resolver=cirq.ParamResolver(resolver or {}), qubit_order=order
    )
    return big_endian_to_qcpp(result.final_state_vector, n)


@pytest.mark.parametrize("lowered", [False, True])
@pytest.mark.parametrize("shape", [SMALL[0], pytest.param(SCENARIOS[0], marks=pytest.mark.heavy)], ids=str)
def test_cirq_simulates_the_default_profile_to_qcpps_state(shape: tuple[int, int, int], lowered: bool) -> None:
    ref, n = reference(*shape, lowered), compiled(*shape, lowered, True).qubits
    assert fidelity(ref, cirq_state(compiled(*shape, lowered, True).to_qasm(), n)) == pytest.approx(1.0, abs=1e-9)
    unbound = compiled(*shape, lowered, False).to_qasm()  # inputs become sympy symbols
    assert fidelity(ref, cirq_state(unbound, n, BIND)) == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("profile", OTHER)
def test_cirq_and_the_qdk_need_the_include_the_other_profiles_leave_out(profile: str) -> None:
    from cirq.contrib.qasm_import import QasmException
    from qdk.openqasm import QasmError, import_openqasm

    text = compiled(2, 4, 1, True, True).to_qasm(profile=profile)
    with pytest.raises(QasmException, match="Unknown gate"):
        cirq_state(text, 11)
    with pytest.raises((QasmError, Exception), match="StdGateCalledButNotIncluded"):
        import_openqasm(text, name="program")


def test_no_entangling_gate_without_the_include_loads_in_both_cirq_and_the_qdk() -> None:
    """Why no profile without the include can serve Cirq and the QDK (and PennyLane refuses the include): without it,
    Cirq knows OpenQASM 2's built-in ``CX`` but not ``ctrl @``, the QDK ``ctrl @ U`` but not ``CX`` nor a standard
    gate. ``benchmarks/qasm_clients.py --constructs`` shows the whole table, the clients in their own environments
    included."""
    from cirq.contrib.qasm_import import QasmException
    from qdk.openqasm import import_openqasm

    bell = np.array([1, 0, 0, 1]) / np.sqrt(2)
    builtin_cx = "OPENQASM 3.0;\nqubit[2] q;\nU(pi/2, 0, pi) q[0];\nCX q[0], q[1];\n"
    controlled_u = "OPENQASM 3.0;\nqubit[2] q;\nU(pi/2, 0, pi) q[0];\nctrl @ U(pi, 0, pi) q[0], q[1];\n"
    assert fidelity(bell, cirq_state(builtin_cx, 2)) == pytest.approx(1.0, abs=1e-9)
    with pytest.raises(QasmException, match="@"):
        cirq_state(controlled_u, 2)
    for text in (builtin_cx, builtin_cx.replace("CX", "cx"), builtin_cx.replace("CX", "cz")):
        with pytest.raises(Exception, match="StdGateCalledButNotIncluded"):
            import_openqasm(text, name="program")
    import_openqasm(controlled_u, name="program")


def qdk_state(text: str, n: int) -> np.ndarray:
    from qdk import qsharp
    from qdk.openqasm import ProgramType, import_openqasm

    qsharp.init()
    import_openqasm(text, program_type=ProgramType.Fragments)
    return big_endian_to_qcpp(np.asarray(qsharp.dump_machine().as_dense_state()), n)


@pytest.mark.parametrize("lowered", [False, True])
@pytest.mark.parametrize("shape", [SMALL[0], pytest.param(SCENARIOS[0], marks=pytest.mark.heavy)], ids=str)
def test_the_qdk_simulates_the_default_profile_to_qcpps_state(shape: tuple[int, int, int], lowered: bool) -> None:
    from qdk import qsharp
    from qdk.openqasm import import_openqasm

    c = compiled(*shape, lowered, True)
    assert fidelity(reference(*shape, lowered), qdk_state(c.to_qasm(), c.qubits)) == pytest.approx(1.0, abs=1e-9)
    qsharp.init()
    import_openqasm(compiled(*shape, lowered, False).to_qasm(), name="program")  # unbound: inputs as parameters


@pytest.mark.heavy
@pytest.mark.parametrize("lowered", [False, True])
def test_cirq_and_the_qdk_on_two_robots(lowered: bool) -> None:
    ref = reference(2, 3, 2, lowered)
    text = compiled(2, 3, 2, lowered, True).to_qasm()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert fidelity(ref, cirq_state(text, 16)) == pytest.approx(1.0, abs=1e-9)
        assert fidelity(ref, qdk_state(text, 16)) == pytest.approx(1.0, abs=1e-9)


# --- bad input ----------------------------------------------------------------------------------------------------
def test_api_refuses_an_unknown_profile_and_a_profile_with_version_2() -> None:
    c = compiled(2, 4, 1, True, True)
    with pytest.raises(OptionError, match=r"^profile: expected default or portable or braket, got 'pennylane'$"):
        c.to_qasm(profile="pennylane")
    with pytest.raises(OptionError, match=r"^profile: 'portable' is an OpenQASM 3 profile; with version 2 use"):
        c.to_qasm(version=2, profile="portable")
    assert c.to_qasm(version=2, profile="default") == c.to_qasm(version=2)


def test_write_qasm_writes_the_profile_text(tmp_path: object) -> None:
    from pathlib import Path

    c = compiled(2, 4, 1, False, False)
    path = Path(str(tmp_path)) / "c.qasm"
    c.write_qasm(path, profile="braket")
    assert path.read_text() == c.to_qasm(profile="braket")
    with pytest.raises(OptionError):
        c.write_qasm(Path(str(tmp_path)) / "d.qasm", version=2, profile="braket")
    assert not (Path(str(tmp_path)) / "d.qasm").exists()


def test_clients_load_the_unbound_circuit_without_the_first_phase_separator() -> None:
    """Without the first phase separator ``gamma_0`` names no gate, so the unbound text declares no input for it:
    Qiskit, Cirq and the QDK load it as they load the default's, and with the angles bound it gives qcpp's state
    (a ``gamma_0`` among the values binds nothing)."""
    import qiskit.qasm3
    from qdk import qsharp
    from qdk.openqasm import import_openqasm
    from qiskit.quantum_info import Statevector

    s, bind = grid_scenario(2, 4, robots=1), {**BIND, "gamma_1": 0.5, "beta_1": 0.4}
    c = qcpp_compile(s, 2, lowered=True, first_phase=False)
    text = c.to_qasm()
    assert "gamma_0" not in text and "input float[64] gamma_1;" in text
    ref = simulate_statevector(qcpp_compile(s, 2, lowered=True, bind=bind, first_phase=False).circuit)
    assert fidelity(ref, cirq_state(text, c.qubits, bind)) == pytest.approx(1.0, abs=1e-9)
    loaded = qiskit.qasm3.loads(text)
    bound = loaded.assign_parameters({q: bind[q.name] for q in loaded.parameters})
    assert fidelity(ref, np.asarray(Statevector(bound).data)) == pytest.approx(1.0, abs=1e-9)
    qsharp.init()
    import_openqasm(text, name="program")  # unbound: inputs as parameters
