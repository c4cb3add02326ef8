"""Noise-aware placement of a routed circuit on a calibrated device: the same gates on better qubits.

A routed circuit uses a subgraph of a coupling graph (the couplers its two-qubit gates act on). Any embedding of
that subgraph into a device's coupling graph runs the same gates, with the same SWAPs, on other qubits and
couplers; on a calibrated device (per-qubit and per-coupler errors, T1 / T2) some embeddings are far better than
others. :func:`embedding_sites` searches them with rustworkx's VF2 (the subgraph isomorphism Qiskit's ``VF2Layout``
and ``VF2PostLayout`` use) from every device qubit as an anchor, scoring each by our own ESP model rather than
Qiskit's average-error heuristic. :func:`post_layout` keeps, of the best found on the circuit's own device, the one
of the highest ESP (:func:`log_score`: with idle decoherence where the device has T1 / T2), or the circuit as it
was if none is better. The circuit may also be routed on another lattice (the heavy-hex cells on ``heavy-hex:D``,
which :mod:`qcpp.pipeline.candidates` places on IBM's devices). A relabelled circuit is the routed circuit with
every physical qubit renamed (:func:`qcpp.routing.routed_circuit.embed_routed`): gate for gate the same, so equal to
the input up to the new layouts.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx, h
    >>> from qcpp.routing.native import esp, to_native
    >>> from qcpp.routing.sabre import route
    >>> dev = get_device("ibm_fez")
    >>> c = Circuit([("data", 3)], [Section("s", [h(0), cx(0, 1), cx(1, 2)])])
    >>> r = to_native(route(c, dev, (0, 1, 2)))
    >>> better = post_layout(r)
    >>> esp(better) >= esp(r), better.circuit.count_ops() == r.circuit.count_ops()
    (True, True)
"""

from __future__ import annotations

import itertools
import math
from functools import cache
from typing import Any

from qcpp.hardware.device import Device
from qcpp.routing.native import esp, esp_idle, idle_times_s, one_qubit_name
from qcpp.routing.routed_circuit import RoutedCircuit, embed_routed

__all__ = [
    "EMBEDDINGS_KEPT", "MAPPINGS_PER_ANCHOR", "MAX_PATTERN_QUBITS", "embedding_sites", "embeddings",
    "log_score", "post_layout",
]

EMBEDDINGS_KEPT = 2
"""Embeddings :func:`embedding_sites` returns (its model's best; the caller rescoring them exactly)."""

MAPPINGS_PER_ANCHOR = 10
"""Embeddings VF2 enumerates per anchor qubit."""

MAX_PATTERN_QUBITS = 64
"""Circuits using more qubits get no search (they fill most of a device: few embeddings exist, and VF2 from every
anchor would cost seconds each)."""


def log_score(routed: RoutedCircuit) -> float:
    """Natural log of the ESP :func:`post_layout` maximises: with idle decoherence where the device has T1 / T2."""
    gate_esp = esp(routed)
    value = esp_idle(routed, gate_esp=gate_esp)
    value = gate_esp if value is None else value
    return math.log(value) if value > 0 else -math.inf


def embeddings(routed: RoutedCircuit, device: Device, keep: int = EMBEDDINGS_KEPT) -> list[RoutedCircuit]:
    """``routed`` written on ``device`` at each of :func:`embedding_sites`."""
    return [embed_routed(routed, device, sites) for sites in embedding_sites(routed, device, keep)]


def embedding_sites(
    routed: RoutedCircuit, device: Device, keep: int = EMBEDDINGS_KEPT, per_anchor: int = MAPPINGS_PER_ANCHOR,
    call_limit: int = 200_000, found_memo: dict[Any, list[tuple[int, ...]]] | None = None,
) -> list[tuple[int, ...]]:  # fmt: skip
    """The ``keep`` best-scoring embeddings found of ``routed``'s coupling subgraph in ``device`` (module docs),
    best first, as ``sites``: qubit ``i`` of ``routed`` -> qubit of ``device``, distinct on the qubits ``routed``
    uses (its gates and layouts); the qubits it leaves unused fill the free sites in order, repeating them where
    ``routed`` (on a larger lattice) has more qubits than ``device``: they carry no gates. Empty if none is found,
    or ``routed`` uses more qubits than ``device`` has or than :data:`MAX_PATTERN_QUBITS`.

    The search: the circuit's qubits (those its gates or layouts touch) are ordered breadth-first from the busiest;
    for every device qubit as the anchor of the first, rustworkx's VF2 (the subgraph isomorphism Qiskit's
    ``VF2Layout`` / ``VF2PostLayout`` run) enumerates up to ``per_anchor`` embeddings with the device's qubits
    ordered breadth-first from that anchor (so each anchor explores its own region), and every embedding is scored
    by :func:`log_score`'s model computed per qubit and coupler with the idle times of ``routed`` itself (gate
    durations differ little between qubits): ``sum count * log(1 - error)`` over couplers and one-qubit gates,
    readout of the measured qubits, and the idle factor with the anchor region's T1 / T2.

    ``found_memo`` (a dict the caller owns, for one device): the embeddings VF2 enumerated, keyed by the circuit's
    qubit order and coupling subgraph, which are all they depend on. Several circuits on the same couplers (a routing
    before and after one-qubit merging) then share one search and are scored each by its own gates.
    """
    import numpy as np
    import rustworkx as rx

    n = device.num_qubits
    m = routed.circuit.num_qubits
    used_set = {q for g in routed.circuit.gates for q in g[1]} | set(routed.initial_layout) | set(routed.final_layout)
    if device.is_all_to_all or len(used_set) > min(n, MAX_PATTERN_QUBITS):
        return []
    pairs: dict[tuple[int, int], int] = {}
    ones: dict[str, dict[int, int]] = {}
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            key = (min(qs), max(qs))
            pairs[key] = pairs.get(key, 0) + 1
        elif g[0] != "rz":
            name = one_qubit_name(device, g)
            ones.setdefault(name, {})
            ones[name][qs[0]] = ones[name].get(qs[0], 0) + 1
    adjacency: dict[int, set[int]] = {q: set() for q in used_set}
    for a, b in pairs:
        adjacency[a].add(b)
        adjacency[b].add(a)
    order = _bfs_order(adjacency)
    pos = {q: i for i, q in enumerate(order)}
    pattern = rx.PyGraph()
    pattern.add_nodes_from(range(len(order)))
    pattern.add_edges_from_no_data([(pos[a], pos[b]) for a, b in pairs])
    # per-site costs
    log2 = np.full((n, n), -np.inf)
    for (a, b), e in zip(device.coupling, device.error_2q, strict=True):
        log2[a, b] = log2[b, a] = math.log1p(-e) if e < 1 else -np.inf
    e1 = dict(device.error_1q)
    u = np.array([pos[a] for a, b in pairs], dtype=int)
    v = np.array([pos[b] for a, b in pairs], dtype=int)
    counts = np.array(list(pairs.values()), dtype=float)
    site_cost = [(np.log1p(-np.array(e1[name])), np.array([per.get(q, 0) for q in order], dtype=float))
                 for name, per in ones.items()]  # fmt: skip
    measured = np.zeros(len(order))
    for lq in routed.measured:
        measured[pos[routed.final_layout[lq]]] = 1.0
    log_ro = np.log1p(-np.array(device.readout_error))
    idle = idle_times_s(routed)
    idle_v = np.array([0.0 if idle is None else idle[q] for q in order])
    t1 = np.array([np.inf if t is None else t for t in device.t1_s or (None,) * n])
    t2 = np.minimum(np.array([np.inf if t is None else t for t in device.t2_s or (None,) * n]), 2 * t1)

    def score(maps: Any) -> Any:
        total = (counts * log2[maps[:, u], maps[:, v]]).sum(axis=1)
        for log_e, per in site_cost:
            total += (per * log_e[maps]).sum(axis=1)
        total += (measured * log_ro[maps]).sum(axis=1)
        if device.t1_s is not None and idle is not None:
            fid = (3 + np.exp(-idle_v / t1[maps]) + 2 * np.exp(-idle_v / t2[maps])) / 6
            total += np.log(fid).sum(axis=1)
        return total

    memo_key = (tuple(order), tuple(sorted((pos[a], pos[b]) for a, b in pairs)), per_anchor, call_limit)
    found = None if found_memo is None else found_memo.get(memo_key)
    if found is None:
        found = []
        for dev_order, graph in _anchor_graphs(device):
            if len(dev_order) < len(order):
                continue
            maps = rx.vf2_mapping(graph, pattern, subgraph=True, induced=False, id_order=True, call_limit=call_limit)
            for k, mapping in enumerate(maps):
                if k >= per_anchor:
                    break
                site = [0] * len(order)
                for dev_node, pat_node in mapping.items():
                    site[pat_node] = dev_order[dev_node]
                found.append(tuple(site))
        if found_memo is not None:
            found_memo[memo_key] = found
    if not found:
        return []
    arr = np.array(sorted(set(found)), dtype=int)
    scores = score(arr)
    best = np.argsort(-scores, kind="stable")[:keep]
    out = []
    for row in best:
        placed = {q: int(arr[row, pos[q]]) for q in order}
        free = itertools.cycle(sorted(set(range(n)) - set(placed.values())) or [placed[order[0]]])
        out.append(tuple(placed[i] if i in placed else next(free) for i in range(m)))
    return out


@cache
def _anchor_graphs(device: Device) -> tuple[tuple[tuple[int, ...], Any], ...]:
    """Per anchor qubit of ``device``: its qubits breadth-first from that anchor (:func:`_bfs_from`) and the coupling
    graph with node ``i`` the ``i``-th of them (so VF2 with ``id_order`` explores the anchor's region first).
    Memoised per device (a frozen value): every search on a device reads the same graphs, never changes them."""
    import rustworkx as rx

    adjacency: dict[int, list[int]] = {q: [] for q in range(device.num_qubits)}
    for a, b in device.coupling:
        adjacency[a].append(b)
        adjacency[b].append(a)
    out = []
    for anchor in range(device.num_qubits):
        dev_order = _bfs_from(adjacency, anchor)
        at = {q: i for i, q in enumerate(dev_order)}
        graph = rx.PyGraph()
        graph.add_nodes_from(range(len(dev_order)))
        graph.add_edges_from_no_data([(at[a], at[b]) for a, b in device.coupling])
        out.append((tuple(dev_order), graph))
    return tuple(out)


def _bfs_order(adjacency: dict[int, set[int]]) -> list[int]:
    """Every node, breadth-first from the one of most neighbours, component by component (busiest first)."""
    order: list[int] = []
    seen: set[int] = set()
    for root in sorted(adjacency, key=lambda q: (-len(adjacency[q]), q)):
        if root in seen:
            continue
        seen.add(root)
        queue = [root]
        while queue:
            q = queue.pop(0)
            order.append(q)
            for r in sorted(adjacency[q], key=lambda x: (-len(adjacency[x]), x)):
                if r not in seen:
                    seen.add(r)
                    queue.append(r)
    return order


def _bfs_from(adjacency: dict[int, list[int]], root: int) -> list[int]:
    """The device's qubits breadth-first from ``root``, then the rest of the device in index order."""
    order, seen, queue = [], {root}, [root]
    while queue:
        q = queue.pop(0)
        order.append(q)
        for r in sorted(adjacency[q]):
            if r not in seen:
                seen.add(r)
                queue.append(r)
    return order + [q for q in range(len(adjacency)) if q not in seen]


def post_layout(routed: RoutedCircuit, keep: int = EMBEDDINGS_KEPT) -> RoutedCircuit:
    """``routed`` (native gates) moved onto the best embedding found of its coupling subgraph on its own device by
    :func:`log_score`, or ``routed`` itself where none scores higher (module docs)."""
    best, best_score = routed, log_score(routed)
    for moved in embeddings(routed, routed.device, keep):
        score = log_score(moved)
        if score > best_score:
            best, best_score = moved, score
    return best
