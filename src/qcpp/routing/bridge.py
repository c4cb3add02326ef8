"""Far two-qubit phases through clean device qubits: a copy chain instead of SWAPs there and back.

A lowered ``rzz`` is ``cx a b; rz b; cx a b``. When ``a`` and ``b`` sit far apart on the device (a node's visit
bits of two robots live in different robot patches of the medial layout; :mod:`qcpp.layout.medial`), a router
moves one of them next to the other with SWAPs (3 CX per step) and, in a window that returns home
(:func:`qcpp.routing.windows.route_windows`), moves it back: about ``6 d`` CX for distance ``d``. The phase only
needs the *value* of ``a`` next to ``b``: copy it into a clean device qubit ``h`` next to ``b`` along a chain of
clean qubits, apply ``cx h b; rz b; cx h b``, and undo the chain (its CX in reverse order). A chain step into
a clean neighbour is one CX (``cx u v``: ``v = u``); a step into a clean qubit two steps away goes through any
qubit ``m`` between them, whatever it holds, with four (``cx u m; cx m v; cx u m; cx m v``: ``v ^= u``, ``m``
unchanged). On the medial layout clean qubits are every other site (node sites and plaquette centres), so the
chain costs about ``2 d`` CX each way and the phase about ``4 d`` instead of ``6 d``. Where ``b`` has no clean
neighbour (a plaquette centre's neighbours are all edges), the chain ends two steps from ``b`` and each
``cx h b`` is the 4-CX step above. Copying ``b`` next to ``a`` instead (``cx a h; rz h; cx a h``, ``h`` holding
``b``) phases the same parity; the cheaper side wins. In a run of ``rzz`` and ``rz`` (no qubit's value changes
inside it) copies stay until the run's end and serve its later terms, and they travel towards the run's hub (the
member of least total distance to the others), so a node visited by three robots copies two visit bits once.

:func:`bridge_far_phases` rewrites a circuit section by section (every section is clean at both ends, so any
device qubit that is neither a data qubit's home nor used by the section is |0> inside it) and keeps a
rewritten section only where its window routes to fewer two-qubit gates than the original one (both routed
from home with :func:`qcpp.routing.windows.route_window`, as :func:`~qcpp.routing.windows.route_windows` will):
never worse, window by window. Sections of more than :data:`MAX_PAIRS` two-qubit gates are left alone. The gates
of the section other than the far phases, and their order, are
unchanged; on every input whose non-data device qubits start in |0> the rewritten circuit equals the original
one (``tests/compiler/bridge_test.py``: basis-state and statevector checks, QCEC on routed circuits).

Example:
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx, rz
    >>> from qcpp.hardware.device import get_device
    >>> c = Circuit([("data", 2)], [Section("phase", [cx(0, 1), rz(0.4, 1), cx(0, 1)])])
    >>> out, layout = bridge_far_phases(c, (0, 8), get_device("grid:1x9"))
    >>> layout  # the copy of qubit 0 travels over the clean qubits 1..7
    (0, 8, 1, 2, 3, 4, 5, 6, 7)
    >>> [g.name for g in out.gates].count("cx"), out.num_qubits
    (16, 9)
"""

from __future__ import annotations

import heapq
from collections.abc import Sequence
from typing import Any

import numpy as np

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate, cx
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.sabre import window_cx
from qcpp.routing.windows import Positions, commuting_middle, route_window

__all__ = ["bridge_far_phases", "copy_chain", "has_rzz"]

BRIDGE_STEP_CX = 4
"""CX of one chain step into a clean qubit two steps away, through whatever qubit lies between."""


def _bridged_cx(c: int, t: int, dist: Any) -> list[tuple[int, int]]:
    """``t ^= c`` as CX pairs: one CX between neighbours, four through a qubit ``m`` between them (``cx c m; cx m t;
    cx c m; cx m t``, ``m`` unchanged whatever it holds)."""
    if dist[c, t] == 1:
        return [(c, t)]
    m = int(np.flatnonzero((dist[c] == 1) & (dist[t] == 1))[0])
    return [(c, m), (m, t), (c, m), (m, t)]


def _within_two(context: RoutingContext, dist: Any) -> dict[int, list[tuple[int, int]]]:
    """Per qubit asked about so far, the other qubits one or two steps away with their distance, ascending (the
    context keeps them for the last distance matrix: a relay pass asks for chains on one device)."""
    if not context.within_two or context.within_two[0][0] is not dist:
        context.within_two[:] = [(dist, {})]
    return context.within_two[0][1]


def _near(u: int, dist: Any, within: dict[int, list[tuple[int, int]]]) -> list[tuple[int, int]]:
    hit = within.get(u)
    if hit is None:
        near = np.flatnonzero((dist[u] <= 2) & (dist[u] > 0))
        hit = within[u] = list(zip(near.tolist(), dist[u, near].astype(int).tolist(), strict=True))
    return hit


def copy_chain(
    source: int, target: int, clean: set[int], dist: Any, within: dict[int, list[tuple[int, int]]] | None = None
) -> tuple[list[tuple[int, int]], int] | None:
    """The cheapest chain copying ``source`` into a clean qubit (the *holder*) within two steps of ``target``.

    Chain steps are CX into a clean neighbour (1 CX) or into a clean qubit two steps away (4 CX, through any
    qubit); the holder then acts on ``target`` twice (``cx h t`` or its 4-CX bridge), so the chain wins where
    ``2 chain + 2 x (1 or 4)`` is smallest.

    Args:
        source: Physical qubit whose value is copied.
        target: Physical qubit the copy must end near.
        clean: Physical qubits that are |0> (the chain's holders).
        dist: All-pairs device distances (:func:`qcpp.layout.placement.distances`).
        within: Per qubit, the qubits one or two steps away with their distance, for ``dist`` (filled as asked;
            default: a fresh table).

    Returns:
        ``(CX pairs (control, target) in order, the holder)``, or ``None`` when ``source`` is within two steps
        of ``target`` (nothing to gain) or no chain exists.
    """
    if dist[source, target] <= 2:
        return None
    within = {} if within is None else within
    best: dict[int, int] = {source: 0}
    back: dict[int, tuple[int, int]] = {}
    heap = [(0, source)]
    goal: tuple[int, int] | None = None  # (total CX, holder)
    while heap and clean:
        cost, u = heapq.heappop(heap)
        if cost > best.get(u, 1 << 30) or (goal is not None and 2 * cost >= goal[0]):
            continue
        if u != source and dist[u, target] <= 2:
            total = 2 * cost + 2 * (1 if dist[u, target] == 1 else BRIDGE_STEP_CX)
            if goal is None or total < goal[0]:
                goal = (total, u)
        for v, step in _near(u, dist, within):  # ascending, as when the clean qubits were sorted per call
            if v not in clean:
                continue
            new = cost + (1 if step == 1 else BRIDGE_STEP_CX)
            if new < best.get(v, 1 << 30):
                best[v] = new
                back[v] = (u, int(step))
                heapq.heappush(heap, (new, v))
    if goal is None:
        return None
    hops: list[tuple[int, int]] = []
    v = goal[1]
    while v != source:
        u, _ = back[v]
        hops.append((u, v))
        v = u
    pairs = [p for u, v in reversed(hops) for p in _bridged_cx(u, v, dist)]
    return pairs, goal[1]


def _holders(pairs: Sequence[tuple[int, int]], clean: set[int]) -> list[int]:
    """The clean qubits that hold the chain's source value after ``pairs`` (through-qubits are restored)."""
    content: dict[int, int] = {}  # qubit -> parity of the original qubits it holds (a bit mask over ids)
    ids: dict[int, int] = {}
    for pair in pairs:
        for q in pair:
            if q not in content:
                ids[q] = len(ids)
                content[q] = 0 if q in clean else 1 << ids[q]
    c, _ = pairs[0]
    for u, v in pairs:
        content[v] ^= content[u]
    return [q for q in content if q in clean and content[q] == 1 << ids[c]]


def _is_rzz(gates: Sequence[Gate], i: int) -> bool:
    if i + 2 >= len(gates):
        return False
    a, r, b = gates[i], gates[i + 1], gates[i + 2]
    return (a[0] == b[0] == "cx" and a[1] == b[1] and r[0] == "rz" and r[1] == (a[1][1],))


def has_rzz(gates: Sequence[Gate]) -> bool:
    """Whether ``gates`` contain a lowered ``rzz`` (``cx a b; rz b; cx a b``)."""
    return any(_is_rzz(gates, i) for i in range(len(gates)))


def _phase_block(gates: Sequence[Gate], i: int) -> int:
    """End of the run of ``rzz`` patterns and ``rz`` gates that starts at ``i`` (``i`` itself: no run)."""
    j = i
    while j < len(gates):
        if _is_rzz(gates, j):
            j += 3
        elif gates[j][0] == "rz":
            j += 1
        else:
            break
    return j


def _hubs(block: Sequence[Gate], dist: Any) -> dict[int, int]:
    """Per qubit of the run's ``rzz``: the hub of its group (qubits joined by ``rzz``), the member of least total
    distance to the others."""
    parent: dict[int, int] = {}

    def root(q: int) -> int:
        while parent.setdefault(q, q) != q:
            q = parent[q]
        return q

    for i in range(len(block)):
        if _is_rzz(block, i):
            a, b = block[i][1]
            parent[root(a)] = root(b)
    groups: dict[int, list[int]] = {}
    for q in parent:
        groups.setdefault(root(q), []).append(q)
    hub: dict[int, int] = {}
    for members in groups.values():
        centre = min(members, key=lambda q: (sum(dist[q, p] for p in members), q))
        hub.update(dict.fromkeys(members, centre))
    return hub


MAX_PAIRS = 500
"""Sections with more two-qubit gates than this are left as they are: in the balance arithmetic's one large
window the register phase runs after a compute that SABRE routes with drift, so distances at home say little
there (relayed, that window routed to more CX on 4x4/2 and on 6x6/3 when tried), and routing it twice costs
seconds."""

SWAP_CX = 3
"""CX of a SWAP: a router brings a far qubit next to its partner and back for about ``2 x 3 (d - 1)`` CX."""


def _relay_block(
    block: Sequence[Gate], clean: set[int], dist: Any, within: dict[int, list[tuple[int, int]]]
) -> list[Gate] | None:
    """A run of ``rzz`` and ``rz`` (diagonal: no qubit's value changes inside it) with far ``rzz`` relayed.

    Copies made for one ``rzz`` stay until the end of the run and serve later ``rzz`` on the same qubit (a
    node's third robot, a register bit's other partners); every chain is undone, in reverse order, at the end.
    A far ``rzz`` stays as it is where SWAPs there and back (:data:`SWAP_CX`) are estimated cheaper.
    """
    clean = set(clean)
    hub = _hubs(block, dist)
    copies: dict[int, list[int]] = {}  # qubit -> holders of its value
    out: list[Gate] = []
    relays: list[list[Gate]] = []
    i = 0
    while i < len(block):
        if not _is_rzz(block, i):
            out.append(block[i])
            i += 1
            continue
        (a, b), rz_gate = block[i][1], block[i + 1]
        i += 3
        here = [(s, t, side) for side, (x_, y_) in enumerate(((a, b), (b, a)))
                for s in (x_, *copies.get(x_, ())) for t in (y_, *copies.get(y_, ()))]  # fmt: skip
        near = [(2 * len(_bridged_cx(s, t, dist)), s, t, side) for s, t, side in here
                if dist[s, t] <= 2 and (s, t) not in ((a, b), (b, a))]  # fmt: skip
        stay = 2 * SWAP_CX * (int(dist[a, b]) - 1) + 2
        best: tuple = (stay, None, None, 0, None)
        if near:
            best = min(best, (*min(near), None), key=lambda o: o[0])
        for s, t, side in here:
            value, other = (a, b)[side], (b, a)[side]
            if dist[value, hub[value]] < dist[other, hub[other]]:
                continue  # copies travel towards the hub, where the run's other terms can reuse them
            found = copy_chain(s, t, clean, dist, within)
            if found is not None:
                chain, holder = found
                cost = 2 * len(chain) + 2 * len(_bridged_cx(holder, t, dist))
                if cost < best[0]:
                    best = (cost, holder, t, side, chain)
        _, s, t, side, chain = best
        if s is None:
            out += [cx(a, b), rz_gate, cx(a, b)]
            continue
        if chain is not None:
            relay = [cx(*p) for p in chain]
            out += relay
            relays.append(relay)
            value = (a, b)[side]
            for v in _holders(chain, clean):
                clean.discard(v)
                copies.setdefault(value, []).append(v)
        # s holds the value of (a, b)[side], t of the other: (cx s t; rz t; cx s t) phases the parity a ^ b
        hit = [cx(*p) for p in _bridged_cx(s, t, dist)]
        out += [*hit, Gate(rz_gate[0], (t,), rz_gate[2], rz_gate[3]), *hit]
    if not relays:
        return None
    for relay in reversed(relays):
        out += relay[::-1]
    return out


def _rewrite(
    gates: list[Gate], clean: set[int], dist: Any, within: dict[int, list[tuple[int, int]]]
) -> list[Gate] | None:
    """The section's gates (physical qubits) with far ``rzz`` relayed by copy chains (``None``: none)."""
    out: list[Gate] = []
    changed = False
    i = 0
    while i < len(gates):
        j = _phase_block(gates, i)
        if j == i:
            out.append(gates[i])
            i += 1
            continue
        new = _relay_block(gates[i:j], clean, dist, within)
        out += gates[i:j] if new is None else new
        changed |= new is not None
        i = j
    return out if changed else None


def _routed_twoq(
    gates: Sequence[Gate], device: Device, dist: Any, options: RoutingOptions, context: RoutingContext
) -> int:
    """Two-qubit gates of the section's window (physical qubits) routed from home, as
    :func:`~qcpp.routing.windows.route_windows` routes it."""
    pairs = [g[1] for g in gates if len(g[1]) == 2]
    commuting = options.commuting_phases and commuting_middle(gates) is not None
    ops = route_window(pairs, Positions.identity(device.num_qubits), device, dist, 0, options, context,  # type: ignore[arg-type]
                       commuting)  # fmt: skip
    return window_cx(ops)


def bridge_far_phases(
    circuit: Circuit,
    layout: Sequence[int],
    device: Device,
    dist: Any = None,
    only_if_cheaper: bool = True,
    options: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> tuple[Circuit, tuple[int, ...]]:
    """Relay far ``rzz`` phases through clean device qubits where that routes to fewer gates (module docs).

    Args:
        circuit: Lowered, every section clean at both ends, first register ``data`` (e.g. the output of
            :func:`qcpp.layout.medial.allocate_ancillas`).
        layout: Logical qubit -> physical qubit (home) of every qubit of ``circuit``.
        device: The device.
        dist: Its all-pairs distances, if already known.
        only_if_cheaper: Keep a rewritten section only where its window routes to fewer two-qubit gates
            (``False``: keep every rewrite; for tests).
        options: The routing settings the windows are compared with (those of the final routing).
        context: The run's memos and watches (default: a fresh one).

    Returns:
        ``(circuit, layout)``: registers ``data`` and ``site`` (every other physical qubit used, ascending),
        and logical qubit -> physical qubit.
    """
    from qcpp.hardware.device import distances

    d = distances(device) if dist is None else dist
    context = RoutingContext() if context is None else context
    within = _within_two(context, d)
    first = circuit.registers[0] if circuit.registers else None
    n_data = first.size if first is not None and first.name == "data" else 0
    homes = [int(p) for p in layout[:n_data]]
    reach = np.isfinite(d[homes[0]]) if homes else np.ones(device.num_qubits, dtype=bool)
    spare = set(np.flatnonzero(reach).tolist()) - set(homes)
    sections: list[tuple[str, list[Gate]]] = []
    for sec in circuit.sections:
        gates = [Gate(g[0], tuple(int(layout[q]) for q in g[1]), g[2], g[3]) for g in sec.gates]
        used = {q for g in gates for q in g[1]}
        new = _rewrite(gates, spare - used, d, within) if sum(len(g[1]) == 2 for g in gates) <= MAX_PAIRS else None
        if new is not None and (
            not only_if_cheaper
            or _routed_twoq(new, device, d, options, context) < _routed_twoq(gates, device, d, options, context)
        ):
            gates = new
        sections.append((sec.name, gates))
    sites = sorted({q for _, gates in sections for g in gates for q in g[1]} - set(homes))
    index = {p: i for i, p in enumerate(homes)} | {p: n_data + i for i, p in enumerate(sites)}
    out = [Section(name, [Gate(g[0], tuple(index[q] for q in g[1]), g[2], g[3]) for g in gates])
           for name, gates in sections]  # fmt: skip
    registers = [Register("data", n_data)] + ([Register("site", len(sites))] if sites else [])
    return Circuit(registers, out), (*homes, *sites)
