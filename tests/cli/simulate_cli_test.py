"""``qcpp simulate``: JSON keys and values, methods that must agree, one-line errors with exit code 2."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from qcpp.cli.commands.simulate import parse_angles
from qcpp.problem.scenario_io import load_scenario
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.training import initial_angles

from .clirun import assert_one_line_error, run

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
PAPER = str(EXAMPLES / "paper_3x3.toml")
KEYS = {"scenario", "method", "p", "angles", "expectation", "p_optimum", "amplitudes_held", "seconds", "qubits",
        "basis_states", "rule", "initial"}


def run_json(*args: str) -> dict[str, object]:
    res = run(*args, "--json")
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_subspace_json_against_the_simulator() -> None:
    out = run_json("simulate", PAPER, "-p", "2", "--angles", "0.3,1.2,-0.1,0.7")
    assert set(out) == KEYS
    q = SubspaceQAOA(load_scenario(PAPER))
    angles = [0.3, 1.2, -0.1, 0.7]
    assert out["method"] == "subspace" and out["p"] == 2 and out["angles"] == angles
    assert out["initial"] == "initial_path"
    assert out["expectation"] == pytest.approx(q.expectation(angles), abs=1e-12)
    assert out["p_optimum"] == pytest.approx(q.p_optimum(angles), abs=1e-12)
    assert out["amplitudes_held"] == 1.0 and out["qubits"] is None and out["basis_states"] == q.dimension


@pytest.mark.slow
def test_statevector_matches_subspace_on_the_paper_scenario() -> None:
    sub = run_json("simulate", PAPER, "-p", "1", "--angles", "0.3,1.2")
    dense = run_json("simulate", PAPER, "-p", "1", "--angles", "0.3,1.2", "--method", "statevector")
    assert set(dense) == KEYS and dense["method"] == "statevector"
    assert abs(dense["expectation"] - sub["expectation"]) < 1e-8
    assert abs(dense["p_optimum"] - sub["p_optimum"]) < 1e-8
    assert abs(dense["amplitudes_held"] - 1.0) < 1e-8  # measured: the compiled circuit stays feasible, clean
    assert dense["qubits"] > 12 and dense["basis_states"] == 2 ** dense["qubits"]


def test_random_angles_come_from_the_seed() -> None:
    a = run_json("simulate", PAPER, "-p", "2", "--seed", "7")
    b = run_json("simulate", PAPER, "-p", "2", "--seed", "7")
    c = run_json("simulate", PAPER, "-p", "2", "--seed", "8")
    assert a["angles"] == b["angles"] != c["angles"]
    expected = initial_angles(SubspaceQAOA(load_scenario(PAPER)), 2, "random", 7)
    assert a["angles"] == pytest.approx(expected.tolist())


def test_text_output() -> None:
    res = run("simulate", PAPER, "-p", "1", "--angles", "0.3,1.2")
    assert res.exit_code == 0, res.output
    for fragment in ("expectation <C>", "probability of the optimum", "angles [g0, b0, ...]", "0.3, 1.2"):
        assert fragment in res.stdout


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (["--method", "dense"], ["--method", "dense"]),
        (["--angles", "0.1,0.2,0.3"], ["needs 2 angles"]),
        (["--angles", "0.1,abc"], ["--angles", "'abc'"]),
        (["-p", "0"], ["-p", "at least 1"]),
        (["--rule", "fuzzy"], ["--rule"]),
    ],
)
def test_bad_options_exit_2_with_one_line(args: list[str], fragments: list[str]) -> None:
    assert_one_line_error(run("simulate", PAPER, *args), *fragments)


def test_missing_file_and_too_many_qubits() -> None:
    assert_one_line_error(run("simulate", "no/such.toml"), "no/such.toml")
    big = str(EXAMPLES / "two_robots_4x4.toml")
    assert_one_line_error(run("simulate", big, "--method", "statevector", "--angles", "0.1,0.2"), "more than 26")


def test_parse_angles() -> None:
    assert parse_angles("1, -2.5,3e-1") == [1.0, -2.5, 0.3]
    with pytest.raises(ValueError, match="'x'"):
        parse_angles("1,x")


def test_a_layer_whose_phase_separator_is_empty_still_takes_its_gamma(tmp_path: Path) -> None:
    # one robot corner to corner on 2x2: both paths cost the same, so the phase separator emits no gate and
    # gamma_0 appears in no gate; binding it must still work in every command that binds angles
    scenario = tmp_path / "flat.toml"
    scenario.write_text("[grid]\nrows = 2\ncols = 2\n\n[[robots]]\nstart = [0, 0]\ngoal = [1, 1]\n")
    for args in (
        ("validate", str(scenario), "--backend", "statevector"),
        ("simulate", str(scenario), "--method", "statevector", "--angles", "0.3,0.7"),
        ("compile", str(scenario), "--lowered", "--bind", "gamma_0=0.3", "beta_0=0.7", "--json"),
    ):
        res = run(*args)
        assert res.exit_code == 0, (args, res.output)
    assert "unknown symbol" in run("compile", str(scenario), "--bind", "gamma_1=0.3").stderr


def test_the_initial_state_is_the_one_given() -> None:
    """``--initial`` reaches the simulator: on a split move graph the JSON equals the API's numbers from that state,
    and the two states give different numbers."""
    import qcpp

    args = ["simulate", "--grid", "3x4", "--robot", "0,0:2,3", "--obstacle", "1,1", "--hard-obstacles", "-p", "1",
            "--angles", "0.3,0.7"]  # fmt: skip
    s = qcpp.grid_scenario(3, 4, robots=[((0, 0), (2, 3))], obstacles=[(1, 1)], hard_obstacles=True)
    rows = {}
    for initial in ("initial_path", "representatives"):
        rows[initial] = run_json(*args, "--initial", initial)
        api = qcpp.simulate_qaoa(s, 1, angles=[0.3, 0.7], initial=initial)
        assert rows[initial]["initial"] == initial
        assert rows[initial]["expectation"] == pytest.approx(api.expectation, abs=1e-12)
        assert rows[initial]["p_optimum"] == pytest.approx(api.p_optimum, abs=1e-12)
    assert rows["initial_path"]["expectation"] != pytest.approx(rows["representatives"]["expectation"], abs=1e-6)
