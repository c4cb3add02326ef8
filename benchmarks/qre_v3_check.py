"""Can ``qdk.qre`` (the QDK's new resource estimator) stand in for the legacy ``qdk.openqasm.estimate``?

Run: ``python benchmarks/qre_v3_check.py``. Model: qubit_gate_ns_e3, surface code, error budget 1e-3 (the defaults of
``qcpp estimate --physical``); circuits: the default 3x3 scenario with one robot at p = 1, targets nisq and ft,
``gamma_0 = 0.3, beta_0 = 0.7``, written in the logical-AND model
(:func:`~qcpp.estimators.qdk_reading.logical_and_qasm`, the text ``benchmarks/ft_vs_qdk.py`` compares).

For each circuit the script prints the legacy estimate (:func:`~qcpp.estimators.qdk_reading.qdk_read`: physical
qubits, runtime, code distance, T factories) and every entry of the Pareto frontier ``qdk.qre.estimate`` returns
for the same OpenQASM text (``OpenQASMApplication``), the same qubit (``GateBased(error_rate=1e-3, gate_time=50,
measurement_time=100)``: qubit_gate_ns_e3's error rates and times) and ``SurfaceCode`` under ``max_error=1e-3``,
with each of its two distillation factories (``RoundBasedFactory``, ``Litinski19Factory``). The last column says
whether an entry equals the legacy estimate in physical qubits and runtime.
"""

from __future__ import annotations

import argparse
import sys

from qcpp.estimators.qdk_reading import logical_and_qasm, qdk_read
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario

ANGLES = {"gamma_0": 0.3, "beta_0": 0.7}
TARGETS = ("nisq", "ft")


def _distance(entry: object) -> int | None:
    """The surface-code distance an entry of the qre frontier was built with."""
    from qdk.qre.models import SurfaceCode

    for node in entry.source.nodes:  # type: ignore[attr-defined]
        if isinstance(node.transform, SurfaceCode):
            return int(node.transform.distance)
    return None


def main(argv: list[str] | None = None) -> int:
    """Print the legacy estimate and the qre frontier per circuit."""
    argparse.ArgumentParser(prog="qre_v3_check.py", description=__doc__.split("\n\n")[0]).parse_args(argv)
    from qdk import qre
    from qdk.qre.application import OpenQASMApplication
    from qdk.qre.models import GateBased, Litinski19Factory, RoundBasedFactory, SurfaceCode

    arch = GateBased(error_rate=1e-3, gate_time=50, measurement_time=100)
    print("| circuit | estimator | physical qubits | runtime (us) | code distance | error | equals legacy |")
    print("|---|---|---:|---:|---:|---:|---|")
    for target in TARGETS:
        circuit = compile_scenario(default_scenario(3, 3, 1), 1, PlanOptions(target=target), bindings=ANGLES).circuit
        text = logical_and_qasm(lower(circuit, basis=LOGICAL_BASIS))
        old = qdk_read(text).physical
        name = f"3x3/1 {target}"
        print(f"| {name} | legacy (`qdk.openqasm.estimate`) | {old.physical_qubits:,} | {old.runtime_s * 1e6:,.1f} "
              f"| {old.code_distance} | (budget 1e-3) | |")
        for factory in (RoundBasedFactory, Litinski19Factory):
            table = qre.estimate(OpenQASMApplication(text), arch, SurfaceCode.q() * factory.q(), max_error=1e-3)
            for entry in sorted(table, key=lambda e: e.qubits):
                same = entry.qubits == old.physical_qubits and abs(entry.runtime - old.runtime_s * 1e9) < 1
                print(f"| {name} | qre, {factory.__name__} | {entry.qubits:,} | {entry.runtime / 1e3:,.1f} "
                      f"| {_distance(entry)} | {entry.error:.2e} | {'yes' if same else 'no'} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
