"""Time the CLI's start-up: wall and CPU seconds of short commands, and the slowest imports.

Runs each command ``--repeat`` times (default 5) as ``python -m qcpp ...`` in a fresh interpreter and prints the
median wall time and the median CPU time (user + system of the child), then the five imports with the largest
cumulative time of ``python -X importtime -m qcpp --version``. The sources timed are those on ``PYTHONPATH``
(this checkout's ``src`` when it is unset), so two checkouts compare by running the script twice::

    PYTHONPATH=/path/to/other/src python benchmarks/startup.py
    python benchmarks/startup.py

On a shared machine the wall times depend on everyone else's jobs; the CPU times much less so.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
COMMANDS: tuple[tuple[str, ...], ...] = (
    ("--version",),
    ("--help",),
    ("estimate", "--grid", "3x3", "--json"),
    ("solve", str(REPO / "examples" / "paper_3x3.toml"), "-m", "dfs", "--json"),
)


def _env() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": os.environ.get("PYTHONPATH") or str(REPO / "src"), "MPLBACKEND": "Agg"}


def time_command(args: tuple[str, ...], repeat: int) -> tuple[float, float]:
    """Median wall and CPU seconds of ``python -m qcpp ARGS`` over ``repeat`` runs.

    Raises:
        RuntimeError: if a run fails.
    """
    walls, cpus = [], []
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        res = subprocess.run([sys.executable, "-m", "qcpp", *args], capture_output=True, env=_env())
        walls.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
        if res.returncode != 0:
            raise RuntimeError(f"qcpp {' '.join(args)} exited {res.returncode}: {res.stderr.decode()[-300:]}")
    return statistics.median(walls), statistics.median(cpus)


def slowest_imports(count: int = 5) -> list[tuple[str, float, float]]:
    """The ``count`` imports of ``qcpp --version`` with the largest cumulative time: (module, self s, cumulative s)."""
    res = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "qcpp", "--version"], capture_output=True, text=True, env=_env()
    )
    rows = []
    for line in res.stderr.splitlines():
        if not line.startswith("import time:") or "self [us]" in line:
            continue
        self_us, cumulative_us, name = line.removeprefix("import time:").split("|")
        rows.append((name.strip(), int(self_us) / 1e6, int(cumulative_us) / 1e6))
    return sorted(rows, key=lambda row: -row[2])[:count]


def main(argv: list[str] | None = None) -> int:
    """Print the table of start-up times and the slowest imports."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per command (default 5; the median is shown)")
    args = parser.parse_args(argv)
    print(f"sources: {_env()['PYTHONPATH']}  (median of {args.repeat} runs)")
    print(f"{'command':<50} {'wall s':>7} {'CPU s':>7}")
    for command in COMMANDS:
        wall, cpu = time_command(command, args.repeat)
        shown = " ".join(Path(a).relative_to(REPO).as_posix() if a.startswith(str(REPO)) else a for a in command)
        print(f"{'qcpp ' + shown:<50} {wall:>7.2f} {cpu:>7.2f}")
    print()
    print("slowest imports of 'qcpp --version' (cumulative)")
    print(f"{'module':<50} {'self s':>7} {'cum. s':>7}")
    for name, own, cumulative in slowest_imports():
        print(f"{name:<50} {own:>7.3f} {cumulative:>7.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
