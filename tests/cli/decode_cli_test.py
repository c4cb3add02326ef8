"""``qcpp decode``: measured counts of ``qcpp compile --qasm F --measure`` read back as paths, as
``qcpp.decode_counts`` reads them; the counts formats a Qiskit user saves; bad files are one line, exit 2."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

import qcpp

from .clirun import assert_one_line_error, run

ROOT = Path(__file__).resolve().parents[2]
FIELD = ["--grid", "2x3", "--robots", "2"]


@pytest.fixture(scope="module")
def sampled(tmp_path_factory: pytest.TempPathFactory) -> tuple[qcpp.Scenario, dict[str, int], list[str]]:
    """Two robots on 2x3 (14 data qubits): the circuit ``qcpp compile --measure`` writes, sampled by Qiskit's seeded
    StatevectorSampler; its counts and its shots as bitstrings."""
    from qiskit import QuantumCircuit
    from qiskit.primitives import StatevectorSampler

    qasm = tmp_path_factory.mktemp("decode") / "c.qasm"
    res = run("compile", *FIELD, "--lowered", "--bind", "gamma_0=0.4", "beta_0=1.1", "--qasm", str(qasm),
              "--qasm-version", "2", "--measure")  # fmt: skip
    assert res.exit_code == 0, res.output
    circuit = QuantumCircuit.from_qasm_str(qasm.read_text())
    data = StatevectorSampler(seed=11).run([circuit], shots=3000).result()[0].data.meas
    return qcpp.grid_scenario(2, 3, robots=2), data.get_counts(), data.get_bitstrings()


def _write(path: Path, data: object) -> str:
    path.write_text(json.dumps(data))
    return str(path)


def test_a_round_trip_decodes_as_the_api_does(sampled: tuple, tmp_path: Path) -> None:
    s, counts, memory = sampled
    want = qcpp.decode_counts(s, counts, optimum=qcpp.solve(s)).to_dict()
    assert len(want["outcomes"]) >= 3 and want["feasible_share"] == 1.0  # the mixer keeps the paths feasible
    assert 0 < want["p_optimum"] < 1
    as_result = {"results": [{"data": {"counts": {hex(int(k, 2)): v for k, v in counts.items()}}}]}
    for name, data in (("counts", counts), ("memory", memory), ("result", as_result)):
        res = run("decode", *FIELD, "--counts", _write(tmp_path / f"{name}.json", data), "--json")
        assert res.exit_code == 0, res.output
        got = json.loads(res.stdout)
        assert {k: got[k] for k in want} == want, name  # CP-SAT's proven optimum, as qcpp.solve gives it
        assert got["optimum_source"] == "cpsat" and got["distinct"] == len(want["outcomes"])
    res = run("decode", *FIELD, "--counts", str(tmp_path / "counts.json"), "--optimum", "-1000", "--json")
    assert json.loads(res.stdout)["p_optimum"] == 0 and json.loads(res.stdout)["optimum_source"] == "given"


def test_the_text_names_the_top_outcomes_and_the_totals_within_80_columns(sampled: tuple, tmp_path: Path) -> None:
    s, counts, _ = sampled
    d = qcpp.decode_counts(s, counts, optimum=qcpp.solve(s))
    path = _write(tmp_path / "counts.json", counts)
    from typer.testing import CliRunner

    from qcpp.cli.app import app

    res = CliRunner().invoke(app, ["decode", *FIELD, "--counts", path, "--top", "3"], env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    lines = res.stdout.splitlines()
    assert max(map(len, lines)) <= 80, max(lines, key=len)
    text = " ".join(res.stdout.translate(str.maketrans(dict.fromkeys("│┃", " "))).split())  # cells unwrapped
    assert f"{d.shots:,} shots" in text and f"{len(d.outcomes)} distinct" in text
    assert "feasible 100.0% of shots" in text and f"P(optimum) {d.p_optimum:.4g}" in text
    assert "CP-SAT, proven" in text
    for o in d.outcomes[:3]:  # each robot's nodes, in order
        assert f"{o.shots:,}" in text
        assert all(" ".join(f"({r},{c})" for r, c in nodes) in text for nodes in o.nodes)
    assert "the 3 most frequent outcome(s)" in text


def test_the_help_example_file_decodes(tmp_path: Path) -> None:
    res = run("decode", str(ROOT / "examples" / "paper_3x3.toml"), "--counts", str(ROOT / "examples" / "counts" /
              "3x3.json"), "--optimum", "-6", "--json")  # fmt: skip
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["shots"] == 1000 and data["feasible_share"] == 1.0 and data["optimum_source"] == "given"


@pytest.mark.parametrize(
    ("content", "fragment"),
    [
        (None, "cannot read the file"),
        ("not json", "not JSON"),
        ('{"0101": 3}', "has 4 bits; the scenario's data register has 14"),
        ('{"01x0101010101": 3}', "characters other than 0 and 1"),
        ('{"00101010101010": -3}', "must be a non-negative integer, got -3"),
        ('{"00101010101010": 1.5}', "must be a non-negative integer"),
        ('{"0010101 0101010": 3}', "several classical registers"),
        ('{"00101010101010": 0}', "no shots"),
        ('[1, 2]', "must hold bitstrings"),
        ('"0101"', "expected a JSON object"),
        ('{"0x4000": 1}', "outside the 14-bit data register"),
    ],
)
def test_a_bad_counts_file_is_one_line_naming_it(tmp_path: Path, content: str | None, fragment: str) -> None:
    path = tmp_path / "bad.json"
    if content is not None:
        path.write_text(content)
    assert_one_line_error(run("decode", *FIELD, "--counts", str(path), "--optimum", "-1"), str(path), fragment)


def test_missing_or_bad_options_are_one_line() -> None:
    assert_one_line_error(run("decode", *FIELD), "--counts")
    counts = str(ROOT / "examples" / "counts" / "3x3.json")
    assert_one_line_error(run("decode", str(ROOT / "examples" / "paper_3x3.toml"), "--counts", counts, "--top", "0"),
                          "--top")  # fmt: skip
    assert_one_line_error(run("decode", str(ROOT / "examples" / "paper_3x3.toml"), "--counts", counts,
                              "--time-limit", "0"), "--time-limit")  # fmt: skip


def test_an_endless_or_silent_counts_file_is_one_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """``--counts /dev/zero`` read until the memory ran out, and a FIFO nobody writes to waited for ever: the file is
    read as a scenario file is (:func:`qcpp.io.inputs.read_bounded`: bounded in size and in waiting)."""
    from qcpp.cli.commands import decode

    monkeypatch.setattr(decode, "MAX_COUNTS_BYTES", 1 << 16)  # /dev/zero stops after 64 KiB, not 256 MiB
    assert_one_line_error(run("decode", *FIELD, "--counts", "/dev/zero", "--optimum", "-1"), "/dev/zero",
                          "larger than")  # fmt: skip
    monkeypatch.setattr("qcpp.io.inputs.INPUT_WAIT", 0.05)
    fifo = tmp_path / "counts.json"
    os.mkfifo(fifo)
    assert_one_line_error(run("decode", *FIELD, "--counts", str(fifo), "--optimum", "-1"), str(fifo),
                          "no process wrote to the FIFO")  # fmt: skip
