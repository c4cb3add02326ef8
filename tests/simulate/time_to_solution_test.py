"""examples/experiments/time_to_solution.py: its quick mode (smoke test), its path-count table, its helpers."""

from __future__ import annotations

import csv
import importlib.util
import json
import sys
from pathlib import Path

import pytest

from gridcover.paths import enumerate_paths
from gridcover.presets import default_scenario

SCRIPT = Path(__file__).resolve().parents[2] / "examples" / "experiments" / "time_to_solution.py"


@pytest.fixture(scope="module")
def tts():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("experiment_time_to_solution", SCRIPT)
    assert spec and spec.loader
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # the script's dataclasses look their module up there
    try:
        spec.loader.exec_module(mod)
        yield mod
    finally:
        sys.modules.pop(spec.name, None)


@pytest.mark.parametrize("n", [3, 4, 5])
def test_corner_path_counts(tts, n: int) -> None:  # type: ignore[no-untyped-def]
    assert len(enumerate_paths(default_scenario(n, n, 1), 0)) == tts.CORNER_PATHS[n]


def test_obstacle_instances_are_seeded_and_keep_the_endpoints_free(tts) -> None:  # type: ignore[no-untyped-def]
    a, b = tts.make_instance(6, 3, True, 0), tts.make_instance(6, 3, True, 0)
    assert a.scenario == b.scenario and len(a.scenario.obstacles) == 3
    ends = {x for rb in a.scenario.robots for x in (rb.start, rb.goal)}
    assert not ends & set(a.scenario.obstacles)
    assert tts.make_instance(6, 3, False, 0).scenario.obstacles == ()


def test_time_to_reach_and_cpsat_best_by(tts) -> None:  # type: ignore[no-untyped-def]
    run = {"seconds": 2.0, "trace": [5.0, 3.0, 3.0, 1.0]}
    assert tts.time_to_reach(run, 3.0) == 1.0 and tts.time_to_reach(run, 1.0) == 2.0
    assert tts.time_to_reach(run, 0.0) is None
    res = {"improvements": [[0.1, 9.0], [0.5, 4.0], [3.0, 2.0]]}
    assert tts.cpsat_best_by(res, 0.05) is None and tts.cpsat_best_by(res, 1.0) == 4.0


@pytest.mark.slow
def test_quick_mode(tts, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    out = tts.main(["--quick", "--out", str(tmp_path)])
    png = (tmp_path / "figures" / "time_to_solution.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000
    md = (tmp_path / "results" / "time_to_solution.md").read_text()
    assert "examples/experiments/time_to_solution.py --quick" in md and "|---|" in md
    rows = list(csv.DictReader((tmp_path / "results" / "time_to_solution.csv").open()))
    data = json.loads((tmp_path / "results" / "time_to_solution.json").read_text())
    assert len(data["instances"]) == len(out["instances"]) == 8
    for inst in out["instances"]:
        r = inst.results
        # quick mode: every instance is small enough for exhaustive search; CP-SAT never beats it and, when it
        # proves its answer within its 2 s wall-clock limit (not on a loaded machine, so not assumed), equals it
        assert r["dfs"]["attempted"] and r["cpsat"]["cost"] >= r["dfs"]["cost"]
        assert not r["cpsat"]["proven"] or r["dfs"]["cost"] == r["cpsat"]["cost"]
        assert r["optimum"] == {"value": r["dfs"]["cost"], "proven": True}
        assert all(run["cost"] >= r["dfs"]["cost"] for m in ("anneal", "genetic") for run in r[m])
    methods = {row["method"] for row in rows}
    assert methods == {"dfs", "cpsat", "anneal", "genetic", "qaoa"}
    assert all("PROJECTION" in row["note"] for row in rows if row["method"] == "qaoa")
    assert not list((tmp_path / "figures").glob(".*")) and not list((tmp_path / "results").glob(".*"))
