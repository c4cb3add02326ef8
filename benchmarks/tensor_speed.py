"""Tensor-network validation speed (quimb + cotengra) of compiled, lowered QAOA circuits at 18-40 qubits.

Run: ``python benchmarks/tensor_speed.py``. For each default scenario at p = 1: qubits, gates, seconds of each
check of :func:`simulate.validate.validate` (MPS ancilla probability, MPS amplitudes, exact contraction of a
seeded sample of amplitudes, path search included) and the largest amplitude error against the subspace simulator.
"""

from __future__ import annotations

import time

from gridcover.presets import default_scenario
from simulate.validate import validate

CASES = ((3, 3, 1, None), (3, 3, 2, 16), (3, 4, 2, 6))


def main() -> int:
    print(f"{'scenario':<12} {'qubits':>6} {'gates':>6} {'checks (method: seconds)':<62} {'max err':>8} {'total s':>8}")
    for rows, cols, robots, sample in CASES:
        start = time.perf_counter()
        r = validate(default_scenario(rows, cols, robots), 1, backend="tensor", seed=7, max_amplitudes=sample)
        checks = ", ".join(f"{c.name[:9]} {c.method}: {c.seconds:.1f}" for c in r.checks)
        name = f"{rows}x{cols}/{robots}"
        total = time.perf_counter() - start
        print(f"{name:<12} {r.qubits:>6} {r.gates:>6} {checks:<62} {r.max_amplitude_error:>8.1e} {total:>8.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
