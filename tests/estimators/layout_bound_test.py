"""The layout bound's pieces: path lengths on heavy-hex lattices, distances on grids, layers, the placement."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from qcpp.estimators.layout_bound import gate_distances, hex_path_lengths, layout_twoq_bound, section_charges
from qcpp.hardware.device import distances, get_device
from qcpp.lowering.passes import lower
from qcpp.pipeline.device_compile import layout_device
from qcpp.pipeline.device_plan import device_plan_options
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.presets import default_scenario


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


@pytest.mark.parametrize(("shape", "device"), [((3, 3, 2), "grid"), ((2, 3, 1), "heavy-hex")])
def test_later_layers_cost_what_the_first_costs(shape: tuple[int, int, int], device: str) -> None:
    """The bound builds one layer and counts it p times: the same as placing every section of the p-layer
    circuit."""
    s = default_scenario(*shape)
    dev = layout_device(s, device)
    assert dev is not None
    from qcpp.layout.medial import medial_placement

    plan = device_plan_options(PlanOptions(), dev)
    homes = medial_placement(s, dev)
    assert homes is not None
    circuit = lower(qaoa_plan(s, 3, replace(plan, fuse=False)).circuit())
    charges = section_charges(circuit.sections, homes, dev)
    assert charges is not None
    assert layout_twoq_bound(s, 3, PlanOptions(), dev) == sum(c for _, c in charges)


def test_every_section_gets_distinct_free_qubits_for_its_ancillas(monkeypatch: pytest.MonkeyPatch) -> None:
    """The placement the charges use: data at their homes, ancillas on qubits no data qubit and no other ancilla
    of the section holds, each gate charged 1 + 6 (d - 1) at its distance there."""
    from qcpp.estimators import layout_bound

    s = default_scenario(3, 3, 2)
    dev = layout_device(s, "grid")
    assert dev is not None
    from qcpp.layout.medial import medial_placement

    homes = medial_placement(s, dev)
    assert homes is not None
    circuit = lower(qaoa_plan(s, 1, replace(device_plan_options(PlanOptions(), dev), fuse=False)).circuit())
    seen: list[tuple[np.ndarray, np.ndarray]] = []
    real = layout_bound.gate_distances

    def spy(device, a, b):  # type: ignore[no-untyped-def]
        seen.append((a, b))
        return real(device, a, b)

    monkeypatch.setattr(layout_bound, "gate_distances", spy)
    charges = section_charges(circuit.sections, homes, dev)
    assert charges is not None
    a, b = seen[0]
    dist = distances(dev)
    assert (a != b).all()
    assert sum(c for _, c in charges) == int((1 + 6 * (dist[a, b] - 1)).sum())
    start = 0
    n_data = len(homes)
    for sec in circuit.sections:  # map each section's qubits back through the gates' order
        pairs = [g[1] for g in sec.gates if len(g[1]) == 2]
        where: dict[int, int] = {}
        for (x, y), pa, pb in zip(pairs, a[start : start + len(pairs)], b[start : start + len(pairs)], strict=True):
            for q, at in ((x, int(pa)), (y, int(pb))):
                assert where.setdefault(q, at) == at  # one place per qubit in a section
        start += len(pairs)
        for q, at in where.items():
            if q < n_data:
                assert at == homes[q]
            else:
                assert at not in homes
        assert len(set(where.values())) == len(where)
    assert start == len(a)


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
    monkeypatch: pytest.MonkeyPatch, shape: tuple[int, int, int], device: str
) -> None:
    """Built gate by gate from the placement (an independent shortest-path routine), the routing the bound
    describes is valid and costs exactly the bound on a grid, at most it on heavy-hex (path lengths)."""
    from qcpp.estimators import layout_bound
    from qcpp.layout.medial import medial_placement

    s = default_scenario(*shape)
    dev = layout_device(s, device)
    assert dev is not None
    homes = medial_placement(s, dev)
    assert homes is not None
    plan = device_plan_options(PlanOptions(), dev)
    circuit = lower(qaoa_plan(s, 1, replace(plan, fuse=False)).circuit())
    seen: list[tuple[np.ndarray, np.ndarray]] = []
    real = layout_bound.gate_distances
    monkeypatch.setattr(layout_bound, "gate_distances", lambda d, a, b: seen.append((a, b)) or real(d, a, b))
    charges = section_charges(circuit.sections, homes, dev)
    assert charges is not None
    bound = sum(c for _, c in charges)
    assert bound == layout_twoq_bound(s, 1, PlanOptions(), dev)
    routed = _swap_chain_routing(dev.coupling, dev.num_qubits, np.stack(seen[0], axis=1))
    assert routed == bound if device == "grid" else routed <= bound
