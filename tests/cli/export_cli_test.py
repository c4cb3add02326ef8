"""``qcpp export`` and ``qcpp solve --method qubo`` from the command line."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from tests.cli.clirun import assert_one_line_error, run

SCEN = "examples/two_robots_4x4.toml"


@pytest.mark.parametrize("fmt", ["ising", "qubo", "lp", "mps", "bqm"])
def test_every_format_is_written(fmt: str, tmp_path: Path) -> None:
    if fmt == "bqm":
        pytest.importorskip("dimod")
    out = tmp_path / f"model.{fmt}"
    res = run("export", SCEN, "--format", fmt, "--out", str(out), "--json")
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)
    assert summary["format"] == fmt and summary["form"] == "per-robot" and summary["edge_variables"] == 48
    text = out.read_text()
    if fmt in ("ising", "qubo"):
        assert len(json.loads(text)["variables"]) == summary["variables"]


def test_paper_form_and_explicit_penalty(tmp_path: Path) -> None:
    out = tmp_path / "p.json"
    res = run("export", SCEN, "--format", "qubo", "--form", "paper", "--out", str(out))
    assert res.exit_code == 0 and "paper form, 48 variables" in res.stderr
    assert json.loads(out.read_text())["penalty"] is None
    res = run("export", SCEN, "-f", "qubo", "--penalty", "8", "-o", str(out))
    assert res.exit_code == 0 and json.loads(out.read_text())["penalty"] == 8.0


def test_standard_output() -> None:
    res = run("export", SCEN, "--format", "ising", "--out", "-")
    assert res.exit_code == 0
    assert json.loads(res.stdout)["convention"].startswith("E = offset")


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (["--format", "csv"], ["--format", "csv"]),
        (["--format", "qubo", "--form", "exact"], ["--form", "exact"]),
        (["--format", "qubo", "--form", "paper", "--penalty", "3"], ["--penalty", "per-robot only"]),
        (["--format", "qubo", "--penalty", "0"], ["--penalty", "positive"]),
        (["--format", "qubo", "--penalty", "nan"], ["--penalty", "positive"]),
        (["--format", "qubo", "--json"], ["--json", "--out"]),
    ],
)
def test_bad_options_are_one_line_errors(args: list[str], fragments: list[str], tmp_path: Path) -> None:
    out = tmp_path / "x.json"
    extra = [] if "--json" in args else ["--out", str(out)]
    res = run("export", SCEN, *args, *(["--out", "-"] if "--json" in args else extra))
    assert_one_line_error(res, *fragments)
    assert not out.exists()


def test_missing_folder_and_scenario(tmp_path: Path) -> None:
    res = run("export", SCEN, "--format", "qubo", "--out", str(tmp_path / "no" / "x"))
    assert_one_line_error(res, "does not exist")
    res = run("export", "no/such.toml", "--format", "qubo", "--out", str(tmp_path / "x"))
    assert_one_line_error(res, "no/such.toml")


def test_without_dimod_bqm_says_what_to_install_and_the_rest_still_works(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(sys.modules, "dimod", None)
    monkeypatch.setitem(sys.modules, "dwave.samplers", None)
    out = tmp_path / "m.json"
    assert_one_line_error(run("export", SCEN, "--format", "bqm", "--out", str(out)), "pip install 'qcpp[annealing]'")
    assert not out.exists()
    for fmt in ("ising", "qubo", "lp"):
        assert run("export", SCEN, "--format", fmt, "--out", str(out)).exit_code == 0
    assert_one_line_error(run("solve", SCEN, "--method", "qubo"), "the qubo method", "pip install 'qcpp[annealing]'")


def test_solve_qubo_finds_the_optimum_of_two_robots_4x4() -> None:
    pytest.importorskip("dwave.samplers")
    res = run("solve", SCEN, "--method", "qubo", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["method"] == "qubo" and out["cost"] == -2.0
    assert any("100 reads" in n for n in out["notes"])


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (["--method", "qubo", "--sampler", "anneal"], ["--sampler", "'anneal'", "tabu, sa"]),
        (["--method", "cpsat", "--sampler", "sa"], ["--sampler", "--method qubo only"]),
    ],
)
def test_bad_sampler_is_a_one_line_error(args: list[str], fragments: list[str]) -> None:
    assert_one_line_error(run("solve", SCEN, *args), *fragments)


def test_solve_qubo_with_simulated_annealing_answers_feasible_paths() -> None:
    pytest.importorskip("dwave.samplers")
    from qcpp.problem.paths import is_feasible, path_from_nodes
    from qcpp.problem.scenario_io import load_scenario

    res = run("solve", SCEN, "--method", "qubo", "--sampler", "sa", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    s = load_scenario(SCEN)
    masks = [path_from_nodes(s.grid, [tuple(n) for n in nodes]) for nodes in out["paths"]]
    assert all(is_feasible(s, r, m) for r, m in enumerate(masks))
    assert out["notes"][0].endswith(", sa") and any("100 reads" in n for n in out["notes"])
    default = json.loads(run("solve", SCEN, "--method", "qubo", "--json").stdout)
    assert default["notes"][0].endswith(", tabu")  # tabu stays the default


def test_the_written_line_fits_80_columns(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from qcpp.cli.app import app

    out = tmp_path / "a-rather-long-file-name.json"
    res = CliRunner().invoke(app, ["export", SCEN, "-f", "qubo", "-o", str(out)], env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    lines = res.stderr.strip().splitlines()
    assert len(lines) >= 2 and all(len(line) <= 80 or " " not in line for line in lines), lines
    assert " ".join(lines) == f"wrote {out}: qubo, per-robot form, 76 variables, 1112 interactions, penalty P = 11"


def test_help() -> None:
    from typer.testing import CliRunner

    from qcpp.cli.app import app

    res = CliRunner().invoke(app, ["export", "--help"], env={"COLUMNS": "200"})
    assert res.exit_code == 0
    for flag in ("--format", "--form", "--penalty", "--out", "--json", "--allow-large"):
        assert flag in res.stdout
    assert "qubo" in CliRunner().invoke(app, ["solve", "--help"], env={"COLUMNS": "200"}).stdout
