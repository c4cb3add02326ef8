"""qcpp.simulate.time_to_solution (the 99% criterion) and examples/experiments/time_to_solution.py:
quick mode, helpers."""

from __future__ import annotations

import csv
import importlib.util
import json
import math
import sys
from pathlib import Path

import pytest

from qcpp.problem.paths import enumerate_paths
from qcpp.problem.presets import default_scenario
from qcpp.simulate.success import success_probability
from qcpp.simulate.time_to_solution import qaoa_on_device, repeated_runs, shot_seconds

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


def test_repeated_runs_reach_the_target() -> None:
    r = repeated_runs(run_seconds=2.0, successes=1, runs=4)
    assert float(success_probability(0.25, r.tries)) >= 0.99 > float(success_probability(0.25, r.tries - 1))
    assert r.seconds == 2.0 * r.tries
    best, worst = r.seconds_range
    assert best <= r.seconds <= worst
    never = repeated_runs(1.0, 0, 5)
    assert never.tries == never.seconds == float("inf") and math.isfinite(never.seconds_range[0])
    assert repeated_runs(3.0, 5, 5).seconds == 3.0  # every run succeeds: one run is enough


@pytest.mark.parametrize("esp", [1.0, 0.5, 0.03, 1e-12])
def test_a_shot_succeeds_with_p_optimum_times_esp(esp: float) -> None:
    t = qaoa_on_device(0.4, estimates=7, shots_per_estimate=10, shot_time=1e-5, esp=esp)
    assert t.p_shot == pytest.approx(0.4 * esp)
    # the fewest shots that reach 99% at that per-shot rate, training unchanged by the noise
    assert float(success_probability(0.4 * esp, t.shots)) >= 0.99 > float(success_probability(0.4 * esp, t.shots - 1))
    assert t.training_shots == 70 and t.seconds == pytest.approx((70 + t.shots) * 1e-5)
    assert t.shots >= qaoa_on_device(0.4, 7, 10, 1e-5).shots


@pytest.mark.parametrize("p", [1e-9, 3e-15, 1e-16, 8e-178, 1e-300])
def test_tiny_success_rates_give_finite_counts_at_once(p: float) -> None:
    # a routed circuit's ESP can be 1e-177: the count must come back (it once looped on n - 1 == n in floats)
    n = qaoa_on_device(1.0, 1, 1, 1e-6, esp=p).shots
    assert math.isfinite(n) and n == pytest.approx(math.log(0.01) / math.log1p(-p), rel=1e-9)
    if n < 2**53:
        assert float(success_probability(p, n)) >= 0.99 > float(success_probability(p, n - 1))
    assert qaoa_on_device(1.0, 1, 1, 1e-6, esp=5e-324).shots == float("inf")  # past the largest float


def test_esp_must_be_a_probability() -> None:
    for bad in (-0.1, 1.5):
        with pytest.raises(ValueError, match="esp"):
            qaoa_on_device(0.5, 1, 1, 1e-6, esp=bad)
    assert qaoa_on_device(0.5, 1, 1, 1e-6, esp=0.0).seconds == float("inf")


def test_qaoa_on_device_counts_training_and_sampling() -> None:
    shot = shot_seconds(depth=1000, two_qubit_depth=400)
    assert shot == pytest.approx((400 * 300 + 600 * 50 + 1000) * 1e-9)
    t = qaoa_on_device(0.2, estimates=50, shots_per_estimate=1000, shot_time=shot)
    assert t.training_shots == 50_000 and t.shots == 21  # 1 - 0.8^21 >= 0.99 > 1 - 0.8^20
    assert t.seconds == pytest.approx((50_000 + 21) * shot)
    assert qaoa_on_device(0.0, 1, 1, shot).seconds == float("inf")
    assert qaoa_on_device(1.0 + 2e-16, 1, 1, shot).shots == 1  # a norm rounded past 1
    with pytest.raises(ValueError):
        shot_seconds(10, 11)


def test_doctests() -> None:
    import doctest

    import qcpp.simulate.time_to_solution

    assert doctest.testmod(qcpp.simulate.time_to_solution).failed == 0


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


@pytest.mark.heavy
def test_quick_mode(tts, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    """The whole ``--quick`` run (3x3 with two robots, with and without an obstacle: two instances; the one-robot
    rows of the full run are recompiled by results_freshness_test)."""
    _assert_quick_run(tts, tmp_path)


def _assert_quick_run(tts, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    out = tts.main(["--quick", "--out", str(tmp_path)])
    png = (tmp_path / "figures" / "time_to_solution.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000
    md = (tmp_path / "results" / "time_to_solution.md").read_text()
    assert "examples/experiments/time_to_solution.py --quick" in md and "|---|" in md
    rows = list(csv.DictReader((tmp_path / "results" / "time_to_solution.csv").open()))
    data = json.loads((tmp_path / "results" / "time_to_solution.json").read_text())
    cfg = tts.QUICK
    assert len(out["instances"]) == 2 * len(cfg.sizes) * len(cfg.robots)  # each with and without an obstacle
    assert len(data["rows"]) == len(rows) == len(out["rows"])
    for inst in out["instances"]:
        r = inst.results
        # quick mode: every instance is small enough for exhaustive search; CP-SAT never beats it and, when it
        # proves its answer within its 2 s wall-clock limit (not on a loaded machine, so not assumed), equals it
        assert r["dfs"]["attempted"] and r["cpsat"]["cost"] >= r["dfs"]["cost"]
        assert not r["cpsat"]["proven"] or r["dfs"]["cost"] == r["cpsat"]["cost"]
        assert r["optimum"] == {"value": r["dfs"]["cost"], "proven": True}
        assert all(run["cost"] >= r["dfs"]["cost"] for m in ("anneal", "genetic") for run in r[m])
    assert {row["method"] for row in rows} == {"dfs", "cpsat", "anneal", "genetic", "qaoa", "qaoa_device"}
    assert all("IDEAL ALL-TO-ALL" in row["note"] for row in rows if row["method"] == "qaoa")
    ideal = [row for row in data["rows"] if row["method"] == "qaoa"]
    on_device = [row for row in data["rows"] if row["method"] == "qaoa_device"]
    assert ideal and len(on_device) == len(ideal) * len(tts.QUICK.devices)
    for row in on_device:
        assert row["device"] in tts.QUICK.devices and row["fits"] and row["routed_kind"] == "exact"
        ibm = row["device"].startswith("ibm_")  # the snapshots with T1 / T2: a shot succeeds with idle decoherence
        assert 0 < row["esp"] < 1 and (row["esp_idle"] is not None) == ibm
        shot_esp = row["esp_idle"] if ibm else row["esp"]
        assert shot_esp <= row["esp"] and row["p_shot"] == pytest.approx(row["p_opt"] * shot_esp)
        assert row["duration_model"] == ("device" if ibm else "assumed")
        assert "P(opt) x ESP" in row["note"] and ("idle decoherence" in row["note"]) == ibm
    twoq = {(row["instance"], row["device"]): row["routed_twoq"] for row in on_device}
    for inst in {row["instance"] for row in on_device}:  # SWAPs on heavy-hex; none on the all-to-all ion trap
        assert twoq[(inst, "ibm_fez")] > twoq[(inst, "quantinuum_helios")]
    assert "SUCCESS PER SHOT = P(opt) x ESP" in md
    assert all(json.loads(row["scenario"])["grid"] and row["qcpp_version"] for row in rows)
    assert "IDEAL ALL-TO-ALL DEVICE PROJECTION" in md
    assert not list((tmp_path / "figures").glob(".*")) and not list((tmp_path / "results").glob(".*"))
