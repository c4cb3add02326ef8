"""Routed counts of ``compile --device grid`` (medial layout) as a sum over classes of windows, without routing
the whole circuit.

On a square grid with the medial layout (:func:`qcpp.pipeline.device_compile.medial_compile`) every section of the
lowered, unfused circuit is a *window*: its ancillas are allocated near its data
(:func:`qcpp.layout.medial.allocate_ancillas`), its far phases relayed (:func:`qcpp.routing.bridge.bridge_far_phases`)
and it is routed by SABRE on the device around it, every qubit home at its end
(:func:`qcpp.routing.windows.route_windows`). All three decide from the window's gates, the data homes and the clean
qubits around it, so the routed circuit's counts are the sum of its windows'. :func:`routed_sum` groups windows by
*signature* (lowered gates with qubits named by first use, data homes relative to their bounding box, and the
device cropped :data:`MARGIN` sites around that box), routes one representative per class on its crop with
compile's own functions, and multiplies (layer ``k``'s windows are layer 0's with other angles).

Invariant: a crop answers for the device only if nothing the representative touches (ancilla and relay homes,
routed gates, every routing patch of the searches: :meth:`qcpp.routing.context.RoutingContext.watching`) comes within
:data:`GUARD` sites of a side that is not a device edge and no part was routed on its whole connected component;
otherwise the class is split at twice the margin, up to the whole device. Windows that need the whole device (the
balance and coupling gadgets; with several robots every visit gadget) are routed on it, one SABRE run each, as
compile does, up to :data:`WHOLE_DEVICE_MAX_QUBITS` qubits and the caller's work budget; beyond either the sum is
``None``. So the sum is fast where windows are local (one robot) and no faster than compile where they are not.

Exact (``tests/compiler/window_classes_test.py`` compares with ``compile_for_device(..., layout_method="medial")``):
lowered and native gate counts by name, SWAPs, and the ESP on devices with uniform error rates (its logarithm is a
sum over classes). Depth and duration are upper bounds: the windows' own, summed, plus one level per one-qubit gate
that trails its qubit's last two-qubit gate in a window (the router defers it into a later window). The argument
and its evidence: ``docs/resource-estimates.md``, "The routed cost as a sum over window classes".

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> s = routed_sum(default_scenario(3, 3, 1), 1, device="grid")
    >>> s.device.name, s.windows, s.two_qubit > 106
    ('grid:5x5', 6, True)
"""

from __future__ import annotations

import dataclasses
import math
from collections import Counter
from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from qcpp.gadgets.partial_mixer import McxPartialMixer
from qcpp.hardware.device import Device, get_device
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate
from qcpp.layout.medial import allocate_ancillas, grid_shape, medial_placement
from qcpp.lowering.passes import lower
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.problem.scenario import Scenario
from qcpp.routing.bridge import bridge_far_phases
from qcpp.routing.context import RoutingContext
from qcpp.routing.native import native_gates
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.windows import route_windows

__all__ = ["GUARD", "MARGIN", "WHOLE_DEVICE_MAX_QUBITS", "RoutedSum", "WindowClass", "routed_sum"]

MARGIN = 5
"""Sites around a window's data qubits that its first crop keeps (doubled while the crop does not answer)."""

GUARD = 3
"""A crop answers if the representative's ancilla homes and routed gates keep this many sites from every side of
the crop that is not a device edge (one more than the routing patch's radius)."""

ROUTED_CLASSES_LIMIT = 1 << 14
"""Entries the run's memo of routed classes (:attr:`~qcpp.routing.context.RoutingContext.window_classes`: what one
routed window of a class costs, per signature and device gate set: native gates, durations, SABRE's seed, the
:class:`~qcpp.routing.options.RoutingOptions`) holds before it starts over."""

WHOLE_DEVICE_MAX_QUBITS = 4_096
"""Largest device a window spanning it is routed on (routing needs the device's dense distance matrix): on a
larger one, a window whose crop is the whole device makes the sum ``None``."""


@dataclass(frozen=True)
class WindowClass:
    """Windows with one signature and what one of them costs routed.

    Attributes:
        multiplicity: Windows in the class (each layer's counted once per layer).
        lowered_ops: Lowered gate counts by name of one window, after the relays.
        swaps: SWAPs its routing inserts.
        native_ops: Native gate counts by device gate name of one routed window.
        depth, two_qubit_depth: ASAP depths of one routed native window.
        duration_s: ASAP length of one routed native window in seconds (``None``: no durations).
    """

    multiplicity: int
    lowered_ops: tuple[tuple[str, int], ...]
    swaps: int
    native_ops: tuple[tuple[str, int], ...]
    depth: int
    two_qubit_depth: int
    duration_s: float | None


@dataclass(frozen=True)
class RoutedSum:
    """The routed circuit's figures summed over window classes.

    Attributes:
        device: The device (the one ``compile --device`` routes on).
        p: QAOA layers.
        windows: Windows of the whole circuit (state preparation + ``p`` layers).
        classes: The :class:`WindowClass` es.
        lowered_ops: Lowered gate counts by name (after compile's relays of far phases).
        compiled_ops: Lowered gate counts by name of the compiled circuit, before allocation and relays (what
            :func:`qcpp.pipeline.device_compile.auto_tries_greedy` decides on).
        swaps: SWAPs of the routed windows.
        native_ops: Native gate counts by name.
        two_qubit: Routed two-qubit gates (native two-qubit gates = lowered CX + 3 per SWAP).
        one_qubit: Native one-qubit gates.
        log_esp: Natural log of the estimated success probability (``None``: the device's errors are not uniform).
        depth_bound, two_qubit_depth_bound: Sums of the windows' own depths (the depth also counts each one-qubit
            gate the router defers into a later window once).
        duration_bound_s: Likewise for durations, plus one readout (``None``: no durations published).
    """

    device: Device
    p: int
    windows: int
    classes: tuple[WindowClass, ...]
    lowered_ops: dict[str, int]
    compiled_ops: dict[str, int]
    swaps: int
    native_ops: dict[str, int]
    two_qubit: int
    one_qubit: int
    log_esp: float | None
    depth_bound: int
    two_qubit_depth_bound: int
    duration_bound_s: float | None

    @property
    def esp(self) -> float | None:
        """Estimated success probability (``exp(log_esp)``)."""
        return None if self.log_esp is None else math.exp(self.log_esp)


# --- windows and their signatures --------------------------------------------------------------------------
@dataclass(frozen=True)
class _Template:
    """One pattern of high-level gates lowered: gates on tokens (qubits by first use), which tokens are data."""

    gates: tuple[tuple[str, tuple[int, ...]], ...]
    is_data: tuple[bool, ...]
    ops: tuple[tuple[str, int], ...]


def _pattern(block: Sequence[Gate], n_data: int) -> tuple[Hashable, list[int]]:
    """A block's gates with qubits named by first use (and which are data), and its qubits in that order."""
    token: dict[int, int] = {}
    body = []
    for g in block:
        qs = []
        for q in g[1]:
            t = token.get(q)
            if t is None:
                t = token[q] = len(token)
            qs.append(t)
        body.append((g[0], tuple(qs), tuple(map(str, g[2])), g[3]))
    order = list(token)
    return (tuple(body), tuple(q < n_data for q in order)), order


def _lower_template(block: Sequence[Gate], order: list[int], registers: Sequence[Register], n_data: int) -> _Template:
    low = lower(Circuit(registers, [Section("w", tuple(block))]))
    token = {q: i for i, q in enumerate(order)}
    gates = []
    for g in low.gates:
        qs = []
        for q in g[1]:
            t = token.get(q)
            if t is None:  # a qubit the lowering adds (the ``work`` register)
                t = token[q] = len(token)
            qs.append(t)
        gates.append((g[0], tuple(qs)))
    is_data = tuple(q < n_data for q in token)
    return _Template(tuple(gates), is_data, tuple(sorted(Counter(g[0] for g in low.gates).items())))


def _windows(plan: Any, p: int) -> list[tuple[int, Sequence[Gate], str]]:
    """``(multiplicity, block, section name)``: the blocks of the sections that stand for the circuit of ``p``
    layers, each with how many like it that circuit has (:meth:`qcpp.plan.qaoa.QaoaPlan.layer_sections`)."""
    out = []
    for name, g, n in plan.layer_sections(p):
        blocks = g.emit_blocks() if isinstance(g, McxPartialMixer) else [g.emit()]
        for b in blocks:
            out.append((n, b, name))
    return out


# --- routing one representative ----------------------------------------------------------------------------
def _grid(rows: int, cols: int) -> tuple[Device, np.ndarray]:
    """The crop's device and its distances (Manhattan: a rectangle of the square lattice); small crops are
    remembered (a whole device's dense matrix is not: up to 134 MB)."""
    return _small_grid(rows, cols) if rows * cols <= 1_024 else _grid_of(rows, cols)


def _grid_of(rows: int, cols: int) -> tuple[Device, np.ndarray]:
    r, c = np.divmod(np.arange(rows * cols), cols)
    dist = (np.abs(r[:, None] - r[None, :]) + np.abs(c[:, None] - c[None, :])).astype(float)
    return get_device(f"grid:{rows}x{cols}"), dist


_small_grid = lru_cache(maxsize=128)(_grid_of)


@dataclass(frozen=True)
class _Crop:
    top: int
    left: int
    rows: int
    cols: int
    open_sides: tuple[bool, bool, bool, bool]  # top, bottom, left, right: a side that is not a device edge


def _crop(box: tuple[int, int, int, int], margin: int, shape: tuple[int, int]) -> _Crop:
    r0, r1, c0, c1 = box
    top, bottom = max(0, r0 - margin), min(shape[0] - 1, r1 + margin)
    left, right = max(0, c0 - margin), min(shape[1] - 1, c1 + margin)
    sides = (top > 0, bottom < shape[0] - 1, left > 0, right < shape[1] - 1)
    return _Crop(top, left, bottom - top + 1, right - left + 1, sides)


def _inside(crop: _Crop, sites: np.ndarray, guard: int = GUARD) -> bool:
    """Every site (local row-major index) keeps ``guard`` sites from the crop's open sides."""
    if not sites.size:
        return True
    r, c = np.divmod(sites, crop.cols)
    top, bottom, left, right = crop.open_sides
    return not (
        (top and r.min() < guard)
        or (bottom and r.max() > crop.rows - 1 - guard)
        or (left and c.min() < guard)
        or (right and c.max() > crop.cols - 1 - guard)
    )


def _route_on(
    windows: Sequence[tuple[_Template, Sequence[tuple[int, int]]]], crop: _Crop, occupied: np.ndarray, seed: int,
    options: RoutingOptions, context: RoutingContext,
) -> list[_Routed] | str | None:  # fmt: skip
    """Allocate, relay and route windows on ``crop`` with compile's functions, one section each: per window its
    lowered gates after the relays and its routed gates (on the crop's qubits); ``None`` if the crop does not
    answer for the device (module docs), ``"whole"`` if a part was routed on its whole component (no crop
    answers)."""
    dev, dist = _grid(crop.rows, crop.cols)
    sub = occupied[crop.top : crop.top + crop.rows, crop.left : crop.left + crop.cols]
    homes = np.flatnonzero(sub.ravel())
    index = {int(h): i for i, h in enumerate(homes)}
    n_data = len(homes)
    sections = []
    width = 0
    for w, (template, data_sites) in enumerate(windows):
        slot: dict[int, int] = {}
        d = a = 0
        for t, is_data in enumerate(template.is_data):
            if is_data:
                r, c = data_sites[d]
                slot[t] = index[(r - crop.top) * crop.cols + (c - crop.left)]
                d += 1
            else:
                slot[t] = n_data + a
                a += 1
        width = max(width, a)
        sections.append(Section(f"w{w}", [Gate(name, tuple(slot[t] for t in qs), (), None)
                                          for name, qs in template.gates]))  # fmt: skip
    registers = [Register("data", n_data)] + ([Register("anc", width)] if width else [])
    with context.watching() as watch:  # the search's and the relays' candidate patches included
        try:
            logical, layout = allocate_ancillas(Circuit(registers, sections), [int(h) for h in homes], dev, dist,
                                                options.allocation_search, options, context)  # fmt: skip
        except ValueError:  # more ancillas than free qubits in the crop
            return None
        logical, layout = bridge_far_phases(logical, layout, dev, dist, options=options, context=context)
        routed = route_windows(logical, dev, layout, seed=seed, measured=(), dist=dist, options=options,
                               context=context)  # fmt: skip
    if watch.whole_component and any(crop.open_sides):
        return "whole"  # routed on the whole crop: the device beyond it would change the routing
    touched = {q for g in routed.circuit.gates if len(g[1]) == 2 for q in g[1]} | set(layout[n_data:])
    if not _inside(crop, np.array(sorted(touched), dtype=int)):
        return None
    if not _inside(crop, np.array(sorted(watch.qubits), dtype=int), guard=1):
        return None  # a patch reached a side the crop cut: on the device it would be larger
    fused = dict(routed.fused)
    by_name: dict[str, list[Gate]] = {}
    for sec in routed.circuit.sections:  # a window's one-qubit gates may trail into the next window's gates
        by_name.setdefault(sec.name, []).extend(sec.gates)
    out = []
    for w, sec in enumerate(logical.sections):
        lowered = tuple((g[0], tuple(g[1])) for g in sec.gates)
        gates = by_name.get(f"w{w}", [])
        cx = sum(1 for g in gates if len(g[1]) == 2) - sum(1 for _, qs in lowered if len(qs) == 2)
        merged = fused.get(f"w{w}", 0)  # each SWAP adds 3 CX, 2 fewer where fused with a CX (routing.sabre.assemble)
        out.append(_Routed((cx + 2 * merged) // 3, lowered, gates, merged))
    return out


@dataclass(frozen=True)
class _Routed:
    """One window as compile writes it: SWAPs, lowered gates after the relays (names and qubits), routed gates."""

    swaps: int
    lowered: tuple[tuple[str, tuple[int, ...]], ...]
    gates: Sequence[Gate]
    fused: int = 0


@dataclass(frozen=True)
class _Cost:
    """What one routed window of a class costs: its lowered gate counts after the relays, SWAPs, native depth and
    two-qubit depth, duration, the native one-qubit gates (and their seconds) that trail its last two-qubit
    gates (see :func:`_trailing`), and its SWAPs fused with a CX (two CX fewer each)."""

    lowered_ops: tuple[tuple[str, int], ...]
    swaps: int
    depth: int
    two_qubit_depth: int
    duration_s: float | None
    late: int
    late_s: float | None
    fused: int = 0


def _summary(routed: _Routed, device: Device) -> _Cost:
    """The :class:`_Cost` of one routed window."""
    ops = tuple(sorted(Counter(name for name, _ in routed.lowered).items()))
    return _Cost(ops, routed.swaps, *_native_schedule(routed.gates, device), *_trailing(routed.lowered, device),
                 routed.fused)  # fmt: skip


def _trailing(lowered: Sequence[tuple[str, tuple[int, ...]]], device: Device) -> tuple[int, float | None]:
    """Native one-qubit gates of a window (lowered gates) that follow their qubit's last two-qubit gate in it (all
    of a qubit's if it has none), and their total duration at the device's longest one-qubit gate time
    (``None``: none)."""
    seen: set[int] = set()
    count = 0
    for name, qs in reversed(lowered):
        if len(qs) == 2:
            seen.update(qs)
        elif qs[0] not in seen:
            count += len(_expansion(name, 1, device))
    if device.duration_1q_s is None:
        return count, None
    return count, count * max((d for _, per in device.duration_1q_s for d in per), default=0.0)


def _native_counts(lowered: Counter[str], swaps: int, device: Device, fused: int = 0) -> Counter[str]:
    """Native gates (by the device's gate name, ``sx`` for ``rx(pi/2)``) of lowered gates plus SWAPs (3 CX each, 2
    fewer for each of the ``fused`` ones)."""
    out: Counter[str] = Counter()
    counts = Counter(lowered)
    counts["cx"] += 3 * swaps - 2 * fused
    for name, k in counts.items():
        for native, _ in _expansion(name, 2 if name in ("cx", "cz") else 1, device):
            out[native] += k
    return out


def _uniform_log_errors(device: Device) -> dict[str, float] | None:
    """``log(1 - error)`` per native gate name and ``"readout"``, if the device's errors are uniform."""
    out = {}
    for name, per in device.error_1q:
        if len(set(per)) > 1:
            return None
        out[name] = math.log1p(-per[0]) if per else 0.0
    if len(set(device.error_2q)) > 1 or len(set(device.readout_error)) > 1:
        return None
    out[device.two_qubit_gate] = math.log1p(-device.error_2q[0])
    out["readout"] = math.log1p(-device.readout_error[0])
    return out


def routed_sum(
    scenario: Scenario,
    p: int,
    options: PlanOptions = DEFAULT_PLAN,
    device: str | Device = "grid",
    *,
    seed: int = 0,
    arrangement: str = "tile",
    whole_device_work: int | None = None,
    stage: Callable[[str], None] | None = None,
    routing: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> RoutedSum | None:
    """The routed figures of ``compile_for_device(scenario, p, device, options, layout_method="medial")`` as a sum
    over window classes (see the module docs), or ``None`` where the medial layout does not apply (not a square
    grid, or too small for it) or a window needs the whole device beyond :data:`WHOLE_DEVICE_MAX_QUBITS` qubits or
    ``whole_device_work``.

    Args:
        scenario: The scenario.
        p: QAOA layers.
        options: The plan options, as given to compile (``phase_layout="auto"`` is settled for the device).
        device: A device name or :class:`Device` (the unsized ``grid`` is sized as compile sizes it).
        seed: SABRE's seed (compile's default).
        arrangement: The medial layout's robot arrangement.
        whole_device_work: At most this many (windows routed on the whole device x device qubits), else ``None``
            is returned as soon as the budget is exceeded; ``None``: no limit.
        stage: Called with the stage as it starts (``routing window classes (12 done, 30 to go)``).
        routing: The routing settings, as given to compile.
        context: The run's memos (default: a fresh one).

    Returns:
        The :class:`RoutedSum`, or ``None``.

    Raises:
        ValueError: a window needs more ancillas than the (sized) device has free qubits.
    """
    from qcpp.pipeline.device_compile import medial_device

    dev = medial_device(scenario, device, arrangement)
    if dev is None:
        return None
    n_data = scenario.num_variables
    blocks = _templated_blocks(scenario, p, options, device)
    dev = _sized_device(dev, device, n_data, blocks)
    homes = _data_homes(scenario, dev, arrangement)
    context = RoutingContext() if context is None else context
    run = _Run(dev, homes, seed, routing, context, _device_key(dev, seed, routing))
    classes = _routed_classes(_placed_windows(blocks, homes), run, whole_device_work, stage or (lambda _text: None))
    if classes is None:
        return None
    return _summed(classes, dev, p, n_data)


# --- the steps of routed_sum ------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Block:
    """One window of the plan's sections, lowered: how many like it the circuit of ``p`` layers has, its
    :class:`_Template` (shared by every window whose lowered gates route alike: angles do not route) and its data
    qubits in the template's token order."""

    weight: int
    template: _Template
    data: tuple[int, ...]


def _templated_blocks(scenario: Scenario, p: int, options: PlanOptions, device: str | Device) -> list[_Block]:
    """The windows of the unfused plan compile builds for ``device`` (medial layout), lowered once per pattern of
    high-level gates.

    Invariant: blocks whose lowered gates and data tokens are equal share one :class:`_Template` object (the first
    one lowered), so their classes differ only by where their data sit.
    """
    from qcpp.pipeline.device_plan import device_plan_options
    from qcpp.plan.qaoa import qaoa_plan

    opts = dataclasses.replace(device_plan_options(options, device, layout_method="medial"), fuse=False)
    plan = qaoa_plan(scenario, min(p, 1 if opts.first_phase else 2), opts)  # its layers stand for all p
    n_data = scenario.num_variables
    registers = plan.registers
    templates: dict[Hashable, _Template] = {}  # per pattern of high-level gates (angles included)
    shared: dict[Hashable, _Template] = {}  # per lowered gates without angles: what routing sees
    blocks = []
    for weight, block, _ in _windows(plan, p):
        key, order = _pattern(block, n_data)
        template = templates.get(key)
        if template is None:
            template = templates[key] = _lower_template(block, order, registers, n_data)
        template = shared.setdefault((template.gates, template.is_data), template)  # angles do not route
        data = tuple(q for q, is_data in zip(order, template.is_data, strict=False) if is_data)
        blocks.append(_Block(weight, template, data))
    return blocks


def _sized_device(dev: Device, device: str | Device, n_data: int, blocks: Sequence[_Block]) -> Device:
    """``dev`` grown as compile grows the unsized ``grid`` until every block's ancillas fit beside the data.

    Raises:
        ValueError: a block needs more ancillas than a device other than the unsized ``grid`` has free qubits.
    """
    from qcpp.pipeline.device_compile import grown_device

    need = max((sum(not x for x in b.template.is_data) for b in blocks), default=0)
    while dev.num_qubits - n_data < need:  # compile grows the unsized grid while a section lacks free qubits
        if device != "grid":
            raise ValueError(f"a section needs {need} ancillas; device {dev.name} has {dev.num_qubits - n_data} "
                             "free qubits")  # fmt: skip
        dev = grown_device(dev)
    return dev


@dataclass(frozen=True)
class _Homes:
    """The data homes of the medial layout on a square grid device: its ``shape`` (rows, columns), which sites
    hold a data qubit (``occupied``, that shape) and each data qubit's row and column (``rows``, ``cols``)."""

    shape: tuple[int, int]
    occupied: np.ndarray
    rows: np.ndarray
    cols: np.ndarray


def _data_homes(scenario: Scenario, dev: Device, arrangement: str) -> _Homes:
    """Where the medial layout puts the scenario's data qubits on ``dev`` (a square grid large enough for it)."""
    shape = grid_shape(dev)
    assert shape is not None
    homes = medial_placement(scenario, dev, arrangement)
    assert homes is not None
    occupied = np.zeros(shape, dtype=bool)
    rows_of, cols_of = np.divmod(np.array(homes, dtype=int), shape[1])
    occupied[rows_of, cols_of] = True
    return _Homes(shape, occupied, rows_of, cols_of)


@dataclass(frozen=True)
class _Window:
    """A window placed on the device: its weight (windows like it), template, its data qubits' sites (row,
    column) and their bounding box (top, bottom, left, right; ``None``: no data qubit)."""

    weight: int
    template: _Template
    sites: tuple[tuple[int, int], ...]
    box: tuple[int, int, int, int] | None


def _placed_windows(blocks: Sequence[_Block], homes: _Homes) -> list[_Window]:
    """The blocks that occur (weight > 0) with their data qubits' sites, in the blocks' order."""
    out = []
    for b in blocks:
        if b.weight:
            rs, cs = homes.rows[list(b.data)], homes.cols[list(b.data)]
            box = (int(rs.min()), int(rs.max()), int(cs.min()), int(cs.max())) if len(b.data) else None
            out.append(_Window(b.weight, b.template, tuple(zip(rs.tolist(), cs.tolist(), strict=True)), box))
    return out


def _signature(window: _Window, margin: int, homes: _Homes) -> tuple[Hashable, _Crop]:
    """The window's class at ``margin``: its gates, data sites relative to their box, and the crop around.

    Two windows with equal signatures route alike on the device (module docs), so one representative answers for
    both wherever the crop answers.
    """
    shape = homes.shape
    box = window.box
    if box is None:  # no data qubit: allocation looks at the whole device
        box = (0, shape[0] - 1, 0, shape[1] - 1)
    crop = _crop(box, margin, shape)
    env = homes.occupied[crop.top : crop.top + crop.rows, crop.left : crop.left + crop.cols]
    rel = tuple((r - box[0], c - box[2]) for r, c in window.sites)
    template = window.template
    return (template.gates, template.is_data, rel, margin, crop.rows, crop.cols, box[0] - crop.top,
            box[2] - crop.left, crop.open_sides, env.tobytes()), crop  # fmt: skip


def _grouped(windows: Sequence[_Window], margin: int, homes: _Homes) -> dict[Hashable, list[_Window]]:
    """The windows grouped by their :func:`_signature` at ``margin``, groups and members in first-seen order."""
    out: dict[Hashable, list[_Window]] = {}
    for w in windows:
        out.setdefault(_signature(w, margin, homes)[0], []).append(w)
    return out


def _device_key(dev: Device, seed: int, routing: RoutingOptions) -> Hashable:
    """What besides a class's signature decides its routed cost: the device's gate set, its durations per gate
    name (the first of each: the crops' devices are uniform), SABRE's seed and the routing settings."""
    timing = None if dev.duration_2q_s is None or dev.duration_1q_s is None else (
        dev.duration_2q_s[:1], tuple((name, per[:1]) for name, per in dev.duration_1q_s))  # fmt: skip
    return (dev.two_qubit_gate, tuple(dev.native_gates), timing, seed, routing)


@dataclass(frozen=True)
class _Run:
    """One sum's routing: the sized device, its data homes, SABRE's seed, the routing settings, the run's memos
    (mutable: the routed classes are remembered there) and the memo key of the device (:func:`_device_key`)."""

    device: Device
    homes: _Homes
    seed: int
    routing: RoutingOptions
    context: RoutingContext
    device_key: Hashable


def _routed_classes(
    windows: Sequence[_Window], run: _Run, whole_device_work: int | None, say: Callable[[str], None]
) -> list[tuple[list[_Window], _Cost]] | None:
    """Every window in a class with what one routed window of the class costs, classes in resolution order.

    Classes are resolved at the smallest margin whose crop answers for the device (:func:`_classes_on_crops`);
    those only the whole device answers for are routed on it in one batch (:func:`_whole_device_costs`). Every
    class's cost is remembered in ``run.context`` (which starts over past :data:`ROUTED_CLASSES_LIMIT` entries).

    Returns:
        ``(members, cost)`` per class, or ``None`` where the whole device's windows exceed
        :data:`WHOLE_DEVICE_MAX_QUBITS` or ``whole_device_work``.
    """
    found = _classes_on_crops(windows, run, whole_device_work, say)
    if found is None:
        return None
    entries, results, whole_batch = found
    if whole_batch:
        say(f"routing {len(whole_batch):,} window classes on the whole device")
        for i, cost in zip(whole_batch, _whole_device_costs([entries[i][1][0] for i in whole_batch], run), strict=True):
            results[i] = cost
    memo = run.context.window_classes
    if len(memo) > ROUTED_CLASSES_LIMIT:
        memo.clear()
    for (sig, _), result in zip(entries, results, strict=True):
        memo[(sig, run.device_key)] = result
    out = []
    for (_, group), result in zip(entries, results, strict=True):
        assert result is not None
        out.append((group, result))
    return out


def _classes_on_crops(
    windows: Sequence[_Window], run: _Run, whole_device_work: int | None, say: Callable[[str], None]
) -> tuple[list[tuple[Hashable, list[_Window]]], list[_Cost | None], list[int]] | None:
    """Resolve the window classes: each class's signature and members, its cost where the run's memo knows it or a
    crop answers for the device (a class whose representative needs a larger crop is split by its members'
    signatures at twice the margin, or at the whole device), and the positions of the classes left for the whole
    device (cost ``None`` so far).

    Returns:
        ``(entries, costs, whole-device positions)``, or ``None`` as soon as the whole device's classes exceed
        :data:`WHOLE_DEVICE_MAX_QUBITS` or ``whole_device_work``.
    """
    dev, homes = run.device, run.homes
    entries: list[tuple[Hashable, list[_Window]]] = []  # resolved classes: signature, members
    results: list[_Cost | None] = []
    whole_batch: list[int] = []
    work = math.inf if whole_device_work is None else whole_device_work
    whole = max(homes.shape)  # a margin whose crop is the whole device
    pending = [(MARGIN, sig, group) for sig, group in _grouped(windows, MARGIN, homes).items()]
    while pending:
        if len(entries) % 25 == 0:  # a line now and then, not one per class
            say(f"routing window classes ({len(entries):,} done, {len(pending):,} to go)")
        margin, sig, group = pending.pop()
        hit = run.context.window_classes.get((sig, run.device_key))
        first = group[0]
        crop = _signature(first, margin, homes)[1]
        if hit is None and any(crop.open_sides):
            routed = _route_on([(first.template, first.sites)], crop, homes.occupied, run.seed, run.routing,
                               run.context)  # fmt: skip
            if routed is None or routed == "whole":
                wider = whole if routed == "whole" else 2 * margin  # no crop short of the device answers
                pending.extend((wider, s2, g2) for s2, g2 in _grouped(group, wider, homes).items())
                continue
            hit = _summary(routed[0], dev)  # type: ignore[index]
        elif hit is None:  # routed with the others on the whole device
            whole_batch.append(len(entries))
            if dev.num_qubits > WHOLE_DEVICE_MAX_QUBITS or len(whole_batch) * dev.num_qubits > work:
                return None
        entries.append((sig, group))
        results.append(hit)
    return entries, results, whole_batch


def _whole_device_costs(representatives: Sequence[_Window], run: _Run) -> list[_Cost]:
    """The cost of each representative routed on the whole device, all in one routing (as compile routes them)."""
    shape = run.homes.shape
    crop = _crop((0, shape[0] - 1, 0, shape[1] - 1), 0, shape)
    batch = _route_on([(w.template, w.sites) for w in representatives], crop, run.homes.occupied, run.seed,
                      run.routing, run.context)  # fmt: skip
    assert batch is not None, "the whole device answers for itself"
    return [_summary(r, run.device) for r in batch]


def _summed(classes: Sequence[tuple[list[_Window], _Cost]], dev: Device, p: int, n_data: int) -> RoutedSum:
    """The :class:`RoutedSum` of the classes: each class's cost times its windows' total weight, plus one readout
    (its duration, and its error in the ESP) per data qubit.

    Invariant: depth and duration add each window's trailing one-qubit gates once (they wait for their qubit's
    next two-qubit gate in a later window), so both are upper bounds; counts and the ESP are exact.
    """
    log_errors = _uniform_log_errors(dev)
    out: list[WindowClass] = []
    lowered: Counter[str] = Counter()
    compiled: Counter[str] = Counter()
    native: Counter[str] = Counter()
    swaps = windows = depth = depth2 = 0
    duration: float | None = 0.0
    for group, result in classes:
        weight = sum(m.weight for m in group)
        template = group[0].template
        windows += weight
        compiled.update({k: v * weight for k, v in template.ops})
        ops = Counter(dict(result.lowered_ops))  # after the relays, as compile writes it
        lowered.update({k: v * weight for k, v in ops.items()})
        counts = _native_counts(ops, result.swaps, dev, result.fused)
        swaps += weight * result.swaps
        native.update({k: v * weight for k, v in counts.items() if v})
        # a window's one-qubit gates after a qubit's last two-qubit gate in it wait for that qubit's next
        # two-qubit gate (router's rule), in a later window: each such native gate adds at most one level there
        depth += weight * (result.depth + result.late)
        depth2 += weight * result.two_qubit_depth
        if duration is not None and result.duration_s is not None and result.late_s is not None:
            duration += weight * (result.duration_s + result.late_s)
        else:
            duration = None
        out.append(WindowClass(weight, result.lowered_ops, result.swaps, tuple(sorted(counts.items())),
                               result.depth, result.two_qubit_depth, result.duration_s))  # fmt: skip
    twoq_name = dev.two_qubit_gate
    two = native.get(twoq_name, 0)
    one = sum(v for k, v in native.items() if k != twoq_name)
    log_esp = None
    if log_errors is not None:
        log_esp = sum(v * log_errors.get(k, 0.0) for k, v in native.items()) + n_data * log_errors["readout"]
    if duration is not None and dev.readout_duration_s:
        duration += max(dev.readout_duration_s)
    elif duration is not None:
        duration = None
    return RoutedSum(dev, p, windows, tuple(out), dict(lowered), dict(compiled), swaps, dict(native), two,
                     one, log_esp, depth, depth2, duration)  # fmt: skip


def _expansion(name: str, arity: int, device: Device) -> tuple[tuple[str, tuple[int, ...]], ...]:
    """The native gates (device gate name, roles ``0``/``1`` of the lowered gate's qubits) one lowered gate
    becomes (:func:`qcpp.routing.native.to_native`)."""
    return _expansion_of(name, arity, device.two_qubit_gate, tuple(device.native_gates))


@lru_cache(maxsize=256)
def _expansion_of(name: str, arity: int, twoq: str, native: tuple[str, ...]) -> tuple[tuple[str, tuple[int, ...]], ...]:
    """Pure memo: ``_expansion_of.cache_clear()`` empties it."""
    params = (math.pi / 2,) if name in ("rz", "rx") else ()
    gates = native_gates(Gate(name, tuple(range(arity)), params, None), twoq, "x" in native)
    sx = "sx" in native
    return tuple(("sx" if sx and g[0] == "rx" else g[0], tuple(g[1])) for g in gates)


def _native_schedule(gates: Sequence[Gate], device: Device) -> tuple[int, int, float | None]:
    """ASAP depth, two-qubit depth and length in seconds (``None`` unless the device's durations are uniform,
    so that the crop stands for any part of it) of one routed window in native gates, without building them."""
    n = 1 + max((q for g in gates for q in g[1]), default=-1)
    level, level2, clock = [0] * n, [0] * n, [0.0] * n
    timed = device.duration_1q_s is not None and device.duration_2q_s is not None
    if timed and (len(set(device.duration_2q_s)) > 1 or any(len(set(per)) > 1 for _, per in device.duration_1q_s)):
        timed = False
    d1 = {name: per[0] for name, per in device.duration_1q_s} if timed else {}
    d2 = device.duration_2q_s[0] if timed and device.duration_2q_s else 0.0
    expansions: dict[tuple[str, int], tuple[tuple[str, tuple[int, ...]], ...]] = {}
    for g in gates:
        qs = g[1]
        shape = (g[0], len(qs))
        expansion = expansions.get(shape)
        if expansion is None:
            expansion = expansions[shape] = _expansion(g[0], len(qs), device)
        for name, roles in expansion:
            if len(roles) == 2:
                a, b = qs[roles[0]], qs[roles[1]]
                top = max(level[a], level[b]) + 1
                top2 = max(level2[a], level2[b]) + 1
                start = max(clock[a], clock[b]) + d2
                level[a] = level[b] = top
                level2[a] = level2[b] = top2
                clock[a] = clock[b] = start
            else:
                q = qs[roles[0]]
                level[q] += 1
                if timed:
                    clock[q] += d1[name]
    return max(level, default=0), max(level2, default=0), max(clock, default=0.0) if timed else None
