"""Routing section by section, every window returning each qubit home: the medial path's router.

:func:`route_windows` routes every section of a lowered circuit (a gadget: compute, rotate, uncompute) as a
*window* from the same home layout back to it (:func:`route_window`): SABRE routes the compute on the device qubits
around the section (a patch, :mod:`qcpp.routing.patches`), then the middle, whose SWAPs are then undone, and the
uncompute replays the compute's routed ops backwards. The result has ``initial_layout == final_layout``, and each
section's routed cost depends only on its gates and its neighbourhood on the device (the routed cost of a gadget
kind is fixed where the layout is translation-invariant: ``tests/compiler/medial_test.py``). Large windows (the
balance arithmetic) try several seeds and keep the whole window's cheapest
(:attr:`~qcpp.routing.options.RoutingOptions.large_window_pairs`). A middle of commuting blocks (the register
phase, an Ising phase: :mod:`qcpp.routing.commuting`) is also routed in any order, and the cheaper middle kept;
:func:`route_windows` then writes the section's blocks in the order they ran.

Searches route the same windows many times (the ancilla allocation's candidates, the heavy-hex cells' plan
variants, the relays' comparison), so a routed window is memoised in the run's
:class:`~qcpp.routing.context.RoutingContext` on its physical pairs, its seed and the settings its routing reads
(:attr:`~qcpp.routing.options.RoutingOptions.window_key`; on a heavy-hex lattice up to the lattice's translations,
where the qubits around the window are the same: :class:`~qcpp.routing.patches.Lattice`), with the patches its
routing saw, replayed into the context's open watches on a hit. A window routed ahead in another process
(:mod:`qcpp.routing.prefetch`, :func:`route_physical_window`) is taken, and replayed alike, on its first miss.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx
    >>> c = Circuit([("data", 3)], [Section("g", [cx(0, 2), cx(0, 2)])])
    >>> r = route_windows(c, get_device("grid:1x3"), (0, 1, 2))
    >>> r.initial_layout == r.final_layout, r.swaps
    (True, 2)
"""

from __future__ import annotations

from collections import deque
from collections.abc import Hashable, Sequence
from typing import Any, NamedTuple

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate
from qcpp.routing.commuting import commuting_blocks, graph_distances, route_blocks
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.patches import Coord, indexed_patch, patch_index, sabre_local
from qcpp.routing.positions import Positions
from qcpp.routing.routed_circuit import RoutedCircuit
from qcpp.routing.sabre import assemble, checked_inputs, window_cx

__all__ = [
    "Positions",
    "SeenRouting",
    "commuting_middle",
    "middle_order",
    "mirror_length",
    "prefetch_key",
    "route_physical_window",
    "route_window",
    "route_window_cx",
    "route_windows",
    "window_memoised",
]


def mirror_length(pairs: Sequence[tuple[int, int]]) -> int:
    """The largest ``m <= len(pairs) / 2`` such that the last ``m`` pairs are the first ``m`` reversed (as
    unordered pairs): a gadget's uncompute mirrors its compute.

    >>> mirror_length([(0, 1), (1, 2), (2, 3), (2, 1), (1, 0)])
    2
    """
    m = 0
    n = len(pairs)
    while m < n // 2:
        (a, b), (c, d) = pairs[m], pairs[n - 1 - m]
        if not ((a == c and b == d) or (a == d and b == c)):
            break
        m += 1
    return m


def commuting_middle(gates: Sequence[Gate]) -> tuple[tuple[int, int], ...] | None:
    """:func:`~qcpp.routing.commuting.commuting_blocks` of a window's middle, after its compute of
    :func:`mirror_length` two-qubit gates: what :func:`route_windows` routes in any order (``None``: nothing).

    >>> from qcpp.ir.gates import cx, rz
    >>> commuting_middle([cx(0, 1), cx(1, 2), rz(0.3, 2), cx(1, 2), cx(2, 3), rz(0.2, 3), cx(2, 3), cx(0, 1)])
    ((1, 3), (4, 6))
    """
    pairs = [g[1] for g in gates if len(g[1]) == 2]
    return commuting_blocks(gates, mirror_length(pairs))  # type: ignore[arg-type]


def _route_part(
    context: RoutingContext, pairs: list[tuple[int, int]], pos: Positions, device: Device, dist: Any, seed: int,
    trials: int | None, options: RoutingOptions,
) -> list[tuple]:  # fmt: skip
    """Route logical ``pairs`` from the current positions (``pos`` is not changed): ``("gate", k)`` and physical
    ``("swap", (p, q))`` in order."""
    if not pairs:
        return []
    if device.is_all_to_all:
        return [("gate", k) for k in range(len(pairs))]
    where = pos.where
    patch, coupling, local = indexed_patch(context, {where[q] for pr in pairs for q in pr}, device, dist,
                                           options.window_radius)  # fmt: skip
    lpairs = tuple([(local[where[a]], local[where[b]]) for a, b in pairs])
    if options.window_seeds == 1:
        best = sabre_local(context, coupling, len(patch), lpairs, seed, trials)
    else:
        best = min(
            (sabre_local(context, coupling, len(patch), lpairs, seed + i, trials) for i in range(options.window_seeds)),
            key=lambda evs: sum(ev[0] == "swap" for ev in evs),
        )
    return [("swap", (patch[ev[1][0]], patch[ev[1][1]])) if ev[0] == "swap" else ev for ev in best]


def _play(
    events: Sequence[tuple], pairs: Sequence[tuple[int, int]], pos: Positions
) -> list[tuple[str, tuple[int, int]]]:
    """Apply ``events`` to ``pos``: SWAPs move qubits (as :meth:`Positions.swap`), ``("gate", k)`` becomes
    ``("cx", pairs[k] at their positions)``."""
    out: list[tuple[str, tuple[int, int]]] = []
    append = out.append
    where, who = pos.where, pos.who
    for ev in events:
        if ev[0] == "swap":
            p, q = ev[1]
            a, b = who[p], who[q]
            who[p], who[q] = b, a
            if a >= 0:
                where[a] = q
            if b >= 0:
                where[b] = p
            append(ev)  # type: ignore[arg-type]
        else:
            a, b = pairs[ev[1]]
            append(("cx", (where[a], where[b])))
    return out


def route_window(
    pairs: list[tuple[int, int]], pos: Positions, device: Device, dist: Any, seed: int = 0,
    options: RoutingOptions = DEFAULT_ROUTING, context: RoutingContext | None = None, commuting: bool = False,
) -> list[tuple[str, tuple[int, int]]]:  # fmt: skip
    """One window's routed ops (``("cx", (p, q))``, ``("swap", (p, q))``), leaving every qubit where it was: the
    compute (the first :func:`mirror_length` pairs) is routed by SABRE, then the middle, whose SWAPs are undone
    in reverse, then the uncompute replays the compute's routed ops backwards (pair ``k`` of the compute is pair
    ``n - 1 - k`` of the uncompute).

    Args:
        pairs: The window's two-qubit gates on logical qubits.
        pos: Where every logical qubit is (unchanged on return).
        device: The target.
        dist: The device's all-pairs distances (:func:`qcpp.layout.placement.distances`).
        seed: SABRE's first seed.
        options: The routing settings (trials, patch radius, the large windows' search).
        context: The run's memos and watches (default: a fresh one).
        commuting: Whether the middle is a run of commuting blocks (:func:`commuting_middle` of the window's
            gates): its blocks may then run in another order
            (:attr:`~qcpp.routing.options.RoutingOptions.commuting_phases`; :func:`middle_order` reads which).

    Returns:
        The ops. They depend only on where the pairs' qubits are (the physical pairs), the device, ``seed``,
        ``commuting`` and ``options.window_key``, so they are memoised on those (module docs).
    """
    context = RoutingContext() if context is None else context
    entry, by = _memo_window(context, pairs, pos, device, dist, seed, options, commuting)
    if by is None:
        return list(entry[0])
    moved = patch_index(context, device, dist, options.window_radius).lattice.moved  # type: ignore[union-attr]
    return [(name, (moved(a, by), moved(b, by))) for name, (a, b) in entry[0]]


def route_window_cx(
    pairs: list[tuple[int, int]], pos: Positions | None, device: Device, dist: Any, seed: int = 0,
    options: RoutingOptions = DEFAULT_ROUTING, context: RoutingContext | None = None, commuting: bool = False,
) -> int:  # fmt: skip
    """``window_cx(route_window(...))``, memoised with the window (searches ask for the count only); ``pos``
    ``None``: every qubit on the physical qubit of its number (``pairs`` are physical)."""
    context = RoutingContext() if context is None else context
    return _memo_window(context, pairs, pos, device, dist, seed, options, commuting)[0][1]  # type: ignore[no-any-return]


def _memo_window(
    context: RoutingContext, pairs: list[tuple[int, int]], pos: Positions | None, device: Device, dist: Any,
    seed: int, options: RoutingOptions, commuting: bool = False,
) -> tuple[tuple[Any, ...], Coord | None]:  # fmt: skip
    """:func:`route_window`'s memo entry ``(ops, window_cx, patch qubits, whole-component parts, ...)`` and the
    lattice translation that takes its qubits to this window's (``None``: none needed)."""
    if device.is_all_to_all:
        pos = Positions.identity(device.num_qubits) if pos is None else pos
        ops, cx_ = _route_window(context, pairs, pos, device, dist, seed, options, commuting)
        return (tuple(ops), cx_, frozenset(), 0), None
    index = patch_index(context, device, dist, options.window_radius)
    if pos is None:
        physical = tuple(pairs)
    else:
        where = pos.where
        physical = tuple((where[a], where[b]) for a, b in pairs)
    settings = (seed, options.window_key, commuting and options.commuting_phases)
    lattice = index.lattice
    hit, key, translated_key, shift = _memo_entry(context, index, physical, settings)
    if hit is None:
        pos = Positions.identity(device.num_qubits) if pos is None else pos
        centres: set[int] = set()
        context.centres.append(centres)
        ahead = context.prefetched.pop(prefetch_key(device, physical, settings), None) if context.prefetched else None
        answer = ahead.result() if ahead is not None else None
        try:
            with context.watching() as watch:
                if answer is not None:  # routed ahead in another process: its answer, and what it saw, replayed
                    ops, cx_ = answer.ops, answer.cx
                    context.taken_ahead += 1
                    for open_centres in context.centres:
                        open_centres.update(answer.centres)
                    context.saw_patch(answer.qubits, answer.whole_component)
                else:
                    ops, cx_ = _route_window(context, pairs, pos, device, dist, seed, options, commuting)
        finally:
            del context.centres[next(i for i, c in enumerate(context.centres) if c is centres)]
        if len(context.windows) >= context.window_limit:
            context.windows.clear()
        hit = (tuple(ops), cx_, frozenset(watch.qubits), watch.whole_component, shift)
        if translated_key is not None and not watch.whole_component:
            context.windows.setdefault(translated_key, []).append((*lattice.around(centres, shift), hit))  # type: ignore[union-attr, arg-type]
        else:
            hit = context.windows[key] = (*hit[:4], None)
        return hit, None
    by = None if hit[4] is None or hit[4] == shift else (shift[0] - hit[4][0], shift[1] - hit[4][1])  # type: ignore[index]
    if context.watches:
        seen = hit[2] if by is None else {lattice.moved(q, by) for q in hit[2]}  # type: ignore[union-attr]
        context.saw_patch(seen, hit[3])
    return hit, by


def _memo_entry(
    context: RoutingContext, index: Any, physical: tuple[tuple[int, int], ...], settings: tuple
) -> tuple[tuple | None, tuple, tuple | None, Coord | None]:  # fmt: skip
    """The memo entry answering the window of ``physical`` pairs (``None``: none yet), its key on the physical
    pairs, and on a lattice the key of its translation class and the translation of its pairs (else ``None``): a
    translated entry answers where the qubits around its patches are the same; a window routed on its whole
    component, or on no lattice, is kept on its physical pairs."""
    key: tuple = ("window", index.token, physical, settings)
    lattice = index.lattice
    if lattice is None or not physical:
        return context.windows.get(key), key, None, None
    rel, shift = lattice.canonical(physical)
    translated_key = ("window", index.token, "translated", rel, settings)
    for cells, holds, entry in context.windows.get(translated_key, ()):
        if lattice.holds(cells, shift) == holds:
            return entry, key, translated_key, shift
    return context.windows.get(key), key, translated_key, shift


def window_memoised(
    context: RoutingContext, physical: tuple[tuple[int, int], ...], device: Device, dist: Any, seed: int,
    options: RoutingOptions, commuting: bool = False,
) -> bool:  # fmt: skip
    """Whether ``context`` already holds :func:`route_window`'s answer for the window of these physical pairs
    (as :func:`route_window_cx` with ``pos=None`` would find it)."""
    if device.is_all_to_all:
        return False
    index = patch_index(context, device, dist, options.window_radius)
    settings = (seed, options.window_key, commuting and options.commuting_phases)
    return _memo_entry(context, index, physical, settings)[0] is not None


class SeenRouting(NamedTuple):
    """A window routed without the window memo, and what its routing saw (:func:`route_physical_window`).

    Attributes:
        ops: The window's ops, as :func:`route_window` gives them.
        cx: Their :func:`~qcpp.routing.sabre.window_cx`.
        qubits: The device qubits of every patch routed.
        whole_component: Parts routed on their whole connected component.
        centres: The qubits the patches were grown around.
    """

    ops: list[tuple[str, tuple[int, int]]]
    cx: int
    qubits: frozenset[int]
    whole_component: int
    centres: frozenset[int]


def route_physical_window(
    context: RoutingContext, physical: Sequence[tuple[int, int]], device: Device, dist: Any, seed: int = 0,
    options: RoutingOptions = DEFAULT_ROUTING, commuting: bool = False,
) -> SeenRouting:  # fmt: skip
    """The window of ``physical`` pairs routed from home in ``context`` without its window memo (what
    :func:`route_window` computes on a miss), and what the routing saw, which a memo hit replays: the answer a
    process routing ahead hands back (:mod:`qcpp.routing.prefetch`)."""
    around: set[int] = set()
    context.centres.append(around)
    try:
        with context.watching() as watch:
            ops, cx_ = _route_window(context, list(physical), Positions.identity(device.num_qubits), device, dist,
                                     seed, options, commuting)  # fmt: skip
    finally:
        del context.centres[next(i for i, c in enumerate(context.centres) if c is around)]
    return SeenRouting(ops, cx_, frozenset(watch.qubits), watch.whole_component, frozenset(around))


def prefetch_key(device: Device, physical: tuple[tuple[int, int], ...], settings: tuple) -> Hashable:
    """The key of a window routed ahead (:attr:`RoutingContext.prefetched`): the device, the window's physical pairs
    and the settings its routing reads (``(seed, options.window_key, commuting phases)``)."""
    return id(device), physical, settings


def _route_window(
    context: RoutingContext, pairs: list[tuple[int, int]], pos: Positions, device: Device, dist: Any, seed: int,
    options: RoutingOptions, commuting: bool = False,
) -> tuple[list[tuple[str, tuple[int, int]]], int]:  # fmt: skip
    """:func:`route_window` without its memo, and the ops' :func:`~qcpp.routing.sabre.window_cx`."""
    m = mirror_length(pairs)
    trials = options.trials
    large = m >= options.large_window_pairs
    base_trials = options.large_window_trials if large and options.large_window_trials else trials
    tries = [(s, base_trials) for s in range(seed, seed + (options.large_window_seeds if large else 1))]
    if options.large_window_pairs <= m <= options.large_window_max_pairs and trials is not None:  # a wider search
        tries += [(s, max(trials, options.wide_window_trials)) for s in range(seed, seed + options.wide_window_seeds)]
    best: list[tuple[str, tuple[int, int]]] | None = None
    best_cx = 0
    for s, t in tries:  # each try returns every qubit home, so ``pos`` is unchanged between tries
        for ops in _window_ops(context, pairs, m, pos, device, dist, s, t, options, commuting):
            cx_ = window_cx(ops)
            if best is None or cx_ < best_cx:
                best, best_cx = ops, cx_
    assert best is not None
    return best, best_cx


def _window_ops(
    context: RoutingContext, pairs: list[tuple[int, int]], m: int, pos: Positions, device: Device, dist: Any,
    seed: int, trials: int | None, options: RoutingOptions, commuting: bool = False,
) -> list[list[tuple[str, tuple[int, int]]]]:  # fmt: skip
    """:func:`route_window` with one seed (``m``: the compute's length): the window's ops with SABRE's middle and,
    if the middle is a run of commuting blocks, with :func:`~qcpp.routing.commuting.route_blocks`'s."""
    n = len(pairs)
    middle_pairs = pairs[m : n - m]
    compute = _route_part(context, pairs[:m], pos, device, dist, seed, trials, options)
    ops = _play(compute, pairs, pos)
    middles = [_route_part(context, middle_pairs, pos, device, dist, seed, trials, options)]
    paired = len(middle_pairs) % 2 == 0 and middle_pairs[::2] == middle_pairs[1::2]  # blocks: two equal cx each
    if commuting and options.commuting_phases and middle_pairs and paired and not device.is_all_to_all:
        middles.append(_route_blocks(context, middle_pairs, pos, device, dist, options))
    mirrored = pairs[::-1]  # the uncompute's k-th pair from the end is mirrored[k]
    out = []
    for middle in middles:
        window = ops + _play(middle, middle_pairs, pos)
        window += _play([ev for ev in reversed(middle) if ev[0] == "swap"], pairs, pos)
        out.append(window)
    uncompute = _play(list(reversed(compute)), mirrored, pos)
    return [window + uncompute for window in out]


def _route_blocks(
    context: RoutingContext, pairs: list[tuple[int, int]], pos: Positions, device: Device, dist: Any,
    options: RoutingOptions,
) -> list[tuple]:  # fmt: skip
    """:func:`~qcpp.routing.commuting.route_blocks` of a commuting middle (``pairs``: its blocks' ``cx``, two per
    block) on the patch SABRE routes it on (so the route depends only on that patch, as SABRE's does), as
    :func:`_route_part`'s events."""
    where = pos.where
    patch, coupling, local = indexed_patch(context, {where[q] for pr in pairs for q in pr}, device, dist,
                                           options.window_radius)  # fmt: skip
    key = ("patch graph", coupling, len(patch))
    graph = context.windows.get(key)
    if graph is None:
        neighbours: list[list[int]] = [[] for _ in patch]
        for a, b in coupling:
            neighbours[a].append(b)
            neighbours[b].append(a)
        graph = context.windows[key] = (neighbours, graph_distances(neighbours))
    blocks = [(local[where[a]], local[where[b]]) for a, b in pairs[::2]]
    events = route_blocks(blocks, graph[0], graph[1])
    return [("swap", (patch[ev[1][0]], patch[ev[1][1]])) if ev[0] == "swap" else ev for ev in events]


def middle_order(
    ops: Sequence[tuple[str, tuple[int, int]]], pairs: Sequence[tuple[int, int]], pos: Positions
) -> list[int]:
    """The order a window's routed ``ops`` (from ``pos``) run its commuting middle's blocks in: the blocks (two
    ``cx`` each, after the compute's :func:`mirror_length` pairs of ``pairs``) as indices into the middle, in the
    order their first ``cx`` runs; blocks on the same two qubits keep their relative order.

    >>> pos = Positions((0, 1, 2), 3)
    >>> middle_order([("cx", (1, 2)), ("cx", (1, 2)), ("cx", (0, 1)), ("cx", (0, 1))], [(0, 1)] * 2 + [(1, 2)] * 2, pos)
    [1, 0]
    """
    n = len(pairs)
    m = mirror_length(pairs)
    blocks: dict[frozenset[int], deque[int]] = {}
    for j, pair in enumerate(pairs[m : n - m : 2]):
        blocks.setdefault(frozenset(pair), deque()).append(j)
    who = dict(enumerate(pos.who))
    order: list[int] = []
    open_: dict[frozenset[int], int] = {}
    k = 0
    for name, (p, q) in ops:
        if name == "swap":
            who[p], who[q] = who[q], who[p]
            continue
        if m <= k < n - m:
            key = frozenset((who[p], who[q]))
            if key in open_:
                del open_[key]
            else:
                open_[key] = blocks[key].popleft()
                order.append(open_[key])
        k += 1
    return order


def route_windows(
    circuit: Circuit,
    device: Device,
    layout: Sequence[int],
    seed: int = 0,
    measured: Sequence[int] | None = None,
    dist: Any = None,
    options: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> RoutedCircuit:
    """Route every section as a window that returns every qubit home (:func:`route_window`): the routed
    circuit's final layout is its initial layout, and a window's routed cost depends only on its gates and the
    device around its qubits.

    Args:
        circuit: Lowered, one section per gadget.
        device: The target.
        layout: Logical qubit ``i`` -> physical qubit (the home of every qubit).
        seed: SABRE's seed.
        measured: Logical qubits measured at the end (default: the ``data`` register, else all).
        dist: The device's all-pairs distances (:func:`qcpp.layout.placement.distances`), if already known.
        options: The routing settings (:meth:`~qcpp.routing.options.RoutingOptions.for_cells` on the heavy-hex
            cells).
        context: The run's memos and watches (default: a fresh one).

    Returns:
        The :class:`~qcpp.routing.routed_circuit.RoutedCircuit` (``initial_layout == final_layout == layout``).
    """
    from qcpp.hardware.device import distances

    context = RoutingContext() if context is None else context
    gates, section_of, home, measured_ = checked_inputs(circuit, device, layout, measured)
    if dist is None:
        dist = distances(device)
    pos = Positions(home, device.num_qubits)
    ops: list[tuple[str, tuple[int, int]]] = []
    owners: list[str] = []
    op_window: list[int] = []
    gate_window: list[int] = []
    sections = list(circuit.sections)
    for w, sec in enumerate(sections):
        pairs = [g[1] for g in sec.gates if len(g[1]) == 2]
        blocks = commuting_middle(sec.gates) if options.commuting_phases else None
        window = route_window(pairs, pos, device, dist, seed, options, context, blocks is not None)  # type: ignore[arg-type]
        if blocks is not None:
            reordered = _reordered(sec, blocks, middle_order(window, pairs, pos))  # type: ignore[arg-type]
            if reordered is not None:
                sections[w] = reordered
        ops += window
        owners += [sec.name] * len(window)
        op_window += [w] * len(window)
        gate_window += [w] * len(sec.gates)
    if sections != list(circuit.sections):
        gates = [g for sec in sections for g in sec.gates]
    return assemble(gates, section_of, home, device.num_qubits, ops, device, measured_, owners,
                    (gate_window, op_window))  # fmt: skip


def _reordered(section: Section, blocks: Sequence[tuple[int, int]], order: Sequence[int]) -> Section | None:
    """``section`` with its commuting middle's blocks (gate indices, :func:`~qcpp.routing.commuting.commuting_blocks`)
    in ``order``, each block with the diagonal one-qubit gates between it and the block written before it (the gates
    before the first block stay where they are); ``None`` where every qubit meets its blocks in the order written
    (the routed circuit is then the same without reordering)."""
    pairs = [frozenset(section.gates[i][1]) for i, _ in blocks]
    per_qubit: dict[int, list[int]] = {}
    for j in range(len(blocks)):
        for q in pairs[j]:
            per_qubit.setdefault(q, []).append(j)
    rank = {j: r for r, j in enumerate(order)}
    if all(rank[a] < rank[b] for js in per_qubit.values() for a, b in zip(js, js[1:])):
        return None
    gates = section.gates
    start, end = blocks[0][0], blocks[-1][1] + 1
    units = [gates[start : blocks[0][1] + 1]] + [gates[blocks[j - 1][1] + 1 : blocks[j][1] + 1]
                                                  for j in range(1, len(blocks))]  # fmt: skip
    middle = [g for j in order for g in units[j]]
    return Section(section.name, (*gates[:start], *middle, *gates[end:]))
