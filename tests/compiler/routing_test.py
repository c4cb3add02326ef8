"""Devices, layout and routing: every two-qubit gate on a coupling, routed == unrouted up to the layouts, ESP.

Evidence, not assertion: the routed circuit's statevector is compared with the unrouted one's (permuted by the
reported layouts, free qubits |0>), the native translation is checked the same way (up to a global phase), and
our ESP is cross-checked against an independent computation from Qiskit's own ``Target`` of the IBM Fez
snapshot on a circuit Qiskit transpiled itself.
"""

from __future__ import annotations

import doctest
import importlib
import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from qiskit import transpile

from qcpp.hardware.device import DeviceError, device_names, get_device, heavy_hex_qubits, named_device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cx, h, rx, ry
from qcpp.layout.placement import localize_ancillas, place
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.routing.native import esp, to_native
from qcpp.routing.routed_circuit import RoutedCircuit
from qcpp.routing.sabre import route
from qcpp.simulate.equivalence import to_qiskit
from qcpp.simulate.statevector import simulate_statevector

BIND = {"gamma_0": 0.37, "beta_0": 0.81}


@pytest.mark.parametrize(
    "module",
    [
        "qcpp.hardware.device",
        "qcpp.routing.sabre",
        "qcpp.routing.routed_circuit",
        "qcpp.routing.windows",
        "qcpp.routing.patches",
        "qcpp.routing.native",
        "qcpp.routing.options",
        "qcpp.routing.context",
        "qcpp.layout.placement",
        "qcpp.pipeline.device_compile",
    ],
)
def test_doctests(module: str) -> None:
    """These modules have examples (tests/doctests_test.py runs every module's, so here they are counted)."""
    tests = doctest.DocTestFinder().find(importlib.import_module(module))
    assert sum(len(t.examples) for t in tests) > 0


# --- devices -----------------------------------------------------------------------------------------------
def test_families_have_the_lattice_sizes() -> None:
    g = get_device("grid:3x4")
    assert (g.num_qubits, len(g.coupling)) == (12, 3 * 3 + 2 * 4)
    for d in (3, 5, 7):
        hh = get_device(f"heavy-hex:{d}")
        assert hh.num_qubits == heavy_hex_qubits(d)
        degrees = np.bincount(np.array(hh.coupling).ravel(), minlength=hh.num_qubits)
        assert degrees.max() == 3  # heavy-hex: degree at most 3
    a = get_device("all-to-all:6")
    assert a.is_all_to_all and len(a.coupling) == 15


@pytest.mark.parametrize("need", [1, 2, 15, 16, 17, 80, 144, 333])
def test_families_without_size_are_the_smallest_that_fit(need: int) -> None:
    g = get_device("grid", min_qubits=need)
    k = int(g.name.split(":")[1].split("x")[0])
    assert k * k >= need and (k - 1) ** 2 < need
    hh = get_device("heavy-hex", min_qubits=need)
    d = int(hh.name.split(":")[1])
    assert hh.num_qubits >= need and (d == 3 or heavy_hex_qubits(d - 2) < need)
    assert get_device("all-to-all", min_qubits=need).num_qubits == max(need, 2)


@pytest.mark.parametrize(
    "bad", ["grid:3", "grid:0x4", "heavy-hex:4", "heavy-hex:x", "all-to-all:1", "nope", "ibm_fez:3"]
)
def test_bad_device_names_are_one_clear_error(bad: str) -> None:
    with pytest.raises(DeviceError) as exc:
        get_device(bad)
    assert bad.split(":")[0] in str(exc.value) and "\n" not in str(exc.value)


@pytest.mark.parametrize("name", device_names())
def test_named_devices_state_source_date_and_consistent_data(name: str) -> None:
    d = named_device(name)
    raw = json.loads((Path(__file__).resolve().parents[2] / "src/qcpp/hardware/data" / f"{name}.json").read_text())
    assert raw["source"] and raw["date"] and d.source == raw["source"]
    assert d.two_qubit_gate in d.native_gates
    assert all(0 <= e < 1 for e in d.error_2q) and all(0 <= e < 1 for e in d.readout_error)
    assert len(d.error_2q) == len(d.coupling) and len(set(d.coupling)) == len(d.coupling)


def test_ibm_snapshot_matches_qiskit_ibm_runtime() -> None:
    from qiskit_ibm_runtime.fake_provider import FakeFez  # the test extra has it: this runs wherever the tests do

    backend = FakeFez()
    d = named_device("ibm_fez")
    target = backend.target
    assert d.num_qubits == backend.num_qubits
    for (a, b), e in zip(d.coupling, d.error_2q, strict=True):
        assert target["cz"][(a, b)].error == e
    dropped = [q for q, p in target["cz"].items() if p.error is not None and p.error >= 1.0]
    assert dropped and all(tuple(sorted(q)) not in d.edge_index() for q in dropped)
    assert dict(d.error_1q)["sx"][7] == target["sx"][(7,)].error
    assert d.readout_error[7] == target["measure"][(7,)].error
    for q in (0, 7, 155):
        assert (d.t1_s[q], d.t2_s[q]) == (target.qubit_properties[q].t1, target.qubit_properties[q].t2)


@pytest.mark.parametrize("name", device_names())
def test_coherence_times_are_loaded_per_qubit_where_the_source_has_them(name: str) -> None:
    d = named_device(name)
    raw = json.loads((Path(__file__).resolve().parents[2] / "src/qcpp/hardware/data" / f"{name}.json").read_text())
    if "t1_s" not in raw:
        assert d.t1_s is None and d.t2_s is None
        return
    assert d.t1_s is not None and d.t2_s is not None
    assert list(d.t1_s) == raw["t1_s"] and list(d.t2_s) == raw["t2_s"]
    assert len(d.t1_s) == len(d.t2_s) == d.num_qubits
    assert all(t is None or 1e-7 < t < 1e-1 for t in (*d.t1_s, *d.t2_s))


def test_family_coherence_times_are_the_template_medians_or_absent() -> None:
    fez = named_device("ibm_fez")
    hh = get_device("heavy-hex:3")
    assert hh.t1_s == (float(np.median(fez.t1_s)),) * hh.num_qubits
    assert hh.t2_s == (float(np.median(fez.t2_s)),) * hh.num_qubits
    assert get_device("grid:3x3").t1_s is None and get_device("all-to-all:4").t2_s is None


# --- routing -----------------------------------------------------------------------------------------------
def _on_coupling(routed: RoutedCircuit) -> bool:
    edges = routed.device.edge_index()
    return all(len(g[1]) < 2 or tuple(g[1]) in edges for g in routed.circuit.gates)


def _statevector(circuit: Circuit, prefix: list[Gate], num_qubits: int) -> np.ndarray:
    regs = list(circuit.registers)
    if num_qubits > circuit.num_qubits:
        regs.append(("pad", num_qubits - circuit.num_qubits))
    return simulate_statevector(Circuit(regs, [Section("prep", prefix), *circuit.sections]))


def _permuted(state: np.ndarray, n: int, big: int, layout: tuple[int, ...]) -> np.ndarray:
    """The logical ``n``-qubit state on ``big`` physical qubits, logical qubit i on ``layout[i]``, others |0>."""
    out = np.zeros(2**big, dtype=complex)
    idx = np.arange(2**n)
    phys = np.zeros_like(idx)
    for i, p in enumerate(layout):
        phys |= ((idx >> i) & 1) << p
    out[phys] = state
    return out


def _assert_equal_up_to_layouts(logical: Circuit, routed: RoutedCircuit, seed: int, global_phase: bool) -> None:
    """The routed circuit's state equals the logical one's moved by the layouts, on the physical qubits that a gate
    or a layout touches (each of the others is |0> before and after in both, so leaving it out changes nothing but
    the statevector's size: 2^19 amplitudes on heavy-hex:3 against 2^8 on the qubits a 2x3/1 circuit uses)."""
    n = logical.num_qubits
    used = sorted({q for g in routed.circuit.gates for q in g[1]} | {*routed.initial_layout, *routed.final_layout})
    index = {p: i for i, p in enumerate(used)}
    big = len(used)
    data = logical.registers[0].size
    rng = np.random.default_rng(seed)
    prefix = [g for q in range(data) for g in (ry(float(rng.uniform(0, 3)), q), rx(float(rng.uniform(0, 3)), q))]
    want = _permuted(_statevector(logical, prefix, n), n, big, tuple(index[p] for p in routed.final_layout))
    moved = [Gate(g[0], tuple(index[routed.initial_layout[q]] for q in g[1]), g[2], g[3]) for g in prefix]
    sections = [Section(sec.name, [Gate(g[0], tuple(index[q] for q in g[1]), g[2], g[3]) for g in sec.gates])
                for sec in routed.circuit.sections]  # fmt: skip
    compact = Circuit([("q", big)], sections)
    got = _statevector(compact, moved, big)
    overlap = abs(np.vdot(want, got))
    assert overlap == pytest.approx(1.0, abs=1e-9)
    if not global_phase:
        assert np.allclose(want, got, atol=1e-9)


OBSTACLE = {
    "grid": {"rows": 3, "cols": 4, "obstacles": [[1, 1]]},
    "robots": [{"start": [1, 2], "goal": [2, 0]}],
    "objective": {"obstacles": "hard"},
}
SMALL = [
    ("2x3/1", default_scenario(2, 3, 1), ["grid:3x4", "heavy-hex:3", "all-to-all:12"]),
    ("3x4 hard obstacle, interior start", scenario_from_dict(OBSTACLE), ["grid:4x4", "all-to-all:14"]),
    ("3x3/1", default_scenario(3, 3, 1), ["grid:4x4"]),
]
CASES = [(label, s, d) for label, s, devices in SMALL for d in devices]


@pytest.mark.parametrize(("label", "s", "device"), CASES, ids=[f"{c[0]}-{c[2]}" for c in CASES])
def test_routed_equals_unrouted_up_to_layouts(label: str, s: Scenario, device: str) -> None:
    logical = compile_scenario(s, 1, PlanOptions(fuse=False), lowered=True, bindings=BIND).circuit
    dev = get_device(device)
    routed = route(logical, dev, place(logical, dev))
    assert _on_coupling(routed)
    _assert_equal_up_to_layouts(logical, routed, seed=1, global_phase=False)
    native = to_native(routed)
    assert set(native.circuit.count_ops()) <= {*dev.native_gates, "rx", "rz"}
    assert _on_coupling(native)
    _assert_equal_up_to_layouts(logical, native, seed=2, global_phase=True)


def _matrix(gates: list[Gate], n: int) -> np.ndarray:
    """The matrix of ``gates`` on ``n`` qubits (qubit ``q`` is bit ``q`` of the basis index, as in the IR)."""
    from qcpp.ir.gates import unitary

    total = np.eye(1 << n, dtype=complex)
    for g in gates:
        u, qs = unitary(g), g[1]
        step = np.zeros((1 << n, 1 << n), dtype=complex)
        for col in range(1 << n):
            local = sum(((col >> q) & 1) << j for j, q in enumerate(qs))
            rest = col & ~sum(1 << q for q in qs)
            for row in range(1 << len(qs)):
                step[rest | sum(((row >> j) & 1) << q for j, q in enumerate(qs)), col] += u[row, local]
        total = step @ total
    return total


def test_each_native_form_is_its_gate_up_to_a_global_phase() -> None:
    """:func:`qcpp.routing.native.native_gates` of every gate a routed circuit holds, for every kind of device
    (two-qubit gate ``cz`` or ``rzz``, ``x`` native or not), is that gate up to a global phase, as a matrix. The
    QAOA circuits the routing tests compare commute with Z on every qubit, so a native form off by a Z on each
    side (``h`` written ``rz sx^dg rz``) leaves their states equal; the matrices do not."""
    from qcpp.hardware.device import device_names
    from qcpp.ir.gates import cz, rz, s, sdg, t, tdg, x
    from qcpp.routing.native import native_gates

    kinds = {(d.two_qubit_gate, "x" in d.native_gates) for d in map(get_device, device_names())}
    assert {twoq for twoq, _ in kinds} <= {"cz", "rzz"}
    gates = [x(0), h(0), h(1), t(0), tdg(1), s(0), sdg(1), rz(0.3, 1), rx(0.7, 0), cx(0, 1), cx(1, 0), cz(0, 1)]
    for twoq in ("cz", "rzz"):
        for native_x in (True, False):
            for g in gates:
                want, got = _matrix([g], 2), _matrix(native_gates(g, twoq, native_x), 2)
                phase = np.vdot(want.ravel(), got.ravel()) / 4
                assert abs(abs(phase) - 1) < 1e-9 and np.allclose(got, phase * want, atol=1e-9), (g, twoq, native_x)


@settings(max_examples=25, deadline=None)
@given(st.data())
def test_random_circuits_route_onto_any_device(data: st.DataObject) -> None:
    n = data.draw(st.integers(2, 7))
    pairs = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(lambda p: p[0] != p[1])
    gates: list[Gate] = []
    for a, b in data.draw(st.lists(pairs, min_size=1, max_size=25)):
        gates += [h(a), cx(a, b), rx(0.3 + a, b)]
    logical = Circuit([("data", n)], [Section("s", gates)])
    dev = get_device(data.draw(st.sampled_from(["grid:2x4", "grid:3x3", "heavy-hex:3"])))
    layout = data.draw(st.permutations(range(dev.num_qubits)))[:n]
    routed = route(logical, dev, layout, seed=data.draw(st.integers(0, 3)))
    assert _on_coupling(routed)
    assert routed.circuit.count_ops()["cx"] == logical.count_ops()["cx"] + 3 * routed.swaps - 2 * routed.num_fused
    _assert_equal_up_to_layouts(logical, routed, seed=0, global_phase=False)


@pytest.mark.parametrize(
    "s",
    [default_scenario(2, 3, 1), pytest.param(default_scenario(3, 3, 1), marks=pytest.mark.heavy)],  # 14, 21 qubits
    ids=["2x3/1", "3x3/1"],
)
def test_local_ancillas_keep_the_circuit_up_to_ancilla_renaming(s: Scenario) -> None:
    logical = compile_scenario(s, 1, PlanOptions(fuse=False), lowered=True, bindings=BIND).circuit
    local = localize_ancillas(logical, s, spare=6, local_cap=3)
    assert local.num_qubits > logical.num_qubits
    assert local.count_ops() == logical.count_ops()
    n = local.num_qubits
    rng = np.random.default_rng(3)
    data = logical.registers[0].size
    prefix = [ry(float(rng.uniform(0, 3)), q) for q in range(data)]
    want = _permuted(
        _statevector(logical, prefix, logical.num_qubits), logical.num_qubits, n, tuple(range(logical.num_qubits))
    )
    assert np.allclose(_statevector(local, prefix, n), want, atol=1e-9)


def test_compile_for_device_reports_layouts_and_fits_the_device() -> None:
    # greedy: the smallest lattice that holds the circuit (auto may keep the cell layout on heavy-hex:7 instead)
    s = default_scenario(3, 3, 1)
    r = compile_for_device(s, 1, "heavy-hex", bindings=BIND, lowered=True, layout_method="greedy")
    assert r.routed.device.name == "heavy-hex:3"
    assert _on_coupling(r.routed)
    summary = r.summary()
    assert summary["device"]["qubits"] == 19 and len(summary["initial_layout"]) == r.logical_qubits
    assert 0 < summary["routed"]["esp"] < 1 and summary["routed"]["duration_s"] > 0
    with pytest.raises(ValueError, match="needs 15 qubits"):
        compile_for_device(default_scenario(3, 3, 1), 1, "grid:3x3")


# --- ESP against Qiskit's own transpiled circuit -----------------------------------------------------------
def test_esp_matches_an_independent_computation_on_qiskits_transpiled_circuit() -> None:
    from qiskit_ibm_runtime.fake_provider import FakeFez  # the test extra has it: this runs wherever the tests do

    backend = FakeFez()
    device = named_device("ibm_fez")
    s = default_scenario(3, 3, 1)
    logical = compile_scenario(s, 1, lowered=True, bindings=BIND).circuit
    qc = to_qiskit(logical)
    from qiskit.transpiler import CouplingMap

    cmap = CouplingMap([list(e) for e in device.coupling] + [[b, a] for a, b in device.coupling])
    tqc = transpile(qc, coupling_map=cmap, basis_gates=["cz", "rz", "sx", "x"], optimization_level=1, seed_transpiler=0)
    final = tqc.layout.final_index_layout()
    data = range(s.num_variables)
    target = backend.target
    independent = 1.0
    ours: list[Gate] = []
    for inst in tqc.data:
        qs = tuple(tqc.find_bit(b).index for b in inst.qubits)
        name = inst.operation.name
        independent *= 1 - (target[name][qs].error or 0.0)
        if name == "sx":
            ours.append(rx(math.pi / 2, qs[0]))
        else:
            ours.append(Gate(name, qs, tuple(float(x) for x in inst.operation.params), None))
    for q in data:
        independent *= 1 - target["measure"][(final[q],)].error
    circuit = Circuit([("q", device.num_qubits)], [Section("s", ours)])
    routed = RoutedCircuit(circuit, device, tuple(range(len(final))), tuple(final), 0, tuple(data))
    assert esp(routed) == pytest.approx(independent, rel=1e-9)
    assert 0 < independent < 1


@pytest.mark.parametrize(
    ("gates", "ops"),
    [
        # a SWAP after a cx on the same pair (cx a b; SWAP = cx b a; cx a b)
        ([cx(0, 1), rx(0.4, 0), cx(0, 2)], [("cx", (0, 1)), ("swap", (0, 1)), ("cx", (1, 2))]),
        # a SWAP before a cx on the same pair; the pending h moves before the SWAP
        ([h(0), ry(0.3, 1), cx(0, 1), rx(0.5, 1)], [("swap", (0, 1)), ("cx", (1, 0))]),
    ],
    ids=["cx then swap", "swap then cx"],
)
def test_a_swap_next_to_a_cx_on_its_pair_is_fused(gates: list[Gate], ops: list) -> None:
    """Two CX for a SWAP and the CX beside it instead of four, and the circuit is unchanged up to the layouts."""
    from qcpp.routing.sabre import assemble

    logical = Circuit([("data", 3)], [Section("s", gates)])
    windows = ([0] * len(gates), [0] * len(ops))  # one window, as route_windows hands it over
    dev = get_device("grid:1x3")
    assert assemble(list(gates), ["s"] * len(gates), (0, 1, 2), 3, ops, dev, (0, 1, 2)).fused == ()  # route()
    routed = assemble(list(gates), ["s"] * len(gates), (0, 1, 2), 3, ops, dev, (0, 1, 2), None, windows)
    assert routed.fused == (("s", 1),) and routed.swaps == 1
    assert routed.circuit.count_ops()["cx"] == logical.count_ops()["cx"] + 3 - 2
    assert _on_coupling(routed)
    _assert_equal_up_to_layouts(logical, routed, seed=3, global_phase=False)


# --- memoised windows ----------------------------------------------------------------------------------------
@settings(max_examples=8, deadline=None)
@given(st.data())
def test_a_memoised_window_is_the_window_routed_afresh(data: st.DataObject) -> None:
    """route_window's memo (and the per-device patches and SABRE passes it reuses) changes nothing: a window routed
    again from a warm cache, or at the same physical pairs under other logical names, gives the ops of a cold
    routing, and replays the patches the routing saw into the context's open watches."""
    from qcpp.hardware.device import distances
    from qcpp.routing.context import RoutingContext
    from qcpp.routing.options import DEFAULT_ROUTING
    from qcpp.routing.windows import Positions, route_window

    dev = get_device(data.draw(st.sampled_from(["grid:4x4", "heavy-hex:3"])))
    dist = distances(dev)
    n = data.draw(st.integers(3, 8))
    homes = data.draw(st.permutations(range(dev.num_qubits)))[:n]
    k = data.draw(st.integers(1, 12))
    pairs = [tuple(data.draw(st.lists(st.integers(0, n - 1), min_size=2, max_size=2, unique=True))) for _ in range(k)]
    pairs += pairs[::-1]  # a compute and its mirror

    context = RoutingContext()

    def routed() -> tuple[list, set[int], int]:
        with context.watching() as watch:
            pos = Positions(tuple(homes), dev.num_qubits)
            ops = route_window(pairs, pos, dev, dist, 0, DEFAULT_ROUTING, context)  # type: ignore[arg-type]
        return ops, watch.qubits, watch.whole_component

    cold = routed()
    assert cold[1]  # the routing saw a patch
    assert routed() == cold  # warm: the memo's answer
    renamed = [(n - 1 - a, n - 1 - b) for a, b in pairs]  # the same physical pairs, the qubits named backwards
    pos = Positions(tuple(homes[::-1]), dev.num_qubits)
    assert route_window(renamed, pos, dev, dist, 0, DEFAULT_ROUTING, context) == cold[0]  # type: ignore[arg-type]


def _window_cx_reference(ops: list) -> int:
    """window_cx as first written: per SWAP, the op before it on both qubits or the next op on either."""
    nxt: list = [None] * len(ops)
    seen: dict[int, int] = {}
    for k in range(len(ops) - 1, -1, -1):
        found = [seen[q] for q in ops[k][1] if q in seen]
        nxt[k] = min(found) if found else None
        for q in ops[k][1]:
            seen[q] = k
    last: dict[int, int] = {}
    total = 0
    for k, (name, (p, q)) in enumerate(ops):
        total += 1
        if name == "swap":
            j = last.get(p)
            after = nxt[k] is not None and ops[nxt[k]][0] == "cx" and set(ops[nxt[k]][1]) == {p, q}
            total += 0 if (j is not None and j == last.get(q)) or after else 2
        last[p] = last[q] = k
    return total


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["cx", "swap"]), st.permutations(range(4)).map(lambda p: tuple(p[:2]))),
                max_size=14))  # fmt: skip
def test_window_cx_equals_its_reference(ops: list) -> None:
    from qcpp.routing.sabre import window_cx

    assert window_cx(ops) == _window_cx_reference(ops)


def test_window_cx_counts_the_cx_that_assemble_writes() -> None:
    """The searches score windows by :func:`window_cx` instead of assembling them: on every sequence of up to three
    ``cx`` and SWAP ops on the pairs of three qubits (routed in one window, so SWAPs fuse with a ``cx`` before or
    after them on their pair), it equals the ``cx`` that :func:`qcpp.routing.sabre.assemble` writes for the ops."""
    import itertools

    from qcpp.routing.sabre import assemble, window_cx

    device = get_device("grid:2x2")
    kinds = [(name, pair) for name in ("cx", "swap") for pair in ((0, 1), (1, 0), (1, 2), (0, 2))]
    for length in range(1, 4):
        for ops in itertools.product(kinds, repeat=length):
            who, gates = [0, 1, 2, 3], []  # identity layout; a SWAP moves the logical qubits it holds
            for name, (p, q) in ops:
                if name == "swap":
                    who[p], who[q] = who[q], who[p]
                else:
                    gates.append(cx(who[p], who[q]))
            windows = ([0] * len(gates), [0] * len(ops))
            routed = assemble(gates, ["s"] * len(gates), (0, 1, 2, 3), 4, list(ops), device, (), None, windows)
            written = sum(g.name == "cx" for g in routed.circuit.gates)
            assert window_cx(list(ops)) == written, ops


@settings(max_examples=20, deadline=None)
@given(st.data())
def test_the_direct_sabre_call_routes_as_the_sabreswap_pass(data: st.DataObject) -> None:
    """run_sabre (Qiskit's routing call with the arguments SabreSwap builds) gives the pass's own routing."""
    from qiskit import QuantumCircuit
    from qiskit.converters import circuit_to_dag, dag_to_circuit
    from qiskit.transpiler import PassManager
    from qiskit.transpiler.passes import SabreSwap

    from qcpp.routing.context import RoutingContext
    from qcpp.routing.patches import patch_sabre, run_sabre
    from qcpp.routing.routed_circuit import coupling_map

    dev = get_device(data.draw(st.sampled_from(["grid:3x3", "heavy-hex:3"])))
    size = dev.num_qubits
    qc = QuantumCircuit(size)
    for _ in range(data.draw(st.integers(1, 25))):
        a, b = data.draw(st.permutations(range(size)))[:2]
        qc.cx(a, b)
    seed, trials = data.draw(st.integers(0, 9)), data.draw(st.sampled_from([1, 4, 16]))
    shape = patch_sabre(RoutingContext(), tuple(dev.coupling), size)
    fast = dag_to_circuit(run_sabre(shape, circuit_to_dag(qc), seed, trials))
    reference = PassManager([SabreSwap(coupling_map(dev), heuristic="decay", seed=seed, trials=trials)]).run(qc)
    assert [(i.operation.name, [fast.find_bit(q).index for q in i.qubits]) for i in fast.data] == [
        (i.operation.name, [reference.find_bit(q).index for q in i.qubits]) for i in reference.data
    ]


def test_the_patch_radius_comes_from_the_options_and_a_cleared_context_routes_afresh() -> None:
    """RoutingOptions.window_radius decides the patches (qubits 0 and 4 of a line: within two couplings their
    neighbourhood connects them, within one it does not and the part is routed on the whole line), each setting
    memoised apart; a cleared RoutingContext forgets its memos and routes the window to the same ops."""
    from dataclasses import replace

    from qcpp.layout.placement import distances
    from qcpp.routing.context import RoutingContext
    from qcpp.routing.options import DEFAULT_ROUTING
    from qcpp.routing.windows import Positions, route_window

    dev = get_device("grid:1x9")
    dist = distances(dev)
    pairs = [(0, 4), (0, 4)]
    context = RoutingContext()
    with context.watching() as wide:
        ops = route_window(pairs, Positions.identity(9), dev, dist, 0, DEFAULT_ROUTING, context)  # type: ignore[arg-type]
    with context.watching() as narrow:
        route_window(pairs, Positions.identity(9), dev, dist, 0, replace(DEFAULT_ROUTING, window_radius=1), context)  # type: ignore[arg-type]
    assert wide.whole_component == 0 and wide.qubits == set(range(7))
    assert narrow.whole_component > 0 and narrow.qubits == set(range(9))
    assert context.windows and context.patch_indexes
    context.clear()
    assert not context.windows and not context.patch_indexes
    assert route_window(pairs, Positions.identity(9), dev, dist, 0, DEFAULT_ROUTING, context) == ops  # type: ignore[arg-type]
