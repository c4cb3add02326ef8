"""Routed == unrouted up to the reported layouts, proven by MQT QCEC on circuits too wide for a statevector.

The routed circuit is relabelled so that physical qubit ``initial_layout[i]`` is wire ``i`` and followed by a
CX network that moves every logical qubit from its final position back to wire ``i``; QCEC then compares it
with the unrouted circuit on every input whose ancillas and free qubits are |0>.
"""

from __future__ import annotations

import dataclasses

import pytest

from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cx, rz
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.problem.presets import default_scenario
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.routed_circuit import RoutedCircuit
from qcpp.simulate.equivalence import check_equivalence
from tests.compiler.short_search import SHORT_SEARCH

BIND = {"gamma_0": 0.3, "beta_0": 0.7}


def aligned(routed: RoutedCircuit, n: int) -> Circuit:
    """The routed circuit on wires ``0..n-1`` = logical qubits at the start and (after the CX network) the end."""
    big = routed.device.num_qubits
    wire = {p: i for i, p in enumerate(routed.initial_layout)}
    wire.update({p: n + j for j, p in enumerate(p for p in range(big) if p not in wire)})
    gates = [Gate(g[0], tuple(wire[q] for q in g[1]), g[2], g[3]) for g in routed.circuit.gates]
    pos = [wire[routed.final_layout[i]] for i in range(n)]  # wire holding logical i now
    holder = {w: i for i, w in enumerate(pos)}
    for i in range(n):
        a = pos[i]
        if a == i:
            continue
        gates += [cx(a, i), cx(i, a), cx(a, i)]  # swap wires a and i
        j = holder.pop(i, None)
        pos[i], holder[i] = i, i
        if j is not None:
            pos[j], holder[a] = a, j
        else:
            holder.pop(a, None)
    return Circuit([("data", n), ("free", big - n)], [Section("routed", gates)])


def _check(scenario_args: tuple[int, int, int], device: str, broken: bool = False, layout_method: str = "auto",
           lowered: bool = True, context: RoutingContext | None = None, every_input: bool = False,
           chosen: str = "O3 passes", optimize_for: str | None = None, zero_start: bool = False,
           routing: RoutingOptions = DEFAULT_ROUTING) -> str:  # fmt: skip
    """QCEC's verdict on the routed circuit against its logical circuit: on every input of the data qubits, or (a
    candidate simplified for the all-|0> start, :mod:`qcpp.routing.known_state`, unless ``every_input``) on the
    all-|0> input. ``chosen``: a part of the chosen candidate's name asserted where ``lowered`` is off."""
    s = default_scenario(*scenario_args)
    r = compile_for_device(s, 1, device, lowered=lowered, bindings=BIND, layout_method=layout_method,
                           context=context, optimize_for=optimize_for, zero_start=zero_start,
                           routing=routing)  # fmt: skip
    if not lowered:  # what compile writes on a named device: a candidate optimised by Qiskit's passes
        assert "O3 passes" in r.chosen and chosen in r.chosen, r.chosen
    if not zero_start:  # the candidates all keep the unitary
        assert r.equal_on_every_input and not any("from |0>" in c["name"] for c in r.candidates), r.candidates
        assert len(r.routed.initial_layout) == len(r.routed.final_layout) == r.logical.num_qubits
    from_zero = "from |0>" in r.chosen and not every_input
    n = r.logical.num_qubits
    b = aligned(r.routed, n)
    a_gates = list(r.logical.gates)
    if broken:
        a_gates.append(rz(0.1, 0))
    a = Circuit([("data", n), ("free", b.num_qubits - n)], [Section("logical", a_gates)])
    # native gates equal the lowered ones up to a global phase (module docs of qcpp.routing.native)
    return check_equivalence(a, b, num_plain=0 if from_zero else s.num_variables, global_phase_ok=not lowered).criterion


@pytest.mark.slow
@pytest.mark.parametrize("device", ["grid:6x6", "heavy-hex:5", "google_willow"])
def test_qcec_proves_routed_equal_to_unrouted(device: str) -> None:
    assert _check((3, 3, 1), device) == "equivalent"


@pytest.mark.slow
@pytest.mark.parametrize("device", ["google_willow"])
def test_qcec_proves_the_native_circuit_a_named_device_gets_equal_to_its_logical_circuit(device: str) -> None:
    """The routed circuit compile writes on a named device (chosen among candidates; on Willow routed with local
    ancillas) against the logical circuit compile reports for it."""
    assert _check((3, 3, 1), device, lowered=False) in ("equivalent", "equivalent_up_to_global_phase")


@pytest.mark.slow
def test_qcec_proves_both_circuits_routed_on_a_calibrated_device_equal_to_their_logical_circuits() -> None:
    """ibm_torino, one robot on 3x3: the lowered routing, and the native circuit compile writes there (ours after
    Qiskit's optimisation), each against its logical circuit; with ``--optimize-for twoq`` alone the written one
    still equals it on every input, and with ``--zero-start`` too (ours simplified for the all-|0> start) it equals
    it on the all-|0> input the device runs from, and not on every input of the data qubits (it lost ``cx`` that act
    only on the robots' start state). One routing context serves the compiles, so the compiles on the heavy-hex
    lattices that they share run once. Equality holds whatever the searches find: they are shortened
    (:data:`~tests.compiler.short_search.SHORT_SEARCH`; every step still runs)."""
    context, short = RoutingContext(), SHORT_SEARCH
    assert _check((3, 3, 1), "ibm_torino", context=context, routing=short) == "equivalent"
    written = _check((3, 3, 1), "ibm_torino", lowered=False, context=context, routing=short)
    assert written in ("equivalent", "equivalent_up_to_global_phase")
    twoq = _check((3, 3, 1), "ibm_torino", lowered=False, context=context, optimize_for="twoq", routing=short)
    assert twoq in ("equivalent", "equivalent_up_to_global_phase")
    zero = _check((3, 3, 1), "ibm_torino", lowered=False, context=context, chosen="from |0>", optimize_for="twoq",
                  zero_start=True, routing=short)  # fmt: skip
    assert zero in ("equivalent", "equivalent_up_to_global_phase")
    assert _check((3, 3, 1), "ibm_torino", lowered=False, context=context, every_input=True, chosen="from |0>",
                  optimize_for="twoq", zero_start=True, routing=short) == "not_equivalent"  # fmt: skip


@pytest.mark.slow
def test_qcec_proves_the_cells_placed_on_an_ibm_device_equal_to_their_logical_circuit() -> None:
    """One robot on 3x3: the heavy-hex cells routed on heavy-hex:7, placed on Torino and optimised by Qiskit's
    passes (the candidate compile adds there), against the logical circuit with local ancillas it carries."""
    from qcpp.hardware.device import named_device
    from qcpp.pipeline.candidates import calibrated_candidates
    from qcpp.pipeline.device_compile import _cells_elsewhere
    from qcpp.pipeline.device_plan import device_plan_options
    from qcpp.plan.compile import compile_scenario
    from qcpp.plan.options import DEFAULT_PLAN
    from qcpp.routing.context import RoutingContext

    s, dev = default_scenario(3, 3, 1), named_device("ibm_torino")
    options = dataclasses.replace(device_plan_options(DEFAULT_PLAN, dev, "auto"), fuse=False)
    compiled = compile_scenario(s, 1, options, lowered=True, bindings=BIND)
    circuit = compiled.circuit
    measured = range(s.num_variables)
    cells = _cells_elsewhere(compiled.plan, circuit, dev, 0, measured, BIND, None, DEFAULT_ROUTING, RoutingContext(),
                             DEFAULT_ROUTING.placement_max_twoq)  # fmt: skip
    assert cells is not None and cells[0].startswith("cells on heavy-hex:")
    cands = calibrated_candidates([], dev, circuit, measured, qiskit_seeds=0, elsewhere=(cells,))
    placed = [c for c in cands if c.name.endswith("our placement + O3 passes")]
    assert placed and all(c.logical is cells[1] for c in cands)
    logical, routed = cells[1], placed[0].native
    n = logical.num_qubits
    b = aligned(routed, n)
    a = Circuit([("data", n), ("free", b.num_qubits - n)], [Section("logical", list(logical.gates))])
    assert check_equivalence(a, b, num_plain=s.num_variables, global_phase_ok=True).criterion in (
        "equivalent", "equivalent_up_to_global_phase")


@pytest.mark.slow
def test_qcec_catches_a_wrong_circuit() -> None:
    assert _check((3, 3, 1), "grid:6x6", broken=True) == "not_equivalent"



@pytest.mark.slow
def test_qcec_proves_a_reordered_register_phase_equal_to_the_written_one() -> None:
    """Two robots on the medial grid: the balance window's register phase routes to fewer CX in another order than
    written (:mod:`qcpp.routing.commuting`), and the routed circuit is still the unrouted one."""
    plain = dataclasses.replace(DEFAULT_ROUTING, commuting_phases=False)
    counts = [
        compile_for_device(default_scenario(2, 3, 2), 1, "grid", lowered=True, bindings=BIND, layout_method="medial",
                           routing=routing).routed.circuit.count_ops()["cx"]
        for routing in (DEFAULT_ROUTING, plain)
    ]  # fmt: skip
    assert counts[0] < counts[1]
    assert _check((2, 3, 2), "grid", layout_method="medial") == "equivalent"


OBSTACLE_2X3_2 = {"grid": {"rows": 2, "cols": 3, "obstacles": [[1, 1]]},
                  "robots": [{"start": [0, 0], "goal": [0, 2]}, {"start": [1, 0], "goal": [1, 2]}],
                  "objective": {"obstacles": "hard"}}  # fmt: skip


@pytest.mark.slow
def test_qcec_proves_a_sibling_devices_search_placed_on_an_ibm_device_equal_to_its_logical_circuit() -> None:
    """Two robots on 2x3 with a hard obstacle (the 3x3 case the candidate was added for takes minutes in QCEC;
    the path is the same): the greedy path's search on ibm_fez (``--optimize-for twoq`` adds it on ibm_torino),
    placed on Torino and optimised by Qiskit's passes, against the logical circuit it carries (the partial mixers
    planned on Fez: the same operator)."""
    from qcpp.hardware.device import named_device
    from qcpp.pipeline.candidates import calibrated_candidates
    from qcpp.pipeline.device_compile import _searched_on_siblings
    from qcpp.pipeline.device_plan import device_plan_options
    from qcpp.plan.compile import compile_scenario
    from qcpp.plan.options import DEFAULT_PLAN
    from qcpp.problem.scenario import scenario_from_dict

    s, dev = scenario_from_dict(OBSTACLE_2X3_2), named_device("ibm_torino")
    options = dataclasses.replace(device_plan_options(DEFAULT_PLAN, dev, "auto"), fuse=False)
    compiled = compile_scenario(s, 1, options, lowered=True, bindings=BIND)
    circuit = compiled.circuit
    measured = range(s.num_variables)
    found = _searched_on_siblings(compiled.plan, circuit, dev, 0, ("ours", "qiskit"), measured, BIND,
                                  DEFAULT_ROUTING, RoutingContext(), lambda _: None)  # fmt: skip
    assert [name for name, _, _ in found] == ["search on ibm_fez"]
    cands = calibrated_candidates([], dev, circuit, measured, qiskit_seeds=0, elsewhere=found, from_zero_start=True)
    placed = [c for c in cands if c.name.endswith("our placement + O3 passes")]
    assert placed and all(c.logical is found[0][1] for c in cands)
    logical, routed = found[0][1], placed[0].native
    n = logical.num_qubits
    b = aligned(routed, n)
    a = Circuit([("data", n), ("free", b.num_qubits - n)], [Section("logical", list(logical.gates))])
    assert check_equivalence(a, b, num_plain=s.num_variables, global_phase_ok=True).criterion in (
        "equivalent", "equivalent_up_to_global_phase")
    # the same placement simplified for the all-|0> start: fewer CZ, the same state from |0...0>
    zero = next(c for c in cands if c.name == placed[0].name.replace(" + O3 passes", " + from |0> + O3 passes"))
    assert zero.twoq < placed[0].twoq
    b = aligned(zero.native, n)
    assert check_equivalence(a, b, num_plain=0, global_phase_ok=True).criterion in (
        "equivalent", "equivalent_up_to_global_phase")
