"""``qcpp compile --measure``: the data qubits measured in the written OpenQASM, as ``Compiled.to_qasm(measure=True)``
writes them (streamed or routed), and refused without ``--qasm``."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

import qcpp
from qcpp.cli.app import app

BIND = ["--bind", "gamma_0=0.3", "beta_0=0.7"]


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(app, list(args))
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize(("version", "profile"), [("3", "default"), ("3", "braket"), ("2", "default")])
def test_streamed_measure_equals_the_api(tmp_path: Path, version: str, profile: str) -> None:
    out = tmp_path / "c.qasm"
    code, stdout, _ = run("compile", "--grid", "2x3", "--robots", "2", "--lowered", *BIND, "--qasm", str(out),
                          "--qasm-version", version, "--qasm-profile", profile, "--measure", "--json")  # fmt: skip
    assert code == 0 and json.loads(stdout)["qasm"]["measured"] == "meas"
    c = qcpp.compile(qcpp.grid_scenario(2, 3, robots=2), lowered=True, bind={"gamma_0": 0.3, "beta_0": 0.7})
    assert out.read_text() == c.to_qasm(int(version), profile, measure=True)


def test_routed_measure_reads_the_final_layout(tmp_path: Path) -> None:
    out = tmp_path / "c.qasm"
    code, stdout, _ = run("compile", "--grid", "2x2", "--robots", "1", "--device", "grid:3x3", *BIND,
                          "--qasm", str(out), "--measure", "--json")  # fmt: skip
    assert code == 0
    final = json.loads(stdout)["final_layout"]
    lines = out.read_text().split("// measure\n")[1].splitlines()
    assert lines == [f"meas[{i}] = measure q[{final[i]}];" for i in range(4)]


def test_measure_without_qasm_is_refused(tmp_path: Path) -> None:
    code, _, stderr = run("compile", "--grid", "2x2", "--robots", "1", "--measure")
    assert code == 2 and "--measure: applies with --qasm only" in stderr
    code, stdout, _ = run("compile", "--grid", "2x2", "--robots", "1", "--qasm", str(tmp_path / "c.qasm"), "--json")
    assert code == 0 and "measured" not in json.loads(stdout)["qasm"]
