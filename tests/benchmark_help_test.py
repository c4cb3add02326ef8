"""Every benchmark script answers ``--help`` with its usage at once instead of running (they take minutes).

Each script runs in this process as ``python benchmarks/NAME.py --help`` would run it (as ``__main__``, its folder
first on ``sys.path``, from an empty working directory): an interpreter per script would cost a second of CPU each
and check nothing more. ``sys.path`` and the modules the script imports from the repository's own folders are
restored afterwards, so no script sees another's.
"""

from __future__ import annotations

import runpy
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOT_SCRIPTS = {"cpu_durations.py"}  # a pytest plugin (``-p cpu_durations``), not run by itself
SCRIPTS = sorted(p.name for p in (ROOT / "benchmarks").glob("*.py") if p.name not in NOT_SCRIPTS)
LOCAL = (ROOT / "benchmarks", ROOT / "examples")
"""Folders whose modules a script may import by their bare names (its own folder, the experiments it reuses)."""


def _local(module: object) -> bool:
    path = getattr(module, "__file__", None)
    return path is not None and any(Path(path).resolve().is_relative_to(folder) for folder in LOCAL)


@pytest.mark.parametrize("script", SCRIPTS)
def test_help_prints_the_usage_and_runs_nothing(
    script: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(sys, "path", [str(ROOT / "benchmarks"), *sys.path])  # the original list comes back
    monkeypatch.setattr(sys, "argv", [str(ROOT / "benchmarks" / script), "--help"])
    monkeypatch.chdir(tmp_path)
    before = set(sys.modules)
    try:
        with pytest.raises(SystemExit) as exit_:
            runpy.run_path(str(ROOT / "benchmarks" / script), run_name="__main__")
    finally:
        for name in set(sys.modules) - before:
            if _local(sys.modules[name]):
                del sys.modules[name]
    out = capsys.readouterr()
    assert exit_.value.code in (0, None), out.err[-2000:]
    assert out.out.startswith(f"usage: {script}"), out.out[:500]
    assert not list(tmp_path.iterdir())  # wrote nothing
