"""Compile speed on real scenarios: build, lower and write OpenQASM 3 (and 2, bound) for the default scenarios.

Run: ``python benchmarks/compile_speed.py [p]``. Prints one row per (grid, robots) with wall and CPU seconds of
each step; the target of the issue is build + lower + write under 10 s for 10x10 with 4 robots at p = 1.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from collections.abc import Callable
from typing import TypeVar

from qcpp.lowering.passes import lower
from qcpp.lowering.qasm import write_qasm
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.presets import default_scenario

T = TypeVar("T")
CASES = ((3, 3, 1), (5, 5, 2), (8, 8, 3), (10, 10, 4))


def timed(fn: Callable[[], T]) -> tuple[T, float, float]:
    wall, cpu = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - wall, time.process_time() - cpu


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("p", type=int, nargs="?", default=1, help="QAOA layers (default 1)")
    p = parser.parse_args(argv).p
    header = (
        f"{'grid':>6} {'robots':>6} {'qubits':>7} {'gates (lowered)':>16} "
        f"{'build':>13} {'lower':>13} {'write qasm3':>13} {'bind+qasm2':>13} {'total':>13}"
    )
    print(f"p = {p}; each step as wall s / CPU s")
    print(header)
    with tempfile.TemporaryDirectory() as d:
        for rows, cols, robots in CASES:
            s = default_scenario(rows, cols, robots)
            circuit, w1, c1 = timed(lambda s=s: qaoa_circuit(s, p))
            lowered, w2, c2 = timed(lambda c=circuit: lower(c))
            _, w3, c3 = timed(lambda lc=lowered: write_qasm(lc, os.path.join(d, "c.qasm"), version=3))
            values = {name: 0.1 * (i + 1) for i, name in enumerate(lowered.symbols)}
            _, w4, c4 = timed(
                lambda lc=lowered, v=values: write_qasm(lc.bind(v), os.path.join(d, "c2.qasm"), version=2)
            )
            cells = [f"{w:6.2f}/{c:5.2f}" for w, c in ((w1, c1), (w2, c2), (w3, c3), (w4, c4))]
            total = f"{w1 + w2 + w3:6.2f}/{c1 + c2 + c3:5.2f}"
            print(
                f"{f'{rows}x{cols}':>6} {robots:>6} {lowered.num_qubits:>7} {len(lowered):>16,} "
                + " ".join(f"{x:>13}" for x in cells)
                + f" {total:>13}"
            )
    print("total = build + lower + write qasm3")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
