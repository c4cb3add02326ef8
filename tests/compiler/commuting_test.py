"""The commuting-phase router: every block runs once with its qubits adjacent, routed windows stay exact, and a
window never routes to more CX with it than without it."""

from __future__ import annotations

import dataclasses

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.api.scenarios import grid_scenario
from qcpp.hardware.device import distances, get_device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cx, h, rx, rz, s, t
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.routing.commuting import commuting_blocks, graph_distances, route_blocks
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.windows import Positions, route_window, route_windows
from tests.compiler.routing_test import _assert_equal_up_to_layouts, _on_coupling

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
WITHOUT = dataclasses.replace(DEFAULT_ROUTING, commuting_phases=False)


def _neighbours(device: str) -> list[list[int]]:
    dev = get_device(device)
    out: list[list[int]] = [[] for _ in range(dev.num_qubits)]
    for a, b in dev.coupling:
        out[a].append(b)
        out[b].append(a)
    return out


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_every_block_runs_once_with_its_qubits_adjacent(data: st.DataObject) -> None:
    neighbours = _neighbours(data.draw(st.sampled_from(["grid:1x6", "grid:3x3", "grid:4x5", "heavy-hex:3"])))
    n = len(neighbours)
    nodes = st.integers(0, n - 1)
    pairs = data.draw(st.lists(st.tuples(nodes, nodes).filter(lambda p: p[0] != p[1]), min_size=1, max_size=30))
    events = route_blocks(pairs, neighbours)
    dist = graph_distances(neighbours)
    holder = list(range(n))  # node -> the qubit that started on it
    at = list(range(n))
    ran: list[int] = []
    k = 0
    while k < len(events):
        name, arg = events[k]
        if name == "swap":
            u, v = arg
            assert v in neighbours[u] and u < v
            holder[u], holder[v] = holder[v], holder[u]
            at[holder[u]], at[holder[v]] = u, v
            k += 1
            continue
        assert arg % 2 == 0 and events[k + 1] == ("gate", arg + 1)  # a block's two cx run together
        a, b = pairs[arg // 2]
        assert dist[at[a]][at[b]] == 1
        ran.append(arg // 2)
        k += 2
    assert sorted(ran) == list(range(len(pairs)))
    assert route_blocks(pairs, neighbours, dist) == events  # a pure function of its arguments


def test_a_middle_with_a_non_diagonal_gate_or_an_unpaired_cx_is_not_a_commuting_run() -> None:
    compute = [h(0), cx(0, 1), cx(1, 2)]
    uncompute = [cx(1, 2), cx(0, 1), h(0)]
    blocks = [cx(0, 3), rz(0.2, 3), t(0), cx(0, 3), s(1), cx(1, 3), rz(0.4, 3), cx(1, 3)]
    assert commuting_blocks(compute + blocks + uncompute, 2) == ((3, 6), (8, 10))
    assert commuting_blocks(compute + blocks[:2] + [h(3)] + blocks[2:] + uncompute, 2) is None  # h between
    assert commuting_blocks(compute + blocks[:-1] + uncompute, 2) is None  # an unpaired cx
    assert commuting_blocks([*compute, cx(0, 3), rz(0.1, 3), cx(3, 0), *uncompute], 2) is None  # not the same cx
    assert commuting_blocks(compute + uncompute, 2) is None  # no middle


@settings(max_examples=40, deadline=None)
@given(st.data())
def test_windows_with_commuting_middles_stay_exact_and_never_route_to_more(data: st.DataObject) -> None:
    """A compute of cx and Hadamards, its mirror, and between them blocks with diagonal gates: routed with and
    without the commuting router from random homes, both equal the logical circuit (statevectors, up to the
    layouts) and the commuting one has at most the other's CX."""
    n = data.draw(st.integers(3, 7))
    qubit = st.integers(0, n - 1)
    pair = st.tuples(qubit, qubit).filter(lambda p: p[0] != p[1])
    compute: list[Gate] = []
    for a, b in data.draw(st.lists(pair, max_size=6)):
        compute += [h(a), cx(a, b)]
    middle: list[Gate] = []
    for a, b in data.draw(st.lists(pair, min_size=1, max_size=14)):
        middle += [rz(0.1 + a, a), cx(a, b), rz(0.3 + b, b), cx(a, b)]
    gates = compute + middle + compute[::-1]
    logical = Circuit([("data", n)], [Section("phase", gates), Section("mixer", [rx(0.5, q) for q in range(n)])])
    device = get_device(data.draw(st.sampled_from(["grid:3x3", "grid:2x4", "heavy-hex:3"])))
    layout = tuple(data.draw(st.permutations(range(device.num_qubits)))[:n])
    counts = []
    for options in (DEFAULT_ROUTING, WITHOUT):
        routed = route_windows(logical, device, layout, options=options, context=RoutingContext())
        assert _on_coupling(routed) and routed.final_layout == layout
        _assert_equal_up_to_layouts(logical, routed, seed=0, global_phase=False)
        counts.append(routed.circuit.count_ops().get("cx", 0))
    assert counts[0] <= counts[1]


def test_the_balance_windows_route_to_fewer_cx_with_the_commuting_router() -> None:
    """The register phase of the balance arithmetic (45 blocks on 10 bits) on 4x4/2 with a hard obstacle: fewer CX
    on the grid, the same one-qubit gates."""
    scenario = grid_scenario(4, 4, robots=2, obstacles=[(1, 2)], hard_obstacles=True)
    results = []
    for options in (DEFAULT_ROUTING, WITHOUT):
        r = compile_for_device(scenario, 1, "grid", lowered=True, bindings=BIND, routing=options)
        results.append(r.routed.circuit)
    with_, without = (c.count_ops() for c in results)
    assert with_.pop("cx") < without.pop("cx")
    assert with_ == without  # the same one-qubit gates


@pytest.mark.parametrize("device", ["grid:4x4", "heavy-hex:3"])
def test_a_commuting_window_is_memoised_apart_from_the_same_pairs_routed_in_order(device: str) -> None:
    """One context answers the window as a commuting one and as an ordered one, each as a fresh context does, and
    without the option a commuting window routes as an ordered one."""
    dev = get_device(device)
    dist = distances(dev)
    blocks = [p for p in ((0, 3), (1, 4), (2, 3), (0, 4), (3, 4)) for _ in range(2)]
    pairs = [(0, 1), (1, 2), *blocks, (1, 2), (0, 1)]
    homes = tuple(range(0, 2 * 5, 2))

    def routed(context: RoutingContext, options: RoutingOptions, commuting: bool) -> list:
        pos = Positions(homes, dev.num_qubits)
        return route_window(pairs, pos, dev, dist, 0, options, context, commuting)  # type: ignore[arg-type]

    context = RoutingContext()
    ordered = routed(context, DEFAULT_ROUTING, False)
    assert routed(context, DEFAULT_ROUTING, True) == routed(RoutingContext(), DEFAULT_ROUTING, True)
    assert routed(RoutingContext(), WITHOUT, True) == ordered
