"""The layout bound's pieces: path lengths on heavy-hex lattices, distances on grids, the kind sum, the placement."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from qcpp.estimators.layout_bound import (
    PlacedBlock,
    bound_plan,
    gate_distances,
    hex_path_lengths,
    layout_twoq_bound,
    placed_blocks,
)
from qcpp.hardware.device import Device, distances, get_device
from qcpp.layout.medial import medial_placement
from qcpp.lowering.passes import lower
from qcpp.pipeline.device_compile import layout_device
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.plan.qaoa import QaoaPlan
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario
from qcpp.routing.context import RoutingContext
from tests.compiler.conftest import scenarios


def _all_pairs(n: int) -> tuple[np.ndarray, np.ndarray]:
    a, b = np.divmod(np.arange(n * n), n)
    return a, b


@pytest.mark.parametrize("d", [3, 5, 7, 9])
def test_heavy_hex_paths_are_never_shorter_than_the_distance_and_mostly_equal(d: int) -> None:
    dev = get_device(f"heavy-hex:{d}")
    a, b = _all_pairs(dev.num_qubits)
    exact = distances(dev)[a, b]
    lengths = hex_path_lengths(d, a, b)
    assert (lengths >= exact).all()  # a path: the bound stays sound
    assert (lengths == exact).mean() > 0.85 and lengths.sum() <= 1.03 * exact.sum()
    assert (lengths[exact == 1] == 1).all() and (lengths[a == b] == 0).all()


def test_a_path_one_step_shorter_would_be_caught() -> None:
    dev = get_device("heavy-hex:5")
    a, b = _all_pairs(dev.num_qubits)
    assert not (hex_path_lengths(5, a, b) - 1 >= distances(dev)[a, b]).all()


@pytest.mark.parametrize("name", ["grid:4x6", "heavy-hex:7", "ibm_torino"])
def test_gate_distances_are_at_least_breadth_first_distances(name: str) -> None:
    dev = get_device(name)
    a, b = _all_pairs(dev.num_qubits)
    exact = distances(dev)[a, b]
    joined = np.isfinite(exact)  # a calibration snapshot may be in pieces
    a, b, exact = a[joined], b[joined], exact[joined]
    got = gate_distances(dev, a, b)
    assert (got >= exact).all()
    if not name.startswith("heavy-hex"):
        assert (got == exact).all()


def _free_nearest(start: int, neighbours: dict[int, list[int]], homes: set[int], taken: set[int]) -> int:
    """Breadth first from ``start``, neighbours in index order: the first qubit neither a home nor taken."""
    order, seen = [start], {start}
    for u in order:
        if u not in homes and u not in taken:
            return u
        for v in neighbours[u]:
            if v not in seen:
                seen.add(v)
                order.append(v)
    raise AssertionError("no free qubit")


def _reference_bound(scenario: Scenario, p: int, dev: Device, options: PlanOptions = DEFAULT_PLAN) -> int:
    """The module docs' placement written out on every lowered section of the ``p``-layer circuit, gate by gate:
    no kinds, no layers counted ``p`` times."""
    homes = medial_placement(scenario, dev)
    assert homes is not None
    n = len(homes)
    neighbours: dict[int, list[int]] = {q: [] for q in range(dev.num_qubits)}
    for x, y in dev.coupling:
        neighbours[x].append(y)
        neighbours[y].append(x)
    neighbours = {q: sorted(set(vs)) for q, vs in neighbours.items()}
    first, second = [], []
    for sec in lower(bound_plan(scenario, p, options, dev).circuit()).sections:
        placed: dict[int, int] = {}
        first_data = next((q for g in sec.gates for q in g[1] if q < n), 0)
        for g in sec.gates:
            for q in g[1]:
                if q >= n and q not in placed:
                    near = next((x for x in g[1] if x != q and (x < n or x in placed)), first_data)
                    at = homes[near] if near < n else placed[near]
                    placed[q] = _free_nearest(at, neighbours, set(homes), set(placed.values()))
            if len(g[1]) == 2:
                x, y = (homes[q] if q < n else placed[q] for q in g[1])
                first.append(x)
                second.append(y)
    d = gate_distances(dev, np.array(first, dtype=np.int64), np.array(second, dtype=np.int64))
    return int((1 + 6 * (d - 1)).sum())


@pytest.mark.parametrize(("shape", "device", "p"), [((3, 3, 2), "grid", 3), ((2, 3, 1), "heavy-hex", 2)])
def test_the_kind_sum_is_the_placement_of_every_section(shape: tuple[int, int, int], device: str, p: int) -> None:
    """Kind by kind, one layer counted ``p`` times: the same as placing every section of the ``p``-layer circuit."""
    s = default_scenario(*shape)
    dev = layout_device(s, device)
    assert dev is not None
    assert layout_twoq_bound(bound_plan(s, p, PlanOptions(), dev), dev) == _reference_bound(s, p, dev)


@pytest.mark.parametrize("p", [1, 3])
def test_the_kind_sum_without_the_first_phase_separator_is_the_placement_of_every_section(p: int) -> None:
    """Layer 1's phase separator counted ``p - 1`` times, layer 0's mixer ``p`` times: the ``p``-layer circuit."""
    s, options = default_scenario(3, 3, 2), PlanOptions(first_phase=False)
    dev = layout_device(s, "grid")
    assert dev is not None
    bound = layout_twoq_bound(bound_plan(s, p, options, dev), dev)
    assert bound == _reference_bound(s, p, dev, options) < _reference_bound(s, p, dev)


@given(scenarios(max_side=4, max_robots=2), st.integers(0, 2), st.sampled_from(["grid", "heavy-hex"]))
@settings(max_examples=8)
def test_the_kind_sum_is_the_placement_of_every_section_on_random_scenarios(s: Scenario, p: int, device: str) -> None:
    dev = layout_device(s, device)
    assume(dev is not None and medial_placement(s, dev) is not None)
    assert dev is not None
    assert layout_twoq_bound(bound_plan(s, p, PlanOptions(), dev), dev) == _reference_bound(s, p, dev)


def _placed(shape: tuple[int, int, int], device: str, p: int) -> tuple[Device, tuple[int, ...], QaoaPlan]:
    """The default scenario of ``shape`` on the ``device`` family sized for it: the device, the medial placement's
    homes and the bound's plan of ``p`` layers."""
    s = default_scenario(*shape)
    dev = layout_device(s, device)
    assert dev is not None
    homes = medial_placement(s, dev)
    assert homes is not None
    return dev, homes, bound_plan(s, p, PlanOptions(), dev)


def _gates(block: PlacedBlock) -> list[tuple[int, int, int]]:
    """A placed section's two-qubit gates: ``(device qubit, device qubit, how many)``, sorted."""
    pairs = block.where[block.route.pairs].tolist()
    return sorted((a, b, int(n)) for (a, b), n in zip(pairs, block.route.counts, strict=True))


def test_each_kind_is_routed_once_and_its_route_serves_every_gadget_of_the_kind() -> None:
    dev, homes, plan = _placed((4, 4, 2), "grid", 2)
    context = RoutingContext()
    shared = placed_blocks(plan, homes, dev, context.kind_routes)
    first = list(plan.sections(layers=1))
    assert [n for n, _ in first] == [n for n, _ in plan.sections()][: len(first)]
    assert {n for n, _ in first} == {"initial_state", "phase_0", "mixer_0"}
    gadgets = [g for _, g in first]
    assert len(context.kind_routes) == len({g.kind for g in gadgets}) < len(gadgets)

    class Forgetful(dict):  # type: ignore[type-arg]
        def __setitem__(self, key: object, value: object) -> None:
            pass  # every gadget gets a route read from its own gates

    own = placed_blocks(plan, homes, dev, Forgetful())
    assert shared is not None and own is not None and len(shared) == len(own)
    for x, y in zip(shared, own, strict=True):
        assert x.multiplicity == y.multiplicity
        assert _gates(x) == _gates(y)
    before = len(context.kind_routes)
    assert layout_twoq_bound(plan, dev, context) is not None and len(context.kind_routes) == before


def test_every_section_gets_distinct_free_qubits_for_its_ancillas() -> None:
    """The placement the charges use: data at their homes, ancillas on qubits no data qubit and no other ancilla
    of the section holds; every two-qubit gate of the circuit is charged once, at 1 + 6 (d - 1)."""
    dev, homes, plan = _placed((3, 3, 2), "grid", 2)
    blocks = placed_blocks(plan, homes, dev)
    assert blocks is not None
    dist = distances(dev)
    total = charged = 0
    for block in blocks:
        where, route = block.where, block.route
        assert len(set(where.tolist())) == len(where)  # one place per qubit in a section
        assert set(where[route.data].tolist()) <= set(homes)
        ancillas = np.setdiff1d(np.arange(len(where)), route.data)
        assert not set(where[ancillas].tolist()) & set(homes)
        a, b = where[route.pairs[:, 0]], where[route.pairs[:, 1]]
        total += block.multiplicity * int(route.counts.sum())
        charged += block.multiplicity * int((route.counts * (1 + 6 * (dist[a, b] - 1))).sum())
    assert total == plan.cost().two_qubit
    assert charged == layout_twoq_bound(plan, dev)


def _swap_chain_routing(device_coupling: tuple[tuple[int, int], ...], n: int, pairs: np.ndarray) -> int:
    """Route every gate of ``pairs`` (physical qubits, in order) as the bound says: SWAP the first qubit's state
    along a shortest path (networkx) until it is next to the second's, apply the gate, SWAP back. Checks every
    SWAP and gate is on a coupling and the layout is back after each gate; returns the CX count (3 per SWAP)."""
    import networkx as nx

    graph = nx.Graph(device_coupling)
    edges = {frozenset(e) for e in device_coupling}
    state = list(range(n))  # physical qubit -> whose state it holds
    cx = 0
    for x, y in pairs.tolist():
        path = nx.shortest_path(graph, x, y)
        swaps = list(zip(path[:-2], path[1:-1], strict=True))  # x's state walks to the qubit next to y
        for u, v in swaps:
            assert frozenset((u, v)) in edges
            state[u], state[v] = state[v], state[u]
        at = path[-2]  # the qubit next to y, now holding x's state
        assert state[at] == x and frozenset((at, y)) in edges
        for u, v in reversed(swaps):
            state[u], state[v] = state[v], state[u]
        cx += 1 + 2 * 3 * len(swaps)
        assert state == list(range(n))  # the layout is back: the next gate starts from the placement
    return cx


@pytest.mark.parametrize(("shape", "device"), [((2, 3, 1), "grid"), ((2, 3, 1), "heavy-hex")])
def test_the_swap_chain_routing_of_the_placement_costs_at_most_the_bound(
    shape: tuple[int, int, int], device: str
) -> None:
    """Built gate by gate from the placement (an independent shortest-path routine), the routing the bound
    describes is valid and costs exactly the bound on a grid, at most it on heavy-hex (path lengths)."""
    dev, homes, plan = _placed(shape, device, 1)
    blocks = placed_blocks(plan, homes, dev)
    assert blocks is not None
    pairs = np.concatenate([np.repeat(x.where[x.route.pairs], x.multiplicity * x.route.counts, axis=0) for x in blocks])
    bound = layout_twoq_bound(plan, dev)
    routed = _swap_chain_routing(dev.coupling, dev.num_qubits, pairs)
    assert routed == bound if device == "grid" else routed <= bound
