"""``qcpp compile --qasm-profile``: the streamed and routed writers give the API's text; bad input is one line."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from qcpp.api.compiling import compile as qcpp_compile
from qcpp.api.scenarios import grid_scenario
from tests.cli.clirun import assert_one_line_error, run


@pytest.mark.parametrize("profile", ["portable", "braket"])
@pytest.mark.parametrize("lowered", [False, True])
def test_the_written_file_is_the_apis_profile_text(tmp_path: Path, profile: str, lowered: bool) -> None:
    out = tmp_path / "c.qasm"
    flags = ["--lowered"] if lowered else []
    res = run(
        "compile", "--grid", "2x4", "--robots", "1", *flags, "--qasm", str(out), "--qasm-profile", profile, "--json"
    )
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["qasm"] == {"path": str(out), "version": 3, "profile": profile}
    expected = qcpp_compile(grid_scenario(2, 4, robots=1), lowered=lowered).to_qasm(profile=profile)
    assert out.read_text() == expected
    assert "include" not in expected


def test_the_default_profile_is_the_file_without_the_flag(tmp_path: Path) -> None:
    a, b = tmp_path / "a.qasm", tmp_path / "b.qasm"
    assert run("compile", "--grid", "2x4", "--robots", "1", "--qasm", str(a)).exit_code == 0
    res = run("compile", "--grid", "2x4", "--robots", "1", "--qasm", str(b), "--qasm-profile", "default", "--json")
    assert res.exit_code == 0, res.output
    assert a.read_bytes() == b.read_bytes()
    assert json.loads(res.stdout)["qasm"] == {"path": str(b), "version": 3}  # the summary as without the flag


@pytest.mark.heavy
def test_a_routed_circuit_in_the_braket_profile(tmp_path: Path) -> None:
    out = tmp_path / "r.qasm"
    res = run("compile", "--grid", "2x2", "--robots", "1", "--device", "grid", "--lowered", "--qasm", str(out),
              "--qasm-profile", "braket")  # fmt: skip
    assert res.exit_code == 0, res.output
    text = out.read_text()
    assert "cnot q[" in text and "include" not in text and "cx " not in text


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (["--qasm-profile", "pennylane"], ("--qasm-profile", "expected default or portable or braket", "pennylane")),
        (["--qasm-profile", "portable", "--qasm-version", "2"], ("--qasm-profile", "OpenQASM 3", "--qasm-version 2")),
    ],
)
def test_bad_profiles_are_one_line_and_exit_2(tmp_path: Path, args: list[str], fragments: tuple[str, ...]) -> None:
    out = tmp_path / "x.qasm"
    res = run("compile", "--grid", "2x4", "--robots", "1", "--qasm", str(out), *args)
    assert_one_line_error(res, *fragments)
    assert not out.exists()
