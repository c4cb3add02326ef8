"""Dense statevector simulation of compiled, lowered QAOA circuits (the paper simulated its 3x3 case, 20 qubits).

Run: ``python benchmarks/statevector_speed.py``. Prints qubits, gates, seconds (wall / CPU) and the probability
held on feasible assignments with clean ancillas (1 up to round-off: the check the simulation is for).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from qcpp.plan.compile import compile_scenario
from qcpp.problem.paths import assignment_bits, enumerate_paths
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.simulate.sparse import basis_from_bits
from qcpp.simulate.statevector import simulate_statevector


def held_on_feasible(s: Scenario, psi: np.ndarray) -> float:
    """Probability on feasible assignments with every ancilla in |0> (one robot)."""
    idx = [basis_from_bits(list(assignment_bits(s, [m]))) for m in enumerate_paths(s, 0)]
    return float(np.sum(np.abs(psi[idx]) ** 2))


def main() -> int:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    cases = [
        ("examples/paper_3x3.toml", load_scenario("examples/paper_3x3.toml")),
        ("default 3x3, 1 robot", default_scenario(3, 3, 1)),
    ]
    print(f"{'scenario':<26} {'p':>2} {'qubits':>6} {'gates':>7} {'wall s':>7} {'CPU s':>6} {'held':>14}")
    for name, s in cases:
        for p in (1, 2, 3):
            angles = {f"gamma_{i}": 0.1 * (i + 1) for i in range(p)}
            angles |= {f"beta_{i}": 0.5 + 0.1 * (i + 1) for i in range(p)}
            circuit = compile_scenario(s, p, lowered=True, bindings=angles).circuit
            wall, cpu = time.perf_counter(), time.process_time()
            psi = simulate_statevector(circuit)
            wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
            held = held_on_feasible(s, psi)
            print(
                f"{name:<26} {p:>2} {circuit.num_qubits:>6} {len(circuit):>7} {wall:>7.2f} {cpu:>6.2f} {held:>14.12f}"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
