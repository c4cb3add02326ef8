"""Ctrl-C and SIGTERM on a real ``qcpp`` process: ``interrupted``, exit 130, a valid cache, and a rerun resumes.

The sweep has one slow point (14x14, 2 robots, p = 3: several seconds) and nine fast ones; with two workers the
slow one occupies a worker while the other finishes the fast ones, so the signal arrives with finished results
in the cache and work still running. Before the fix the process ran on until every queued point was done.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from estimators.sweep import PointResult, grid_points, sweep

REPO = Path(__file__).resolve().parents[2]
FAST = [(2, 2), (2, 3), (2, 4), (3, 2), (3, 3), (3, 4), (4, 2), (4, 3), (4, 4)]
ARGS = ["estimate", "--grid", "2x2..4x4,14x14", "--robots", "2", "-p", "3", "-j", "2", "--json"]


def start(args: list[str], env: dict[str, str]) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-m", "qcpp", *args],
        cwd=REPO,
        env={**os.environ, "PYTHONPATH": str(REPO / "src"), **env},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def wait_for_files(folder: Path, n: int, proc: subprocess.Popen[str], limit: float = 120.0) -> None:
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline and proc.poll() is None:
        if folder.is_dir() and len(list(folder.glob("*.json"))) >= n:
            return
        time.sleep(0.05)
    pytest.fail(f"the sweep did not cache {n} results in time (exit code {proc.poll()})")


def wait_until_catching_sigterm(proc: subprocess.Popen[str], limit: float = 60.0) -> None:
    """Wait until the CLI installed its signal handling: SIGTERM appears in the caught set (Linux /proc)."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline and proc.poll() is None:
        status = Path(f"/proc/{proc.pid}/status").read_text()
        caught = int(next(line.split()[1] for line in status.splitlines() if line.startswith("SigCgt:")), 16)
        if caught & (1 << (signal.SIGTERM - 1)):
            return
        time.sleep(0.02)
    pytest.fail("the CLI did not start")


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_signal_stops_a_sweep_keeps_the_cache_and_a_rerun_resumes(tmp_path: Path, sig: signal.Signals) -> None:
    cache = tmp_path / "cache"
    proc = start(ARGS, {"QCPP_CACHE_DIR": str(cache)})
    wait_for_files(cache, len(FAST), proc)
    proc.send_signal(sig)
    try:
        out, err = proc.communicate(timeout=20)  # before the fix: until the slow point was done
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail("the process did not stop after the signal")
    assert proc.returncode == 130, err
    assert err.strip().splitlines() == ["interrupted"]
    assert out == ""
    assert not [p.name for p in cache.iterdir() if not p.name.endswith(".json")]  # no temporary files
    files = sorted(cache.glob("*.json"))
    results = [PointResult.from_dict(json.loads(f.read_text())) for f in files]  # every entry is whole
    fast = grid_points(FAST, [2], [3])
    assert {r.point for r in results} >= set(fast)
    # the rerun resumes: every finished point comes from the cache, with the counts a fresh run gives
    again = sweep(fast, cache=cache, jobs=1, progress=False)
    assert all(r.cached for r in again)
    fresh = sweep(fast[:2], use_cache=False, jobs=1, progress=False)
    assert [r.counts for r in fresh] == [r.counts for r in again[:2]]


def test_interrupting_a_single_process_command(tmp_path: Path) -> None:
    """In-process work (``-j 1``): the main thread is interrupted mid-computation; nothing is cached half-way."""
    cache = tmp_path / "cache"
    args = ["estimate", "--grid", "14x14", "--robots", "2", "-p", "3", "-j", "1"]
    proc = start(args, {"QCPP_CACHE_DIR": str(cache)})
    wait_until_catching_sigterm(proc)
    time.sleep(1.0)  # into the imports or the computation: the signal is honoured at any point
    proc.send_signal(signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail("the process did not stop after the signal")
    assert proc.returncode == 130, err
    assert err.strip().splitlines()[-1] == "interrupted" and "Traceback" not in err
    assert not cache.exists() or not list(cache.iterdir())
