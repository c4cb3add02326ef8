"""The ESP with idle decoherence, the calibrated Qiskit target and the choice among routed candidates."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import cz, rx, rz
from qcpp.routing.native import esp, esp_idle, idle_fidelity, idle_times_s
from qcpp.routing.options import DEFAULT_ROUTING
from qcpp.routing.routed_circuit import RoutedCircuit
from tests.compiler.short_search import SHORT_SEARCH

US = 1e-6


def toy_device(t1: tuple[float | None, ...] | None = (100 * US, 200 * US, None),
               t2: tuple[float | None, ...] | None = (50 * US, 500 * US, 100 * US)) -> Device:  # fmt: skip
    """Three qubits on a line, every figure chosen by hand."""
    return Device(
        name="toy", num_qubits=3, coupling=((0, 1), (1, 2)), native_gates=("cz", "rz", "sx", "x"),
        two_qubit_gate="cz",
        error_1q=(("rz", (0.0,) * 3), ("sx", (0.001, 0.002, 0.003)), ("x", (0.001, 0.002, 0.003))),
        error_2q=(0.01, 0.02), readout_error=(0.05, 0.0, 0.1),
        duration_1q_s=(("rz", (0.0,) * 3), ("sx", (1 * US,) * 3), ("x", (1 * US,) * 3)),
        duration_2q_s=(2 * US, 3 * US), readout_duration_s=(1 * US,) * 3,
        source="by hand", date="-", family="grid", t1_s=t1, t2_s=t2,
    )  # fmt: skip


def toy_routed(device: Device) -> RoutedCircuit:
    # q0: sx [0, 1], cz01 [1, 3], then waits for the readout at 6: idle 3 us
    # q1: cz01 [1, 3], cz12 [3, 6]: never idle;  q2: sx [0, 1], rz (virtual), cz12 [3, 6]: idle 2 us (T1 unknown)
    gates = [rx(math.pi / 2, 0), rx(math.pi / 2, 2), rz(0.3, 2), cz(0, 1), cz(1, 2)]
    circuit = Circuit([Register("q", 3)], [Section("s", gates)])
    return RoutedCircuit(circuit, device, (0, 1, 2), (0, 1, 2), 0, (0, 2))


def test_idle_times_follow_the_asap_schedule_by_hand() -> None:
    t = idle_times_s(toy_routed(toy_device()))
    assert t is not None
    assert [round(x / US, 9) for x in t] == [3.0, 0.0, 2.0]


def test_esp_with_idle_decoherence_is_the_hand_computed_product() -> None:
    routed = toy_routed(toy_device())
    gates = (1 - 0.001) * (1 - 0.003) * (1 - 0.01) * (1 - 0.02) * (1 - 0.05) * (1 - 0.1)
    assert esp(routed) == pytest.approx(gates, rel=1e-12)
    idle_q0 = (3 + math.exp(-3 / 100) + 2 * math.exp(-3 / 50)) / 6  # q2 idles too, but its T1 is unknown
    assert esp_idle(routed) == pytest.approx(gates * idle_q0, rel=1e-12)


def test_t2_is_capped_at_twice_t1_and_no_coherence_data_means_no_idle_figure() -> None:
    assert idle_fidelity(5 * US, 100 * US, 1000 * US) == idle_fidelity(5 * US, 100 * US, 200 * US)
    assert idle_fidelity(5 * US, 100 * US, 150 * US) < idle_fidelity(5 * US, 100 * US, 200 * US) < 1
    assert esp_idle(toy_routed(toy_device(t1=None, t2=None))) is None


# --- the calibrated target, Qiskit's O3 as a candidate, placement by our ESP model ---------------------------
def test_the_target_carries_the_device_files_calibration() -> None:
    from qcpp.hardware.device import named_device
    from qcpp.routing.target import device_target

    dev = named_device("ibm_torino")
    t = device_target(dev)
    a, b = dev.coupling[5]
    assert t["cz"][(a, b)].error == t["cz"][(b, a)].error == dev.error_2q[5]
    assert t["cz"][(a, b)].duration == dev.duration_2q_s[5]
    assert t["sx"][(3,)].error == dict(dev.error_1q)["sx"][3] and t["rz"][(3,)].error == 0.0
    assert t["measure"][(3,)].error == dev.readout_error[3]
    assert (t.qubit_properties[3].t1, t.qubit_properties[3].t2) == (dev.t1_s[3], dev.t2_s[3])
    assert len(t["cz"]) == 2 * len(dev.coupling)


def _state_up_to_layouts(routed: RoutedCircuit, logical: Circuit) -> float:
    """|<P_final U P_init^-1 psi | routed psi>| for a random product input on the logical qubits."""
    import numpy as np

    from qcpp.ir.gates import ry
    from qcpp.simulate.statevector import simulate_statevector

    rng = np.random.default_rng(5)
    n, big = logical.num_qubits, routed.circuit.num_qubits
    angles = rng.uniform(0, 3, n)
    prep = Section("prep", [ry(float(a), q) for q, a in enumerate(angles)])
    want = simulate_statevector(Circuit(logical.registers, [prep, *logical.sections]))
    moved = Section("prep", [ry(float(a), routed.initial_layout[q]) for q, a in enumerate(angles)])
    got = simulate_statevector(Circuit(routed.circuit.registers, [moved, *routed.circuit.sections]))
    idx = np.arange(2**n)
    phys = np.zeros_like(idx)
    for lq in range(n):
        phys |= ((idx >> lq) & 1) << routed.final_layout[lq]
    placed = np.zeros(2**big, dtype=complex)
    placed[phys] = want
    return float(abs(np.vdot(placed, got)))


def test_qiskit_o3_reads_back_a_circuit_equal_up_to_the_layouts_with_symbols_kept() -> None:
    from qcpp.hardware.device import get_device
    from qcpp.ir.angles import Angle
    from qcpp.ir.gates import cx, h
    from qcpp.routing.qiskit_o3 import qiskit_o3

    gamma = Angle.symbol("gamma_0", 2.0) + 0.25
    gates = [h(0), cx(0, 1), cx(0, 2), rz(gamma, 2), cx(1, 2), cx(0, 2), rx(0.4, 1), cx(2, 0)]
    logical = Circuit([Register("data", 3)], [Section("s", gates)])
    routed = qiskit_o3(logical, get_device("grid:2x3"), seed=1)
    assert {"gamma_0"} == {name for g in routed.circuit.gates for p in g[2] if isinstance(p, Angle)
                           for name, _ in p.terms}  # fmt: skip
    edges = routed.device.edge_index()
    assert all(len(g[1]) == 1 or g[1] in edges for g in routed.circuit.gates)
    bound = {"gamma_0": 0.7}
    on = Circuit(routed.circuit.registers, [Section(s.name, [g.bind(bound) if g[2] else g for g in s.gates])
                                              for s in routed.circuit.sections])  # fmt: skip
    ref = Circuit(logical.registers, [Section("s", [g.bind(bound) if g[2] else g for g in gates])])
    assert _state_up_to_layouts(RoutedCircuit(on, routed.device, routed.initial_layout, routed.final_layout, 0,
                                              routed.measured), ref) == pytest.approx(1.0, abs=1e-9)  # fmt: skip


def test_placement_moves_a_circuit_onto_the_best_coupler_by_hand() -> None:
    from qcpp.hardware.device import named_device
    from qcpp.routing.noise_aware import post_layout

    dev = named_device("ibm_fez")
    worst = max(range(len(dev.coupling)), key=lambda i: dev.error_2q[i])
    a, b = dev.coupling[worst]
    circuit = Circuit([Register("q", dev.num_qubits)], [Section("s", [cz(a, b)] * 10)])
    moved = post_layout(RoutedCircuit(circuit, dev, (a, b), (a, b), 0, ()))
    best = min(range(len(dev.coupling)), key=lambda i: dev.error_2q[i])
    # no one-qubit gates, nothing measured, never idle: the ESP is the coupler's (1 - e)^10 alone
    assert tuple(sorted(next(iter(moved.circuit.gates))[1])) == dev.coupling[best]
    assert esp(moved) == pytest.approx((1 - dev.error_2q[best]) ** 10)


def test_qiskit_wins_where_it_is_better() -> None:
    from qcpp.hardware.device import named_device
    from qcpp.ir.gates import cx, h
    from qcpp.pipeline.candidates import calibrated_candidates, choose
    from qcpp.routing.sabre import route

    dev = named_device("ibm_fez")
    logical = Circuit([Register("data", 3)], [Section("s", [h(0), cx(0, 1), cx(1, 2), cx(0, 2), cx(0, 1)])])
    import numpy as np

    from qcpp.hardware.device import distances

    d = distances(dev)[0]
    reach = np.where(np.isfinite(d))[0]
    ends = (0, int(reach[np.argmax(d[reach])]), int(reach[np.argsort(d[reach])[len(reach) // 2]]))
    far = route(logical, dev, ends, seed=0)  # our "routing" from a layout across the device: many SWAPs
    cands = calibrated_candidates([far], dev, qiskit_circuit=logical, measured=range(3), qiskit_seeds=1)
    names = [c.name for c in cands]
    assert names[0] == "qcpp" and "qiskit O3 seed 0" in names
    for figure in ("twoq", "esp"):
        chosen = choose(cands, figure)
        assert chosen.name.startswith("qiskit O3"), (figure, [(c.name, c.twoq, c.esp) for c in cands])
        assert chosen.twoq == min(c.twoq for c in cands) < cands[0].twoq
        assert chosen.lowered is None  # Qiskit's exists in native gates only


def test_choice_ranks_by_the_asked_figure_and_refuses_others() -> None:
    from qcpp.hardware.device import named_device
    from qcpp.pipeline.candidates import RoutedCandidate, choose

    dev = named_device("ibm_fez")
    i_best = min(range(len(dev.coupling)), key=lambda i: dev.error_2q[i])
    i_worst = max(range(len(dev.coupling)), key=lambda i: dev.error_2q[i])

    def cand(name: str, edge: tuple[int, int], k: int) -> RoutedCandidate:
        c = Circuit([Register("q", dev.num_qubits)], [Section("s", [cz(*edge)] * k)])
        return RoutedCandidate(name, RoutedCircuit(c, dev, edge, edge, 0, ()))

    few_bad, more_good = cand("few", dev.coupling[i_worst], 2), cand("more", dev.coupling[i_best], 3)
    assert (1 - dev.error_2q[i_best]) ** 3 > (1 - dev.error_2q[i_worst]) ** 2  # the snapshot has a faulty-ish coupler
    assert choose([few_bad, more_good], "twoq").name == "few"
    assert choose([few_bad, more_good], "esp").name == "more"
    with pytest.raises(ValueError, match="optimize for"):
        choose([few_bad], "depth")


def test_ranked_routes_start_with_the_search_winner() -> None:
    from qcpp.hardware.device import get_device
    from qcpp.layout.placement_search import ranked_routes, search_route, two_qubit_count
    from qcpp.plan.compile import compile_scenario
    from qcpp.plan.options import PlanOptions
    from qcpp.problem.presets import default_scenario
    from qcpp.routing.options import RoutingOptions

    c = compile_scenario(default_scenario(2, 3, 1), 1, PlanOptions(fuse=False), lowered=True).circuit
    dev = get_device("heavy-hex:3")
    opts = RoutingOptions(placement_layouts=4, placement_seeds=2, placement_refine=2)
    ranked = ranked_routes(c, dev, count=3, options=opts)
    one = search_route(c, dev, options=opts)
    assert list(ranked[0].circuit.gates) == list(one.circuit.gates) and ranked[0].initial_layout == one.initial_layout
    counts = [two_qubit_count(r.circuit) for r in ranked]
    assert counts == sorted(counts) and len(ranked) == 3


@pytest.mark.heavy  # compiles 3x3/1 on both IBM snapshots with every candidate (tens of seconds)
@pytest.mark.parametrize("name", ["ibm_fez", "ibm_torino"])
def test_compile_on_a_named_device_is_never_worse_than_qiskit_o3(name: str) -> None:
    from qcpp.hardware.device import named_device
    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.problem.presets import default_scenario
    from qcpp.routing.context import RoutingContext
    from qcpp.routing.qiskit_o3 import qiskit_o3

    s, bind = default_scenario(3, 3, 1), {"gamma_0": 0.3, "beta_0": 0.7}
    dev, context = named_device(name), RoutingContext()  # one run's memos: the two figures share their searches
    # Qiskit's O3 is a candidate whatever the searches find: they are shortened (every step still runs)
    by_esp = compile_for_device(s, 1, name, bindings=bind, context=context, routing=SHORT_SEARCH)
    by_twoq = compile_for_device(s, 1, name, bindings=bind, optimize_for="twoq", context=context, routing=SHORT_SEARCH)
    peers = [qiskit_o3(by_esp.compiled.circuit, dev, seed, range(s.num_variables)) for seed in range(3)]
    assert by_esp.optimize_for == "esp" and by_esp.chosen in {c["name"] for c in by_esp.candidates}
    assert esp_idle(by_esp.routed) >= max(esp_idle(p) for p in peers)
    twoq = [sum(1 for g in r.circuit.gates if len(g[1]) == 2) for r in (by_twoq.routed, *peers)]
    assert twoq[0] <= min(twoq[1:])
    summary = by_esp.summary()["routed"]
    assert summary["esp_idle"] < summary["esp"] and summary["chosen"] == by_esp.chosen


_ONE_QUBIT = ("h", "x", "s", "sdg", "t", "tdg")


@st.composite
def _lowered_circuits(draw: st.DrawFn) -> list[tuple[str, tuple[int, ...], float]]:
    """Up to 30 gates of a lowered circuit on 4 qubits: ``cx``, the fixed one-qubit gates and ``rz``/``rx``."""
    out = []
    for _ in range(draw(st.integers(1, 30))):
        kind = draw(st.sampled_from(("cx", "one", "rz", "rx")))
        if kind == "cx":
            a, b = draw(st.lists(st.integers(0, 3), min_size=2, max_size=2, unique=True))
            out.append(("cx", (a, b), 0.0))
        else:
            name = draw(st.sampled_from(_ONE_QUBIT)) if kind == "one" else kind
            out.append((name, (draw(st.integers(0, 3)),), draw(st.floats(-3, 3))))
    return out


@settings(max_examples=25, deadline=None)
@given(_lowered_circuits(), st.integers(0, 5))
def test_qiskit_optimized_keeps_a_routed_circuit_and_its_layouts(
    spec: list[tuple[str, tuple[int, ...], float]], seed: int
) -> None:
    """Our routing after Qiskit's optimisation at its layout: the same state from the same input, every gate on a
    coupling, the layouts and SWAP count unchanged, one symbol kept as a symbol."""
    from qcpp.hardware.device import get_device
    from qcpp.ir import gates as G
    from qcpp.ir.angles import Angle
    from qcpp.routing.qiskit_o3 import qiskit_optimized
    from qcpp.routing.sabre import route

    gamma = Angle.symbol("gamma_0", 2.0) + 0.25
    gates = [G.rz(gamma, 0)]
    for name, qs, theta in spec:
        gates.append(G.cx(*qs) if name == "cx" else getattr(G, name)(theta, *qs) if name in ("rz", "rx")
                     else getattr(G, name)(*qs))  # fmt: skip
    logical = Circuit([Register("data", 4)], [Section("s", gates)])
    dev = get_device("grid:2x3")
    routed = route(logical, dev, (0, 5, 2, 3), seed=seed)  # a layout with the pairs apart: SWAPs to keep
    done = qiskit_optimized(routed)
    assert (done.initial_layout, done.final_layout, done.swaps, done.measured) == (
        routed.initial_layout, routed.final_layout, routed.swaps, routed.measured)  # fmt: skip
    edges = dev.edge_index()
    assert all(len(g[1]) == 1 or g[1] in edges for g in done.circuit.gates)
    assert {g[0] for g in done.circuit.gates} <= {"cz", "rz", "rx", "x"}
    symbols = {name for g in done.circuit.gates for p in g[2] if isinstance(p, Angle) for name, _ in p.terms}
    assert symbols <= {"gamma_0"}
    bound = {"gamma_0": 0.7}

    def bind(c: Circuit) -> Circuit:
        return Circuit(c.registers, [Section(s.name, [g.bind(bound) if g[2] else g for g in s.gates])
                                     for s in c.sections])  # fmt: skip

    ref = bind(logical)
    for r in (routed, done):
        moved = RoutedCircuit(bind(r.circuit), dev, r.initial_layout, r.final_layout, r.swaps, r.measured)
        assert _state_up_to_layouts(moved, ref) == pytest.approx(1.0, abs=1e-9)


def test_qiskit_optimized_merges_the_one_qubit_gates_of_a_routing() -> None:
    """3x3/1 routed on ibm_torino: gate by gate, every ``cx`` brings its Hadamards; optimised, fewer ``sx`` pulses
    and no more ``cz``; the candidates carry it (and its placements) only where Qiskit candidates are asked for."""
    from qcpp.hardware.device import named_device
    from qcpp.pipeline.candidates import calibrated_candidates
    from qcpp.pipeline.device_compile import greedy_route
    from qcpp.plan.compile import compile_scenario
    from qcpp.plan.options import PlanOptions
    from qcpp.problem.presets import default_scenario
    from qcpp.routing.native import to_native
    from qcpp.routing.qiskit_o3 import qiskit_optimized

    s = default_scenario(3, 3, 1)
    c = compile_scenario(s, 1, PlanOptions(fuse=False, phase_layout="spatial"), lowered=True,
                         bindings={"gamma_0": 0.3, "beta_0": 0.7}).circuit  # fmt: skip
    dev = named_device("ibm_torino")
    routed = greedy_route(c, dev, measured=range(s.num_variables))
    plain, done = to_native(routed).circuit.count_ops(), qiskit_optimized(routed).circuit.count_ops()
    assert done["cz"] <= plain["cz"]
    assert done["rx"] < 0.9 * plain["rx"], (plain, done)
    assert esp_idle(qiskit_optimized(routed)) > esp_idle(to_native(routed))
    # one VF2 search serves both (the same couplers), each scored by its own gates: as without the memo
    from qcpp.routing.noise_aware import embedding_sites

    memo: dict[object, list[tuple[int, ...]]] = {}
    for r in (to_native(routed), qiskit_optimized(routed)):
        assert embedding_sites(r, dev, found_memo=memo) == embedding_sites(r, dev)
    assert len(memo) == 1
    with_qiskit = [x.name for x in calibrated_candidates([routed], dev, c, range(s.num_variables), qiskit_seeds=1)]
    alone = [x.name for x in calibrated_candidates([routed], dev, None, range(s.num_variables))]
    assert "qcpp + O3 passes" in with_qiskit and "qcpp + O3 passes + our placement" in with_qiskit
    assert not any("O3" in name for name in alone)


def test_a_routing_on_a_larger_lattice_is_placed_on_a_named_device() -> None:
    """A routing on heavy-hex:9 (193 qubits) moves onto ibm_fez (156): distinct sites for the qubits it uses, every
    two-qubit gate on a coupler, the same gates and layouts relabelled; the qubits it leaves unused carry nothing."""
    from qcpp.hardware.device import get_device, named_device
    from qcpp.ir.gates import cx, h
    from qcpp.routing.native import to_native
    from qcpp.routing.noise_aware import embedding_sites
    from qcpp.routing.routed_circuit import embed_routed
    from qcpp.routing.sabre import route

    hexd, fez = get_device("heavy-hex:9"), named_device("ibm_fez")
    a, b = hexd.coupling[40]
    c = next(x for x in hexd.coupling if b in x and a not in x)
    third = c[0] if c[1] == b else c[1]
    logical = Circuit([Register("data", 3)], [Section("s", [h(0), cx(0, 1), cx(1, 2), cx(0, 2)])])
    routed = to_native(route(logical, hexd, (a, b, third), seed=0))
    used = {q for g in routed.circuit.gates for q in g[1]} | set(routed.initial_layout) | set(routed.final_layout)
    sites = embedding_sites(routed, fez)
    assert sites and routed.circuit.num_qubits > fez.num_qubits
    for s in sites:
        assert len(s) == routed.circuit.num_qubits and len({s[q] for q in used}) == len(used)
        moved = embed_routed(routed, fez, s)
        pairs = {tuple(sorted(g[1])) for g in moved.circuit.gates if len(g[1]) == 2}
        assert pairs <= set(fez.coupling)
        assert [g[0] for g in moved.circuit.gates] == [g[0] for g in routed.circuit.gates]
        assert moved.initial_layout == tuple(s[q] for q in routed.initial_layout)


@pytest.mark.heavy  # compiles 3x3/1 on ibm_fez with every candidate, twice
def test_the_searches_on_defect_free_lattices_are_placed_on_an_ibm_device() -> None:
    """One robot on 3x3 on Fez: compile also compiles the circuit on heavy-hex:3 .. 9 (greedy layout, placement
    search, partial mixers planned there) and offers those routings placed where they embed; the chosen one has
    the fewest CZ, fewer than without the lattices, and the result reports the logical circuit its layouts index:
    the lattice's partial-mixer choice, the same operator as the plan's circuit (statevector). With the lattice
    search off there are no such candidates (a compile sharing the first's memos: the searches on Fez itself are
    the same). Both compiles run the shorter search (:data:`SHORT_SEARCH`) on every lattice the default reaches;
    the default search's result on a one-robot 3x3 field is the committed ensemble row that
    ``experiments_test.py::test_ensemble_devices_quick_mode`` recompiles."""
    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.problem.presets import default_scenario
    from qcpp.routing.context import RoutingContext
    from qcpp.simulate.statevector import simulate_statevector

    s, bind, context = default_scenario(3, 3, 1), {"gamma_0": 0.3, "beta_0": 0.7}, RoutingContext()
    short = replace(SHORT_SEARCH, lattice_search_max_distance=DEFAULT_ROUTING.lattice_search_max_distance)
    r = compile_for_device(s, 1, "ibm_fez", bindings=bind, optimize_for="twoq", context=context, routing=short)
    by_name = {c["name"]: c["two_qubit"] for c in r.candidates}
    lattices = {n.split(" + ")[0] for n in by_name if n.startswith("search on heavy-hex:")}
    assert lattices and lattices <= {f"search on heavy-hex:{d}" for d in (3, 5, 7, 9)}
    assert by_name[r.chosen] == min(by_name.values()) and r.chosen.startswith("search on heavy-hex:"), r.chosen
    assert len(r.routed.initial_layout) == r.logical.num_qubits == r.compiled.circuit.num_qubits
    assert list(r.logical.gates) != list(r.compiled.circuit.gates)  # the lattice's choice of parity networks
    assert np.allclose(simulate_statevector(r.logical), simulate_statevector(r.compiled.circuit), atol=1e-9)
    off = compile_for_device(s, 1, "ibm_fez", bindings=bind, optimize_for="twoq", context=context,
                             routing=replace(short, lattice_search_max_distance=0))  # fmt: skip
    assert not any(c["name"].startswith("search on heavy-hex:") for c in off.candidates)  # twoq: Torino's stays
    assert by_name[r.chosen] < min(c["two_qubit"] for c in off.candidates)


@pytest.mark.heavy  # compiles 3x4/1 on ibm_torino with every candidate, and the cells on heavy-hex:9
def test_the_cells_routed_on_a_lattice_beat_qiskit_on_an_ibm_device() -> None:
    """One robot on 3x4: the cell layout routed on heavy-hex:9 and placed on Torino writes fewer CZ than Qiskit's
    routings of Torino, and the chosen candidate has the fewest; with ``--layout medial`` the result reports the
    cells' logical circuit (local ancillas), which its layouts index (``routing_qcec_test`` proves the two equal up
    to the layouts). The two compiles share their memos (the cells are routed once). The cells' candidate does not
    depend on the placement searches, so both compiles run the shorter search (:data:`SHORT_SEARCH`)."""
    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.problem.presets import default_scenario
    from qcpp.routing.context import RoutingContext

    s, bind, context = default_scenario(3, 4, 1), {"gamma_0": 0.3, "beta_0": 0.7}, RoutingContext()
    r = compile_for_device(s, 1, "ibm_torino", bindings=bind, optimize_for="twoq", context=context,
                           routing=SHORT_SEARCH)  # fmt: skip
    by_name = {c["name"]: c["two_qubit"] for c in r.candidates}
    cells = [n for n in by_name if n.startswith("cells on heavy-hex:")]
    qiskit = [n for n in by_name if n.startswith("qiskit")]
    assert cells and qiskit and min(by_name[n] for n in cells) < min(by_name[n] for n in qiskit)
    assert by_name[r.chosen] == min(by_name.values())
    r = compile_for_device(s, 1, "ibm_torino", bindings=bind, optimize_for="twoq", layout_method="medial",
                           context=context, routing=SHORT_SEARCH)  # fmt: skip
    assert r.chosen.startswith("cells on heavy-hex:"), r.chosen
    assert r.logical.num_qubits > r.compiled.circuit.num_qubits  # the cells' local ancillas
    assert len(r.routed.initial_layout) == len(r.routed.final_layout) == r.logical.num_qubits


@pytest.mark.heavy  # compiles 3x3/2 with an obstacle on ibm_torino with every candidate, by each figure
def test_searches_on_the_other_ibm_device_are_offered_only_for_twoq() -> None:
    """Two robots on 3x3 with a hard obstacle on Torino: with ``--optimize-for twoq`` compile also runs the greedy
    path's search on Fez and places it on Torino where it embeds; after Qiskit's passes that routing has fewer CZ
    than every candidate of the default ``esp`` compile, which does not offer it (its candidates, and so its output,
    are as before). Neither offers the candidates simplified for the all-|0> start unless ``zero_start``; with it,
    the twoq compile offers them for the sibling's placement too and writes one of them, with fewer CZ still. Every
    compile runs the shorter search (:data:`SHORT_SEARCH`), on both devices: what is checked is which candidates
    each figure offers and that the sibling's routing wins the twoq choice, not how far the searches go."""
    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.problem.scenario import scenario_from_dict
    from qcpp.routing.context import RoutingContext

    s = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[1, 2]]},
                            "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}],
                            "objective": {"obstacles": "hard"}})  # fmt: skip
    bind, context = {"gamma_0": 0.3, "beta_0": 0.7}, RoutingContext()
    by_esp = compile_for_device(s, 1, "ibm_torino", bindings=bind, context=context, routing=SHORT_SEARCH)
    assert by_esp.optimize_for == "esp" and not by_esp.zero_start
    assert not any(c["name"].startswith("search on ibm_") or "from |0>" in c["name"] for c in by_esp.candidates)
    by_twoq = compile_for_device(s, 1, "ibm_torino", bindings=bind, context=context, optimize_for="twoq",
                                 routing=SHORT_SEARCH)  # fmt: skip
    assert not any("from |0>" in c["name"] for c in by_twoq.candidates) and by_twoq.equal_on_every_input
    assert by_twoq.chosen.startswith("search on ibm_fez + our placement"), by_twoq.chosen
    twoq = sum(1 for g in by_twoq.routed.circuit.gates if len(g[1]) == 2)
    assert twoq < min(c["two_qubit"] for c in by_esp.candidates)
    assert {tuple(sorted(g[1])) for g in by_twoq.routed.circuit.gates if len(g[1]) == 2} <= set(
        by_twoq.routed.device.coupling)
    zero = compile_for_device(s, 1, "ibm_torino", bindings=bind, context=context, optimize_for="twoq",
                              zero_start=True, routing=SHORT_SEARCH)  # fmt: skip
    assert zero.zero_start and "from |0>" in zero.chosen and not zero.equal_on_every_input, zero.chosen
    assert any(c["name"].startswith("search on ibm_fez + our placement") and "from |0>" in c["name"]
               for c in zero.candidates)  # fmt: skip
    assert sum(1 for g in zero.routed.circuit.gates if len(g[1]) == 2) < twoq
    assert {tuple(sorted(g[1])) for g in zero.routed.circuit.gates if len(g[1]) == 2} <= set(
        zero.routed.device.coupling)
