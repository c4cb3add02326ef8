"""The hardware verdict checked against a noisy simulation: P(optimum) under the device's noise beside ESP x P(optimum).

Run: ``python benchmarks/noisy_verdict.py [--quick] [--shots N] [--max-qubits K] [--max-ideal-qubits K]
[--device NAME ...] [--time]`` (``--quick``: p = 1 only; defaults: 400 shots, 16 active qubits for the noisy runs,
22 for the ideal one, every named device). Needs the extra ``noise`` (qiskit-aer).

For every small default scenario of the verdict (:data:`SMALL` of ``benchmarks/routing_verdict.py``), every named
device and p = 1..3: the QAOA angles are trained on qcpp's exact subspace simulator (``qcpp.train_qaoa`` with
:data:`qcpp.training.qaoa_solver.SINGLE_START`: this check compares noise models, not trainings), the circuit is
compiled with them and routed as ``qcpp compile --device NAME`` does, and its ESP (:func:`qcpp.routing.native.esp`)
computed. Every row with ESP >= 0.1 (the verdict's "feasible") is simulated
with the device file's noise model (:mod:`qcpp.simulate.noisy`: depolarising + thermal relaxation per gate, idle
relaxation, read-out; T1/T2 and durations only where the file has them) on its active qubits, when they are at
most ``--max-qubits`` (state-vector trajectories cost 2^k per gate and shot); the others show ``-``. The routed
circuit without noise is simulated (exactly: one state vector) up to ``--max-ideal-qubits``.

Columns: routed two-qubit gates, active qubits, ESP, P(optimum) of the trained state (subspace simulator), the
same read from the routed circuit without noise (aer, exact; the routing and the conversion checked), ESP x P(optimum),
P(optimum) under noise (+- its standard error with sampled trajectories), the ratio noisy / (ESP x P(optimum)),
and where the device file has T1/T2 (the IBM snapshots) P(optimum) under noise without the idle relaxation (gate
and read-out errors only, what the ESP model charges), the idle-aware product (ESP with idle decoherence,
:func:`qcpp.routing.native.esp_idle`, x P(optimum)) and the ratio of the noisy figure to it. With ``--time`` two
more columns: the run time :func:`qcpp.simulate_noisy`'s guard predicts for the noisy run
(:func:`qcpp.simulate.noisy.noisy_need`) and the wall time it took.
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import qcpp
from qcpp.hardware.device import device_names
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.plan.options import PlanOptions
from qcpp.problem.limits import format_duration
from qcpp.problem.presets import default_scenario
from qcpp.routing.native import RUNNABLE_ESP, esp, esp_idle
from qcpp.simulate.noisy import active_qubits, noisy_need, simulate_noisy
from qcpp.training.evaluate import feasible_assignments
from qcpp.training.qaoa_solver import SINGLE_START

SMALL = ((2, 2, 1), (2, 3, 1), (3, 3, 1), (3, 4, 1), (4, 4, 1), (3, 3, 2), (4, 4, 2))
"""The verdict's small default scenarios (``benchmarks/routing_verdict.py``)."""

FEASIBLE_ESP = RUNNABLE_ESP


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--shots", type=int, default=400)
    ap.add_argument("--max-qubits", type=int, default=16)
    ap.add_argument("--max-ideal-qubits", type=int, default=22)
    ap.add_argument("--device", action="append", choices=device_names(), help="only these devices (repeatable)")
    ap.add_argument("--time", action="store_true", help="the noisy run's predicted and measured wall time")
    args = ap.parse_args()
    layers = (1,) if args.quick else (1, 2, 3)
    trained: dict[tuple[int, int, int, int], tuple[dict[str, float], float, list[int]]] = {}
    print("| device | p | scenario | routed 2q | active qubits | ESP | P(opt) ideal | P(opt) routed, no noise "
          "| ESP x P(opt) | P(opt) noisy | noisy / (ESP x P(opt)) | P(opt) noisy, no idle relaxation "
          "| ESP idle x P(opt) | noisy / (ESP idle x P(opt)) | method |"
          + (" noisy run predicted | noisy run measured |" if args.time else ""))  # fmt: skip
    rule = "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
    print(rule + ("---:|---:|" if args.time else ""))
    for name in args.device or device_names():
        for p in layers:
            for rows, cols, robots in SMALL:
                key = (rows, cols, robots, p)
                s = default_scenario(rows, cols, robots)
                if key not in trained:
                    sol = qcpp.train_qaoa(s, p, **SINGLE_START)
                    angles = {}
                    for k in range(p):
                        angles[f"gamma_{k}"], angles[f"beta_{k}"] = sol.angles[2 * k], sol.angles[2 * k + 1]
                    feasible, optimal = feasible_assignments(s)
                    trained[key] = (angles, float(sol.p_optimum), feasible[optimal].tolist())
                angles, ideal, targets = trained[key]
                start = time.perf_counter()
                routed = compile_for_device(s, p, name, PlanOptions(), bindings=angles).routed
                e = esp(routed)
                if e < FEASIBLE_ESP:
                    break  # the scenarios grow: the rest of this device and p are below the line too
                ops = routed.circuit.count_ops()
                twoq = sum(v for k, v in ops.items() if k in ("cz", "rzz", "cx"))
                k = len(active_qubits(routed))
                cells = [name, str(p), f"{rows}x{cols}/{robots}", f"{twoq:,}", str(k), f"{e:.3f}", f"{ideal:.3f}"]
                idle_esp = esp_idle(routed, gate_esp=e)
                idle_product = "-" if idle_esp is None else f"{idle_esp * ideal:.3f}"
                if k > args.max_qubits:
                    clean_cell = "-"
                    if k <= args.max_ideal_qubits:
                        clean_cell = f"{simulate_noisy(routed, targets, noise=False).p_optimum:.3f}"
                    cells += [clean_cell, f"{e * ideal:.3f}", "-", "-", "-", idle_product, "-",
                              f"not simulated ({k} > {args.max_qubits} qubits)"]  # fmt: skip
                    if args.time:
                        cells += [format_duration(noisy_need(routed, shots=args.shots).seconds or 0.0), "-"]
                else:
                    clean = simulate_noisy(routed, targets, noise=False)
                    predicted = noisy_need(routed, shots=args.shots).seconds or 0.0
                    t0 = time.perf_counter()
                    noisy = simulate_noisy(routed, targets, shots=args.shots)
                    measured = time.perf_counter() - t0
                    err = f" +- {noisy.stderr:.3f}" if noisy.shots else ""
                    ratio = noisy.p_optimum / (e * ideal) if e * ideal > 0 else math.nan
                    gates_only = "-"
                    if routed.device.t1_s is not None:  # idle relaxation applies: the run without it beside
                        g = simulate_noisy(routed, targets, idle=False, shots=args.shots)
                        gates_only = f"{g.p_optimum:.3f}" + (f" +- {g.stderr:.3f}" if g.shots else "")
                    idle_ratio = "-" if idle_esp is None or idle_esp * ideal <= 0 else (
                        f"{noisy.p_optimum / (idle_esp * ideal):.2f}")  # fmt: skip
                    how = noisy.method + (f", {noisy.shots} shots" if noisy.shots else "")
                    cells += [f"{clean.p_optimum:.3f}", f"{e * ideal:.3f}", f"{noisy.p_optimum:.3f}{err}",
                              f"{ratio:.2f}", gates_only, idle_product, idle_ratio, how]  # fmt: skip
                    if args.time:
                        cells += [format_duration(predicted), format_duration(measured)]
                print("| " + " | ".join(cells) + " |", flush=True)
                seconds = time.perf_counter() - start
                print(f"[{name} p={p} {rows}x{cols}/{robots}: {seconds:.0f} s]", file=sys.stderr, flush=True)


if __name__ == "__main__":
    main()
