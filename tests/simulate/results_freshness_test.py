"""The committed results in docs/results cannot go stale unnoticed.

Every row of every ``docs/results/*.json`` records its scenario, its options and the qcpp version. This test
recomputes the cheap columns from those records with today's code and fails when they disagree:

* the compiled circuit's qubits, depth, two-qubit depth and gate count at the row's ``p`` (every file with
  QAOA rows);
* the routed circuit on the row's device (routed two-qubit count, depth, two-qubit depth, ESP) for the
  time-to-solution study's device rows;
* ``P(optimum)`` (and ``<C>`` where recorded) of the state at the row's recorded angles, on the exact
  feasible-subspace simulator;
* exhaustive search (cost, assignments scored) and the seeded simulated-annealing runs (cost, evaluations,
  paths), which are deterministic;
* every column derived by formula (shots and runs for 99%, time per shot, P(opt) x ESP, the 99% times).

The default run recomputes what is cheap (every circuit: the estimator takes 5 s for all files together; states
of at most :data:`CHEAP_DIMENSION` assignments; the 3x3/1 device rows); ``-m heavy`` recomputes every state of at
most :data:`HEAVY_DIMENSION` assignments and the device rows of :func:`checked_devices` (every instance, on every
device but one of the two calibrated IBM devices, alternating, so that both are checked within CI's time budget).
After a compiler change, regenerate with the commands in docs/experiments.md (``python examples/experiments/
<name>.py``; the file's ``command`` field names it).
"""

from __future__ import annotations

import csv
import json
import math
from collections.abc import Sequence
from functools import cache
from pathlib import Path
from typing import Any

import pytest

import qcpp
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.routing.context import RoutingContext
from qcpp.simulate.success import shots_for, tries_for
from qcpp.simulate.time_to_solution import GATE_MODEL, shot_seconds
from qcpp.training.objectives import Gibbs
from qcpp.training.training import cost_scale

RESULTS = Path(__file__).resolve().parents[2] / "docs" / "results"
FILES = ("time_to_solution", "qaoa_training", "qaoa_3x3", "annealing_two_robots", "qaoa_two_robots", "mixer_warm_start",
         "multi_angle")
CIRCUIT_FILES = ("time_to_solution", "qaoa_training", "qaoa_3x3", "qaoa_two_robots", "mixer_warm_start", "multi_angle")
CHEAP_DIMENSION = 2_000
"""States of up to this many assignments are recomputed in the default run."""
HEAVY_DIMENSION = 100_000
"""States of more assignments (two_robots_5x5: 73.8 million, 1.2 GB) are not recomputed, even under ``heavy``."""
CHEAP_DEVICE_INSTANCES = ("3x3/1",)
"""Time-to-solution instances whose routed device rows the default run recomputes (~1 s per device)."""
CALIBRATED_DEVICES = ("ibm_fez", "ibm_torino")
"""The devices whose compiles run Qiskit's O3 three times and our placement searches on the device and on the
abstract lattices (tens of CPU-seconds per row): the heavy step recompiles each instance on one of them."""


def checked_devices(devices: Sequence[str], index: int, calibrated: bool = True) -> tuple[str, ...]:
    """The devices (of ``devices``) whose rows the heavy step recomputes for an instance: the uncalibrated ones, and
    with ``calibrated`` the :data:`CALIBRATED_DEVICES` entry ``index`` picks (``index`` even: ``ibm_fez``, odd:
    ``ibm_torino``), so that instances taken in turn check both calibrated devices at one calibrated compile per
    depth each.

    >>> checked_devices(["ibm_fez", "ibm_torino", "google_willow"], 1)
    ('ibm_torino', 'google_willow')
    >>> checked_devices(["ibm_fez", "ibm_torino", "google_willow"], 1, calibrated=False)
    ('google_willow',)
    """
    chosen = CALIBRATED_DEVICES[index % len(CALIBRATED_DEVICES)] if calibrated else None
    return tuple(d for d in devices if d not in CALIBRATED_DEVICES or d == chosen)


def _load(name: str) -> dict[str, Any]:
    return json.loads((RESULTS / f"{name}.json").read_text())


@cache
def _scenario(text: str) -> Scenario:
    return scenario_from_dict(json.loads(text))


@cache
def _circuit(text: str, p: int, initial: str = "initial_path") -> dict[str, int]:
    from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
    from qcpp.plan.options import PlanOptions

    plan = PlanOptions(initial=initial)  # type: ignore[arg-type]
    est = estimate_point(Point.from_scenario(_scenario(text), p), EstimateOptions(plan=plan, depth="exact"))
    assert est.depth is not None
    return {"qubits": est.qubits, "depth": est.depth.depth, "two_qubit_depth": est.depth.two_qubit_depth,
            "gates": est.cost.total}


@cache
def _routed(text: str, p: int, device: str) -> dict[str, Any]:
    return _routed_in(text, p, device, None)


def _routed_in(text: str, p: int, device: str, context: RoutingContext | None) -> dict[str, Any]:
    """The estimator's routed fields of the scenario ``text`` at depth ``p`` on ``device``, routed with ``context``
    (the memos the rows of one scenario share, as the experiment shares them; the fields do not depend on it)."""
    from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
    from qcpp.estimators.routed import routed_fields

    s = _scenario(text)
    est = estimate_point(Point.from_scenario(s, p), EstimateOptions(depth="none"))
    c = est.cost
    return routed_fields(s, p, est.options.plan, device, qubits=est.qubits, cx=c.two_qubit,
                         one_qubit=c.single_qubit, total_gates=c.total, context=context)


@cache
def _qaoa(text: str, initial: str = "initial_path") -> Any:
    from qcpp.simulate.subspace import SubspaceQAOA

    return SubspaceQAOA(_scenario(text), initial=initial)  # type: ignore[arg-type]


@cache
def _dimension(text: str) -> int:
    """Feasible assignments of the scenario (the subspace simulator's dimension), by path enumeration."""
    s = _scenario(text)
    return math.prod(len(enumerate_paths(s, k)) for k in range(s.num_robots))


def _key(row: dict[str, Any]) -> str:
    return json.dumps(row["scenario"], sort_keys=True)


def _label(name: str, row: dict[str, Any]) -> tuple[Any, ...]:
    return (name, row.get("instance", row.get("scenario_file")), row.get("method"), row.get("p"), row.get("device"))


def _rows(name: str, heavy: bool, cheap: Any) -> list[dict[str, Any]]:
    """The file's rows: all of them (heavy) or those ``cheap(row)`` accepts."""
    return [r for r in _load(name)["rows"] if heavy or cheap(r)]


SAME_RESULTS: dict[str, frozenset[str]] = {"0.2.0": frozenset({"0.1.0"})}
"""Version -> earlier versions whose committed results it still produces unchanged. 0.2.0 moved every module into
the one package ``qcpp`` and changed no circuit, count, state or solver run (``scripts/behaviour_fingerprint.py``
gives the same hashes on both); the recomputations below check every recomputable column of every file against
today's code either way. A version that changes what the studies compute gets no entry: its results must be
regenerated."""


def _current(version: str) -> bool:
    return version == qcpp.__version__ or version in SAME_RESULTS.get(qcpp.__version__, frozenset())


@pytest.mark.parametrize("name", FILES)
def test_every_row_records_scenario_options_and_version(name: str) -> None:
    data = _load(name)
    assert _current(data["qcpp_version"]), f"regenerate docs/results/{name}.* for qcpp {qcpp.__version__}"
    assert data["command"].startswith(f"python examples/experiments/{name}.py"), data["command"]
    assert "--quick" not in data["command"], f"docs/results/{name}.json is a quick run"
    assert data["rows"]
    for row in data["rows"]:
        assert _current(row["qcpp_version"])
        assert isinstance(row["options"], dict)
        _scenario(_key(row))  # a valid scenario
    md = (RESULTS / f"{name}.md").read_text()
    assert f"qcpp {data['qcpp_version']}" in md and "quick mode" not in md


@pytest.mark.parametrize("name", CIRCUIT_FILES)
def test_circuit_columns_match_the_compiler(name: str) -> None:
    checked = 0
    for row in _load(name)["rows"]:
        if "qubits" not in row or row.get("method") == "qaoa_device":
            continue
        want = _circuit(_key(row), int(row["p"]), row["options"].get("initial", "initial_path"))
        got = {k: row[k] for k in want if k in row}
        assert got == {k: want[k] for k in got}, _label(name, row)
        checked += 1
    assert checked > 0


CHEAP_OR_EVERY_ROW = (pytest.param(False, id="cheap"), pytest.param(True, id="every_row", marks=pytest.mark.heavy))
"""The ``heavy`` argument of a recomputation: the default run checks the cheap rows, the heavy step every row."""


def _device_instances() -> list[Any]:
    """One parameter per time-to-solution instance with device rows, with the devices to recompute: the cheap ones
    in the default run on every device; every other one in the heavy step on the uncalibrated devices, and on a
    calibrated one for one instance of each of the first :data:`CALIBRATED_SIZES` sizes (with or without the
    obstacle, in turn along the sizes, on :func:`checked_devices`' device of that turn). Past those sizes the
    devices of :data:`SAMPLED_DEVICES` are recompiled for one instance of each size too, in the same turn. One test
    per instance, so that the heavy step's two workers share the recompilations (the largest instances take minutes
    each)."""
    rows = [r for r in _load("time_to_solution")["rows"] if r["method"] == "qaoa_device"]
    devices = tuple(dict.fromkeys(r["device"] for r in rows))
    names = list(dict.fromkeys(r["instance"] for r in rows))
    sizes = list(dict.fromkeys(n.removesuffix(OBSTACLE_SUFFIX) for n in names))
    params = []
    for n in names:
        k = sizes.index(n.removesuffix(OBSTACLE_SUFFIX))
        in_turn = n.endswith(OBSTACLE_SUFFIX) == (k % 2 == 1)
        checked = checked_devices(devices, k, calibrated=k < CALIBRATED_SIZES and in_turn)
        if k >= CALIBRATED_SIZES and not in_turn:
            checked = tuple(d for d in checked if d not in SAMPLED_DEVICES)
        params.append(pytest.param(n, devices, id=n) if n in CHEAP_DEVICE_INSTANCES else
                      pytest.param(n, checked, id=n, marks=pytest.mark.heavy))
    return params


CALIBRATED_SIZES = 2
"""Sizes (in the study's order: 3x3 with one and two robots first) whose calibrated IBM rows the heavy step
recompiles, one instance each. At the study's depth (p = 5) every circuit has more two-qubit gates than the
placement search takes (:attr:`~qcpp.routing.options.RoutingOptions.placement_max_twoq`), so a calibrated compile
runs the same steps on each (the greedy routings, Qiskit's O3 candidates, ESP scoring) on a longer circuit: 3x3/3
takes 18 CPU-seconds on ``ibm_fez``, a 4x4 or 5x5 instance 30-90. The calibrated placement searches run on the
smaller circuit of the ensemble's one-robot 3x3 row at depth 1 (the ensemble experiment's quick run, see
:data:`ENSEMBLE_CALIBRATED_CELLS`); the larger instances stay recompiled on the uncalibrated devices."""

SAMPLED_DEVICES = ("google_willow",)
"""Uncalibrated devices whose compiles of the larger instances take tens of CPU-seconds (the cell layout with local
ancillas on Willow's grid, at the study's depth): past the first :data:`CALIBRATED_SIZES` sizes the heavy step
recompiles them for one instance per size, with or without the obstacle in turn; the same steps run on both."""

OBSTACLE_SUFFIX = " +obst"
"""How the time-to-solution study names the instance of a size with an obstacle."""


@pytest.mark.parametrize(("instance", "devices"), _device_instances())
def test_device_rows_match_the_router(instance: str, devices: tuple[str, ...]) -> None:
    checked = 0
    for r in _load("time_to_solution")["rows"]:
        if r["method"] != "qaoa_device" or r["instance"] != instance or r["device"] not in devices:
            continue
        want = _routed(_key(r), int(r["p"]), r["device"])
        assert r["device"] == want["device"] and r["fits"] == want["fits"], _label("time_to_solution", r)
        for k in ("routed_kind", "routed_twoq", "routed_depth", "routed_twoq_depth"):
            assert r[k] == want[k], (_label("time_to_solution", r), k)
        _check_esp(r, want, "time_to_solution")
        if want["duration_s"] is not None:
            assert r["duration_model"] == "device"
            assert r["shot_us"] == pytest.approx(want["duration_s"] * 1e6, rel=1e-9)
        checked += 1
    assert checked == len(devices)


@pytest.mark.parametrize("heavy", CHEAP_OR_EVERY_ROW)
def test_recorded_angles_give_the_recorded_state(heavy: bool) -> None:
    checked = 0
    for name in ("time_to_solution", "qaoa_3x3", "qaoa_two_robots", "qaoa_training", "mixer_warm_start"):
        for r in _load(name)["rows"]:
            if r.get("method") != "qaoa" or "angles" not in r:
                continue
            if _dimension(_key(r)) > (HEAVY_DIMENSION if heavy else CHEAP_DIMENSION):
                continue
            q = _qaoa(_key(r), r["options"].get("initial", "initial_path"))
            assert len(r["angles"]) == 2 * r["p"], _label(name, r)
            assert q.p_optimum(r["angles"]) == pytest.approx(r["p_opt"], rel=1e-6, abs=1e-12), _label(name, r)
            e = r.get("expectation", r.get("e_final"))
            if e is not None:
                assert q.expectation(r["angles"]) == pytest.approx(e, rel=1e-6, abs=1e-9), _label(name, r)
            checked += 1
    assert checked > 0


@pytest.mark.parametrize("heavy", CHEAP_OR_EVERY_ROW)
def test_recorded_multi_angle_betas_give_the_recorded_state(heavy: bool) -> None:
    """Multi-angle rows (gammas 0, a product state: cheap even at 4x4): P(optimum) and ``<C>`` from the betas."""
    import numpy as np

    from qcpp.training.mixer_only import multi_robot_states, p_optimum_and_gradients, product_objective
    from qcpp.training.objectives import Expectation

    checked = 0
    for r in _load("multi_angle")["rows"]:
        cheap = r["scenario_file"] == "examples/two_robots_4x4.toml"
        if _dimension(_key(r)) > HEAVY_DIMENSION or not (heavy or cheap):
            continue
        q = _qaoa(_key(r))
        probs = [abs(v) ** 2 for v in multi_robot_states(q, r["betas"], r["p"])]
        optima = [tuple(int(i) for i in np.unravel_index(k, q.dims)) for k in q.optimum()[1]]
        assert p_optimum_and_gradients(probs, optima)[0] == pytest.approx(r["p_opt"], rel=1e-6, abs=1e-12), r["p"]
        assert product_objective(q, probs, Expectation())[1] == pytest.approx(r["expectation"], rel=1e-6, abs=1e-9)
        checked += 1
    assert checked > 0


def test_exhaustive_search_and_seeded_annealing_rows() -> None:
    from qcpp.problem.solvers import anneal, dfs

    checked = 0
    for name in ("qaoa_3x3", "annealing_two_robots"):
        for r in _load(name)["rows"]:
            s = _scenario(_key(r))
            if r["method"] == "dfs" and math.prod(r.get("paths_per_robot", [1])) <= 40_000:
                sol = dfs(s)
                assert (sol.cost.total, sol.evaluated) == (r["cost"], r["evaluated"]), _label(name, r)
                checked += 1
            elif r["method"] == "anneal" and r.get("evaluated", 0) and s.grid.rows <= 4:
                o = r["options"]
                sol = anneal(s, seed=o["seed"], iterations=o["iterations"])
                got = (sol.cost.total, sol.evaluated, list(sol.paths))
                assert got == (r["cost"], r["evaluated"], r["paths"]), _label(name, r)
                checked += 1
            elif r["method"] == "anneal_seeds":  # successes = runs that reached the exhaustive optimum
                best = next(d["cost"] for d in _load(name)["rows"] if d["method"] == "dfs" and _key(d) == _key(r))
                assert r["successes"] == sum(c <= best + 1e-9 for c in r["costs"]), _label(name, r)
    assert checked >= 4


def _check_solver_formulas(r: dict[str, Any]) -> None:
    """The columns both time-to-solution studies derive by formula from a row's own fields: an anneal or genetic
    row's successes, tries and time for 99%; a QAOA row's time per shot, shots and time for 99% (and its ``p``)."""
    if r["method"] in ("anneal", "genetic"):
        assert r["successes"] == sum(c <= r["optimum"] + 1e-9 for c in r["run_costs"])
        assert r["tries_99"] == tries_for(r["successes"] / r["runs"])
        assert r["tts_99"] == pytest.approx(r["run_seconds"] * r["tries_99"])
    elif r["method"] == "qaoa":
        o = r["options"]
        shot = shot_seconds(r["depth"], r["two_qubit_depth"], o["gate_model"])
        assert r["shot_us"] == pytest.approx(shot * 1e6) and r["p"] == o["p"]
        assert r["shots_99"] == shots_for(min(1.0, r["p_opt"]))
        assert r["training_shots"] == r["circuit_estimates"] * o["shots_per_estimate"]
        assert r["tts_99"] == pytest.approx((r["training_shots"] + r["shots_99"]) * shot)


def _check_esp(r: dict[str, Any], want: dict[str, Any], study: str) -> None:
    """``r``'s ESP of the gates and with idle decoherence are the router's (``want``); idle where the device has
    T1 / T2 (the IBM snapshots), ``None`` elsewhere."""
    assert r["esp"] == pytest.approx(want["esp"], rel=1e-9), _label(study, r)
    if want["esp_idle"] is None:
        assert r["esp_idle"] is None, _label(study, r)
    else:
        assert r["esp_idle"] == pytest.approx(want["esp_idle"], rel=1e-9), _label(study, r)
    assert (r["esp_idle"] is not None) == r["device"].startswith("ibm_") or not r["fits"], _label(study, r)


def _check_device_time(r: dict[str, Any], training_shots: int) -> None:
    """A device row that fits: the assumed shot time from its routed depths, a shot's success ``P(optimum) x ESP``
    (ESP with idle decoherence where the row has it), the shots for 99% and the 99% time with ``training_shots``
    counted at the shot time."""
    if r["duration_model"] == "assumed":
        shot_us = shot_seconds(r["routed_depth"], r["routed_twoq_depth"], GATE_MODEL) * 1e6
        assert r["shot_us"] == pytest.approx(shot_us)
    shot_esp = r["esp"] if r["esp_idle"] is None else r["esp_idle"]
    assert r["esp_idle"] is None or r["esp_idle"] < r["esp"]  # idling only loses
    assert r["p_shot"] == pytest.approx(min(1.0, r["p_opt"]) * shot_esp, rel=1e-12)
    assert r["shots_99"] == shots_for(r["p_shot"])
    assert r["tts_99"] == pytest.approx((training_shots + r["shots_99"]) * r["shot_us"] * 1e-6)


def test_time_to_solution_derived_columns() -> None:
    rows = _load("time_to_solution")["rows"]
    methods = {r["method"] for r in rows}
    assert methods == {"dfs", "cpsat", "anneal", "genetic", "qaoa", "qaoa_device"}
    ideal = {(r["instance"], r["p"]): r for r in rows if r["method"] == "qaoa"}
    for r in rows:
        _check_solver_formulas(r)
        if r["method"] == "dfs":
            s = _scenario(_key(r))
            if r["size"] <= 4:  # the path counts, by enumeration where it is cheap
                assert r["assignments"] == math.prod(len(enumerate_paths(s, k)) for k in range(s.num_robots))
            if r["attempted"]:
                assert r["tts_99"] == r["seconds"]
        elif r["method"] == "qaoa":
            assert r["p_opt"] == pytest.approx(r["p_opt_by_level"][-1])
        elif r["method"] == "qaoa_device":
            twin = ideal[(r["instance"], r["p"])]  # the same trained state and training
            assert (r["p_opt"], r["training_shots"]) == (twin["p_opt"], twin["training_shots"])
            assert r["options"]["device"] == r["device"]
            if r["fits"]:
                _check_device_time(r, r["training_shots"])


def test_time_to_solution_csv_holds_the_json_rows() -> None:
    rows = _load("time_to_solution")["rows"]
    with (RESULTS / "time_to_solution.csv").open(newline="") as fh:
        table = list(csv.DictReader(fh))
    assert len(table) == len(rows)
    for a, b in zip(table, rows):
        assert a["instance"] == b["instance"] and a["method"] == b["method"]
        assert json.loads(a["scenario"]) == b["scenario"] and json.loads(a["options"]) == b["options"]


# ---------------------------------------------------------------- the ensemble study (experiments/ensembles.py)

ENSEMBLE_FILES = tuple(sorted(p.stem for p in RESULTS.glob("ensembles*.json")))


@cache
def _ensemble_file(name: str) -> dict[str, Any]:
    """An ensemble results file, read once per process (it is large; the tests only read it)."""
    return _load(name)


ENSEMBLE_CELLS = tuple(
    pytest.param(name, cell, id=f"{name}-{cell}")
    for name in ENSEMBLE_FILES for cell in _ensemble_file(name)["config"]["cells"]
)
"""(file, cell) of every committed ensemble cell: one test per cell, so the heavy step's two workers share them."""
CHEAP_ENSEMBLE_INSTANCES = 2
"""Instances per cell whose states the default run recomputes (and the first one's circuits; ``heavy``: every
instance's states and circuits)."""


@cache
def _ensemble_rows(name: str, cell: str) -> tuple[dict[str, Any], ...]:
    """The rows of one cell of an ensemble results file (read once per process: the file is large)."""
    return tuple(r for r in _ensemble_file(name)["rows"] if r["cell"] == cell)


@pytest.mark.parametrize("name", ENSEMBLE_FILES)
def test_ensemble_rows_are_the_generators_instances(name: str) -> None:
    """Every row records its scenario, options and version; the scenario is the seeded generator's instance."""
    from qcpp.problem.ensembles import random_scenario

    data = _ensemble_file(name)
    assert _current(data["qcpp_version"]), f"regenerate docs/results/{name}.* for qcpp {qcpp.__version__}"
    assert data["command"].startswith("python examples/experiments/ensembles.py"), data["command"]
    assert "--quick" not in data["command"] and data["rows"]
    if name != "ensembles":
        assert f"--name {name}" in data["command"]
    md = (RESULTS / f"{name}.md").read_text()
    assert f"qcpp {data['qcpp_version']}" in md and "quick mode" not in md
    cfg = data["config"]
    for r in data["rows"]:
        assert _current(r["qcpp_version"]) and isinstance(r["options"], dict)
        rows_, cols_, robots = (int(x) for x in r["cell"].replace("/", "x").split("x"))
        want = random_scenario(rows_, cols_, robots, cfg["density"], seed=cfg["seed"], index=r["index"])
        assert _scenario(_key(r)) == want, _label(name, r)
    cells = {r["cell"] for r in data["rows"]}
    counts = {c: cfg["instances"] for c in cfg["cells"]} | dict(cfg.get("cell_instances", ()))
    assert cells == set(cfg["cells"]) and len(data["rows"]) == sum(counts.values()) * (4 + cfg["p_max"])
    for cell, n in counts.items():  # instances 0 .. n-1 of each cell, once each
        assert sorted({r["index"] for r in data["rows"] if r["cell"] == cell}) == list(range(n)), cell


@pytest.mark.parametrize("heavy", CHEAP_OR_EVERY_ROW)
@pytest.mark.parametrize(("name", "cell"), ENSEMBLE_CELLS)
def test_ensemble_recorded_angles_and_circuits(name: str, cell: str, heavy: bool) -> None:
    checked = 0
    for r in _ensemble_rows(name, cell):
        if r["method"] != "qaoa" or not (heavy or r["index"] < CHEAP_ENSEMBLE_INSTANCES):
            continue
        q = _qaoa(_key(r))
        assert len(r["angles"]) == len(r["best_angles"]) == 2 * r["p"], _label(name, r)
        scale = 1.0 if r["optimum_in_basis"] else 0.0  # outside the QAOA's basis the optimum has probability 0
        assert scale * q.p_optimum(r["angles"]) == pytest.approx(r["p_opt"], rel=1e-6, abs=1e-12), _label(name, r)
        assert scale * q.p_optimum(r["best_angles"]) == pytest.approx(r["best_p_opt"], rel=1e-6, abs=1e-12)
        assert q.expectation(r["angles"]) == pytest.approx(r["expectation"], rel=1e-6, abs=1e-9), _label(name, r)
        if heavy or r["index"] == 0:
            want = _circuit(_key(r), int(r["p"]))
            assert {k: r[k] for k in want} == want, _label(name, r)
        checked += 1
    assert checked > 0


@pytest.mark.parametrize("cell", ["3x3/1", "3x3/2"])
def test_the_default_training_retrained_gives_the_recorded_angles(cell: str) -> None:
    """The other checks recompute states from recorded angles; this one reruns the training itself (the first
    instance of the cell, to p = 3), so a change of the default training shows up as stale results."""
    from qcpp.training.layerwise import train_layerwise

    rows = {r["p"]: r for r in _ensemble_file("ensembles")["rows"] if r["method"] == "qaoa" and r["cell"] == cell
            and r["index"] == 0}
    levels = train_layerwise(_qaoa(_key(rows[1])), 3)
    for p, (level, estimates) in enumerate(zip(levels.levels, levels.level_estimates), start=1):
        assert list(level.angles) == pytest.approx(rows[p]["angles"], abs=1e-6), (cell, p)
        assert estimates == rows[p]["circuit_estimates"], (cell, p)


@pytest.mark.parametrize(("name", "cell"), ENSEMBLE_CELLS)
def test_ensemble_derived_columns(name: str, cell: str) -> None:
    """The exhaustive optimum, SA/GA success counts, the QAOA's shots and times, and the search's invariants:
    never below the default (it starts from the default's angles) unless a level below reached the ceiling,
    never lower at a greater depth, and within the ceiling's upper bound."""
    from qcpp.problem.solvers import dfs

    rows = _ensemble_rows(name, cell)
    qaoa_rows: dict[str, list[dict[str, Any]]] = {}
    for r in rows:
        _check_solver_formulas(r)
        if r["method"] == "dfs":
            sol = dfs(_scenario(_key(r)))
            assert (sol.cost.total, sol.evaluated) == (r["optimum"], r["assignments"]), _label(name, r)
        elif r["method"] == "qaoa":
            shot = shot_seconds(r["depth"], r["two_qubit_depth"], r["options"]["gate_model"])
            assert r["best_sampling_99"] == pytest.approx(shots_for(min(1.0, r["best_p_opt"])) * shot)
            assert r["best_p_opt"] <= r["ceiling_upper"] + 1e-12
            if r["best_start"] == "reached":  # a level below reached the ceiling (0.999): the search stopped there
                assert r["best_p_opt"] >= 1 - r["options"]["search"].get("tolerance", 1e-3) - 1e-9
            else:
                assert r["p_opt"] <= r["best_p_opt"] + 1e-12, _label(name, r)
            qaoa_rows.setdefault(r["instance"], []).append(r)
    for levels in qaoa_rows.values():
        levels.sort(key=lambda r: r["p"])
        assert all(b["best_p_opt"] >= a["best_p_opt"] - 1e-12 for a, b in zip(levels, levels[1:]))
        assert all(b["circuit_estimates"] > a["circuit_estimates"] for a, b in zip(levels, levels[1:]))


# ---------------------------------------------------------------- the ensembles on named devices (ensemble_devices.py)

DEVICE_FIELDS = ("device", "fits", "routed_kind", "routed_twoq", "routed_depth", "routed_twoq_depth")


def _ensemble_device_instances() -> list[Any]:
    """One heavy parameter per (cell, instance) the heavy step recompiles (:data:`HEAVY_ENSEMBLE_DEVICE_INSTANCES`
    per cell, each on :func:`checked_devices`): one test per instance, so that the heavy step's two workers share
    the recompilations evenly."""
    if not (RESULTS / "ensemble_devices.json").exists():
        return []
    cells = _load("ensemble_devices")["config"]["cells"]
    return [pytest.param(c, i, id=f"{c}#{i}", marks=pytest.mark.heavy)
            for c in cells for i in range(HEAVY_ENSEMBLE_DEVICE_INSTANCES)]  # fmt: skip


def _ensemble_checked_devices(cells: Sequence[str], cell: str, index: int, devices: Sequence[str]) -> tuple[str, ...]:
    """The devices whose rows the heavy step recomputes for instance ``index`` of ``cell``: the uncalibrated ones,
    and for one instance of each cell of :data:`ENSEMBLE_CALIBRATED_CELLS` (``index`` = the cell's place, modulo
    :data:`HEAVY_ENSEMBLE_DEVICE_INSTANCES`) the calibrated device of :func:`checked_devices` for the cell's place."""
    assert set(ENSEMBLE_CALIBRATED_CELLS) <= set(cells), "a calibrated cell the study no longer has"
    place = list(cells).index(cell)
    calibrated = cell in ENSEMBLE_CALIBRATED_CELLS and index == place % HEAVY_ENSEMBLE_DEVICE_INSTANCES
    return checked_devices(devices, place, calibrated=calibrated)


ENSEMBLE_CALIBRATED_CELLS = ("3x3/2",)
"""Cells whose calibrated IBM rows the heavy step recompiles here, one instance each (the second instance of 3x3/2,
on ``ibm_torino``). The first instance of 3x3/1 on ``ibm_fez`` at depth 1 is the experiment's quick run, which
``experiments_test.py::test_ensemble_devices_quick_mode`` compares with its recorded row field for field. A
calibrated compile of a 4x4 instance takes about 40 CPU-seconds and runs the steps these two rows exercise between
them (the one-robot row's placement searches on the device and on the lattices; the two-robot row's circuit, with
more two-qubit gates than the search takes, routed greedily; Qiskit's O3 candidates and ESP scoring in both), so
the 4x4 cell stays recompiled on the uncalibrated devices, as :data:`CALIBRATED_SIZES` keeps the time-to-solution
rows."""


def _check_ensemble_device_row(r: dict[str, Any], context: RoutingContext) -> None:
    """``r``'s routed figures, ESP and shot time are what the router gives its scenario, depth and device now
    (routed with ``context``, shared by the rows of ``r``'s instance as the experiment shares it)."""
    want = _routed_in(_key(r), int(r["p"]), r["device"], context)
    assert {k: r[k] for k in DEVICE_FIELDS} == {k: want[k] for k in DEVICE_FIELDS}, _label("ensemble_devices", r)
    _check_esp(r, want, "ensemble_devices")
    if want["duration_s"] is not None:
        assert r["duration_model"] == "device" and r["shot_us"] == pytest.approx(want["duration_s"] * 1e6, rel=1e-9)


CHEAP_ENSEMBLE_DEVICES = ("google_willow", "quantinuum_helios")
"""Devices whose ensemble rows the default run recomputes (a few CPU-seconds per instance): a calibrated IBM
device's compile runs its placement searches on the device and on the abstract lattices (tens of CPU-seconds per
row), so those rows are the heavy step's (:func:`test_ensemble_device_rows_match_the_router`, which recompiles the
first instances on every device)."""


def test_ensemble_device_rows_of_the_first_instance_match_the_router() -> None:
    """The default run's share: the first instance of the first cell at its shallowest depth, on
    :data:`CHEAP_ENSEMBLE_DEVICES`."""
    data = _load("ensemble_devices")
    cell, p = data["config"]["cells"][0], min(data["config"]["depths"])
    rows = [r for r in data["rows"] if r["cell"] == cell and r["index"] == 0 and r["p"] == p
            and r["device"] in CHEAP_ENSEMBLE_DEVICES]  # fmt: skip
    assert {r["device"] for r in rows} == set(CHEAP_ENSEMBLE_DEVICES) <= set(data["config"]["devices"])
    context = RoutingContext()
    for r in rows:
        _check_ensemble_device_row(r, context)


HEAVY_ENSEMBLE_DEVICE_INSTANCES = 2
"""Instances per cell whose device rows (every depth on the uncalibrated devices, and for one instance per cell the
shallowest depth on a calibrated one: :func:`_ensemble_checked_devices`) the heavy step recompiles: a change of
the router or the device data changes some of them; all of them would take most of CI's time budget."""


@pytest.mark.parametrize(("cell", "index"), _ensemble_device_instances())
def test_ensemble_device_rows_match_the_router(cell: str, index: int) -> None:
    """Every row of the instance (every depth and device) is recorded; those on :func:`_ensemble_checked_devices` are
    routed again, with one context as the experiment routes them: every depth on the uncalibrated devices, the
    shallowest on the calibrated one (a calibrated compile of a deeper circuit takes 30-40 CPU-seconds and runs the
    same steps on a longer circuit)."""
    data = _load("ensemble_devices")
    rows = [r for r in data["rows"] if r["cell"] == cell and r["index"] == index]
    assert sorted((r["p"], r["device"]) for r in rows) == sorted(
        (p, d) for p in data["config"]["depths"] for d in data["config"]["devices"])
    devices = _ensemble_checked_devices(data["config"]["cells"], cell, index, data["config"]["devices"])
    shallowest = min(data["config"]["depths"])
    context = RoutingContext()
    for r in rows:
        if r["device"] in devices and (r["device"] not in CALIBRATED_DEVICES or r["p"] == shallowest):
            _check_ensemble_device_row(r, context)


def test_ensemble_device_derived_columns() -> None:
    """Every row: one per instance, depth and device; the reference's P(optimum), estimates, ideal and classical
    times copied faithfully; the device's shot probability, shots and 99% time by formula."""
    data = _load("ensemble_devices")
    assert _current(data["qcpp_version"]) and data["command"].startswith("python examples/experiments/ensemble_devices")
    assert "--quick" not in data["command"]
    cfg = data["config"]
    ref = _ensemble_file(Path(cfg["reference"]).stem)["rows"]
    qaoa = {(r["cell"], r["index"], r["p"]): r for r in ref if r["method"] == "qaoa"}
    classical: dict[tuple[str, int], float] = {}
    for r in ref:
        if r["method"] in ("dfs", "cpsat", "anneal", "genetic"):
            key = (r["cell"], r["index"])
            classical[key] = min(classical.get(key, math.inf), math.inf if r["tts_99"] is None else r["tts_99"])
    keys = {(r["cell"], r["index"], r["p"], r["device"]) for r in data["rows"]}
    assert len(keys) == len(data["rows"]) == len(cfg["cells"]) * cfg["instances"] * len(cfg["depths"]) * len(
        cfg["devices"])
    for r in data["rows"]:
        assert _current(r["qcpp_version"]) and r["options"]["device"] == r["device"] and r["options"]["p"] == r["p"]
        b = qaoa[(r["cell"], r["index"], r["p"])]
        assert r["scenario"] == b["scenario"], _label("ensemble_devices", r)
        assert (r["p_opt"], r["circuit_estimates"], r["ideal_tts_99"]) == (b["p_opt"], b["circuit_estimates"],
                                                                           b["tts_99"])
        assert r["best_classical_s"] == classical[(r["cell"], r["index"])]
        if not r["fits"]:
            assert r["tts_99"] is None
            continue
        _check_device_time(r, r["circuit_estimates"] * r["options"]["shots_per_estimate"])


@pytest.mark.heavy
def test_training_restarts_alternative_retrains_to_its_records() -> None:
    """The single-start schedule's figures are what ``qcpp.train_qaoa`` with the recorded options gives: one
    instance trained again to the recorded depth, every level's P(optimum) and angles equal to the records."""
    data = _load("training_restarts")
    rows = sorted((r for r in data["rows"] if r["instance"] == data["rows"][0]["instance"]), key=lambda r: r["p"])
    options = {k: v for k, v in rows[0]["options"].items() if k in ("restart_every_level", "gibbs_scale")}
    assert options == {"restart_every_level": False, "gibbs_scale": data["config"]["alternative"]["gibbs_scale"]}
    res = qcpp.train_qaoa(_scenario(_key(rows[0])), len(rows), **options)
    assert res.schedule is not None
    for r, level in zip(rows, res.schedule.levels, strict=True):
        assert list(level.angles) == pytest.approx(r["angles"], abs=1e-9), _label("tr", r)
        assert level.p_optimum == pytest.approx(r["p_opt"], rel=1e-9, abs=1e-12), _label("tr", r)


@pytest.mark.skipif(not (RESULTS / "training_restarts.json").exists(), reason="no committed training_restarts")
def test_training_restarts_rows_match_their_reference_and_angles() -> None:
    """The single-start schedule's records: the reference studies' default and best found copied faithfully, the
    best known the maximum of the three, the single-start P(optimum), <C> and Gibbs objective at its recorded
    angles (a few instances of the cells with small states)."""
    data = _load("training_restarts")
    assert _current(data["qcpp_version"]) and "--quick" not in data["command"]
    assert data["command"].startswith("python examples/experiments/training_restarts.py")
    ref = {(r["cell"], r["index"], r["p"]): r for name in data["config"]["references"]
           for r in _load(Path(name).stem)["rows"] if r["method"] == "qaoa"}
    checked = 0
    for r in data["rows"]:
        b = ref[(r["cell"], r["index"], r["p"])]
        assert r["scenario"] == b["scenario"] and r["options"]["restart_every_level"] is False
        assert (r["default_p_opt"], r["best_p_opt"], r["default_circuit_estimates"]) == (
            b["p_opt"], b["best_p_opt"], b["circuit_estimates"])
        assert r["best_known"] == max(r["best_p_opt"], r["default_p_opt"], r["p_opt"])
        if r["index"] < CHEAP_ENSEMBLE_INSTANCES and _dimension(_key(r)) <= CHEAP_DIMENSION:
            q = _qaoa(_key(r))
            assert q.p_optimum(r["angles"]) == pytest.approx(r["p_opt"], rel=1e-6, abs=1e-12), _label("tr", r)
            assert q.expectation(r["angles"]) == pytest.approx(r["expectation"], rel=1e-6, abs=1e-9)
            gibbs = Gibbs(data["config"]["alternative"]["gibbs_scale"] / cost_scale(q))
            assert q.objective_and_gradient(r["angles"], gibbs)[0] == pytest.approx(r["gibbs_alternative"], rel=1e-9)
            checked += 1
    assert checked > 0
