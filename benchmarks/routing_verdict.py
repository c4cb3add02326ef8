"""A verdict for today's devices: the largest scenario that fits, routed, with its duration and ESP.

Run: ``python benchmarks/routing_verdict.py [--quick]`` (``--quick``: p = 1 only).

Table 1, per named device and p = 1..3: among the default scenarios (grids R x C, 2 <= R <= C <= 12, robots 1..4, every
``--ancilla-budget`` in :data:`BUDGETS`), the one with the most decision variables (data qubits) whose qubit count fits
the device's largest connected component; among its fitting budgets the one of fewest lowered CX (so the walk trades
qubits for two-qubit gates only where qubits are short). That scenario is then compiled and routed exactly as ``qcpp
compile --device NAME`` does (:func:`qcpp.pipeline.device_compile.compile_for_device`), and the table shows its routed
native two-qubit gates, duration (``-``: the device's source publishes no gate times) and ESP (product of (1 - error)
over native gates and of (1 - readout error) over the data qubits).

Table 2: which small default scenarios (p = 1..3) reach ESP >= 0.1 on each device (routed the same way).
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass

from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.estimators.routed import _largest_component
from qcpp.hardware.device import device_names, named_device
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario, max_default_robots
from qcpp.routing.native import duration_s, esp

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


def routed(c: Candidate, p: int, device: str) -> tuple[int, float | None, float, float]:
    """Routed native two-qubit gates, duration, ESP, seconds."""
    start = time.perf_counter()
    r = compile_for_device(default_scenario(c.rows, c.cols, c.robots), p, device, PlanOptions(ancilla_budget=c.budget))
    ops = r.routed.circuit.count_ops()
    twoq = sum(v for k, v in ops.items() if k in ("cz", "rzz", "cx"))
    return twoq, duration_s(r.routed), esp(r.routed), time.perf_counter() - start


def _fmt_duration(d: float | None) -> str:
    return "-" if d is None else f"{d * 1e3:.3g} ms"


def main() -> None:
    layers = (1,) if "--quick" in sys.argv else (1, 2, 3)
    print("| device | qubits | p | largest default scenario that fits | budget | qubits used | lowered cx "
          "| routed 2q | duration | ESP |")  # fmt: skip
    print("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|")
    biggest = max(_largest_component(named_device(name)) for name in device_names())
    pool = {p: candidates(p, biggest) for p in layers}
    for name in device_names():
        dev = named_device(name)
        usable = _largest_component(dev)
        for p in layers:
            fits = [c for c in pool[p] if c.qubits <= usable]
            best_data = max(c.data_qubits for c in fits)
            pick = min((c for c in fits if c.data_qubits == best_data), key=lambda c: (c.cx, c.qubits))
            twoq, dur, e, _ = routed(pick, p, name)
            budget = "default" if pick.budget is None else str(pick.budget)
            print(
                f"| {name} | {usable} | {p} | {pick.label} ({pick.data_qubits} variables) | {budget} | {pick.qubits} "
                f"| {pick.cx:,} | {twoq:,} | {_fmt_duration(dur)} | {e:.2g} |",
                flush=True,
            )
    print()
    print("| device | p | scenarios with ESP >= 0.1 (routed 2q, ESP) | best ESP of the rest |")
    print("|---|---:|---|---|")
    for name in device_names():
        for p in layers:
            good, rest = [], []
            for rows, cols, robots in SMALL:
                c = Candidate(rows, cols, robots, None, 0, 0, 0)
                twoq, _, e, _ = routed(c, p, name)
                (good if e >= 0.1 else rest).append((e, f"{c.label} ({twoq:,}, {e:.2f})"))
            best_rest = max(rest)[1] if rest else "-"
            print(f"| {name} | {p} | {', '.join(t for _, t in good) or 'none'} | {best_rest} |", flush=True)


if __name__ == "__main__":
    main()
