"""A geometry-preserving placement on square-grid devices (the medial lattice) and local ancilla allocation.

**Placement** (:func:`medial_placement`). For an ``R x C`` problem grid, robot ``r``'s copy of the grid takes a
``(2R - 1) x (2C - 1)`` patch of the device: edge ``(i, j)-(i, j+1)`` sits on device site ``(2i, 2j+1)`` and
``(i, j)-(i+1, j)`` on ``(2i+1, 2j)`` (edge midpoints), node sites ``(2i, 2j)`` and plaquette centres
``(2i+1, 2j+1)`` stay free for ancillas. A plaquette's four edges are then device neighbours of its centre, an
outer edge and the plaquette edge it meets at a corner are both neighbours of that corner's node site. The ``k``
robots' patches are *tiled* by default (side by side, ``down x across`` patches with ``down across >= k``):
every partial mixer acts on one robot, so tiling keeps each partial mixer inside its own patch. The other
arrangement, ``interleave``, puts the ``k`` copies of every site side by side (a ``down x across`` block per
medial site), which brings the phase separator's per-node cross-robot terms together but stretches every
plaquette, and routes to more CX in both parts.

**Allocation** (:func:`allocate_ancillas`). Every section of a circuit compiled with ``fuse=False`` returns its
ancillas to |0> at both ends (``docs/architecture.md``, "Sections"), so each section may use *any* free device
qubits as its ancillas. Per section, in order of first use, each ancilla gets the free physical qubit (not a data
qubit's home, not taken by another ancilla of the same section) that minimises the interaction-weighted
shortest-path distance to the qubits it meets in that section (data qubits at their homes, ancillas already
allocated), ties broken by the distance to the section's data centroid, then by index. So a partial mixer's
ANDs land on the plaquette centre and the corner node sites, a phase gadget's registers next to its data. With
``search`` (what :func:`qcpp.pipeline.device_compile.compile_for_device` uses), each partial mixer's ancillas are also
tried on their next few best free qubits and the allocation whose window routes to the fewest two-qubit gates is
kept (3x3/1: 228 to 210 routed CX). The gate order is unchanged (the operator is unchanged); the circuit's
ancillas are renamed to one register ``site`` of the physical qubits used, and the returned layout sends each
logical qubit to its home.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.hardware.device import get_device
    >>> s = default_scenario(3, 3, 1)
    >>> medial_shape(s)
    (5, 5)
    >>> homes = medial_placement(s, get_device("grid:5x5"))
    >>> [divmod(homes[v], 5) for v in range(3)]  # edges (0,0)-(0,1), (0,0)-(1,0), (0,1)-(0,2)
    [(0, 1), (1, 0), (0, 3)]
    >>> medial_placement(s, get_device("grid:4x4")) is None  # too small: the caller falls back
    True
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from qcpp.hardware.device import Device, grid_coupling
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate
from qcpp.layout.heavy_hex import hex_placement
from qcpp.plan.phase_layout import tiling
from qcpp.problem.scenario import Scenario
from qcpp.routing.bridge import has_rzz
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.windows import route_window_cx

__all__ = ["allocate_ancillas", "allocate_section", "grid_shape", "medial_placement", "medial_shape"]


def grid_shape(device: Device) -> tuple[int, int] | None:
    """``(rows, cols)`` if the device's coupling is the square lattice of :func:`qcpp.hardware.device.grid_coupling`
    (qubit ``r * cols + c``), else ``None``."""
    if device.is_all_to_all or device.family != "grid":
        return None
    n = device.num_qubits
    for rows in range(1, n + 1):
        cols = n // rows
        edges = rows * (cols - 1) + cols * (rows - 1)
        if n % rows == 0 and len(device.coupling) == edges and device.coupling == grid_coupling(rows, cols):
            return rows, cols
    return None


ARRANGEMENTS = ("tile", "interleave")
"""How the robots' copies share the device: side by side, or interleaved site by site (see the module docs)."""


def _arrangement(scenario: Scenario, arrangement: str) -> tuple[int, int]:
    patch = (2 * scenario.grid.rows - 1, 2 * scenario.grid.cols - 1)
    if arrangement not in ARRANGEMENTS:
        raise ValueError(f"arrangement must be one of {', '.join(ARRANGEMENTS)}, not {arrangement!r}")
    return tiling(scenario.num_robots, patch if arrangement == "tile" else (1, 1))


def medial_shape(scenario: Scenario, arrangement: str = "tile") -> tuple[int, int]:
    """Rows and columns of device the medial layout of ``scenario`` spans."""
    down, across = _arrangement(scenario, arrangement)
    return down * (2 * scenario.grid.rows - 1), across * (2 * scenario.grid.cols - 1)


def medial_placement(scenario: Scenario, device: Device, arrangement: str = "tile") -> tuple[int, ...] | None:
    """Home of every data qubit (variable index -> physical qubit) on a square-grid device, or ``None`` if the
    device is not a square grid or the layout does not fit (``tile`` also tries the other arrangements of
    patches than :func:`~qcpp.plan.phase_layout.tiling`'s). On a heavy-hex lattice device:
    :func:`qcpp.layout.heavy_hex.hex_placement` (one heavy-hex cell per plaquette; ``arrangement`` does not apply).

    Args:
        scenario: The scenario.
        device: The device.
        arrangement: ``tile`` (robot ``r``'s patch is patch ``divmod(r, across)`` of a ``down x across``
            arrangement) or ``interleave`` (robot ``r = (dr, dc)`` of a ``down x across`` block takes medial site
            ``(a, b)`` to device site ``(down a + dr, across b + dc)``: the copies of one grid edge sit side by
            side, a plaquette is stretched by ``down`` and ``across``).
    """
    if device.family == "heavy-hex":
        return hex_placement(scenario, device)
    shape = grid_shape(device)
    if shape is None:
        return None
    g = scenario.grid
    patch = (2 * g.rows - 1, 2 * g.cols - 1)
    k = scenario.num_robots
    preferred = _arrangement(scenario, arrangement)
    if arrangement == "tile":
        fitting = [
            (down, across)
            for across in range(1, k + 1)
            if (down := -(-k // across)) * patch[0] <= shape[0] and across * patch[1] <= shape[1]
        ]
    else:
        fitting = [preferred] if preferred[0] * patch[0] <= shape[0] and preferred[1] * patch[1] <= shape[1] else []
    if not fitting:
        return None
    down, across = preferred if preferred in fitting else fitting[0]
    cols = shape[1]
    homes = []
    for v in range(scenario.num_variables):
        robot, e = scenario.variable_of(v)
        a, b = g.edge_sites[e]
        dr, dc = divmod(robot, across)
        if arrangement == "tile":
            row, col = dr * patch[0] + a, dc * patch[1] + b
        else:
            row, col = down * a + dr, across * b + dc
        homes.append(row * cols + col)
    return tuple(homes)


def _distances(device: Device) -> np.ndarray:
    from qcpp.hardware.device import distances

    return distances(device)


def _section_ancillas(gates: Sequence[Gate], n_data: int) -> tuple[list[int], dict[int, dict[int, int]], set[int]]:
    """A section's ancillas in order of first use, their two-qubit partners (with gate counts) and its data."""
    partners: dict[int, dict[int, int]] = {}
    order: list[int] = []
    data_in: set[int] = set()
    for g in gates:
        qs = g[1]
        for q in qs:
            if q >= n_data and q not in partners:
                partners[q] = {}
                order.append(q)
            elif q < n_data:
                data_in.add(q)
        if len(qs) == 2:
            a, b = qs
            if a >= n_data:
                partners[a][b] = partners[a].get(b, 0) + 1
            if b >= n_data:
                partners[b][a] = partners[b].get(a, 0) + 1
    return order, partners, data_in


def _ancilla_keys(
    order: list[int], partners: dict[int, dict[int, int]], centre: np.ndarray, to_free: np.ndarray,
    data_homes: Sequence[int], n_data: int,
) -> tuple[list[np.ndarray], list[list[tuple[int, float]]]]:  # fmt: skip
    """Per ancilla of ``order``: the part of its placement key (:func:`_place_ancillas`) that the other ancillas do
    not change (``centre`` plus 1e6 x its weighted distances to its data partners' homes), and its ancilla partners
    with their weights x 1e6. The search places a section's ancillas hundreds of times: this part is summed once.
    The keys are sums of integers, so exact in any order."""
    base: list[np.ndarray] = []
    links: list[list[tuple[int, float]]] = []
    for q in order:
        key = centre.copy()
        linked = []
        for partner, w in partners[q].items():
            if partner < n_data:
                key += (w * 1e6) * to_free[data_homes[partner]]
            else:
                linked.append((partner, w * 1e6))
        key.flags.writeable = False
        base.append(key)
        links.append(linked)
    return base, links


def _place_ancillas(
    order: list[int], base: list[np.ndarray], links: list[list[tuple[int, float]]], to_free: np.ndarray,
    free: np.ndarray, ranks: Sequence[int] = (), start: dict[int, int] | None = None,
) -> dict[int, int]:  # fmt: skip
    """Each ancilla (in ``order``) on the free qubit of least interaction-weighted distance to the qubits it
    meets that are already placed, ties by the distance to the section's data (:func:`_ancilla_key`);
    ``ranks[i] = r > 0`` puts ancilla ``order[i]`` on its ``r``-th best qubit instead (the search of
    :func:`allocate_ancillas`). ``to_free[p]``: the distances from device qubit ``p`` to the free qubits.
    ``start``: the first ancillas' placement, as this placed them (the search varies one ancilla at a time and
    places those before it once)."""
    home = dict(start) if start else {}
    busy = free.searchsorted(list(home.values())).tolist() if home else []
    for i in range(len(home), len(order)):
        key = _ancilla_key(i, base, links, to_free, home, busy)
        rank = ranks[i] if i < len(ranks) else 0
        j = _ranked(key, rank) if rank else int(key.argmin())
        if not math.isfinite(key[j]):
            j = int(key.argmin())
        busy.append(j)
        home[order[i]] = int(free[j])
    return home


def _ancilla_key(i: int, base: list[np.ndarray], links: list[list[tuple[int, float]]], to_free: np.ndarray,
                 home: dict[int, int], busy: Sequence[int]) -> np.ndarray:  # fmt: skip
    """The placement key of the ``i``-th ancilla over the free qubits, the ancillas before it at ``home`` (on the
    free qubits ``busy``, there infinite): ``base[i]`` plus 1e6 x the weighted distances to its ancilla partners
    ``links[i]`` (:func:`_ancilla_keys`; sums of integers, so exactly cost * 1e6 + centre)."""
    key = None  # a fresh array: base[i] is shared
    for partner, w in links[i]:
        at = home.get(partner)
        if at is not None:
            if key is None:
                key = base[i] + w * to_free[at]
            else:
                key += w * to_free[at]
    if key is None:
        key = base[i].copy()
    key[busy] = np.inf
    return key


def _choices(key: np.ndarray, ranks: int) -> list[int]:
    """Where :func:`_place_ancillas` puts an ancilla of this key with rank ``0 .. ranks``: the ``r``-th finite
    entry of the stable order (ties by index), else the first minimum (one pass per rank for all of them).

    >>> _choices(np.array([3.0, 1.0, 2.0, 1.0, np.inf]), 4)
    [1, 3, 2, 0, 1]
    """
    rest = key.copy()
    first = int(key.argmin())
    out = []
    for _ in range(ranks + 1):
        j = int(rest.argmin())
        out.append(j if math.isfinite(rest[j]) else first)
        rest[j] = np.inf
    return out


def _prefix_choices(i: int, base: list[np.ndarray], links: list[list[tuple[int, float]]], to_free: np.ndarray,
                    free: np.ndarray, prefix: dict[int, int], top: int) -> list[int]:  # fmt: skip
    """:func:`_choices` of the ``i``-th ancilla, the ancillas before it at ``prefix``: what
    :func:`_place_ancillas` does with it for each rank ``0 .. top``, its key built once for all of them."""
    busy = free.searchsorted(list(prefix.values())).tolist() if prefix else []
    return _choices(_ancilla_key(i, base, links, to_free, prefix, busy), top)


def _ranked(key: np.ndarray, rank: int) -> int:
    """``np.argsort(key, kind="stable")[rank]`` (ties by index) where that is finite, else ``argmin(key)``: the
    first minimum, ``rank`` times set aside (a few passes instead of a sort).

    >>> _ranked(np.array([3.0, 1.0, 2.0, 1.0, 2.0]), 2), _ranked(np.array([3.0, 1.0, 2.0, 1.0, 2.0]), 3)
    (2, 4)
    """
    rest = key.copy()
    for _ in range(rank):
        rest[int(rest.argmin())] = np.inf
    j = int(rest.argmin())
    return j if math.isfinite(rest[j]) else int(key.argmin())


def _search_key(gates: Sequence[Gate], data_homes: Sequence[int], n_data: int, taken: np.ndarray, device: Device,
                order: list[int], margin: int) -> tuple | None:  # fmt: skip
    """What the search's answer for a section depends on, up to translation on a square grid: its gates (data
    qubits as positions relative to the section's data, ancillas by order of first use), the occupied sites and
    the device's border within ``margin`` of that data
    (:attr:`~qcpp.routing.options.RoutingOptions.search_margin`; ``None``: not a square grid)."""
    shape = grid_shape(device)
    if shape is None:
        return None
    rows, cols = shape
    data = sorted({q for g in gates for q in g[1] if q < n_data})
    if not data:
        return None
    rc = [divmod(int(data_homes[q]), cols) for q in data]
    r0, c0 = min(r for r, _ in rc), min(c for _, c in rc)
    r1, c1 = max(r for r, _ in rc), max(c for _, c in rc)
    slot = {q: i for i, q in enumerate(order)}

    def rel(q: int) -> tuple:
        if q < n_data:
            r, c = divmod(int(data_homes[q]), cols)
            return ("d", r - r0, c - c0)
        return ("a", slot[q])

    body = tuple((g[0], tuple(rel(q) for q in g[1])) for g in gates if len(g[1]) == 2)
    lo_r, hi_r = max(0, r0 - margin), min(rows - 1, r1 + margin)
    lo_c, hi_c = max(0, c0 - margin), min(cols - 1, c1 + margin)
    box = taken.reshape(rows, cols)[lo_r : hi_r + 1, lo_c : hi_c + 1]
    shift = np.array([lo_r - r0, lo_c - c0])
    occupied = tuple(tuple(int(v) for v in rc_) for rc_ in np.argwhere(box) + shift)
    border = (lo_r - r0, hi_r - r0, lo_c - c0, hi_c - c0)
    return body, occupied, border, len(order)


def _routed_cost(twoq: Sequence[tuple[int, int]], home: dict[int, int], data_where: dict[int, int], device: Device,
                 dist: np.ndarray, options: RoutingOptions, context: RoutingContext) -> int:  # fmt: skip
    """Two-qubit gates of a section's window routed from home (as :func:`qcpp.routing.windows.route_windows` with
    ``options``, so the window the search keeps routes as measured): ``twoq`` its two-qubit gates' qubits,
    ``data_where`` the homes of its data qubits, ``home`` its ancillas'."""
    where = {**data_where, **home}
    pairs = [(where[a], where[b]) for a, b in twoq]
    return route_window_cx(pairs, None, device, dist, 0, options, context)


def _free_sites(
    context: RoutingContext, device: Device, d: np.ndarray, data_homes: tuple[int, ...]
) -> tuple[np.ndarray, ...]:
    """The occupied mask, the free qubits in the data's component and every qubit's distances to them; the context
    keeps the last answer (the cells' plan choice allocates one section at a time on the same homes)."""
    for dev, dist, homes, answer in context.free_sites:
        if dev is device and dist is d and homes == data_homes:
            return answer
    taken = np.zeros(device.num_qubits, dtype=bool)
    taken[list(data_homes)] = True
    reach = np.isfinite(d[data_homes[0]]) if data_homes else np.ones(device.num_qubits, dtype=bool)
    free = np.flatnonzero(~taken & reach)
    to_free = np.ascontiguousarray(d[:, free])  # row p: distances from p to the free qubits
    for a in (taken, free, to_free):
        a.flags.writeable = False  # shared between calls
    context.free_sites[:] = [(device, d, data_homes, (taken, free, to_free))]
    return taken, free, to_free


def allocate_ancillas(
    circuit: Circuit, data_homes: Sequence[int], device: Device, dist: np.ndarray | None = None,
    search: bool = False, options: RoutingOptions = DEFAULT_ROUTING, context: RoutingContext | None = None,
) -> tuple[Circuit, tuple[int, ...]]:  # fmt: skip
    """Give every section's ancillas the nearest free device qubits (see the module docs).

    Args:
        circuit: Lowered, compiled with ``fuse=False`` (every section clean at both ends); its first
            ``len(data_homes)`` qubits are the data qubits.
        data_homes: Physical qubit of every data qubit.
        device: The device.
        dist: Its all-pairs distances (:func:`qcpp.layout.placement.distances`), if already known.
        search: For every section of at most ``options.search_max_pairs`` two-qubit gates and no ``rzz`` (phase
            sections are left to :func:`qcpp.routing.bridge.bridge_far_phases`; in practice: the partial mixers),
            also try each ancilla on its 2nd .. (1 + ``options.search_ranks``)-th best free qubit (the later ones
            placed greedily after it), ``options.search_rounds`` rounds, and keep the allocation whose window
            routes to the fewest two-qubit gates (the greedy one on ties). The answer is memoised in ``context``
            per section up to translation on a square grid (:func:`_search_key`).
        options: The search's settings (:class:`~qcpp.routing.options.RoutingOptions`); its windows are routed
            with them.
        context: The run's memos and watches (default: a fresh one).

    Returns:
        ``(circuit, layout)``: the circuit with registers ``data`` and ``site`` (the physical qubits used as
        ancillas, ascending), and logical qubit -> physical qubit.

    Raises:
        ValueError: a section needs more ancillas than the device has free qubits (in the data's component).
    """
    d = _distances(device) if dist is None else dist
    context = RoutingContext() if context is None else context
    n_data = len(data_homes)
    taken, free, to_free = _free_sites(context, device, d, tuple(int(h) for h in data_homes))
    renamed: list[tuple[str, dict[int, int]]] = []  # per section: ancilla -> physical qubit
    used: set[int] = set()
    for sec in circuit.sections:
        home = _section_homes(sec, data_homes, device, d, search, options, context, taken, free, to_free)
        used.update(home.values())
        renamed.append((sec.name, home))
    sites = sorted(used)
    index = {p: n_data + i for i, p in enumerate(sites)}
    sections = []
    for sec, (_, home) in zip(circuit.sections, renamed, strict=True):
        rename = {q: index[p] for q, p in home.items()}
        sections.append(Section(sec.name, [Gate(g[0], tuple(rename.get(q, q) for q in g[1]), g[2], g[3])
                                           for g in sec.gates]))  # fmt: skip
    registers = [Register("data", n_data)] + ([Register("site", len(sites))] if sites else [])
    layout = (*(int(p) for p in data_homes), *sites)
    return Circuit(registers, sections), tuple(layout)


def allocate_section(
    section: Section, data_homes: Sequence[int], device: Device, dist: np.ndarray | None = None,
    search: bool = False, options: RoutingOptions = DEFAULT_ROUTING, context: RoutingContext | None = None,
) -> dict[int, int]:
    """The physical qubit of each ancilla of one section, as :func:`allocate_ancillas` allocates it (same
    arguments; a section's ancillas do not depend on the other sections'), without building the renamed circuit:
    what the cells' plan choice needs of every candidate section (:mod:`qcpp.pipeline.cellmixer`).

    Returns:
        Logical ancilla (a qubit ``>= len(data_homes)`` of ``section``) -> physical qubit.
    """
    d = _distances(device) if dist is None else dist
    context = RoutingContext() if context is None else context
    taken, free, to_free = _free_sites(context, device, d, tuple(int(h) for h in data_homes))
    return _section_homes(section, data_homes, device, d, search, options, context, taken, free, to_free)


def _section_homes(
    sec: Section, data_homes: Sequence[int], device: Device, d: np.ndarray, search: bool, options: RoutingOptions,
    context: RoutingContext, taken: np.ndarray, free: np.ndarray, to_free: np.ndarray,
) -> dict[int, int]:  # fmt: skip
    """:func:`allocate_section` with the free sites known (:func:`_free_sites`)."""
    n_data = len(data_homes)
    order, partners, data_in = _section_ancillas(sec.gates, n_data)
    if len(order) > len(free):
        raise ValueError(
            f"section {sec.name} needs {len(order)} ancillas; device {device.name} has {len(free)} free qubits"
        )
    centre = to_free[[data_homes[q] for q in sorted(data_in)]].sum(axis=0) if data_in else np.zeros(len(free))
    base, links = _ancilla_keys(order, partners, centre, to_free, data_homes, n_data)
    home = _place_ancillas(order, base, links, to_free, free)
    twoq = sum(1 for g in sec.gates if len(g[1]) == 2)
    if (search and order and twoq <= options.search_max_pairs and not device.is_all_to_all
            and not has_rzz(sec.gates)):  # fmt: skip
        shape_key = _search_key(sec.gates, data_homes, n_data, taken, device, order, options.search_margin)
        key = None if shape_key is None else (shape_key, options)
        ranks = context.allocations.get(key) if key is not None else None
        if ranks is None:
            twoq = [g[1] for g in sec.gates if len(g[1]) == 2]
            data_where = {q: int(data_homes[q]) for qs in twoq for q in qs if q < n_data}
            ranks = [0] * len(order)
            best = _routed_cost(twoq, home, data_where, device, d, options, context)  # type: ignore[arg-type]
            tried: dict[tuple, int] = {tuple(ranks): best, tuple(home.items()): best}  # a later round repeats
            top = min(options.search_ranks, len(free) - 1)
            for _ in range(options.search_rounds):
                improved = False
                prefix: dict[int, int] = {}  # the ancillas before the i-th, placed by the current ranks
                for i in range(len(order)):
                    choices = None  # where the i-th ancilla goes by rank (the ancillas before it at prefix)
                    for r in range(1 + top):
                        if r == ranks[i]:
                            continue
                        trial = [*ranks[:i], r, *ranks[i + 1 :]]
                        cost = tried.get(tuple(trial))
                        if cost is None:
                            if choices is None:
                                choices = _prefix_choices(i, base, links, to_free, free, prefix, top)
                            other = _place_ancillas(order, base, links, to_free, free, trial,
                                                    {**prefix, order[i]: int(free[choices[r]])})  # fmt: skip
                            placed = tuple(other.items())
                            cost = tried.get(placed)
                            if cost is None:
                                cost = tried[placed] = _routed_cost(twoq, other, data_where, device, d, options,
                                                                    context)  # type: ignore[arg-type]
                            tried[tuple(trial)] = cost
                        if cost < best:
                            best, ranks, improved = cost, trial, True
                    if choices is None:
                        choices = _prefix_choices(i, base, links, to_free, free, prefix, top)
                    prefix = {**prefix, order[i]: int(free[choices[ranks[i]]])}
                if not improved:
                    break
            ranks = tuple(ranks)
            if key is not None:
                context.allocations[key] = ranks
        if any(ranks):
            home = _place_ancillas(order, base, links, to_free, free, ranks)
    return home
