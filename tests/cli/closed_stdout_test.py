"""A closed (``>&-``) or broken (``| head -1``) standard output: every command exits quietly with code 1.

Both are made deterministic: the child starts with descriptor 1 closed, or writing into a pipe whose read end is
already closed (what ``head -1`` leaves behind once it has its line), so no test depends on timing.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = str(REPO / "examples" / "paper_3x3.toml")

HEAVY = pytest.mark.heavy  # a fresh interpreter per case (1-3 s each): the full set runs in CI's heavy step
COMMANDS = [
    pytest.param(["estimate", "--grid", "3x3"], id="estimate", marks=HEAVY),
    pytest.param(["estimate", "--grid", "3x3", "--format", "csv"], id="estimate-csv", marks=HEAVY),
    pytest.param(["solve", EXAMPLE, "-m", "dfs"], id="solve"),
    pytest.param(["solve", EXAMPLE, "-m", "cpsat", "--json"], id="solve-cpsat-json", marks=HEAVY),
    pytest.param(["compile", EXAMPLE, "--lowered", "--qasm", "-"], id="compile-qasm-stdout", marks=HEAVY),
    pytest.param(["simulate", EXAMPLE], id="simulate", marks=HEAVY),
    pytest.param(["validate", EXAMPLE], id="validate", marks=HEAVY),
    pytest.param(["solve", "--help"], id="help", marks=HEAVY),
    pytest.param(["--version"], id="version", marks=HEAVY),
]
BROKEN = [
    pytest.param(["estimate", "--grid", "3x3", "--json"], id="estimate-json"),
    pytest.param(["solve", EXAMPLE, "-m", "anneal", "--json"], id="solve-json", marks=HEAVY),
    pytest.param(["compile", EXAMPLE], id="compile", marks=HEAVY),
    pytest.param(["simulate", EXAMPLE, "--json"], id="simulate-json", marks=HEAVY),
    pytest.param(["validate", EXAMPLE, "--json"], id="validate-json", marks=HEAVY),
    pytest.param(["--help"], id="help", marks=HEAVY),
]


def _env() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(REPO / "src"), "MPLBACKEND": "Agg"}


def _close_stdout() -> None:
    os.close(1)


@pytest.mark.parametrize("args", COMMANDS)
def test_closed_stdout_exits_quietly(args: list[str]) -> None:
    res = subprocess.run([sys.executable, "-m", "qcpp", *args], stdin=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         preexec_fn=_close_stdout, env=_env(), text=True, timeout=300)
    assert res.returncode == 1
    assert res.stderr == ""


@pytest.mark.parametrize("args", BROKEN)
def test_broken_pipe_exits_quietly(args: list[str]) -> None:
    read, write = os.pipe()
    os.close(read)  # the reader is gone before the first byte
    try:
        res = subprocess.run([sys.executable, "-m", "qcpp", *args], stdin=subprocess.DEVNULL, stdout=write,
                             stderr=subprocess.PIPE, env=_env(), text=True, timeout=300)
    finally:
        os.close(write)
    assert res.returncode == 1
    assert res.stderr == ""


@HEAVY
def test_closed_stdout_never_lends_its_descriptor_to_an_output_file(tmp_path: Path) -> None:
    """With descriptor 1 closed the next open() would get it; the QASM must still be the file's only content."""
    out = tmp_path / "o.qasm"
    res = subprocess.run([sys.executable, "-m", "qcpp", "compile", EXAMPLE, "--qasm", str(out), "--json"],
                         stdin=subprocess.DEVNULL, stderr=subprocess.PIPE, preexec_fn=_close_stdout, env=_env(),
                         text=True, timeout=300)
    assert res.returncode == 1 and res.stderr == ""
    if out.exists():  # written before the first stdout write failed: then whole, and only QASM
        text = out.read_text()
        assert text.startswith("OPENQASM") and "{" not in text.split("\n", 1)[0]


def _reader_gone_with_stdout(fd: int) -> bool:
    from qcpp.cli.app import _reader_gone

    saved = os.dup(1)
    try:
        os.dup2(fd, 1)
        return _reader_gone()
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def test_small_output_into_a_pipe_whose_reader_left_is_not_success() -> None:
    """All of a short output fits in the pipe: the writes succeed, but when the reader has gone by the end
    (``| head -1`` done) the exit code says the output was not read; an open reader is success."""
    read, write = os.pipe()
    try:
        assert not _reader_gone_with_stdout(write)
        os.close(read)
        assert _reader_gone_with_stdout(write)
    finally:
        os.close(write)
