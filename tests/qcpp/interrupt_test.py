"""Ctrl-C and SIGTERM on a real ``qcpp`` process: ``interrupted``, exit 130, and only whole rows printed.

``qcpp estimate`` streams rows as it computes them (no process pool, no cache: estimates come from the gadgets'
costs): the signal arrives after some rows are out and more are being computed; the process must stop at once,
leave every printed row whole and say ``interrupted``.
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

REPO = Path(__file__).resolve().parents[2]
ARGS = ["estimate", "--grid", "2x2..40x40", "--robots", "1..8", "-p", "1..5", "--depth", "none", "--format", "jsonl"]


def start(args: list[str], env: dict[str, str]) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-m", "qcpp", *args],
        cwd=REPO,
        env={**os.environ, "PYTHONPATH": str(REPO / "src"), **env},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def stop(proc: subprocess.Popen[str], sig: signal.Signals) -> str:
    """Send ``sig``; the process must stop within 20 s with exit 130, ``interrupted`` and no traceback.

    Returns:
        What it printed on stdout after the signal.
    """
    proc.send_signal(sig)
    try:
        out, err = proc.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail("the process did not stop after the signal")
    assert proc.returncode == 130, err
    assert err.strip().splitlines()[-1] == "interrupted" and "Traceback" not in err
    return out


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
def test_signal_stops_a_streaming_sweep_with_whole_rows(tmp_path: Path, sig: signal.Signals) -> None:
    proc = start(ARGS, {})
    assert proc.stdout is not None
    first = [proc.stdout.readline() for _ in range(20)]  # rows are out: the sweep is under way
    out = stop(proc, sig)
    lines = [line for line in "".join(first).splitlines() + out.splitlines() if line]
    rows = [json.loads(line) for line in lines]  # every printed row is whole
    assert len(rows) >= 20 and len(rows) < 60_000


def test_interrupting_a_single_process_command(tmp_path: Path) -> None:
    """The main thread is interrupted mid-computation (a table waits for every row, so nothing is printed)."""
    args = ["estimate", "--grid", "2x2..40x40", "--robots", "1..8", "-p", "1..5", "--depth", "none"]
    proc = start(args, {})
    wait_until_catching_sigterm(proc)
    # into the computation (the sweep runs for about half a minute). Earlier, under load, the signal can land inside a C
    # extension's import, which Python reports as "ImportError: initialization failed" (seen once under heavy load;
    # an open item in the closing note of the session that wrote this test).
    time.sleep(3.0)
    stop(proc, signal.SIGINT)
