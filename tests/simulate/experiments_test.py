"""Success measures, state measures (CVaR, reach), angle fits, annealing at a budget, and the experiment scripts."""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from qcpp.problem.cost import cost
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import anneal, dfs
from qcpp.simulate.annealing_runs import anneal_success
from qcpp.simulate.state_measures import (
    cost_distribution,
    cvar,
    layers_to_reach,
    state_metrics,
    uniform_hit_probability,
)
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.simulate.success import shots_for, success_probability, tries_for, wilson_interval
from qcpp.training.angle_fit import AngleFit, fit_angles
from qcpp.training.training import train

from .script_module import load_script

REPO = Path(__file__).resolve().parents[2]
SCRIPTS = REPO / "examples" / "experiments"


def small_two_robots() -> Scenario:
    """Two robots on 3x3; robot 0's initial path crosses the soft obstacle, so the initial state is not optimal."""
    return scenario_from_dict(
        {
            "grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1]]},
            "robots": [{"start": [0, 0], "goal": [0, 2]}, {"start": [2, 0], "goal": [2, 2]}],
        }
    )


@pytest.fixture(scope="module")
def qaoa() -> SubspaceQAOA:
    return SubspaceQAOA(small_two_robots())


# ---------------------------------------------------------------- success measures


def test_success_probability_matches_sampling_the_state(qaoa: SubspaceQAOA) -> None:
    angles = [0.2, 1.0, 0.1, 0.6]
    psi = qaoa.state(angles)
    p = qaoa.p_optimum_from_state(psi)
    assert 0.01 < p < 0.5  # a state where S matters
    optimal = set(qaoa.optimal_assignments())
    shots, runs = 20, 2000
    draws = qaoa.sample_from_state(psi, shots * runs, seed=7)
    hits = np.array([d in optimal for d in draws]).reshape(runs, shots).any(axis=1)
    predicted = float(success_probability(p, shots))
    assert abs(hits.mean() - predicted) < 4 * math.sqrt(predicted * (1 - predicted) / runs)


def test_success_probability_edges_and_precision() -> None:
    assert success_probability(0.0, 100) == 0.0
    assert success_probability(1.0, 1) == 1.0 and success_probability(1.0, 0) == 0.0
    assert success_probability(0.3, 0) == 0.0
    assert float(success_probability(1e-20, 10)) == pytest.approx(1e-19, rel=1e-9)  # 1-(1-p)^S would give 0
    grid = success_probability(np.array([[0.1], [0.5]]), np.array([1, 2, 3]))
    assert grid.shape == (2, 3) and np.allclose(grid[1], [0.5, 0.75, 0.875])
    for bad in (-0.1, 1.1, float("nan")):
        with pytest.raises(ValueError):
            success_probability(bad, 1)
    with pytest.raises(ValueError):
        success_probability(0.5, -1)


@pytest.mark.parametrize("p", [1e-4, 0.013, 0.1, 0.25, 0.5, 0.9, 0.999])
@pytest.mark.parametrize("target", [0.5, 0.9, 0.99])
def test_shots_for_is_the_fewest(p: float, target: float) -> None:
    n = shots_for(p, target)
    assert isinstance(n, int) and n >= 1
    assert 1 - (1 - p) ** n >= target - 1e-12
    if n > 1:
        assert 1 - (1 - p) ** (n - 1) < target + 1e-12


def test_tries_for_is_shots_for() -> None:
    assert [tries_for(p) for p in (0.01, 0.3, 0.9, 1.0)] == [shots_for(p) for p in (0.01, 0.3, 0.9, 1.0)]


def test_shots_for_edges() -> None:
    assert shots_for(0.0) == math.inf and shots_for(1.0) == 1
    with pytest.raises(ValueError):
        shots_for(0.5, 1.0)
    with pytest.raises(ValueError):
        shots_for(1.5)


def test_wilson_interval() -> None:
    lo, hi = wilson_interval(5, 10)
    assert (round(lo, 4), round(hi, 4)) == (0.2366, 0.7634)  # the textbook 95% value
    assert wilson_interval(0, 20)[0] == 0.0 and wilson_interval(20, 20)[1] == 1.0
    a, b = wilson_interval(3, 17), wilson_interval(14, 17)
    assert a[0] == pytest.approx(1 - b[1]) and a[1] == pytest.approx(1 - b[0])
    assert wilson_interval(30, 100)[0] < 0.3 < wilson_interval(30, 100)[1]
    with pytest.raises(ValueError):
        wilson_interval(3, 2)


# ---------------------------------------------------------------- functions of the state


def _brute_distribution(q: SubspaceQAOA, angles: list[float]) -> dict[float, float]:
    probs = q.probabilities(angles)
    out: dict[float, float] = {}
    for idx in itertools.product(*(range(d) for d in q.dims)):
        c = round(cost(q.scenario, q.assignment(idx)), 9)
        out[c] = out.get(c, 0.0) + float(probs[idx])
    return {c: w for c, w in out.items() if w > 0}


def test_cost_distribution_against_the_cost_of_every_assignment(qaoa: SubspaceQAOA) -> None:
    angles = [0.3, 0.9, 0.05, 1.7]
    values, w = cost_distribution(qaoa, angles)
    assert np.all(np.diff(values) > 0)
    brute = _brute_distribution(qaoa, angles)
    assert sorted(brute) == pytest.approx(values.tolist())
    assert [brute[c] for c in sorted(brute)] == pytest.approx(w.tolist(), abs=1e-12)
    # a state array gives the same; so does the float-diagonal path (no compact levels)
    psi = qaoa.state(angles)
    assert np.allclose(cost_distribution(qaoa, psi)[1], w)


def test_cost_distribution_without_compact_levels(qaoa: SubspaceQAOA, monkeypatch: pytest.MonkeyPatch) -> None:
    angles = [0.3, 0.9]
    ref_v, ref_w = cost_distribution(qaoa, angles)
    monkeypatch.setattr(qaoa, "cost_levels", lambda: None)
    v, w = cost_distribution(qaoa, angles)
    assert np.allclose(v, ref_v) and np.allclose(w, ref_w)


def test_cvar_by_definition(qaoa: SubspaceQAOA) -> None:
    angles = [0.3, 0.9, 0.05, 1.7]
    probs = qaoa.probabilities(angles).reshape(-1)
    costs = np.array([cost(qaoa.scenario, qaoa.assignment(np.unravel_index(k, qaoa.dims))) for k in range(probs.size)])
    order = np.argsort(costs, kind="stable")
    for alpha in (0.01, 0.2, 0.5, 1.0):
        # walk the outcomes from the cheapest, taking probability until alpha is used up
        left, acc = alpha, 0.0
        for k in order:
            take = min(left, probs[k])
            acc += take * costs[k]
            left -= take
            if left <= 0:
                break
        assert cvar(qaoa, angles, alpha) == pytest.approx(acc / alpha, abs=1e-9)
    assert cvar(qaoa, angles, 1.0) == pytest.approx(qaoa.expectation(angles), abs=1e-9)
    assert cvar(qaoa, angles, 1e-9) == pytest.approx(costs[order][probs[order] > 1e-12][0])
    for bad in (0.0, 1.5):
        with pytest.raises(ValueError):
            cvar(qaoa, angles, bad)


def test_state_metrics_agree_with_the_simulator(qaoa: SubspaceQAOA) -> None:
    angles = [0.1, 2.0]
    m = state_metrics(qaoa, angles, alpha=0.3)
    assert m.expectation == pytest.approx(qaoa.expectation(angles))
    assert m.p_optimum == pytest.approx(qaoa.p_optimum(angles))
    assert m.cvar == pytest.approx(cvar(qaoa, angles, 0.3)) and m.alpha == 0.3


def test_uniform_hit_probability_against_exhaustive_search() -> None:
    s = small_two_robots()
    lists = [enumerate_paths(s, r) for r in range(s.num_robots)]
    costs = [cost(s, list(a)) for a in itertools.product(*lists)]
    best = min(costs)
    expected = sum(abs(c - best) < 1e-9 for c in costs) / len(costs)
    assert uniform_hit_probability(SubspaceQAOA(s)) == pytest.approx(expected)


def test_layers_to_reach_is_where_the_amplitude_becomes_nonzero() -> None:
    s = scenario_from_dict({"grid": {"rows": 3, "cols": 4}, "robots": [{"start": [0, 0], "goal": [0, 3]}]})
    q = SubspaceQAOA(s)
    rng = np.random.default_rng(3)
    depth = {m: layers_to_reach(q, (m,)) for m in q.bases[0]}
    assert depth[q.bases[0][0]] == 0 and max(depth.values()) >= 2  # the test spans several depths
    for p in range(1, max(depth.values()) + 1):
        angles = rng.uniform(0.3, 2.8, 2 * p)  # generic angles: no accidental zeros
        probs = q.probabilities(angles)[...]
        for k, m in enumerate(q.bases[0]):
            assert (probs[k] > 1e-20) == (depth[m] <= p), (p, k, depth[m])
    assert layers_to_reach(q, (q.bases[0][-1],), max_layers=0) is None
    assert layers_to_reach(q, (0,)) is None  # the empty edge set is no basis path


# ---------------------------------------------------------------- angle fits


def test_fit_angles_improves_each_objective(qaoa: SubspaceQAOA) -> None:
    x0 = [0.1, 0.4, 0.2, 0.3]
    start = state_metrics(qaoa, x0, 0.2)
    e = fit_angles(qaoa, [x0], "expectation", maxiter=60)
    c = fit_angles(qaoa, [x0], "cvar", alpha=0.2, maxiter=60)
    p = fit_angles(qaoa, [x0, [0.0, 1.0, 0.0, 1.0]], "p_optimum", maxiter=60)
    assert e.value < start.expectation and e.value == pytest.approx(e.metrics.expectation)
    assert c.value < start.cvar and c.value == pytest.approx(c.metrics.cvar)
    assert p.value > start.p_optimum and p.value == pytest.approx(p.metrics.p_optimum)
    assert p.restarts == 2 and p.p == 2 and len(p.angles) == 4
    assert e.trace[0] == pytest.approx(start.expectation)  # COBYLA evaluates the start first
    assert e.value == min(e.trace) and c.value == min(c.trace) and p.value == max(p.trace)  # best point seen
    assert e.evaluations == len(e.trace) + 1  # one start: its trace plus the final metrics


def test_fit_angles_rejects_bad_input(qaoa: SubspaceQAOA) -> None:
    with pytest.raises(ValueError):
        fit_angles(qaoa, [[0.1, 0.2]], "median")  # type: ignore[arg-type]
    with pytest.raises(ValueError):
        fit_angles(qaoa, [])
    with pytest.raises(ValueError):
        fit_angles(qaoa, [[0.1, 0.2], [0.1, 0.2, 0.3, 0.4]])
    with pytest.raises(ValueError):
        fit_angles(qaoa, [[0.1, 0.2, 0.3]])


def test_angle_fit_from_training_keeps_the_best(qaoa: SubspaceQAOA) -> None:
    runs = [train(qaoa, 1, "lbfgsb", init="random", seed=k, maxiter=15) for k in range(3)]
    fit = AngleFit.from_training(qaoa, runs, alpha=0.25)
    best = min(runs, key=lambda r: r.expectation)
    assert fit.angles == best.angles and fit.value == best.expectation
    assert fit.metrics.expectation == pytest.approx(best.expectation)
    assert fit.evaluations == sum(r.num_evaluations for r in runs) + 1
    with pytest.raises(ValueError):
        AngleFit.from_training(qaoa, [])


# ---------------------------------------------------------------- annealing at a budget


def test_anneal_success_counts_optimal_runs() -> None:
    s = small_two_robots()
    best = dfs(s).cost.total
    rows = anneal_success(s, [3, 400], range(6), best)  # 3 < the default 10 cycles: clamped
    assert [r.iterations for r in rows] == [3, 400] and all(r.runs == 6 for r in rows)
    direct = [anneal(s, seed=k, iterations=400) for k in range(6)]
    assert rows[1].successes == sum(d.cost.total == best for d in direct)
    assert rows[1].evaluations == pytest.approx(np.mean([d.evaluated for d in direct]))
    assert rows[1].max_evaluations == max(d.evaluated for d in direct)
    impossible = anneal_success(s, [50], range(3), best - 1.0)
    assert impossible[0].successes == 0 and impossible[0].rate == 0.0
    lo, hi = rows[1].interval()
    assert lo <= rows[1].rate <= hi
    with pytest.raises(ValueError):
        anneal_success(s, [0], range(2), best)
    with pytest.raises(ValueError):
        anneal_success(s, [10], [], best)


# ---------------------------------------------------------------- the scripts' quick mode (smoke test)


def _load(name: str) -> ModuleType:
    return load_script(SCRIPTS / f"{name}.py", f"experiment_{name}")


@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "figures"),
    [
        ("qaoa_3x3", ["qaoa_3x3_cost.png", "qaoa_3x3_initial.png", "qaoa_3x3_optimum.png"]),
        ("annealing_two_robots", ["annealing_cost.png", "annealing_two_robots_4x4_paths.png"]),
        ("qaoa_two_robots", ["qaoa_two_robots.png"]),
    ],
)
def test_script_quick_mode(name: str, figures: list[str], tmp_path: Path) -> None:
    _check_quick_mode(name, figures, tmp_path)


@pytest.mark.heavy
def test_mixer_warm_start_quick_mode(tmp_path: Path) -> None:
    out = _check_quick_mode("mixer_warm_start", [], tmp_path)
    ceiling = out["examples/two_robots_4x4.toml"]["ceiling"]
    warm = out["examples/two_robots_4x4.toml"]["warm"]
    assert [c.p for c in ceiling] == [w.p for w in warm] == [1, 2]
    assert all(c.p_optimum >= w_row["p_opt"] - 1e-12 for c, w_row in
               zip(ceiling, (r for r in out["rows"] if r["table"] == "mixer_only")))


@pytest.mark.heavy
def test_multi_angle_quick_mode(tmp_path: Path) -> None:
    out = _check_quick_mode("multi_angle", [], tmp_path)
    rows = [r for r in out["rows"] if r["table"] == "trained"]
    ceilings = [r for r in out["rows"] if r["table"] == "ceiling"]
    assert [r["p"] for r in rows] == [r["p"] for r in ceilings] == [1, 2]
    assert all(c["p_opt"] >= r["p_opt"] - 1e-12 for r, c in zip(rows, ceilings))
    sizes = [len(r["betas"]) for r in rows]
    assert sizes == [r["parameters"] for r in rows] == [sizes[0], 2 * sizes[0]]


def _check_quick_mode(name: str, figures: list[str], tmp_path: Path):  # type: ignore[no-untyped-def]
    out = _load(name).main(["--quick", "--out", str(tmp_path)])
    for f in figures:
        data = (tmp_path / "figures" / f).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 5000
    md = (tmp_path / "results" / f"{name}.md").read_text()
    assert f"examples/experiments/{name}.py --quick" in md and "| --- |" not in md and "|---|" in md
    assert not list((tmp_path / "figures").glob(".*"))  # no temporary files left behind
    records = json.loads((tmp_path / "results" / f"{name}.json").read_text())
    assert records["command"] == f"python examples/experiments/{name}.py --quick" and records["rows"]
    for row in records["rows"]:  # every row says what produced it (the freshness test relies on this)
        assert scenario_from_dict(row["scenario"]) and isinstance(row["options"], dict) and row["qcpp_version"]
        if row.get("method") == "qaoa":
            assert row["qubits"] > 0 and row["depth"] >= row["two_qubit_depth"] > 0
            assert len(row["angles"]) == 2 * row["p"]
    if name == "qaoa_3x3":
        best = out["dfs"].paths
        assert all(m == best for m in out["most_probable"].values())
    elif name == "annealing_two_robots":
        r = out["two_robots_4x4"]
        assert r["anneal"].cost.total == r["dfs"].cost.total
    elif name == "qaoa_two_robots":
        s = load_scenario(REPO / "examples" / "two_robots_4x4.toml")
        assert out["optima"]["two_robots_4x4"] == dfs(s).cost.total
        fits = out["fits"]["two_robots_4x4"]
        assert fits[(2, "p_optimum")].value >= fits[(2, "expectation")].metrics.p_optimum
    return out


@pytest.mark.parametrize("module", ["simulate.success", "simulate.state_measures", "training.angle_fit",
                                    "simulate.annealing_runs"])  # fmt: skip
def test_doctests(module: str) -> None:
    import doctest
    import importlib

    assert doctest.testmod(importlib.import_module(f"qcpp.{module}")).failed == 0


# ---------------------------------------------------------------- the ensemble study


def test_ensemble_cells_parse_and_bad_ones_are_refused() -> None:
    import argparse

    mod = _load("ensembles")
    assert mod.parse_cell("3x4/2") == (3, 4, 2)
    for bad in ("3x3", "3x3/0", "1x3/1", "axb/1"):
        with pytest.raises(argparse.ArgumentTypeError, match="cell"):
            mod.parse_cell(bad)
    cfg = mod.parse_args(["--cells", "3x3/1", "4x4/1", "--out", "unused"])[1]
    assert (cfg.instances_in("3x3/1"), cfg.instances_in("4x4/1")) == (300, 30)  # the full study's override
    argv = ["--cells", "3x3/1", "3x3/2", "--instances", "5", "3x3/2=7", "--out", "unused"]
    _, cfg, _, _, command, _, _ = mod.parse_args(argv)
    assert (cfg.instances_in("3x3/1"), cfg.instances_in("3x3/2")) == (5, 7) and "--instances 5 3x3/2=7" in command
    for bad in (["--instances", "0"], ["--instances", "3x3/1=x"], ["--cells", "3x3/2", "--instances", "3x3/1=4"]):
        with pytest.raises(SystemExit):
            mod.parse_args([*bad, "--out", "unused"])
    assert mod.quartiles([1.0, 2.0, 3.0, 4.0, 5.0]) == (3.0, 2.0, 4.0)
    assert mod.quartiles([1.0, math.inf, math.inf]) == (math.inf, 1.0, math.inf)


def test_ensembles_reuse_takes_over_an_earlier_runs_records(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """With every instance in the earlier run, nothing is computed (no cluster starts) and the records are the
    earlier ones; an earlier run with other settings is refused with one line and exit 2."""
    mod = _load("ensembles")
    committed = json.loads(Path("docs/results/ensembles.json").read_text())
    argv = ["--cells", "3x3/2", "3x3/1", "--instances", "2", "--reuse", "docs/results/ensembles.json"]
    out = mod.main([*argv, "--out", str(tmp_path)])
    want = [r for cell in ("3x3/2", "3x3/1") for r in committed["rows"] if r["cell"] == cell and r["index"] < 2]
    assert out["rows"] == want and out["results"] == []
    written = json.loads((tmp_path / "results" / "ensembles.json").read_text())
    assert written["reused"]["instances"] == 4 and written["reused"]["command"] == committed["command"]
    assert "--reuse" not in written["command"]  # the records are what the recorded command computes
    note = (tmp_path / "results" / "ensembles.md").read_text()
    assert "computed 0 instances in" in note and "took over the records of 4 instances from an earlier run" in note
    with pytest.raises(SystemExit) as exit_:
        mod.main([*argv, "--seed", "1", "--out", str(tmp_path / "other")])
    assert exit_.value.code == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == "--reuse: the earlier run's seed is 0, this run's 1"
    with pytest.raises(SystemExit):
        mod.parse_args([*argv[:-1], str(tmp_path / "missing.json"), "--out", "unused"])
    assert "--reuse: no results file at" in capsys.readouterr().err
    other_settings = json.dumps({"qcpp_version": mod.qcpp.__version__, "config": {}})
    for i, text in enumerate(("not json", "[1, 2]", other_settings)):
        bad = tmp_path / f"bad{i}.json"
        bad.write_text(text)
        with pytest.raises(SystemExit) as exit_:
            mod.main([*argv[:-1], str(bad), "--out", str(tmp_path / "bad")])
        assert exit_.value.code == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("--reuse: "), err


def test_ensembles_unreachable_scheduler_is_one_line_and_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """The OSError ``dask_client`` raises for an address it cannot reach ends the script as the qcpp commands end
    on an OSError: one line on stderr, exit 2, nothing written."""
    import qcpp.simulate.cluster

    mod = _load("ensembles")

    def unreachable(address: str, workers: int | None = None) -> None:
        raise OSError(f"dask scheduler {address!r} unreachable: timed out")

    monkeypatch.setattr(qcpp.simulate.cluster, "dask_client", unreachable)
    with pytest.raises(SystemExit) as exit_:
        mod.main(["--cells", "3x3/1", "--instances", "1", "--scheduler", "tcp://10.0.0.5:8786", "--out", str(tmp_path)])
    assert exit_.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["error: dask scheduler 'tcp://10.0.0.5:8786' unreachable: timed out"], err
    assert not (tmp_path / "results").exists()


def test_ensemble_devices_bad_input_is_refused_with_its_reason(capsys: pytest.CaptureFixture[str]) -> None:
    mod = _load("ensemble_devices")
    cases = ((["--devices", "nowhere"], "--devices: unknown nowhere"), (["--cells", "5x5/3"], "--cells: 5x5/3 not in"),
             (["--depths", "9"], "--depths: each in 1..8"), (["--instances", "0"], "--instances: 1..30"))
    for argv, message in cases:
        with pytest.raises(SystemExit) as exit_:
            mod.parse_args([*argv, "--out", "unused"])
        assert exit_.value.code == 2 and message in capsys.readouterr().err, argv


@pytest.mark.heavy
def test_ensemble_devices_quick_mode(tmp_path: Path) -> None:
    """One instance at depth 1 on an all-to-all and a calibrated heavy-hex device: both fit, ESP in (0, 1], the
    reference's figures carried over, the table written; and each row is the committed full run's row of that
    instance, depth and device, field for field (so this is also the freshness check of that calibrated row:
    results_freshness_test's ``ENSEMBLE_CALIBRATED_CELLS``)."""
    mod = _load("ensemble_devices")
    rows = mod.main(["--quick", "--out", str(tmp_path)])["rows"]
    assert [(r["cell"], r["index"], r["p"], r["device"]) for r in rows] == [
        ("3x3/1", 0, 1, "quantinuum_helios"), ("3x3/1", 0, 1, "ibm_fez")]
    committed = {(r["cell"], r["index"], r["p"], r["device"]): r
                 for r in json.loads((REPO / "docs" / "results" / "ensemble_devices.json").read_text())["rows"]}
    for r in rows:
        assert r == committed[(r["cell"], r["index"], r["p"], r["device"])], r["device"]
    assert all(r["fits"] and 0 < r["esp"] <= 1 and r["tts_99"] > 0 for r in rows)
    helios, fez = rows
    assert helios["routed_twoq"] < fez["routed_twoq"]  # all-to-all needs no SWAPs
    assert helios["esp_idle"] is None and 0 < fez["esp_idle"] < fez["esp"]  # idle decoherence where T1/T2 are known
    assert fez["p_shot"] == pytest.approx(fez["p_opt"] * fez["esp_idle"])
    md = (tmp_path / "results" / "ensemble_devices.md").read_text()
    assert "`python examples/experiments/ensemble_devices.py --quick`" in md and "| 3x3/1 | ibm_fez | 1 |" in md


@pytest.mark.heavy
def test_ensembles_quick_mode(tmp_path: Path) -> None:
    out = _check_quick_mode("ensembles", ["ensembles.png"], tmp_path)
    rows = [r for r in out["rows"] if r["method"] == "qaoa"]
    assert {r["cell"] for r in rows} == {"3x3/1", "3x3/2"} and {r["p"] for r in rows} == {1, 2, 3}
    assert all(r["best_p_opt"] >= r["p_opt"] - 1e-12 for r in rows)
    assert {r["method"] for r in out["rows"]} == {"dfs", "cpsat", "anneal", "genetic", "qaoa"}


@pytest.mark.heavy
def test_training_restarts_quick_mode(tmp_path: Path) -> None:
    """The single-start training on the first instances of the 3x3 cells: the references copied, the best known
    bounding all three, and the single-start schedule's own Gibbs temperature used (with the default's starts at
    p = 1, only ``gibbs_scale`` can make its angles differ there)."""
    mod = _load("training_restarts")
    out = mod.main(["--quick", "--out", str(tmp_path)])
    rows = out["rows"]
    assert {r["cell"] for r in rows} == {"3x3/1", "3x3/2"} and {r["p"] for r in rows} == {1, 2, 3}
    assert all(r["best_known"] == max(r["best_p_opt"], r["default_p_opt"], r["p_opt"]) for r in rows)
    assert all(r["options"]["gibbs_scale"] == mod.ALTERNATIVE["gibbs_scale"] for r in rows)
    p1 = [r for r in rows if r["p"] == 1]
    assert any(r["angles"] != r["default_angles"] for r in p1)
    md = (tmp_path / "results" / "training_restarts.md").read_text()
    assert "`python examples/experiments/training_restarts.py --quick`" in md and "|---|" in md
