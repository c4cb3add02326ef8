"""``qcpp`` CLI skeleton and ``qcpp solve``: JSON output, drawings, plots, and one-line errors (exit 2)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from qcpp.cli.app import QcppTyper, app
from qcpp.cli.commands.solve import SOLVE_METHODS
from qcpp.cli.render import render_ascii
from qcpp.problem.cost import cost_parts
from qcpp.problem.errors import ScenarioError
from qcpp.problem.paths import is_feasible, path_from_nodes
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import dfs

from .clirun import assert_one_line_error, run

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("example", "method"),
    [("paper_3x3.toml", "dfs"), ("paper_3x3.toml", "anneal"), ("paper_3x3.toml", "genetic"),
     ("two_robots_4x4.toml", "dfs"), ("two_robots_4x4.toml", "anneal"), ("two_robots_4x4.toml", "genetic")],
)
def test_solve_json(example: str, method: str) -> None:
    res = run("solve", str(EXAMPLES / example), "--method", method, "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)  # stdout is exactly one JSON object (no progress, no drawing)
    for key in ("method", "paths", "cost", "cost_parts", "seconds", "evaluated"):
        assert key in out
    assert out["method"] == method and set(out["cost_parts"]) == {"c1", "c2", "c3"}
    s = load_scenario(EXAMPLES / example)
    masks = []
    for r, (nodes, rb) in enumerate(zip(out["paths"], s.robots, strict=True)):
        nodes = [tuple(n) for n in nodes]
        assert nodes[0] == rb.start and nodes[-1] == rb.goal
        mask = path_from_nodes(s.grid, nodes)
        assert is_feasible(s, r, mask) and mask.bit_count() == len(nodes) - 1
        masks.append(mask)
    parts = cost_parts(s, masks)
    assert out["cost"] == pytest.approx(parts.total)
    assert out["cost_parts"] == pytest.approx({"c1": parts.c1, "c2": parts.c2, "c3": parts.c3})
    assert out["cost"] == pytest.approx(dfs(s).cost.total)  # the defaults find the optimum on these examples
    if method == "dfs":
        assert out["evaluated"] == out["paths_per_robot"][0] ** len(s.robots)
    else:
        assert out["seed"] == 0 and out["rule"] == "exact" and out["trace_length"] > 0


def test_solve_human_output_draws_the_paths() -> None:
    path = EXAMPLES / "two_robots_4x4.toml"
    res = run("solve", str(path), "-m", "dfs")
    assert res.exit_code == 0, res.output
    s = load_scenario(path)
    assert render_ascii(s, dfs(s).paths) in res.stdout
    assert "total" in res.stdout and "c3 node degrees" in res.stdout and "method dfs" in res.stdout


def test_plot_writes_png_and_no_temp_file(tmp_path: Path) -> None:
    png, trace = tmp_path / "paths.png", tmp_path / "trace.png"
    res = run("solve", str(EXAMPLES / "paper_3x3.toml"), "-m", "anneal", "--plot", str(png),
              "--plot-trace", str(trace), "--json")
    assert res.exit_code == 0, res.output
    json.loads(res.stdout)
    assert png.read_bytes()[:8] == PNG and trace.read_bytes()[:8] == PNG
    assert sorted(p.name for p in tmp_path.iterdir()) == ["paths.png", "trace.png"]


def test_bad_scenario_names_the_field(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text('[grid]\nrows = 3\ncols = 3\n\n[[robots]]\nstart = [0, 0]\ngoal = [5, 0]\n')
    assert_one_line_error(run("solve", str(bad)), "robots[0].goal", "outside")
    broken = tmp_path / "broken.toml"
    broken.write_text("[grid\nrows = 3\n")
    assert_one_line_error(run("solve", str(broken), "--json"), "broken.toml")


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("solve", "/no/such/file.toml"), "cannot read"),
        (("solve", str(EXAMPLES / "paper_3x3.toml"), "--method", "magic"), "--method"),
        (("solve", str(EXAMPLES / "paper_3x3.toml"), "--rule", "fast"), "--rule"),
        (("solve", str(EXAMPLES / "paper_3x3.toml"), "-m", "dfs", "--plot-trace", "t.png"), "trace"),
        (("solve", str(EXAMPLES / "paper_3x3.toml"), "-m", "dfs", "--plot", "/no/such/dir/p.png"),
         "folder /no/such/dir does not exist"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(args: tuple[str, ...], fragment: str) -> None:
    assert_one_line_error(run(*args), fragment)


def test_method_choices_follow_the_registry(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = []

    def fake(scenario, *, seed, rule, progress):  # type: ignore[no-untyped-def]
        calls.append((seed, rule))
        return SOLVE_METHODS["dfs"](scenario, seed=seed, rule=rule, progress=progress)

    monkeypatch.setitem(SOLVE_METHODS, "fake", fake)
    res = run("solve", str(EXAMPLES / "paper_3x3.toml"), "-m", "fake", "--seed", "9", "--rule", "paper", "--json")
    assert res.exit_code == 0, res.output
    assert calls == [(9, "paper")]


def test_every_registered_command_gets_the_error_handler() -> None:
    demo = QcppTyper()

    @demo.command("boom")
    def boom(kind: str) -> None:
        raise {"scenario": ScenarioError("grid.rows", "bad"), "value": ValueError("two\nlines"),
               "os": FileNotFoundError(2, "No such file or directory", "x.png"), "bug": RuntimeError("bug"),
               "memory": MemoryError()}[kind]

    @demo.callback()
    def root() -> None:
        """demo"""

    runner = CliRunner()
    assert_one_line_error(runner.invoke(demo, ["boom", "scenario"]), "grid.rows: bad")
    assert_one_line_error(runner.invoke(demo, ["boom", "value"]), "two lines")
    assert_one_line_error(runner.invoke(demo, ["boom", "os"]), "x.png")
    assert_one_line_error(runner.invoke(demo, ["boom", "memory"]), "out of memory")
    assert_one_line_error(runner.invoke(demo, ["boom", "--bogus"]), "No such option: --bogus")
    res = runner.invoke(demo, ["boom", "bug"], env={"QCPP_DEBUG": ""})  # a bug is not an input error: exit 1
    assert (res.exit_code, res.stderr) == (1, "error: internal error: RuntimeError: bug (set QCPP_DEBUG=1 for the "
                                              "traceback; please report it)\n")
    res = runner.invoke(demo, ["boom", "bug"], env={"QCPP_DEBUG": "1"})  # the traceback, for a bug report
    assert res.exit_code == 1 and isinstance(res.exception, RuntimeError)
    assert isinstance(demo, typer.Typer)


def test_all_commands_registered_and_help() -> None:
    names = {c.name for c in app.registered_commands}
    assert {"solve", "compile", "estimate"} <= names
    res = run("solve", "--help")
    assert res.exit_code == 0 and "--method" in res.stdout and "--json" in res.stdout


def test_python_dash_m_entry_point() -> None:
    res = subprocess.run([sys.executable, "-m", "qcpp", "--version"], capture_output=True, text=True, check=False)
    assert res.returncode == 0 and res.stdout.startswith("qcpp ")


@pytest.mark.parametrize(
    ("args", "flag"),
    [
        (["estimate", "--grid", "12x20", "--grid", "20x30"], "--grid"),
        (["estimate", "--scenario", str(EXAMPLES / "paper_3x3.toml"), "--scenario",
          str(EXAMPLES / "two_robots_4x4.toml")], "--scenario"),
        (["estimate", "-p", "1", "--layers", "2"], "-p/--layers"),
        (["compile", str(EXAMPLES / "paper_3x3.toml"), "-p", "1", "-p", "2"], "-p/--layers"),
        (["validate", str(EXAMPLES / "paper_3x3.toml"), "-p", "1", "-p", "2"], "-p/--layers"),
        (["verify", str(EXAMPLES / "paper_3x3.toml"), "-p", "1", "-p", "2"], "-p/--layers"),
        (["solve", str(EXAMPLES / "paper_3x3.toml"), "--method", "dfs", "--method", "cpsat"], "--method/-m"),
    ],
)  # fmt: skip
def test_an_option_of_one_value_given_twice_is_refused_not_read_as_its_last(args: list[str], flag: str) -> None:
    """Click keeps the last of a repeated option: a sweep meant over two grids or two files would silently be of
    one. One line, exit 2, naming the option."""
    assert_one_line_error(run(*args), f"{flag}: given twice; give it once")


def test_options_that_collect_their_values_and_repeated_flags_are_still_accepted() -> None:
    res = run("estimate", "--grid", "3x3", "--robot", "0,0:2,2", "--robot", "0,2:2,0", "--wide", "--wide", "--json")
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)[0]["robots"] == 2
