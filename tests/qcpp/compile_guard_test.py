"""``qcpp compile`` size guard: predicted from the plan, refused in one line with exit 2, --max-gates / --force."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from circuitgen.lowering import lower
from circuitgen.qaoa import qaoa_circuit
from estimators.guard import BYTES_PER_GATE, predict_size
from gridcover.presets import default_scenario
from gridcover.scenario import load_scenario, save_scenario
from qcpp.cli import app

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

    monkeypatch.setattr("qcpp.commands.compile.compile_scenario", boom)
    res = CliRunner().invoke(app, ["compile", str(path), "-p", "5", "--max-gates", "1000"])
    assert res.exit_code == 2 and "refusing to build" in res.stderr
