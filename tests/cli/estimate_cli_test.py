"""``qcpp estimate``: formats, ranges, skipped grids, scenario files, plot, physical estimates, formulas, bad input."""

from __future__ import annotations

import csv
import importlib.util
import io
import json
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from qcpp.cli.commands.estimate import register
from qcpp.estimators.counts import count
from qcpp.estimators.formulas import QUANTITIES
from qcpp.lowering.passes import lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario_io import save_scenario


def _app() -> typer.Typer:
    if importlib.util.find_spec("qcpp.cli.app") is not None:  # the real CLI, once it registers the command
        from qcpp.cli import app as cli_app

        app = getattr(cli_app, "app", None)
        if isinstance(app, typer.Typer) and any(c.name == "estimate" for c in app.registered_commands):
            return app
    app = typer.Typer()
    register(app)

    @app.callback()
    def main() -> None:
        """qcpp"""

    return app


@pytest.fixture
def run():  # type: ignore[no-untyped-def]
    runner = CliRunner()
    env = {"COLUMNS": "250"}  # estimate keeps no cache on disk

    def invoke(*args: str):  # type: ignore[no-untyped-def]
        return runner.invoke(_app(), ["estimate", *args], env=env)

    return invoke


def test_json_one_point_has_the_exact_counts(run) -> None:  # type: ignore[no-untyped-def]
    res = run("--grid", "3x3", "--robots", "1", "--json")
    assert res.exit_code == 0, res.output
    rows = json.loads(res.stdout)
    assert len(rows) == 1
    rc = count(lower(qaoa_circuit(default_scenario(3, 3, 1), 1)))
    row = rows[0]
    for key in ("rows", "cols", "robots", "p", "qubits", "data_qubits", "ancillas", "cx", "single_qubit", "t"):
        assert key in row
    assert (row["qubits"], row["cx"], row["depth"], row["two_qubit_depth"]) == (rc.qubits, rc.cx, rc.depth,
                                                                                rc.two_qubit_depth)
    assert row["depth_kind"] == "exact"
    assert set(row["sections"]) == {"initial_state", "phase", "mixer"}


def test_ranges_and_compare_paper_in_csv(run) -> None:  # type: ignore[no-untyped-def]
    res = run("--grid", "2x2..2x3", "--robots", "1..2", "-p", "1..2", "--compare", "paper", "--format", "csv")
    assert res.exit_code == 0, res.output
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    assert [(r["rows"], r["cols"], r["robots"], r["p"]) for r in rows] == [
        (r, c, k, p) for r, c in [("2", "2"), ("2", "3")] for k in "12" for p in "12"
    ]
    assert all(r["paper_cx"] and r["ratio_cx"] for r in rows)


def test_markdown_and_table(run) -> None:  # type: ignore[no-untyped-def]
    md = run("--grid", "2x2", "--format", "md", "--compare", "paper")
    assert md.exit_code == 0
    lines = md.stdout.splitlines()
    assert lines[0].startswith("| rows |") and "paper_cx" in lines[0] and len(lines) == 3
    table = run("--grid", "2x2", "--wide")
    assert table.exit_code == 0 and "two_qubit_depth" in table.stdout


def test_plot_is_written_atomically(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / "plots" / "est.png"
    missing = run("--grid", "2x2", "--plot", str(out), "--json")  # folders are never created
    assert missing.exit_code == 2 and "folder" in missing.stderr and not out.parent.exists()
    out.parent.mkdir()
    res = run("--grid", "2x2..3x3", "--robots", "1..2", "--compare", "paper", "--plot", str(out), "--json")
    assert res.exit_code == 0, res.output
    assert out.read_bytes()[:4] == b"\x89PNG"
    assert [p.name for p in out.parent.iterdir()] == ["est.png"]
    assert len(json.loads(res.stdout)) == 8


def test_plot_metric_and_every_p(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / "t.png"
    res = run("--grid", "2x2..3x3", "-p", "1..2", "--depth", "none", "--metric", "t", "--plot", str(out), "--json")
    assert res.exit_code == 0, res.output
    assert out.read_bytes()[:4] == b"\x89PNG" and f"wrote {out}" in res.stderr
    assert sorted({r["p"] for r in json.loads(res.stdout)}) == [1, 2]


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (("--metric", "cnots", "--plot", "x.png"), ("--metric: expected qubits or", "cx or", "esp_idle, got 'cnots'")),
        (("--metric", "t"), ("--metric: applies with --plot only",)),
        (("--metric", "physical_qubits", "--plot", "x.png"), ("--metric: physical_qubits needs --physical",)),
        (("--metric", "routed_twoq", "--plot", "x.png"), ("--metric: routed_twoq needs --device",)),
        (("--metric", "depth", "--depth", "none", "--plot", "x.png"), ("--metric: depth needs a depth",)),
    ],
)
def test_bad_metric_is_one_line_before_any_work(run, tmp_path: Path, args: tuple[str, ...],  # type: ignore[no-untyped-def]
                                                fragments: tuple[str, ...]) -> None:  # fmt: skip
    args = tuple(str(tmp_path / a) if a.endswith(".png") else a for a in args)
    res = run("--grid", "2x2", *args)
    assert res.exit_code == 2 and res.stdout == "", res.output
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    for fragment in fragments:
        assert fragment in lines[0]
    assert not list(tmp_path.iterdir())


def test_scenario_file_and_rule(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "s.toml"
    save_scenario(default_scenario(2, 3, 2), path)
    from_file = json.loads(run("--scenario", str(path), "-p", "1..2", "--json").stdout)
    default = json.loads(run("--grid", "2x3", "--robots", "2", "-p", "1..2", "--json").stdout)
    assert [r["cx"] for r in from_file] == [r["cx"] for r in default]
    assert [r["scenario"] for r in from_file] == ["custom", "custom"]
    paper_rule = json.loads(run("--grid", "3x3", "--rule", "paper", "--json").stdout)[0]
    exact_rule = json.loads(run("--grid", "3x3", "--json").stdout)[0]
    assert paper_rule["rule"] == "paper" and paper_rule["cx"] != exact_rule["cx"]


def test_paper_doubling_reading(run) -> None:  # type: ignore[no-untyped-def]
    literal = json.loads(run("--grid", "3x3", "--compare", "paper", "--json").stdout)[0]
    logic = json.loads(run("--grid", "3x3", "--compare", "paper", "--paper-doubling", "logic", "--json").stdout)[0]
    assert literal["paper_cx"] - logic["paper_cx"] == 4 * 8  # four partial mixers, the 8-CNOT rotation once less



def test_any_robot_count_and_skipped_grids_reported_once(run) -> None:  # type: ignore[no-untyped-def]
    res = run("--grid", "2x2..2x3", "--robots", "4..6", "--format", "jsonl")
    assert res.exit_code == 0, res.output
    rows = [json.loads(line) for line in res.stdout.splitlines()]
    assert [(r["cols"], r["robots"]) for r in rows] == [(2, 4), (3, 4), (3, 5), (3, 6)]
    assert res.stderr.count("skipped") == 1 and "skipped 2 of 6 points" in res.stderr
    none = run("--grid", "2x2", "--robots", "5")
    assert none.exit_code == 2 and none.stderr.startswith("error: ") and len(none.stderr.splitlines()) == 1


def test_physical_estimates(run) -> None:  # type: ignore[no-untyped-def]
    res = run("--grid", "3x3", "--robots", "2", "--physical", "--json")
    assert res.exit_code == 0, res.output
    row = json.loads(res.stdout)[0]
    assert row["physical_qubits"] > row["qubits"] and row["physical_runtime_s"] > 0
    assert "qubit_gate_ns_e3" in row["physical_model"] and "QDK resource estimator" in res.stderr
    maj = run("--grid", "3x3", "--physical", "--qubit-model", "qubit_maj_ns_e6", "--qec-scheme", "floquet_code",
              "--error-budget", "0.01", "--json")
    assert maj.exit_code == 0, maj.output
    assert "floquet_code" in json.loads(maj.stdout)[0]["physical_model"]
    refused = run("--grid", "3x3", "--physical", "--qec-scheme", "floquet_code")
    assert refused.exit_code == 2 and len(refused.stderr.strip().splitlines()) == 1


def test_depth_kinds_and_toffoli_model(run) -> None:  # type: ignore[no-untyped-def]
    bound = json.loads(run("--grid", "3x3", "--depth", "bound", "--json").stdout)[0]
    exact = json.loads(run("--grid", "3x3", "--depth", "exact", "--json").stdout)[0]
    none = json.loads(run("--grid", "3x3", "--depth", "none", "--json").stdout)[0]
    assert (bound["depth_kind"], exact["depth_kind"], none["depth_kind"]) == ("bound", "exact", None)
    assert bound["depth"] >= exact["depth"] and none["depth"] is None
    four = json.loads(run("--grid", "3x3", "--toffoli-t", "4", "--json").stdout)[0]
    assert four["ft_t_logic"] == exact["ft_t_logic"] - 3 * exact["ft_toffoli_full"]


def test_phase_separator_options(run) -> None:  # type: ignore[no-untyped-def]
    feasible = json.loads(run("--grid", "4x4", "--robots", "2", "--json").stdout)[0]
    whole = json.loads(run("--grid", "4x4", "--robots", "2", "--phase", "whole-space", "--json").stdout)[0]
    shallow = json.loads(run("--grid", "4x4", "--robots", "2", "--optimize", "depth", "--json").stdout)[0]
    assert feasible["sections"]["phase"]["cx"] < whole["sections"]["phase"]["cx"]
    assert feasible["sections"]["mixer"] == whole["sections"]["mixer"] == shallow["sections"]["mixer"]
    assert run("--phase", "ising").exit_code == 2 and run("--optimize", "t").exit_code == 2


def test_formula(run) -> None:  # type: ignore[no-untyped-def]
    text = run("--formula")
    assert text.exit_code == 0 and "V = 2*cols*rows - cols - rows" in text.stdout
    data = json.loads(run("--formula", "--json").stdout)
    assert set(data["formulas"]) == set(QUANTITIES)


@pytest.mark.parametrize(
    "args",
    [
        ("--grid", "3"),
        ("--grid", "1x3"),
        ("--grid", "4x4..3x3"),
        ("--robots", "9"),
        ("--robots", "0..2"),
        ("-p", "x"),
        ("--rule", "fast"),
        ("--format", "xml"),
        ("--compare", "qiskit"),
        ("--scenario", "/nonexistent/file.toml"),
        ("--paper-doubling", "rotation"),
        ("--scenario", "examples/paper_3x3.toml", "--grid", "3x3"),
        ("--epsilon", "2"),
        ("--depth", "deep"),
        ("--toffoli-t", "5"),
        ("--target", "qpu"),
        ("--qubit-model", "transmon"),
        ("--qec-scheme", "color"),
        ("--error-budget", "0"),
    ],
)
def test_bad_input_exits_2_with_one_line(run, args: tuple[str, ...]) -> None:  # type: ignore[no-untyped-def]
    res = run(*args)
    assert res.exit_code == 2
    assert res.stdout == ""
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")


def test_ancilla_budget_trades_ancillas_for_cnots_and_matches_the_compiled_circuit(run) -> None:  # type: ignore[no-untyped-def]
    free = json.loads(run("--grid", "5x5", "--robots", "2", "--json").stdout)[0]
    res = run("--grid", "5x5", "--robots", "2", "--ancilla-budget", "40", "--json")
    assert res.exit_code == 0, res.output
    tight = json.loads(res.stdout)[0]
    assert tight["ancillas"] <= 40 < free["ancillas"]
    assert tight["cx"] > free["cx"]
    rc = count(lower(qaoa_circuit(default_scenario(5, 5, 2), 1, PlanOptions(ancilla_budget=40))))
    assert (tight["qubits"], tight["cx"], tight["t"]) == (rc.qubits, rc.cx, rc.t)
    bad = run("--grid", "3x3", "--ancilla-budget", "-1")
    assert bad.exit_code == 2


def test_explain_names_the_chosen_phase_construction_and_its_alternatives(run) -> None:  # type: ignore[no-untyped-def]
    res = run("--grid", "5x5", "--robots", "2", "--explain", "--json")
    assert res.exit_code == 0, res.output
    json.loads(res.stdout)  # stdout stays machine-readable
    assert "balance" in res.stderr and "arithmetic" in res.stderr and "couplings:" in res.stderr


def test_cli_defaults_are_the_estimators_defaults() -> None:
    """The command spells its defaults out (it imports the estimators lazily, for a fast start): keep them equal."""
    import inspect

    from qcpp.cli.commands.estimate import estimate
    from qcpp.estimators.estimate import DEFAULT_DEPTH_BUDGET

    assert inspect.signature(estimate).parameters["depth_budget"].default == DEFAULT_DEPTH_BUDGET


def _run80(*args: str):  # type: ignore[no-untyped-def]
    """``qcpp estimate ARGS`` on an 80-column terminal."""
    return CliRunner().invoke(_app(), ["estimate", *args], env={"COLUMNS": "80"})


def _widest(text: str) -> int:
    return max((len(line) for line in text.splitlines()), default=0)


def test_physical_figures_from_a_depth_bound_are_marked_approximate_not_exact() -> None:
    args = ("--grid", "3x3", "--robots", "2", "--target", "ft", "--physical")
    shown = ("--columns", "robots,rotation_depth,physical_qubits,physical_runtime_s")
    bound = _run80(*args, "--depth", "bound", *shown)
    assert bound.exit_code == 0, bound.output
    title = " ".join(" ".join(bound.stdout.splitlines()[:3]).split())
    assert "~N: from a depth bound" in title and "--depth exact gives the exact figure" in title
    cells = bound.stdout.splitlines()[-2].split("│")
    assert cells[2].strip().startswith("<=") and cells[3].strip().startswith("~") and cells[4].strip()[0] == "~"
    exact = _run80(*args, "--depth", "exact", *shown)
    assert exact.exit_code == 0 and "~" not in exact.stdout
    md = _run80(*args, "--depth", "bound", "--format", "md", *shown).stdout
    assert "| ~" in md and md.rstrip().endswith("(--depth exact gives the exact figure)")
    latex = _run80(*args, "--depth", "bound", "--format", "latex", *shown).stdout
    assert r"$\sim$" in latex.splitlines()[5] and r"$\sim$N: from a depth bound" in latex.splitlines()[0]
    kinds = {d: json.loads(_run80(*args, "--depth", d, "--json").stdout)[0]["physical_depth_kind"]
             for d in ("bound", "exact", "none")}  # fmt: skip
    assert kinds == {"bound": "bound", "exact": "exact", "none": "rotation_count"}


def test_the_ft_target_shows_the_fault_tolerant_columns_and_nisq_keeps_its_own() -> None:
    from qcpp.estimators.tables import MAIN_COLUMNS

    ft = _run80("--grid", "4x4", "--robots", "1..2", "--target", "ft")
    assert ft.exit_code == 0, ft.output
    header = next(line for line in ft.stdout.splitlines() if "┃ rows" in line)
    assert "ft_total_t" in header and "rotation_depth" in header and _widest(ft.stdout) <= 80
    assert "ft_*: fault-tolerant model estimates" in " ".join(ft.stdout.split())
    assert "ft_rotations" in ft.stdout  # named in the hidden-columns note at 80 columns
    wide = CliRunner().invoke(_app(), ["estimate", "--grid", "4x4", "--target", "ft"], env={"COLUMNS": "90"})
    header = next(line for line in wide.stdout.splitlines() if "┃ rows" in line)
    assert all(c in header for c in ("ft_total_t", "ft_rotations", "rotation_depth"))
    md = _run80("--grid", "4x4", "--target", "ft", "--format", "md").stdout
    assert all(c in md for c in ("ft_total_t", "ft_rotations", "rotation_depth"))
    latex = _run80("--grid", "4x4", "--target", "ft", "--format", "latex").stdout
    assert all(h in latex for h in ("T (FT model)", "rotations (FT model)", "rotation depth"))
    nisq = _run80("--grid", "4x4", "--format", "md").stdout
    assert [c.strip() for c in nisq.splitlines()[0].strip("|").split("|")] == list(MAIN_COLUMNS)


def test_output_fits_80_columns() -> None:
    formula = _run80("--formula")
    assert formula.exit_code == 0 and _widest(formula.stdout) <= 80 and "qubits =" in formula.stdout
    physical = _run80("--grid", "3x3", "--physical", "--format", "csv")
    assert "QDK resource estimator" in physical.stderr and _widest(physical.stderr) <= 80
    skipped = _run80("--grid", "2x2..2x3", "--robots", "5", "--format", "csv")
    assert "skipped" in skipped.stderr and _widest(skipped.stderr) <= 80
    too_many = _run80("--grid", "3x3", "--robots", "9")
    assert too_many.exit_code == 2 and "--robots" in too_many.stderr and "at most 8" in too_many.stderr
    assert len(too_many.stderr.strip().splitlines()) == 1 and _widest(too_many.stderr) <= 100
    bogus = _run80("--columns", "ft_total")
    assert bogus.exit_code == 2 and "--columns" in bogus.stderr and "did you mean ft_total_t" in bogus.stderr
    assert "--format csv" in bogus.stderr and _widest(bogus.stderr) <= 100


def test_robots_and_layers_take_comma_lists(run) -> None:  # type: ignore[no-untyped-def]
    res = run("--grid", "3x3", "--robots", "1,3..4", "-p", "2,1", "--format", "csv", "--columns", "robots,p")
    assert res.exit_code == 0, res.output
    assert res.stdout.split() == ["robots,p", "1,1", "1,2", "3,1", "3,2", "4,1", "4,2"]
    bad = run("--robots", "2,,8")
    assert bad.exit_code == 2 and "--robots: expected N, A..B or a comma list of them" in bad.stderr


@pytest.mark.parametrize(
    "args", [("--qec-scheme", "floquet_code"), ("--qubit-model", "qubit_maj_ns_e6"), ("--error-budget", "0.01")]
)
def test_physical_options_without_physical_are_refused(run, args: tuple[str, ...]) -> None:  # type: ignore[no-untyped-def]
    res = run("--grid", "3x3", *args)
    assert res.exit_code == 2 and res.stdout == ""
    assert res.stderr.strip() == f"error: {args[0]}: applies with --physical only (no --physical given)"


@pytest.mark.parametrize("positional", [True, False])
def test_a_scenario_file_with_grid_is_refused_naming_how_it_was_given(run, positional: bool) -> None:  # type: ignore[no-untyped-def]
    """A file given positionally is named as the file in the message, not as ``--scenario`` (not given)."""
    path = "examples/two_robots_4x4.toml"
    res = run(path, "--grid", "6x6") if positional else run("--scenario", path, "--grid", "6x6")
    assert res.exit_code == 2 and res.stdout == ""
    named = f"the scenario file {path!r}" if positional else "--scenario"
    expected = f"error: {named} gives the grid and the robots: do not combine it with --grid or --robots"
    assert res.stderr.strip() == expected
