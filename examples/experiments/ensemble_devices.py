"""The ensemble study on named devices: QAOA's time to the optimum with ESP, instance by instance.

The ensemble study (``ensembles.py``) projects QAOA on an ideal all-to-all device. This script takes the first
``--instances`` instances of some of its cells (``--reference``, default the committed results) and routes their
depth-``p`` circuits onto named devices the way ``time_to_solution.py`` does (the estimator's routed circuit:
routed counts, the estimated success probability ESP of one shot, the shot time from the device's durations where
published). A shot succeeds with ``P(optimum) x ESP`` (the default training's ``P(optimum)`` from the reference;
ESP with idle decoherence where the device has T1 / T2, the IBM snapshots, else of the gates alone);
the 99% time counts every training shot (objective estimates x 1000 shots, at the routed shot time) and the shots
for 99%. Beside it the ideal-device time and the fastest classical method's, both from the reference's records.

It tabulates per cell, device and depth: how many instances fit, the median [quartiles] of ESP (of the gates, and
with idle decoherence) and of the device's
99% time, the device's time over the ideal one, and on how many instances QAOA on the device beats the fastest
classical method. One Dask task per instance (as ``ensembles.py``).

Outputs: ``results/ensemble_devices.md``, ``results/ensemble_devices.json`` (one record per instance, depth and
device). Run: ``python examples/experiments/ensemble_devices.py [--quick] [--cells 3x3/1] [--instances N]
[--depths 1 2 3] [--devices ibm_fez ...] [--reference FILE]``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import _ensemble_tasks
from _common import REPO, Options, Table, fresh_output_folder, write_results
from ensembles import Config as StudyConfig
from ensembles import _mqq, best_classical_times, instances_of, parse_cell, run_on_dask
from time_to_solution import DEVICES

import qcpp
from qcpp.io.atomic import write_text_atomic

NAME = "ensemble_devices"
REFERENCE = "docs/results/ensembles.json"
CELLS = ("3x3/1", "3x3/2", "4x4/1")
"""The cells whose circuits are small enough to fit every named device at the default depths."""
INSTANCES = 10
DEPTHS = (1, 2, 3)
TARGET = 0.99


@dataclass(frozen=True)
class Config:
    reference: str
    cells: tuple[str, ...]
    density: float
    seed: int
    instances: int
    depths: tuple[int, ...]
    devices: tuple[str, ...]


def _mqq_or_dash(values: Sequence[float]) -> str:
    return _mqq(values) if values else "-"


def parse_args(argv: Sequence[str] | None) -> tuple[Options, Config, list[dict[str, Any]], str | None, int, str]:
    """The options, the configuration, the reference's rows, the scheduler, the workers and the command line."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one instance of 3x3/1 at depth 1 on two devices")
    ap.add_argument("--out", type=Path, default=None, help="output root (default: a new qcpp-experiments-* folder)")
    ap.add_argument("--reference", default=REFERENCE, metavar="FILE", help=f"ensembles.py's records ({REFERENCE})")
    ap.add_argument("--cells", nargs="+", type=parse_cell, default=None, metavar="RxC/N",
                    help=f"cells of the reference (default {' '.join(CELLS)})")
    ap.add_argument("--instances", type=int, default=None, help=f"instances per cell (default {INSTANCES})")
    ap.add_argument("--depths", type=int, nargs="+", default=None, metavar="P",
                    help=f"QAOA depths (default {' '.join(map(str, DEPTHS))})")
    ap.add_argument("--devices", nargs="+", default=None, metavar="NAME",
                    help=f"named devices (default {' '.join(DEVICES)})")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS", help="a running Dask scheduler")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes, one thread each")
    ns = ap.parse_args(argv)
    path = Path(ns.reference) if Path(ns.reference).is_absolute() else REPO / ns.reference
    if not path.is_file():
        ap.error(f"--reference: no such file {ns.reference}")
    reference = json.loads(path.read_text(encoding="utf-8"))
    rc = reference["config"]
    cells = tuple(f"{r}x{c}/{n}" for r, c, n in ns.cells) if ns.cells else (("3x3/1",) if ns.quick else CELLS)
    missing = [c for c in cells if c not in rc["cells"]]
    if missing:
        ap.error(f"--cells: {', '.join(missing)} not in {ns.reference}")
    depths = tuple(ns.depths) if ns.depths else ((1,) if ns.quick else DEPTHS)
    if any(not 1 <= p <= rc["p_max"] for p in depths):
        ap.error(f"--depths: each in 1..{rc['p_max']} (the reference's depths)")
    devices = tuple(ns.devices) if ns.devices else (("quantinuum_helios", "ibm_fez") if ns.quick else DEVICES)
    unknown = [d for d in devices if d not in qcpp.devices()]
    if unknown:
        ap.error(f"--devices: unknown {', '.join(unknown)} (known: {', '.join(qcpp.devices())})")
    instances = ns.instances if ns.instances is not None else (1 if ns.quick else INSTANCES)
    available = min(StudyConfig(**rc).instances_in(c) for c in cells)
    if not 1 <= instances <= available:
        ap.error(f"--instances: 1..{available} (the reference's instances in these cells)")
    cfg = Config(ns.reference, cells, rc["density"], rc["seed"], instances, depths, devices)
    command = "python examples/experiments/ensemble_devices.py" + " ".join(
        [""] + (["--quick"] if ns.quick else [])
        + ([f"--cells {' '.join(cells)}"] if ns.cells else [])
        + ([f"--instances {ns.instances}"] if ns.instances is not None else [])
        + ([f"--depths {' '.join(map(str, depths))}"] if ns.depths else [])
        + ([f"--devices {' '.join(devices)}"] if ns.devices else [])
        + ([f"--reference {ns.reference}"] if ns.reference != REFERENCE else []))
    opts = Options(quick=ns.quick, out=fresh_output_folder() if ns.out is None else ns.out, seed=rc["seed"])
    return opts, cfg, reference["rows"], ns.scheduler, ns.workers, command


def device_rows(results: list[dict[str, Any]], reference: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """One record per instance, depth and device: the routed figures of ``results`` (``device_instance``'s), the
    reference's P(optimum), objective estimates, ideal 99% time and fastest classical time, and the device's 99%
    time (``None`` where the circuit does not fit)."""
    from qcpp.simulate.time_to_solution import qaoa_on_device
    from qcpp.training.layerwise import SHOTS_PER_ESTIMATE

    qaoa = {(r["cell"], r["index"], r["p"]): r for r in reference if r["method"] == "qaoa"}
    classical = best_classical_times(reference)
    rows = []
    for res in results:
        for d in res["devices"]:
            b = qaoa[(res["cell"], res["index"], d["p"])]
            assert b["scenario"] == res["scenario"], (res["cell"], res["index"])
            row = {"cell": res["cell"], "index": res["index"], "instance": f"{res['cell']} #{res['index']}",
                   "scenario": res["scenario"], "qcpp_version": qcpp.__version__, "method": "qaoa_device",
                   "options": {"p": d["p"], "device": d["device"], "shots_per_estimate": SHOTS_PER_ESTIMATE,
                               "target": TARGET},
                   **d, "p_opt": b["p_opt"], "circuit_estimates": b["circuit_estimates"],
                   "ideal_tts_99": b["tts_99"], "best_classical_s": classical[b["instance"]]}
            t = (qaoa_on_device(b["p_opt"], b["circuit_estimates"], SHOTS_PER_ESTIMATE, d["shot_us"] * 1e-6, TARGET,
                                esp=_ensemble_tasks.shot_esp(d)) if d["fits"] else None)
            row |= {"p_shot": t and t.p_shot, "shots_99": t and t.shots, "training_s": t and t.training_seconds,
                    "sampling_s": t and t.sampling_seconds, "tts_99": t and t.seconds}
            rows.append(row)
    return rows


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    from qcpp.pipeline.device_compile import ESP_MODEL
    from qcpp.routing.native import IDLE_MODEL

    opts, cfg, reference, scheduler, workers, command = parse_args(argv)
    study = StudyConfig(cfg.cells, cfg.density, cfg.instances, max(cfg.depths), 0, 0, 0, 0.0, {}, cfg.seed)
    tasks = instances_of(study)
    load_before = os.getloadavg()[0]
    t0 = time.perf_counter()
    try:
        results = run_on_dask(tasks, cfg, scheduler, workers, fn=_ensemble_tasks.device_instance)
    except KeyboardInterrupt:
        print("interrupted: nothing written", file=sys.stderr)
        raise SystemExit(130) from None
    seconds = time.perf_counter() - t0
    load = (load_before, os.getloadavg()[0])
    rows = device_rows(results, reference)
    t = Table("QAOA on named devices: ESP and the 99% time with training counted (median [lower quartile, upper "
              "quartile] over the instances that fit), against the ideal all-to-all device and the fastest "
              "classical method per instance",
              ["cell", "device", "p", "fit", "ESP", "ESP idle", "99% time s", "device / ideal", "QAOA faster on"])
    for cell in cfg.cells:
        for device in cfg.devices:
            for p in cfg.depths:
                sel = [r for r in rows if (r["cell"], r["device"], r["p"]) == (cell, device, p)]
                fit = [r for r in sel if r["fits"]]
                faster = sum(r["tts_99"] < r["best_classical_s"] for r in fit)
                idle = [r["esp_idle"] for r in fit if r["esp_idle"] is not None]
                t.add(cell, device, p, f"{len(fit)} of {len(sel)}", _mqq_or_dash([r["esp"] for r in fit]),
                      _mqq_or_dash(idle), _mqq_or_dash([r["tts_99"] for r in fit]),
                      _mqq_or_dash([r["tts_99"] / r["ideal_tts_99"] for r in fit
                                    if math.isfinite(r["ideal_tts_99"])]),
                      f"{faster} of {len(fit)}")
    notes = [f"qcpp {qcpp.__version__}. Reference: {cfg.reference} (density {cfg.density:g}, seed {cfg.seed}); the "
             f"first {cfg.instances} instances of {', '.join(cfg.cells)}; depths {', '.join(map(str, cfg.depths))}.",
             "Routing: qcpp.estimators.routed.routed_fields, as time_to_solution.py (the default plan). A shot "
             f"succeeds with P(optimum) x ESP. ESP of the gates: {ESP_MODEL}. Where the device has T1/T2 (the IBM "
             f"snapshots), a shot's ESP is that times the {IDLE_MODEL} (the column ESP idle). Shot time: the "
             "device's durations where published, "
             "else the ideal gate model on the routed depths. Training: the reference's objective estimates x 1000 "
             "shots at the routed shot time. Device / ideal: over the instances whose ideal time is finite.",
             "The fastest classical time per instance is the reference's (wall-clock, on the machine and at the "
             "load of its run).",
             f"Whole run {seconds:.0f} s on a {os.cpu_count()}-core machine, load average (1 min) {load[0]:.1f} at "
             f"the start and {load[1]:.1f} at the end."]
    opts.results.mkdir(parents=True, exist_ok=True)
    write_results(opts, NAME, command, [t], notes)
    dump = {"qcpp_version": qcpp.__version__, "command": command, "config": asdict(cfg), "seconds": seconds,
            "load_average": list(load), "rows": rows}
    write_text_atomic(opts.results / f"{NAME}.json", json.dumps(dump, indent=1) + "\n")
    print(f"wrote {opts.results / f'{NAME}.json'}")
    return {"config": cfg, "rows": rows}


if __name__ == "__main__":
    main()
