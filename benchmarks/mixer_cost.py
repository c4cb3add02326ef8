"""Mixer and circuit CNOTs per QAOA layer: qcpp 0.1's construction, ours (nisq and ft), and Qiskit O3, in one run.

Run: ``python benchmarks/mixer_cost.py [--quick] [--no-qiskit]``.

Columns (all CX per layer, p = 1, default scenarios and a few with obstacles / interior endpoints):

* ``0.1 mixer``: qcpp 0.1's mixer, recomputed from its construction: the exact rule as the plain-edge network
  (:func:`qcpp.problem.sbf.direct_exact_logic`), each step a multi-controlled X lowered as 0.1 did (a v-chain of
  ``2k - 3`` full 6-CX Toffolis for ``k >= 3`` controls, 6 CX for two, 1 for one), mirrored, plus the controlled
  XXXX rotation (8 CX);
* ``mixer nisq`` / ``mixer ft``: this version's mixer layer as its plan reports it (partial mixers fused at their
  boundaries, :mod:`qcpp.gadgets.junction`; a test proves every piece's cost equal to its lowered gate
  count), and their ratio to 0.1;
* ``qiskit O3 paper-structured``: Qiskit's transpiler at optimization level 3 on the paper-structured logical
  circuit of the same scenario: initial state, the paper's phase separator (RZ/RZZ of the Ising Hamiltonian),
  and per partial mixer one ``MCXGate`` per step of the same exact rule (plain-edge network) into ancillas, the
  controlled XXXX rotation, the mirror; as many qubits as our circuit, so Qiskit's MCX synthesis sees idle clean
  ancillas;
* ``ours``: our lowered circuit's CX (read off the emitted circuit), and ``ours / qiskit``;
* ``qiskit O3 on ours``: Qiskit O3 applied to our own high-level circuit (ANDs given to Qiskit as its ``RCCXGate``
  plus ``sdg``, the exact gadget we use): it never beats our lowering (``tests/compiler/junction_test.py``).
"""

from __future__ import annotations

import argparse
import sys
import time

from qcpp.gadgets.partial_mixer import partial_mixer
from qcpp.ir.circuit import Circuit
from qcpp.lowering.passes import lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_circuit, qaoa_plan
from qcpp.problem.grid import Grid
from qcpp.problem.presets import default_scenario
from qcpp.problem.sbf import direct_exact_logic
from qcpp.problem.scenario import Objective, Robot, Scenario

DEFAULT = ((3, 3, 1), (4, 4, 2), (5, 5, 2), (6, 6, 3), (8, 8, 3))


def extra_scenarios() -> list[tuple[str, Scenario]]:
    g = Grid(5, 5)
    return [
        ("5x5/2 obst soft", Scenario(g, (Robot((0, 0), (4, 4)), Robot((0, 4), (4, 0))), ((1, 3), (2, 2)))),
        (
            "5x5/2 obst hard",
            Scenario(g, (Robot((0, 0), (4, 4)), Robot((0, 4), (4, 0))), ((1, 3), (2, 2)), Objective(obstacles="hard")),
        ),
        ("5x5/2 interior", Scenario(g, (Robot((1, 1), (3, 4)), Robot((2, 0), (0, 3))))),
        ("6x6/1 interior", Scenario(Grid(6, 6), (Robot((2, 2), (4, 5)),))),
    ]


def cx_01(k: int) -> int:
    """CX of 0.1's lowering of a k-control X (v-chain of full Toffolis)."""
    return {0: 0, 1: 1, 2: 6}.get(k, 6 * (2 * k - 3))


def mixer_01(s: Scenario) -> int:
    total = 0
    for r in range(s.num_robots):
        for q in s.grid.plaquettes:
            lg = direct_exact_logic(s, r, q)
            if lg.never:
                continue
            total += 2 * sum(cx_01(len(st.literals)) for st in lg.steps) + 8
    return total


def mixer_new(s: Scenario, target: str) -> int:
    """One layer's mixer CX as the plan reports it: the partial mixers fused at their boundaries."""
    return qaoa_plan(s, 1, PlanOptions(target=target)).cost_by_part()["mixer"].cx  # type: ignore[arg-type]


# --- Qiskit side --------------------------------------------------------------------------------------------
def to_qiskit(circuit: Circuit, bindings: dict[str, float]):  # type: ignore[no-untyped-def]
    """Our IR (bound) as a Qiskit circuit with Qiskit's own gates (MCXGate, RCCXGate, CRXGate, RZZGate, ...)."""
    from qiskit import QuantumCircuit
    from qiskit.circuit.library import MCXGate, RCCXGate

    c = circuit.bind(bindings)
    qc = QuantumCircuit(c.num_qubits)
    for name, qs, params, state in c.gates:
        ps = [float(p) for p in params]
        if name in ("x", "h", "t", "tdg", "s", "sdg"):
            getattr(qc, name)(qs[0])
        elif name in ("rz", "rx", "ry"):
            getattr(qc, name)(ps[0], qs[0])
        elif name in ("cx", "cz"):
            getattr(qc, name)(*qs)
        elif name in ("crz", "cry", "crx", "rzz"):
            getattr(qc, name)(ps[0], *qs)
        elif name == "ccx":
            qc.ccx(*qs)
        elif name == "mcx":
            qc.append(MCXGate(len(qs) - 1, ctrl_state=state[::-1]), list(qs))
        elif name in ("and", "and_dg"):
            flips = [q for q, b in zip(qs[:2], state or "11", strict=True) if b == "0"]
            for q in flips:
                qc.x(q)
            if name == "and":
                qc.append(RCCXGate(), list(qs))
                qc.sdg(qs[2])
            else:
                qc.s(qs[2])
                qc.append(RCCXGate().inverse(), list(qs))
            for q in flips:
                qc.x(q)
        elif name == "csbf":
            k, a, b, cc, d = qs
            for q in (a, b, cc, d):
                qc.h(q)
            qc.cx(a, b)
            qc.cx(b, cc)
            qc.cx(cc, d)
            qc.crz(ps[0], k, d)
            qc.cx(cc, d)
            qc.cx(b, cc)
            qc.cx(a, b)
            for q in (a, b, cc, d):
                qc.h(q)
        else:
            raise ValueError(f"no Qiskit form for {name}")
    return qc


def paper_structured(s: Scenario) -> Circuit:
    """The paper's structure with our exact rule: initial state, the RZ/RZZ phase separator of the Ising
    Hamiltonian, and the mixer as MCX steps of the plain-edge exact rule; as many ancillas as our circuit has."""
    from qcpp.ir.angles import Angle
    from qcpp.ir.circuit import Register, Section
    from qcpp.ir.gates import csbf, mcx

    ours = qaoa_circuit(s, 1, PlanOptions(phase="whole-space"))
    n = s.num_variables
    width = 0
    sections = [sec for sec in ours.sections if not sec.name.startswith("mixer")]
    for r in range(s.num_robots):
        for q in s.grid.plaquettes:
            lg = direct_exact_logic(s, r, q)
            if lg.never:
                continue
            width = max(width, lg.num_temps)
            steps = []
            for st in lg.steps:
                controls = [n + lit.temp if lit.is_temp else s.variable_index(r, lit.signal) for lit in st.literals]
                state = "".join("1" if lit.value else "0" for lit in st.literals)
                steps.append(mcx(controls, n + st.target, state))
            data = [s.variable_index(r, e) for e in q.edges]
            rotation = csbf(Angle.symbol("beta_0"), n + lg.output, *data)
            sections.append(Section("mixer_0", (*steps, rotation, *reversed(steps))))
    width = max(width, qaoa_circuit(s, 1).register("logic").size)
    return Circuit([Register("data", n), Register("logic", width)], sections)


def qiskit_cx(circuit: Circuit) -> tuple[int, float]:
    from qiskit import transpile

    qc = to_qiskit(circuit, {"gamma_0": 0.3, "beta_0": 0.7})
    t = time.perf_counter()
    out = transpile(qc, basis_gates=["cx", "rz", "sx", "x", "h", "s", "sdg", "t", "tdg"], optimization_level=3)
    return int(out.count_ops().get("cx", 0)), time.perf_counter() - t


def corner_classes(s: Scenario, robot: int, q) -> str:  # type: ignore[no-untyped-def]
    rb, vmask = s.robots[robot], s.variable_mask
    out = ""
    for corner, outer in zip(q.corners, q.outer_edges, strict=True):
        if corner in (rb.start, rb.goal):
            out += "E"
        elif sum(1 for e in outer if (vmask >> e) & 1) == 2:
            out += "B"
        else:
            out += "N"
    diagonal = {rb.start, rb.goal} in ({q.corners[0], q.corners[2]}, {q.corners[1], q.corners[3]})
    return out + ("-D" if diagonal else "")


def kinds_table(cases: list[tuple[str, Scenario]]) -> None:
    """One row per partial-mixer kind met in ``cases``: corner classes (a b c d), cost per target."""
    seen: dict[object, tuple[str, object, object]] = {}
    for _, s in cases:
        for r in range(s.num_robots):
            for q in s.grid.plaquettes:
                m = partial_mixer(s, r, q, 0.5, s.num_variables, "exact", "nisq")
                f = partial_mixer(s, r, q, 0.5, s.num_variables, "exact", "ft")
                if m is not None and m.kind not in seen:
                    seen[m.kind] = (corner_classes(s, r, q), m, f)
    print("\npartial-mixer kinds (corner classes a b c d: E endpoint, B two variable outer edges, N neither;")
    print("-D: start and goal on the diagonal); lowered cost of one partial mixer")
    print(
        f"{'kind':<8} {'nisq cx':>7} {'rz':>3} {'t+tdg':>5} {'temps':>5}   "
        f"{'ft cx':>5} {'rz':>3} {'ANDs':>4} {'temps':>5}"
    )
    for label, m, f in sorted(seen.values(), key=lambda v: (v[1].cost().cx, v[0])):  # type: ignore[attr-defined]
        mc, fc, fl = m.cost(), f.cost(), f.logical_cost()  # type: ignore[attr-defined]
        print(
            f"{label:<8} {mc.cx:>7} {mc.rotations:>3} {mc.t:>5} {m.num_temps:>5}   "  # type: ignore[attr-defined]
            f"{fc.cx:>5} {fc.rotations:>3} {fl['and']:>4} {f.num_temps:>5}"  # type: ignore[attr-defined]
        )


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="three scenarios only")
    parser.add_argument("--no-qiskit", action="store_true", help="without the Qiskit columns")
    args = parser.parse_args(argv)
    quick = args.quick
    with_qiskit = not args.no_qiskit
    cases: list[tuple[str, Scenario]] = [(f"{r}x{c}/{n}", default_scenario(r, c, n)) for r, c, n in DEFAULT]
    cases += extra_scenarios()
    if quick:
        cases = cases[:2] + cases[-2:-1]
    head = f"{'scenario':<16} {'0.1 mixer':>9} {'mixer nisq':>10} {'ratio':>6} {'mixer ft':>8} {'ratio':>6}"
    if with_qiskit:
        head += f" {'qiskit O3 paper-str.':>20} {'ours':>7} {'ours/qk':>7} {'qiskit O3 on ours':>17} {'qk s':>6}"
    print("CX per layer (p = 1); ratios are ours over 0.1's mixer; qiskit columns: whole circuit")
    print(head)
    for label, s in cases:
        old = mixer_01(s)
        nisq, ft = mixer_new(s, "nisq"), mixer_new(s, "ft")
        row = f"{label:<16} {old:>9,} {nisq:>10,} {nisq / old:>6.3f} {ft:>8,} {ft / old:>6.3f}"
        if with_qiskit:
            peer, t1 = qiskit_cx(paper_structured(s))
            high = qaoa_circuit(s, 1)
            ours = sum(1 for g in lower(high).gates if g[0] == "cx")
            assert ours == qaoa_plan(s, 1).cost().cx
            peer_ours, t2 = qiskit_cx(high)
            row += f" {peer:>20,} {ours:>7,} {ours / peer:>7.3f} {peer_ours:>17,} {t1 + t2:>6.1f}"
        print(row, flush=True)
    kinds_table(cases)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
