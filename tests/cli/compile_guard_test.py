"""``qcpp compile``: the size guard (predicted from the plan, refused in one line with exit 2, --max-gates / --force)
and streamed OpenQASM (the same file as writing the whole circuit)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from qcpp.cli.app import app
from qcpp.estimators.guard import BYTES_PER_GATE, predict_size
from qcpp.lowering.passes import lower
from qcpp.lowering.qasm import to_qasm2, to_qasm3
from qcpp.plan.compile import compile_scenario, parse_bindings
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario_io import load_scenario, save_scenario

EXAMPLE = "examples/paper_3x3.toml"


def test_prediction_is_the_lowered_gate_count() -> None:
    for rows, cols, robots, p in [(3, 3, 1, 2), (2, 4, 5, 1), (4, 3, 2, 3)]:
        s = default_scenario(rows, cols, robots)
        size = predict_size(s, p)
        low = lower(qaoa_circuit(s, p))
        assert (size.gates, size.qubits) == (len(low), low.num_qubits)
        assert size.bytes == size.gates * BYTES_PER_GATE


def test_over_the_limit_is_refused_in_one_line(tmp_path: Path) -> None:
    out = tmp_path / "c.qasm"
    gates = predict_size(load_scenario(EXAMPLE), 2).gates
    args = ["compile", EXAMPLE, "-p", "2", "--lowered", "--max-gates", "100", "--qasm", str(out)]
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2 and res.stdout == ""
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: refusing to build")
    assert f"{gates:,} gates" in lines[0] and "--max-gates" in lines[0] and "--force" in lines[0]
    assert not out.exists()


def test_force_and_a_higher_limit_build(tmp_path: Path) -> None:
    for extra in (["--max-gates", "100", "--force"], ["--max-gates", "10000000"]):
        res = CliRunner().invoke(app, ["compile", EXAMPLE, "-p", "1", *extra, "--json"])
        assert res.exit_code == 0, res.output


def test_the_guard_runs_before_building(tmp_path: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "big.toml"
    save_scenario(default_scenario(6, 6, 3), path)

    def boom(*args, **kwargs):  # type: ignore[no-untyped-def]
        raise AssertionError("the circuit was built")

    monkeypatch.setattr("qcpp.cli.commands.compile.compile_scenario", boom)
    res = CliRunner().invoke(app, ["compile", str(path), "-p", "5", "--max-gates", "1000"])
    assert res.exit_code == 2 and "refusing to build" in res.stderr


@pytest.mark.parametrize("lowered", [True, False])
def test_streamed_qasm_equals_the_whole_circuit_written_at_once(tmp_path: Path, lowered: bool) -> None:
    out = tmp_path / "s.qasm"
    flags = ["--lowered"] if lowered else []
    for version, binds in (("3", []), ("2", ["--bind", "gamma_0=0.1", "beta_0=0.2", "gamma_1=0.3", "beta_1=0.4"])):
        args = ["compile", EXAMPLE, "-p", "2", *flags, "--qasm", str(out), "--qasm-version", version, *binds, "--json"]
        res = CliRunner().invoke(app, args)
        assert res.exit_code == 0, res.output
        bindings = parse_bindings(binds[1:])
        whole = compile_scenario(load_scenario(EXAMPLE), 2, lowered=lowered, bindings=bindings).circuit
        assert out.read_text() == (to_qasm3(whole) if version == "3" else to_qasm2(whole))
        summary = json.loads(res.stdout)
        assert summary["gates"] == dict(sorted(whole.count_ops().items()))
        assert summary["symbols"] == list(whole.symbols) and summary["qubits"] == whole.num_qubits


def test_streamed_compile_rejects_unknown_bindings(tmp_path: Path) -> None:
    out = tmp_path / "s.qasm"
    res = CliRunner().invoke(app, ["compile", EXAMPLE, "-p", "1", "--qasm", str(out), "--bind", "gamma_7=1"])
    assert res.exit_code == 2 and "gamma_7" in res.stderr and not out.exists()


def _slow(monkeypatch: pytest.MonkeyPatch, seconds_per_gate: float) -> None:
    """Make the time model predict ``seconds_per_gate`` per lowered gate (no work is slower for it)."""
    import qcpp.estimators.guard as guard

    monkeypatch.setattr(guard, "GATES_PER_SECOND", 1.0 / seconds_per_gate)


def test_allow_large_lifts_the_grid_limit_not_the_size_guard(monkeypatch: pytest.MonkeyPatch) -> None:
    """``--allow-large`` lets a grid past 50x50 through to the prediction, which still refuses a compile over an
    hour or over the memory available (naming ``--force``, not ``--allow-large``); the 51x51 circuit is never
    built here."""
    args = ["compile", "--grid", "51x51", "--robots", "1", "--lowered"]
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2 and "over the limit of 2,500 (50x50)" in res.stderr and "--allow-large" in res.stderr
    _slow(monkeypatch, 1.0)  # thousands of gates: hours
    res = CliRunner().invoke(app, [*args, "--allow-large"])
    assert res.exit_code == 2 and res.stdout == ""
    line = res.stderr.strip()
    assert "50x50" not in line and "over the limit of 1 h; pass --force to run it anyway" in line, line
    res = CliRunner().invoke(app, [*args, "--allow-large"], env={"QCPP_MEMORY_AVAILABLE": "1000"})
    assert res.exit_code == 2 and "GB available; pass --force to try anyway" in res.stderr, res.stderr


def test_force_lifts_the_size_guard(monkeypatch: pytest.MonkeyPatch) -> None:
    _slow(monkeypatch, 100.0)  # 288 gates: about 8 h
    res = CliRunner().invoke(app, ["compile", EXAMPLE, "--lowered"])
    assert res.exit_code == 2 and "pass --force to run it anyway" in res.stderr
    assert CliRunner().invoke(app, ["compile", EXAMPLE, "--lowered", "--allow-large"]).exit_code == 2
    assert CliRunner().invoke(app, ["compile", EXAMPLE, "--lowered", "--force", "--json"]).exit_code == 0


@pytest.mark.parametrize("json_out", [False, True])
def test_a_long_compile_prints_its_prediction_first(monkeypatch: pytest.MonkeyPatch, json_out: bool) -> None:
    """Predicted over a minute: one note on stderr with the time and the peak memory, in text mode only."""
    _slow(monkeypatch, 1.0)  # 288 gates: about 5 min, under the hour
    res = CliRunner().invoke(app, ["compile", EXAMPLE, "--lowered", *(["--json"] if json_out else [])],
                             env={"QCPP_PROGRESS": "off", "COLUMNS": "200"})  # fmt: skip
    assert res.exit_code == 0, res.stderr
    notes = [line for line in res.stderr.splitlines() if line.startswith("note: ")]
    if json_out:
        assert notes == [] and json.loads(res.stdout)["total_gates"] == 288
    else:
        assert notes == ["note: compiling 288 gates on 15 qubits: predicted to run for about 5 min, peak 0.1 GB of "
                         "memory"]  # fmt: skip
    _slow(monkeypatch, 0.1)  # about 30 s: no note
    res = CliRunner().invoke(app, ["compile", EXAMPLE, "--lowered"], env={"QCPP_PROGRESS": "off"})
    assert res.exit_code == 0 and "note:" not in res.stderr
