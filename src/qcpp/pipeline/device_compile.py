"""From a scenario to a routed circuit on a device: compile, allocate, place, route, translate to native gates.

:func:`compile_for_device` is what ``qcpp compile --device NAME`` runs. It compiles and lowers with
``fuse=False`` (every gadget a section of its own, clean at both ends; the lowered count is 2-12 CX above the
fused one on the default grids), then takes one of two paths (``layout_method``, default ``auto``):

* **medial** (square-grid devices and heavy-hex lattices that hold it; the unsized families ``grid`` and
  ``heavy-hex`` are sized for it, :func:`layout_device`): :func:`qcpp.layout.medial.medial_placement` puts every
  edge qubit on its edge's midpoint of a ``(2R-1) x (2C-1)`` patch per robot on a square grid, and on a
  heavy-hex lattice one heavy-hex cell per plaquette (:mod:`qcpp.layout.heavy_hex`);
  :func:`qcpp.layout.medial.allocate_ancillas` gives every section the free device
  qubits nearest its data as ancillas (for the partial mixers, the sites whose window routes to the fewest
  gates among the nearest few), :func:`qcpp.routing.bridge.bridge_far_phases` relays far ``rzz`` phases (a node's
  visit bits of different robots) through clean device qubits where that routes cheaper than SWAPs, and
  :func:`qcpp.routing.windows.route_windows` routes every section with
  Qiskit's SABRE on the patch around it, uncompute mirrored, every qubit back home at the section's end (so
  ``initial_layout == final_layout``); on a large square grid the layout leaves mostly empty (a long strip's),
  all of this runs on the sub-grid around the layout, with the same result (:func:`_cropped`);
* **greedy** (any device; the fallback, and for small circuits where it routes to fewer two-qubit gates,
  :attr:`~qcpp.routing.options.RoutingOptions.auto_compare_max_twoq`; on the unsized ``heavy-hex`` it is then
  routed on the smallest lattice that holds the circuit, where it needs no room for the cells): optionally region-local
  ancillas (:func:`qcpp.layout.placement.localize_ancillas`, ``local_ancillas=True``), then :func:`best_layout`
  (our greedy placement refined forward-backward with SABRE, or Qiskit's ``SabreLayout``: the fewest SWAPs wins)
  and one SABRE routing of the whole circuit (:func:`qcpp.routing.sabre.route`); on circuits of at most
  :attr:`~qcpp.routing.options.RoutingOptions.placement_max_twoq` two-qubit gates, a placement search from that
  layout instead (:func:`greedy_route`: many ``SabreLayout`` starts and SABRE seeds, SWAPs fused with an adjacent
  ``cx``, the fewest CX kept; deterministic), for the circuit as compiled and for the one whose partial mixers
  use the equally cheap networks that route cheapest (:func:`qcpp.pipeline.routed_mixers.routed_mixers`), the
  one of fewer two-qubit gates kept.

Unless ``lowered``, the routed circuit is translated to the device's native gates
(:func:`qcpp.routing.native.to_native`). On a named device the result is the best of
:func:`qcpp.pipeline.candidates.calibrated_candidates`; on IBM's heavy-hex devices ``auto`` adds to them the
heavy-hex cells routed on the abstract lattice ``heavy-hex:D`` and, for circuits the placement search takes, the
greedy path's routings on the defect-free lattices ``heavy-hex:3`` .. ``heavy-hex:9`` that hold the circuit
(:attr:`~qcpp.routing.options.RoutingOptions.lattice_search_max_distance`; no one size routes cheapest for every
circuit), which the candidates place on the device where their couplers embed.
:attr:`DeviceCompileResult.layout_method` says which path was taken. Every setting of routing, allocation and the
searches comes in one :class:`~qcpp.routing.options.RoutingOptions` value and the memos of the run in one
:class:`~qcpp.routing.context.RoutingContext`, both passed down explicitly.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> r = compile_for_device(default_scenario(3, 3, 1), p=1, device="grid", bindings={"gamma_0": 0.3})
    >>> r.routed.device.name, r.layout_method, r.routed.initial_layout == r.routed.final_layout
    ('grid:5x5', 'medial', True)
    >>> sorted(r.routed.circuit.count_ops())
    ['cz', 'rx', 'rz']
    >>> r = compile_for_device(default_scenario(3, 3, 1), p=1, device="heavy-hex")
    >>> r.layout_method, r.routed.device.name  # cheaper here than the cells on a larger lattice
    ('greedy', 'heavy-hex:3')
    >>> cells = compile_for_device(default_scenario(3, 3, 1), p=1, device="heavy-hex", layout_method="medial")
    >>> cells.routed.device.name
    'heavy-hex:7'
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

from qcpp.errors import OptionError
from qcpp.hardware.device import IBM_DEVICES, Device, device_names, distances, get_device, heavy_hex_distance
from qcpp.ir.circuit import Circuit, Section
from qcpp.layout.heavy_hex import hex_distance, hex_placement
from qcpp.layout.medial import allocate_ancillas, grid_shape, medial_placement, medial_shape
from qcpp.layout.placement import localize_ancillas, place
from qcpp.layout.placement_search import qiskit_sabre_layout, ranked_routes, search_route
from qcpp.pipeline.candidates import (
    FROM_ZERO,
    OPTIMIZE_FOR,
    QISKIT_SEEDS,
    calibrated_candidates,
    choose,
    default_objective,
    is_calibrated,
    zero_start_refusal,
)
from qcpp.pipeline.cellmixer import cell_mixers
from qcpp.pipeline.device_plan import device_plan_options
from qcpp.pipeline.routed_mixers import routed_mixers
from qcpp.plan.compile import CompileResult, compile_scenario
from qcpp.plan.options import DEFAULT_PLAN, LAYOUT_METHODS, PlanOptions
from qcpp.plan.qaoa import QaoaPlan
from qcpp.problem.scenario import Scenario
from qcpp.routing.bridge import bridge_far_phases
from qcpp.routing.context import RoutingContext, collector_paused
from qcpp.routing.native import IDLE_MODEL, duration_s, esp_figures, to_native
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions, effort_of
from qcpp.routing.prefetch import can_prefetch, prefetch_windows
from qcpp.routing.routed_circuit import RoutedCircuit, embed_routed
from qcpp.routing.sabre import route
from qcpp.routing.windows import commuting_middle, mirror_length, route_windows

__all__ = [
    "DeviceCompileResult",
    "auto_tries_greedy",
    "compile_for_device",
    "device_for",
    "greedy_route",
    "grown_device",
    "hex_device",
    "layout_device",
    "medial_device",
]


@dataclass(frozen=True)
class DeviceCompileResult:
    """A routed circuit and where it came from.

    Attributes:
        compiled: The unrouted lowered circuit (logical qubits).
        logical: The circuit routed (logical qubits): the compiled circuit, after the optional local-ancilla
            pass, or with partial mixers planned for the routing (:mod:`qcpp.pipeline.routed_mixers`, the
            heavy-hex cells' :mod:`qcpp.pipeline.cellmixer`); the same operator.
        routed: The routed circuit (native gates unless compiled ``lowered``).
        lowered: Whether the routed circuit keeps CX + one-qubit gates.
        seconds: Wall time of everything.
        layout_method: ``medial`` (geometric layout: medial on square grids, cells on heavy-hex lattices;
            windows routed home) or ``greedy`` (:func:`best_layout`).
        optimize_for: The figure the routing was chosen by (``esp`` or ``twoq``).
        chosen: The candidate that won (:mod:`qcpp.pipeline.candidates`; ``qcpp``: compile's own routing).
        candidates: Every candidate's ``{name, two_qubit, esp, esp_idle}`` (empty where there was one: the
            families).
        zero_start: Whether the candidates simplified for the all-|0> start were offered (``zero_start``).
        effort: The routing settings' name (:func:`~qcpp.routing.options.effort_of`: ``full``, ``quick`` or
            ``custom``).
    """

    compiled: CompileResult
    logical: Circuit
    routed: RoutedCircuit
    lowered: bool
    seconds: float
    layout_method: str = "greedy"
    optimize_for: str = "twoq"
    chosen: str = "qcpp"
    candidates: tuple[dict[str, Any], ...] = ()
    zero_start: bool = False
    effort: str = "full"

    @property
    def logical_qubits(self) -> int:
        """Qubits of the logical circuit that was routed."""
        return self.logical.num_qubits

    @property
    def equal_on_every_input(self) -> bool:
        """Whether the routed circuit equals the logical circuit on every input (as a unitary, up to the layouts),
        not only on the all-|0> start: false where the chosen candidate is simplified for that start
        (``zero_start``, :data:`~qcpp.pipeline.candidates.FROM_ZERO` in its name); then no gate may run before
        it."""
        return FROM_ZERO not in self.chosen

    def compile_summary(self) -> dict[str, Any]:
        """What ``qcpp compile --device --json`` prints: the routed circuit's
        :func:`~qcpp.plan.compile.compile_summary` fields (qubits, gates, registers of the device) with
        :meth:`summary`'s and a ``device_note``."""
        circuit, device = self.routed.circuit, self.routed.device
        return {
            **self.compiled.summary(),
            "qubits": circuit.num_qubits,
            "gates": dict(sorted(circuit.count_ops().items())),
            "total_gates": len(circuit),
            "lowered": self.lowered,
            "registers": {r.name: r.size for r in circuit.registers},
            "seconds": self.seconds,
            **self.summary(),
            "device_note": (
                f"device {device.name} ({device.num_qubits} qubits; {self.logical_qubits} logical on "
                f"{len(self.routed.active_qubits)} physical); layouts: logical qubit i -> physical qubit"
            ),
        }

    def summary(self) -> dict[str, Any]:
        """JSON-ready: ``device``, ``initial_layout``, ``final_layout``, ``routed`` (gates, two-qubit count, swaps,
        ESP of the gates with its model, ESP with idle decoherence (``esp_idle``, ``None`` on devices without
        T1 / T2) with its model, both also as base-10 logs (``log10_esp``, ``log10_esp_idle``: finite where the ESP
        underflows to 0, as in ``qcpp estimate``), duration in seconds)."""
        r = self.routed
        native = r if not self.lowered else to_native(r)
        ops = r.circuit.count_ops()
        figures = esp_figures(native)
        return {
            "device": r.device.summary(),
            "initial_layout": list(r.initial_layout),
            "final_layout": list(r.final_layout),
            "routed": {
                "router": ROUTERS[self.layout_method] + (candidates_note(self.zero_start) if self.candidates else ""),
                "layout": self.layout_method,
                "two_qubit": sum(v for k, v in ops.items() if k in ("cx", "cz", "rzz")),
                "swaps": r.swaps,
                "esp": figures["esp"],
                "esp_model": ESP_MODEL,
                "esp_idle": figures["esp_idle"],
                "esp_idle_model": f"esp x {IDLE_MODEL}",
                "log10_esp": figures["log10_esp"],
                "log10_esp_idle": figures["log10_esp_idle"],
                "optimize_for": self.optimize_for,
                "effort": self.effort,
                "zero_start": self.zero_start,
                "equal_on_every_input": self.equal_on_every_input,
                "chosen": self.chosen,
                "candidates": list(self.candidates),
                "duration_s": duration_s(native),
            },
        }


ROUTERS = {
    "medial": "geometric layout (medial on a square grid, one cell per plaquette on heavy-hex) with local ancillas, "
    "far phases relayed through clean qubits; qiskit SabreSwap per section, each section returning home",
    "greedy": "qiskit SabreSwap of the whole circuit from the better of our greedy layout and qiskit SabreLayout; "
    f"on circuits of at most {DEFAULT_ROUTING.placement_max_twoq} two-qubit gates the fewest CX over that layout and "
    f"{DEFAULT_ROUTING.placement_layouts} ({DEFAULT_ROUTING.calibrated_placement_layouts} on a named device) "
    "SabreLayout starts, SWAPs fused with an adjacent cx",
}
"""What each layout method routes with (on a named device, the chosen candidate may be another: ``chosen``)."""

CANDIDATES_NOTE = (
    "; on a named device that is the first of the routed candidates, and compile writes the best of them by "
    "optimize_for (compile's own routings; on a heavy-hex device the same search on defect-free lattices, placed on "
    "the device; Qiskit O3's; each also placed by the device's errors and after Qiskit's O3 passes{zero}): chosen "
    "names it, candidates lists them"
)
"""Appended to the router's description where compile chose among candidates (:mod:`qcpp.pipeline.candidates`;
``{zero}``: :data:`ZERO_START_NOTE` with ``zero_start``)."""

ZERO_START_NOTE = (
    "; with zero_start ours also with the cx that act on basis states from the all-|0> start removed, 'from |0>': "
    "equal to the logical circuit on that input only"
)
"""The ``zero_start`` candidates in :data:`CANDIDATES_NOTE`."""


def candidates_note(zero_start: bool) -> str:
    """:data:`CANDIDATES_NOTE` for a compile with or without ``zero_start``."""
    return CANDIDATES_NOTE.format(zero=ZERO_START_NOTE if zero_start else "")

ESP_MODEL = (
    "product of (1 - gate error) over every native gate and (1 - readout error) over the measured data qubits; "
    "device data, no idle decoherence or crosstalk"
)


def device_for(spec: str, qubits: int) -> Device:
    """The device named ``spec``; a family without a size gets its smallest member with ``qubits`` qubits."""
    return get_device(spec, min_qubits=qubits)


def _two_qubit_only(c: Circuit, reverse: bool = False) -> Circuit:
    gates = [g for g in c.gates if len(g[1]) == 2]
    if reverse:
        gates.reverse()
    return Circuit(c.registers, [Section("two_qubit", gates)])


LAYOUTS = ("ours", "qiskit")
"""Layout seeds :func:`best_layout` may try: our placement refined, and Qiskit's SabreLayout."""


def best_layout(
    circuit: Circuit,
    device: Device,
    refine_rounds: int = 3,
    seed: int = 0,
    layouts: tuple[str, ...] = LAYOUTS,
    options: RoutingOptions = DEFAULT_ROUTING,
) -> tuple[int, ...]:
    """The layout of fewest routed SWAPs among: our placement and its forward-backward SABRE refinements
    (``"ours"``), and Qiskit's ``SabreLayout`` (``"qiskit"``), routed with ``options``' trials."""
    if device.is_all_to_all:
        return place(circuit, device)
    forward = _two_qubit_only(circuit)
    swaps: dict[tuple[int, ...], int] = {}  # forward routing's SWAPs by layout (a refinement round routes it too)

    def forward_swaps(layout: tuple[int, ...]) -> int:
        if layout not in swaps:
            swaps[layout] = route(forward, device, layout, seed=seed, trials=options.trials).swaps
        return swaps[layout]

    candidates: list[tuple[int, ...]] = []
    if "ours" in layouts:
        layout = place(circuit, device)
        candidates.append(layout)
        backward = _two_qubit_only(circuit, reverse=True)
        for _ in range(refine_rounds):
            ahead = route(forward, device, layout, seed=seed, trials=options.trials)
            swaps.setdefault(layout, ahead.swaps)
            layout = route(backward, device, ahead.final_layout, seed=seed, trials=options.trials).final_layout
            candidates.append(layout)
    if "qiskit" in layouts:
        candidates.append(qiskit_sabre_layout(circuit, device, seed, options))
    return candidates[min((forward_swaps(lay), i) for i, lay in enumerate(candidates))[1]]


def compile_for_device(
    scenario: Scenario,
    p: int,
    device: str | Device,
    options: PlanOptions = DEFAULT_PLAN,
    *,
    lowered: bool = False,
    bindings: Mapping[str, float] | None = None,
    local_ancillas: bool = False,
    seed: int = 0,
    layouts: tuple[str, ...] = LAYOUTS,
    layout_method: str = "auto",
    arrangement: str = "tile",
    stage: Callable[[str], None] | None = None,
    routing: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
    optimize_for: str | None = None,
    bind_field: str = "bind",
    zero_start: bool = False,
) -> DeviceCompileResult:
    """Compile ``scenario`` and route it onto ``device`` (steps in the module docs).

    Args:
        scenario: The scenario.
        p: QAOA layers.
        device: A :class:`Device` or a name for :func:`qcpp.hardware.device.get_device` (a family without a size
            gets its smallest member that holds the circuit).
        options: How the circuit is built; routing always compiles it unfused (``fuse=False``: every partial
            mixer clean at both ends, so its ancillas can be placed and checked section by section).
        lowered: Keep CX + one-qubit gates (default: the device's native gates).
        bindings: Angle values (symbols may stay unbound).
        local_ancillas: Run :func:`qcpp.layout.placement.localize_ancillas` first.
        seed: SABRE's seed.
        layouts: Layout seeds to try (:func:`best_layout`, greedy method only).
        layout_method: ``auto``, ``medial`` or ``greedy`` (:data:`LAYOUT_METHODS`).
        arrangement: The medial layout's robot arrangement, ``tile`` or ``interleave``.
        stage: Called with the name of each stage as it starts (``choosing partial-mixer plans on the cells
            (3 / 18)``), for progress on a long compile.
        routing: Every setting of routing, allocation and the searches.
        context: The memos of the run (default: a fresh one; a caller compiling many circuits may share one). The
            whole result is memoised in it too: the same call again (progress aside) returns it at once.
        optimize_for: On a named device, the figure the routed candidates are chosen by (:data:`OPTIMIZE_FOR`:
            ``esp`` or ``twoq``; default :func:`qcpp.pipeline.candidates.default_objective`: ``esp`` on named
            devices). The families keep compile's single routing.
        bind_field: The argument that gave ``bindings``, starting the message of an unknown symbol (``--bind``).
        zero_start: On a named device, also offer compile's routings simplified for the all-|0> start the device
            runs from (:func:`qcpp.routing.known_state.from_zero`; ``+ from |0> + O3 passes``), with either figure:
            the written circuit then equals the logical one on that input only, so no gates may run before it
            (:attr:`DeviceCompileResult.equal_on_every_input`). Off, the candidates keep the unitary.

    Python's cyclic garbage collector is paused meanwhile (:func:`qcpp.routing.context.collector_paused`: the
    searches' memos hold hundreds of thousands of objects, which its passes would traverse again and again).

    Returns:
        The :class:`DeviceCompileResult`.

    Raises:
        qcpp.hardware.device.DeviceError: an unknown device.
        qcpp.errors.OptionError: ``zero_start`` where it does not apply (not a named device with couplers, or
            ``lowered``: :func:`~qcpp.pipeline.candidates.zero_start_refusal`).
        ValueError: the device is too small.
    """
    if zero_start:
        refusal = zero_start_refusal(device, lowered)
        if refusal is not None:
            raise OptionError("zero_start", refusal)
    key = None
    if context is not None:  # the caller's: the same call may have run in it
        named = get_device(device) if isinstance(device, str) and device in device_names() else device
        key = (scenario, p, named, options, lowered, tuple(sorted(bindings.items())) if bindings else None,
               local_ancillas, seed, tuple(layouts), layout_method, arrangement, routing, optimize_for, zero_start)
        hit = context.compiles.get(key)
        if hit is not None:
            return hit  # type: ignore[no-any-return]
    with collector_paused():  # the run's memos (in a context made here) are dropped before it resumes
        result = _compile_for_device(scenario, p, device, options, lowered, bindings, local_ancillas, seed, layouts,
                                     layout_method, arrangement, stage, routing, context, optimize_for,
                                     bind_field, zero_start)  # fmt: skip
    result = replace(result, effort=effort_of(routing))
    if context is not None:
        context.keep_compile(key, result)
    return result


def _compile_for_device(
    scenario: Scenario, p: int, device: str | Device, options: PlanOptions, lowered: bool,
    bindings: Mapping[str, float] | None, local_ancillas: bool, seed: int, layouts: tuple[str, ...],
    layout_method: str, arrangement: str, stage: Callable[[str], None] | None, routing: RoutingOptions,
    context: RoutingContext | None, optimize_for: str | None, bind_field: str = "bind", zero_start: bool = False,
) -> DeviceCompileResult:  # fmt: skip
    """:func:`compile_for_device`'s work (run with the cyclic garbage collector paused)."""
    start = time.perf_counter()
    if optimize_for is not None and optimize_for not in OPTIMIZE_FOR:
        raise ValueError(f"optimize for one of {', '.join(OPTIMIZE_FOR)}, not {optimize_for!r}")
    context = RoutingContext() if context is None else context
    options = device_plan_options(options, device, layout_method)
    say = stage or (lambda _text: None)
    say("compiling the circuit")
    compiled = compile_scenario(scenario, p, replace(options, fuse=False), lowered=True, bindings=bindings,
                                bind_field=bind_field)
    circuit = compiled.circuit
    measured = range(scenario.num_variables)
    if layout_method not in LAYOUT_METHODS:
        raise ValueError(f"layout method must be one of {', '.join(LAYOUT_METHODS)}, not {layout_method!r}")
    if layout_method != "greedy" and not local_ancillas:
        geometric = medial_compile(scenario, circuit, device, seed=seed, measured=measured, arrangement=arrangement,
                                   plan=compiled.plan, bindings=bindings, stage=stage, routing=routing,
                                   context=context)  # fmt: skip
        if geometric is not None:
            logical, routed = geometric
            method = "medial"
            if layout_method == "auto" and auto_tries_greedy(_two_qubit(circuit), routing):
                other = routed.device
                if device == "heavy-hex":  # greedy needs no room for the cells: the smallest lattice that holds it
                    other = device_for(device, circuit.num_qubits)
                say(f"routing the whole circuit on {other.name} to compare")
                greedy_logical, greedy = _with_routed_mixers(
                    circuit, [_greedy_compare(circuit, other, seed, layouts, measured, routing, context)],
                    lambda c: [_greedy_compare(c, other, seed, layouts, measured, routing, context)],
                    compiled.plan, other, bindings, routing, context, say)  # fmt: skip
                if _two_qubit(greedy[0].circuit) < _two_qubit(routed.circuit):
                    logical, routed, method = greedy_logical, greedy[0], "greedy"
            return _finish(compiled, logical, [routed], circuit, lowered, start, method, optimize_for, measured, say,
                           zero_start=zero_start)  # fmt: skip
        if layout_method == "medial":
            rows, cols = medial_shape(scenario, arrangement)
            dev = device if isinstance(device, Device) else get_device(device, min_qubits=circuit.num_qubits)
            if dev.family == "heavy-hex" and heavy_hex_distance(dev) is not None:
                raise ValueError(f"--layout medial: {scenario.grid.rows}x{scenario.grid.cols} with "
                                 f"{scenario.num_robots} robot(s) needs heavy-hex:{hex_distance(scenario)}; device "
                                 f"{dev.name} is smaller")  # fmt: skip
            if dev.family == "heavy-hex" and is_calibrated(dev):  # IBM's: the cells on heavy-hex:D, placed on it
                cells = _cells_elsewhere(compiled.plan, circuit, dev, seed, measured, bindings, stage, routing,
                                         context, max_twoq=None)  # fmt: skip
                assert cells is not None
                used = len({q for g in cells[2].circuit.gates for q in g[1]})
                return _finish(compiled, cells[1], [], circuit, lowered, start, "medial", optimize_for, measured, say,
                               (cells,), device=dev, qiskit_seeds=0, zero_start=zero_start,
                               none_fit=f"--layout medial: the heavy-hex cells of {scenario.grid.rows}x"
                               f"{scenario.grid.cols} with {scenario.num_robots} robot(s), routed on "
                               f"{cells[2].device.name}, use {used} qubits and do not embed in {dev.name} (heavy-hex "
                               "in IBM's shape, with defects); use --layout auto or greedy")  # fmt: skip
            if dev.family == "heavy-hex":
                raise ValueError(f"--layout medial: {dev.name} is heavy-hex, but not a heavy-hex:D lattice as "
                                 "Qiskit's CouplingMap.from_heavy_hex builds it (the one the cell layout maps); use "
                                 "--device heavy-hex or --layout greedy")  # fmt: skip
            if grid_shape(dev) is None:
                raise ValueError(f"--layout medial needs a square-grid or heavy-hex lattice device; {dev.name} is "
                                 "neither")  # fmt: skip
            raise ValueError(f"--layout medial: {scenario.grid.rows}x{scenario.grid.cols} with {scenario.num_robots} "
                             f"robot(s) needs a {rows}x{cols} grid; device {dev.name} is smaller")  # fmt: skip
    dev = device if isinstance(device, Device) else device_for(device, circuit.num_qubits)
    if circuit.num_qubits > dev.num_qubits:
        raise ValueError(f"the circuit needs {circuit.num_qubits} qubits; device {dev.name} has {dev.num_qubits}")
    if local_ancillas:
        circuit = localize_ancillas(circuit, scenario, dev.num_qubits - circuit.num_qubits)
    say(f"routing the whole circuit on {dev.name}")
    count = routing.calibrated_routings if is_calibrated(dev) else 1
    ours = greedy_routes(circuit, dev, seed, layouts, measured, routing, context, count=count)
    logical = circuit
    if not local_ancillas:  # localized ancillas are no longer the plan's sections
        logical, ours = _with_routed_mixers(
            circuit, ours, lambda c: greedy_routes(c, dev, seed, layouts, measured, routing, context, count=count),
            compiled.plan, dev, bindings, routing, context, say)  # fmt: skip
    elsewhere: list[tuple[str, Circuit, RoutedCircuit]] = []
    if layout_method == "auto" and not local_ancillas:
        cells = _cells_elsewhere(compiled.plan, circuit, dev, seed, measured, bindings, stage, routing, context,
                                 routing.placement_max_twoq)  # fmt: skip
        elsewhere = ([] if cells is None else [cells]) + _searched_elsewhere(
            compiled.plan, circuit, dev, seed, layouts, measured, bindings, routing, context, say)
        if (default_objective(dev) if optimize_for is None else optimize_for) == "twoq":
            elsewhere += _searched_on_siblings(compiled.plan, circuit, dev, seed, layouts, measured, bindings,
                                               routing, context, say)  # fmt: skip
    return _finish(compiled, logical, ours, circuit, lowered, start, "greedy", optimize_for, measured, say,
                   tuple(elsewhere), zero_start=zero_start)  # fmt: skip


def _searched_elsewhere(
    plan: QaoaPlan, circuit: Circuit, device: Device, seed: int, layouts: tuple[str, ...], measured: range,
    bindings: Mapping[str, float] | None, routing: RoutingOptions, context: RoutingContext,
    say: Callable[[str], None],
) -> list[tuple[str, Circuit, RoutedCircuit]]:  # fmt: skip
    """On a named heavy-hex device, ``circuit`` (at most ``routing.placement_max_twoq`` two-qubit gates) compiled
    as the greedy path compiles it on each ``heavy-hex:D`` lattice that holds it, ``D`` up to
    ``routing.lattice_search_max_distance``, as ``(name, logical circuit, routing)`` for
    :func:`~qcpp.pipeline.candidates.calibrated_candidates` to place on the device where its couplers embed. Empty
    elsewhere."""
    if not _searches_apply(circuit, device, routing):
        return []
    lattices = [get_device(f"heavy-hex:{d}") for d in range(3, routing.lattice_search_max_distance + 1, 2)]
    return _searched_on(lattices, plan, circuit, device, seed, layouts, measured, bindings, routing, context, say)


def _searched_on_siblings(
    plan: QaoaPlan, circuit: Circuit, device: Device, seed: int, layouts: tuple[str, ...], measured: range,
    bindings: Mapping[str, float] | None, routing: RoutingOptions, context: RoutingContext,
    say: Callable[[str], None],
) -> list[tuple[str, Circuit, RoutedCircuit]]:  # fmt: skip
    """With ``--optimize-for twoq`` on a named heavy-hex device, ``circuit`` (at most ``routing.placement_max_twoq``
    two-qubit gates) compiled as the greedy path compiles it on each *other* shipped IBM device
    (:data:`~qcpp.hardware.device.IBM_DEVICES`, a fixed list: a device file changes no other device's result; its wider
    placement search and partial mixers planned there), as ``(name, logical circuit, routing)`` for
    :func:`~qcpp.pipeline.candidates.calibrated_candidates` to place on ``device`` where its couplers embed: the
    devices' defects differ, so the same search starts elsewhere and now and then finds fewer SWAPs. Only for
    ``twoq``: the default ``esp`` keeps the candidates it had. Empty elsewhere."""
    if not _searches_apply(circuit, device, routing):
        return []
    siblings = [get_device(name) for name in IBM_DEVICES if name != device.name]
    return _searched_on(siblings, plan, circuit, device, seed, layouts, measured, bindings, routing, context, say)


def _searches_apply(circuit: Circuit, device: Device, routing: RoutingOptions) -> bool:
    """Whether the greedy path's searches on other hosts are candidates: on a named heavy-hex device, for a circuit
    of at most ``routing.placement_max_twoq`` two-qubit gates (and at least one)."""
    calibrated_hex = device.family == "heavy-hex" and is_calibrated(device)
    return calibrated_hex and 0 < _two_qubit(circuit) <= routing.placement_max_twoq


def _searched_on(
    hosts: Sequence[Device], plan: QaoaPlan, circuit: Circuit, device: Device, seed: int, layouts: tuple[str, ...],
    measured: range, bindings: Mapping[str, float] | None, routing: RoutingOptions, context: RoutingContext,
    say: Callable[[str], None],
) -> list[tuple[str, Circuit, RoutedCircuit]]:  # fmt: skip
    """``circuit`` compiled as the greedy path compiles it (:func:`greedy_routes`, partial mixers planned for the
    routing) on each host that holds it, in order, as ``(f"search on {host}", logical circuit, routing)``."""
    out = []
    for host in hosts:
        if host.num_qubits < circuit.num_qubits:
            continue
        say(f"routing the whole circuit on {host.name} to place it on {device.name}")

        def routes(c: Circuit, host: Device = host) -> list[RoutedCircuit]:
            return greedy_routes(c, host, seed, layouts, measured, routing, context)

        logical, routed = _with_routed_mixers(circuit, routes(circuit), routes, plan, host, bindings, routing,
                                              context, say)  # fmt: skip
        out.append((f"search on {host.name}", logical, routed[0]))
    return out


def _with_routed_mixers(
    circuit: Circuit, routes: list[RoutedCircuit], route_again: Callable[[Circuit], list[RoutedCircuit]],
    plan: QaoaPlan, device: Device, bindings: Mapping[str, float] | None, routing: RoutingOptions,
    context: RoutingContext, say: Callable[[str], None],
) -> tuple[Circuit, list[RoutedCircuit]]:  # fmt: skip
    """``(circuit, routes)``, or the circuit with its partial mixers planned for the routing
    (:func:`qcpp.pipeline.routed_mixers.routed_mixers` on ``device``) and ``route_again`` of it, where its first
    routing has fewer two-qubit gates than ``routes[0]``."""
    chosen = routed_mixers(plan, circuit, device, bindings, routing, context, stage=say)
    if chosen is circuit:
        return circuit, routes
    again = route_again(chosen)
    if _two_qubit(again[0].circuit) < _two_qubit(routes[0].circuit):
        return chosen, again
    return circuit, routes


def _cells_elsewhere(
    plan: QaoaPlan, circuit: Circuit, device: Device, seed: int, measured: range,
    bindings: Mapping[str, float] | None, stage: Callable[[str], None] | None, routing: RoutingOptions,
    context: RoutingContext, max_twoq: int | None,
) -> tuple[str, Circuit, RoutedCircuit] | None:  # fmt: skip
    """On a named heavy-hex device, the cell layout routed on the smallest ``heavy-hex:D`` lattice that holds it
    (:func:`medial_compile`), as ``(name, logical circuit, routing)`` for
    :func:`~qcpp.pipeline.candidates.calibrated_candidates` to place on the device where its couplers embed: IBM's
    lattices are heavy-hex in another numbering and shape, with defects, so the cells are not laid out on them
    directly. ``None`` on other devices, and on circuits of more than ``max_twoq`` two-qubit gates (``auto`` passes
    ``routing.placement_max_twoq``: larger cell routings use more qubits than the embedding search takes; ``None``:
    no limit, for ``--layout medial``)."""
    too_large = max_twoq is not None and _two_qubit(circuit) > max_twoq
    if device.family != "heavy-hex" or not is_calibrated(device) or too_large:
        return None
    cells = medial_compile(plan.scenario, circuit, "heavy-hex", seed=seed, measured=measured, plan=plan,
                           bindings=bindings, stage=stage, routing=routing, context=context)  # fmt: skip
    if cells is None:
        return None
    logical, routed = cells
    return f"cells on {routed.device.name}", logical, routed


def _finish(
    compiled: CompileResult, logical: Circuit, ours: list[RoutedCircuit], circuit: Circuit, lowered: bool,
    start: float, method: str, optimize_for: str | None, measured: range, say: Callable[[str], None],
    elsewhere: tuple[tuple[str, Circuit, RoutedCircuit], ...] = (),
    device: Device | None = None,
    qiskit_seeds: int = QISKIT_SEEDS,
    none_fit: str = "no routed candidate",
    zero_start: bool = False,
) -> DeviceCompileResult:  # fmt: skip
    """The result: on a named device (``device``, default ``ours[0]``'s) the best of
    :func:`qcpp.pipeline.candidates.calibrated_candidates` (from ``ours``, compile's routings of ``logical``, the
    routings ``elsewhere`` placed on the device, and, unless ``lowered``, all of these after Qiskit's O3 passes and
    ``qiskit_seeds`` Qiskit O3 routings of ``circuit``) by ``optimize_for`` (``None``: the device's
    :func:`~qcpp.pipeline.candidates.default_objective`), with the candidates simplified for the all-|0> start
    where ``zero_start``; elsewhere ``ours[0]``.

    Raises:
        ValueError: ``none_fit``, where there is no candidate (``ours`` empty and nothing ``elsewhere`` embeds)."""
    device = ours[0].device if device is None else device
    objective = default_objective(device) if optimize_for is None else optimize_for
    if not is_calibrated(device):
        routed = ours[0] if lowered else to_native(ours[0])
        return DeviceCompileResult(compiled, logical, routed, lowered, time.perf_counter() - start, method,
                                   optimize_for=objective, zero_start=zero_start)  # fmt: skip
    say(f"scoring routed candidates on {device.name} (ESP, two-qubit gates, Qiskit O3)")
    candidates = calibrated_candidates(ours, device, None if lowered else circuit, measured, qiskit_seeds,
                                       elsewhere=elsewhere, from_zero_start=zero_start)  # fmt: skip
    pool = [c for c in candidates if c.lowered is not None] if lowered else candidates
    if not pool:
        raise ValueError(none_fit)
    chosen = choose(pool, objective)
    routed = chosen.lowered if lowered else chosen.native
    assert routed is not None
    if chosen.logical is not None:  # Qiskit's routing of the compiled circuit, or the cells' of theirs
        logical = chosen.logical
    return DeviceCompileResult(compiled, logical, routed, lowered, time.perf_counter() - start, method,
                               optimize_for=objective, chosen=chosen.name,
                               candidates=tuple(c.summary() for c in candidates), zero_start=zero_start)  # fmt: skip


def greedy_route(
    circuit: Circuit,
    device: Device,
    seed: int = 0,
    layouts: tuple[str, ...] = LAYOUTS,
    measured: range | None = None,
    options: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> RoutedCircuit:
    """The ``greedy`` path's routing of the whole circuit: from :func:`best_layout`, one SABRE routing; on circuits
    of at most ``options.placement_max_twoq`` two-qubit gates, the cheapest of a placement search that starts with
    that layout (:func:`qcpp.layout.placement_search.search_route`: many layouts and seeds, SWAPs fused with an
    adjacent ``cx``; memoised in ``context``)."""
    return greedy_routes(circuit, device, seed, layouts, measured, options, context, count=1)[0]


def greedy_routes(
    circuit: Circuit,
    device: Device,
    seed: int = 0,
    layouts: tuple[str, ...] = LAYOUTS,
    measured: range | None = None,
    options: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
    count: int = 1,
) -> list[RoutedCircuit]:
    """:func:`greedy_route`'s routing first, then (where it runs the placement search) up to ``count - 1`` of the
    search's next cheapest (:func:`qcpp.layout.placement_search.ranked_routes`). On a named device the search is
    the wider one of :meth:`~qcpp.routing.options.RoutingOptions.for_calibrated`."""
    if is_calibrated(device):
        options = options.for_calibrated()
    layout = best_layout(circuit, device, seed=seed, layouts=layouts, options=options)
    if device.is_all_to_all or _two_qubit(circuit) > options.placement_max_twoq:
        return [route(circuit, device, layout, seed=seed, measured=measured, trials=options.trials)]
    if count == 1:
        return [search_route(circuit, device, starts=(layout,), seed=seed, measured=measured, options=options,
                             context=context)]  # fmt: skip
    return ranked_routes(circuit, device, starts=(layout,), seed=seed, measured=measured, count=count,
                         options=options, context=context)  # fmt: skip


def _greedy_compare(
    circuit: Circuit, device: Device, seed: int, layouts: tuple[str, ...], measured: range | None,
    options: RoutingOptions, context: RoutingContext,
) -> RoutedCircuit:  # fmt: skip
    """:func:`greedy_route` of ``circuit`` on ``device``, or, on a square grid of more than
    ``options.greedy_compare_max_qubits`` qubits (a long strip's square medial grid: a routing of the whole circuit
    costs SABRE and the placement a dense distance matrix of every device qubit), on its top-left sub-grid of about
    ``sqrt(n) x sqrt(n)`` sites for ``n`` circuit qubits, written on ``device`` (a sub-grid is an induced subgraph:
    every routed gate is on a coupling of ``device``)."""
    shape = grid_shape(device)
    if shape is None or device.num_qubits <= options.greedy_compare_max_qubits:
        return greedy_route(circuit, device, seed, layouts, measured, options, context)
    n = circuit.num_qubits
    rows = min(shape[0], math.isqrt(n - 1) + 1)
    cols = min(shape[1], -(-n // rows))
    sub, sites = _top_left(device, rows, cols)
    return embed_routed(greedy_route(circuit, sub, seed, layouts, measured, options, context), device, sites)


def auto_tries_greedy(two_qubit: int, routing: RoutingOptions = DEFAULT_ROUTING) -> bool:
    """Whether the ``auto`` layout, on a device that holds the geometric layout, also routes a circuit of
    ``two_qubit`` lowered two-qubit gates greedily and keeps the fewer routed two-qubit gates (one routing of a
    small circuit may need fewer SWAPs than its windows). Above ``routing.auto_compare_max_twoq`` ``auto`` is the
    geometric layout, so what predicts that layout's routing predicts ``auto``'s.

    Example:
        >>> auto_tries_greedy(2_000), auto_tries_greedy(2_001)
        (True, False)
    """
    return two_qubit <= routing.auto_compare_max_twoq


def _two_qubit(c: Circuit) -> int:
    return sum(1 for g in c.gates if len(g[1]) == 2)


def medial_device(scenario: Scenario, spec: str | Device, arrangement: str = "tile") -> Device | None:
    """The device the medial layout uses: ``spec`` itself if it is a square grid that holds the layout; for the
    unsized family ``grid``, the smallest square grid that holds it; otherwise ``None``."""
    if isinstance(spec, Device):
        return spec if medial_placement(scenario, spec, arrangement) is not None else None
    if spec == "grid":
        rows, cols = medial_shape(scenario, arrangement)
        side = max(rows, cols)
        return get_device(f"grid:{side}x{side}")
    if not spec.startswith("grid:") and get_device(spec).family != "grid":
        return None
    dev = get_device(spec)
    return dev if medial_placement(scenario, dev, arrangement) is not None else None


def hex_device(scenario: Scenario, spec: str | Device) -> Device | None:
    """The device the heavy-hex cell layout (:mod:`qcpp.layout.heavy_hex`) uses: ``spec`` itself if it is a
    heavy-hex lattice that holds the layout; for the unsized family ``heavy-hex``, the smallest that holds it
    (:func:`qcpp.layout.heavy_hex.hex_distance`); otherwise ``None`` (also for named heavy-hex devices, whose qubit
    numbering is another)."""
    if isinstance(spec, Device):
        dev = spec
    elif spec == "heavy-hex":
        return get_device(f"heavy-hex:{hex_distance(scenario)}")
    elif spec.startswith("heavy-hex:"):
        dev = get_device(spec)
    else:
        return None
    return dev if dev.family == "heavy-hex" and hex_placement(scenario, dev) is not None else None


def layout_device(scenario: Scenario, spec: str | Device, arrangement: str = "tile") -> Device | None:
    """The device of the geometric layout: :func:`medial_device` on square grids, :func:`hex_device` on heavy-hex
    lattices, ``None`` elsewhere."""
    if isinstance(spec, Device):
        family = spec.family
    else:
        name = spec.partition(":")[0]
        family = name if name in ("grid", "heavy-hex") else get_device(spec).family
    if family == "heavy-hex":
        return hex_device(scenario, spec)
    return medial_device(scenario, spec, arrangement)


def grown_device(dev: Device) -> Device:
    """The next bigger member of the unsized family ``grid`` or ``heavy-hex`` (a section needs more free qubits):
    one more row and column, two more in distance.

    Example:
        >>> grown_device(get_device("grid:5x5")).name, grown_device(get_device("heavy-hex:3")).name
        ('grid:6x6', 'heavy-hex:5')
    """
    if dev.family == "heavy-hex":
        return get_device(f"heavy-hex:{int(dev.name.split(':')[1]) + 2}")
    side = int(dev.name.split("x")[-1]) + 1
    return get_device(f"grid:{side}x{side}")


def medial_compile(
    scenario: Scenario,
    circuit: Circuit,
    spec: str | Device,
    seed: int = 0,
    measured: range | None = None,
    arrangement: str = "tile",
    plan: QaoaPlan | None = None,
    bindings: Mapping[str, float] | None = None,
    stage: Callable[[str], None] | None = None,
    routing: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> tuple[Circuit, RoutedCircuit] | None:
    """The geometric layout (medial on square grids, one cell per plaquette on heavy-hex lattices), local ancillas
    and home-returning windows for ``circuit`` (lowered, ``fuse=False``) on ``spec``, or ``None`` where the device
    is neither kind or does not hold it. The unsized families ``grid`` and ``heavy-hex`` grow (by one row and
    column, by two in distance) while a section needs more ancillas than the free qubits. ``arrangement``: how
    the robots' copies share a square grid (:data:`qcpp.layout.medial.ARRANGEMENTS`).
    With ``plan`` (the one ``circuit`` was compiled from, :attr:`qcpp.plan.compile.CompileResult.plan`, and its
    ``bindings``), on a heavy-hex lattice every partial mixer takes its cheapest equally short plan on its cell
    (:func:`qcpp.pipeline.cellmixer.cell_mixers`). ``stage`` is called with the name of each stage as it starts;
    ``routing`` and ``context`` are the routing's settings and the run's memos (default: a fresh context).

    Returns:
        ``(logical circuit with local ancillas, routed circuit)``.
    """
    say = stage or (lambda _text: None)
    context = RoutingContext() if context is None else context
    dev = layout_device(scenario, spec, arrangement)
    try:
        while dev is not None:
            homes = medial_placement(scenario, dev, arrangement)
            assert homes is not None
            cropped = _cropped(dev, homes, routing)
            if cropped is not None:  # a long strip's square grid: routed on the rows around the strip, written on dev
                sub, sites = cropped
                on_crop = _route_on_crop(circuit, sub, [sites.index(h) for h in homes], dev, seed, measured, say,
                                         routing, context)  # fmt: skip
                if on_crop is not None:
                    return on_crop[0], embed_routed(on_crop[1], dev, sites)
            dist = distances(dev)
            planned = circuit
            _route_large_windows_ahead(circuit, homes, dev, dist, seed, routing, context)
            if plan is not None and dev.family == "heavy-hex":
                planned = cell_mixers(plan, circuit, dev, homes, dist, bindings, stage=say,
                                      routing=routing, context=context)  # fmt: skip
            say(f"allocating ancillas on {dev.name}")
            try:
                logical, layout = allocate_ancillas(
                    planned, homes, dev, dist, routing.allocation_search, routing, context
                )
            except ValueError:
                if spec not in ("grid", "heavy-hex"):
                    raise
                context.stop_prefetch()  # its windows were placed on this device
                dev = grown_device(dev)
                continue
            return _relay_and_route(logical, layout, dev, dist, seed, measured, say, routing, context)
    finally:  # a window routed ahead and not taken (an error, a grown device) stops here
        context.stop_prefetch()
    return None


def _route_large_windows_ahead(
    circuit: Circuit, homes: tuple[int, ...], dev: Device, dist: Any, seed: int, routing: RoutingOptions,
    context: RoutingContext,
) -> None:  # fmt: skip
    """Start routing the large windows of ``circuit`` (the balance arithmetic's) in a forked process
    (:func:`qcpp.routing.prefetch.prefetch_windows`) while the cells' plan choice (heavy-hex) and the ancilla
    allocation search run: their sections keep their gates through that choice, and a section's ancillas and relays
    depend on that section alone (:func:`~qcpp.layout.medial.allocate_ancillas`,
    :func:`~qcpp.routing.bridge.bridge_far_phases`), so they are placed here as the final routing will place them
    and the windows' physical pairs are those it will route."""
    if not routing.route_ahead or not can_prefetch():
        return
    windows = routing.for_cells() if dev.family == "heavy-hex" else routing
    large = [sec for sec in circuit.sections
             if mirror_length([g[1] for g in sec.gates if len(g[1]) == 2]) >= windows.large_window_pairs]  # fmt: skip
    if not large:
        return
    try:
        logical, layout = allocate_ancillas(Circuit(circuit.registers, large), homes, dev, dist,
                                            routing.allocation_search, routing, context)  # fmt: skip
    except ValueError:  # too few free qubits: medial_compile grows the device
        return
    logical, layout = bridge_far_phases(logical, layout, dev, dist, options=routing, context=context)
    ahead = [(tuple((layout[g[1][0]], layout[g[1][1]]) for g in sec.gates if len(g[1]) == 2),
              windows.commuting_phases and commuting_middle(sec.gates) is not None)
             for sec in logical.sections]  # fmt: skip
    prefetch_windows(context, ahead, dev, dist, seed, windows)


def _cropped(dev: Device, homes: tuple[int, ...], options: RoutingOptions) -> tuple[Device, list[int]] | None:
    """The top-left sub-grid of a ``grid:RxC`` device of more than ``options.crop_min_qubits`` qubits that holds
    the homes with ``options.crop_pad`` rows and columns to spare, and its sites on ``dev`` (row-major, so indices
    keep their order), if it has at most half the device's qubits; else ``None``.

    The medial path decides from distances and routing patches near each section's qubits (nearest free sites,
    relays within two sites, SABRE on the qubits within two sites), so on the crop it allocates, relays and routes
    as on the device, in a fraction of the time: no dense distance matrix of every device qubit (its memory grows
    with the square of the device's qubits). ``tests/compiler/hardware_crop_test.py`` compares both."""
    shape = grid_shape(dev)
    if shape is None or dev.num_qubits <= options.crop_min_qubits or not dev.name.startswith("grid:"):
        return None
    rows_of, cols_of = zip(*(divmod(h, shape[1]) for h in homes), strict=True)
    pad = options.crop_pad
    rows, cols = min(shape[0], max(rows_of) + 1 + pad), min(shape[1], max(cols_of) + 1 + pad)
    if 2 * rows * cols > dev.num_qubits:
        return None
    return _top_left(dev, rows, cols)


def _top_left(dev: Device, rows: int, cols: int) -> tuple[Device, list[int]]:
    """The ``grid:{rows}x{cols}`` device and its sites on the square grid ``dev`` (its top-left corner, row-major:
    an induced subgraph, so a gate on a coupling of the sub-grid is on one of ``dev``)."""
    shape = grid_shape(dev)
    assert shape is not None
    return get_device(f"grid:{rows}x{cols}"), [r * shape[1] + c for r in range(rows) for c in range(cols)]


def _route_on_crop(
    circuit: Circuit, sub: Device, homes: list[int], dev: Device, seed: int, measured: range | None,
    say: Callable[[str], None], options: RoutingOptions, context: RoutingContext,
) -> tuple[Circuit, RoutedCircuit] | None:  # fmt: skip
    """:func:`_medial_route` on the crop ``sub`` of ``dev``, or ``None`` where the device beyond the crop could
    have changed it: a section wants more free qubits than the crop has, a routing patch (the allocation search's
    and the relays' candidates included) reaches the crop's last row or column short of the device's edge, or a
    window was routed on its whole connected component (the crop's, not the device's): the checks
    :mod:`qcpp.estimators.window_classes` makes of its crops."""
    shape, full = grid_shape(sub), grid_shape(dev)
    assert shape is not None and full is not None
    with context.watching() as watch:
        try:
            logical, routed = _medial_route(circuit, sub, tuple(homes), seed, measured, say, options, context)
        except ValueError:
            return None
    last_row = shape[0] < full[0] and any(q // shape[1] == shape[0] - 1 for q in watch.qubits)
    last_col = shape[1] < full[1] and any(q % shape[1] == shape[1] - 1 for q in watch.qubits)
    if watch.whole_component or last_row or last_col:
        return None
    return logical, routed


def _medial_route(
    circuit: Circuit, dev: Device, homes: tuple[int, ...], seed: int, measured: range | None,
    say: Callable[[str], None], options: RoutingOptions, context: RoutingContext,
) -> tuple[Circuit, RoutedCircuit]:  # fmt: skip
    """Allocation, relays and windows of the medial path on a square grid ``dev`` with data ``homes``."""
    dist = distances(dev)
    say(f"allocating ancillas on {dev.name}")
    logical, layout = allocate_ancillas(circuit, homes, dev, dist, options.allocation_search, options, context)
    return _relay_and_route(logical, layout, dev, dist, seed, measured, say, options, context)


def _relay_and_route(
    logical: Circuit, layout: tuple[int, ...], dev: Device, dist: Any, seed: int, measured: range | None,
    say: Callable[[str], None], options: RoutingOptions, context: RoutingContext,
) -> tuple[Circuit, RoutedCircuit]:  # fmt: skip
    """Relays of far phases (:func:`qcpp.routing.bridge.bridge_far_phases`) and the windows routed home (with the
    cells' large-window search on a heavy-hex lattice)."""
    say("relaying far phases")
    logical, layout = bridge_far_phases(logical, layout, dev, dist, options=options, context=context)
    say(f"routing {len(logical.sections):,} windows")
    windows = options.for_cells() if dev.family == "heavy-hex" else options
    return logical, route_windows(logical, dev, layout, seed=seed, measured=measured, dist=dist, options=windows,
                                  context=context)  # fmt: skip
