"""``qcpp compile`` and ``qcpp estimate`` accept exactly the same plan flags and build the same PlanOptions."""

from __future__ import annotations

import json

import pytest
import typer

from qcpp.cli.app import app
from qcpp.cli.commands.plan_flags import PLAN_FLAGS
from qcpp.estimators.counts import count
from qcpp.lowering.passes import lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario_io import load_scenario

from .clirun import assert_one_line_error, run

EXAMPLE = "examples/paper_3x3.toml"


def _flags(command: str) -> dict[str, tuple[str | None, object]]:
    """Every option of a command: flag -> (help, default)."""
    click_app = typer.main.get_command(app)
    cmd = click_app.commands[command]  # type: ignore[attr-defined]
    return {name: (o.help, o.default) for o in cmd.params for name in o.opts if name.startswith("--")}


def test_compile_estimate_and_validate_take_the_same_plan_flags() -> None:
    compile_flags, estimate_flags, validate_flags = _flags("compile"), _flags("estimate"), _flags("validate")
    for flag in PLAN_FLAGS:
        assert flag in compile_flags and compile_flags[flag] == estimate_flags[flag] == validate_flags[flag], flag
    plan_like = {"--rule", "--initial", "--target", "--phase", "--optimize", "--ancilla-budget", "--fuse",
                 "--phase-layout", "--mixer-angles", "--skip-first-phase"}
    assert set(compile_flags) & plan_like == set(estimate_flags) & plan_like == set(PLAN_FLAGS)
    assert set(validate_flags) & plan_like == set(PLAN_FLAGS)


@pytest.mark.parametrize("command", ["compile", "estimate"])
@pytest.mark.parametrize(
    ("flag", "value"),
    [("--rule", "fast"), ("--initial", "path"), ("--target", "qpu"), ("--phase", "ising"), ("--optimize", "t"),
     ("--ancilla-budget", "-1"), ("--phase-layout", "ring"), ("--mixer-angles", "many")],
)  # fmt: skip
def test_a_bad_plan_flag_is_one_line_naming_it(command: str, flag: str, value: str) -> None:
    where = [EXAMPLE] if command == "compile" else ["--scenario", EXAMPLE]
    assert_one_line_error(run(command, *where, flag, value), flag)


def test_estimate_with_representatives_equals_the_compiled_circuit() -> None:
    res = run("estimate", "--scenario", EXAMPLE, "-p", "2", "--initial", "representatives", "--json")
    assert res.exit_code == 0, res.output
    row = json.loads(res.stdout)[0]
    options = PlanOptions(initial="representatives")
    rc = count(lower(qaoa_circuit(load_scenario(EXAMPLE), 2, options)))
    assert (row["qubits"], row["cx"], row["single_qubit"]) == (rc.qubits, rc.cx, rc.single_qubit)
    assert row["depth"] == rc.depth
    res = run("compile", EXAMPLE, "-p", "2", "--initial", "representatives", "--lowered", "--json")
    compiled = json.loads(res.stdout)
    assert compiled["gates"]["cx"] == row["cx"] and compiled["qubits"] == row["qubits"]


def test_skip_first_phase_estimates_the_compiled_circuit_and_the_rows_say_so() -> None:
    grid = ["--grid", "3x3", "--robots", "2", "-p", "2"]  # two robots: the phase separator has CX
    res = run("estimate", *grid, "--skip-first-phase", "--json")
    assert res.exit_code == 0, res.output
    row = json.loads(res.stdout)[0]
    rc = count(lower(qaoa_circuit(default_scenario(3, 3, 2), 2, PlanOptions(first_phase=False))))
    assert row["first_phase"] is False
    assert (row["qubits"], row["cx"], row["single_qubit"]) == (rc.qubits, rc.cx, rc.single_qubit)
    assert row["depth"] == rc.depth
    default = json.loads(run("estimate", *grid, "--json").stdout)[0]
    assert "first_phase" not in default and default["cx"] > row["cx"]  # the default's rows keep their fields
    res = run("compile", *grid, "--skip-first-phase", "--lowered", "--json", "--bind", "gamma_0=0.3")
    assert res.exit_code == 0, res.output
    compiled = json.loads(res.stdout)
    assert compiled["first_phase"] is False and "gamma_0" not in compiled["symbols"]
    assert compiled["gates"]["cx"] == row["cx"] and compiled["qubits"] == row["qubits"]


@pytest.mark.parametrize("command", ["compile", "estimate"])
def test_skip_first_phase_from_a_superposition_is_one_line_naming_the_flag(command: str) -> None:
    # one robot corner to corner: its descent path leaves its initial path, so the mixed start is a superposition
    res = run(command, "--grid", "3x3", "--robots", "1", "--initial", "local_search_mix", "--skip-first-phase")
    assert_one_line_error(res, "--skip-first-phase", "local_search_mix")


def test_skip_first_phase_refuses_the_closed_forms() -> None:
    assert_one_line_error(run("estimate", "--formula", "--skip-first-phase"), "--skip-first-phase", "--formula")


def test_compile_explain_says_when_the_circuit_has_no_phase_separator() -> None:
    """At p = 1 without the first phase separator the explained phase plan is in no layer of the circuit: the title
    says so; at p = 2 the plan is layer 1's, and the title is the usual one."""
    titles = {}
    for p in ("1", "2"):
        res = run("compile", "--grid", "3x3", "--robots", "2", "-p", p, "--skip-first-phase", "--explain")
        assert res.exit_code == 0, res.output
        text = " ".join(res.stdout.split())  # the title may wrap at the runner's width
        titles[p] = text[text.index("phase separator: construction") :][:120]
    assert "this circuit has none" in titles["1"] and "this circuit has none" not in titles["2"]
