"""The committed results in docs/results cannot go stale unnoticed.

Every row of ``time_to_solution.json`` and ``qaoa_training.json`` records its scenario, its options and the
qcpp version. This test recomputes the cheap columns from those records with today's code and fails when they
disagree: the compiled circuit's qubits, depth and two-qubit depth (and gate count) at the row's ``p``, the path
counts, and every column derived by formula (shots and runs for 99%, time per shot, the 99% times). The CSV must
hold the JSON's rows, and the Markdown the same version. After a compiler change, regenerate with
``python examples/experiments/time_to_solution.py`` and ``python examples/experiments/qaoa_training.py``.
"""

from __future__ import annotations

import csv
import json
import math
from functools import cache
from pathlib import Path
from typing import Any

import pytest

import qcpp
from gridcover.paths import enumerate_paths
from gridcover.scenario import Scenario, scenario_from_dict
from simulate.success import shots_for, tries_for
from simulate.time_to_solution import shot_seconds

RESULTS = Path(__file__).resolve().parents[2] / "docs" / "results"
FILES = ("time_to_solution", "qaoa_training")


def _load(name: str) -> dict[str, Any]:
    return json.loads((RESULTS / f"{name}.json").read_text())


@cache
def _scenario(text: str) -> Scenario:
    return scenario_from_dict(json.loads(text))


@cache
def _circuit(text: str, p: int) -> dict[str, int]:
    from estimators.estimate import EstimateOptions, Point, estimate_point

    est = estimate_point(Point.from_scenario(_scenario(text), p), EstimateOptions(depth="exact"))
    assert est.depth is not None
    return {"qubits": est.qubits, "depth": est.depth.depth, "two_qubit_depth": est.depth.two_qubit_depth,
            "gates": est.cost.total}


def _key(row: dict[str, Any]) -> str:
    return json.dumps(row["scenario"], sort_keys=True)


@pytest.mark.parametrize("name", FILES)
def test_every_row_records_scenario_options_and_version(name: str) -> None:
    data = _load(name)
    assert data["qcpp_version"] == qcpp.__version__, f"regenerate docs/results/{name}.* for qcpp {qcpp.__version__}"
    assert data["rows"]
    for row in data["rows"]:
        assert row["qcpp_version"] == qcpp.__version__
        assert isinstance(row["options"], dict) and row["options"]
        _scenario(_key(row))  # a valid scenario
    assert f"qcpp {qcpp.__version__}" in (RESULTS / f"{name}.md").read_text()


@pytest.mark.parametrize("name", FILES)
def test_circuit_columns_match_the_compiler(name: str) -> None:
    checked = 0
    for row in _load(name)["rows"]:
        if "qubits" not in row:
            continue
        want = _circuit(_key(row), int(row["p"]))
        got = {k: row[k] for k in want if k in row}
        assert got == {k: want[k] for k in got}, (name, row.get("instance", row.get("scenario_file")), row["p"])
        checked += 1
    assert checked > 0


def test_time_to_solution_derived_columns() -> None:
    rows = _load("time_to_solution")["rows"]
    methods = {r["method"] for r in rows}
    assert methods == {"dfs", "cpsat", "anneal", "genetic", "qaoa"}
    for r in rows:
        if r["method"] == "dfs":
            s = _scenario(_key(r))
            if r["size"] <= 4:  # the path counts, by enumeration where it is cheap
                assert r["assignments"] == math.prod(len(enumerate_paths(s, k)) for k in range(s.num_robots))
            if r["attempted"]:
                assert r["tts_99"] == r["seconds"]
        elif r["method"] in ("anneal", "genetic"):
            assert r["successes"] == sum(c <= r["optimum"] + 1e-9 for c in r["run_costs"])
            assert r["tries_99"] == tries_for(r["successes"] / r["runs"])
            assert r["tts_99"] == pytest.approx(r["run_seconds"] * r["tries_99"])
        elif r["method"] == "qaoa":
            o = r["options"]
            shot = shot_seconds(r["depth"], r["two_qubit_depth"], o["gate_model"])
            assert r["shot_us"] == pytest.approx(shot * 1e6)
            assert r["shots_99"] == shots_for(min(1.0, r["p_opt"]))
            assert r["training_shots"] == r["circuit_estimates"] * o["shots_per_estimate"]
            assert r["tts_99"] == pytest.approx((r["training_shots"] + r["shots_99"]) * shot)
            assert r["p"] == o["p"] and r["p_opt"] == pytest.approx(r["p_opt_by_level"][-1])


def test_time_to_solution_csv_holds_the_json_rows() -> None:
    rows = _load("time_to_solution")["rows"]
    with (RESULTS / "time_to_solution.csv").open(newline="") as fh:
        table = list(csv.DictReader(fh))
    assert len(table) == len(rows)
    for a, b in zip(table, rows):
        assert a["instance"] == b["instance"] and a["method"] == b["method"]
        assert json.loads(a["scenario"]) == b["scenario"] and json.loads(a["options"]) == b["options"]
