"""``/dev/stdout`` as an output path is standard output, whatever it is redirected to (here a regular file, which
the temporary-file rename through ``/proc`` cannot replace)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest


@pytest.mark.parametrize(
    ("args", "first_line"),
    [
        (["scenario", "--grid", "2x2", "-o", "/dev/stdout"], 'name = "default 2x2, 1 robot(s)"'),
        (["compile", "--grid", "2x2", "--qasm", "/dev/stdout"], "OPENQASM 3.0;"),
    ],
)
def test_dev_stdout_redirected_to_a_file_gets_the_output(tmp_path: Path, args: list[str], first_line: str) -> None:
    out = tmp_path / "redirected"
    with out.open("w") as f:
        run = subprocess.run([sys.executable, "-m", "qcpp", *args], stdout=f, stderr=subprocess.PIPE, text=True,
                             timeout=120, check=False)  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert out.read_text().splitlines()[0] == first_line


@pytest.mark.parametrize("name", ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"])
def test_every_name_of_standard_output_keeps_it_for_the_written_text(name: str) -> None:
    """``--qasm /dev/stdout`` is ``--qasm -``: standard output holds the OpenQASM text only (the summary table went
    there after it), and ``--json`` beside it is refused (JSON and OpenQASM were interleaved); the same for
    ``export --out NAME --json``."""
    from typer.testing import CliRunner

    from qcpp.cli.app import app

    res = CliRunner().invoke(app, ["compile", "--grid", "2x2", "--qasm", name])
    assert res.exit_code == 0, res.output
    assert res.stdout.startswith("OPENQASM 3.0;") and "time:" not in res.stdout and "time:" in res.stderr
    for args in (["compile", "--grid", "2x2", "--qasm", name, "--json"],
                 ["export", "--grid", "2x2", "--out", name, "--json"]):  # fmt: skip
        res = CliRunner().invoke(app, args)
        assert res.exit_code == 2 and res.stdout == "" and res.stderr.startswith("error: "), (args, res.output)
