"""``qcpp solve --method qaoa``: the solver keys plus QAOA's, the drawing and trace, the trace plot, errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from qcpp.cli.commands.solve import SOLVE_METHODS, objective_line, sparkline
from qcpp.cli.render import render_ascii
from qcpp.estimators.tables import terminal_width
from qcpp.problem.paths import path_from_nodes
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import dfs
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.qaoa_solver import solve_qaoa

from .clirun import assert_one_line_error, run

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
PAPER = str(EXAMPLES / "paper_3x3.toml")
PNG = b"\x89PNG\r\n\x1a\n"


def test_the_notes_fit_the_terminal() -> None:
    """The notes (a QAOA run's are 200+ characters) wrap at spaces to ``COLUMNS``, every word kept."""
    from typer.testing import CliRunner

    from qcpp.cli.app import app

    args = ["solve", "--grid", "3x3", "--robots", "2", "-m", "qaoa", "-p", "2"]
    res = CliRunner().invoke(app, args, env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    lines = res.stdout.splitlines()
    first = next(i for i, line in enumerate(lines) if line.startswith("note: p=2, "))
    notes = lines[first:]
    assert len(notes) > 2 and all(len(line) <= 80 for line in notes), notes
    text = " ".join(notes)
    assert "shots at " in text and "per estimate note: <C> " in text and text.endswith(tuple("0123456789"))


def test_the_probability_lines_fit_80_columns() -> None:
    from typer.testing import CliRunner

    from qcpp.cli.app import app

    res = CliRunner().invoke(app, ["solve", PAPER, "-m", "qaoa", "--maxiter", "20"], env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    lines = [line for line in res.stdout.splitlines() if line.startswith(("most probable", "probability of"))]
    assert [line.split(":")[0] for line in lines] == ["most probable assignment (drawn above)",
                                                      "probability of an optimal assignment"]
    assert all(len(line) <= 80 for line in lines), lines


def test_json_has_the_common_keys_and_the_qaoa_ones() -> None:
    res = run("solve", PAPER, "--method", "qaoa", "-p", "2", "--optimizer", "lbfgsb", "--seed", "3", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    for key in ("method", "paths", "cost", "cost_parts", "seconds", "probability", "p", "angles", "trace"):
        assert key in out
    assert out["method"] == "qaoa" and out["p"] == 2 and len(out["angles"]) == 4
    assert out["optimizer"] == "lbfgsb" and out["trace_length"] == len(out["trace"])
    s = load_scenario(PAPER)
    mask = path_from_nodes(s.grid, [tuple(n) for n in out["paths"][0]])
    assert out["cost"] == dfs(s).cost.total  # the paper scenario: the most probable path is the optimum
    q = SubspaceQAOA(s)
    assert out["probability"] == pytest.approx(float(q.probabilities(out["angles"])[q.index_of([mask])]))
    assert out["expectation"] == pytest.approx(q.expectation(out["angles"]))
    assert out["objective"] == "gibbs" and out["evaluations"] >= out["trace_length"]
    direct = solve_qaoa(s, p=2, optimizer="lbfgsb", seed=3)
    assert out["angles"] == list(direct.angles)  # the CLI is the library call


def test_text_draws_the_assignment_and_the_trace() -> None:
    res = run("solve", PAPER, "--method", "qaoa", "--maxiter", "40")
    assert res.exit_code == 0, res.output
    s = load_scenario(PAPER)
    sol = solve_qaoa(s, maxiter=40)
    assert render_ascii(s, sol.solution.paths, legend=False) in res.stdout
    assert f"probability {sol.probability:.4g}" in res.stdout
    assert objective_line("gibbs", sol.trace, terminal_width()) in res.stdout.splitlines()
    assert "angles [g0, b0, ...]" in res.stdout


def test_the_objective_line_fits_the_terminal_and_keeps_its_first_and_last_values() -> None:
    from typer.testing import CliRunner

    from qcpp.cli.app import app

    args = ["solve", PAPER, "-m", "qaoa", "-p", "2", "--optimizer", "cobyla", "--maxiter", "100"]
    trace = json.loads(CliRunner().invoke(app, [*args, "--json"]).stdout)["trace"]
    assert len(trace) > 60  # more iterations than the widest sparkline has bars
    head, last = f"gibbs objective per iteration: {trace[0]:.6g} ", f" {trace[-1]:.6g}"
    for columns in (50, 60, 80, 200):
        res = CliRunner().invoke(app, args, env={"COLUMNS": str(columns)})
        assert res.exit_code == 0, res.output
        line = next(line for line in res.stdout.splitlines() if line.startswith("gibbs objective per iteration: "))
        assert len(line) <= columns and line.startswith(head) and line.endswith(last), (columns, line)
        room = min(60, columns - len(head) - len(last))
        assert line == (head + sparkline(trace, room) + last if room >= 5 else head + last.lstrip()), (columns, line)


def test_objective_line_shrinks_the_sparkline_then_drops_it() -> None:
    trace = [float(i % 7) for i in range(300)]
    shortest = len("cvar objective per iteration: 0 5")
    lines = {w: objective_line("cvar", trace, w) for w in range(shortest, 140)}
    assert all(len(line) <= w for w, line in lines.items())
    assert all(line.startswith("cvar objective per iteration: 0 ") and line.endswith(" 5") for line in lines.values())
    bars = [len(line.split(" ")[5]) if line.count(" ") == 6 else 0 for line in lines.values()]
    assert bars == sorted(bars) and bars[-1] == 60 and 0 in bars and 5 in bars and not set(bars) & {1, 2, 3, 4}


def test_plot_files_are_written_whole(tmp_path: Path) -> None:
    trace, paths = tmp_path / "trace.png", tmp_path / "paths.png"
    res = run("solve", PAPER, "--method", "qaoa", "--maxiter", "20", "--plot-trace", str(trace), "--plot", str(paths))
    assert res.exit_code == 0, res.output
    for f in (trace, paths):
        assert f.read_bytes()[:8] == PNG
    assert sorted(p.name for p in tmp_path.iterdir()) == ["paths.png", "trace.png"]  # no temporary files left


def test_a_failed_plot_leaves_nothing(tmp_path: Path) -> None:
    target = tmp_path / "missing-dir" / "trace.png"
    assert_one_line_error(run("solve", PAPER, "--method", "qaoa", "--maxiter", "2", "--plot-trace", str(target)))
    assert not target.parent.exists()


def test_default_training_is_layerwise_and_objective_is_selectable() -> None:
    s = load_scenario(PAPER)
    res = run("solve", PAPER, "--method", "qaoa", "-p", "2", "--objective", "cvar", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    direct = solve_qaoa(s, p=2, objective="cvar")
    assert out["optimizer"] == "layerwise" and out["objective"] == "cvar"
    assert [lv["p"] for lv in out["levels"]] == [1, 2] and out["angles"] == list(direct.angles)
    assert out["trace"] == list(direct.trace) and out["circuit_estimates"] == direct.circuit_estimates
    assert out["training_shots"] == out["circuit_estimates"] * out["shots_per_estimate"]
    assert out["p_optimum"] == pytest.approx(out["levels"][-1]["p_optimum"])


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (["--method", "qaoa", "--optimizer", "adam"], ["unknown optimizer", "adam"]),
        (["--method", "qaoa", "-p", "0"], ["-p/--layers", "must be at least 1"]),
        (["--method", "dfs", "-p", "2"], ["-p", "qaoa only"]),
        (["--method", "anneal", "--optimizer", "cobyla"], ["--optimizer", "qaoa only"]),
        (["--method", "qaoa", "--objective", "median"], ["unknown objective", "median"]),
        (["--method", "dfs", "--objective", "cvar"], ["--objective", "qaoa only"]),
        (["--method", "qaoa", "--initial", "warm"], ["unknown initial state", "warm"]),
        (["--method", "anneal", "--initial", "local_search"], ["--initial", "qaoa only"]),
        (["--method", "anneal", "--mixer-warm"], ["--mixer-warm", "qaoa only"]),
        (["--method", "qaoa", "--optimizer", "cobyla", "--mixer-warm"], ["--mixer-warm", "layerwise only"]),
        (["--method", "anneal", "--restart-every-level"], ["--restart-every-level", "qaoa only"]),
        (["--method", "qaoa", "--optimizer", "cobyla", "--restart-every-level"],
         ["--restart-every-level", "layerwise only"]),
        (["--method", "qaoa", "--gibbs-scale", "0"], ["--gibbs-scale", "positive finite", "got 0"]),
        (["--method", "qaoa", "--gibbs-scale", "inf"], ["--gibbs-scale", "positive finite", "got inf"]),
        (["--method", "qaoa", "--objective", "cvar", "--gibbs-scale", "5"], ["--gibbs-scale", "gibbs only"]),
        (["--method", "dfs", "--gibbs-scale", "5"], ["--gibbs-scale", "qaoa only"]),
    ],
)
def test_bad_options_exit_2_with_one_line(args: list[str], fragments: list[str]) -> None:
    assert_one_line_error(run("solve", PAPER, *args), *fragments)


def test_mixer_warm_start_is_the_trainers_and_is_reported() -> None:
    """``--mixer-warm``: the answer is ``train_layerwise(mixer_warm=True)``'s, the JSON counts the product-state
    evaluations, and the default run has none."""
    s = load_scenario(PAPER)
    res = run("solve", PAPER, "--method", "qaoa", "-p", "2", "--mixer-warm", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    direct = solve_qaoa(s, p=2, mixer_warm=True)
    assert direct.schedule is not None and direct.schedule.mixer_evaluations > 0
    assert out["mixer_evaluations"] == direct.schedule.mixer_evaluations
    assert out["angles"] == list(direct.angles) and out["p_optimum"] == pytest.approx(direct.p_optimum)
    assert any("mixer-only warm start" in n for n in out["notes"])
    assert solve_qaoa(s, p=2).schedule.mixer_evaluations == 0  # type: ignore[union-attr]
    with pytest.raises(ValueError, match="layerwise"):
        solve_qaoa(s, p=1, optimizer="lbfgsb", mixer_warm=True)


def test_restarts_and_gibbs_scale_are_the_trainers(tmp_path: Path) -> None:
    """``--no-restart-every-level --gibbs-scale 5``: the answer is ``train_layerwise``'s with those options (``eta =
    5 / sigma``), its objective is the Gibbs free energy at that temperature, and it makes fewer runs than the
    default schedule, which is ``train_layerwise``'s defaults (on a two-robot instance that no depth here solves
    with certainty, so eta matters)."""
    import qcpp
    from qcpp.training.layerwise import train_layerwise
    from qcpp.training.objectives import Gibbs
    from qcpp.training.training import cost_scale

    s = qcpp.random_scenario(3, 3, 2, 0.1, seed=0, index=2)
    qcpp.save_scenario(s, tmp_path / "s.toml")
    res = run("solve", str(tmp_path / "s.toml"), "--method", "qaoa", "-p", "2", "--no-restart-every-level",
              "--gibbs-scale", "5", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    q = SubspaceQAOA(load_scenario(tmp_path / "s.toml"))
    eta = 5 / cost_scale(q)
    direct = train_layerwise(q, 2, restart_every_level=False, eta=eta)
    assert out["angles"] == list(direct.angles) and out["p_optimum"] == pytest.approx(direct.p_optimum)
    value = q.objective_and_gradient(out["angles"], Gibbs(eta))[0]
    assert out["levels"][-1]["value"] == pytest.approx(value)
    assert q.objective_and_gradient(out["angles"], Gibbs(eta / 8))[0] != pytest.approx(value)
    assert q.objective_and_gradient(out["angles"], Gibbs(eta * 8))[0] != pytest.approx(value)
    assert any("from the level below only" in n for n in out["notes"])
    default = solve_qaoa(load_scenario(tmp_path / "s.toml"), p=2).schedule
    assert default is not None and direct.runs < default.runs
    assert default.angles == train_layerwise(q, 2).angles
    assert default.angles == train_layerwise(q, 2, restart_every_level=True, eta=40 / cost_scale(q)).angles


@pytest.mark.parametrize("initial", ["local_search", "local_search_mix"])
def test_local_search_initial_state_is_reported(initial: str) -> None:
    """``--initial local_search[_mix]``: the JSON names it, the notes give the descent, the answer is the trained
    one."""
    from qcpp.problem.solvers.descent import local_search

    res = run("solve", PAPER, "--method", "qaoa", "-p", "1", "--initial", initial, "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    warm = local_search(load_scenario(PAPER))
    assert out["initial"] == initial
    assert any(f"cost {warm.initial_cost:g} -> {warm.cost:g}" in n for n in out["notes"])
    assert any("in superposition with the initial paths" in n for n in out["notes"]) == (initial != "local_search")
    direct = solve_qaoa(load_scenario(PAPER), p=1, initial=initial)  # type: ignore[arg-type]
    assert out["angles"] == list(direct.angles) and out["p_optimum"] == pytest.approx(direct.p_optimum)


def test_qaoa_is_registered_beside_the_classical_methods() -> None:
    assert {"dfs", "anneal", "genetic", "qaoa"} <= set(SOLVE_METHODS)
    s = load_scenario(PAPER)
    sol = SOLVE_METHODS["qaoa"](s, seed=0, rule="exact", progress=None)
    assert sol.method == "qaoa" and sol.cost == dfs(s).cost


def test_sparkline() -> None:
    assert sparkline([]) == ""
    assert sparkline([1.0, 1.0]) == "▁▁"
    assert sparkline([1.0, 2.0], width=0) == ""
    line = sparkline(list(range(500)), width=40)
    assert len(line) == 40 and line[0] == "▁" and line[-1] == "█"


TWO_3x3_TOML = """[grid]
rows = 3
cols = 3

[[robots]]
start = [0, 0]
goal = [2, 2]

[[robots]]
start = [0, 2]
goal = [2, 0]
"""


def _multi_angle_round_trip(scenario: str, tmp_path: Path, unbound: bool = False) -> dict:
    """``--optimizer multi-angle`` at p = 1, then ``qcpp compile --mixer-angles multi`` bound with its ``bindings``."""
    res = run("solve", scenario, "--method", "qaoa", "-p", "1", "--optimizer", "multi-angle", "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    q = SubspaceQAOA(load_scenario(scenario))
    assert out["optimizer"] == "multi-angle" and len(out["angles"]) == sum(len(b.pairs) for b in q.robot_bases)
    assert out["circuit_estimates"] == out["evaluations"] * (1 + 2 * len(out["angles"]))
    qasm = tmp_path / "bound.qasm"
    binds = [f"{k}={v}" for k, v in out["bindings"].items()]
    res = run("compile", scenario, "-p", "1", "--mixer-angles", "multi", "--qasm", str(qasm), "--bind", *binds)
    assert res.exit_code == 0, res.output
    text = qasm.read_text()
    assert "input float" not in text and "beta_r" not in text
    if unbound:
        res = run("compile", scenario, "-p", "1", "--mixer-angles", "multi", "--qasm", "-")
        assert res.exit_code == 0 and "input float[64] beta_r1_q0_0;" in res.stdout
    return out


@pytest.mark.heavy
def test_multi_angle_training_binds_the_compiled_multi_angle_circuit(tmp_path: Path) -> None:
    path = tmp_path / "two_3x3.toml"
    path.write_text(TWO_3x3_TOML)
    out = _multi_angle_round_trip(str(path), tmp_path)
    assert out["p_optimum"] > 0.1


@pytest.mark.heavy
def test_multi_angle_reaches_the_optimum_of_two_robots_4x4_and_binds(tmp_path: Path) -> None:
    four = str(EXAMPLES / "two_robots_4x4.toml")
    out = _multi_angle_round_trip(four, tmp_path, unbound=True)
    q = SubspaceQAOA(load_scenario(four))
    assert out["cost"] == q.optimum()[0] and out["p_optimum"] > 0.99


def test_bad_angles_flag_is_one_line() -> None:
    assert_one_line_error(run("compile", PAPER, "--mixer-angles", "many"), "--mixer-angles", "layer or multi", "many")


@pytest.mark.parametrize(("initial", "noted"), [("initial_path", True), ("local_search", True),
                                                ("local_search_mix", False)])
def test_a_basis_state_start_notes_that_gamma_0_does_nothing(initial: str, noted: bool) -> None:
    """From a basis state the first phase separator is a global phase: the text says so, JSON keeps its keys."""
    args = ["solve", PAPER, "--method", "qaoa", "--maxiter", "5", "--initial", initial]
    res = run(*args)
    assert res.exit_code == 0, res.output
    assert ("g0 has no effect" in res.stdout) is noted, res.stdout
    out = json.loads(run(*args, "--json").stdout)
    assert "g0 has no effect" not in json.dumps(out) and out["initial"] == initial
