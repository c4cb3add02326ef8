"""The phase separator's cost by classes (:mod:`qcpp.plan.phase_classes`) against planning it term by term.

Run: ``python benchmarks/phase_count_speed.py [--no-sweep]``. Prints, for a few default scenarios, the time of the
call graph's phase part listed from the planned gadgets (:func:`qcpp.plan.phase.phase_plan`, then summed) and by
classes (:func:`qcpp.plan.phase_classes.phase_layer`, then summed), and whether both give the same cost (the
default phase separator, then ``--phase whole-space``); then, over every default
scenario of ``qcpp estimate --grid 2x2..40x40 --robots 1..8``, how many the classes answer and how long all of
them take (the rest is left to the plan).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter
from typing import Any

from qcpp.ir.cost import Cost
from qcpp.plan.phase import phase_plan
from qcpp.plan.phase_classes import phase_layer
from qcpp.problem.presets import default_scenario, max_default_robots

SAMPLE = [(10, 10, 2), (20, 20, 4), (30, 30, 8), (40, 40, 1), (40, 40, 8)]
WHOLE_SPACE_SAMPLE = [(10, 10, 2), (16, 16, 3), (20, 20, 4)]
"""``--phase whole-space``: the plan builds the Ising Hamiltonian (a dense ``n x n`` matrix), so smaller grids."""


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-sweep", action="store_true", help="the sample scenarios only, not the sweep")
    args = parser.parse_args(argv)
    print(f"{'scenario':<12}{'plan ms':>10}{'classes ms':>12}{'speed-up':>10}  same cost")
    for representation, sample in (("feasible", SAMPLE), ("whole-space", WHOLE_SPACE_SAMPLE)):
        if representation != "feasible":
            print(f"--phase {representation}:")
        _compare(representation, sample)
    if args.no_sweep:
        return 0
    return _sweep()


def _compare(representation: str, sample: list[tuple[int, int, int]]) -> None:
    for rows, cols, robots in sample:
        s = default_scenario(rows, cols, robots)
        t0 = time.perf_counter()
        plan = phase_plan(s, representation=representation)  # type: ignore[arg-type]
        plan_cost = _summed([(g, 1) for g in plan.gadgets("gamma")])
        t1 = time.perf_counter()
        layer = phase_layer(s, representation=representation)
        assert layer is not None
        layer_cost = _summed([(k.example, n) for k, n in layer.kinds()])
        t2 = time.perf_counter()
        same = plan_cost == layer_cost
        plan_ms, layer_ms = (t1 - t0) * 1e3, (t2 - t1) * 1e3
        print(f"{f'{rows}x{cols}/{robots}':<12}{plan_ms:>10.1f}{layer_ms:>12.1f}{plan_ms / layer_ms:>9.0f}x  {same}")


def _summed(parts: list[tuple[Any, int]]) -> tuple[Cost, Cost]:
    """Lowered and logical cost of ``(gadget, multiplicity)`` pairs (each gadget's own, not a kind's cache)."""
    return Cost.sum(n * g.cost() for g, n in parts), Cost.sum(n * g.logical_cost() for g, n in parts)


def _sweep() -> int:
    answered = left = 0
    sides: Counter[int] = Counter()
    t0 = time.perf_counter()
    for rows in range(2, 41):
        for cols in range(2, 41):
            for robots in range(1, min(8, max_default_robots(rows, cols)) + 1):
                if phase_layer(default_scenario(rows, cols, robots)) is None:
                    left += 1
                    sides[max(rows, cols)] += 1
                else:
                    answered += 1
    seconds = time.perf_counter() - t0
    print(
        f"2x2..40x40 x 1..8 robots: {answered + left:,} scenarios, classes answer {answered:,} in {seconds:.1f} s; "
        f"{left} left to the plan (longer side at most {max(sides, default=0)})"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
