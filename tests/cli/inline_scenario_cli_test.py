"""Scenarios given inline (``--grid RxC --robots N --obstacle R,C --hard-obstacles``) are the scenarios of the
equivalent files, in ``estimate``, ``scenario`` and every command that reads one scenario (``compile``, ``solve``,
``simulate``, ``validate``, ``verify``, ``export``); ``estimate --format latex`` is a booktabs table."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import qcpp
from qcpp.estimators.tables import latex_header
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
    assert inline[0]["scenario"] == "custom" and default[0]["scenario"] == "default"
    assert hard[0]["data_qubits"] == default[0]["data_qubits"] - 2 * 4  # the obstacle's 4 edges leave each robot


def test_obstacles_apply_to_every_grid_of_a_sweep() -> None:
    rows = json.loads(ok("estimate", "--grid", "3x3..4x4", "--robots", "1..2", "--obstacle", "1,1",
                         "--hard-obstacles", "--json"))  # fmt: skip
    assert len(rows) == 8 and {r["scenario"] for r in rows} == {"custom"}
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
    assert ok("scenario", *args, "-o", "/dev/null") == ""  # a device is written to, not an unknown file type
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


THREE_BY_THREE_HARD = """
name = "3x3, 2 robot(s), 1 obstacle(s)"

[grid]
rows = 3
cols = 3
obstacles = [[1, 1]]

[[robots]]
start = [0, 0]
goal = [2, 2]

[[robots]]
start = [0, 2]
goal = [2, 0]

[objective]
obstacles = "hard"
"""
INLINE_HARD = ("--grid", "3x3", "--robots", "2", "--obstacle", "1,1", "--hard-obstacles")

# per command: its arguments after the scenario, and the JSON fields that differ by run (times)
SCENARIO_COMMANDS = {
    "solve": (("--method", "dfs", "--json"), ("seconds",)),
    "simulate": (("-p", "1", "--json"), ("seconds",)),
    "validate": (("--json",), ("seconds", "checks", "scenario")),
    "verify": (("--json",), ("seconds", "checks", "scenario")),
}


@pytest.mark.parametrize("command", sorted(SCENARIO_COMMANDS))
def test_every_scenario_command_reads_the_inline_flags_as_the_equivalent_file(command: str, tmp_path: Path) -> None:
    path = tmp_path / "hard.toml"
    path.write_text(THREE_BY_THREE_HARD)
    assert qcpp.grid_scenario(3, 3, robots=2, obstacles=[(1, 1)], hard_obstacles=True) == load_scenario(path)
    args, varying = SCENARIO_COMMANDS[command]
    inline = json.loads(ok(command, *INLINE_HARD, *args))
    from_file = json.loads(ok(command, str(path), *args))
    if "scenario" not in varying:  # the file's path, or the flags that give the scenario again
        assert from_file.pop("scenario") == str(path)
        assert inline.pop("scenario") == " ".join(INLINE_HARD)
    for key in varying:
        inline.pop(key, None)
        from_file.pop(key, None)
    assert inline == from_file


OWN_ENDPOINTS = ("--grid", "3x4", "--robot", "0,1:2,3", "--robot", "2,0:0,2", "--obstacle", "1,1")
"""Two robots with their own start and goal (not the default placement), given inline."""


@pytest.mark.parametrize("command", sorted(SCENARIO_COMMANDS))
def test_robots_given_one_by_one_are_the_scenario_the_api_builds(command: str, tmp_path: Path) -> None:
    """``--robot START:GOAL`` (repeated) is ``qcpp.grid_scenario(..., robots=[(start, goal), ...])`` in every
    command; the JSON's ``scenario`` gives the flags back."""
    path = tmp_path / "own.toml"
    qcpp.save_scenario(qcpp.grid_scenario(3, 4, robots=[((0, 1), (2, 3)), ((2, 0), (0, 2))], obstacles=[(1, 1)]),
                       path)  # fmt: skip
    args, varying = SCENARIO_COMMANDS[command]
    inline = json.loads(ok(command, *OWN_ENDPOINTS, *args))
    from_file = json.loads(ok(command, str(path), *args))
    if "scenario" not in varying:
        assert inline.pop("scenario") == " ".join(OWN_ENDPOINTS) and from_file.pop("scenario") == str(path)
    for key in varying:
        inline.pop(key, None)
        from_file.pop(key, None)
    assert inline == from_file


def test_robots_given_one_by_one_in_estimate_compile_and_scenario(tmp_path: Path) -> None:
    expected = qcpp.grid_scenario(3, 4, robots=[((0, 1), (2, 3)), ((2, 0), (0, 2))], obstacles=[(1, 1)])
    printed = tmp_path / "printed.toml"
    printed.write_text(ok("scenario", *OWN_ENDPOINTS))
    assert load_scenario(printed) == expected
    rows = json.loads(ok("estimate", *OWN_ENDPOINTS, "-p", "1..2", "--json"))
    assert rows == [qcpp.estimate(expected, p).to_dict() for p in (1, 2)]
    compiled = json.loads(ok("compile", *OWN_ENDPOINTS, "--json"))
    assert compiled["gates"] == json.loads(ok("compile", str(printed), "--json"))["gates"]
    # a range of grids: the same endpoints on each (every grid must hold them)
    rows = json.loads(ok("estimate", "--grid", "3x3..4x4", "--robot", "0,0:2,2", "--robot", "2,0:0,2", "--json"))
    assert [(r["rows"], r["cols"], r["robots"]) for r in rows] == [(3, 3, 2), (3, 4, 2), (4, 3, 2), (4, 4, 2)]


def test_export_inline_writes_the_file_of_the_equivalent_scenario(tmp_path: Path) -> None:
    path = tmp_path / "hard.toml"
    path.write_text(THREE_BY_THREE_HARD)
    summaries = []
    for name, scenario in (("inline.json", INLINE_HARD), ("file.json", (str(path),))):
        summaries.append(json.loads(ok("export", *scenario, "-f", "qubo", "-o", str(tmp_path / name), "--json")))
    assert (tmp_path / "inline.json").read_bytes() == (tmp_path / "file.json").read_bytes()
    assert summaries[0]["scenario"] == " ".join(INLINE_HARD) and summaries[1]["scenario"] == str(path)


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
        (("compile", "--grid", "3x3", "--obstacle", "7,1"), ("--obstacle 7,1:", "(7, 1)", "3x3 grid")),
        (("compile", "--grid", "3x3", "--obstacle", "0,0"),
         ("--obstacle 0,0:", "robot 0's start in the default placement of --robots 1", "--robot START:GOAL")),
        (("estimate", "--grid", "3x3", "--robots", "1..2", "--obstacle", "2,2"),
         ("--obstacle 2,2:", "robot 0's goal in the default placement of --robots 1..2")),
        (("compile", "--grid", "3x3", "--obstacle", "1,1", "--obstacle", "1,1"), ("--obstacle 1,1:", "listed twice")),
        (("estimate", "--grid", "3x3", "--obstacle", " 1,1", "--obstacle", "1,1"), ("--obstacle 1,1:", "listed twice")),
        (("compile", "--grid", "3x3", "--robot", "0,0:1,1", "--obstacle", "1,1"),
         ("--robot 0,0:1,1:", "goal (1, 1) is an obstacle")),
        (("compile", "--grid", "2x2", "--robots", "9"), ("robots", "fits 1 to 4 robots on a 2x2 grid")),
        (("estimate", "--grid", "3x3", "--obstacle", "3,0"), ("--obstacle 3,0:", "(3, 0)", "3x3 grid")),
        (("estimate", "--scenario", "examples/paper_3x3.toml", "--obstacle", "1,1"), ("--obstacle",)),
        (("scenario",), ("--grid",)),
        (("compile", "--robot", "0,0:2,2"), ("--robot", "applies with --grid only")),
        (("compile", "--grid", "3x3", "--robot", "0,0-2,2"), ("--robot", "expected START:GOAL", "'0,0-2,2'")),
        (("compile", "--grid", "3x3", "--robot", "0,0:2,2", "--robots", "1"), ("--robot", "do not give --robots")),
        (("compile", "--grid", "3x3", "--robot", "0,0:3,3"), ("--robot 0,0:3,3:", "goal (3, 3)", "3x3 grid")),
        (("solve", "--grid", "2x2", "--obstacle", "0,0", "--robot", "0,1:1,0", "--robot", "1,0:1,1",
          "--robot", "1,1:0,1", "--robot", "0,1:1,1"),
         ("error: --robot: 4 robots do not fit on the 3 free nodes",)),
        (("scenario", "--grid", "3x3", "--robot", "1,1:1,1"), ("--robot 1,1:1,1:", "goal equals the start")),
        (("compile", "--grid", "3x3", "--robot", "0,0:2,2", "--robot", "0,0:1,2"),
         ("--robot 0,0:1,2:", "start (0, 0) is already robot 0's start")),
        (("estimate", "--grid", "3x3..4x4", "--robot", "0,0:3,3"), ("--robot 0,0:3,3:", "goal (3, 3)", "3x3 grid")),
        (("estimate", "--grid", "3x3", "--robot", "0,0:2,2", "--robots", "1"), ("--robot", "do not give --robots")),
        (("estimate", "--scenario", "examples/paper_3x3.toml", "--robot", "0,0:2,2"), ("--robot",)),
        *(((c,), ("give a scenario file", "--grid")) for c in ("solve", "simulate", "validate", "verify")),
        *(((c, "--hard-obstacles"), ("--hard-obstacles", "applies with --grid only"))
          for c in ("solve", "simulate", "validate", "verify")),
        (("verify", "examples/paper_3x3.toml", "--grid", "3x3"), ("--grid gives the scenario",)),
        (("solve", "--grid", "3x3", "--obstacle", "9,9"), ("--obstacle 9,9:", "(9, 9)", "3x3 grid")),
        (("export", "-f", "qubo", "-o", "x.json"), ("give a scenario file", "--grid")),
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
    by_header = {latex_header(k): k for k in rows[0]}  # readable headers with units, one per column
    header = [by_header[h] for h in lines[3].removesuffix(r" \\").split(" & ")]
    assert {"rows", "cx", "paper_cx"} <= set(header) and lines[3].startswith("rows & cols & robots & $p$ & qubits")
    body = [line.removesuffix(r" \\").split(" & ") for line in lines[5:-2]]
    assert len(body) == len(rows) == 4
    for cells, row in zip(body, rows, strict=True):
        for name, cell in zip(header, cells, strict=True):
            value = row[name]
            if isinstance(value, int) and not isinstance(value, bool):  # thousands grouped in plain LaTeX
                assert cell.replace("{,}", "") == str(value) and (value < 1000) == ("{,}" not in cell), cell
            else:
                assert cell == (f"{value:.4g}" if isinstance(value, float) else str(value))
    for name, align in zip(header, spec.group(1), strict=True):
        assert align == ("l" if isinstance(rows[0][name], str) else "r"), name  # numbers right-aligned
    chosen = ok(*args, "--format", "latex", "--columns", "rows,cx,ratio_cx").splitlines()
    assert chosen[1] == r"\begin{tabular}{rrr}" and chosen[3] == r"rows & CNOTs & CNOTs / paper \\"


def test_formulas_come_as_latex_too() -> None:
    text = ok("estimate", "--formula", "--format", "latex")
    assert r"\begin{align*}" in text and r"\mathrm{data\_qubits} &=" in text


def test_estimate_takes_the_scenario_file_as_its_argument_too() -> None:
    """``qcpp estimate FILE`` is ``qcpp estimate --scenario FILE``, as every other command takes its file; both
    at once is refused."""
    positional = json.loads(ok("estimate", "examples/two_robots_4x4.toml", "-p", "1..2", "--json"))
    flagged = json.loads(ok("estimate", "--scenario", "examples/two_robots_4x4.toml", "-p", "1..2", "--json"))
    for row in (*positional, *flagged):
        row.pop("seconds", None)
    assert positional == flagged and len(positional) == 2
    assert_one_line_error(run("estimate", "examples/two_robots_4x4.toml", "--scenario", "examples/paper_3x3.toml"),
                          "--scenario", "two_robots_4x4.toml", "given already")  # fmt: skip
    assert_one_line_error(run("estimate", "examples/two_robots_4x4.toml", "--grid", "3x3"), "--grid")


def test_scenario_draw_shows_the_field_on_stderr_and_keeps_stdout_a_file() -> None:
    args = ("scenario", "--grid", "4x5", "--robot", "0,0:3,4", "--robot", "3,0:0,4", "--obstacle", "1,1",
            "--obstacle", "2,3")  # fmt: skip
    drawn, plain = run(*args, "--draw"), run(*args)
    assert drawn.exit_code == plain.exit_code == 0
    assert drawn.stdout == plain.stdout and plain.stderr == ""
    rows = [line for line in drawn.stderr.splitlines()[:7] if line]
    assert rows == ["S   .   .   .   G", ".   #   .   .   .", ".   .   .   #   .", "S   .   .   .   G"]
    assert "robot 0: (0, 0) -> (3, 4)" in drawn.stderr and "robot 1: (3, 0) -> (0, 4)" in drawn.stderr


@pytest.mark.parametrize("command", ["compile", "verify", "simulate", "validate"])
@pytest.mark.parametrize(
    ("flag", "value", "named"),
    [("-p", "1..3", "-p/--layers"), ("-p", "1,2", "-p/--layers"), ("--robots", "1..3", "--robots"),
     ("--robots", "1,4,8", "--robots")],
)  # fmt: skip
def test_a_range_for_a_single_circuit_command_is_one_line(command: str, flag: str, value: str, named: str) -> None:
    """``qcpp estimate`` takes ranges and lists; a command that builds one circuit says so, naming the flag."""
    robots = [] if flag == "--robots" else ["--robots", "1"]  # given once: a repeated option is refused first
    res = run(command, "--grid", "4x4", *robots, flag, value)
    assert res.exit_code == 2 and res.stdout == ""
    assert res.stderr.strip() == (
        f"error: {named}: one value only, got {value!r}: this command builds one circuit; ranges (A..B) and comma "
        f"lists are for qcpp estimate (see 'qcpp {command} --help')"
    )


def test_a_grid_range_for_compile_names_estimate() -> None:
    res = run("compile", "--grid", "3x3..5x5")
    assert res.exit_code == 2
    assert "one grid only: ranges (A..B) and comma lists are for qcpp estimate" in res.stderr
