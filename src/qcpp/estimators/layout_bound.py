"""A sound routed two-qubit bound: every gate of the circuit compile routes charged at its own distance.

The circuit is the one ``qcpp compile --device`` routes (lowered, unfused: every section returns its ancillas
to |0>, its phase separator laid out as compile lays it out on the device). Its qubits are placed once:

* each data qubit at its home in the geometric layout compile uses where the device holds it
  (:func:`qcpp.layout.medial.medial_placement`: the medial grid on square grids, one cell per plaquette on heavy-hex
  lattices); on any other device, in breadth-first order from a middle qubit of its largest connected component;
* per section, each ancilla (in order of first use) on the free device qubit nearest (breadth first, ties by
  qubit number) to a qubit it meets that is already placed (its first such partner in gate order; else the
  section's first data qubit), free meaning neither a data home nor taken by another ancilla of the same section.

That placement is a valid layout of every section: between sections every non-data qubit is |0>, so any free
qubits may serve as a section's ancillas. Routing then takes every two-qubit gate on its own: SWAP one qubit
along a shortest path until it is next to its partner (``d - 1`` SWAPs of 3 CX for qubits ``d`` apart), apply
the gate, and SWAP back the same way, which restores the layout exactly. Every gate therefore costs
``1 + 6 (d - 1)`` two-qubit gates with ``d`` its distance *in that placement*, and the sum over the gates is the
two-qubit count of a routing compile could write: an upper bound on the best routing of that circuit (not on
SABRE's, which ``tests/estimators/routed_test.py`` checks it exceeds on every scenario small enough to route).
The layers after the first have the first's gates (only the angles differ), so the sum is the initial state's
sections plus ``p`` times the first layer's.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.estimators.estimate import DEFAULT_PLAN
    >>> b = layout_twoq_bound(default_scenario(3, 3, 1), 1, DEFAULT_PLAN, get_device("grid:5x5"))
    >>> b is not None and b >= 106
    True
"""

from __future__ import annotations

import dataclasses
from collections import deque
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from qcpp.hardware.device import Device
from qcpp.problem.scenario import Scenario

__all__ = ["gate_distances", "hex_path_lengths", "layout_twoq_bound", "section_charges"]

_DIJKSTRA_CHUNK = 256
"""Sources per batched breadth-first search on a non-grid device (a chunk's rows are dense: 256 x qubits)."""


def layout_twoq_bound(
    scenario: Scenario, p: int, plan: Any, device: Device, stage: Callable[[str], None] | None = None
) -> int | None:
    """The two-qubit count of the gate-by-gate SWAP routing from one placement (see the module docs).

    Args:
        scenario: The scenario.
        p: QAOA layers.
        plan: Its :class:`qcpp.plan.options.PlanOptions`.
        device: The device (not all-to-all: there every gate costs one, and the coupling graph is large).
        stage: Called with each stage's name as it starts, for progress.

    Returns:
        The bound, or ``None`` where a section needs more free qubits than the device's piece holding its data has.
    """
    from qcpp.layout.medial import medial_placement
    from qcpp.lowering.passes import lower
    from qcpp.pipeline.device_plan import device_plan_options
    from qcpp.plan.qaoa import qaoa_plan

    say = stage or (lambda _text: None)
    settled = device_plan_options(plan, device)
    say("building one layer for the layout bound")
    circuit = lower(qaoa_plan(scenario, 1, dataclasses.replace(settled, fuse=False)).circuit())
    homes = medial_placement(scenario, device)
    if homes is None:
        homes = compact_placement(device, scenario.num_variables)
        if homes is None:
            return None
    say(f"placing {len(circuit.sections):,} sections' ancillas for the layout bound")
    charges = section_charges(circuit.sections, homes, device)
    if charges is None:
        return None
    return sum(c if name.startswith("initial") else p * c for name, c in charges)


def compact_placement(device: Device, n: int) -> tuple[int, ...] | None:
    """``n`` qubits of ``device``'s largest connected component in breadth-first order from its middle qubit (by
    number; a square grid's centre), or ``None`` if the component has fewer.

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> compact_placement(get_device("grid:3x3"), 5)
        (4, 5, 7, 1, 3)
    """
    from scipy.sparse.csgraph import breadth_first_order, connected_components

    _, labels = connected_components(device.graph(), directed=False)
    largest = np.flatnonzero(labels == np.bincount(labels).argmax())
    if len(largest) < n:
        return None
    start = device.num_qubits // 2 if labels[device.num_qubits // 2] == labels[largest[0]] else int(largest[0])
    order = breadth_first_order(device.graph(), start, directed=False, return_predecessors=False)
    return tuple(int(q) for q in order[:n])


def section_charges(
    sections: Sequence[Any], homes: Sequence[int], device: Device
) -> list[tuple[str, int]] | None:
    """Per section, its name and the two-qubit gates its gates cost routed one by one from the placement of the
    module docs, or ``None`` if a section needs more ancillas than there are free qubits.

    Args:
        sections: The lowered circuit's sections (gates ``(name, qubits, ...)``; qubits ``< len(homes)`` data).
        homes: Physical qubit of every data qubit.
        device: The device.

    Returns:
        ``[(section name, charge), ...]`` in order.
    """
    n_data = len(homes)
    graph = device.graph()
    graph = (graph + graph.T).tocsr()  # both directions of every coupling
    indptr, indices = graph.indptr.tolist(), graph.indices.tolist()
    is_home = np.zeros(device.num_qubits, dtype=bool)
    is_home[list(homes)] = True
    home_list = [int(h) for h in homes]
    names: list[str] = []
    firsts: list[np.ndarray] = []
    seconds: list[np.ndarray] = []
    for sec in sections:
        where: dict[int, int] = {}  # ancilla -> physical qubit, this section
        taken: set[int] = set()
        pairs: list[tuple[int, int]] = []
        first_data = next((q for g in sec.gates for q in g[1] if q < n_data), 0)
        for g in sec.gates:
            qs = g[1]
            for q in qs:
                if q >= n_data and q not in where:
                    near = next((x for x in qs if x != q and (x < n_data or x in where)), None)
                    if near is None:
                        near = first_data
                    at = home_list[near] if near < n_data else where[near]
                    spot = _nearest_free(at, indptr, indices, is_home, taken)
                    if spot is None:
                        return None
                    where[q] = spot
                    taken.add(spot)
            if len(qs) == 2:
                a, b = qs
                pairs.append((home_list[a] if a < n_data else where[a], home_list[b] if b < n_data else where[b]))
        names.append(sec.name)
        arr = np.array(pairs, dtype=np.int64).reshape(-1, 2)
        firsts.append(arr[:, 0])
        seconds.append(arr[:, 1])
    sizes = [len(a) for a in firsts]
    d = gate_distances(device, np.concatenate(firsts or [np.zeros(0, np.int64)]),
                       np.concatenate(seconds or [np.zeros(0, np.int64)]))  # fmt: skip
    per_gate = 1 + 6 * (d - 1)
    bounds = np.cumsum([0, *sizes])
    return [(name, int(per_gate[lo:hi].sum())) for name, lo, hi in zip(names, bounds[:-1], bounds[1:], strict=True)]


def _nearest_free(
    start: int, indptr: list[int], indices: list[int], is_home: np.ndarray, taken: set[int]
) -> int | None:
    """The free qubit nearest ``start`` (breadth first, neighbours in index order), ``None`` if none is reachable."""
    if not is_home[start] and start not in taken:
        return start
    seen = {start}
    queue = deque([start])
    while queue:
        u = queue.popleft()
        for v in indices[indptr[u] : indptr[u + 1]]:
            if v in seen:
                continue
            if not is_home[v] and v not in taken:
                return v
            seen.add(v)
            queue.append(v)
    return None


def gate_distances(device: Device, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances between physical qubits ``a[i]`` and ``b[i]`` on ``device``'s coupling graph: the shortest paths'
    on a full square grid (Manhattan) and on any other device but a heavy-hex lattice (breadth first: seconds per
    thousand sources on tens of thousands of qubits); on a heavy-hex lattice the length of a path between them
    (:func:`hex_path_lengths`: at least the distance, so still an upper bound of the routing).

    Args:
        device: The device (connected where the pairs are).
        a, b: Physical qubits, equal length.

    Returns:
        The distances (int64).

    Raises:
        ValueError: a pair in different components.

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> gate_distances(get_device("grid:3x3"), np.array([0, 0]), np.array([8, 1])).tolist()
        [4, 1]
    """
    from qcpp.layout.medial import grid_shape

    shape = grid_shape(device)
    if shape is not None:
        cols = shape[1]
        return np.abs(a // cols - b // cols) + np.abs(a % cols - b % cols)
    from qcpp.hardware.device import heavy_hex_distance

    lattice = heavy_hex_distance(device)
    if lattice is not None:
        return hex_path_lengths(lattice, a, b)
    from scipy.sparse.csgraph import shortest_path

    out = np.zeros(len(a), dtype=np.int64)
    sources, inverse = np.unique(a, return_inverse=True)
    graph = device.graph()
    for lo in range(0, len(sources), _DIJKSTRA_CHUNK):
        chunk = sources[lo : lo + _DIJKSTRA_CHUNK]
        rows = shortest_path(graph, directed=False, unweighted=True, indices=chunk)
        mine = (inverse >= lo) & (inverse < lo + len(chunk))
        got = rows[inverse[mine] - lo, b[mine]]
        if not np.isfinite(got).all():
            raise ValueError(f"device {device.name}: a gate between qubits in different components")
        out[mine] = got.astype(np.int64)
    return out


def _bridge_below(g: np.ndarray, x: np.ndarray, d: int) -> np.ndarray:
    """The largest bridge column ``<= x`` in gap ``g`` of ``heavy-hex:d`` (``-1``: none). Even gaps have bridges
    at ``0, 3, 7, .., 2 d - 3``, odd ones at ``1, 5, .., 2 d - 3 - 2`` and ``2 d - 2``
    (:func:`qcpp.hardware.device.heavy_hex_coordinates`)."""
    even = np.where(x >= 3, 3 + 4 * ((np.minimum(x, 2 * d - 3) - 3) // 4), np.where(x >= 0, 0, -1))
    odd = np.where(x >= 2 * d - 2, 2 * d - 2, np.where(x >= 1, 1 + 4 * ((np.minimum(x, 2 * d - 5) - 1) // 4), -1))
    return np.where(g % 2 == 0, even, odd)


def _bridge_above(g: np.ndarray, x: np.ndarray, d: int) -> np.ndarray:
    """The smallest bridge column ``>= x`` in gap ``g`` of ``heavy-hex:d`` (``-1``: none)."""
    even = np.where(x <= 0, 0, np.where(x <= 2 * d - 3, 3 + 4 * ((np.maximum(x, 3) - 3 + 3) // 4), -1))
    odd = np.where(x <= 2 * d - 5, 1 + 4 * ((np.maximum(x, 1) - 1 + 3) // 4), np.where(x <= 2 * d - 2, 2 * d - 2, -1))
    return np.where(g % 2 == 0, even, odd)


def _line_path(d: int, ga: np.ndarray, xa: np.ndarray, gb: np.ndarray, xb: np.ndarray) -> np.ndarray:
    """Length of a path between row-line qubits ``(2 ga, xa)`` and ``(2 gb, xb)`` of ``heavy-hex:d``: along the
    row lines and down (or up) one gap at a time over a bridge, at each gap the bridge that adds least to the
    horizontal way left (ties: the nearest)."""
    swap = ga > gb
    ga, gb, xa, xb = np.where(swap, gb, ga), np.where(swap, ga, gb), np.where(swap, xb, xa), np.where(swap, xa, xb)
    cur = xa.copy()
    gaps = gb - ga
    length = 2 * gaps
    live = np.flatnonzero(gaps > 0)  # the pairs with gaps left to cross
    for k in range(int(gaps.max(initial=0))):
        live = live[gaps[live] > k]
        g, at, to = ga[live] + k, cur[live], xb[live]
        candidates = np.stack([_bridge_below(g, at, d), _bridge_above(g, at, d),
                               _bridge_below(g, to, d), _bridge_above(g, to, d)])  # fmt: skip
        step = np.abs(candidates - at)
        key = np.where(candidates >= 0, (step + np.abs(candidates - to)) * (4 * d) + step, np.iinfo(np.int64).max)
        chosen = candidates[np.argmin(key, axis=0), np.arange(len(live))]
        length[live] += np.abs(chosen - at)
        cur[live] = chosen
    return length + np.abs(cur - xb)


def hex_path_lengths(d: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Lengths of paths between qubits ``a[i]`` and ``b[i]`` of ``heavy-hex:d`` (Qiskit's numbering), each at
    least their distance; equal to it on most pairs (``tests/estimators/layout_bound_test.py`` compares every pair
    of small lattices with breadth-first distances). A bridge qubit goes to the row line above or below it
    (one step), whichever gives the shorter path; the row lines are joined as in :func:`_line_path`.

    Example:
        >>> from qcpp.hardware.device import heavy_hex_coordinates
        >>> xy = heavy_hex_coordinates(3)
        >>> q = {c: i for i, c in enumerate(xy)}
        >>> hex_path_lengths(3, np.array([q[0, 0], q[0, 0]]), np.array([q[0, 4], q[4, 4]])).tolist()
        [4, 8]
    """
    from qcpp.hardware.device import heavy_hex_coordinates

    xy = np.array(heavy_hex_coordinates(d), dtype=np.int64)
    pairs, inverse = np.unique(np.stack([np.minimum(a, b), np.maximum(a, b)]), axis=1, return_inverse=True)
    ya, xa, yb, xb = xy[pairs[0], 0], xy[pairs[0], 1], xy[pairs[1], 0], xy[pairs[1], 1]
    la, lb = ya % 2 == 1, yb % 2 == 1  # bridge qubits
    best = np.full(len(ya), np.iinfo(np.int64).max)
    for da in (0, 1):  # a bridge qubit steps to the row line above (0) or below (1)
        for db in (0, 1):
            rows = np.flatnonzero((la | (da == 0)) & (lb | (db == 0)))  # a line qubit needs only one of each
            ga = np.where(la[rows], (ya[rows] - 1) // 2 + da, ya[rows] // 2)
            gb = np.where(lb[rows], (yb[rows] - 1) // 2 + db, yb[rows] // 2)
            length = _line_path(d, ga, xa[rows], gb, xb[rows]) + la[rows] + lb[rows]
            best[rows] = np.minimum(best[rows], length)
    best[pairs[0] == pairs[1]] = 0
    return best[inverse.reshape(-1)]
