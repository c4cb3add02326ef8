"""Write measured counts of a compiled circuit as JSON, the file ``qcpp decode --counts`` reads.

Hardware stand-in for the examples: the scenario's QAOA circuit at given angles (``--bind``) or its trained ones
(``qcpp.train_qaoa``), with
the data qubits measured (``Compiled.to_qasm(measure=True)``, what ``qcpp compile --qasm F --measure`` writes),
sampled without noise by Qiskit's seeded ``StatevectorSampler``; the counts of the ``meas`` register are written as
``{bitstring: shots}`` (clbit 0 rightmost), keys sorted.

Usage::

    python scripts/sample_counts.py examples/paper_3x3.toml examples/counts/3x3.json --bind gamma_0=0.2 \
        beta_0=1.4 --shots 1000 --seed 7
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import qcpp


def sample_counts(
    scenario: qcpp.Scenario, p: int, shots: int, seed: int, bind: dict[str, float] | None = None
) -> dict[str, int]:
    """Counts of the ``meas`` register of the measured circuit at angles ``bind`` (``None``: trained), sampled
    with ``seed``."""
    from qiskit import QuantumCircuit
    from qiskit.primitives import StatevectorSampler

    bindings = qcpp.train_qaoa(scenario, p=p).bindings if bind is None else bind
    compiled = qcpp.compile(scenario, p=p, lowered=True, bind=bindings)
    circuit = QuantumCircuit.from_qasm_str(compiled.to_qasm(2, measure=True))
    result = StatevectorSampler(seed=seed).run([circuit], shots=shots).result()
    return dict(sorted(result[0].data.meas.get_counts().items()))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", type=Path)
    parser.add_argument("out", type=Path)
    parser.add_argument("-p", type=int, default=1)
    parser.add_argument("--shots", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--bind", nargs="*", metavar="NAME=VALUE", help="angles (default: trained)")
    args = parser.parse_args()
    bind = None if args.bind is None else {k: float(v) for k, v in (b.split("=", 1) for b in args.bind)}
    counts = sample_counts(qcpp.load_scenario(args.scenario), args.p, args.shots, args.seed, bind)
    args.out.write_text(json.dumps(counts, indent=0) + "\n")
    print(f"{sum(counts.values())} shots, {len(counts)} distinct outcomes -> {args.out}")


if __name__ == "__main__":
    main()
