"""Standard output that is not UTF-8 (``LC_ALL=C PYTHONUTF8=0``, ``PYTHONIOENCODING=ascii``): every command prints,
in ASCII where its text would need more, and JSON carries file names as the characters they are."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PAPER = REPO / "examples" / "paper_3x3.toml"
NOT_UTF8 = [{"LC_ALL": "C", "PYTHONUTF8": "0"}, {"PYTHONIOENCODING": "ascii"}]


def qcpp(*args: str | Path, env: dict[str, str], cwd: Path = REPO) -> subprocess.CompletedProcess[bytes]:
    unset = ("LANG", "LC_CTYPE", "LC_ALL", "PYTHONUTF8", "PYTHONIOENCODING", "COLUMNS")
    full = {k: v for k, v in os.environ.items() if k not in unset}
    full.update(PYTHONPATH=str(REPO / "src"), QCPP_PROGRESS="off", **env)
    return subprocess.run([sys.executable, "-m", "qcpp", *map(str, args)], cwd=cwd, env=full, capture_output=True,
                          timeout=600, check=False)  # fmt: skip


@pytest.mark.parametrize("env", NOT_UTF8, ids=["C locale", "PYTHONIOENCODING=ascii"])
@pytest.mark.parametrize("extra", [(), ("--physical",)], ids=["logical", "physical"])
def test_estimate_draws_its_table_in_ascii(env: dict[str, str], extra: tuple[str, ...]) -> None:
    """The table was drawn with Unicode boxes into a buffer and failed to print: ``'ascii' codec can't encode``."""
    res = qcpp("estimate", "--grid", "3x3", *extra, env=env)
    assert res.returncode == 0, res.stderr.decode(errors="replace")
    res.stdout.decode("ascii")  # every byte ASCII
    assert b"+---" in res.stdout and b"| rows |" in res.stdout


def test_json_names_a_non_ascii_file_in_the_c_locale(tmp_path: Path) -> None:
    """Python reads ``cafe.toml`` with an accent in the C locale as lone surrogates; JSON gets the character."""
    scenario = tmp_path / "café.toml"
    shutil.copy(PAPER, scenario)
    env = {"LC_ALL": "C", "PYTHONUTF8": "0"}
    for args in (("solve", scenario.name, "-m", "dfs", "--json"), ("simulate", scenario.name, "--json")):
        res = qcpp(*args, env=env, cwd=tmp_path)
        assert res.returncode == 0, res.stderr.decode(errors="replace")
        data = json.loads(res.stdout)
        assert data["scenario"] == "café.toml"
        data["scenario"].encode("utf-8")  # no lone surrogate left
