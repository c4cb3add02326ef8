"""``qcpp.solve(...).to_dict(scenario)`` is the object ``qcpp solve --json`` prints for the same method and options,
for every method: one builder makes both (the CLI puts its ``scenario`` field first; timing differs)."""

from __future__ import annotations

import importlib.util
import json

import pytest

import qcpp
from tests.cli.clirun import run

TIMING = ("seconds",)
"""Fields that measure the run, not its answer."""

CASES = [
    ("dfs", {}, ()),
    ("cpsat", {}, ()),
    ("anneal", {"seed": 3}, ("--seed", "3")),
    ("genetic", {"seed": 1}, ("--seed", "1")),
    ("anneal", {"seed": 2, "iterations": 80}, ("--seed", "2", "--iterations", "80")),
    ("genetic", {"generations": 3}, ("--generations", "3")),
    ("qaoa", {"p": 2, "maxiter": 30}, ("-p", "2", "--maxiter", "30")),
    ("qaoa", {"p": 1, "optimizer": "multi-angle", "maxiter": 10},
     ("-p", "1", "--optimizer", "multi-angle", "--maxiter", "10")),
    # about two CPU-seconds (two samplings of 100 reads): run with the heavy step
    pytest.param("qubo", {}, (), marks=[
        pytest.mark.heavy,
        pytest.mark.skipif(importlib.util.find_spec("dwave") is None or importlib.util.find_spec("dwave.samplers")
                           is None, reason="the annealing extra (dwave-samplers) is not installed"),
    ]),
]  # fmt: skip


def _answer(d: dict[str, object]) -> dict[str, object]:
    return {k: v for k, v in d.items() if k not in TIMING}


@pytest.mark.parametrize(("method", "options", "flags"), CASES)
def test_the_api_object_is_the_cli_json(method: str, options: dict[str, object], flags: tuple[str, ...]) -> None:
    s = qcpp.grid_scenario(2, 3, robots=2)
    res = run("solve", "--grid", "2x3", "--robots", "2", "-m", method, *flags, "--json")
    assert res.exit_code == 0, res.output
    cli = json.loads(res.stdout)
    assert cli.pop("scenario") == "--grid 2x3 --robots 2"
    api = qcpp.solve(s, method, **options).to_dict(s)  # type: ignore[arg-type]
    assert set(api) == set(cli)
    assert _answer(api) == _answer(cli)
    assert json.loads(json.dumps(api)) == api  # JSON-ready as it stands


def test_the_method_fields_are_in_the_api_object() -> None:
    """What a user of the API missed: cpsat's proof and qaoa's training fields, without going through the CLI."""
    s = qcpp.grid_scenario(2, 3, robots=1)
    proof = qcpp.solve(s, "cpsat").to_dict(s)
    assert proof["proven_optimal"] is True and proof["gap"] == 0 and proof["status"] == "OPTIMAL"
    trained = qcpp.solve(s, "qaoa", p=2, maxiter=30).to_dict(s)
    assert {"probability", "p_optimum", "angles", "levels", "training_shots", "circuit_estimates"} <= set(trained)
    assert trained["p"] == 2 and len(trained["angles"]) == 4 and [lv["p"] for lv in trained["levels"]] == [1, 2]


def test_to_dict_gives_a_fresh_copy() -> None:
    s = qcpp.grid_scenario(2, 3, robots=1)
    sol = qcpp.solve(s, "qaoa", p=1, maxiter=20)
    first = sol.to_dict(s)
    first["angles"].append(99.0)
    first["levels"][0]["p"] = 7
    again = sol.to_dict(s)
    assert 99.0 not in again["angles"] and again["levels"][0]["p"] == 1
