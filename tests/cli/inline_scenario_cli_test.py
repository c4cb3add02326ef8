"""Scenarios given inline (``--grid RxC --robots N --obstacle R,C --hard-obstacles``) are the scenarios of the
equivalent files, in ``estimate``, ``compile`` and ``scenario``; ``estimate --format latex`` is a booktabs table."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import qcpp
from qcpp.problem.scenario_io import load_scenario

from .clirun import assert_one_line_error, run

FIVE_BY_FIVE = """
[grid]
rows = 5
cols = 5
obstacles = [[2, 1]]

[[robots]]
start = [0, 0]
goal = [4, 4]

[[robots]]
start = [0, 4]
goal = [4, 0]
"""


def ok(*args: str) -> str:
    res = run(*args)
    assert res.exit_code == 0, res.output
    return res.stdout


def test_estimate_with_an_obstacle_equals_the_estimate_of_the_equivalent_toml(tmp_path: Path) -> None:
    path = tmp_path / "five.toml"
    path.write_text(FIVE_BY_FIVE)
    inline = json.loads(ok("estimate", "--grid", "5x5", "--robots", "2", "--obstacle", "2,1", "--json"))
    from_file = json.loads(ok("estimate", "--scenario", str(path), "--json"))
    assert inline == from_file
    default = json.loads(ok("estimate", "--grid", "5x5", "--robots", "2", "--json"))
    hard = json.loads(ok("estimate", "--grid", "5x5", "--robots", "2", "--obstacle", "2,1", "--hard-obstacles",
                         "--json"))  # fmt: skip
    assert inline[0]["scenario"] == "file" and default[0]["scenario"] == "default"
    assert hard[0]["data_qubits"] == default[0]["data_qubits"] - 2 * 4  # the obstacle's 4 edges leave each robot


def test_obstacles_apply_to_every_grid_of_a_sweep() -> None:
    rows = json.loads(ok("estimate", "--grid", "3x3..4x4", "--robots", "1..2", "--obstacle", "1,1",
                         "--hard-obstacles", "--json"))  # fmt: skip
    assert len(rows) == 8 and {r["scenario"] for r in rows} == {"file"}
    for row in rows:
        s = qcpp.grid_scenario(row["rows"], row["cols"], robots=row["robots"], obstacles=[(1, 1)], hard_obstacles=True)
        assert qcpp.estimate(s).to_dict() == row


def test_the_scenario_command_prints_and_writes_what_the_inline_flags_build(tmp_path: Path) -> None:
    args = ("--grid", "5x5", "--robots", "2", "--obstacle", "2,1")
    expected = qcpp.grid_scenario(5, 5, robots=2, obstacles=[(2, 1)])
    printed = tmp_path / "printed.toml"
    printed.write_text(ok("scenario", *args))
    assert load_scenario(printed) == expected
    assert "start = [0, 0]" in printed.read_text()  # the default placement, visible
    ok("scenario", *args, "-o", str(tmp_path / "written.json"))
    assert load_scenario(tmp_path / "written.json") == expected
    as_json = tmp_path / "printed.json"
    as_json.write_text(ok("scenario", *args, "--json"))
    assert load_scenario(as_json) == expected
    inline = json.loads(ok("estimate", *args, "--json"))
    assert json.loads(ok("estimate", "--scenario", str(printed), "--json")) == inline


def test_compile_inline_equals_compile_of_the_file(tmp_path: Path) -> None:
    path = tmp_path / "five.toml"
    path.write_text(FIVE_BY_FIVE)
    inline = json.loads(ok("compile", "--grid", "5x5", "--robots", "2", "--obstacle", "2,1", "--lowered", "--json"))
    from_file = json.loads(ok("compile", str(path), "--lowered", "--json"))
    inline.pop("seconds")
    from_file.pop("seconds")
    assert inline == from_file


def test_compile_inline_takes_bindings_after_bind() -> None:
    summary = json.loads(ok("compile", "--grid", "3x3", "--bind", "gamma_0=0.3", "beta_0=0.7", "--json"))
    assert summary["symbols"] == []


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (("compile",), ("give a scenario file", "--grid")),
        (("compile", "--robots", "2"), ("--robots", "applies with --grid only")),
        (("compile", "examples/paper_3x3.toml", "--obstacle", "1,1"), ("--obstacle", "applies with --grid only")),
        (("compile", "examples/paper_3x3.toml", "--grid", "3x3"), ("--grid gives the scenario",)),
        (("compile", "--grid", "3by3"), ("--grid", "expected ROWSxCOLS", "'3by3'")),
        (("compile", "--grid", "3x3", "--obstacle", "1;1"), ("--obstacle", "expected ROW,COL", "'1;1'")),
        (("compile", "--grid", "3x3", "--obstacle", "7,1"), ("grid.obstacles[0]", "(7, 1)", "3x3 grid")),
        (("compile", "--grid", "3x3", "--obstacle", "0,0"), ("robots[0].start", "(0, 0) is an obstacle")),
        (("compile", "--grid", "2x2", "--robots", "9"), ("robots", "fits 1 to 4 robots on a 2x2 grid")),
        (("estimate", "--grid", "3x3", "--obstacle", "3,0"), ("grid.obstacles[0]", "(3, 0)", "3x3 grid")),
        (("estimate", "--scenario", "examples/paper_3x3.toml", "--obstacle", "1,1"), ("--obstacle",)),
        (("scenario",), ("--grid",)),
        (("scenario", "--grid", "3x3", "-o", "x.yaml"), ("x.yaml", "unknown file type")),
    ],
)
def test_bad_inline_scenarios_are_one_line(args: tuple[str, ...], fragments: tuple[str, ...]) -> None:
    assert_one_line_error(run(*args), *fragments)


def test_estimate_latex_is_a_booktabs_table_of_the_json_values() -> None:
    args = ("estimate", "--grid", "3x3..3x4", "--robots", "1", "-p", "1..2", "--compare", "paper")
    text = ok(*args, "--format", "latex")
    rows = json.loads(ok(*args, "--json"))
    lines = text.splitlines()
    spec = re.fullmatch(r"\\begin\{tabular\}\{([rl]+)\}", lines[1])
    assert spec is not None
    assert lines[2] == r"\toprule" and lines[4] == r"\midrule" and lines[-2:] == [r"\bottomrule", r"\end{tabular}"]
    header = [h.replace(r"\_", "_") for h in lines[3].removesuffix(r" \\").split(" & ")]
    body = [line.removesuffix(r" \\").split(" & ") for line in lines[5:-2]]
    assert len(body) == len(rows) == 4
    for cells, row in zip(body, rows, strict=True):
        for name, cell in zip(header, cells, strict=True):
            value = row[name]
            assert cell == (f"{value:.4g}" if isinstance(value, float) else str(value))
    for name, align in zip(header, spec.group(1), strict=True):
        assert align == ("l" if isinstance(rows[0][name], str) else "r"), name  # numbers right-aligned
    chosen = ok(*args, "--format", "latex", "--columns", "rows,cx,ratio_cx").splitlines()
    assert chosen[1] == r"\begin{tabular}{rrr}" and chosen[3] == r"rows & cx & ratio\_cx \\"


def test_formulas_come_as_latex_too() -> None:
    text = ok("estimate", "--formula", "--format", "latex")
    assert r"\begin{align*}" in text and r"\mathrm{data\_qubits} &=" in text
