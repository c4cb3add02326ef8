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
