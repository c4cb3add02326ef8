"""Each size guard's memory prediction against the measured peak of the command it guards (within 1.5x).

The guards of ``qcpp simulate``, ``validate``, ``solve`` (``dfs``, ``qaoa``) and ``compile`` refuse only what
would not fit in the memory available (:func:`qcpp.problem.limits.check_need`), so their predictions must be
honest: here each command runs in a child process on scenarios of several sizes and its peak resident memory
(``ru_maxrss`` of the waited-for command, read in a fresh intermediate process so no other child counts) is
compared with the prediction. Memory, not time: no timing is asserted. The small scenarios run in a few seconds;
the large ones (up to 3 GB) are marked heavy.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from qcpp.estimators.guard import compile_need
from qcpp.plan.options import DEFAULT_PLAN
from qcpp.problem.paths import count_paths
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers.exhaustive import DfsSize
from qcpp.simulate.footprint import simulate_need, training_need, validate_need

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"
TOLERANCE = 1.5

MEASURE = (
    "import json, resource, subprocess, sys\n"
    "res = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
    "peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024\n"
    "print(json.dumps({'code': res.returncode, 'peak': peak, 'stderr': res.stderr[-2000:]}))\n"
)
"""Run a command and print its exit code and peak resident memory (bytes; Linux reports ``ru_maxrss`` in KiB)."""


def peak_of(*args: str) -> int:
    """Peak resident memory of ``qcpp ARGS`` (it must succeed)."""
    env = {**os.environ, "PYTHONPATH": str(REPO / "src"), "QCPP_PROGRESS": "off"}
    out = subprocess.run([sys.executable, "-c", MEASURE, sys.executable, "-m", "qcpp", *args], cwd=REPO, env=env,
                         capture_output=True, text=True, check=True)  # fmt: skip
    result = json.loads(out.stdout)
    assert result["code"] == 0, result["stderr"]
    return int(result["peak"])


def write(tmp_path: Path, rows: int, cols: int, robots: int) -> Path:
    """The preset scenario (robots from the corners) as a TOML file."""
    s = default_scenario(rows, cols, robots)
    text = f"[grid]\nrows = {rows}\ncols = {cols}\n"
    text += "".join(f"[[robots]]\nstart = {list(r.start)}\ngoal = {list(r.goal)}\n" for r in s.robots)
    path = tmp_path / f"s{rows}x{cols}x{robots}.toml"
    path.write_text(text, encoding="utf-8")
    return path


def within(predicted: int, measured: int) -> bool:
    return measured / TOLERANCE <= predicted <= measured * TOLERANCE


def dfs_bytes(s: Scenario) -> int:
    counts = tuple(count_paths(s, r) for r in range(s.num_robots))
    return DfsSize(counts, (True,) * len(counts), s.edges_per_robot, s.grid.num_nodes).bytes


Case = tuple[str, tuple[int, int, int] | str, tuple[str, ...], Callable[[Scenario], int]]

CASES: list[Case] = [  # one per guard but training (a process each: 1.5-3.5 s of CPU); the rest under HEAVY
    ("simulate", (4, 5, 2), (), lambda s: simulate_need(s, 1).bytes),
    ("solve", (3, 5, 3), ("-m", "dfs"), dfs_bytes),
    ("compile", "paper_3x3.toml", ("-p", "2", "--json"), lambda s: compile_need(s, 2, streamed=False).bytes),
    ("validate", "paper_3x3.toml", (), validate_need_bytes := (lambda s: validate_need(s).bytes)),
]
TRAIN = ("-m", "qaoa", "--optimizer", "lbfgsb", "--maxiter", "1")
"""One short L-BFGS-B run: the peak is the first gradient's (the layerwise default's is the same, at more CPU)."""

HEAVY: list[Case] = [
    ("simulate", "paper_3x3.toml", (), lambda s: simulate_need(s, 1).bytes),
    ("simulate", (4, 4, 3), (), lambda s: simulate_need(s, 1).bytes),
    ("solve", "two_robots_4x4.toml", ("-m", "dfs"), dfs_bytes),
    ("simulate", "two_robots_5x5.toml", (), lambda s: simulate_need(s, 1).bytes),
    ("solve", (4, 4, 3), ("-m", "dfs"), dfs_bytes),
    ("solve", "two_robots_5x5.toml", ("-m", "dfs"), dfs_bytes),
    # training: 171,396 amplitudes, 0.22 GB; 952,576 (two robots), 0.25 GB; 1,953,125 (three robots), 0.31 GB
    ("solve", (3, 6, 2), TRAIN, lambda s: training_need(s, 1).bytes),
    ("solve", (4, 5, 2), TRAIN, lambda s: training_need(s, 1).bytes),
    ("solve", (3, 5, 3), TRAIN, lambda s: training_need(s, 1).bytes),
    ("solve", (4, 4, 3), TRAIN, lambda s: training_need(s, 1).bytes),
    # validate: 15,625 assignments (two robots), 54,872 (three robots), 33,856 (two robots, obstacles); left out
    # for its minutes of CPU: 3x6 with two robots, 171,396 assignments, peaked at 0.38 GB (predicted 0.48 GB)
    ("validate", (3, 5, 2), (), validate_need_bytes),
    ("validate", (3, 4, 3), (), validate_need_bytes),
    ("validate", "two_robots_4x4.toml", (), validate_need_bytes),
    # compile: a whole circuit of two robots at p = 3, and streamed circuits of p = 6 and p = 4
    ("compile", "two_robots_4x4.toml", ("-p", "3", "--json"), lambda s: compile_need(s, 3, streamed=False).bytes),
    ("compile", (5, 5, 2), ("-p", "6", "--lowered", "--qasm", "{tmp}/out.qasm"),
     lambda s: compile_need(s, 6, DEFAULT_PLAN, streamed=True).bytes),
    ("compile", (6, 6, 3), ("-p", "4", "--lowered", "--qasm", "{tmp}/out.qasm"),
     lambda s: compile_need(s, 4, DEFAULT_PLAN, streamed=True).bytes),
]
"""With :data:`CASES`, every guard's model (simulate, solve by dfs, training, validate, compile) is checked on at
least three scenarios, the models fitted to two coefficients on more than two."""


def _run_case(tmp_path: Path, case: Case) -> None:
    command, scenario, extra, predict = case
    path = EXAMPLES / scenario if isinstance(scenario, str) else write(tmp_path, *scenario)
    predicted = predict(load_scenario(path))
    args = [a.replace("{tmp}", str(tmp_path)) for a in extra]
    measured = peak_of(command, str(path), *args, "--allow-large")  # the guard itself is not under test here
    assert within(predicted, measured), (
        f"{command} {path.name}: predicted {predicted / 1e9:.3f} GB, measured {measured / 1e9:.3f} GB"
    )


def _id(case: Case) -> str:
    command, scenario, extra, _ = case
    name = scenario if isinstance(scenario, str) else "x".join(map(str, scenario))
    return f"{command}-{' '.join(extra[:2]) or 'default'}-{name}"


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES, ids=_id)
def test_a_guards_memory_prediction_is_within_1_5x_of_the_measured_peak(tmp_path: Path, case: Case) -> None:
    _run_case(tmp_path, case)


@pytest.mark.heavy
@pytest.mark.parametrize("case", HEAVY, ids=_id)
def test_a_guards_memory_prediction_is_within_1_5x_of_the_measured_peak_on_large_work(
    tmp_path: Path, case: Case
) -> None:
    _run_case(tmp_path, case)


def test_within_rejects_a_prediction_off_by_more_than_the_tolerance() -> None:
    assert within(150, 100) and within(67, 100) and not within(151, 100) and not within(66, 100)
