"""The device qubits a window part is routed on (its *patch*), and SABRE run on a patch.

A part of a window (:mod:`qcpp.routing.windows`) is routed on the device qubits within
:attr:`~qcpp.routing.options.RoutingOptions.window_radius` couplings of its qubits' positions, grown to the whole
connected component when that neighbourhood does not connect them (:func:`local_patch`): the routed cost of a
window then depends only on its neighbourhood. :func:`sabre_local` runs Qiskit's ``SabreSwap`` on a patch, relabelled
``0 .. size-1``, and reads its routed DAG directly (``("gate", k)`` for the ``k``-th pair done, ``("swap", (x, y))``);
it is called as the pass calls it, without the pass's per-run checks (:func:`run_sabre`), with one pass per patch
shape (:func:`patch_sabre`). Per device a :class:`PatchIndex` keeps its neighbour lists and every patch computed;
on a heavy-hex lattice its :class:`Lattice` lets a window's memo entry answer its translations. Everything memoised
lives in the caller's :class:`~qcpp.routing.context.RoutingContext`, and every patch routed is reported to its open
watches (:meth:`~qcpp.routing.context.RoutingContext.saw_patch`).

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.hardware.device import distances
    >>> from qcpp.routing.context import RoutingContext
    >>> dev = get_device("grid:1x6")
    >>> context = RoutingContext()
    >>> local_patch(context, {0, 1}, dev, distances(dev), radius=2)
    ((0, 1, 2, 3), ((0, 1), (1, 2), (2, 3)))
    >>> sabre_local(context, ((0, 1), (1, 2)), 3, ((0, 2),), seed=0, trials=1)
    (('swap', (1, 2)), ('gate', 0))
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from typing import Any, NamedTuple

from qcpp.hardware.device import Device
from qcpp.routing.context import RoutingContext
from qcpp.routing.routed_circuit import sabre_target

__all__ = [
    "Coord", "Lattice", "PatchIndex", "PatchSabre", "indexed_patch", "local_patch", "patch_index", "patch_sabre",
    "run_sabre", "sabre_local",
]  # fmt: skip

PATCH_INDEXES_KEPT = 8
"""Devices (with their distances and radius) whose :class:`PatchIndex` a context keeps."""

SABRE_PASSES_KEPT = 4096
"""``SabreSwap`` passes a context keeps before it starts over."""

PARALLEL_MIN_TRIALS = 64
"""Routings of at least this many SABRE trials run them on Qiskit's threads (the large windows' searches,
:class:`~qcpp.routing.options.RoutingOptions`); fewer run one after another. Qiskit keeps the same trial either way
(``tests/compiler/window_memo_test.py``), so this decides only how long a compile waits."""


class PatchIndex:
    """Per device (its distances and the patches' radius): the device's neighbour lists, and every patch computed so
    far (keyed by the positions it was grown around) with whether it is a whole component and its couplings in
    local indices (a search asks for the same patches thousands of times); with ``translate``, its :class:`Lattice`
    where the device is a heavy-hex lattice (else :attr:`lattice` is ``None``)."""

    def __init__(self, device: Device, dist: Any, radius: int, translate: bool = True) -> None:
        self.device = device
        self.dist = dist
        self.radius = radius
        self.neighbours: list[list[int]] = [[] for _ in range(device.num_qubits)]
        self.edges_of: list[list[int]] = [[] for _ in range(device.num_qubits)]  # indices into device.coupling
        for e, (a, b) in enumerate(device.coupling):
            self.neighbours[a].append(b)
            self.neighbours[b].append(a)
            self.edges_of[a].append(e)
            self.edges_of[b].append(e)
        # per positions grown around: (patch, whole component, couplings in local indices, local index of a qubit)
        self.patches: dict[tuple[int, ...], tuple[tuple[int, ...], bool, tuple[tuple[int, int], ...], dict]] = {}
        self.token = object()  # names the device in memo keys without keeping its distances alive
        self.lattice = Lattice.of(device, radius) if translate else None


Coord = tuple[int, int]


class Lattice:
    """A heavy-hex lattice device's qubits on their ``(y, x)`` coordinates
    (:func:`qcpp.hardware.device.heavy_hex_coordinates`), for the translation-invariant window memo
    (:func:`qcpp.routing.windows.route_window`).

    A translation by multiples of :attr:`PERIOD` in both coordinates maps the infinite lattice onto itself, and
    (checked when built, :meth:`of`) the device's couplings are exactly its qubits one step apart and its index
    order is ``(kind, y, x)`` with the kind (data, bridge, flag) given by the coordinates' parities. A patch
    (the qubits within ``radius`` couplings of the qubits it is grown around, :func:`local_patch`) is then
    decided by which coordinates within ``radius`` steps of those qubits hold a qubit (:meth:`around`): a
    path of that many couplings stays there. So a window whose qubits are such a translation of a routed window's
    (:meth:`canonical`), with the same coordinates held around the qubits that routing grew its patches from (the
    compute's qubits, then where the compute left the middle's), gets the same patches, local indices and
    couplings, and SABRE routes it alike: one routing answers both, translated. A window routed on its whole
    component depends on the whole device: it is memoised on its physical pairs instead."""

    PERIOD = 4

    def __init__(self, coords: Sequence[Coord], radius: int) -> None:
        self.radius = radius
        self.y = [c[0] for c in coords]
        self.x = [c[1] for c in coords]
        self.at = {c: i for i, c in enumerate(coords)}
        pad = 2 * radius  # so that a box around any qubits never leaves the grid of cells
        self.width = max(self.x) + 1 + 2 * pad
        cells = (max(self.y) + 1 + 2 * pad) * self.width
        # a set of cells is an integer, bit c for cell c, coordinate (y, x) being cell (y + pad) * width + x + pad;
        # a set relative to a shift is moved up by :attr:`base` bits, so that no cell of it is negative
        self.base = cells
        self.cell = [(y + pad) * self.width + x + pad for y, x in coords]
        self.present = sum(1 << c for c in self.cell) << self.base  # the cells holding a qubit, moved up
        self.span = 2 * (max(self.x) + self.PERIOD) + 1  # (y, x) is code y * span + x, unique for |x| < span / 2
        self.code = [y * self.span + x for y, x in coords]
        steps = [dy * self.width + dx for dy in range(-radius, radius + 1) for dx in range(-radius, radius + 1)
                 if abs(dy) + abs(dx) <= radius]  # fmt: skip
        self.diamond = [sum(1 << (c + step) for step in steps) for c in self.cell]  # cells within radius steps

    @classmethod
    def of(cls, device: Device, radius: int) -> Lattice | None:
        """The lattice of a heavy-hex lattice device, or ``None`` (another device, or one the checks reject)."""
        from qcpp.hardware.device import heavy_hex_coordinates, heavy_hex_distance

        d = heavy_hex_distance(device)
        if d is None:
            return None
        coords = heavy_hex_coordinates(d)
        at = {c: i for i, c in enumerate(coords)}
        steps = {tuple(sorted((i, at[n]))) for i, (y, x) in enumerate(coords) for n in ((y + 1, x), (y, x + 1))
                 if n in at}  # fmt: skip
        kind = [1 if y % 2 else 2 * (x % 2) for y, x in coords]  # data 0, bridge 1, flag 2
        order = sorted(range(len(coords)), key=lambda i: (kind[i], coords[i]))
        if steps != {tuple(sorted(e)) for e in device.coupling} or order != list(range(len(coords))):
            return None  # pragma: no cover - another numbering: the physical memo only
        return cls(coords, radius)

    def canonical(self, pairs: Sequence[tuple[int, int]]) -> tuple[Hashable, Coord]:
        """A key equal for two windows' physical ``pairs`` iff one is the other translated by a multiple of
        :attr:`PERIOD`, and the translation ``(ay, ax)`` that takes the key's relative coordinates to these
        pairs' (the first qubit's coordinates rounded down to multiples of :attr:`PERIOD`: a translation by such
        a multiple moves it by the same)."""
        from itertools import chain

        q = pairs[0][0]
        ay, ax = self.y[q] - self.y[q] % self.PERIOD, self.x[q] - self.x[q] % self.PERIOD
        off = ay * self.span + ax
        code = self.code
        return tuple([code[q] - off for q in chain.from_iterable(pairs)]), (ay, ax)

    def around(self, centres: set[int], shift: Coord) -> tuple[int, int]:
        """The coordinates within :attr:`radius` steps (in ``y`` plus ``x``) of the ``centres`` qubits less
        ``shift`` (as a set of cells, relative to the shift's), and which of them hold a qubit (:meth:`holds`):
        every patch grown around the centres (the qubits within :attr:`radius` couplings, their couplings, whether
        they connect the centres) is decided there."""
        cells = 0
        diamond = self.diamond
        for q in centres:
            cells |= diamond[q]
        cells = (cells << self.base) >> (shift[0] * self.width + shift[1])
        return cells, self.holds(cells, shift)

    def holds(self, cells: int, shift: Coord) -> int:
        """Which of the coordinates ``cells`` (as :meth:`around` gives them) plus ``shift`` hold a qubit."""
        return cells & (self.present >> (shift[0] * self.width + shift[1]))

    def moved(self, q: int, by: Coord) -> int:
        """The qubit at qubit ``q``'s coordinates plus ``by``."""
        return self.at[(self.y[q] + by[0], self.x[q] + by[1])]


def patch_index(context: RoutingContext, device: Device, dist: Any, radius: int) -> PatchIndex:
    """The context's :class:`PatchIndex` of ``device`` with these distances (by identity) and ``radius``."""
    for index in context.patch_indexes:
        if index.device is device and index.dist is dist and index.radius == radius:
            return index  # type: ignore[no-any-return]
    index = PatchIndex(device, dist, radius, translate=context.reuse)
    context.patch_indexes.insert(0, index)
    del context.patch_indexes[PATCH_INDEXES_KEPT:]
    return index


def local_patch(
    context: RoutingContext, positions: set[int], device: Device, dist: Any, radius: int
) -> tuple[tuple[int, ...], tuple[tuple[int, int], ...]]:
    """The device qubits within ``radius`` couplings of ``positions`` (ascending), grown to the whole connected
    component when that neighbourhood does not connect them, and the patch's couplings (in
    :attr:`Device.coupling`'s order) as pairs of indices into it.

    Memoised per device in ``context``; every call reports the patch to the context's open watches and
    ``positions`` to its open centre sets."""
    patch, coupling, _ = indexed_patch(context, positions, device, dist, radius)
    return patch, coupling


def indexed_patch(
    context: RoutingContext, positions: set[int], device: Device, dist: Any, radius: int
) -> tuple[tuple[int, ...], tuple[tuple[int, int], ...], dict[int, int]]:
    """:func:`local_patch` and the patch's local index of each of its qubits (not to be changed: memoised)."""
    index = patch_index(context, device, dist, radius)
    for centres in context.centres:
        centres.update(positions)
    key = tuple(sorted(positions))
    hit = index.patches.get(key)
    if hit is None:
        import numpy as np

        rows = dist[list(key)]
        near = np.flatnonzero((rows <= radius).any(axis=0))
        inside = set(near.tolist())
        seen = {key[0]}
        todo = [key[0]]
        while todo:  # the component of the first position in the neighbourhood
            p = todo.pop()
            for q in index.neighbours[p]:
                if q in inside and q not in seen:
                    seen.add(q)
                    todo.append(q)
        linked = any(q in inside for p in inside for q in index.neighbours[p])  # no edge, no patch
        whole = not linked or not seen.issuperset(key)
        patch = tuple((np.flatnonzero(np.isfinite(rows[0])) if whole else near).tolist())
        local = {p: i for i, p in enumerate(patch)}
        edges = sorted({e for p in patch for e in index.edges_of[p]})  # in the device's order
        coupling = tuple((local[a], local[b]) for a, b in (device.coupling[e] for e in edges)
                         if a in local and b in local)  # fmt: skip
        hit = (patch, whole, coupling, local)
        index.patches[key] = hit
    patch, whole, coupling, local = hit
    context.saw_patch(patch, whole)
    return patch, coupling, local


def pairs_dag(shape: PatchSabre, pairs: Sequence[Sequence[int]]) -> Any:
    """The DAG :func:`run_sabre` routes on ``shape``'s qubits: one ``cx`` per pair, in order, on a copy of its empty
    circuit (what a pass manager would hand the pass: one register ``q``)."""
    dag = shape.empty.copy_empty_like()
    gate, bits = shape.gate, shape.bits
    apply = dag.apply_operation_back
    for a, b in pairs:
        apply(gate, (bits[a], bits[b]), (), check=False)
    return dag


def placed_dags(
    shape: PatchSabre, logical: Any, pairs: Sequence[Sequence[int]], layouts: Sequence[Sequence[int]]
) -> list[Any]:
    """:func:`pairs_dag` of ``pairs`` placed by each of ``layouts`` (logical qubit ``i`` -> qubit of ``shape``), for
    the placement search, which routes one circuit from many layouts.

    Each DAG is a copy of ``logical`` (a DAG of ``cx`` on its logical qubits, :func:`qcpp.routing.sabre.cx_dag`)
    relabelled by Qiskit's own layout routine (the one its ``ApplyLayout`` pass calls): the same gates on the same
    qubits in the same order as :func:`pairs_dag` writes them, so SABRE routes both alike, without a Python call per
    gate. Where Qiskit has no such routine, :func:`pairs_dag` itself.

    Args:
        shape: The device's :class:`PatchSabre` (its qubits are the device's).
        logical: The DAG of ``pairs`` on the logical qubits (:func:`qcpp.routing.sabre.cx_dag`).
        pairs: The circuit's two-qubit gates, in order, on its logical qubits.
        layouts: Placements of the logical qubits.

    Returns:
        One DAG per layout, on the device's qubits.
    """
    from copy import deepcopy

    size = len(shape.bits)
    try:
        from qiskit._accelerate.apply_layout import apply_layout
    except ImportError:  # pragma: no cover - another Qiskit
        return [pairs_dag(shape, [(layout[a], layout[b]) for a, b in pairs]) for layout in layouts]
    out = []
    for layout in layouts:
        dag = deepcopy(logical)
        apply_layout(dag, logical.num_qubits(), size, list(layout), None)
        out.append(dag)
    return out


def sabre_local(
    context: RoutingContext, coupling: tuple[tuple[int, int], ...], size: int, pairs: tuple[tuple[int, int], ...],
    seed: int, trials: int | None,
) -> tuple[tuple, ...]:  # fmt: skip
    """SABRE on a patch (qubits ``0 .. size-1``): ``("gate", k)`` (the ``k``-th pair, done) and ``("swap", (x, y))``
    in order, memoised in ``context`` per ``(patch, pairs, seed, trials)`` so equal neighbourhoods route equally."""
    key = (coupling, size, pairs, seed, trials)
    hit = context.windows.get(key)
    if hit is not None:
        return hit  # type: ignore[no-any-return]
    shape = patch_sabre(context, coupling, size)
    out = run_sabre(shape, pairs_dag(shape, pairs), seed, shape.trials if trials is None else trials,
                    context.parallel_trials)  # fmt: skip
    queues: list[list[int]] = [[] for _ in range(size)]  # per qubit, the pairs it is in, in order
    for k, (a, b) in enumerate(pairs):
        queues[a].append(k)
        queues[b].append(k)
    who = list(range(size))  # position -> the qubit that started there
    ptr = [0] * size
    events: list[tuple] = []
    index = shape.index
    for node in out.topological_op_nodes():  # the order dag_to_circuit writes them in
        qargs = node.qargs
        if index is None:
            x, y = qargs[0]._index, qargs[1]._index
        else:  # pragma: no cover - another Qiskit's bits
            x, y = index[qargs[0]], index[qargs[1]]
        if node.name == "swap":
            who[x], who[y] = who[y], who[x]
            events.append(("swap", (x, y)))
            continue
        a, b = who[x], who[y]
        k = queues[a][ptr[a]]
        if queues[b][ptr[b]] != k:
            raise AssertionError("SABRE reordered the gates of a qubit")  # pragma: no cover
        ptr[a] += 1
        ptr[b] += 1
        events.append(("gate", k))
    result = tuple(events)
    context.windows[key] = result
    return result


class PatchSabre(NamedTuple):
    """What SABRE on one patch shape needs, built once (:func:`patch_sabre`): the pass and its default trials,
    an empty circuit of the patch's qubits (register ``q``) and those qubits, the gate routed, the prepared
    routing call's arguments (``None``: another Qiskit, the pass runs itself) and how the routed circuit's qubits
    give their place (``None``: by their ``_index``)."""

    sabre: Any
    trials: int
    empty: Any
    bits: list[Any]
    gate: Any
    call: tuple[Any, Any, Any] | None
    index: dict[Any, int] | None


def patch_sabre(context: RoutingContext, coupling: tuple[tuple[int, int], ...], size: int) -> PatchSabre:
    """The context's :class:`PatchSabre` of a patch shape: building its pass builds a Qiskit ``Target`` and its
    routing tables, which takes longer than the routing of a window, so the context keeps one per shape."""
    key: Hashable = (coupling, size)
    hit = context.sabre_passes.get(key)
    if hit is None:
        from qiskit import QuantumRegister
        from qiskit.circuit.library import CXGate
        from qiskit.dagcircuit import DAGCircuit
        from qiskit.transpiler import CouplingMap
        from qiskit.transpiler.passes import SabreSwap

        if len(context.sabre_passes) >= SABRE_PASSES_KEPT:
            context.sabre_passes.clear()
        cmap = CouplingMap([list(e) for e in coupling] + [[b, a] for a, b in coupling])
        sabre = SabreSwap(sabre_target(cmap), heuristic="decay", trials=None)
        empty = DAGCircuit()
        reg = QuantumRegister(size, "q")
        empty.add_qreg(reg)
        bits = list(reg)
        registered = [getattr(q, "_index", None) for q in bits] == list(range(size))
        index = None if registered else {q: i for i, q in enumerate(bits)}
        hit = PatchSabre(sabre, sabre.trials, empty, bits, CXGate(), _prepared_call(sabre, size), index)
        context.sabre_passes[key] = hit
    return hit  # type: ignore[no-any-return]


def _prepared_call(sabre: Any, size: int) -> tuple[Any, Any, Any] | None:
    """The routing target, heuristic and trivial layout Qiskit 2's ``sabre_routing`` takes for the pass
    ``sabre`` on ``size`` qubits (:func:`run_sabre`), or ``None`` where Qiskit has no such call."""
    try:
        from qiskit._accelerate.nlayout import NLayout
        from qiskit._accelerate.sabre import Heuristic, RoutingTarget, SetScaling

        if sabre._routing_target is None:
            sabre._routing_target = RoutingTarget.from_target(sabre.target)
        heuristic = (
            Heuristic(attempt_limit=10 * size)
            .with_basic(1.0, SetScaling.Constant)
            .with_lookahead([0.5 / size], SetScaling.Constant)
            .with_decay(0.001, 5)
        )  # SabreSwap.run's "decay"
        return sabre._routing_target, heuristic, NLayout.generate_trivial_layout(size)
    except (ImportError, AttributeError, TypeError):  # pragma: no cover - another Qiskit: the pass itself
        return None


def run_sabre(shape: PatchSabre, dag: Any, seed: int, trials: int, parallel: bool = True) -> Any:
    """``shape.sabre.run(dag)`` (heuristic ``decay``, the pass given ``seed`` and ``trials``) without the pass's
    per-run checks: its routing call with the arguments the pass builds (Qiskit 2's ``sabre_routing``), prepared
    once per shape (:func:`patch_sabre`), where Qiskit has it; else the pass itself. The pass first checks that the
    circuit's qubits lie in one component of the coupling map (a patch is grown until they do,
    :func:`local_patch`) and rebuilds the coupling graph to do so, which costs more than routing a window. Both
    give the same routing. The trials run one after another (``run_in_parallel=False``) unless ``parallel`` and
    there are at least :data:`PARALLEL_MIN_TRIALS`: Qiskit keeps the trial of fewest SWAPs, the first of them on
    ties, either way, and on a window of a few dozen gates starting threads costs more CPU than it saves."""
    sabre = shape.sabre
    sabre.seed, sabre.trials = seed, trials
    if shape.call is None:  # pragma: no cover - another Qiskit: the pass itself
        sabre.property_set["final_layout"] = None
        return sabre.run(dag)
    from qiskit._accelerate.sabre import sabre_routing

    target, heuristic, layout = shape.call
    try:
        out, _ = sabre_routing(dag, target, heuristic, layout, trials, seed, parallel and trials >= PARALLEL_MIN_TRIALS)
    except TypeError:  # pragma: no cover - a Qiskit whose routing call has no run_in_parallel
        out, _ = sabre_routing(dag, target, heuristic, layout, trials, seed)
    return out
