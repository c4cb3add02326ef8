"""Our qubit allocation and placement for a device: local ancillas per region, then an interaction-driven layout.

Two passes on an emitted, lowered circuit (plain functions, ``circuit -> circuit`` and ``circuit -> layout``):

* :func:`localize_ancillas` gives the gadgets local ancillas. Every gadget is its own section and returns its
  ancillas to |0> at both ends (``docs/architecture.md``, "Sections"; compile with ``fuse=False`` so that every
  partial mixer is a section of its own: fused mixer junction runs are clean only at their ends), so a section's
  ancillas may be *any* clean qubits. Small sections (at most ``local_cap`` ancillas: the partial mixers and the
  per-node phase gadgets) are grouped into regions by the grid position of their data qubits (k-means over the
  sections' centroids, ``k`` as large as the device's spare qubits allow); each region gets its own pool of
  ``local_cap`` ancillas, appended as register ``local``. Larger sections (the phase separator's arithmetic over
  all edges) keep the shared ancillas. The gate order is unchanged, so the operator is unchanged; sections of
  different regions then act on disjoint qubits when their data qubits are disjoint, so they may run side by
  side (ASAP), which is a reordering of commuting gates only. No partial mixers that share a qubit are reordered.
* :func:`place` maps logical qubits to physical qubits: greedily, heaviest-interacting first, each qubit onto
  the free physical qubit of the device's largest connected component that minimises the interaction-weighted
  distance to the qubits already placed (distance = shortest path in the coupling graph). The router
  (:func:`qcpp.routing.sabre.route`, Qiskit's SABRE) starts from this layout.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.plan.compile import compile_scenario
    >>> from qcpp.plan.options import PlanOptions
    >>> from qcpp.hardware.device import get_device
    >>> s = default_scenario(3, 3, 1)
    >>> c = compile_scenario(s, 1, PlanOptions(fuse=False), lowered=True).circuit
    >>> local = localize_ancillas(c, s, spare=16)
    >>> c.num_qubits, local.num_qubits, [r.name for r in local.registers]
    (15, 31, ['data', 'logic', 'local'])
    >>> layout = place(local, get_device("grid:6x6"))
    >>> len(layout) == len(set(layout)) == local.num_qubits
    True
"""

from __future__ import annotations

import numpy as np

from qcpp.hardware.device import Device, distances
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate
from qcpp.problem.scenario import Scenario

__all__ = ["DEFAULT_LOCAL_CAP", "localize_ancillas", "place"]

DEFAULT_LOCAL_CAP = 8
"""Ancillas per local pool: the most any partial mixer or per-node phase gadget of the default grids uses."""


def _data_size(circuit: Circuit) -> int:
    first = circuit.registers[0] if circuit.registers else None
    return first.size if first is not None and first.name == "data" else 0


def _section_qubits(sec: Section) -> set[int]:
    return {q for g in sec.gates for q in g[1]}


def _kmeans(points: np.ndarray, k: int, iterations: int = 20) -> np.ndarray:
    """Deterministic k-means (farthest-point start): cluster label per point."""
    centers = [points[0]]
    for _ in range(1, k):
        d = np.min([np.sum((points - c) ** 2, axis=1) for c in centers], axis=0)
        centers.append(points[int(np.argmax(d))])
    c = np.array(centers, dtype=float)
    labels = np.zeros(len(points), dtype=int)
    for _ in range(iterations):
        labels = np.argmin(((points[:, None, :] - c[None, :, :]) ** 2).sum(axis=2), axis=1)
        for j in range(k):
            members = points[labels == j]
            if len(members):
                c[j] = members.mean(axis=0)
    return labels


def localize_ancillas(circuit: Circuit, scenario: Scenario, spare: int, local_cap: int = DEFAULT_LOCAL_CAP) -> Circuit:
    """Give small sections region-local ancillas (see the module docs).

    Args:
        circuit: A circuit of :func:`qcpp.plan.compile.compile_scenario` (first register ``data``), every section
            clean at both ends (compile with ``fuse=False``).
        scenario: Its scenario (the data qubits' grid positions).
        spare: Extra qubits the device can give (``device qubits - circuit.num_qubits``).
        local_cap: Ancillas per local pool; sections using more keep the shared ancillas.

    Returns:
        The circuit with a register ``local`` of ``k * local_cap`` qubits appended (``k = spare // local_cap``
        regions, at most one per small section), or ``circuit`` itself if ``k < 2``.
    """
    n_data = _data_size(circuit)
    k_max = spare // local_cap if local_cap > 0 else 0
    small: list[int] = []
    centroids: list[tuple[float, float]] = []
    edges = scenario.grid.edges
    for i, sec in enumerate(circuit.sections):
        qs = _section_qubits(sec)
        anc = [q for q in qs if q >= n_data]
        data = [q for q in qs if q < n_data]
        if anc and len(anc) <= local_cap and data:
            mids = [np.add(*edges[scenario.variable_of(q)[1]]) / 2 for q in data]
            centroids.append(tuple(np.mean(mids, axis=0)))
            small.append(i)
    k = min(k_max, len({c for c in centroids}))
    if k < 2:
        return circuit
    labels = _kmeans(np.array(centroids, dtype=float), k)
    base = circuit.num_qubits
    region_of = dict(zip(small, labels.tolist()))
    sections = []
    for i, sec in enumerate(circuit.sections):
        region = region_of.get(i)
        if region is None:
            sections.append(sec)
            continue
        anc = sorted(q for q in _section_qubits(sec) if q >= n_data)
        rename = {q: base + region * local_cap + j for j, q in enumerate(anc)}
        gates = [Gate(g[0], tuple(rename.get(q, q) for q in g[1]), g[2], g[3]) for g in sec.gates]
        sections.append(Section(sec.name, gates))
    return Circuit([*circuit.registers, Register("local", k * local_cap)], sections)


def _largest_component(dist: np.ndarray) -> np.ndarray:
    reach = np.isfinite(dist)
    sizes = reach.sum(axis=1)
    return np.flatnonzero(reach[int(np.argmax(sizes))])


def place(circuit: Circuit, device: Device) -> tuple[int, ...]:
    """Greedy interaction-weighted placement of ``circuit``'s qubits on ``device`` (see the module docs).

    Returns:
        Logical qubit ``i`` -> physical qubit.

    Raises:
        ValueError: the device's largest connected component has fewer qubits than the circuit.
    """
    n = circuit.num_qubits
    dist = distances(device)
    comp = _largest_component(dist)
    if len(comp) < n:
        raise ValueError(f"the circuit needs {n} qubits; device {device.name} has {len(comp)} connected ones")
    weight: dict[tuple[int, int], int] = {}
    for g in circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            key = (min(qs), max(qs))
            weight[key] = weight.get(key, 0) + 1
    nbrs: list[dict[int, int]] = [{} for _ in range(n)]
    for (a, b), w in weight.items():
        nbrs[a][b] = nbrs[a].get(b, 0) + w
        nbrs[b][a] = nbrs[b].get(a, 0) + w
    total = np.array([sum(d.values()) for d in nbrs], dtype=float)
    sub = dist[np.ix_(comp, comp)]
    free = np.ones(len(comp), dtype=bool)
    pos = [-1] * n
    attach = np.zeros(n)  # interaction weight to already placed qubits
    placed = np.zeros(n, dtype=bool)
    center = int(np.argmin(sub.sum(axis=1)))
    for _ in range(n):
        cand = np.where(~placed, attach * 1e6 + total, -1.0)
        lq = int(np.argmax(cand))
        near = [(pos[b], w) for b, w in nbrs[lq].items() if placed[b]]
        if near:
            cols = np.array([p for p, _ in near])
            ws = np.array([w for _, w in near], dtype=float)
            cost = sub[:, cols] @ ws
        else:
            cost = sub[:, center].copy()
        cost[~free] = np.inf
        p = int(np.argmin(cost))
        pos[lq] = p
        free[p] = False
        placed[lq] = True
        for b, w in nbrs[lq].items():
            attach[b] += w
    return tuple(int(comp[p]) for p in pos)
