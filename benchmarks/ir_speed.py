"""Speed of the gate IR on a synthetic workload shaped like the target QAOA circuits.

Run: ``python benchmarks/ir_speed.py`` (plain script, one core). Workload: 720 data qubits,
two QAOA layers with 250,000 rzz + 720 rz with symbolic angles in total, 2,000 mcx with 4-8
mixed-polarity controls targeting a 64-qubit logic register, 650 csbf. Random qubits are
drawn first (untimed); then it times building the circuit, ``lower``, ``to_qasm3``
(symbolic), ``bind`` and ``to_qasm2``, in wall-clock and CPU seconds. Target: < 10 s in all.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from typing import TypeVar

import numpy as np

from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, CircuitBuilder, Register
from qcpp.ir.gates import csbf, h, mcx, rz, rzz
from qcpp.lowering.passes import lower
from qcpp.lowering.qasm import to_qasm2, to_qasm3

N_DATA = 720
N_LOGIC = 64
LAYERS = 2
N_RZZ = 250_000
N_MCX = 2_000
N_CSBF = 650

T = TypeVar("T")


Spec = dict[str, list]


def random_spec(seed: int = 7) -> Spec:
    """Random qubits and coefficients (drawn up front so that ``build`` times only the IR)."""
    rng = np.random.default_rng(seed)
    n_pairs = N_RZZ // LAYERS
    spec: Spec = {"rzz": [], "rz": [], "mcx": [], "csbf": []}
    for _ in range(LAYERS):
        a = rng.integers(0, N_DATA, n_pairs)
        b = (a + rng.integers(1, N_DATA, n_pairs)) % N_DATA  # b != a
        coeff = rng.uniform(-2, 2, n_pairs)
        spec["rzz"].append(list(zip(coeff.tolist(), a.tolist(), b.tolist(), strict=True)))
        spec["rz"].append(rng.uniform(-1, 1, N_DATA // LAYERS).tolist())
        mcxs = []
        for _ in range(N_MCX // LAYERS):
            k = int(rng.integers(4, 9))
            qs = rng.choice(N_DATA, k, replace=False).tolist()
            mcxs.append((qs, "".join(rng.choice(["0", "1"], k).tolist())))
        spec["mcx"].append(mcxs)
        spec["csbf"].append([rng.choice(N_DATA, 4, replace=False).tolist() for _ in range(N_CSBF // LAYERS)])
    return spec


def build(spec: Spec) -> Circuit:
    """The synthetic circuit: initial state, then per layer a phase and a mixer section."""
    b = CircuitBuilder([Register("data", N_DATA), Register("logic", N_LOGIC)])
    logic = list(range(N_DATA, N_DATA + N_LOGIC))
    b.append([h(q) for q in range(N_DATA)], section="initial_state")
    for layer in range(LAYERS):
        gamma = f"gamma_{layer}"
        b.append(
            [rzz(Angle.symbol(gamma, c), a, q) for c, a, q in spec["rzz"][layer]],
            section=f"phase_{layer}",
        )
        b.append(rz(Angle.symbol(gamma, c), q) for q, c in enumerate(spec["rz"][layer]))
        beta = Angle.symbol(f"beta_{layer}", 2.0)
        csbfs = spec["csbf"][layer]
        gates = []
        for i, (qs, state) in enumerate(spec["mcx"][layer]):
            gates.append(mcx(qs, logic[i % N_LOGIC], state))
            if i % 3 == 0 and i // 3 < len(csbfs):
                gates.append(csbf(beta, logic[i % N_LOGIC], *csbfs[i // 3]))
        b.append(gates, section=f"mixer_{layer}")
    return b.build()


def main() -> int:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    rows: list[tuple[str, float, float, str]] = []

    def timed(label: str, fn: Callable[[], T], detail: Callable[[T], str]) -> T:
        w0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        rows.append((label, time.perf_counter() - w0, time.process_time() - c0, detail(out)))
        return out

    spec = random_spec()
    circ = timed("build", lambda: build(spec), lambda c: f"{len(c):,} gates, {c.count_ops()}")
    low = timed("lower", lambda: lower(circ), lambda c: f"{len(c):,} gates on {c.num_qubits} qubits")
    timed("to_qasm3", lambda: to_qasm3(low), lambda s: f"{len(s) / 1e6:.1f} MB, symbolic")
    values = {s: 0.1 * (i + 1) for i, s in enumerate(low.symbols)}
    bound = timed("bind", lambda: low.bind(values), lambda c: f"symbols left: {len(c.symbols)}")
    timed("to_qasm2", lambda: to_qasm2(bound), lambda s: f"{len(s) / 1e6:.1f} MB")
    width = max(len(r[0]) for r in rows)
    print(f"{'step':<{width}}  {'wall':>7}  {'cpu':>7}  detail")
    for label, wall, cpu, detail in rows:
        print(f"{label:<{width}}  {wall:6.2f}s  {cpu:6.2f}s  {detail}")
    wall = sum(r[1] for r in rows)
    cpu = sum(r[2] for r in rows)
    print(f"{'total':<{width}}  {wall:6.2f}s  {cpu:6.2f}s  (target < 10 s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
