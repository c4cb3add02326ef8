"""`qcpp compile` end to end: the written OpenQASM loads in Qiskit and simulates to our state."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from qiskit import qasm2, qasm3
from qiskit.quantum_info import Statevector
from typer.testing import CliRunner

from qcpp.cli.app import app
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.scenario_io import load_scenario
from qcpp.simulate.statevector import simulate_statevector

EXAMPLE = Path(__file__).parents[2] / "examples" / "paper_3x3.toml"
ANGLES = {"gamma_0": 0.3, "beta_0": 0.7}


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(app, list(args))
    return result.exit_code, result.stdout, result.stderr


def our_state() -> np.ndarray:
    return simulate_statevector(qaoa_circuit(load_scenario(EXAMPLE), 1).bind(ANGLES))


def test_default_qasm3_loads_in_qiskit_and_gives_our_state(tmp_path: Path) -> None:
    out = tmp_path / "out.qasm"
    code, _, err = run("compile", str(EXAMPLE), "--qasm", str(out))
    assert code == 0, err
    qc = qasm3.loads(out.read_text())
    bound = qc.assign_parameters({p: ANGLES[p.name] for p in qc.parameters})
    theirs = Statevector(bound).data
    ours = our_state()
    assert theirs.shape == ours.shape
    assert np.allclose(theirs, ours, atol=1e-9)


@pytest.mark.heavy  # Qiskit's dense statevector of the lowered circuit (with work qubits): ~30-50 s
def test_lowered_bound_qasm2_matches_our_state_and_counts(tmp_path: Path) -> None:
    out = tmp_path / "out2.qasm"
    code, stdout, err = run(
        "compile", str(EXAMPLE), "-p", "1", "--lowered", "--bind", "gamma_0=0.3", "beta_0=0.7",
        "--qasm", str(out), "--qasm-version", "2", "--json",
    )
    assert code == 0, err
    summary = json.loads(stdout)
    qc = qasm2.loads(out.read_text())
    assert qc.num_qubits == summary["qubits"]
    assert dict(qc.count_ops()) == summary["gates"]
    theirs = Statevector(qc).data
    ours = our_state()
    n_high = qaoa_circuit(load_scenario(EXAMPLE), 1).num_qubits
    assert qc.num_qubits >= n_high  # lowering may add clean work qubits above the high-level ones
    assert np.allclose(theirs[: len(ours)], ours, atol=1e-9)
    assert np.linalg.norm(theirs[len(ours) :]) < 1e-9
    data = summary["qubit_map"]["data"]
    assert [d["qubit"] for d in data] == list(range(12))
    assert summary["qubit_map"]["ancillas"] == list(range(12, summary["qubits"]))


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--qasm-version", "2", "--qasm", "{tmp}/x.qasm"], "gamma_0, beta_0; give them with --bind NAME=VALUE"),
        (["--qasm-version", "2", "--qasm", "{tmp}/x.qasm", "--device", "grid"], "give them with --bind NAME=VALUE"),
        (["--bind", "delta_0=1"], "--bind: unknown symbol"),
        (["--bind", "gamma_0"], "NAME=VALUE"),
        (["--rule", "fast"], "--rule"),
    ],
)
def test_errors_are_one_line_and_exit_2(tmp_path: Path, args: list[str], needle: str) -> None:
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    code, _, err = run("compile", str(EXAMPLE), *args)
    assert code == 2
    assert needle in err
    assert len(err.strip().splitlines()) == 1
    assert not (tmp_path / "x.qasm").exists()


@pytest.mark.parametrize(
    "args", [("--qasm-version", "2"), ("--qasm-version", "3"), ("--qasm-profile", "portable"), ("--measure",)]
)
def test_qasm_flags_without_qasm_are_refused(args: tuple[str, ...]) -> None:
    """Like the other "applies with" flags: an OpenQASM flag with no file to shape is refused, not ignored."""
    code, out, err = run("compile", str(EXAMPLE), *args)
    assert code == 2 and out == ""
    assert err.strip() == f"error: {args[0]}: applies with --qasm only (no --qasm given)"
