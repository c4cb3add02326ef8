"""Time to the optimum with 99% probability: DFS, CP-SAT, annealing, the GA and QAOA, by grid size, one rule for all.

Instances: ``n x n`` grids, ``n = 3 .. 6``, with 1, 2 and 3 robots in the default corner-to-corner placement
(:func:`qcpp.problem.presets.default_scenario`), each once without and once with soft obstacles (``n^2 // 12``
interior nodes, at least one, drawn with a seeded generator away from the robots' endpoints). Every objective
setting is the default. Every row of the results records its scenario, its method's options and the qcpp
version; ``tests/simulate/results_freshness_test.py`` recomputes the circuit columns from them.

The criterion (:mod:`qcpp.simulate.time_to_solution`): the time to reach an optimal assignment with probability 99%.

* **DFS** (:func:`qcpp.problem.solvers.dfs`): exhaustive, deterministic; its run time. Attempted up to ``dfs_max``
  combinations, ``(corner-to-corner paths)^robots`` (OEIS A007764; soft obstacles do not change the path set).
* **CP-SAT** (:func:`qcpp.problem.solvers.cpsat`, 1 worker, deterministic): the time at which it first found an
  optimal assignment (and, separately, the time of its proof). Limit ``cpsat_limit`` per instance,
  ``cpsat_named_limit`` on 6x6 with 2 and 3 robots without obstacles.
* **SA** (:func:`qcpp.problem.solvers.anneal`) and **GA** (:func:`qcpp.problem.solvers.genetic`), with
  ``components="initial"`` (on these grids every robot's paths form one move-graph component): ``runs``
  independent runs (seeds 0..runs-1) at a fixed budget; a run succeeds if its best is optimal; time = mean run
  time x the runs needed for 99% at the observed rate (range: the rate's 95% Wilson interval).
* **QAOA** where the feasible-subspace simulator holds the state (at most ``qaoa_max_dim`` assignments): the
  default training (:func:`qcpp.training.layerwise.train_layerwise`: Gibbs objective, L-BFGS-B layer by layer,
  restarts at every level) to
  the depth fixed before the run, ``qaoa_p`` for every instance; ``P(optimum)`` of the trained state; the shots
  for 99%; and a **projected ideal-device time**: every shot (training shots included: objective estimates x
  ``SHOTS_PER_ESTIMATE``) at the circuit's time from the compiler's exact depth
  (:func:`qcpp.estimators.estimate.estimate_point`) under :data:`qcpp.simulate.time_to_solution.GATE_MODEL`, an ideal
  all-to-all device (no routing, no noise, no error correction). Training shots are all counted at the final
  depth's shot time (an upper bound: lower levels run shorter circuits). The classical simulation's own time is
  listed but is not part of the device time.
* **QAOA on today's devices** (``devices``: the IBM Heron snapshots ``ibm_fez`` and ``ibm_torino``, the square
  grid ``google_willow`` and the trapped-ion ``quantinuum_helios``): the same trained state and training, the
  depth-``p`` circuit compiled and routed onto the device by the estimator
  (:func:`qcpp.estimators.routed.routed_fields`, i.e. :func:`qcpp.pipeline.device_compile.compile_for_device`: exact
  routed counts), and the device's noise and time. **Model: a shot succeeds with probability P(optimum) x ESP**, ESP =
  the product of ``1 - error`` over every native gate and readout of the routed circuit (an error anywhere ruins
  the shot), times, where the device has T1 / T2 (the IBM snapshots), the idle decoherence of every qubit in the
  ASAP schedule (:func:`qcpp.routing.native.esp_idle`); both figures are in the rows (``esp``, ``esp_idle``).
  Still optimistic: no crosstalk or leakage, and training counted at its noiseless number of estimates. Shot time:
  the routed circuit's ASAP schedule with the device's gate durations plus one readout where the device data has
  durations (the IBM snapshots); ``google_willow`` and ``quantinuum_helios`` publish
  none (their data files say so), so their shot time is the ideal gate model above applied to the routed
  circuit's depth and two-qubit depth, labelled ``assumed`` (for trapped ions, whose gates and transport take
  tens of microseconds or more, a large underestimate).

Optimum: DFS's or CP-SAT's proven value, else the best any method found (marked "best known").

Outputs: ``results/time_to_solution.md``, ``results/time_to_solution.csv`` (one row per instance and method),
``results/time_to_solution.json`` and ``figures/time_to_solution.png``.
Run: ``python examples/experiments/time_to_solution.py [--quick]``.
"""

from __future__ import annotations

import csv
import io
import json
import math
import statistics
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np
from _common import Table, command_line, parse, pyplot, save_figure, write_results
from _ensemble_tasks import device_columns, shot_esp

import qcpp
from qcpp.io.atomic import write_text_atomic
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_to_dict
from qcpp.problem.solvers import anneal, cpsat, dfs, genetic

NAME = "time_to_solution"
CORNER_PATHS = {3: 12, 4: 184, 5: 8512, 6: 1262816, 7: 575780564, 8: 789360053252}
"""Simple corner-to-corner paths on an n x n grid (OEIS A007764; the quick test checks 3..5 by enumeration)."""
NAMED = {(6, 2), (6, 3)}
"""Obstacle-free instances with the longer CP-SAT limit."""
TOL = 1e-9
TARGET = 0.99
OFF_SCALE = 1e8
"""Seconds (about three years) above which the figure leaves a device's QAOA time out (the tables have it)."""


@dataclass(frozen=True)
class Config:
    sizes: tuple[int, ...]
    robots: tuple[int, ...]
    dfs_max: float
    cpsat_limit: float
    cpsat_named_limit: float
    runs: int
    sa_iterations: int
    ga_generations: int
    qaoa_max_dim: int
    qaoa_p: int
    devices: tuple[str, ...]


DEVICES = ("ibm_fez", "ibm_torino", "google_willow", "quantinuum_helios")
"""Named devices (``qcpp/hardware/data``) the QAOA rows are compiled for."""
FULL = Config((3, 4, 5, 6), (1, 2, 3), 1e6, 10.0, 30.0, 8, 2000, 10, 40_000, 5, DEVICES)
QUICK = Config((3,), (2,), 1e6, 2.0, 2.0, 3, 500, 3, 200, 2, ("ibm_fez", "quantinuum_helios"))


@dataclass
class Instance:
    n: int
    robots: int
    obstacles: bool
    scenario: Scenario
    results: dict[str, Any] = field(default_factory=dict)

    @property
    def label(self) -> str:
        return f"{self.n}x{self.n}/{self.robots}" + (" +obst" if self.obstacles else "")


def make_instance(n: int, robots: int, obstacles: bool, seed: int) -> Instance:
    """The default placement, plus seeded soft obstacles on interior non-endpoint nodes if asked."""
    base = default_scenario(n, n, robots)
    if not obstacles:
        return Instance(n, robots, False, base)
    ends = {x for rb in base.robots for x in (rb.start, rb.goal)}
    candidates = [(r, c) for r in range(1, n - 1) for c in range(1, n - 1) if (r, c) not in ends]
    rng = np.random.default_rng([seed, n, robots])
    k = min(len(candidates), max(1, n * n // 12))
    chosen = sorted(candidates[i] for i in rng.choice(len(candidates), size=k, replace=False))
    s = Scenario(base.grid, base.robots, tuple(chosen), base.objective, name=f"{base.name}, {k} soft obstacle(s)")
    return Instance(n, robots, True, s)


# ---------------------------------------------------------------------------------------------- methods


def run_dfs(inst: Instance, cfg: Config) -> dict[str, Any]:
    combos = CORNER_PATHS[inst.n] ** inst.robots
    if combos > cfg.dfs_max:
        return {"attempted": False, "assignments": combos}
    sol = dfs(inst.scenario)
    assert sol.evaluated == combos, (inst.label, sol.evaluated, combos)
    return {"attempted": True, "assignments": combos, "seconds": sol.seconds, "cost": sol.cost.total}


def run_cpsat(inst: Instance, cfg: Config) -> dict[str, Any]:
    limit = cfg.cpsat_named_limit if (inst.n, inst.robots) in NAMED and not inst.obstacles else cfg.cpsat_limit
    res = cpsat(inst.scenario, time_limit=limit, workers=1)
    return {
        "limit": limit,
        "seconds": res.solution.seconds,
        "proven": res.proven_optimal,
        "cost": res.solution.cost.total,
        "bound": res.bound,
        "gap": res.gap,
        "improvements": [list(x) for x in res.improvements],
    }


def run_local(inst: Instance, cfg: Config, method: str) -> list[dict[str, Any]]:
    """``cfg.runs`` independent SA or GA runs (seeds 0..runs-1)."""
    out = []
    for k in range(cfg.runs):
        if method == "anneal":
            sol = anneal(inst.scenario, seed=k, iterations=cfg.sa_iterations, components="initial")
        else:
            sol = genetic(inst.scenario, seed=k, generations=cfg.ga_generations, components="initial")
        out.append({"seed": k, "seconds": sol.seconds, "cost": sol.cost.total, "trace": list(sol.trace),
                    "evaluated": sol.evaluated})
    return out


def local_summary(runs: list[dict[str, Any]], optimum: float) -> dict[str, Any]:
    """Successes, mean run time and the 99% time of repeated runs."""
    from qcpp.simulate.time_to_solution import repeated_runs

    ok = sum(r["cost"] <= optimum + TOL for r in runs)
    rr = repeated_runs(statistics.fmean(r["seconds"] for r in runs), ok, len(runs), TARGET)
    return {"successes": ok, "runs": len(runs), "run_seconds": rr.run_seconds, "tries_99": rr.tries,
            "tts_99": rr.seconds, "tts_99_range": list(rr.seconds_range),
            "median_cost": statistics.median(r["cost"] for r in runs), "best_cost": min(r["cost"] for r in runs)}


def time_to_reach(run: dict[str, Any], target: float) -> float | None:
    """Seconds until the run's best-so-far first reached ``target`` (iterations taken as equally long)."""
    trace = run["trace"]
    hit = next((i for i, v in enumerate(trace) if v <= target + TOL), None)
    return None if hit is None else run["seconds"] * (hit + 1) / len(trace)


def cpsat_best_by(res: dict[str, Any], t: float) -> float | None:
    """CP-SAT's best cost found within ``t`` seconds (``None``: nothing yet)."""
    found = [c for s, c in res["improvements"] if s <= t]
    return min(found) if found else None


def qaoa_circuit_columns(scenario: Scenario, p: int) -> dict[str, Any]:
    """The compiler's figures of the depth-``p`` circuit (the cheap, recomputable part of a QAOA row)."""
    from _common import circuit_columns

    return circuit_columns(scenario, p)


def run_qaoa(
    inst: Instance, cfg: Config, optimum: float, context: qcpp.RoutingContext | None = None
) -> dict[str, Any] | None:
    """Default training to the fixed depth, then the projected 99% time on an ideal device and on each device
    (routed with ``context``, the run's routing memos, :func:`_ensemble_tasks.device_columns`)."""
    from qcpp.simulate.subspace import SubspaceQAOA
    from qcpp.simulate.time_to_solution import GATE_MODEL, qaoa_on_device, shot_seconds
    from qcpp.training.layerwise import SHOTS_PER_ESTIMATE, train_layerwise

    if CORNER_PATHS[inst.n] ** inst.robots > cfg.qaoa_max_dim:
        return None
    q = SubspaceQAOA(inst.scenario)
    assert abs(q.optimum()[0] - optimum) < 1e-6, (inst.label, q.optimum()[0], optimum)
    res = train_layerwise(q, cfg.qaoa_p)
    circuit = qaoa_circuit_columns(inst.scenario, cfg.qaoa_p)
    shot = shot_seconds(circuit["depth"], circuit["two_qubit_depth"], GATE_MODEL)
    dev = qaoa_on_device(res.p_optimum, res.circuit_estimates, SHOTS_PER_ESTIMATE, shot, TARGET)
    devices = []
    for name in cfg.devices:
        d = device_columns(inst.scenario, cfg.qaoa_p, name, context)
        if d["fits"]:
            t = qaoa_on_device(res.p_optimum, res.circuit_estimates, SHOTS_PER_ESTIMATE, d["shot_us"] * 1e-6, TARGET,
                               esp=shot_esp(d))
            d |= {"p_shot": t.p_shot, "shots_99": t.shots, "training_s": t.training_seconds,
                  "sampling_s": t.sampling_seconds, "tts_99": t.seconds}
        devices.append(d)
    return {"dimension": q.dimension, "p": cfg.qaoa_p, "p_opt": res.p_optimum,
            "p_opt_by_level": [lv.p_optimum for lv in res.levels], "angles": list(res.levels[-1].angles),
            "objective": res.objective, "circuit_estimates": res.circuit_estimates,
            "simulations": res.num_evaluations, "training_seconds_simulated": res.seconds, **circuit,
            "shot_us": shot * 1e6, "training_shots": dev.training_shots, "shots_99": dev.shots,
            "training_s": dev.training_seconds, "sampling_s": dev.sampling_seconds, "tts_99": dev.seconds,
            "devices": devices}


# ---------------------------------------------------------------------------------------------- study


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    from qcpp.pipeline.device_compile import ESP_MODEL
    from qcpp.routing.native import IDLE_MODEL
    from qcpp.simulate.time_to_solution import GATE_MODEL
    from qcpp.training.layerwise import DEFAULT_MAXITER, DEFAULT_RANDOM_STARTS, SHOTS_PER_ESTIMATE
    from qcpp.training.objectives import GIBBS_SCALE

    opts = parse(__doc__.splitlines()[0], argv)
    cfg = QUICK if opts.quick else FULL
    t_all = time.perf_counter()
    instances = [make_instance(n, r, ob, opts.seed) for n in cfg.sizes for r in cfg.robots for ob in (False, True)]
    context = qcpp.RoutingContext()  # the run's routing memos: a soft-obstacle twin reuses the placement searches
    for inst in instances:
        t0 = time.perf_counter()
        res = inst.results
        res["dfs"] = run_dfs(inst, cfg)
        res["cpsat"] = run_cpsat(inst, cfg)
        if res["dfs"]["attempted"]:
            # the exhaustive optimum: CP-SAT never beats it, and equals it when it proved its answer (whether it
            # proves it within its wall-clock limit depends on the machine's load, so that is not assumed)
            assert res["cpsat"]["cost"] >= res["dfs"]["cost"] - 1e-9, inst.label
            assert not res["cpsat"]["proven"] or abs(res["dfs"]["cost"] - res["cpsat"]["cost"]) < 1e-9, inst.label
        res["anneal"] = run_local(inst, cfg, "anneal")
        res["genetic"] = run_local(inst, cfg, "genetic")
        proven = res["dfs"]["attempted"] or res["cpsat"]["proven"]
        exact = res["dfs"]["cost"] if res["dfs"]["attempted"] else res["cpsat"]["cost"]
        best = min([res["cpsat"]["cost"]] + [r["cost"] for m in ("anneal", "genetic") for r in res[m]])
        if proven:
            assert best >= exact - TOL, (inst.label, best)  # nothing beats a proven optimum
        opt = exact if proven else best
        res["optimum"] = {"value": opt, "proven": proven}
        res["anneal_tts"] = local_summary(res["anneal"], opt)
        res["genetic_tts"] = local_summary(res["genetic"], opt)
        res["qaoa"] = run_qaoa(inst, cfg, opt, context) if proven else None
        print(f"{inst.label:16} optimum {opt:g} ({'proven' if proven else 'best known'}) "
              f"in {time.perf_counter() - t0:.1f} s", file=sys.stderr, flush=True)

    options = {
        "dfs": {"max_combinations": cfg.dfs_max},
        "cpsat": {"workers": 1, "time_limit": cfg.cpsat_limit},
        "anneal": {"iterations": cfg.sa_iterations, "components": "initial", "seeds": cfg.runs},
        "genetic": {"generations": cfg.ga_generations, "components": "initial", "seeds": cfg.runs},
        "qaoa": {"p": cfg.qaoa_p, "training": "layerwise", "objective": "gibbs", "gibbs_eta_sigma": GIBBS_SCALE,
                 "maxiter": DEFAULT_MAXITER, "random_starts": DEFAULT_RANDOM_STARTS, "restart_every_level": True,
                 "shots_per_estimate": SHOTS_PER_ESTIMATE, "gate_model": GATE_MODEL, "device": "ideal all-to-all"},
        "qaoa_device": {"compile": "qcpp.estimators.routed.routed_fields"
                                   " (qcpp.pipeline.device_compile.compile_for_device)",
                        "plan": "default", "success_model": "P(opt) x ESP", "esp_model": ESP_MODEL,
                        "duration_model": "device durations where published, else gate_model on the routed depths "
                                          "(assumed)"},
    }
    rows = result_rows(instances, options)
    tables = [_main_table(instances, cfg), _qaoa_table(instances), _device_table(instances, cfg),
              _verdict_table(instances, cfg), _named_table(instances)]
    flat = [_flat(r) for r in rows]
    fields: list[str] = []
    for r in flat:
        fields += [k for k in r if k not in fields]
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=fields)
    writer.writeheader()
    writer.writerows(flat)
    write_text_atomic(opts.results / f"{NAME}.csv", buf.getvalue())
    print(f"wrote {opts.results / f'{NAME}.csv'}")
    seconds = time.perf_counter() - t_all
    dump = {"qcpp_version": qcpp.__version__, "command": command_line(Path(__file__).name, opts),
            "config": asdict(cfg), "seconds": seconds, "rows": rows}
    write_text_atomic(opts.results / f"{NAME}.json", json.dumps(dump, indent=1, default=_json_default) + "\n")
    print(f"wrote {opts.results / f'{NAME}.json'}")
    notes = [
        f"qcpp {qcpp.__version__}. One process, one thread per method (CP-SAT: 1 worker) on a shared 2-core "
        "machine; timings are wall clock.",
        "Criterion for every method: time to reach an optimal assignment with probability 99%. DFS and CP-SAT are "
        "deterministic (their time; CP-SAT: when it first found the optimum). SA and GA: mean run time x runs "
        f"needed at the observed success rate over {cfg.runs} independent runs (range: the rate's 95% Wilson "
        "interval; 'inf' = no run succeeded).",
        f"SA: {cfg.sa_iterations} iterations, GA: {cfg.ga_generations} generations (population 192). CP-SAT limit "
        f"{cfg.cpsat_limit:g} s ({cfg.cpsat_named_limit:g} s on 6x6/2 and 6x6/3 without obstacles). DFS attempted "
        f"up to {cfg.dfs_max:.0e} combinations.",
        f"QAOA: depth fixed in advance at p = {cfg.qaoa_p} for every instance; default training (Gibbs objective, "
        f"eta = {GIBBS_SCALE:g}/sigma, L-BFGS-B layer by layer from p = 1, restarts at every level). IDEAL "
        "ALL-TO-ALL DEVICE PROJECTION, not a "
        f"measurement: two-qubit layers {GATE_MODEL['t_2q_ns']:g} ns, other layers {GATE_MODEL['t_1q_ns']:g} ns, "
        f"readout {GATE_MODEL['readout_ns']:g} ns per shot, no routing, no noise, no error correction; depth = the "
        "compiler's exact depth; training = objective estimates (a gradient = 1 + 4p estimates) x "
        f"{SHOTS_PER_ESTIMATE} shots, all at the final depth's shot time.",
        f"QAOA on devices ({', '.join(cfg.devices)}): the same trained state and training; the depth-{cfg.qaoa_p} "
        "circuit compiled and routed onto the device (qcpp.estimators.routed.routed_fields = "
        "qcpp.pipeline.device_compile.compile_for_device, default plan). SUCCESS PER SHOT = P(opt) x ESP: "
        "an error anywhere ruins the shot "
        f"(ESP of the gates: {ESP_MODEL}; where the device has T1/T2, the IBM snapshots, times the {IDLE_MODEL}); "
        "still optimistic: no crosstalk or leakage, training at its noiseless number of estimates. "
        "Shot time: the routed schedule with the device's gate and readout durations ('device': the IBM "
        "snapshots); google_willow and quantinuum_helios publish no gate durations, so theirs is the ideal gate "
        "model above on the routed depth and two-qubit depth ('assumed'; for trapped ions a large underestimate).",
        f"Whole study: {seconds:.0f} s.",
    ]
    write_results(opts, NAME, command_line(Path(__file__).name, opts), tables, notes)
    _figure(opts, instances)
    return {"instances": instances, "config": cfg, "rows": rows}


def result_rows(instances: list[Instance], options: dict[str, Any]) -> list[dict[str, Any]]:
    """One record per instance and method: the scenario, the method's options, the qcpp version, the results."""
    rows = []
    for inst in instances:
        r = inst.results
        opt, proven = r["optimum"]["value"], r["optimum"]["proven"]
        base = {"instance": inst.label, "size": inst.n, "robots": inst.robots,
                "obstacles": len(inst.scenario.obstacles), "scenario": scenario_to_dict(inst.scenario),
                "qcpp_version": qcpp.__version__, "optimum": opt, "optimum_proven": proven}
        d, c = r["dfs"], r["cpsat"]
        rows.append({**base, "method": "dfs", "options": options["dfs"], "attempted": d["attempted"],
                     "assignments": d["assignments"], "seconds": d.get("seconds"),
                     "tts_99": d.get("seconds") if d["attempted"] else None})
        first = next((s for s, v in c["improvements"] if v <= opt + TOL), None)
        rows.append({**base, "method": "cpsat", "options": options["cpsat"] | {"time_limit": c["limit"]},
                     "seconds": c["seconds"], "proven": c["proven"], "cost": c["cost"],
                     "bound": c["bound"] if math.isfinite(c["bound"]) else None, "gap": c["gap"], "tts_99": first})
        for m in ("anneal", "genetic"):
            rows.append({**base, "method": m, "options": options[m], **r[f"{m}_tts"],
                         "run_costs": [x["cost"] for x in r[m]]})
        q = r.get("qaoa")
        if q is not None:
            ideal = {k: v for k, v in q.items() if k != "devices"}
            rows.append({**base, "method": "qaoa", "options": options["qaoa"], **ideal,
                         "note": "IDEAL ALL-TO-ALL DEVICE PROJECTION"})
            shared = {k: q[k] for k in ("dimension", "p", "p_opt", "angles", "circuit_estimates", "training_shots")}
            for d in q["devices"]:
                rows.append({**base, "method": "qaoa_device",
                             "options": options["qaoa"] | {"device": d["device"]} | options["qaoa_device"],
                             **shared, **d, "note": f"PROJECTION ON {d['device']}: success per shot = P(opt) x ESP"
                             + (" with idle decoherence" if d.get("esp_idle") is not None else "")})
    return rows


def _flat(row: dict[str, Any]) -> dict[str, Any]:
    return {k: (json.dumps(v, sort_keys=True) if isinstance(v, (dict, list)) else v) for k, v in row.items()}


def _json_default(x: Any) -> Any:
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    raise TypeError(type(x))


def _fmt_s(x: float | None) -> str:
    if x is None:
        return "-"
    if not math.isfinite(x):
        return "inf"
    return f"{x:.3g}"


def _main_table(instances: list[Instance], cfg: Config) -> Table:
    t = Table("Time to the optimum with 99% probability (seconds; SA/GA: successes/runs, 99% time and its range)",
              ["instance", "combinations", "optimum", "DFS", "CP-SAT first opt (proof)", "SA ok", "SA 99%",
               "GA ok", "GA 99%", f"QAOA p={cfg.qaoa_p} ideal device 99%", "QAOA best real device 99%"])
    for inst in instances:
        r = inst.results
        opt, proven = r["optimum"]["value"], r["optimum"]["proven"]
        d, c = r["dfs"], r["cpsat"]
        dfs_s = _fmt_s(d["seconds"]) if d["attempted"] else "gives up"
        first = next((s for s, v in c["improvements"] if v <= opt + TOL), None)
        proof = _fmt_s(c["seconds"]) if c["proven"] else f"not at {c['limit']:g} s"
        cells = []
        for m in ("anneal", "genetic"):
            s = r[f"{m}_tts"]
            lo, hi = s["tts_99_range"]
            cells += [f"{s['successes']}/{s['runs']}", f"{_fmt_s(s['tts_99'])} ({_fmt_s(lo)}-{_fmt_s(hi)})"]
        q = r.get("qaoa")
        qaoa = "-" if q is None else f"{_fmt_s(q['tts_99'])} (P={q['p_opt']:.3g})"
        best = _best_device(q)
        real = "-" if best is None else f"{_fmt_s(best['tts_99'])} ({best['device']})"
        t.add(inst.label, f"{d['assignments']:.3g}", f"{opt:g}" + ("" if proven else " (best known)"), dfs_s,
              f"{_fmt_s(first)} ({proof})", *cells, qaoa, real)
    return t


def _qaoa_table(instances: list[Instance]) -> Table:
    t = Table("QAOA, default training, depth fixed in advance; projected IDEAL all-to-all device time",
              ["instance", "assignments", "p", "P(opt) at p=1..", "qubits", "depth", "2q depth", "us/shot",
               "estimates", "training shots", "shots for 99%", "training s", "sampling s", "99% s",
               "simulated training s"])
    for inst in instances:
        q = inst.results.get("qaoa")
        if not q:
            continue
        t.add(inst.label, q["dimension"], q["p"], " ".join(f"{v:.2g}" for v in q["p_opt_by_level"]), q["qubits"],
              q["depth"], q["two_qubit_depth"], q["shot_us"], q["circuit_estimates"], q["training_shots"],
              q["shots_99"], q["training_s"], q["sampling_s"], q["tts_99"], q["training_seconds_simulated"])
    return t


def _best_device(q: dict[str, Any] | None) -> dict[str, Any] | None:
    """The device row with the shortest 99% time (``None``: no QAOA or no device fits)."""
    rows = [] if q is None else [d for d in q["devices"] if d["fits"]]
    return min(rows, key=lambda d: d["tts_99"]) if rows else None


def best_classical(r: dict[str, Any]) -> float:
    """The shortest 99% time of DFS, CP-SAT (first optimum), SA and GA on one instance."""
    opt = r["optimum"]["value"]
    times = [r["dfs"]["seconds"]] if r["dfs"]["attempted"] else []
    first = next((s for s, v in r["cpsat"]["improvements"] if v <= opt + TOL), None)
    times += [first] if first is not None else []
    times += [r[f"{m}_tts"]["tts_99"] for m in ("anneal", "genetic")]
    return min(times)


def _device_table(instances: list[Instance], cfg: Config) -> Table:
    t = Table(f"QAOA p={cfg.qaoa_p} on today's devices: routed circuit, ESP of the gates and with idle decoherence "
              "(where the device has T1/T2), success per shot = P(opt) x ESP (with idle decoherence where known), "
              "99% time with training (seconds); ratio = QAOA / best classical 99% time",
              ["instance", "device", "routed 2q", "routed 2q depth", "ESP gates", "ESP idle", "us/shot (model)",
               "P(opt) x ESP", "shots for 99%", "training s", "sampling s", "99% s", "ratio"])
    for inst in instances:
        q = inst.results.get("qaoa")
        if not q:
            continue
        classical = best_classical(inst.results)
        t.add(inst.label, "ideal all-to-all", "-", q["two_qubit_depth"], 1.0, 1.0, f"{q['shot_us']:.4g} (ideal)",
              q["p_opt"], q["shots_99"], q["training_s"], q["sampling_s"], q["tts_99"],
              f"{q['tts_99'] / classical:.3g}")
        for d in q["devices"]:
            if not d["fits"]:
                t.add(inst.label, d["device"], "does not fit", *["-"] * 10)
                continue
            idle = "-" if d.get("esp_idle") is None else d["esp_idle"]
            t.add(inst.label, d["device"], d["routed_twoq"], d["routed_twoq_depth"], d["esp"], idle,
                  f"{d['shot_us']:.4g} ({d['duration_model']})", d["p_shot"], _fmt_s(d["shots_99"]),
                  d["training_s"], _fmt_s(d["sampling_s"]), _fmt_s(d["tts_99"]), f"{d['tts_99'] / classical:.3g}")
    return t


def _verdict_table(instances: list[Instance], cfg: Config) -> Table:
    """Per device: the range of QAOA's 99% times and of their ratio to the best classical method's, and how
    often QAOA is the faster."""
    t = Table(f"Verdict over the {sum(1 for i in instances if i.results.get('qaoa'))} instances with QAOA "
              f"(p={cfg.qaoa_p}): QAOA 99% time and its ratio to the best classical 99% time (DFS, CP-SAT first "
              "optimum, SA, GA)",
              ["device", "instances that fit", "shot ESP range", "QAOA 99% s (min-max)", "ratio (min-max)",
               "QAOA faster on", "ratio to DFS (min-max)", "sampling only s (min-max)",
               "sampling only faster on"])
    rows: dict[str, list[tuple[float, ...]]] = {"ideal all-to-all": []}
    fits: dict[str, int] = {"ideal all-to-all": 0}
    for inst in instances:
        q = inst.results.get("qaoa")
        if not q:
            continue
        classical = best_classical(inst.results)
        d_fs = inst.results["dfs"]
        dfs_s = d_fs["seconds"] if d_fs["attempted"] else math.nan
        rows["ideal all-to-all"].append((1.0, q["tts_99"], q["tts_99"] / classical, q["tts_99"] / dfs_s,
                                         q["sampling_s"], q["sampling_s"] / classical))
        fits["ideal all-to-all"] += 1
        for d in q["devices"]:
            rows.setdefault(d["device"], [])
            fits[d["device"]] = fits.get(d["device"], 0) + bool(d["fits"])
            if d["fits"]:
                rows[d["device"]].append((shot_esp(d), d["tts_99"], d["tts_99"] / classical, d["tts_99"] / dfs_s,
                                          d["sampling_s"], d["sampling_s"] / classical))
    for name, vals in rows.items():
        if not vals:
            t.add(name, 0, *["-"] * 7)
            continue
        esp, tts, ratio, vs_dfs, sampling, sampling_ratio = zip(*vals)
        vs = [v for v in vs_dfs if not math.isnan(v)]
        t.add(name, fits[name], f"{min(esp):.3g}-{max(esp):.3g}", f"{_fmt_s(min(tts))}-{_fmt_s(max(tts))}",
              f"{_fmt_s(min(ratio))}-{_fmt_s(max(ratio))}", f"{sum(r < 1 for r in ratio)} of {len(vals)}",
              f"{_fmt_s(min(vs))}-{_fmt_s(max(vs))}" if vs else "-",
              f"{_fmt_s(min(sampling))}-{_fmt_s(max(sampling))}",
              f"{sum(r < 1 for r in sampling_ratio)} of {len(vals)}")
    return t


def _named_table(instances: list[Instance]) -> Table:
    t = Table("CP-SAT on the 6x6 multi-robot instances (no obstacles)",
              ["instance", "limit s", "proven", "seconds", "best", "bound", "gap", "first found best at s"])
    for inst in instances:
        if (inst.n, inst.robots) in NAMED and not inst.obstacles:
            c = inst.results["cpsat"]
            first = next((s for s, v in c["improvements"] if v <= c["cost"] + TOL), None)
            t.add(inst.label, c["limit"], c["proven"], c["seconds"], c["cost"], c["bound"], c["gap"], _fmt_s(first))
    return t


def _figure(opts, instances: list[Instance]) -> None:  # type: ignore[no-untyped-def]
    plt = pyplot()
    robots = sorted({i.robots for i in instances})
    fig, axes = plt.subplots(1, len(robots), figsize=(5.2 * len(robots), 4.4), sharey=True, squeeze=False)
    colours = {"DFS": "tab:blue", "CP-SAT first optimum": "tab:green", "SA 99%": "tab:red", "GA 99%": "tab:purple",
               "QAOA 99% (ideal device, training counted)": "tab:orange",
               f"QAOA 99% on best real device (P(opt) x ESP; above {OFF_SCALE:.0e} s omitted)": "tab:brown"}
    real = list(colours)[-1]
    for ax, nr in zip(axes[0], robots):
        for obst, ls in ((False, "-"), (True, "--")):
            group = [i for i in instances if i.robots == nr and i.obstacles == obst]
            series: dict[str, list[tuple[int, float]]] = {k: [] for k in colours}
            for inst in group:
                r, opt = inst.results, inst.results["optimum"]["value"]
                if r["dfs"]["attempted"]:
                    series["DFS"].append((inst.n, r["dfs"]["seconds"]))
                first = next((s for s, v in r["cpsat"]["improvements"] if v <= opt + TOL), None)
                if first is not None:
                    series["CP-SAT first optimum"].append((inst.n, max(first, 1e-4)))
                for key, m in (("SA 99%", "anneal"), ("GA 99%", "genetic")):
                    v = r[f"{m}_tts"]["tts_99"]
                    if math.isfinite(v):
                        series[key].append((inst.n, v))
                q = r.get("qaoa")
                if q is not None and math.isfinite(q["tts_99"]):
                    series["QAOA 99% (ideal device, training counted)"].append((inst.n, q["tts_99"]))
                best = _best_device(q)
                if best is not None and best["tts_99"] <= OFF_SCALE:
                    series[real].append((inst.n, best["tts_99"]))
            for key, pts in series.items():
                if pts:
                    xs, ys = zip(*pts)
                    ax.plot(xs, ys, ls, marker="o", color=colours[key], label=key if not obst else None)
        ax.set_yscale("log")
        ax.set_xlabel("grid size n (n x n)")
        ax.set_title(f"{nr} robot(s): solid = no obstacles, dashed = soft obstacles", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.set_xticks(sorted({i.n for i in instances}))
    axes[0][0].set_ylabel("seconds to the optimum with 99% probability")
    axes[0][-1].legend(frameon=False, fontsize=8, loc="upper left")
    fig.tight_layout()
    save_figure(fig, opts.figures / f"{NAME}.png")
    plt.close(fig)


if __name__ == "__main__":
    main()
