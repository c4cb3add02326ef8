"""``qcpp solve`` at real field sizes: ``--time-limit`` on anneal and genetic, ``--iterations`` / ``--generations``,
CP-SAT's ``--workers`` and relative gap, and Ctrl-C answering with the best found so far.

No test depends on timing: a limit of a nanosecond has passed before the first step can start, and the Ctrl-C here
is raised from the solver's own progress call (a known step), in-process; the real signals on a real process are in
:mod:`tests.cli.interrupt_test`.
"""

from __future__ import annotations

import dataclasses
import json
import signal
import threading
from pathlib import Path

import pytest

from qcpp.cli import interrupt
from qcpp.cli.commands import solve as solve_cmd
from qcpp.cli.progress import Progress
from qcpp.problem.cost import cost_parts
from qcpp.problem.paths import is_feasible, path_from_nodes
from qcpp.problem.scenario_io import load_scenario

from .clirun import assert_one_line_error, run

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
FILE = str(EXAMPLES / "two_robots_4x4.toml")


def assert_valid_paths(out: dict[str, object]) -> None:
    s = load_scenario(FILE)
    masks = [path_from_nodes(s.grid, [tuple(n) for n in nodes]) for nodes in out["paths"]]  # type: ignore[attr-defined]
    assert all(is_feasible(s, r, m) for r, m in enumerate(masks))
    assert out["cost"] == pytest.approx(cost_parts(s, masks).total)


@pytest.mark.parametrize("method", ["anneal", "genetic"])
def test_a_time_limit_stops_with_the_best_so_far_and_says_so(method: str) -> None:
    res = run("solve", FILE, "-m", method, "--time-limit", "1e-9", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["stopped"] == "time limit" and any(n.startswith("stopped at the time limit") for n in out["notes"])
    assert_valid_paths(out)
    text = run("solve", FILE, "-m", method, "--time-limit", "1e-9")
    assert text.exit_code == 0 and f"{method}: stopped at the time limit: the best found so far" in text.stdout


def test_iterations_and_generations_set_the_length_of_the_run() -> None:
    a = json.loads(run("solve", FILE, "-m", "anneal", "--iterations", "60", "--json").stdout)
    g = json.loads(run("solve", FILE, "-m", "genetic", "--generations", "3", "--json").stdout)
    restarts = int(a["notes"][0].split()[0])  # "1 restart(s) (one per combination ...)"
    assert a["trace_length"] == 60 * restarts and g["trace_length"] == 3
    assert "stopped" not in a and "stopped" not in g


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("-m", "dfs", "--time-limit", "5"), "--time-limit: applies to --method cpsat, anneal or genetic only"),
        (("-m", "anneal", "--time-limit", "0"), "--time-limit: expected a positive number"),
        (("-m", "anneal", "--workers", "2"), "--workers: applies to --method cpsat only"),
        (("-m", "cpsat", "--workers", "0"), "--workers: expected a positive integer, got 0"),
        (("-m", "anneal", "--iterations", "0"), "--iterations: expected a positive integer"),
        (("-m", "anneal", "--generations", "5"), "--generations: applies to --method genetic only"),
    ],
)
def test_bad_limits_are_one_line_and_exit_2(args: tuple[str, ...], fragment: str) -> None:
    assert_one_line_error(run("solve", FILE, *args), fragment)


@pytest.mark.parametrize(("args", "workers"), [((), 1), (("--workers", "3"), 3)])
def test_workers_reach_or_tools(monkeypatch: pytest.MonkeyPatch, args: tuple[str, ...], workers: int) -> None:
    from ortools.sat.python import cp_model

    seen: list[int] = []
    solve = cp_model.CpSolver.solve

    def spy(self: cp_model.CpSolver, *a: object, **k: object) -> object:
        seen.append(self.parameters.num_workers)
        return solve(self, *a, **k)

    monkeypatch.setattr(cp_model.CpSolver, "solve", spy)
    res = run("solve", str(EXAMPLES / "paper_3x3.toml"), "-m", "cpsat", *args)
    assert res.exit_code == 0, res.output
    assert seen == [workers] and f"{workers} worker(s)" in res.stdout


def test_an_unproven_answer_prints_the_relative_gap(capsys: pytest.CaptureFixture[str]) -> None:
    from qcpp.problem.solvers.cpsat import cpsat

    s = load_scenario(FILE)
    res = cpsat(s)
    unproven = dataclasses.replace(res, proven_optimal=False, bound=res.bound - 8.0, status="FEASIBLE")
    solve_cmd._print_result(s, unproven.solution, "cpsat", None, unproven, "gibbs", False, FILE)
    gap = 8.0 / max(1.0, abs(res.solution.cost.total))
    assert f"gap 8 = {100 * gap:.3g}% of |cost| (FEASIBLE)" in capsys.readouterr().out


def test_the_json_gives_the_relative_gap() -> None:
    out = json.loads(run("solve", FILE, "-m", "cpsat", "--json").stdout)
    assert out["proven_optimal"] and out["relative_gap"] == 0.0


class _InterruptingProgress(Progress):
    """The CLI's progress, raising SIGINT in-process at the solver's first progress call (a known step)."""

    def update(self, done: int, total: int | None = None) -> None:  # type: ignore[override]
        super().update(done, total)
        if done == self.interrupt_at:
            signal.raise_signal(signal.SIGINT)

    interrupt_at = 0


@pytest.mark.parametrize(("method", "args", "at"), [("anneal", ("--iterations", "1000"), 10),
                                                      ("genetic", ("--generations", "50"), 1)])  # fmt: skip
def test_ctrl_c_prints_the_best_so_far_then_interrupted(monkeypatch: pytest.MonkeyPatch, method: str,
                                                        args: tuple[str, ...], at: int) -> None:  # fmt: skip
    """As the real command line: the signal handling installed, the first SIGINT a stop request; the answer is
    printed whole, then ``interrupted`` and exit 130."""
    monkeypatch.setattr(interrupt, "_installed", True)
    monkeypatch.setattr(interrupt, "_requested", [])
    monkeypatch.setattr(interrupt, "_reported", threading.Event())
    monkeypatch.setattr(_InterruptingProgress, "interrupt_at", at)
    monkeypatch.setattr(solve_cmd, "Progress", _InterruptingProgress)
    previous = signal.getsignal(signal.SIGINT)
    res = run("solve", FILE, "-m", method, *args, "--json")
    assert signal.getsignal(signal.SIGINT) is previous  # the block put the handler back
    assert res.exit_code == 130, res.output
    assert res.stderr.strip().splitlines()[-1] == "interrupted" and "Traceback" not in res.output
    out = json.loads(res.stdout)
    assert out["stopped"] == "interrupted" and out["trace_length"] == at
    assert_valid_paths(out)
