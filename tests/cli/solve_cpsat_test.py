"""``qcpp solve --method cpsat``: the common keys plus the proof fields, --time-limit, the text output, errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from qcpp.problem.cost import cost_parts
from qcpp.problem.paths import is_feasible, path_from_nodes
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import dfs

from .clirun import assert_one_line_error, run

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("example", ["paper_3x3.toml", "two_robots_4x4.toml", "obstacles_hard_4x4.toml"])
def test_json_proves_the_dfs_optimum(example: str) -> None:
    res = run("solve", str(EXAMPLES / example), "--method", "cpsat", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    for key in ("method", "paths", "cost", "cost_parts", "seconds", "proven_optimal", "bound", "gap", "status"):
        assert key in out
    s = load_scenario(EXAMPLES / example)
    masks = [path_from_nodes(s.grid, [tuple(n) for n in nodes]) for nodes in out["paths"]]
    assert all(is_feasible(s, r, m) for r, m in enumerate(masks))
    assert out["cost"] == pytest.approx(cost_parts(s, masks).total)
    assert out["method"] == "cpsat" and out["proven_optimal"] is True and out["status"] == "OPTIMAL"
    assert out["cost"] == pytest.approx(dfs(s).cost.total) == pytest.approx(out["bound"]) and out["gap"] == 0


def test_time_limit_reports_a_bound() -> None:
    # two robots on 5x5 (optimum -16 by exhaustive search) do not close in 0.1 s
    res = run("solve", str(EXAMPLES / "two_robots_5x5.toml"), "-m", "cpsat", "--time-limit", "0.1", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["cost"] >= -16
    if out["proven_optimal"]:
        assert out["cost"] == -16
    if out["bound"] is not None:  # null when CP-SAT stopped before its first solution
        assert out["bound"] <= -16 and out["gap"] == pytest.approx(out["cost"] - out["bound"])
        assert out["relative_gap"] == pytest.approx(out["gap"] / max(1.0, abs(out["cost"])))


def test_text_says_whether_it_is_proven() -> None:
    res = run("solve", str(EXAMPLES / "paper_3x3.toml"), "-m", "cpsat")
    assert res.exit_code == 0, res.output
    assert "method cpsat" in res.stdout and "cpsat: proven optimal (OPTIMAL)" in res.stdout


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("-m", "dfs", "--time-limit", "5"), "--time-limit: applies to --method cpsat, anneal or genetic only"),
        (("-m", "cpsat", "--time-limit", "0"), "--time-limit: expected a positive number"),
        (("-m", "cpsat", "--time-limit", "-3"), "--time-limit"),
        (("-m", "cpsat", "--time-limit", "inf"), "--time-limit"),
        (("-m", "cpsat", "-p", "2"), "-p: applies to --method qaoa only"),
    ],
)
def test_bad_options_are_one_line_and_exit_2(args: tuple[str, ...], fragment: str) -> None:
    assert_one_line_error(run("solve", str(EXAMPLES / "paper_3x3.toml"), *args), fragment)


def test_weights_that_are_not_exact_rationals_are_a_clean_error(tmp_path: Path) -> None:
    bad = tmp_path / "irrational.toml"
    bad.write_text('[grid]\nrows = 3\ncols = 3\n\n[[robots]]\nstart = [0, 0]\ngoal = [2, 2]\n\n'
                   "[objective]\nalpha = [0.30000000000000004, 1.0, 1.0]\n")
    assert_one_line_error(run("solve", str(bad), "-m", "cpsat"), "0.30000000000000004", "CP-SAT")
