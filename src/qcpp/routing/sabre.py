"""Routing a lowered circuit onto a device with Qiskit's SABRE, seeded with our layout; native gates; ESP, duration.

:func:`route` takes a lowered circuit (``cx`` plus one-qubit gates) and an initial layout (logical qubit ``i``
-> physical qubit) and returns a :class:`RoutedCircuit` on the device's physical qubits (IR qubit ``i`` is
physical qubit ``i``, so OpenQASM's ``q[i]`` is physical ``i``). Only the two-qubit gates are handed to Qiskit's
``SabreSwap`` (a well-kept router: we do not write our own); the routed order of two-qubit gates and the SWAPs
it inserts are read back, every one-qubit gate of ours is put back on its qubit's current physical position just
before that qubit's next two-qubit gate, and every SWAP becomes three ``cx``. Our gates keep their angles (also
symbolic ones) and their section names (a SWAP belongs to the section of the gate before it). A SWAP next to a
``cx`` on the same two qubits (nothing between them on either) is fused with it into two ``cx`` instead of four
in :func:`route_windows` and in :func:`route` with ``fuse=True`` (:func:`_assemble`; :attr:`RoutedCircuit.fused`
counts them). Routing never
reorders the gates of one logical qubit, so the routed circuit equals the original up to the layouts:
``routed = P_final . original . P_initial^-1`` on inputs whose unused physical qubits are |0>
(``tests/qcpp/routing_test.py`` checks it with a statevector and with QCEC).

:func:`route_windows` routes section by section instead, each section (a gadget: compute, rotate, uncompute)
from the same home layout back to it: SABRE routes the compute on the device qubits around the section, then
the middle, whose SWAPs are then undone, and the uncompute replays the compute's routed ops backwards
(:func:`route_window`). Its result has ``initial_layout == final_layout``, and each section's routed cost
depends only on its gates and its neighbourhood on the device (the routed cost of a gadget kind is fixed where
the layout is translation-invariant: ``tests/qcpp/medial_test.py``). Searches route the same windows many
times (the ancilla allocation's candidates, the heavy-hex cells' plan variants), so a routed window is memoised
on its physical pairs and settings (on a heavy-hex lattice up to the lattice's translations, where the qubits
around the window are the same: :class:`_Lattice`), SABRE's routing of a patch on the patch's shape and the pairs,
and the patches themselves per device (:data:`_WINDOW_CACHE`); SABRE is called as ``SabreSwap`` calls it, without
the pass's per-run checks (:func:`_run_sabre`), and its routed DAG is read directly.

:func:`to_native` rewrites a routed circuit into the device's native gates (exact up to a global phase):
``cx = h cz h`` and ``cz = rz(pi/2) rz(pi/2) rzz(-pi/2)`` (trapped ions); ``h = rz(pi/2) sx rz(pi/2)`` where
``sx`` is written ``rx(pi/2)`` (the IR has no ``sx``; the device's ``sx`` error and duration are charged for
it); ``t, tdg, s, sdg`` are ``rz`` of their angle; ``x`` stays ``x`` where native (``rx(pi)`` otherwise).

:func:`esp` is the estimated success probability: the product of ``(1 - error)`` over every gate of the
native circuit (per qubit / per coupling, from the device data) and of ``(1 - readout error)`` over the
measured qubits (the data qubits at their final positions). Idle decoherence, crosstalk and leakage are not
modelled. :func:`duration_s` is the ASAP schedule's length with the device's per-gate durations plus one
readout, or ``None`` where the device publishes no durations.

Example:
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx, h
    >>> from qcpp.devices.device import get_device
    >>> c = Circuit([("data", 3)], [Section("s", [h(0), cx(0, 1), cx(0, 2), cx(1, 2)])])
    >>> r = route(c, get_device("grid:1x3"), initial_layout=(0, 1, 2))
    >>> r.circuit.num_qubits, r.swaps, r.initial_layout, r.final_layout
    (3, 1, (0, 1, 2), (0, 2, 1))
    >>> all(g[0] != "cx" or tuple(sorted(g[1])) in {(0, 1), (1, 2)} for g in r.circuit.gates)
    True
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Hashable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

from qcpp.devices.device import Device
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate, cx, cz, rx, rz, rzz

__all__ = [
    "PatchWatch",
    "Positions",
    "RoutedCircuit",
    "coupling_map",
    "duration_s",
    "embed_routed",
    "esp",
    "mirror_length",
    "route",
    "route_window",
    "route_windows",
    "to_native",
    "watching_patches",
    "window_cx",
]

DEFAULT_TRIALS = 16
"""SABRE trials per routing: the best of 16 randomised routings (Qiskit's default is the CPU count)."""


@dataclass(frozen=True)
class RoutedCircuit:
    """A circuit on a device's physical qubits.

    Attributes:
        circuit: IR qubit ``i`` = physical qubit ``i`` (one register ``q`` of ``device.num_qubits``).
        device: The device.
        initial_layout: Logical qubit ``i`` of the input circuit -> physical qubit at the start.
        final_layout: Logical qubit ``i`` -> physical qubit at the end.
        swaps: SWAPs inserted (each three ``cx`` in :attr:`circuit`, or two with the ``cx`` it is fused with).
        measured: Logical qubits measured at the end (the data qubits), for :func:`esp`.
        fused: Per section name, how many of its SWAPs are fused with a ``cx`` of that section on the same pair
            of qubits (:func:`_assemble`: ``cx`` + SWAP is two ``cx``, not four): :attr:`circuit` has
            ``3 swaps - 2 fused`` more ``cx`` than the logical circuit.
    """

    circuit: Circuit
    device: Device
    initial_layout: tuple[int, ...]
    final_layout: tuple[int, ...]
    swaps: int
    measured: tuple[int, ...]
    fused: tuple[tuple[str, int], ...] = ()

    @property
    def num_fused(self) -> int:
        """SWAPs fused with a ``cx`` (each saves two ``cx``)."""
        return sum(k for _, k in self.fused)


def embed_routed(routed: RoutedCircuit, device: Device, sites: Sequence[int]) -> RoutedCircuit:
    """``routed`` (on a device whose coupling graph is the subgraph of ``device`` induced by ``sites``, its
    qubit ``i`` on ``sites[i]``) written on ``device``'s qubits: the same gates, SWAPs and layouts, relabelled.

    Example:
        >>> from qcpp.devices.device import get_device
        >>> small = route(Circuit([("data", 2)], [Section("s", [cx(0, 1)])]), get_device("grid:1x2"), (0, 1))
        >>> big = embed_routed(small, get_device("grid:3x3"), [4, 5])
        >>> [g[1] for g in big.circuit.gates], big.initial_layout
        ([(4, 5)], (4, 5))
    """
    to = tuple(sites)
    sections = [Section(sec.name, [Gate(g[0], tuple(to[q] for q in g[1]), g[2], g[3]) for g in sec.gates])
                for sec in routed.circuit.sections]  # fmt: skip
    return RoutedCircuit(Circuit([Register("q", device.num_qubits)], sections), device,
                         tuple(to[p] for p in routed.initial_layout), tuple(to[p] for p in routed.final_layout),
                         routed.swaps, routed.measured, routed.fused)  # fmt: skip


def coupling_map(device: Device) -> Any:
    """The device's couplings as a Qiskit ``CouplingMap`` (both directions)."""
    from qiskit.transpiler import CouplingMap

    edges = [list(e) for e in device.coupling] + [[b, a] for a, b in device.coupling]
    return CouplingMap(edges)


def route(
    circuit: Circuit,
    device: Device,
    initial_layout: Sequence[int],
    seed: int = 0,
    measured: Sequence[int] | None = None,
    trials: int | None = DEFAULT_TRIALS,
    fuse: bool = False,
) -> RoutedCircuit:
    """Route a lowered circuit onto ``device`` from ``initial_layout`` with Qiskit's SABRE.

    Args:
        circuit: One- and two-qubit gates only (e.g. :func:`qcpp.lowering.passes.lower`'s output).
        device: The target; it needs at least ``circuit.num_qubits`` qubits.
        initial_layout: Logical qubit ``i`` -> physical qubit (distinct).
        seed: SABRE's seed.
        measured: Logical qubits measured at the end (default: the ``data`` register, else all).
        trials: SABRE's trials (the best of that many randomised routings; Qiskit's default if ``None``).
        fuse: Write a SWAP next to a ``cx`` on the same two qubits as two ``cx`` (:func:`_assemble`, anywhere in
            the circuit); by default every SWAP is three ``cx``.

    Returns:
        The :class:`RoutedCircuit` (lowered gates plus ``cx`` for SWAPs).

    Raises:
        ValueError: the device is too small, the layout is not a placement, or a gate acts on 3+ qubits.
    """
    from qiskit import QuantumCircuit
    from qiskit.transpiler import PassManager
    from qiskit.transpiler.passes import SabreSwap

    gates, section_of, layout, measured_ = _flatten(circuit, device, initial_layout, measured)
    big = device.num_qubits
    qc = QuantumCircuit(big)
    for g in gates:
        if len(g[1]) == 2:
            qc.cx(layout[g[1][0]], layout[g[1][1]])
    if device.is_all_to_all or qc.size() == 0:
        routed_ops = [("cx", tuple(layout[q] for q in g[1])) for g in gates if len(g[1]) == 2]
    else:
        sabre = SabreSwap(coupling_map(device), heuristic="decay", seed=seed, trials=trials)
        out = PassManager([sabre]).run(qc)
        routed_ops = [(inst.operation.name, tuple(out.find_bit(b).index for b in inst.qubits)) for inst in out.data]
    # one window for everything: a whole-circuit routing has no per-window sums to keep apart
    windows = ([0] * len(gates), [0] * len(routed_ops)) if fuse else None
    return _assemble(gates, section_of, layout, big, routed_ops, device, measured_, None, windows)  # type: ignore[arg-type]


def _assemble(
    gates: list[Gate],
    section_of: list[str],
    layout: tuple[int, ...],
    big: int,
    routed_ops: Sequence[tuple[str, tuple[int, int]]],
    device: Device,
    measured: tuple[int, ...],
    op_sections: Sequence[str] | None = None,
    windows: tuple[Sequence[int], Sequence[int]] | None = None,
) -> RoutedCircuit:
    """Our gates in the routed order: ``routed_ops`` lists ``("swap", (p, q))`` and ``("cx", (p, q))`` on physical
    qubits (each ``cx`` is the next two-qubit gate of the logical qubits on ``p`` and ``q``); every one-qubit gate
    goes on its qubit's current position just before that qubit's next two-qubit gate. A SWAP belongs to
    ``op_sections[i]`` if given, else to the section of the gate before it. ``windows``: the window (index) of
    every gate and of every routed op, if the ops were routed window by window (:func:`route_windows`, or all in
    one window: :func:`route` with ``fuse=True``); only then are SWAPs fused (below), otherwise every SWAP is three
    ``cx``.

    A SWAP next to a ``cx`` on the same two qubits, with nothing between them on either qubit, is *fused* with it
    (``cx a b`` then ``SWAP = cx a b; cx b a; cx a b``: the two ``cx a b`` cancel, two ``cx`` remain; the same
    the other way round), where both belong to the same section (so a window's routed gates depend on that
    window alone). Before a SWAP whose next operation on both qubits is a ``cx`` between them, the one-qubit
    gates pending on them (the gates before that ``cx``) are put at their positions before the SWAP, where they
    all belong to the SWAP's section, so the SWAP and the ``cx`` meet."""
    n = len(layout)
    queues: list[list[int]] = [[] for _ in range(n)]
    for i, g in enumerate(gates):
        for q in g[1]:
            queues[q].append(i)
    who = [-1] * big  # physical -> logical (-1: a free qubit, |0>)
    for lq, p in enumerate(layout):
        who[p] = lq
    where = list(layout)
    ptr = [0] * n
    emitted: list[tuple[str, Gate]] = []
    last_section = section_of[0] if section_of else "main"

    def flush(lq: int) -> None:
        nonlocal last_section
        q = queues[lq]
        while ptr[lq] < len(q) and len(gates[q[ptr[lq]]][1]) == 1:
            i = q[ptr[lq]]
            g = gates[i]
            emit(section_of[i], Gate(g[0], (where[lq],), g[2], g[3]), window_of_gate[i])
            last_section = section_of[i]
            ptr[lq] += 1

    last_on: dict[int, int] = {}  # physical qubit -> index in ``emitted`` of the last gate on it
    fused: dict[str, int] = {}
    skip: set[int] = set()  # ops whose ``cx`` a SWAP before them already emitted (fused)
    fuse = windows is not None
    window_of_gate: Sequence[Any] = windows[0] if windows is not None else section_of
    window_of_op: Sequence[Any] | None = windows[1] if windows is not None else None
    emitted_window: list[Any] = []

    def emit(section: str, g: Gate, window: Any) -> None:
        for q in g[1]:
            last_on[q] = len(emitted)
        emitted.append((section, g))
        emitted_window.append(window)

    def pending_in(lq: int, window: Any) -> bool:
        """Whether every one-qubit gate pending on ``lq`` belongs to ``window``."""
        q, i = queues[lq], ptr[lq]
        while i < len(q) and len(gates[q[i]][1]) == 1:
            if window_of_gate[q[i]] != window:
                return False
            i += 1
        return True

    following = _next_ops(routed_ops)

    swaps = 0
    for k, (name, (p1, p2)) in enumerate(routed_ops):
        if name == "swap":
            swaps += 1
            owner = op_sections[k] if op_sections is not None else last_section
            window = window_of_op[k] if window_of_op is not None else owner
            j = last_on.get(p1)
            before = emitted[j] if j is not None and j == last_on.get(p2) else None
            if (fuse and before is not None and emitted_window[j] == window and before[1][0] == "cx"
                    and set(before[1][1]) == {p1, p2}):  # fmt: skip
                a, b = before[1][1]  # cx a b; SWAP (cx a b; cx b a; cx a b) = cx b a; cx a b
                emitted[j] = (before[0], cx(b, a))
                emit(owner, cx(a, b), window)
                fused[owner] = fused.get(owner, 0) + 1
            else:
                nxt = following[k]
                after = routed_ops[nxt] if nxt is not None else None
                l1_, l2_ = who[p1], who[p2]
                if (fuse and after is not None and after[0] == "cx" and set(after[1]) == {p1, p2} and l1_ >= 0
                        and l2_ >= 0
                        and window_of_gate[queues[l1_][_next_twoq(queues[l1_], ptr[l1_], gates)]] == window
                        and pending_in(l1_, window) and pending_in(l2_, window)):  # fmt: skip
                    flush(l1_)
                    flush(l2_)
                    x_, y_ = after[1]  # SWAP (cx x y; cx y x; cx x y); cx x y = cx x y; cx y x
                    emit(owner, cx(x_, y_), window)
                    emit(owner, cx(y_, x_), window)
                    skip.add(nxt)  # type: ignore[arg-type]
                    fused[owner] = fused.get(owner, 0) + 1
                else:
                    for a, b in ((p1, p2), (p2, p1), (p1, p2)):
                        emit(owner, cx(a, b), window)
            l1, l2 = who[p1], who[p2]
            who[p1], who[p2] = l2, l1
            if l1 >= 0:
                where[l1] = p2
            if l2 >= 0:
                where[l2] = p1
            continue
        a, b = who[p1], who[p2]
        flush(a)
        flush(b)
        i = queues[a][ptr[a]]
        if queues[b][ptr[b]] != i or gates[i][1] != (a, b):
            raise AssertionError("the router reordered the gates of a qubit")  # pragma: no cover
        g = gates[i]
        if k not in skip:
            emit(section_of[i], Gate(g[0], (p1, p2), g[2], g[3]), window_of_gate[i])
        last_section = section_of[i]
        ptr[a] += 1
        ptr[b] += 1
    for lq in range(n):
        flush(lq)
    return RoutedCircuit(_sectioned(emitted, big), device, layout, tuple(where), swaps, measured,
                         tuple(sorted(fused.items())))  # fmt: skip


def _next_twoq(queue: Sequence[int], start: int, gates: Sequence[Gate]) -> int:
    """Position in ``queue`` (a qubit's gate indices) of its next two-qubit gate from ``start``."""
    i = start
    while len(gates[queue[i]][1]) == 1:
        i += 1
    return i


# --- routing per window, returning home ------------------------------------------------------------------
WINDOW_RADIUS = 2
"""A window is routed on the device qubits within this distance of its qubits' positions (more if that patch is
not connected): the routed cost of a window then depends only on its neighbourhood."""

WINDOW_SEEDS = 1
"""SABRE seeds tried per window (the fewest SWAPs wins). Measured on the medial layout (p = 1): 4 seeds give the
same counts on 3x3/1 and 6x6/3, 0.4% fewer CX on 4x4/2 (4,222 vs 4,240) and 2.1% fewer on 5x5/2 (9,212 vs
9,410), all of it on the phase separator's one large window, at four SABRE runs per window instead of one; so
one."""

LARGE_WINDOW_PAIRS = 200
"""Windows whose compute has at least this many two-qubit gates (on the defaults: the balance arithmetic's one
window) are routed with :data:`LARGE_WINDOW_SEEDS` seeds (and, up to :data:`LARGE_WINDOW_MAX_PAIRS`, also
:data:`WIDE_WINDOW_SEEDS` seeds of :data:`WIDE_WINDOW_TRIALS` trials) and the try whose whole window (compute,
register phase, uncompute) routes to the fewest CX wins, the first on ties: SABRE picks the fewest SWAPs for the
compute alone, but where the compute leaves the register bits decides what the phase between them costs."""

LARGE_WINDOW_SEEDS = 8
"""Seeds tried per large window (:data:`LARGE_WINDOW_PAIRS`), with the caller's trials. Measured with the balance
sinks (:func:`qcpp.plan.phase_layout.balance_sinks`), p = 1, routed CX of the whole circuit, 1 seed -> 8 -> 16:
4x4/2 3,312 -> 3,246 -> 3,246; 5x5/2 7,114 both; 6x6/3 20,340 -> 19,932 (16 seeds: not measured)."""

WIDE_WINDOW_SEEDS = 16
"""Seeds of the wider search, tried after the :data:`LARGE_WINDOW_SEEDS` ones on large windows of at most
:data:`LARGE_WINDOW_MAX_PAIRS`: the tries include the narrower search's, so a window never routes to more CX than
without the wider search (``python benchmarks/balance_window.py``)."""

WIDE_WINDOW_TRIALS = 128
"""SABRE trials per routing of the wider search (at least the caller's): SABRE keeps the trial of fewest SWAPs
for the compute, and more trials find compute routings that also leave the register bits closer."""

LARGE_WINDOW_MAX_PAIRS = 1_000
"""Windows whose compute has more two-qubit gates than this (the balance window from 6x6/3 on: 1,341 there,
4,552 on 12x12/2; 264 on 4x4/2, 544 on 5x5/2) get no wider search: their routing time grows with their size
(12x12/2's estimate == compile test took 464 s under load with it), and on 6x6/3 it routed the whole circuit to
18,072 CX instead of 18,112 (``python benchmarks/routing.py --family grid``)."""

_WINDOW_CACHE: dict[tuple, Any] = {}
"""SABRE runs on patches (:func:`_sabre_local`) and routed windows (:func:`route_window`), memoised."""

WINDOW_CACHE_LIMIT = 1 << 18
"""Entries :data:`_WINDOW_CACHE` holds before a routed window's entry starts it over."""

WHOLE_COMPONENT_PATCHES = 0
"""How many window parts were routed on their whole connected component because the qubits around them did not
connect them (a window spanning far-apart qubits): such a routing depends on the whole device, not on the
neighbourhood (:mod:`qcpp.estimators.window_classes` counts on it)."""


_PATCH_CENTRES: list[set[int]] = []
"""Sets that collect the qubits every patch routed while they are listed was grown around (:func:`_memo_window`
keys a translated window on the lattice around them)."""

PATCH_WATCH: list[set[int]] = []
"""Sets that collect the device qubits of every patch routed while they are listed: :mod:`qcpp.estimators.window_classes`
lists one while it allocates, relays and routes a window on a crop of the device (allocation search and relays
route candidates too), and the crop answers for the device only if no patch reached a side the crop cut.
Listed and unlisted by :func:`watching_patches`."""


@dataclass
class PatchWatch:
    """What the routings inside one :func:`watching_patches` block did.

    Attributes:
        qubits: The device qubits of every patch routed (memoised windows included).
        whole_component: Window parts routed on their whole connected component (set when the block ends).
    """

    qubits: set[int] = field(default_factory=set)
    whole_component: int = 0


@contextlib.contextmanager
def watching_patches() -> Iterator[PatchWatch]:
    """Collect the patches routed inside the block (:data:`PATCH_WATCH`, :data:`WHOLE_COMPONENT_PATCHES`).

    Returns:
        A context manager giving the :class:`PatchWatch` it fills; blocks nest.

    Example:
        >>> with watching_patches() as watch:
        ...     pass
        >>> watch.qubits, watch.whole_component
        (set(), 0)
    """
    watch = PatchWatch()
    before = WHOLE_COMPONENT_PATCHES
    PATCH_WATCH.append(watch.qubits)
    try:
        yield watch
    finally:  # by identity: an empty set equals every other empty set
        del PATCH_WATCH[next(i for i, w in enumerate(PATCH_WATCH) if w is watch.qubits)]
        watch.whole_component = WHOLE_COMPONENT_PATCHES - before


def mirror_length(pairs: Sequence[tuple[int, int]]) -> int:
    """The largest ``m <= len(pairs) / 2`` such that the last ``m`` pairs are the first ``m`` reversed (as
    unordered pairs): a gadget's uncompute mirrors its compute.

    >>> mirror_length([(0, 1), (1, 2), (2, 3), (2, 1), (1, 0)])
    2
    """
    m = 0
    n = len(pairs)
    while m < n // 2 and sorted(pairs[m]) == sorted(pairs[n - 1 - m]):
        m += 1
    return m


class _PatchIndex:
    """Per device (and its distances): the device's neighbour lists, and every patch computed so far (keyed by
    the positions it was grown around) with whether it is a whole component and its couplings in local indices
    (:func:`_patch`, :func:`_route_part` ask for the same patches thousands of times during a search)."""

    def __init__(self, device: Device, dist: Any) -> None:
        self.device = device
        self.dist = dist
        self.neighbours: list[list[int]] = [[] for _ in range(device.num_qubits)]
        self.edges_of: list[list[int]] = [[] for _ in range(device.num_qubits)]  # indices into device.coupling
        for e, (a, b) in enumerate(device.coupling):
            self.neighbours[a].append(b)
            self.neighbours[b].append(a)
            self.edges_of[a].append(e)
            self.edges_of[b].append(e)
        self.patches: dict[tuple[int, ...], tuple[tuple[int, ...], bool, tuple[tuple[int, int], ...]]] = {}
        self.token = object()  # names the device in memo keys without keeping its distances alive
        self.lattice = _Lattice.of(device)


Coord = tuple[int, int]


class _Lattice:
    """A heavy-hex lattice device's qubits on their ``(y, x)`` coordinates
    (:func:`qcpp.devices.device.heavy_hex_coordinates`), for the translation-invariant window memo
    (:func:`_memo_window`).

    A translation by multiples of :attr:`PERIOD` in both coordinates maps the infinite lattice onto itself, and
    (checked when built, :meth:`of`) the device's couplings are exactly its qubits one step apart and its index
    order is ``(kind, y, x)`` with the kind (data, bridge, flag) given by the coordinates' parities. A patch
    (the qubits within ``WINDOW_RADIUS`` couplings of the qubits it is grown around, :func:`_local_patch`) is then
    decided by which coordinates within ``WINDOW_RADIUS`` steps of those qubits hold a qubit (:meth:`around`): a
    path of that many couplings stays there. So a window whose qubits are such a translation of a routed window's
    (:meth:`canonical`), with the same coordinates held around the qubits that routing grew its patches from (the
    compute's qubits, then where the compute left the middle's), gets the same patches, local indices and
    couplings, and SABRE routes it alike: one routing answers both, translated. A window routed on its whole
    component depends on the whole device: it is memoised on its physical pairs instead."""

    PERIOD = 4

    def __init__(self, coords: Sequence[Coord]) -> None:
        import numpy as np

        self.y = [c[0] for c in coords]
        self.x = [c[1] for c in coords]
        self.at = {c: i for i, c in enumerate(coords)}
        pad = 2 * WINDOW_RADIUS  # so that a box around any qubits never leaves the array
        self.present = np.zeros((max(self.y) + 1 + 2 * pad, max(self.x) + 1 + 2 * pad), dtype=np.uint8)
        self.present[np.array(self.y) + pad, np.array(self.x) + pad] = 1

    @classmethod
    def of(cls, device: Device) -> _Lattice | None:
        """The lattice of a heavy-hex lattice device, or ``None`` (another device, or one the checks reject)."""
        from qcpp.devices.device import heavy_hex_coordinates, heavy_hex_distance

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
        return cls(coords)

    def canonical(self, pairs: Sequence[tuple[int, int]]) -> tuple[Hashable, Coord]:
        """A key equal for two windows' physical ``pairs`` iff one is the other translated by a multiple of
        :attr:`PERIOD`, and the translation ``(ay, ax)`` that takes the key's relative coordinates to these
        pairs'."""
        flat = [q for pair in pairs for q in pair]
        ys = [self.y[q] for q in flat]
        xs = [self.x[q] for q in flat]
        y0, x0 = min(ys), min(xs)
        ay, ax = y0 - y0 % self.PERIOD, x0 - x0 % self.PERIOD
        return (tuple(y - ay for y in ys), tuple(x - ax for x in xs)), (ay, ax)

    def around(self, centres: set[int], shift: Coord) -> tuple[Any, Any, bytes]:
        """The coordinates within :data:`WINDOW_RADIUS` steps (in ``y`` plus ``x``) of the ``centres`` qubits less
        ``shift``, and which of them hold a qubit: every patch grown around the centres (the qubits within
        :data:`WINDOW_RADIUS` couplings, their couplings, whether they connect the centres) is decided there."""
        import numpy as np

        r = WINDOW_RADIUS
        steps = np.array([(dy, dx) for dy in range(-r, r + 1) for dx in range(-r, r + 1) if abs(dy) + abs(dx) <= r])
        at = np.array([(self.y[q], self.x[q]) for q in centres])
        coords = np.unique((at[:, None, :] + steps[None, :, :]).reshape(-1, 2), axis=0) - np.array(shift)
        ys, xs = coords[:, 0].copy(), coords[:, 1].copy()
        return ys, xs, self.holds(ys, xs, shift)

    def holds(self, ys: Any, xs: Any, shift: Coord) -> bytes:
        """Which of the coordinates ``(ys, xs)`` plus ``shift`` hold a qubit."""
        pad = 2 * WINDOW_RADIUS
        return self.present[ys + (shift[0] + pad), xs + (shift[1] + pad)].tobytes()

    def moved(self, q: int, by: Coord) -> int:
        """The qubit at qubit ``q``'s coordinates plus ``by``."""
        return self.at[(self.y[q] + by[0], self.x[q] + by[1])]


_PATCH_INDEX: list[_PatchIndex] = []
"""The last few devices' :class:`_PatchIndex` (identity-checked: a device and its distance matrix)."""


def _patch_index(device: Device, dist: Any) -> _PatchIndex:
    for index in _PATCH_INDEX:
        if index.device is device and index.dist is dist:
            return index
    index = _PatchIndex(device, dist)
    _PATCH_INDEX.insert(0, index)
    del _PATCH_INDEX[8:]
    return index


def _patch(positions: set[int], device: Device, dist: Any) -> tuple[int, ...]:
    """Device qubits within :data:`WINDOW_RADIUS` of ``positions`` (ascending), grown to the whole connected
    component when that neighbourhood does not connect them."""
    return _local_patch(positions, device, dist)[0]


def _local_patch(positions: set[int], device: Device, dist: Any) -> tuple[tuple[int, ...], tuple[tuple[int, int], ...]]:
    """:func:`_patch` and its couplings (in :attr:`Device.coupling`'s order) as pairs of indices into it; memoised
    per device, the side effects (:data:`PATCH_WATCH`, :data:`WHOLE_COMPONENT_PATCHES`) on every call."""
    index = _patch_index(device, dist)
    for centres in _PATCH_CENTRES:
        centres.update(positions)
    key = tuple(sorted(positions))
    hit = index.patches.get(key)
    if hit is None:
        import numpy as np

        rows = dist[list(key)]
        near = np.flatnonzero((rows <= WINDOW_RADIUS).any(axis=0))
        inside = {int(p) for p in near}
        seen = {key[0]}
        todo = [key[0]]
        while todo:  # the component of the first position in the neighbourhood
            p = todo.pop()
            for q in index.neighbours[p]:
                if q in inside and q not in seen:
                    seen.add(q)
                    todo.append(q)
        linked = any(q in inside for p in inside for q in index.neighbours[p])  # as before: no edge, no patch
        whole = not linked or not seen.issuperset(key)
        patch = tuple(int(p) for p in (np.flatnonzero(np.isfinite(rows[0])) if whole else near))
        local = {p: i for i, p in enumerate(patch)}
        edges = sorted({e for p in patch for e in index.edges_of[p]})  # in the device's order
        coupling = tuple((local[a], local[b]) for a, b in (device.coupling[e] for e in edges)
                         if a in local and b in local)  # fmt: skip
        hit = (patch, whole, coupling)
        index.patches[key] = hit
    patch, whole, coupling = hit
    if whole:
        global WHOLE_COMPONENT_PATCHES
        WHOLE_COMPONENT_PATCHES += 1
    return _watched(patch), coupling


def _watched(patch: tuple[int, ...]) -> tuple[int, ...]:
    for seen in PATCH_WATCH:
        seen.update(patch)
    return patch


def _sabre_local(coupling: tuple[tuple[int, int], ...], size: int, pairs: tuple[tuple[int, int], ...], seed: int,
                 trials: int | None) -> tuple[tuple, ...]:  # fmt: skip
    """SABRE on a patch (qubits ``0 .. size-1``): ``("gate", k)`` (the ``k``-th pair, done) and ``("swap", (x, y))``
    in order, cached per ``(patch, pairs, seed, trials)`` so equal neighbourhoods route equally."""
    key = (coupling, size, pairs, seed, trials)
    hit = _WINDOW_CACHE.get(key)
    if hit is not None:
        return hit
    from qiskit import QuantumRegister
    from qiskit.circuit.library import CXGate
    from qiskit.dagcircuit import DAGCircuit

    dag = DAGCircuit()
    reg = QuantumRegister(size, "q")  # the circuit a PassManager would hand the pass: one register q, our cx
    dag.add_qreg(reg)
    gate = CXGate()
    for a, b in pairs:
        dag.apply_operation_back(gate, (reg[a], reg[b]), (), check=False)
    sabre, default_trials = _sabre_pass(coupling, size)
    sabre.seed, sabre.trials = seed, default_trials if trials is None else trials
    out = _run_sabre(sabre, dag, size)
    queues: dict[int, list[int]] = {}
    for k, (a, b) in enumerate(pairs):
        queues.setdefault(a, []).append(k)
        queues.setdefault(b, []).append(k)
    who = list(range(size))  # position -> the qubit that started there
    ptr = dict.fromkeys(queues, 0)
    events: list[tuple] = []
    index = {q: i for i, q in enumerate(out.qubits)}
    for node in out.topological_op_nodes():  # the order dag_to_circuit writes them in
        x, y = (index[q] for q in node.qargs)
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
    _WINDOW_CACHE[key] = result
    return result


_SABRE_PASSES: dict[tuple, tuple[Any, int]] = {}


def _run_sabre(sabre: Any, dag: Any, size: int) -> Any:
    """``sabre.run(dag)`` (heuristic ``decay``) without the pass's per-run checks: its routing call with the
    arguments the pass builds (Qiskit 2's ``sabre_routing``), where Qiskit has it; else the pass itself. The pass
    first checks that the circuit's qubits lie in one component of the coupling map (a patch is grown until they
    do, :func:`_local_patch`) and rebuilds the coupling graph to do so, which took longer than the routing of a
    window. ``tests/qcpp/routing_test.py`` checks both give the same routing."""
    try:
        from qiskit._accelerate.nlayout import NLayout
        from qiskit._accelerate.sabre import Heuristic, RoutingTarget, SetScaling, sabre_routing

        if sabre._routing_target is None:
            sabre._routing_target = RoutingTarget.from_target(sabre.target)
        heuristic = (
            Heuristic(attempt_limit=10 * size)
            .with_basic(1.0, SetScaling.Constant)
            .with_lookahead([0.5 / size], SetScaling.Constant)
            .with_decay(0.001, 5)
        )  # SabreSwap.run's "decay"
        layout = NLayout.generate_trivial_layout(size)
    except (ImportError, AttributeError, TypeError):  # pragma: no cover - another Qiskit: the pass itself
        sabre.property_set["final_layout"] = None
        return sabre.run(dag)
    out, _ = sabre_routing(dag, sabre._routing_target, heuristic, layout, sabre.trials, sabre.seed)
    return out


def _sabre_pass(coupling: tuple[tuple[int, int], ...], size: int) -> tuple[Any, int]:
    """A ``SabreSwap`` pass for a patch, and its default trials: building one builds a Qiskit ``Target`` and its
    routing tables, which took longer than the routing of a window, so a pass is reused per patch (its seed and
    trials set per run)."""
    hit = _SABRE_PASSES.get((coupling, size))
    if hit is None:
        from qiskit.transpiler import CouplingMap
        from qiskit.transpiler.passes import SabreSwap

        if len(_SABRE_PASSES) >= 4096:
            _SABRE_PASSES.clear()
        cmap = CouplingMap([list(e) for e in coupling] + [[b, a] for a, b in coupling])
        sabre = SabreSwap(cmap, heuristic="decay", trials=None)
        hit = _SABRE_PASSES[(coupling, size)] = (sabre, sabre.trials)
    return hit


class Positions:
    """Where every logical qubit is (``where``: logical -> physical) and who is on every physical qubit (``who``:
    physical -> logical, -1 for a free qubit) while windows are routed; ``swap`` moves both."""

    def __init__(self, layout: tuple[int, ...], size: int) -> None:
        self.where = list(layout)
        self.who = [-1] * size
        for lq, p in enumerate(layout):
            self.who[p] = lq

    @classmethod
    def identity(cls, size: int) -> Positions:
        """Every physical qubit holding the logical qubit of its own number."""
        pos = cls.__new__(cls)
        pos.where = list(range(size))
        pos.who = list(range(size))
        return pos

    def swap(self, p: int, q: int) -> None:
        a, b = self.who[p], self.who[q]
        self.who[p], self.who[q] = b, a
        if a >= 0:
            self.where[a] = q
        if b >= 0:
            self.where[b] = p


def _route_part(
    pairs: list[tuple[int, int]], pos: Positions, device: Device, dist: Any, seed: int, trials: int | None
) -> list[tuple]:
    """Route logical ``pairs`` from the current positions (``pos`` is not changed): ``("gate", k)`` and physical
    ``("swap", (p, q))`` in order."""
    if not pairs:
        return []
    if device.is_all_to_all:
        return [("gate", k) for k in range(len(pairs))]
    patch, coupling = _local_patch({pos.where[q] for pr in pairs for q in pr}, device, dist)
    local = {p: i for i, p in enumerate(patch)}
    lpairs = tuple((local[pos.where[a]], local[pos.where[b]]) for a, b in pairs)
    best = min(
        (_sabre_local(coupling, len(patch), lpairs, seed + i, trials) for i in range(WINDOW_SEEDS)),
        key=lambda evs: sum(ev[0] == "swap" for ev in evs),
    )
    return [("swap", (patch[ev[1][0]], patch[ev[1][1]])) if ev[0] == "swap" else ev for ev in best]


def _play(
    events: Sequence[tuple], pairs: Sequence[tuple[int, int]], pos: Positions
) -> list[tuple[str, tuple[int, int]]]:
    """Apply ``events`` to ``pos``: SWAPs move qubits, ``("gate", k)`` becomes ``("cx", pairs[k] at their
    positions)``."""
    out: list[tuple[str, tuple[int, int]]] = []
    for ev in events:
        if ev[0] == "swap":
            pos.swap(*ev[1])
            out.append(ev)  # type: ignore[arg-type]
        else:
            a, b = pairs[ev[1]]
            out.append(("cx", (pos.where[a], pos.where[b])))
    return out


def route_window(
    pairs: list[tuple[int, int]], pos: Positions, device: Device, dist: Any, seed: int = 0,
    trials: int | None = DEFAULT_TRIALS, large_seeds: int | None = None, large_trials: int | None = None,
) -> list[tuple[str, tuple[int, int]]]:  # fmt: skip
    """One window's routed ops (``("cx", (p, q))``, ``("swap", (p, q))``), leaving every qubit where it was: the
    compute (the first :func:`mirror_length` pairs) is routed by SABRE, then the middle, whose SWAPs are undone
    in reverse, then the uncompute replays the compute's routed ops backwards (pair ``k`` of the compute is pair
    ``n - 1 - k`` of the uncompute). ``large_seeds``, ``large_trials``: seeds a large window tries (default
    :data:`LARGE_WINDOW_SEEDS`) and SABRE's trials per seed there (default ``trials``).

    The ops depend only on where the pairs' qubits are (the physical pairs), the device and the search's
    settings, so they are memoised on those (in :data:`_WINDOW_CACHE`, with the patches the routing saw, replayed
    into :data:`PATCH_WATCH` and :data:`WHOLE_COMPONENT_PATCHES` on a hit; on a heavy-hex lattice up to the
    lattice's translations, :class:`_Lattice`): the allocation search and the cells' plan choice route the same
    window many times."""
    entry, by = _memo_window(pairs, pos, device, dist, seed, trials, large_seeds, large_trials)
    if by is None:
        return list(entry[0])
    moved = _patch_index(device, dist).lattice.moved  # type: ignore[union-attr]
    return [(name, (moved(a, by), moved(b, by))) for name, (a, b) in entry[0]]


def route_window_cx(
    pairs: list[tuple[int, int]], pos: Positions | None, device: Device, dist: Any, seed: int = 0,
    trials: int | None = DEFAULT_TRIALS, large_seeds: int | None = None, large_trials: int | None = None,
) -> int:  # fmt: skip
    """``window_cx(route_window(...))``, memoised with the window (searches ask for the count only); ``pos``
    ``None``: every qubit on the physical qubit of its number (``pairs`` are physical)."""
    return _memo_window(pairs, pos, device, dist, seed, trials, large_seeds, large_trials)[0][1]


def _memo_window(
    pairs: list[tuple[int, int]], pos: Positions | None, device: Device, dist: Any, seed: int, trials: int | None,
    large_seeds: int | None, large_trials: int | None,
) -> tuple[tuple[Any, ...], Coord | None]:  # fmt: skip
    """:func:`route_window`'s memo entry ``(ops, window_cx, patch qubits, whole-component parts, ...)`` and the
    lattice translation that takes its qubits to this window's (``None``: none needed; :class:`_Lattice`)."""
    global WHOLE_COMPONENT_PATCHES
    if device.is_all_to_all:
        pos = Positions.identity(device.num_qubits) if pos is None else pos
        ops, cx_ = _route_window(pairs, pos, device, dist, seed, trials, large_seeds, large_trials)
        return (tuple(ops), cx_, frozenset(), 0), None
    index = _patch_index(device, dist)
    if pos is None:
        physical = tuple(pairs)
    else:
        where = pos.where
        physical = tuple((where[a], where[b]) for a, b in pairs)
    settings = (seed, trials, large_seeds, large_trials, WINDOW_RADIUS, LARGE_WINDOW_PAIRS, LARGE_WINDOW_SEEDS,
                WIDE_WINDOW_SEEDS, WIDE_WINDOW_TRIALS, LARGE_WINDOW_MAX_PAIRS)  # fmt: skip
    lattice = index.lattice
    key: tuple = ("window", index.token, physical, settings)
    shift = None
    translated: list = []
    if lattice is not None and physical:
        rel, shift = lattice.canonical(physical)
        translated = _WINDOW_CACHE.setdefault(("window", index.token, "translated", rel, settings), [])
    hit = None
    for ys, xs, holds, entry in translated:  # the same window elsewhere, with the same qubits around its patches
        if lattice.holds(ys, xs, shift) == holds:  # type: ignore[union-attr, arg-type]
            hit = entry
            break
    else:  # routed on its whole component, or no lattice: memoised on its physical pairs
        hit = _WINDOW_CACHE.get(key)
    if hit is None:
        pos = Positions.identity(device.num_qubits) if pos is None else pos
        centres: set[int] = set()
        _PATCH_CENTRES.append(centres)
        try:
            with watching_patches() as watch:
                ops, cx_ = _route_window(pairs, pos, device, dist, seed, trials, large_seeds, large_trials)
        finally:
            del _PATCH_CENTRES[next(i for i, c in enumerate(_PATCH_CENTRES) if c is centres)]
        if len(_WINDOW_CACHE) >= WINDOW_CACHE_LIMIT:
            _WINDOW_CACHE.clear()
        hit = (tuple(ops), cx_, frozenset(watch.qubits), watch.whole_component, shift)
        if lattice is not None and shift is not None and not watch.whole_component:
            translated.append((*lattice.around(centres, shift), hit))
            _WINDOW_CACHE[("window", index.token, "translated", rel, settings)] = translated
        else:
            hit = _WINDOW_CACHE[key] = (*hit[:4], None)
        return hit, None
    by = None if hit[4] is None or hit[4] == shift else (shift[0] - hit[4][0], shift[1] - hit[4][1])  # type: ignore[index]
    if PATCH_WATCH:
        seen = hit[2] if by is None else {lattice.moved(q, by) for q in hit[2]}  # type: ignore[union-attr]
        for watch_ in PATCH_WATCH:
            watch_.update(seen)
    WHOLE_COMPONENT_PATCHES += hit[3]
    return hit, by


def _route_window(
    pairs: list[tuple[int, int]], pos: Positions, device: Device, dist: Any, seed: int, trials: int | None,
    large_seeds: int | None, large_trials: int | None,
) -> tuple[list[tuple[str, tuple[int, int]]], int]:  # fmt: skip
    """:func:`route_window` without its memo, and the ops' :func:`window_cx`."""
    m = mirror_length(pairs)
    large = m >= LARGE_WINDOW_PAIRS
    base_trials = large_trials if large and large_trials else trials
    tries = [(s, base_trials) for s in range(seed, seed + ((large_seeds or LARGE_WINDOW_SEEDS) if large else 1))]
    if LARGE_WINDOW_PAIRS <= m <= LARGE_WINDOW_MAX_PAIRS and trials is not None:  # and a wider search
        tries += [(s, max(trials, WIDE_WINDOW_TRIALS)) for s in range(seed, seed + WIDE_WINDOW_SEEDS)]
    best: list[tuple[str, tuple[int, int]]] | None = None
    best_cx = 0
    for s, t in tries:  # each try returns every qubit home, so ``pos`` is unchanged between tries
        ops = _window_ops(pairs, m, pos, device, dist, s, t)
        cx_ = window_cx(ops)
        if best is None or cx_ < best_cx:
            best, best_cx = ops, cx_
    assert best is not None
    return best, best_cx


def window_cx(ops: Sequence[tuple[str, tuple[int, int]]]) -> int:
    """CX of a window's routed ops (:func:`route_window`) as :func:`route_windows` writes them: 1 per ``cx``, 3 per
    SWAP, 2 fewer per SWAP that :func:`_assemble` fuses with a ``cx`` on its pair (the ops alone decide, except
    that one-qubit gates pending from an earlier window keep a SWAP and the ``cx`` after it apart: then this is 2
    below what is written).

    >>> window_cx([("cx", (0, 1)), ("swap", (0, 1)), ("cx", (1, 2))])  # the SWAP fuses with the cx before it
    3
    """
    after = set()  # SWAPs whose next op on both of their qubits is one cx on their pair
    upcoming: dict[int, int] = {}
    for k in range(len(ops) - 1, -1, -1):
        name, (p, q) = ops[k]
        if name == "swap":
            j = upcoming.get(p)
            if j is not None and j == upcoming.get(q) and ops[j][0] == "cx":
                after.add(k)
        upcoming[p] = upcoming[q] = k
    last: dict[int, int] = {}
    total = len(ops)
    for k, (name, (p, q)) in enumerate(ops):
        if name == "swap" and k not in after:
            j = last.get(p)
            if j is None or j != last.get(q):
                total += 2
        last[p] = last[q] = k
    return total


def _next_ops(ops: Sequence[tuple[str, tuple[int, ...]]]) -> list[int | None]:
    """Per op, the index of the next op that touches one of its qubits (``None``: none)."""
    seen: dict[int, int] = {}
    out: list[int | None] = [None] * len(ops)
    for k in range(len(ops) - 1, -1, -1):
        qs = ops[k][1]
        nxt = [seen[q] for q in qs if q in seen]
        out[k] = min(nxt) if nxt else None
        for q in qs:
            seen[q] = k
    return out


def _window_ops(
    pairs: list[tuple[int, int]], m: int, pos: Positions, device: Device, dist: Any, seed: int, trials: int | None
) -> list[tuple[str, tuple[int, int]]]:
    """:func:`route_window` with one seed (``m``: the compute's length)."""
    n = len(pairs)
    compute = _route_part(pairs[:m], pos, device, dist, seed, trials)
    ops = _play(compute, pairs, pos)
    middle = _route_part(pairs[m : n - m], pos, device, dist, seed, trials)
    ops += _play(middle, pairs[m : n - m], pos)
    ops += _play([ev for ev in reversed(middle) if ev[0] == "swap"], pairs, pos)
    mirrored = pairs[::-1]  # the uncompute's k-th pair from the end is mirrored[k]
    ops += _play(list(reversed(compute)), mirrored, pos)
    return ops


def route_windows(
    circuit: Circuit,
    device: Device,
    layout: Sequence[int],
    seed: int = 0,
    measured: Sequence[int] | None = None,
    trials: int | None = DEFAULT_TRIALS,
    dist: Any = None,
    large_seeds: int | None = None,
    large_trials: int | None = None,
) -> RoutedCircuit:
    """Route every section as a window that returns every qubit home (:func:`route_window`): the routed
    circuit's final layout is its initial layout, and a window's routed cost depends only on its gates and the
    device around its qubits (windows are routed on a patch, SABRE's answer cached by the patch's shape and the
    window memoised on its physical pairs, :func:`route_window`).

    Args:
        circuit: Lowered, one section per gadget.
        device: The target.
        layout: Logical qubit ``i`` -> physical qubit (the home of every qubit).
        seed: SABRE's seed.
        measured: Logical qubits measured at the end (default: the ``data`` register, else all).
        trials: SABRE's trials per window.
        dist: The device's all-pairs distances (:func:`qcpp.devices.device.distances`), if already known.
        large_seeds, large_trials: SABRE seeds a large window tries (default :data:`LARGE_WINDOW_SEEDS`) and
            SABRE's trials per seed there (default ``trials``).

    Returns:
        The :class:`RoutedCircuit` (``initial_layout == final_layout == layout``).
    """
    from qcpp.devices.device import distances

    gates, section_of, home, measured_ = _flatten(circuit, device, layout, measured)
    if dist is None:
        dist = distances(device)
    pos = Positions(home, device.num_qubits)
    ops: list[tuple[str, tuple[int, int]]] = []
    owners: list[str] = []
    op_window: list[int] = []
    gate_window: list[int] = []
    for w, sec in enumerate(circuit.sections):
        pairs = [g[1] for g in sec.gates if len(g[1]) == 2]
        window = route_window(pairs, pos, device, dist, seed, trials, large_seeds, large_trials)  # type: ignore[arg-type]
        ops += window
        owners += [sec.name] * len(window)
        op_window += [w] * len(window)
        gate_window += [w] * len(sec.gates)
    return _assemble(gates, section_of, home, device.num_qubits, ops, device, measured_, owners,
                     (gate_window, op_window))  # fmt: skip


def _flatten(
    circuit: Circuit, device: Device, initial_layout: Sequence[int], measured: Sequence[int] | None
) -> tuple[list[Gate], list[str], tuple[int, ...], tuple[int, ...]]:
    """Checked inputs of a router: the gates, their section names, the layout, the measured qubits."""
    n, big = circuit.num_qubits, device.num_qubits
    layout = tuple(int(p) for p in initial_layout)
    if n > big:
        raise ValueError(f"the circuit needs {n} qubits; device {device.name} has {big}")
    if len(layout) != n or len(set(layout)) != n or any(not 0 <= p < big for p in layout):
        raise ValueError(f"initial layout must place {n} logical qubits on distinct physical qubits < {big}")
    gates: list[Gate] = []
    section_of: list[str] = []
    for sec in circuit.sections:
        for g in sec.gates:
            if len(g[1]) > 2:
                raise ValueError(f"route needs a lowered circuit; gate {g[0]} acts on {len(g[1])} qubits")
        gates.extend(sec.gates)
        section_of.extend([sec.name] * len(sec.gates))
    if measured is None:
        data = next((r for r in circuit.registers if r.name == "data"), None)
        measured = tuple(range(data.size)) if data is not None and circuit.registers[0] is data else tuple(range(n))
    return gates, section_of, layout, tuple(measured)


def _sectioned(emitted: list[tuple[str, Gate]], num_qubits: int) -> Circuit:
    sections: list[Section] = []
    run: list[Gate] = []
    name = None
    for sec, g in emitted:
        if sec != name and run:
            sections.append(Section(name, run))  # type: ignore[arg-type]
            run = []
        name = sec
        run.append(g)
    if run:
        sections.append(Section(name, run))  # type: ignore[arg-type]
    return Circuit([Register("q", num_qubits)], sections)


# --- native gates ------------------------------------------------------------------------------------------
_HALF_PI = math.pi / 2
_RZ_OF = {"t": math.pi / 4, "tdg": -math.pi / 4, "s": _HALF_PI, "sdg": -_HALF_PI}


def _native_gates(g: Gate, twoq: str, native_x: bool) -> list[Gate]:
    name, qs = g[0], g[1]
    if name == "cx":
        c, t = qs
        return [*_native_gates(Gate("h", (t,), (), None), twoq, native_x), *_native_cz(c, t, twoq),
                *_native_gates(Gate("h", (t,), (), None), twoq, native_x)]  # fmt: skip
    if name == "cz":
        return _native_cz(*qs, twoq)
    if name == "h":
        (q,) = qs
        return [rz(_HALF_PI, q), rx(_HALF_PI, q), rz(_HALF_PI, q)]
    if name in _RZ_OF:
        return [rz(_RZ_OF[name], qs[0])]
    if name == "x":
        return [g] if native_x else [rx(math.pi, qs[0])]
    if name in ("rz", "rx"):
        return [g]
    raise ValueError(f"to_native: no native form for gate {name!r}")


def _native_cz(a: int, b: int, twoq: str) -> list[Gate]:
    if twoq == "cz":
        return [cz(a, b)]
    return [rz(_HALF_PI, a), rz(_HALF_PI, b), rzz(-_HALF_PI, a, b)]  # CZ up to a global phase


def to_native(routed: RoutedCircuit) -> RoutedCircuit:
    """The routed circuit in the device's native gates (equal up to a global phase); see the module docs."""
    twoq = routed.device.two_qubit_gate
    native_x = "x" in routed.device.native_gates
    sections = [
        Section(sec.name, [n for g in sec.gates for n in _native_gates(g, twoq, native_x)])
        for sec in routed.circuit.sections
    ]
    circuit = Circuit(routed.circuit.registers, sections)
    return RoutedCircuit(circuit, routed.device, routed.initial_layout, routed.final_layout, routed.swaps,
                         routed.measured)  # fmt: skip


# --- figures of merit --------------------------------------------------------------------------------------
def _one_qubit_name(device: Device, g: Gate) -> str:
    """The device gate a one-qubit IR gate stands for (``rx(+-pi/2)`` is ``sx`` where the device has ``sx``)."""
    name = g[0]
    if name == "rx" and "sx" in device.native_gates:
        return "sx"
    return name


def esp(routed: RoutedCircuit) -> float:
    """Estimated success probability of a native routed circuit (model in the module docs).

    Returns:
        ``prod (1 - e_gate) * prod_{measured} (1 - e_readout)``.

    Raises:
        ValueError: a gate the device has no error figure for.
    """
    device = routed.device
    e1 = dict(device.error_1q)
    edge = device.edge_index()
    log = 0.0
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            if g[0] != device.two_qubit_gate:
                raise ValueError(f"esp: {g[0]} is not native on {device.name} (use to_native)")
            e = device.error_2q[edge[qs]]
        else:
            name = _one_qubit_name(device, g)
            if name not in e1:
                raise ValueError(f"esp: {name} is not native on {device.name} (use to_native)")
            e = e1[name][qs[0]]
        log += math.log1p(-e) if e < 1 else -math.inf
    for lq in routed.measured:
        log += math.log1p(-device.readout_error[routed.final_layout[lq]])
    return math.exp(log)


def duration_s(routed: RoutedCircuit) -> float | None:
    """ASAP schedule length of a native routed circuit plus one readout, in seconds (``None``: no durations)."""
    device = routed.device
    if device.duration_1q_s is None or device.duration_2q_s is None or device.readout_duration_s is None:
        return None
    d1 = dict(device.duration_1q_s)
    edge = device.edge_index()
    free = [0.0] * device.num_qubits
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            start = max(free[qs[0]], free[qs[1]])
            free[qs[0]] = free[qs[1]] = start + device.duration_2q_s[edge[qs]]
        else:
            q = qs[0]
            free[q] += d1[_one_qubit_name(device, g)][q]
    readout = max((device.readout_duration_s[routed.final_layout[lq]] for lq in routed.measured), default=0.0)
    return max(free, default=0.0) + readout
