"""The public API gives what the command line gives for the same scenario and options: estimate rows (a default
placement, a file, a device), compile counts and summaries, routed layouts, OpenQASM text."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import qcpp
from tests.cli.clirun import run

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def cli_json(*args: str) -> object:
    res = run(*args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_an_estimate_of_a_default_placement_is_the_grid_row() -> None:
    [row] = cli_json("estimate", "--grid", "3x4", "--robots", "2", "-p", "2", "--json")
    est = qcpp.estimate(qcpp.grid_scenario(3, 4, robots=2), p=2)
    assert est.to_dict() == row
    assert row["scenario"] == "default"
    assert (est.qubits, est.cx, est.t, est.depth) == (row["qubits"], row["cx"], row["t"], row["depth"])


def test_an_estimate_of_a_file_with_options_is_the_scenario_row() -> None:
    path = EXAMPLES / "two_robots_4x4.toml"
    args = ("--target", "ft", "--compare", "paper", "--epsilon", "1e-4", "--toffoli-t", "4")
    [row] = cli_json("estimate", "--scenario", str(path), "-p", "3", *args, "--json")
    est = qcpp.estimate(
        qcpp.load_scenario(path), 3, target="ft", compare_paper=True, epsilon=1e-4, toffoli_t=4
    )
    assert est.to_dict() == row
    assert est.paper_cx == row["paper_cx"] and est.ft_total_t == row["ft_total_t"]  # every column is an attribute
    assert set(est.columns) == set(row)


@pytest.mark.slow
def test_an_estimate_with_a_device_has_the_routed_columns_of_the_cli() -> None:
    [row] = cli_json("estimate", "--grid", "3x3", "--robots", "1", "--device", "grid", "--json")
    est = qcpp.estimate(qcpp.grid_scenario(3, 3, robots=1), device="grid")
    assert est.to_dict() == row
    assert est.routed_twoq == row["routed_twoq"] and est.device == row["device"]


def test_compile_counts_summary_and_qasm_are_the_cli_s(tmp_path: Path) -> None:
    path = EXAMPLES / "paper_3x3.toml"
    out = tmp_path / "cli.qasm"
    summary = cli_json("compile", str(path), "-p", "2", "--lowered", "--bind", "gamma_0=0.3", "beta_1=0.5",
                       "--qasm", str(out), "--json")  # fmt: skip
    c = qcpp.compile(qcpp.load_scenario(path), 2, lowered=True, bind={"gamma_0": 0.3, "beta_1": 0.5})
    assert c.counts() == summary["gates"]
    assert c.qubits == summary["qubits"]
    assert list(c.symbols) == summary["symbols"]
    expected = {k: v for k, v in summary.items() if k not in ("seconds", "qasm")}
    assert c.to_dict() == expected
    assert c.to_qasm(3) == out.read_text()


def test_a_high_level_compile_with_plan_options_counts_as_the_cli() -> None:
    path = EXAMPLES / "two_robots_4x4.toml"
    summary = cli_json("compile", str(path), "--phase", "whole-space", "--initial", "representatives", "--json")
    c = qcpp.compile(qcpp.load_scenario(path), phase="whole-space", initial="representatives")
    assert c.counts() == summary["gates"] and not c.lowered


@pytest.mark.slow
def test_routed_layouts_are_the_cli_s() -> None:
    path = EXAMPLES / "paper_3x3.toml"
    summary = cli_json("compile", str(path), "--device", "heavy-hex", "--lowered", "--json")
    c = qcpp.compile(qcpp.load_scenario(path), device="heavy-hex", lowered=True)
    assert c.initial_layout == summary["initial_layout"]
    assert c.final_layout == summary["final_layout"]
    assert c.counts() == summary["gates"]
    assert c.device is not None and c.device.name == summary["device"]["name"]
    assert {k: v for k, v in summary.items() if k != "seconds"} == c.to_dict()
    assert (c.esp, c.esp_idle) == (summary["routed"]["esp"], summary["routed"]["esp_idle"])


def test_to_qiskit_loads_the_same_gates() -> None:
    c = qcpp.compile(qcpp.grid_scenario(3, 3, robots=1), lowered=True)
    qc = c.to_qiskit()
    assert qc.num_qubits == c.qubits
    assert dict(qc.count_ops()) == c.counts()
    assert sorted(p.name for p in qc.parameters) == sorted(c.symbols)


def test_a_saved_scenario_loads_back_equal(tmp_path: Path) -> None:
    s = qcpp.grid_scenario(5, 5, robots=3, obstacles=[(2, 2), (1, 3)], hard_obstacles=True)
    for suffix in (".toml", ".json"):
        qcpp.save_scenario(s, tmp_path / f"s{suffix}")
        assert qcpp.load_scenario(tmp_path / f"s{suffix}") == s


def test_solvers_and_simulators_run_through_the_api() -> None:
    s = qcpp.grid_scenario(3, 3, robots=1, obstacles=[(1, 1)])
    best = qcpp.solve(s, "dfs")
    assert qcpp.solve(s).cost.total == pytest.approx(best.cost.total)  # cpsat proves the same optimum
    trained = qcpp.train_qaoa(s, 1, maxiter=20)
    assert trained.solution.cost.total >= best.cost.total - 1e-9
    ev = qcpp.simulate_qaoa(s, 1, angles=list(trained.angles))
    assert ev.expectation >= best.cost.total - 1e-9


@pytest.mark.parametrize("initial", ["initial_path", "representatives"])
def test_trained_bindings_compile_to_the_trained_state(initial: str) -> None:
    """``train_qaoa(...).bindings`` binds the compiled circuit (same rule and initial state): its lowered
    statevector reads the optimum with the probability training reports."""
    from qcpp.simulate.statevector import simulate_statevector
    from qcpp.training.evaluate import feasible_assignments

    s = qcpp.grid_scenario(2, 3, robots=[((0, 0), (1, 2))])
    trained = qcpp.train_qaoa(s, 2, initial=initial, maxiter=30)
    assert set(trained.bindings) == {"gamma_0", "beta_0", "gamma_1", "beta_1"}
    circuit = qcpp.compile(s, 2, initial=initial, bind=trained.bindings, lowered=True)
    assert circuit.symbols == ()
    psi = simulate_statevector(circuit.circuit)
    probs = np.abs(psi) ** 2
    feasible, optimal = feasible_assignments(s)
    assert probs[feasible].sum() == pytest.approx(1.0)  # ancillas clean, every amplitude feasible
    assert probs[feasible[optimal]].sum() == pytest.approx(trained.p_optimum, abs=1e-9)


def test_the_public_names_load_lazily_and_are_listed() -> None:
    assert set(qcpp.__all__) <= set(dir(qcpp))
    for name in qcpp.__all__:
        assert getattr(qcpp, name) is not None
    assert {"google_willow", "ibm_fez", "ibm_torino", "quantinuum_helios"} <= set(qcpp.devices())
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        qcpp.nope  # noqa: B018


def test_a_scenario_draws_itself_and_an_estimate_shows_as_a_table() -> None:
    s = qcpp.grid_scenario(4, 5, robots=2, obstacles=[(1, 1), (2, 3)])
    svg = s._repr_svg_()
    assert svg.count("<rect") == 1 + 2 and svg.count("<circle") == 2 * 2
    html = qcpp.estimate(s)._repr_html_()
    assert "<table>" in html and "<td style='text-align:right'>" in html


def test_a_solution_gives_node_paths_and_the_cli_json() -> None:
    """``Solution.node_paths(scenario)`` walks each robot's edge mask from start to goal, and
    ``Solution.to_dict(scenario)`` is ``qcpp solve --json``'s object (timing aside)."""
    s = qcpp.grid_scenario(3, 4, robots=[((0, 0), (2, 3)), ((2, 0), (0, 3))], obstacles=[(1, 1)])
    best = qcpp.solve(s, "dfs")
    nodes = best.node_paths(s)
    for path, robot, mask in zip(nodes, s.robots, best.paths, strict=True):
        assert path[0] == robot.start and path[-1] == robot.goal and len(set(path)) == len(path)
        assert len(path) - 1 == bin(mask).count("1")
    res = run("solve", "--grid", "3x4", "--robot", "0,0:2,3", "--robot", "2,0:0,3", "--obstacle", "1,1",
              "-m", "dfs", "--json")  # fmt: skip
    cli = json.loads(res.stdout)
    api = best.to_dict(s)
    assert [[tuple(n) for n in p] for p in cli["paths"]] == [list(p) for p in nodes]
    for d in (cli, api):
        d.pop("seconds")
    assert {k: v for k, v in cli.items() if k in api} == api
