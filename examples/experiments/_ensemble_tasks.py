"""One instance of the ensemble study (``ensembles.py``): every method on one scenario, run on a Dask worker; and
the per-instance tasks of the studies built on it (``training_restarts.py``: :func:`train_instance`;
``ensemble_devices.py``: :func:`device_instance`).

Self-contained (it imports only ``qcpp``, numpy and the standard library) because ``ensembles.py`` ships it to the
workers by value: a worker of a remote scheduler needs qcpp installed, not this folder.

The rules are those of ``time_to_solution.py``: the time to reach an optimal assignment with probability 99%.

* DFS (exhaustive, deterministic): its run time. CP-SAT (1 worker): when it first found the optimum.
* SA and GA (``components="initial"``): ``runs`` seeded runs at a fixed budget; mean run time x the runs needed for
  99% at the observed success rate.
* QAOA at every depth ``p = 1 .. p_max``, each a depth fixed before the run: the default training
  (:func:`qcpp.training.layerwise.train_layerwise`; its level ``p`` is what training to depth ``p`` gives) and its
  ``P(optimum)``; the ideal all-to-all device time of training (objective estimates up to level ``p`` x
  ``SHOTS_PER_ESTIMATE`` shots) plus the shots for 99%, every shot at the depth-``p`` circuit's time
  (:data:`qcpp.simulate.time_to_solution.GATE_MODEL`). Beside it the best ``P(optimum)`` the expensive search finds
  (:func:`qcpp.training.angle_search.search_p_optimum`, warm-started from the default's angles) and the ansatz's
  ceiling bound.

Where a robot's paths split into move-graph components the QAOA basis (the initial path's component) may miss the
optimum: ``optimum_in_basis`` is then false and the QAOA's ``P(optimum)`` is 0 at every depth (the ceiling too).
"""

from __future__ import annotations

import statistics
import time
from typing import Any

TOL = 1e-9
TARGET = 0.99


def run_instance(cell: str, index: int, scenario: dict[str, Any], cfg: dict[str, Any]) -> dict[str, Any]:
    """Every method on one scenario (``cfg``: the study's configuration as a dict); JSON-ready."""
    from qcpp.problem.scenario import scenario_from_dict
    from qcpp.problem.solvers import anneal, cpsat, dfs, genetic
    from qcpp.simulate.time_to_solution import repeated_runs

    t_all = time.perf_counter()
    s = scenario_from_dict(scenario)
    out: dict[str, Any] = {"cell": cell, "index": index, "scenario": scenario}
    d = dfs(s)
    out["dfs"] = {"seconds": d.seconds, "cost": d.cost.total, "assignments": d.evaluated}
    c = cpsat(s, time_limit=cfg["cpsat_limit"], workers=1)
    out["cpsat"] = {"seconds": c.solution.seconds, "proven": c.proven_optimal, "cost": c.solution.cost.total,
                    "improvements": [list(x) for x in c.improvements]}
    optimum = d.cost.total
    assert c.solution.cost.total >= optimum - 1e-9, (cell, index)
    out["optimum"] = optimum
    for method in ("anneal", "genetic"):
        runs = []
        for k in range(cfg["runs"]):
            if method == "anneal":
                sol = anneal(s, seed=k, iterations=cfg["sa_iterations"], components="initial")
            else:
                sol = genetic(s, seed=k, generations=cfg["ga_generations"], components="initial")
            runs.append({"seconds": sol.seconds, "cost": sol.cost.total})
        ok = sum(r["cost"] <= optimum + TOL for r in runs)
        rr = repeated_runs(statistics.fmean(r["seconds"] for r in runs), ok, len(runs), TARGET)
        out[method] = {"successes": ok, "runs": len(runs), "run_seconds": rr.run_seconds, "tries_99": rr.tries,
                       "tts_99": rr.seconds, "tts_99_range": list(rr.seconds_range),
                       "run_costs": [r["cost"] for r in runs]}
    out["qaoa"] = run_qaoa(s, optimum, cfg)
    out["seconds"] = time.perf_counter() - t_all
    return out


def run_qaoa(s: Any, optimum: float, cfg: dict[str, Any]) -> dict[str, Any]:
    """Default training and expensive search at ``p = 1 .. cfg["p_max"]``, with the circuit and the 99% time."""
    from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
    from qcpp.simulate.subspace import SubspaceQAOA
    from qcpp.simulate.success import shots_for
    from qcpp.simulate.time_to_solution import GATE_MODEL, shot_seconds
    from qcpp.training.angle_search import SearchBudget, search_p_optimum
    from qcpp.training.layerwise import SHOTS_PER_ESTIMATE, train_layerwise

    q = SubspaceQAOA(s)
    in_basis = abs(q.optimum()[0] - optimum) <= 1e-6 * max(1.0, abs(optimum))
    p_max = cfg["p_max"]
    t0 = time.perf_counter()
    res = train_layerwise(q, p_max)
    train_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    search = search_p_optimum(q, p_max, warm=[lv.angles for lv in res.levels],
                              budget=SearchBudget(**cfg["search"]), seed=cfg["seed"])
    search_s = time.perf_counter() - t0
    levels = []
    for lv, best, estimates in zip(res.levels, search, res.level_estimates):
        est = estimate_point(Point.from_scenario(s, lv.p), EstimateOptions(depth="exact"))
        assert est.depth is not None
        shot = shot_seconds(est.depth.depth, est.depth.two_qubit_depth, GATE_MODEL)
        p_opt = lv.p_optimum if in_basis else 0.0
        best_p = best.p_optimum if in_basis else 0.0
        shots = shots_for(min(1.0, p_opt))
        training_shots = estimates * SHOTS_PER_ESTIMATE
        levels.append({
            "p": lv.p, "p_opt": p_opt, "angles": list(lv.angles), "expectation": lv.expectation,
            "circuit_estimates": estimates, "training_shots": training_shots,
            "qubits": est.qubits, "depth": est.depth.depth, "two_qubit_depth": est.depth.two_qubit_depth,
            "gates": est.cost.total, "shot_us": shot * 1e6, "shots_99": shots,
            "tts_99": (training_shots + shots) * shot,
            "best_p_opt": best_p, "best_angles": list(best.angles), "best_start": best.start,
            "search_runs": best.runs, "search_evaluations": best.evaluations, "reach_layers": best.reach_layers,
            "ceiling_upper": best.ceiling_upper if in_basis else 0.0,
            "best_sampling_99": shots_for(min(1.0, best_p)) * shot,
        })
    return {"dimension": q.dimension, "optimum_in_basis": in_basis, "training_seconds_simulated": train_s,
            "search_seconds": search_s, "levels": levels}


def device_columns(scenario: Any, p: int, device: str, context: Any = None) -> dict[str, Any]:
    """The depth-``p`` circuit of ``scenario`` routed onto ``device`` by the estimator: routed counts, ESP (of the
    gates alone, ``esp``, and with idle decoherence where the device has T1 / T2, ``esp_idle``, else ``None``) and
    the time of one shot (device durations where published, else the ideal gate model on the routed depths,
    ``assumed``). ``context``: the routing memos to share with other rows of the scenario (a
    :class:`qcpp.routing.context.RoutingContext`; default: a fresh one); the figures are the same either way."""
    from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
    from qcpp.estimators.routed import routed_fields
    from qcpp.simulate.time_to_solution import GATE_MODEL, shot_seconds

    est = estimate_point(Point.from_scenario(scenario, p), EstimateOptions(depth="none"))
    c = est.cost
    f = routed_fields(scenario, p, est.options.plan, device, qubits=est.qubits, cx=c.two_qubit,
                      one_qubit=c.single_qubit, total_gates=c.total, context=context)
    out = {k: f[k] for k in ("device", "fits", "routed_kind", "routed_twoq", "routed_depth", "routed_twoq_depth",
                             "esp", "esp_idle")}
    if not f["fits"]:
        return {**out, "duration_model": None, "shot_us": None}
    if f["duration_s"] is not None:
        return {**out, "duration_model": "device", "shot_us": f["duration_s"] * 1e6}
    shot = shot_seconds(f["routed_depth"], f["routed_twoq_depth"], GATE_MODEL)
    return {**out, "duration_model": "assumed", "shot_us": shot * 1e6}


def shot_esp(row: dict[str, Any]) -> float:
    """The ESP a shot on ``row``'s device succeeds with: with idle decoherence where the device has T1 / T2
    (``esp_idle``), else the gates' alone (``esp``)."""
    return row["esp"] if row.get("esp_idle") is None else row["esp_idle"]


def device_instance(cell: str, index: int, scenario: dict[str, Any], cfg: dict[str, Any]) -> dict[str, Any]:
    """One instance's circuits at the depths ``cfg["depths"]`` routed onto each of ``cfg["devices"]``
    (:func:`device_columns`, with ``p`` added, one routing context for all: the devices share the compiles on the
    abstract lattices); JSON-ready."""
    from qcpp.problem.scenario import scenario_from_dict
    from qcpp.routing.context import RoutingContext

    t0 = time.perf_counter()
    s = scenario_from_dict(scenario)
    context = RoutingContext()
    routed = [{"p": p, **device_columns(s, p, name, context)} for p in cfg["depths"] for name in cfg["devices"]]
    return {"cell": cell, "index": index, "scenario": scenario, "devices": routed,
            "seconds": time.perf_counter() - t0}


def train_instance(cell: str, index: int, scenario: dict[str, Any], cfg: dict[str, Any]) -> dict[str, Any]:
    """The training ``train_layerwise(..., **cfg["alternative"])`` on one scenario, to depth
    ``cfg["p_max"]``: ``P(optimum)``, angles and objective estimates per level, and its seconds."""
    from qcpp.problem.scenario import scenario_from_dict
    from qcpp.problem.solvers import dfs
    from qcpp.simulate.subspace import SubspaceQAOA
    from qcpp.training.layerwise import train_layerwise

    t_all = time.perf_counter()
    s = scenario_from_dict(scenario)
    q = SubspaceQAOA(s)
    optimum = dfs(s).cost.total
    in_basis = abs(q.optimum()[0] - optimum) <= 1e-6 * max(1.0, abs(optimum))
    t0 = time.perf_counter()
    res = train_layerwise(q, cfg["p_max"], **cfg["alternative"])
    return {"cell": cell, "index": index, "scenario": scenario, "optimum_in_basis": in_basis,
            "training_seconds": time.perf_counter() - t0,
            "p_opt": [lv.p_optimum if in_basis else 0.0 for lv in res.levels],
            "angles": [list(lv.angles) for lv in res.levels], "expectation": [lv.expectation for lv in res.levels],
            "circuit_estimates": list(res.level_estimates), "seconds": time.perf_counter() - t_all}
