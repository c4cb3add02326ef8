"""Tensor-network validation speed (quimb + cotengra) of compiled, lowered QAOA circuits at 15-50 qubits.

Run: ``python benchmarks/tensor_speed.py``. Each row is what ``qcpp validate SCENARIO -p P --backend tensor``
does with its defaults (seed 0, at most 256 contracted amplitudes, MPS up to bond 32), timed end to end in this
process: qubits, gates, seconds of each check (MPS ancilla probability and amplitudes, exact contraction with the
partial mixers collapsed into data operators and the phase arithmetic into diagonals, path search included) and
the largest amplitude error against the subspace simulator. Paths are cached in a fresh temporary directory, so
the first row of each scenario includes every path search; the ``(cached)`` row repeats a case with the paths
found (a second ``qcpp validate`` run).
"""

from __future__ import annotations

import argparse
import tempfile
import time

from qcpp.problem.presets import default_scenario
from qcpp.simulate.validate import validate

CASES = ((3, 3, 1, 1, ""), (3, 3, 2, 1, ""), (3, 4, 2, 1, ""), (3, 4, 2, 1, "cached"), (3, 4, 2, 2, ""))


def main() -> int:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    cache = tempfile.mkdtemp(prefix="qcpp-tensor-speed-")
    head = f"{'scenario':<17} {'p':>1} {'qubits':>6} {'gates':>5} {'checks (method: seconds, status)':<92}"
    print(f"{head} {'max err':>8} {'total s':>7}")
    for rows, cols, robots, p, tag in CASES:
        start = time.perf_counter()
        r = validate(default_scenario(rows, cols, robots), p, backend="tensor", seed=0, cache_dir=cache)
        total = time.perf_counter() - start
        checks = ", ".join(f"{c.name[:9]} {c.method[7:]}: {c.seconds:.1f} {c.status}" for c in r.checks)
        name = f"{rows}x{cols}/{robots}" + (f" ({tag})" if tag else "")
        print(f"{name:<17} {p:>1} {r.qubits:>6} {r.gates:>5} {checks:<92} {r.max_amplitude_error:>8.1e} {total:>7.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
