"""CNOT counts side by side: qcpp's own lowering vs Qiskit's O3 transpile of qcpp's OpenQASM 3.

Run: ``python benchmarks/interop.py``. For each default scenario at p = 1 (bound angles): qubits and CX count of
qcpp's lowered circuit, and the CX count Qiskit's ``transpile(..., optimization_level=3)`` (basis cx, rz, sx, x)
reaches from ``qiskit.qasm3.loads`` of the high-level OpenQASM 3 (multi-controlled X as ``ctrl``/``negctrl @ x``
statements, which Qiskit loads as ``MCXGate`` and synthesises with its own methods), and from the lowered
OpenQASM 2. The ratio is Qiskit's high-level result over qcpp's lowering (goal: at most 1.01).
"""

from __future__ import annotations

import argparse
import time

import qiskit.qasm2 as qasm2
import qiskit.qasm3 as qasm3
from qiskit import transpile

from qcpp.lowering.qasm import to_qasm2, to_qasm3
from qcpp.plan.compile import compile_scenario
from qcpp.problem.presets import default_scenario

CASES = ((3, 3, 1), (5, 5, 2))
BASIS = ["cx", "rz", "sx", "x"]
ANGLES = {"gamma_0": 0.37, "beta_0": -1.3}


def _o3_cx(qc: object) -> int:
    out = transpile(qc, basis_gates=BASIS, optimization_level=3, seed_transpiler=1)
    return int(out.count_ops().get("cx", 0))


def main() -> int:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    head = f"{'scenario':<9} {'qubits':>6} {'qcpp lowered CX':>15} {'Qiskit O3 of our QASM3':>22}"
    print(f"{head} {'ratio':>6} {'Qiskit O3 of our lowered QASM2':>30} {'seconds':>7}")
    for rows, cols, robots in CASES:
        start = time.perf_counter()
        s = default_scenario(rows, cols, robots)
        high = compile_scenario(s, 1, bindings=ANGLES).circuit
        low = compile_scenario(s, 1, lowered=True, bindings=ANGLES).circuit
        ours = low.count_ops()["cx"]
        theirs = _o3_cx(qasm3.loads(to_qasm3(high)))
        relowered = _o3_cx(qasm2.loads(to_qasm2(low)))
        name = f"{rows}x{cols}/{robots}"
        print(
            f"{name:<9} {low.num_qubits:>6} {ours:>15,} {theirs:>22,} {theirs / ours:>6.3f} {relowered:>30,} "
            f"{time.perf_counter() - start:>7.1f}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
