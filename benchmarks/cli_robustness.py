"""How fast ``qcpp`` stops on Ctrl-C/SIGTERM, and how wide the resource table gets per terminal width.

Part 1 starts real ``qcpp`` processes, sends the signal once the command is busy, and measures the time until
the process has exited (and its exit code and last stderr line). Part 2 runs the issue's table command at several
``COLUMNS`` and reports the longest output line and the columns shown.

Run:  PYTHONPATH=src python benchmarks/cli_robustness.py
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": str(REPO / "src"), "MPLBACKEND": "Agg"}

CASES = [
    ("estimate sweep", ["estimate", "--grid", "12x12..14x14", "--robots", "2..4", "-p", "3"], 4.0),
    ("validate --backend tensor", ["validate", "examples/two_robots_4x4.toml", "--backend", "tensor"], 6.0),
    ("solve -m qaoa", ["solve", "examples/two_robots_4x4.toml", "-m", "qaoa", "--maxiter", "100000"], 4.0),
]


def stop_time(args: list[str], after: float, sig: signal.Signals) -> tuple[float, int, str]:
    with tempfile.TemporaryDirectory() as cache:
        proc = subprocess.Popen(
            [sys.executable, "-m", "qcpp", *args],
            cwd=REPO,
            env={**ENV, "QCPP_CACHE_DIR": cache},
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        time.sleep(after)
        if proc.poll() is not None:
            return float("nan"), proc.returncode, "finished before the signal"
        t0 = time.perf_counter()
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=120)
        dt = time.perf_counter() - t0
        lines = err.strip().splitlines()
        return dt, proc.returncode, lines[-1] if lines else ""


def table_widths() -> list[tuple[int, int, str]]:
    out = []
    for width in (60, 80, 100, 140, 200):
        res = subprocess.run(
            [sys.executable, "-m", "qcpp", "estimate", "--grid", "3x3..6x6", "--robots", "1..3", "--compare",
             "paper"],
            cwd=REPO, env={**ENV, "COLUMNS": str(width)}, capture_output=True, text=True, check=True,
        )
        longest = max(len(line) for line in (res.stdout + res.stderr).splitlines())
        header = next(line for line in res.stdout.splitlines() if "rows" in line)
        shown = [c.strip() for c in header.strip("┃ ").split("┃")]
        out.append((width, longest, ", ".join(shown)))
    return out


def main() -> None:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    print("| command | signal | sent after (s) | exit code | seconds to exit | last stderr line |")
    print("|---|---|---:|---:|---:|---|")
    for name, args, after in CASES:
        for sig in (signal.SIGINT, signal.SIGTERM):
            dt, code, last = stop_time(args, after, sig)
            print(f"| {name} | {sig.name} | {after:g} | {code} | {dt:.2f} | {last} |")
    print()
    print("| COLUMNS | longest line | columns shown |")
    print("|---:|---:|---|")
    for width, longest, shown in table_widths():
        print(f"| {width} | {longest} | {shown} |")


if __name__ == "__main__":
    main()
