"""Phase-separator cost per QAOA layer: the whole-space RZ/RZZ circuit against the feasible-subspace plan.

Run: ``PYTHONPATH=src python benchmarks/phase_cost.py`` (about a minute; ``--quick`` stops at 10x10). Prints one
table (markdown) for the default scenarios (:func:`qcpp.problem.presets.default_scenario`; 6 and 8 robots, which
it does not place, go on the boundary, see :func:`boundary_scenario`):

* ``paper re(re+1)``: the paper's phase-separator CNOT estimate (``re`` = decision variables);
* ``whole-space CX`` = 2 per nonzero coupling of :func:`qcpp.problem.hamiltonian.ising_hamiltonian` (the whole-space
  plan, exactly what ``qcpp.plan.phase.phase_separator_gates`` emits); ``ours CX`` = the phase part of the call graph,
  :func:`phase_cost` (target ``nisq``); rotations likewise;
* ``T (ft)``: T count of the layer's phase separator in the fault-tolerant model of
  :func:`qcpp.plan.phase.ft_t_count` (AND 4 T, uncompute 0, rotation 30 T at eps = 1e-3), the whole-space form's
  against the ``ft`` plan;
* ``ancillas``: clean ancillas the plan needs; ``plan s``: wall time of planning the phase separator and
  summing its part of the call graph (:func:`phase_cost`, listed from the planned gadgets).

Every figure is an exact count of lowered gates: the call graph's sums, as every estimate reports them
(``tests/compiler/phase_test.py`` checks the gadgets' costs against the emitted, lowered gates).
"""

from __future__ import annotations

import argparse
import sys
import time

from qcpp.estimators.counts import count
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.phase import PhasePlan, ft_t_count, phase_plan
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.grid import Grid
from qcpp.problem.presets import MAX_DEFAULT_ROBOTS, default_scenario
from qcpp.problem.scenario import Robot, Scenario

POINTS = [(3, 3, 1), (4, 4, 2), (5, 5, 2), (6, 6, 3), (8, 8, 3), (10, 10, 4), (12, 12, 4), (16, 16, 6)]
LARGE = (30, 30, 8)


def boundary_scenario(rows: int, cols: int, robots: int) -> Scenario:
    """``robots`` robots spread evenly on the boundary (clockwise from the top-left corner), each going to
    the boundary node half-way round."""
    ring = [(0, c) for c in range(cols)] + [(r, cols - 1) for r in range(1, rows)]
    ring += [(rows - 1, c) for c in range(cols - 2, -1, -1)] + [(r, 0) for r in range(rows - 2, 0, -1)]
    p = len(ring)
    placed = tuple(Robot(ring[i * p // robots], ring[(i * p // robots + p // 2) % p]) for i in range(robots))
    return Scenario(Grid(rows, cols), placed, name=f"boundary {rows}x{cols}, {robots} robot(s)")


def scenario(rows: int, cols: int, robots: int) -> Scenario:
    """The default scenario, or :func:`boundary_scenario` beyond the default placement's robots."""
    if robots <= MAX_DEFAULT_ROBOTS:
        return default_scenario(rows, cols, robots)
    return boundary_scenario(rows, cols, robots)


def phase_cost(s: Scenario, logical: bool = False, **options: object) -> Cost:
    """One layer's phase separator as the call graph sums it (listed from the planned gadgets), with
    :class:`~qcpp.plan.options.PlanOptions` ``options``."""
    graph = qaoa_plan(s, 1, PlanOptions(**options)).call_graph(by_classes=False)  # type: ignore[arg-type]
    return graph.cost_by_part(logical)["phase"]


def phase_circuit(s: Scenario, plan: PhasePlan) -> Circuit:
    """One layer's phase separator as a circuit: each gadget its own section, ancillas after the data."""
    n = s.num_variables
    secs = [Section("phase_0", tuple(g.emit())) for g in plan.gadgets("gamma_0")]
    return Circuit([("data", n), ("logic", max(1, plan.num_ancillas))], secs)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="stop at 10x10")
    quick = parser.parse_args(argv).quick
    points = [p for p in POINTS if not (quick and p[0] > 10)]
    print("| grid | robots | re | paper re(re+1) | whole-space CX | ours CX | ratio | whole-space rot. | ours rot. "
          "| whole-space T (ft) "
          "| ours T (ft) | T ratio | ancillas | plan s |")  # fmt: skip
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for rows, cols, robots in points:
        s = scenario(rows, cols, robots)
        re = s.num_variables
        wc, wl = phase_cost(s, phase="whole-space"), phase_cost(s, True, phase="whole-space")
        t0 = time.perf_counter()
        oc = phase_cost(s)
        dt = time.perf_counter() - t0
        plan = phase_plan(s)
        tw, to = ft_t_count(wl), ft_t_count(phase_cost(s, True, target="ft"))
        print(
            f"| {rows}x{cols} | {robots} | {re:,} | {re * (re + 1):,} | {wc.cx:,} | {oc.cx:,} | "
            f"{oc.cx / max(wc.cx, 1):.3f} | {wc.rotations:,} | "
            f"{oc.rotations:,} | {tw:,} | {to:,} | {to / max(tw, 1):.4f} | {plan.num_ancillas} | {dt:.2f} |"
        )
    print()
    print("Fewer ancillas: ``ancilla_budget`` set to what the balance term's low-ancilla variants need: ``registers``")
    print("(one robot's tree at a time, the lengths copied into small registers) and ``accumulator`` (trees of 4B")
    print("terms added into B-bit registers by a ripple-carry adder).")
    print()
    print("| grid | robots | ancillas (no budget) | CX (no budget) | registers: ancillas | CX | ratio to whole-space "
          "| accumulator: ancillas | CX | ratio to whole-space |")  # fmt: skip
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for rows, cols, robots in points:
        s = scenario(rows, cols, robots)
        plan = phase_plan(s)
        bal = [r for r in plan.explain() if r["group"] == "balance"]
        if not bal or bal[0]["construction"] != "arithmetic":
            continue
        whole = phase_cost(s, phase="whole-space").cx
        cells = []
        for variant in ("registers", "accumulator"):
            budget = max(bal[0]["alternatives"][variant]["ancillas"], 2 * robots)
            few, few_cx = phase_plan(s, ancilla_budget=budget), phase_cost(s, ancilla_budget=budget).cx
            cells.append(f"{few.num_ancillas} | {few_cx:,} | {few_cx / whole:.3f}")
        print(f"| {rows}x{cols} | {robots} | {plan.num_ancillas} | {phase_cost(s).cx:,} | " + " | ".join(cells) + " |")
    print()
    print("Depth of the lowered phase separator (ASAP layers, as ``qcpp.estimators.counts``;"
          " two-qubit depth in brackets):")
    print()
    print("| grid | robots | whole-space | ours (`optimize=cx`) | ours (`optimize=depth`) |")
    print("|---|---:|---:|---:|---:|")
    for rows, cols, robots in points:
        if rows > 10:
            continue
        s = scenario(rows, cols, robots)
        cells = []
        for kw in ({"representation": "whole-space"}, {}, {"optimize": "depth"}):
            k = count(lower(phase_circuit(s, phase_plan(s, **kw))))
            cells.append(f"{k.depth:,} ({k.two_qubit_depth:,})")
        print(f"| {rows}x{cols} | {robots} | " + " | ".join(cells) + " |")
    if not quick:
        rows, cols, robots = LARGE
        s = scenario(rows, cols, robots)
        t0 = time.perf_counter()
        oc = phase_cost(s)
        dt = time.perf_counter() - t0
        print()
        print(f"{rows}x{cols}, {robots} robots ({s.num_variables:,} variables): ours {oc.cx:,} CX, "
              f"{oc.rotations:,} rotations; planned and summed in {dt:.2f} s (whole-space not built)")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
