"""Numbers behind docs/paper-notes.md ("Resource estimates: ...") and docs/resource-estimates.md.

Run: ``python benchmarks/paper_comparison.py``. Prints,
for a few grids at p = 1, our exact counts of the lowered circuit next to the paper's estimate, split into the
phase separator and the mixer, plus the per-partial-mixer table of our construction and the multi-controlled-X
decomposition sizes. Every number in the two documents comes from this output.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass

from qcpp.estimators.counts import ResourceCount, count
from qcpp.estimators.fault_tolerant import FaultTolerantEstimate, fault_tolerant_from_cost
from qcpp.estimators.paper import paper_estimate, paper_partial_mixer, toffoli_decomposition
from qcpp.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer, mixer_work_need, partial_mixer
from qcpp.ir.angles import Angle
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.hamiltonian import ising_hamiltonian
from qcpp.problem.presets import default_scenario
from qcpp.problem.sbf import LocalPicture


def _partial_mixer_types() -> list[tuple[str, McxPartialMixer | ParityPartialMixer | None]]:
    """One partial mixer of robot 0 (top-left to bottom-right) per corner-class pattern (endpoints, interior
    corners, diagonal), with its local picture's label, from grids of sides 2 and 4 (every boundary class)."""
    seen: dict[tuple[int, int, bool], tuple[str, McxPartialMixer | ParityPartialMixer | None]] = {}
    for nr, nc in ((2, 2), (2, 4), (4, 2), (4, 4)):
        s = default_scenario(nr, nc, 2)
        rb = s.robots[0]
        for plaq in s.grid.plaquettes:
            label = LocalPicture.of(plaq.corners, rb.start, rb.goal, [len(o) for o in plaq.outer_edges]).label
            pattern = (label.count("E"), label.count("B"), label.endswith("D"))
            if pattern not in seen:
                seen[pattern] = (label, partial_mixer(s, 0, plaq, Angle.symbol("beta_0"), s.num_variables))
    return list(seen.values())


POINTS = [(3, 3, 1), (3, 3, 2), (4, 4, 2), (6, 6, 3), (8, 8, 4), (10, 10, 4)]


@dataclass(frozen=True)
class _Point:
    rows: int
    cols: int
    robots: int


@dataclass(frozen=True)
class _Result:
    point: _Point
    counts: ResourceCount
    fault_tolerant: FaultTolerantEstimate


def _measure(rows: int, cols: int, robots: int) -> _Result:
    circ = qaoa_circuit(default_scenario(rows, cols, robots), 1)
    ft = fault_tolerant_from_cost(Cost.count(lower(circ, LOGICAL_BASIS).gates))
    return _Result(_Point(rows, cols, robots), count(lower(circ)), ft)


def main(argv: list[str]) -> int:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args(argv)  # --help, and no other argument
    results = [_measure(r, c, k) for r, c, k in POINTS]
    print("## Totals at p = 1 (ours: exact, lowered; paper: its formulas, literal reading)")
    print("| grid | robots | qubits ours / paper | CNOT ours / paper | ratio | single-qubit ours / paper | ratio |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for res in results:
        pt, c = res.point, res.counts
        est = paper_estimate(pt.rows, pt.cols, pt.robots, 1)
        print(
            f"| {pt.rows}x{pt.cols} | {pt.robots} | {c.qubits} / {est.qubits} | {c.cx:,} / {est.cx:,} | "
            f"{c.cx / est.cx:.3f} | {c.single_qubit:,} / {est.single_qubit:,} | "
            f"{c.single_qubit / est.single_qubit:.3f} |"
        )
    print()
    print("## Phase separator (one layer)")
    print("| grid | robots | re | re(re+1) paper CNOT | nonzero ZZ | our CNOT (feasible form) | pairs i<j | ZZ share |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for res in results:
        pt = res.point
        re = pt.robots * (pt.rows * (pt.cols - 1) + pt.cols * (pt.rows - 1))
        zz = ising_hamiltonian(default_scenario(pt.rows, pt.cols, pt.robots)).num_quadratic_terms(1e-12)
        phase = res.counts.sections["phase_0"]
        pairs = re * (re - 1) // 2
        print(
            f"| {pt.rows}x{pt.cols} | {pt.robots} | {re} | {re * (re + 1):,} | {zz:,} | {phase.cx:,} | "
            f"{pairs:,} | {zz / pairs:.3f} |"
        )
    print()
    print("## Mixer (one layer)")
    print("| grid | robots | partial mixers | paper CNOT | our CNOT | our Toffolis | mean Toffolis per PM (paper 88) |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for res in results:
        pt = res.point
        est = paper_estimate(pt.rows, pt.cols, pt.robots, 1)
        mixer = res.counts.sections["mixer_0"]
        n_pm = est.partial_mixers
        print(
            f"| {pt.rows}x{pt.cols} | {pt.robots} | {n_pm} | {est.mixer_cx:,} | {mixer.cx:,} | "
            f"{res.fault_tolerant.toffoli:,} | {res.fault_tolerant.toffoli / n_pm:.1f} |"
        )
    print()
    print("## One partial mixer by type (ours, compiled alone) vs the paper's")
    pm = paper_partial_mixer()
    print(f"paper: {2 * pm.toffolis} Toffolis (44 computed twice), {pm.cx} CNOT, {pm.single_qubit} single-qubit")
    print("| type | Toffolis | cx | x | h | t+tdg | rz | logic temps | work |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for key, m in _partial_mixer_types():
        o, logical = (m.cost(), m.logical_cost()) if m is not None else (Cost(), Cost())
        toffoli = logical["and"] + logical["and_dg"] + logical["ccx"]
        temps, work = (m.num_temps, mixer_work_need([m])) if m is not None else (0, 0)
        print(
            f"| {key} | {toffoli} | {o['cx']} | {o['x']} | {o['h']} | {o['t'] + o['tdg']} | {o['rz']} | "
            f"{temps} | {work} |"
        )
    print()
    print("## Depth (ours; the paper gives none) and the fault-tolerant view (epsilon = 1e-3)")
    print("| grid | robots | depth | phase depth | mixer depth | 2q depth | T (lowered) | T (logical AND) | "
          "rotations | T per rotation |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for res in results:
        pt, c, ft = res.point, res.counts, res.fault_tolerant
        print(
            f"| {pt.rows}x{pt.cols} | {pt.robots} | {c.depth:,} | {c.sections['phase_0'].depth:,} | "
            f"{c.sections['mixer_0'].depth:,} | {c.two_qubit_depth:,} | {c.t:,} | {ft.t_logic:,} | "
            f"{ft.rotations:,} | {ft.t_per_rotation} |"
        )
    print()
    print("## Multi-controlled X with l controls: Toffolis")
    print("| l | ours (clean v-chain, 2l-3) | paper (4(l-2), Barenco Lemma 7.2) |")
    print("|---:|---:|---:|")
    for l_controls in range(3, 7):
        print(f"| {l_controls} | {2 * l_controls - 3} | {toffoli_decomposition(l_controls + 1)} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
