"""A sound routed two-qubit bound, gadget kind by gadget kind: every gate compile routes charged at its own distance.

The circuit is the one ``qcpp compile --device`` routes (:func:`bound_plan`: lowered, unfused, its phase separator
laid out as compile lays it out on the device; every section returns its ancillas to |0>). Its qubits are placed
once:

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

The sum runs over the plan's gadgets as the call graph's estimates do: the state preparation once, each gadget of the
first layer ``p`` times (later layers have its gates, only the angles differ; without the first phase separator, layer
1's phase separator ``p - 1`` times: :meth:`qcpp.plan.qaoa.QaoaPlan.layer_sections`). What a gadget's charge needs of
its gates depends on its kind only (equal kinds have equal gates up to qubit names), so it is worked out once per kind
(:func:`kind_route`, memoised in the run's :class:`~qcpp.routing.context.RoutingContext`): per lowered section, which of
the gadget's qubits each gate meets, which ancilla goes beside which qubit, and how many gates each pair of qubits has.
A gadget's charge is then that route at the distances between the device qubits its own qubits are placed on.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.estimators.estimate import DEFAULT_PLAN
    >>> dev = get_device("grid:5x5")
    >>> b = layout_twoq_bound(bound_plan(default_scenario(3, 3, 1), 1, DEFAULT_PLAN, dev), dev)
    >>> b is not None and b >= 106
    True
"""

from __future__ import annotations

import dataclasses
from collections import deque
from collections.abc import Callable, Hashable, MutableMapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from qcpp.hardware.device import Device
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import QaoaPlan
from qcpp.problem.scenario import Scenario
from qcpp.routing.context import RoutingContext

__all__ = [
    "BlockRoute",
    "KindRoute",
    "PlacedBlock",
    "bound_plan",
    "gate_distances",
    "hex_path_lengths",
    "kind_route",
    "layout_twoq_bound",
    "placed_blocks",
]

_DIJKSTRA_CHUNK = 256
"""Sources per batched breadth-first search on a non-grid device (a chunk's rows are dense: 256 x qubits)."""


def bound_plan(scenario: Scenario, p: int, options: PlanOptions, device: Device | str) -> QaoaPlan:
    """The plan of the circuit compile routes on ``device``: ``options`` settled for the device
    (:func:`qcpp.pipeline.device_plan.device_plan_options`), unfused (every gadget lowered on its own).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> bound_plan(default_scenario(3, 3, 1), 2, PlanOptions(), "grid").options.phase_layout
        'medial'
    """
    from qcpp.pipeline.device_plan import device_plan_options
    from qcpp.plan.qaoa import qaoa_plan

    return qaoa_plan(scenario, p, dataclasses.replace(device_plan_options(options, device), fuse=False))


@dataclass(frozen=True)
class BlockRoute:
    """One lowered section of a gadget kind, in its own labels: label ``i`` is the ``i``-th qubit its gates meet.

    Attributes:
        source: Per label, its position among the gadget's qubits (:func:`_own_labels` of its gates),
            ``-1`` for a ``work`` qubit the lowering adds.
        data: The labels that are data qubits.
        ancillas: ``(ancilla label, label it goes beside)`` in order of first use: beside its first partner
            already placed, else the section's first data qubit; ``-1``: the section meets no data qubit (data qubit
            0's home).
        pairs: The distinct label pairs of its two-qubit gates, shape ``(k, 2)``.
        counts: How many two-qubit gates each pair has.
    """

    source: np.ndarray
    data: np.ndarray
    ancillas: tuple[tuple[int, int], ...]
    pairs: np.ndarray
    counts: np.ndarray


@dataclass(frozen=True)
class KindRoute:
    """What the routed bound needs of a gadget kind (see the module docs).

    Attributes:
        gates: The gadget's high-level gates with its qubits named by :func:`_own_labels` and without angles.
        data: Per qubit of the gadget (in order of first use), whether it is a data qubit.
        blocks: Its lowered sections (:func:`qcpp.plan.qaoa.gadget_blocks`) in order.
    """

    gates: tuple[Hashable, ...]
    data: np.ndarray
    blocks: tuple[BlockRoute, ...]

    def fits(self, gates: tuple[Hashable, ...], qubits: Sequence[int], n_data: int) -> bool:
        """Whether a gadget with these :func:`_own_labels` has this route: the same gates up to qubit names (the
        kind's contract), its data qubits where the route has them. One that does not gets a route of its own."""
        return gates == self.gates and bool(((np.asarray(qubits) < n_data) == self.data).all())


@dataclass(frozen=True)
class PlacedBlock:
    """A lowered section of the circuit placed on the device.

    Attributes:
        multiplicity: How often the circuit holds it (1 for the state preparation, ``p`` for a layer's).
        where: The device qubit of each label of its :class:`BlockRoute`.
        route: The section's route.
    """

    multiplicity: int
    where: np.ndarray
    route: BlockRoute


def _own_labels(gates: Sequence[Any]) -> tuple[tuple[Hashable, ...], list[int]]:
    """``(gates, qubits)``: ``gates`` with qubit ``i`` standing for the ``i``-th qubit they meet and without angles
    (what equal kinds share), and those qubits in order."""
    own: dict[int, int] = {}
    named = tuple((g[0], tuple(own.setdefault(q, len(own)) for q in g[1]), g[3]) for g in gates)
    return named, list(own)


def kind_route(gadget: Any, registers: Sequence[Any], n_data: int) -> KindRoute:
    """The :class:`KindRoute` of ``gadget``'s kind, read from its lowered gates.

    Args:
        gadget: A planned gadget.
        registers: The circuit's registers (``work`` included), as the compiler lowers it.
        n_data: The data qubits (qubits ``< n_data``).

    Returns:
        The route (in the gadget's own labels: any gadget of the kind takes it).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> plan = bound_plan(default_scenario(3, 3, 1), 1, PlanOptions(), "grid")
        >>> mixer = next(g for name, g in plan.sections() if name == "mixer_0")
        >>> route = kind_route(mixer, plan.registers, plan.scenario.num_variables)
        >>> len(route.blocks), int(route.blocks[0].counts.sum()) == mixer.cost().two_qubit
        (1, True)
    """
    from qcpp.ir.circuit import Circuit, Section
    from qcpp.lowering.passes import lower
    from qcpp.plan.qaoa import gadget_blocks

    blocks = gadget_blocks(gadget)
    gates, qubits = _own_labels([g for b in blocks for g in b])
    own = {q: i for i, q in enumerate(qubits)}
    routes = []
    for sec in lower(Circuit(registers, [Section("g", tuple(b)) for b in blocks])).sections:
        label: dict[int, int] = {}
        placed: set[int] = set()
        ancillas: list[tuple[int, int]] = []
        pairs: list[tuple[int, int]] = []
        first_data = next((q for g in sec.gates for q in g[1] if q < n_data), None)
        for g in sec.gates:
            qs = g[1]
            for q in qs:
                if q >= n_data and q not in placed:
                    near = next((x for x in qs if x != q and (x < n_data or x in placed)), first_data)
                    beside = -1 if near is None else label.setdefault(near, len(label))
                    ancillas.append((label.setdefault(q, len(label)), beside))
                    placed.add(q)
            if len(qs) == 2:
                pairs.append((label.setdefault(qs[0], len(label)), label.setdefault(qs[1], len(label))))
        met = list(label)
        unique, counts = np.unique(np.array(pairs, dtype=np.int64).reshape(-1, 2), axis=0, return_counts=True)
        routes.append(BlockRoute(
            source=np.array([own.get(q, -1) for q in met], dtype=np.int64),
            data=np.flatnonzero(np.array(met, dtype=np.int64) < n_data),
            ancillas=tuple(ancillas), pairs=unique.reshape(-1, 2), counts=counts.astype(np.int64),
        ))  # fmt: skip
    return KindRoute(gates, np.array([q < n_data for q in qubits], dtype=bool), tuple(routes))


def placed_blocks(
    plan: QaoaPlan, homes: Sequence[int], device: Device, routes: MutableMapping[Hashable, KindRoute] | None = None
) -> list[PlacedBlock] | None:
    """The circuit's sections placed as the module docs describe: those of
    :meth:`~qcpp.plan.qaoa.QaoaPlan.layer_sections` with their multiplicities, each gadget's from its kind's route
    (taken from ``routes`` or worked out and stored there).

    Args:
        plan: The circuit (:func:`bound_plan`).
        homes: Physical qubit of every data qubit.
        device: The device.
        routes: Kind routes by kind key (:attr:`qcpp.routing.context.RoutingContext.kind_routes`; default: this
            call's own).

    Returns:
        The placed sections in circuit order, or ``None`` if a section needs more ancillas than there are free
        qubits.
    """
    routes = {} if routes is None else routes
    n_data, registers = len(homes), plan.registers
    graph = device.graph()
    graph = (graph + graph.T).tocsr()  # both directions of every coupling
    indptr, indices = graph.indptr.tolist(), graph.indices.tolist()
    home = np.asarray(homes, dtype=np.int64)
    is_home = np.zeros(device.num_qubits, dtype=bool)
    is_home[home] = True
    out: list[PlacedBlock] = []
    for _, gadget, multiplicity in plan.layer_sections():
        gates, qubits = _own_labels(gadget.emit())
        route = routes.get(gadget.kind)
        if route is None:
            route = routes[gadget.kind] = kind_route(gadget, registers, n_data)
        if not route.fits(gates, qubits, n_data):
            route = kind_route(gadget, registers, n_data)
        mine = np.asarray(qubits, dtype=np.int64)
        for block in route.blocks:
            where = np.zeros(len(block.source), dtype=np.int64)
            where[block.data] = home[mine[block.source[block.data]]]
            taken: set[int] = set()
            for ancilla, beside in block.ancillas:
                spot = _nearest_free(int(where[beside]) if beside >= 0 else int(home[0]), indptr, indices, is_home,
                                     taken)  # fmt: skip
                if spot is None:
                    return None
                where[ancilla] = spot
                taken.add(spot)
            out.append(PlacedBlock(multiplicity, where, block))
    return out


def layout_twoq_bound(
    plan: QaoaPlan, device: Device, context: RoutingContext | None = None, stage: Callable[[str], None] | None = None
) -> int | None:
    """The two-qubit count of the gate-by-gate SWAP routing from one placement (see the module docs).

    Args:
        plan: The circuit compile routes (:func:`bound_plan`).
        device: The device (not all-to-all: there every gate costs one, and the coupling graph is large).
        context: The run's memos (its :attr:`~qcpp.routing.context.RoutingContext.kind_routes`; default: a fresh
            one).
        stage: Called with each stage's name as it starts, for progress.

    Returns:
        The bound, or ``None`` where a section needs more free qubits than the device's piece holding its data has.
    """
    from qcpp.layout.medial import medial_placement

    homes = medial_placement(plan.scenario, device)
    if homes is None:
        homes = compact_placement(device, plan.scenario.num_variables)
        if homes is None:
            return None
    if stage is not None:
        stage("placing the gadgets' ancillas for the layout bound")
    routes = (RoutingContext() if context is None else context).kind_routes
    blocks = placed_blocks(plan, homes, device, routes)
    if blocks is None:
        return None
    none = [np.zeros(0, np.int64)]
    first = np.concatenate([x.where[x.route.pairs[:, 0]] for x in blocks] or none)
    second = np.concatenate([x.where[x.route.pairs[:, 1]] for x in blocks] or none)
    weight = np.concatenate([x.multiplicity * x.route.counts for x in blocks] or none)
    return int((weight * (1 + 6 * (gate_distances(device, first, second) - 1))).sum())


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
