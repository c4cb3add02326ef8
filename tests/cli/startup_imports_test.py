"""Start-up stays cheap (issue #18): importing the CLI, ``qcpp --help`` and ``qcpp --version`` load none of the
heavy libraries; the commands import those when they run.

Each check runs in a fresh interpreter (this test process has long imported everything) and reads its
``sys.modules``; nothing here is timed.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"

HEAVY = ("ortools", "scipy", "sympy", "qiskit", "pandas", "quimb", "matplotlib")
"""Top-level packages that must not be imported before a command runs."""

_PROBE = """
import json, sys
argv = sys.argv[1:]
if argv == ["import"]:
    import qcpp.cli.app
else:
    from qcpp.__main__ import main
    sys.argv = ["qcpp", *argv]
    try:
        main()
    except SystemExit:
        pass
loaded = sorted({name.partition(".")[0] for name in sys.modules} & set(json.loads(sys.stdin.readline())))
sys.stderr.write("LOADED " + json.dumps(loaded) + "\\n")
"""


def loaded_heavy(*args: str, heavy: tuple[str, ...] = HEAVY) -> list[str]:
    """The packages of ``heavy`` present in ``sys.modules`` after ``qcpp ARGS`` (``import`` alone: the import)."""
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")]),
        "MPLBACKEND": "Agg",
    }
    res = subprocess.run(
        [sys.executable, "-c", _PROBE, *args],
        input=json.dumps(list(heavy)) + "\n",
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    line = next((x for x in res.stderr.splitlines() if x.startswith("LOADED ")), None)
    assert line is not None, res.stderr
    return json.loads(line.removeprefix("LOADED "))


@pytest.mark.parametrize("args", [("import",), ("--help",), ("--version",)])
def test_start_up_loads_no_heavy_library(args: tuple[str, ...]) -> None:
    assert loaded_heavy(*args) == []


def test_the_probe_sees_a_heavy_import() -> None:
    """The check can fail: a command that needs scipy does load it in the same probe."""
    assert loaded_heavy("simulate", "no/such/file.toml", heavy=("scipy",)) == ["scipy"]


def test_cpsat_loads_ortools_only_when_used() -> None:
    code = (
        "import sys; import qcpp.problem.solvers as g; a = 'ortools' in sys.modules; "
        "from qcpp.problem.solvers import cpsat, CpSatResult; import qcpp.problem.solvers.cpsat; "
        "print(a, 'ortools' in sys.modules, g.cpsat is cpsat, callable(cpsat), CpSatResult.__name__)"
    )
    res = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=120,
        env={**os.environ, "PYTHONPATH": str(SRC)},
    )
    assert res.stdout.split() == ["False", "True", "True", "True", "CpSatResult"], res.stderr
