"""A verdict for today's devices: the largest scenario that fits, routed, with its duration and ESP.

Run: ``python benchmarks/routing_verdict.py [--quick]`` (``--quick``: p = 1 only);
``python benchmarks/routing_verdict.py --calibrated``: the calibrated comparison with Qiskit O3 (below).

Table 1, per named device and p = 1..3: among the default scenarios (grids R x C, 2 <= R <= C <= 12, robots 1..4, every
``--ancilla-budget`` in :data:`BUDGETS`), the one with the most decision variables (data qubits) whose qubit count fits
the device's largest connected component; among its fitting budgets the one of fewest lowered CX (so the walk trades
qubits for two-qubit gates only where qubits are short). That scenario is then compiled and routed exactly as ``qcpp
compile --device NAME`` does (:func:`qcpp.pipeline.device_compile.compile_for_device`), and the table shows its routed
native two-qubit gates, duration (``-``: the device's source publishes no gate times) and ESP (product of (1 - error)
over native gates and of (1 - readout error) over the data qubits).

Table 2: which small default scenarios (p = 1..3) reach ESP >= 0.1 on each device (routed the same way).

Both tables give the ESP of the gates alone and with idle decoherence (:data:`qcpp.routing.native.IDLE_MODEL`;
``-`` where the device's source publishes no T1 / T2).

``--calibrated`` (p = 1, angles bound): on ibm_fez and ibm_torino, for :data:`CALIBRATED` (one-robot 3x3 and 3x4,
two-robot 3x3 without and with a hard obstacle, and with interior endpoints), what
``qcpp compile --device NAME`` writes (``--optimize-for esp``, the default there, and ``--optimize-for twoq``) against
``qiskit.transpile(optimization_level=3)`` of the same lowered circuit onto the calibrated target built from our
device file (:func:`qcpp.routing.target.device_target`), seeds 0-2, the best seed for each figure: two-qubit gates,
ESP of the gates and ESP with idle decoherence, each as qcpp / Qiskit, and the candidate compile chose; the
``twoq`` count (every candidate equal to the logical circuit on every input, as Qiskit's passes keep it); then the
same with ``--zero-start`` (also the candidates simplified for the all-|0> start, :mod:`qcpp.routing.known_state`:
equal to the logical circuit on that input only, a different scope), its ``twoq`` count and the ESP with idle
decoherence ``--optimize-for esp --zero-start`` chooses. One ``--optimize-for twoq --zero-start`` compile gives all
three: its candidates are those of the compile without the option plus the simplified ones, so the fewest two-qubit
gates among the others is what ``twoq`` alone writes, and the highest ESP with idle decoherence among all but the
searches on the sibling device (which only ``twoq`` runs) what ``esp --zero-start`` writes. Then the
compile time of ``qcpp compile --grid 5x5 --robots 2 --device heavy-hex`` (:func:`compile_for_device`, unbound)
against Qiskit O3 (seed 0) of the same lowered circuit onto that lattice's target, in the same run.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import dataclass
from typing import Any

from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.estimators.routed import _largest_component
from qcpp.hardware.device import device_names, named_device
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario, max_default_robots
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.routing.context import RoutingContext
from qcpp.routing.native import RUNNABLE_ESP, duration_s, esp, esp_idle
from qcpp.routing.qiskit_o3 import qiskit_o3

BUDGETS = (None, 64, 48, 32, 16, 0)
"""Ancilla budgets walked (``None``: the phase separator's default, fewest CX)."""

SMALL = ((2, 2, 1), (2, 3, 1), (3, 3, 1), (3, 4, 1), (4, 4, 1), (3, 3, 2), (4, 4, 2))


@dataclass(frozen=True)
class Candidate:
    """A default scenario, a budget, and its plan counts."""

    rows: int
    cols: int
    robots: int
    budget: int | None
    qubits: int
    data_qubits: int
    cx: int

    @property
    def label(self) -> str:
        return f"{self.rows}x{self.cols}/{self.robots}"


def candidates(p: int, max_qubits: int) -> list[Candidate]:
    """Every (grid, robots, budget) whose qubits fit ``max_qubits`` (budget 0, the fewest qubits, decides
    whether a grid and robot count is tried further)."""
    out = []
    for rows in range(2, 13):
        for cols in range(rows, 13):
            for robots in range(1, min(4, max_default_robots(rows, cols)) + 1):
                for budget in (0, *(b for b in BUDGETS if b != 0)):
                    options = EstimateOptions(plan=PlanOptions(ancilla_budget=budget), depth="none")
                    e = estimate_point(Point(rows, cols, robots, p, None), options)
                    if e.qubits <= max_qubits:
                        out.append(Candidate(rows, cols, robots, budget, e.qubits, e.data_qubits, e.cost.cx))
                    elif budget == 0:
                        break
    return out


def routed(c: Candidate, p: int, device: str) -> tuple[int, float | None, float, float | None, float]:
    """Routed native two-qubit gates, duration, ESP (gates), ESP with idle decoherence, seconds."""
    start = time.perf_counter()
    r = compile_for_device(default_scenario(c.rows, c.cols, c.robots), p, device, PlanOptions(ancilla_budget=c.budget))
    ops = r.routed.circuit.count_ops()
    twoq = sum(v for k, v in ops.items() if k in ("cz", "rzz", "cx"))
    return twoq, duration_s(r.routed), esp(r.routed), esp_idle(r.routed), time.perf_counter() - start


def _fmt_duration(d: float | None) -> str:
    return "-" if d is None else f"{d * 1e3:.3g} ms"


def _fmt_esp(e: float | None) -> str:
    return "-" if e is None else f"{e:.2g}"


BIND = {"gamma_0": 0.3, "beta_0": 0.7}
TWO_ROBOTS = [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}]
CALIBRATED: tuple[tuple[str, Scenario], ...] = (
    ("3x3/1", default_scenario(3, 3, 1)),
    ("3x4/1", default_scenario(3, 4, 1)),
    ("3x3/2", default_scenario(3, 3, 2)),
    ("3x3/2, obstacle", scenario_from_dict({"name": "3x3/2, hard obstacle at (1, 2)",
                                            "grid": {"rows": 3, "cols": 3, "obstacles": [[1, 2]]},
                                            "robots": TWO_ROBOTS, "objective": {"obstacles": "hard"}})),
    ("3x3/2, interior", scenario_from_dict({"name": "3x3/2, interior endpoints", "grid": {"rows": 3, "cols": 3},
                                            "robots": [{"start": [1, 1], "goal": [0, 2]},
                                                       {"start": [1, 0], "goal": [2, 2]}]})),
)  # fmt: skip
"""The calibrated comparison's scenarios."""


def _twoq(r: Any) -> int:
    return sum(1 for g in r.circuit.gates if len(g[1]) == 2)


def calibrated() -> None:
    """The ``--calibrated`` tables (module docs)."""
    context = RoutingContext()
    print("| device | scenario | CZ: qcpp / O3 | ESP gates: qcpp / O3 | ESP idle: qcpp / O3 | chosen (esp) "
          "| CZ (twoq): qcpp / O3 | CZ (twoq, --zero-start): qcpp / O3 | ESP idle (esp, --zero-start): qcpp / O3 "
          "| qcpp s / O3 s |")  # fmt: skip
    print("|---|---|---:|---:|---:|---|---:|---:|---:|---:|")
    for name in ("ibm_fez", "ibm_torino"):
        dev = named_device(name)
        for label, s in CALIBRATED:
            start = time.perf_counter()
            ours = compile_for_device(s, 1, name, bindings=BIND, context=context)
            ours_s = time.perf_counter() - start
            zero = compile_for_device(s, 1, name, bindings=BIND, context=context, optimize_for="twoq",
                                      zero_start=True)  # fmt: skip
            start = time.perf_counter()
            peers = [qiskit_o3(ours.compiled.circuit, dev, seed, range(s.num_variables)) for seed in range(3)]
            peer_s = (time.perf_counter() - start) / 3
            o3_twoq = min(_twoq(r) for r in peers)
            o3_esp = max(esp(r) for r in peers)
            o3_idle = max(esp_idle(r) or 0.0 for r in peers)
            q, e, ei = _twoq(ours.routed), esp(ours.routed), esp_idle(ours.routed) or 0.0
            qu = min(c["two_qubit"] for c in zero.candidates if "from |0>" not in c["name"])  # twoq alone
            qz = _twoq(zero.routed)
            ez = max(c["esp_idle"] or 0.0 for c in zero.candidates if not c["name"].startswith("search on ibm_"))
            chosen = ours.chosen.replace("|", "\\|")  # a markdown cell
            print(f"| {name} | {label} | {q:,} / {o3_twoq:,} = {q / o3_twoq:.2f} | {e:.3g} / {o3_esp:.3g} = "
                  f"{e / o3_esp:.2f} | {ei:.3g} / {o3_idle:.3g} = {ei / o3_idle:.2f} | {chosen} "
                  f"| {qu:,} / {o3_twoq:,} = {qu / o3_twoq:.2f} | {qz:,} / {o3_twoq:,} = {qz / o3_twoq:.2f} "
                  f"| {ez:.3g} / {o3_idle:.3g} = {ez / o3_idle:.2f} | {ours_s:.1f} / {peer_s:.1f} |", flush=True)
    print()
    print("| compile | qcpp s | Qiskit O3 s (same circuit, same lattice) | ratio | qcpp 2q | O3 2q |")
    print("|---|---:|---:|---:|---:|---:|")
    s = default_scenario(5, 5, 2)
    start = time.perf_counter()
    ours = compile_for_device(s, 1, "heavy-hex")
    ours_s = time.perf_counter() - start
    start = time.perf_counter()
    peer = qiskit_o3(ours.compiled.circuit, ours.routed.device, 0, range(s.num_variables))
    peer_s = time.perf_counter() - start
    print(f"| 5x5/2 --device heavy-hex ({ours.routed.device.name}) | {ours_s:.1f} | {peer_s:.1f} "
          f"| {ours_s / peer_s:.2f} | {_twoq(ours.routed):,} | {_twoq(peer):,} |", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="p = 1 only")
    parser.add_argument("--calibrated", action="store_true", help="the calibrated comparison with Qiskit O3")
    args = parser.parse_args()
    if args.calibrated:
        calibrated()
        return
    layers = (1,) if args.quick else (1, 2, 3)
    print("| device | coupled qubits (of all) | p | largest default scenario that fits | budget | qubits used "
          "| lowered cx | routed 2q | duration | ESP gates | ESP idle |")  # fmt: skip
    print("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    biggest = max(_largest_component(named_device(name)) for name in device_names())
    pool = {p: candidates(p, biggest) for p in layers}
    for name in device_names():
        dev = named_device(name)
        usable = _largest_component(dev)
        for p in layers:
            fits = [c for c in pool[p] if c.qubits <= usable]
            best_data = max(c.data_qubits for c in fits)
            pick = min((c for c in fits if c.data_qubits == best_data), key=lambda c: (c.cx, c.qubits))
            twoq, dur, e, ei, _ = routed(pick, p, name)
            budget = "default" if pick.budget is None else str(pick.budget)
            print(
                f"| {name} | {usable} (of {dev.num_qubits}) | {p} | {pick.label} ({pick.data_qubits} variables) "
                f"| {budget} | {pick.qubits} "
                f"| {pick.cx:,} | {twoq:,} | {_fmt_duration(dur)} | {e:.2g} | {_fmt_esp(ei)} |",
                flush=True,
            )
    print()
    print(f"| device | p | scenarios with ESP >= {RUNNABLE_ESP:g} (routed 2q, ESP gates, ESP idle) "
          "| best ESP of the rest |")
    print("|---|---:|---|---|")
    for name in device_names():
        for p in layers:
            good, rest = [], []
            for rows, cols, robots in SMALL:
                c = Candidate(rows, cols, robots, None, 0, 0, 0)
                twoq, _, e, ei, _ = routed(c, p, name)
                (good if e >= RUNNABLE_ESP else rest).append((e, f"{c.label} ({twoq:,}, {e:.2f}, {_fmt_esp(ei)})"))
            best_rest = max(rest)[1] if rest else "-"
            print(f"| {name} | {p} | {', '.join(t for _, t in good) or 'none'} | {best_rest} |", flush=True)


if __name__ == "__main__":
    main()
