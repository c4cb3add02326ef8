"""Running a compiled circuit on hardware, without hardware: ``measure=True`` exports, IBM's ``sx`` and the layouts in
``to_qiskit()``, and ``decode_counts`` on sampled counts of the routed circuit."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest
from qiskit import QuantumCircuit, QuantumRegister, qasm2, qasm3, transpile
from qiskit.primitives import StatevectorSampler
from qiskit.quantum_info import Operator, Statevector

import qcpp
from qcpp.lowering.qasm_profiles import PROFILES, iter_qasm_profile
from qcpp.problem.cost import cost_parts
from qcpp.problem.paths import enumerate_paths
from qcpp.routing.native import esp, one_qubit_name
from qcpp.routing.routed_circuit import coupling_map
from qcpp.training.evaluate import feasible_assignments

ANGLES = {"gamma_0": 0.5, "beta_0": 1.1}
SHOTS = 20_000

pytestmark = pytest.mark.xdist_group("hardware_run")  # one worker compiles the module's circuits (tests/conftest.py)


@pytest.fixture(scope="module")
def fez() -> qcpp.Compiled:
    """One robot on 2x3 routed onto ibm_fez with bound angles (its routing moves qubits: final != initial)."""
    c = qcpp.compile(qcpp.grid_scenario(2, 3, robots=1), device="ibm_fez", bind=ANGLES)
    assert c.final_layout != c.initial_layout
    return c


@pytest.fixture(scope="module")
def fez_zero() -> qcpp.Compiled:
    """The same compile with ``zero_start=True``: a routing simplified for the all-|0> start wins (far fewer CZ)."""
    c = qcpp.compile(qcpp.grid_scenario(2, 3, robots=1), device="ibm_fez", bind=ANGLES, zero_start=True)
    assert c.zero_start and not c.equal_on_every_input and "from |0>" in c.to_dict()["routed"]["chosen"]
    return c


def _compact(qc: QuantumCircuit) -> tuple[QuantumCircuit, dict[int, int]]:
    """``qc`` on the qubits its instructions touch only (same order, same classical registers, same global phase),
    and physical qubit -> its index there."""
    used = sorted({qc.find_bit(q).index for inst in qc.data for q in inst.qubits})
    index = {p: i for i, p in enumerate(used)}
    small = QuantumCircuit(QuantumRegister(len(used), "q"), *qc.cregs, global_phase=qc.global_phase)
    for inst in qc.data:
        small.append(inst.operation, [small.qubits[index[qc.find_bit(q).index]] for q in inst.qubits], inst.clbits)
    return small, index


# --- measure=False: what it was ---------------------------------------------------------------------------------
@pytest.mark.parametrize("device", [None, "grid:3x3"])
@pytest.mark.parametrize("lowered", [False, True])
def test_measure_false_is_the_writers_text_and_measure_true_only_adds_the_register(
    device: str | None, lowered: bool
) -> None:
    s = qcpp.grid_scenario(2, 2, robots=1)
    c = qcpp.compile(s, device=device, lowered=lowered, bind={"gamma_0": 0.3, "beta_0": 0.7})
    for version, profile in [(2, "default"), *((3, p) for p in PROFILES)]:
        before = "".join(iter_qasm_profile(c.circuit, version, profile))  # the text to_qasm wrote before the option
        assert c.to_qasm(version, profile) == before
        assert c.to_qasm(version, profile, measure=False) == before
        measured = c.to_qasm(version, profile, measure=True)
        added = [line for line in measured.splitlines() if line not in before.splitlines()]
        n = s.num_variables
        assert len(added) == n + 2  # the declaration, "// measure", one line per data qubit
        assert measured.startswith(before.split("\n// section", 1)[0])
    qc = c.to_qiskit()
    assert qc.num_clbits == 0
    assert dict(sorted(qc.count_ops().items())) == c.counts()  # no sx on the grid family: unchanged names


def test_measure_true_loads_with_the_data_register_on_the_final_layout(fez: qcpp.Compiled) -> None:
    n = fez.scenario.num_variables
    assert fez.measured_qubits == tuple(fez.final_layout[:n])
    qc = fez.to_qiskit(measure=True)
    assert [r.name for r in qc.cregs] == ["meas"] and qc.num_clbits == n
    measures = [(qc.find_bit(i.qubits[0]).index, qc.find_bit(i.clbits[0]).index)
                for i in qc.data if i.operation.name == "measure"]  # fmt: skip
    assert measures == [(fez.final_layout[i], i) for i in range(n)]
    two = qasm2.loads(fez.to_qasm(2, measure=True))
    assert two.num_clbits == n and two.count_ops()["measure"] == n
    for profile in PROFILES:  # every OpenQASM 3 profile writes the same measurement statements
        assert fez.to_qasm(3, profile, measure=True).endswith(fez.to_qasm(3, measure=True).split("// measure\n")[1])


def test_measure_must_be_a_flag(fez: qcpp.Compiled) -> None:
    with pytest.raises(qcpp.OptionError, match="measure"):
        fez.to_qasm(measure=1)  # type: ignore[arg-type]


# --- IBM's basis and layouts in to_qiskit -------------------------------------------------------------------------
def test_ibm_to_qiskit_writes_sx_with_the_same_unitary_and_the_counts_esp_charges(fez: qcpp.Compiled) -> None:
    qc = fez.to_qiskit()
    ops = dict(qc.count_ops())
    assert "rx" not in ops and set(ops) <= {"cz", "rz", "sx", "x"}
    charged = Counter(g[0] if len(g[1]) == 2 else one_qubit_name(fez.device, g) for g in fez.circuit.gates)
    assert ops == dict(charged)  # the gates esp() multiplies, name for name
    assert 0 < esp(fez._routed) == fez.esp  # type: ignore[arg-type]
    as_written = qasm3.loads(fez.to_qasm(3))  # rx(pi/2) as the IR writes it
    a, index_a = _compact(qc)
    b, index_b = _compact(as_written)
    assert index_a == index_b and a.num_qubits <= 12
    assert np.allclose(Operator(a).data, Operator(b).data, atol=1e-10)  # global phase included
    # in the target's basis as is: a translation to it at level 0 on the device's couplings changes nothing
    t = transpile(qc, basis_gates=["cz", "rz", "sx", "x"], coupling_map=coupling_map(fez.device), optimization_level=0)
    assert dict(t.count_ops()) == ops


def test_ibm_to_qiskit_carries_the_layouts(fez: qcpp.Compiled) -> None:
    qc = fez.to_qiskit(measure=True)
    assert qc.layout is not None
    assert qc.layout.initial_index_layout(filter_ancillas=True) == fez.initial_layout
    assert qc.layout.final_index_layout() == fez.final_layout
    assert sorted(qc.layout.routing_permutation()) == list(range(qc.num_qubits))


def test_lowered_routed_keeps_cx_and_rx() -> None:
    c = qcpp.compile(qcpp.grid_scenario(2, 2, robots=1), device="ibm_fez", lowered=True, bind=ANGLES)
    qc = c.to_qiskit()
    assert "sx" not in qc.count_ops() and qc.layout.final_index_layout() == c.final_layout


# --- end to end: sample the routed circuit, decode the paths ---------------------------------------------------
def test_sampled_routed_circuit_decodes_to_feasible_paths_at_the_ideal_p_optimum(fez: qcpp.Compiled) -> None:
    _decodes_at_the_ideal_p_optimum(fez)


def test_a_zero_start_compile_decodes_to_feasible_paths_at_the_ideal_p_optimum(fez_zero: qcpp.Compiled) -> None:
    """Run as it is, from the device's all-|0> start, the circuit simplified for that start samples what the
    logical circuit does."""
    _decodes_at_the_ideal_p_optimum(fez_zero)


def _decodes_at_the_ideal_p_optimum(fez: qcpp.Compiled) -> None:
    """The routed circuit's data register has the subspace simulator's P(optimum), exactly and sampled (decoded)."""
    s = fez.scenario
    ideal = qcpp.simulate_qaoa(s, 1, angles=[ANGLES["gamma_0"], ANGLES["beta_0"]]).p_optimum
    assert 0.05 < ideal < 0.95
    # exactly: the routed circuit's data register, read at the final layout, has the subspace simulator's P(optimum)
    small, index = _compact(fez.to_qiskit())
    probs = Statevector(small).probabilities([index[fez.final_layout[i]] for i in range(s.num_variables)])
    indices, optimal = feasible_assignments(s)
    assert math.isclose(float(probs[indices[optimal]].sum()), ideal, abs_tol=1e-9)
    assert math.isclose(float(probs[indices].sum()), 1.0, abs_tol=1e-9)  # nothing outside the feasible paths
    # sampled, as a sampler on hardware returns the counts
    measured, _ = _compact(fez.to_qiskit(measure=True))
    counts = StatevectorSampler(seed=20240611).run([measured], shots=SHOTS).result()[0].data.meas.get_counts()
    decoded = fez.decode(counts, optimum=qcpp.solve(s))
    assert decoded.shots == SHOTS and decoded.feasible_share == 1.0
    assert all(o.feasible and o.nodes[0] is not None for o in decoded.outcomes)
    assert {o.paths[0] for o in decoded.outcomes} <= set(enumerate_paths(s, 0))
    stderr = math.sqrt(ideal * (1 - ideal) / SHOTS)
    assert abs(decoded.p_optimum - ideal) <= 5 * stderr
    assert decoded.best is not None and decoded.best_cost == qcpp.solve(s).cost.total and decoded.best.optimal


# --- zero_start: routings simplified for the all-|0> start, only when asked ----------------------------------------
@pytest.mark.parametrize("optimize_for", ["esp", "twoq"])
def test_zero_start_off_offers_only_unitary_keeping_candidates_and_on_offers_and_chooses_cheaper_ones(
    optimize_for: str,
) -> None:
    """Off (the default), no candidate is simplified for the all-|0> start, by either figure; on, they are offered
    and one is written: fewer CZ than every unitary-keeping candidate, and the same state from |0...0> as the
    logical circuit (statevector, up to global phase, each logical qubit at its final physical qubit)."""
    s = qcpp.grid_scenario(2, 2, robots=1)
    off = qcpp.compile(s, device="ibm_fez", bind=ANGLES, optimize_for=optimize_for)
    assert not off.zero_start and off.equal_on_every_input
    assert off.to_dict()["routed"]["zero_start"] is False and off.to_dict()["routed"]["equal_on_every_input"]
    assert not any("from |0>" in c["name"] for c in off.to_dict()["routed"]["candidates"])
    on = qcpp.compile(s, device="ibm_fez", bind=ANGLES, optimize_for=optimize_for, zero_start=True)
    routed = on.to_dict()["routed"]
    assert on.zero_start and routed["zero_start"] is True
    assert "from |0>" in routed["chosen"] and not on.equal_on_every_input, routed["chosen"]
    keeping = [c["two_qubit"] for c in routed["candidates"] if "from |0>" not in c["name"]]
    assert sorted(keeping) == sorted(c["two_qubit"] for c in off.to_dict()["routed"]["candidates"])
    assert routed["two_qubit"] < min(keeping)
    note = "// simplified for the all-|0> start"  # the file says where it is valid, in every version and profile
    assert all(on.to_qasm(v, measure=True).splitlines()[1].startswith(note) for v in (2, 3))
    assert on.to_qasm(3, profile="braket").splitlines()[1].startswith(note)
    assert not any(note in off.to_qasm(v) for v in (2, 3))
    # the state from |0...0>: the logical circuit on the final physical qubits, |0> on the others
    small, index = _compact(on.to_qiskit())
    logical = qcpp.compile(s, lowered=True, bind=ANGLES).to_qiskit()
    expected = QuantumCircuit(small.num_qubits)
    expected.compose(logical, [index[p] for p in on.final_layout], inplace=True)
    fidelity = abs(np.vdot(Statevector(expected).data, Statevector(small).data))
    assert math.isclose(fidelity, 1.0, abs_tol=1e-9)


# --- the decoder -----------------------------------------------------------------------------------------------
def test_decode_counts_reads_paths_feasibility_and_cost_per_robot() -> None:
    s = qcpp.grid_scenario(2, 3, robots=2)
    indices, optimal = feasible_assignments(s)
    n = s.num_variables
    good, other = int(indices[optimal][0]), int(indices[~optimal][0])
    counts = {format(good, f"0{n}b"): 5, hex(other): 3, 1: 2}  # bitstring, hexadecimal and integer keys
    d = qcpp.decode_counts(s, counts, optimum=qcpp.solve(s).cost.total)
    assert d.shots == 10 and math.isclose(d.feasible_share, 0.8) and math.isclose(d.p_optimum, 0.5)
    first, second, bad = d.outcomes
    assert (first.shots, first.optimal, second.optimal, bad.feasible, bad.optimal) == (5, True, False, False, False)
    assert first.cost == cost_parts(s, first.paths).total and d.best == first
    for o in (first, second):
        for r, nodes in enumerate(o.nodes):
            assert nodes is not None and nodes[0] == s.robots[r].start and nodes[-1] == s.robots[r].goal
            assert len(o.edges[r]) == len(nodes) - 1
    assert bad.nodes[1] is None and bad.edges[1] == () and bad.edges[0] == (s.grid.edges[0],)
    assert d.to_dict()["outcomes"][0]["nodes"][0][0] == list(s.robots[0].start)
    assert qcpp.decode_counts(s, counts).p_optimum is None



def test_an_outcome_with_no_shots_is_not_an_outcome() -> None:
    """A counts file may list outcomes at 0 shots (a histogram over every bitstring): none was measured, so none is
    an outcome, nor the best feasible one (an optimal path at 0 shots was reported as the best measured)."""
    s = qcpp.grid_scenario(2, 3, robots=2)
    indices, optimal = feasible_assignments(s)
    n = s.num_variables
    good, other = int(indices[optimal][0]), int(indices[~optimal][0])
    d = qcpp.decode_counts(s, {format(good, f"0{n}b"): 0, format(other, f"0{n}b"): 4}, optimum=qcpp.solve(s))
    assert [(o.bits, o.shots) for o in d.outcomes] == [(format(other, f"0{n}b"), 4)]
    assert d.best is not None and d.best.shots == 4 and d.p_optimum == 0 and d.best_cost > qcpp.solve(s).cost.total

class _BitArrayLike:  # what SamplerV2's result[0].data.meas offers
    def get_counts(self) -> dict[str, int]:
        return {"0101": 2}


@pytest.mark.parametrize(
    ("counts", "needle"),
    [({"010": 1}, "not a bitstring of the 4 data bits"), ({"0101 1": 1}, "not a bitstring"), ({"0101": -1}, "shots"),
     ({}, "no shots"), ({16: 1}, "outside"), ([1, 2], "mapping")],
)  # fmt: skip
def test_decode_counts_refuses_bad_counts_in_one_line(counts: object, needle: str) -> None:
    s = qcpp.grid_scenario(2, 2, robots=1)
    assert qcpp.decode_counts(s, _BitArrayLike()).feasible_share == 1.0
    with pytest.raises(qcpp.OptionError, match=needle):
        qcpp.decode_counts(s, counts)
    with pytest.raises(qcpp.OptionError, match="optimum"):
        qcpp.decode_counts(s, {"0101": 1}, optimum="low")
