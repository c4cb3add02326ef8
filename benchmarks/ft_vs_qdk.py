"""qcpp's fault-tolerant estimate against the QDK resource estimator's own reading of the same circuit, per term.

Run: ``python benchmarks/ft_vs_qdk.py [--quick]`` (``--quick``: 3x3/1 only). Model: qubit_gate_ns_e3, surface code,
error budget 1e-3 (the defaults of ``qcpp estimate --physical``); circuits: default scenarios at p = 1, targets
nisq and ft, angles gamma_0 = 0.3, beta_0 = 0.7.

Four estimates of each circuit (:mod:`qcpp.estimators.qdk_reading`):

* **qcpp**: ``qcpp estimate --physical`` (its logical counts, exact depths, handed to the QDK estimator);
* **QDK, file (--bind)**: the QDK reading the OpenQASM 3 file ``qcpp compile --bind`` writes (high level: the
  multi-controlled gates as qcpp's gate definitions, which the QDK decomposes its own way; ANDs and their
  uncomputes written unitarily, no measurement);
* **QDK, file (--lowered --bind)**: the QDK reading the file ``qcpp compile --lowered --bind`` writes (qcpp's own
  decomposition into {cx, x, h, rz, t, tdg, s, sdg}: the gate counts of qcpp's tables);
* **QDK, logical-AND**: the QDK reading the same circuit written in the logical-AND model
  (:func:`~qcpp.estimators.qdk_reading.logical_and_qasm`: AND = ``ccx``, uncompute by measurement, data read out).

Table 1: per term, qcpp / QDK (logical-AND) and qcpp / QDK (each file), min..max over the circuits. Table 2: every
figure. Table 3: the QDK estimator fed qcpp's counts with only the rotation depth replaced by the QDK's, against
the QDK's own estimate of the logical-AND text: the rotation depth is then the whole difference. Table 4: the QDK's
rotation-depth rule re-implemented in Python (:func:`~qcpp.estimators.qdk_reading.asap_rotation_depth`) on the
file's gates, against the QDK's figure, and qcpp's rotation depth beside them.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, replace

from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.estimators.physical import physical_estimate
from qcpp.estimators.qdk_reading import QdkReading, asap_rotation_depth, logical_and_qasm, qdk_read
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.lowering.qasm import to_qasm3
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario

SCENARIOS = ((3, 3, 1), (3, 3, 2), (4, 4, 2))
TARGETS = ("nisq", "ft")
ANGLES = {"gamma_0": 0.3, "beta_0": 0.7}


@dataclass(frozen=True)
class Terms:
    """The per-term figures of one estimate."""

    qubits: int
    logical_qubits: int
    t_states: int
    rotations: int
    rotation_depth: int
    measurements: int
    toffolis: int
    explicit_t: int
    cycles: int
    code_distance: int
    t_factories: int
    physical_qubits: int
    runtime_us: float


TERM_NAMES = {
    "qubits": "logical qubits (circuit)",
    "logical_qubits": "logical qubits with layout overhead",
    "t_states": "T states",
    "rotations": "rotations",
    "rotation_depth": "rotation depth",
    "measurements": "measurements",
    "toffolis": "CCZ + CCiX",
    "explicit_t": "explicit T gates",
    "cycles": "logical depth (cycles)",
    "code_distance": "code distance",
    "t_factories": "T factories",
    "physical_qubits": "physical qubits",
    "runtime_us": "runtime (us)",
}


def _layout_qubits(q: int) -> int:
    """The estimator's PSSPC layout: 2Q + ceil(sqrt(8Q)) + 1 (Beverland et al. 2022)."""
    import math

    return 2 * q + math.ceil(math.sqrt(8 * q)) + 1


def _terms_of_reading(r: QdkReading) -> Terms:
    c, ph = r.counts, r.physical
    return Terms(
        c.num_qubits, r.logical_qubits, ph.t_states, c.rotation_count, c.rotation_depth, c.measurement_count,
        c.ccz_count + c.ccix_count, c.t_count, ph.logical_depth, ph.code_distance, ph.t_factories,
        ph.physical_qubits, ph.runtime_s * 1e6,
    )  # fmt: skip


def run(rows: int, cols: int, robots: int, target: str) -> tuple[Terms, Terms, Terms, Terms, dict[str, int]]:
    """(qcpp, QDK file, QDK logical-AND, QDK lowered file) terms and the rotation-depth check of one circuit."""
    plan = PlanOptions(target=target)  # type: ignore[arg-type]
    est = estimate_point(Point(rows, cols, robots, 1), EstimateOptions(plan=plan, depth="exact", physical=True))
    counts, ph = est.logical_counts, est.physical
    assert ph is not None
    ours = Terms(
        counts.num_qubits, _layout_qubits(counts.num_qubits), ph.t_states, counts.rotation_count,
        counts.rotation_depth, counts.measurement_count, counts.ccz_count + counts.ccix_count, counts.t_count,
        ph.logical_depth, ph.code_distance, ph.t_factories, ph.physical_qubits, ph.runtime_s * 1e6,
    )  # fmt: skip
    circuit = compile_scenario(default_scenario(rows, cols, robots), 1, plan, bindings=ANGLES).circuit
    as_file = qdk_read(to_qasm3(circuit))
    scenario = default_scenario(rows, cols, robots)
    lowered_file = qdk_read(to_qasm3(compile_scenario(scenario, 1, plan, lowered=True, bindings=ANGLES).circuit))
    logical_and = qdk_read(logical_and_qasm(lower(circuit, basis=LOGICAL_BASIS)))
    swapped = physical_estimate(replace(counts, rotation_depth=logical_and.counts.rotation_depth))
    check = {
        "qdk_file": as_file.counts.rotation_depth,
        "python_rule_file": asap_rotation_depth(lower(circuit, peephole=False).gates, circuit.num_qubits),
        "qcpp": counts.rotation_depth,
        "swapped_qubits": swapped.physical_qubits,
        "swapped_runtime_ns": round(swapped.runtime_s * 1e9),
        "qdk_la_qubits": logical_and.physical.physical_qubits,
        "qdk_la_runtime_ns": round(logical_and.physical.runtime_s * 1e9),
    }
    return ours, _terms_of_reading(as_file), _terms_of_reading(logical_and), _terms_of_reading(lowered_file), check


def _ratio(a: float, b: float) -> float:
    return 1.0 if a == b else (a / b if b else float("inf"))


def _span(values: list[float]) -> str:
    lo, hi = min(values), max(values)
    return f"{lo:.2f}" if f"{lo:.2f}" == f"{hi:.2f}" else f"{lo:.2f}..{hi:.2f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="3x3 / 1 robot only")
    args = parser.parse_args()
    scenarios = SCENARIOS[:1] if args.quick else SCENARIOS
    results = []
    for rows, cols, robots in scenarios:
        for target in TARGETS:
            label = f"{rows}x{cols}/{robots} {target}"
            results.append((label, *run(rows, cols, robots, target)))
            print(f"[{label} done]", file=sys.stderr, flush=True)

    print("| term | qcpp / QDK (logical-AND) | within 5% | qcpp / QDK (file, --bind) | qcpp / QDK (file, --lowered "
          "--bind) |")  # fmt: skip
    print("|---|---:|---|---:|---:|")
    for key, name in TERM_NAMES.items():
        la = [_ratio(getattr(o, key), getattr(q, key)) for _, o, _, q, _, _ in results]
        fl = [_ratio(getattr(o, key), getattr(f, key)) for _, o, f, _, _, _ in results]
        lw = [_ratio(getattr(o, key), getattr(w, key)) for _, o, _, _, w, _ in results]
        ok = "yes" if all(abs(r - 1) <= 0.05 for r in la) else "no"
        print(f"| {name} | {_span(la)} | {ok} | {_span(fl)} | {_span(lw)} |")

    print()
    cols = ("qubits", "t_states", "rotation_depth", "measurements", "toffolis", "explicit_t", "cycles",
            "code_distance", "t_factories", "physical_qubits", "runtime_us")  # fmt: skip
    print("| circuit | estimate | " + " | ".join(TERM_NAMES[c] for c in cols) + " |")
    print("|---|---|" + "---:|" * len(cols))
    for label, ours, as_file, logical_and, lowered_file, _ in results:
        readings = (("qcpp", ours), ("QDK, logical-AND", logical_and), ("QDK, file (--bind)", as_file),
                    ("QDK, file (--lowered --bind)", lowered_file))  # fmt: skip
        for who, t in readings:
            cells = [f"{getattr(t, c):,.0f}" if c == "runtime_us" else f"{getattr(t, c):,}" for c in cols]
            print(f"| {label} | {who} | " + " | ".join(cells) + " |")

    print()
    print("| circuit | qcpp counts, QDK's rotation depth: physical qubits | QDK (logical-AND) | "
          "runtime (us) | QDK (logical-AND) |")  # fmt: skip
    print("|---|---:|---:|---:|---:|")
    for label, *_, check in results:
        print(f"| {label} | {check['swapped_qubits']:,} | {check['qdk_la_qubits']:,} | "
              f"{check['swapped_runtime_ns'] / 1e3:,.1f} | {check['qdk_la_runtime_ns'] / 1e3:,.1f} |")  # fmt: skip

    print()
    print("| circuit | rotation depth: QDK on the file | its rule in Python, same gates | qcpp |")
    print("|---|---:|---:|---:|")
    for label, *_, check in results:
        print(f"| {label} | {check['qdk_file']} | {check['python_rule_file']} | {check['qcpp']} |")


if __name__ == "__main__":
    main()
