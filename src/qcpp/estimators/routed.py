"""Routed figures for ``qcpp estimate --device NAME``: exact where affordable, otherwise a labelled bound.

:func:`routed_fields` adds to an estimate row:

* ``device`` (its name; a family without a size is the member ``qcpp compile --device`` picks: for ``grid`` the
  smallest square grid that holds the medial layout, :func:`qcpp.pipeline.device_compile.medial_device`, for
  ``heavy-hex`` the smallest lattice that holds the cell layout, :func:`qcpp.pipeline.device_compile.hex_device` (or,
  where compile finds the greedy routing cheaper on a small circuit, the smallest with the row's qubits), otherwise
  the smallest member with the row's qubits), ``fits``
  (the device's largest connected component has the row's qubits);
* ``routed_twoq``, ``routed_depth``, ``routed_twoq_depth``, ``duration_s``, ``esp`` and ``esp_model``, and
  ``esp_idle`` (ESP with idle decoherence, :func:`qcpp.routing.native.esp_idle`; exact rows on devices with T1 /
  T2 only, else ``None``);
* ``routed_kind`` (the two-qubit count and the ESP) and ``routed_depth_kind`` (the depths and the duration), each
  ``exact`` (equal to what ``qcpp compile --device`` writes) or ``bound``; ``routed_model`` says how they were
  obtained. Three ways, the first that applies:

  1. ``compile``: the lowered circuit has at most :data:`EXACT_MAX_GATES` gates. It is compiled and routed
     exactly as ``qcpp compile --device`` does; every figure is exact.
  2. ``window sum``: a square-grid device that holds the medial layout (the layout compile takes on grids
     above :attr:`qcpp.routing.options.RoutingOptions.auto_compare_max_twoq` two-qubit gates) with at most
     :data:`qcpp.estimators.window_classes.WHOLE_DEVICE_MAX_QUBITS` qubits, and windows needing the whole device
     within :data:`WINDOW_SUM_WORK` (with several robots every visit gadget does: then the sum is no faster than
     compile, and only small devices get it). The routed circuit's windows are summed
     by classes (:func:`qcpp.estimators.window_classes.routed_sum`): the two-qubit count, the one-qubit count and the
     ESP are exact (``routed_kind`` ``exact``); depth, two-qubit depth and duration are the sums of the
     windows' own, an upper bound (``routed_depth_kind`` ``bound``).
  3. ``bound`` (no routing is run): the circuit compile would route (its phase separator laid out as the
     device compile lays it out, :func:`qcpp.pipeline.device_plan.device_plan_options`;
     unfused, every gadget a section),
     every two-qubit gate routed by a SWAP chain to its partner and back along a shortest path, at most
     ``1 + 6 (d - 1)`` two-qubit gates for qubits ``d`` apart. Where the device holds the geometric layout,
     ``d`` is each gate's own distance in one placement of the circuit's qubits (data at their homes, each
     section's ancillas on the nearest free qubits: :mod:`qcpp.estimators.layout_bound`, ``routed_model``
     :data:`LAYOUT_BOUND_MODEL`; the first layer's circuit is built, lowered and placed, seconds at 30x30 with
     8 robots); elsewhere ``d`` is at most :data:`MIXER_SPAN` for a partial
     mixer's gates where the device holds the geometric layout, else at most the diameter bound
     :func:`diameter_bound`; each native two-qubit gate costs
     six native one-qubit gates, and the gates run one after another. ``routed_twoq``, ``routed_depth``,
     ``routed_twoq_depth`` and ``duration_s`` bound *that* routing from above and ``esp`` (worst gate and
     readout errors) from below. It is a routing compile could write, not the one it writes (SABRE's): an
     upper bound of the best routing, loose; it answers "is it hopeless", not "what will it cost".

Rows that do not fit get ``None`` for every routed figure.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.estimators.estimate import DEFAULT_PLAN
    >>> f = routed_fields(default_scenario(3, 3, 1), 1, DEFAULT_PLAN, "grid", qubits=15, cx=106, one_qubit=180)
    >>> f["device"], f["fits"], f["routed_kind"], f["routed_depth_kind"], f["routed_twoq"] > 106
    ('grid:5x5', True, 'exact', 'exact', True)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from qcpp.estimators.counts import count_gates
from qcpp.hardware.device import Device, get_device
from qcpp.problem.scenario import Scenario
from qcpp.routing.context import RoutingContext

__all__ = [
    "BOUND_MODEL",
    "EXACT_MAX_GATES",
    "LAYOUT_BOUND_MODEL",
    "MIXER_SPAN",
    "ROUTED_COLUMNS",
    "SUM_MODEL",
    "WINDOW_SUM_WORK",
    "diameter_bound",
    "routed_fields",
]

EXACT_MAX_GATES = 60_000
"""Lowered circuits up to this many gates are routed exactly by ``estimate --device``."""

WINDOW_SUM_WORK = 100_000
"""The window sum answers only when its windows that need the whole device (with several robots: every node's
visit gadget) times the device's qubits stay within this (each is one SABRE run on the whole device, as in
compile); above it the row gets the bound. 8x8 with 3 robots on its 900-qubit grid is about 60,000."""

ROUTED_COLUMNS: tuple[str, ...] = (
    "device",
    "fits",
    "routed_kind",
    "routed_twoq",
    "routed_twoq_depth",
    "duration_s",
    "esp",
    "esp_idle",
)
"""Columns the ``table`` format adds with ``--device``."""

BOUND_MODEL = (
    "bound: the circuit compile --device routes (phase layout as the device compile sets it), each two-qubit "
    "gate routed by a SWAP chain along a shortest path and back (<= 1 + 6 (d - 1) two-qubit gates: d = the span "
    "of a partial mixer's qubits in the geometric layout for the mixer's gates, else a bound on the device's "
    "diameter), 6 native one-qubit gates per two-qubit gate, gates in sequence, worst gate and readout errors: "
    "bounds that routing, not SABRE's"
)

LAYOUT_BOUND_MODEL = (
    "bound: the circuit compile --device routes (phase layout as the device compile sets it), data qubits at their "
    "homes in the geometric layout, each section's ancillas on the free qubits nearest their partners, each "
    "two-qubit gate routed by a SWAP chain along a shortest path and back (1 + 6 (d - 1) two-qubit gates at its "
    "distance d in that placement; on heavy-hex the length of a path), 6 native one-qubit gates per two-qubit "
    "gate, gates in sequence, worst gate and readout errors: bounds that routing, not SABRE's"
)

MIXER_SPAN = {"grid": 8, "heavy-hex": 12}
"""Per device family, the largest distance between two qubits of one partial mixer's window (data homes and
allocated ancillas) that the bound assumes in the geometric layout (medial grid, heavy-hex cells): the mixer's
gates are charged ``1 + 6 (span - 1)`` each instead of the device diameter's (the tests check the span and that
the mixer's share of the bound is at least its routed gates)."""

COMPILE_MODEL = "compile: the circuit qcpp compile --device writes, routed"
SUM_MODEL = (
    "window sum: the medial layout's windows (one gadget each, routed home) summed by classes of equal gates and "
    "neighbourhood, one representative each allocated, relayed and routed as compile does it; counts and ESP "
    "exact, depth and "
    "duration the sum of the windows' own (windows in sequence: an upper bound)"
)


def diameter_bound(device: Device) -> int:
    """An upper bound on the coupling graph's diameter (1 if all-to-all): twice the eccentricity of a central
    qubit (``d(x, y) <= d(x, m) + d(m, y)``), the better of the middle qubit by number (a square grid's centre) and
    the middle of a shortest path between a qubit farthest from qubit 0 and one farthest from it. On a grid that is
    about the diameter itself, where qubit 0, a corner, would give twice it. On a device in pieces (a calibration
    snapshot with dead couplers) the largest of the pieces' bounds, each from a qubit of its own.

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> diameter_bound(get_device("grid:3x3"))  # the 3x3 grid's diameter is 4
        4
    """
    if device.is_all_to_all:
        return 1
    from scipy.sparse.csgraph import connected_components

    graph = device.graph()
    pieces, labels = connected_components(graph, directed=False)
    bound = 0
    for piece in range(pieces):
        members = np.flatnonzero(labels == piece)
        far, _ = _farthest(graph, int(members[0]))
        _, longest = _farthest(graph, far)
        centres = [longest[len(longest) // 2]] + ([device.num_qubits // 2] if pieces == 1 else [])
        bound = max(bound, 2 * min(len(_farthest(graph, int(m))[1]) - 1 for m in centres))
    return bound


def _farthest(graph: Any, source: int) -> tuple[int, list[int]]:
    """A qubit farthest from ``source`` (breadth first) and a shortest path from ``source`` to it."""
    from scipy.sparse.csgraph import breadth_first_order

    order, pred = breadth_first_order(graph, source, directed=False, return_predecessors=True)
    last = int(order[-1])  # breadth-first order ends on a farthest qubit
    path = [last]
    while path[-1] != source:
        path.append(int(pred[path[-1]]))
    return last, path


def _largest_component(device: Device) -> int:
    from scipy.sparse.csgraph import connected_components

    if device.is_all_to_all or not device.coupling:
        return device.num_qubits if device.coupling else 1
    _, labels = connected_components(device.graph(), directed=False)
    return int(np.bincount(labels).max())


def _worst(values: Any) -> float:
    return max(values, default=0.0)


def _bound(
    device: Device, cx: int, one_qubit: int, data_qubits: int, local_cx: int = 0, span: int | None = None,
    routed_twoq: int | None = None, model: str = BOUND_MODEL,
) -> dict[str, Any]:  # fmt: skip
    """The bound's fields: ``cx`` two-qubit gates, of which ``local_cx`` between qubits at most ``span`` apart,
    routed to at most ``routed_twoq`` two-qubit gates if given (else the diameter and span bound)."""
    if routed_twoq is not None:
        twoq = routed_twoq
    else:
        diameter = diameter_bound(device)
        near = min(span, diameter) if span is not None else diameter
        twoq = local_cx * (1 + 6 * (near - 1)) + (cx - local_cx) * (1 + 6 * (diameter - 1))
    ones = 3 * one_qubit + 6 * twoq
    e2 = _worst(device.error_2q)
    e1 = _worst(e for _, per_q in device.error_1q for e in per_q)
    ro = _worst(device.readout_error)
    log_esp = twoq * math.log1p(-e2) + ones * math.log1p(-e1) + data_qubits * math.log1p(-ro)
    duration = None
    if device.duration_2q_s is not None and device.duration_1q_s is not None and device.readout_duration_s:
        d1 = _worst(d for _, per_q in device.duration_1q_s for d in per_q)
        duration = twoq * _worst(device.duration_2q_s) + ones * d1 + _worst(device.readout_duration_s)
    return {
        "routed_kind": "bound",
        "routed_depth_kind": "bound",
        "routed_model": model,
        "routed_twoq": twoq,
        "routed_depth": twoq + ones,
        "routed_twoq_depth": twoq,
        "duration_s": duration,
        "esp": math.exp(log_esp),
        "esp_model": model,
        "esp_idle": None,
    }


def routed_fields(
    scenario: Scenario,
    p: int,
    plan: Any,
    device: str,
    qubits: int,
    cx: int,
    one_qubit: int,
    total_gates: int | None = None,
    stage: Callable[[str], None] | None = None,
    context: RoutingContext | None = None,
) -> dict[str, Any]:
    """The routed figures of one estimate row (see the module docs).

    Args:
        scenario: The row's scenario.
        p: QAOA layers.
        plan: The row's :class:`qcpp.estimators.estimate.PlanOptions`.
        device: A device name (:func:`qcpp.hardware.device.get_device`).
        qubits, cx, one_qubit: The row's lowered counts (``cx + one_qubit`` picks the way unless ``total_gates``
            is given; the bound recounts the circuit compile routes, whose phase layout may differ from the row's).
        total_gates: The row's lowered gate count (default ``cx + one_qubit``), for the exact/bound choice.
        stage: Called with each stage of the routing as it starts (``3x3 r1 p1 on grid:5x5: routing 6 windows``),
            and with ``""`` when the row is done: progress inside a row that takes long.
        context: The routing memos of the run (:class:`qcpp.routing.context.RoutingContext`; default: a fresh one),
            shared by the rows of one estimate.

    Returns:
        The fields to add to the row.
    """
    context = RoutingContext() if context is None else context
    try:
        return _routed_fields(scenario, p, plan, device, qubits, cx, one_qubit, total_gates, stage, context)
    finally:
        if stage is not None:
            stage("")


def _routed_fields(
    scenario: Scenario, p: int, plan: Any, device: str, qubits: int, cx: int, one_qubit: int,
    total_gates: int | None, stage: Callable[[str], None] | None, context: RoutingContext,
) -> dict[str, Any]:  # fmt: skip
    from qcpp.pipeline.device_compile import ESP_MODEL, compile_for_device, layout_device
    from qcpp.routing.native import duration_s, esp, esp_idle

    # the unsized grid and heavy-hex are sized for the geometric layout, as compile sizes them
    medial = layout_device(scenario, device) if device in ("grid", "heavy-hex") else None
    dev = medial if medial is not None else get_device(device, min_qubits=qubits)
    fits = _largest_component(dev) >= qubits
    g = scenario.grid
    label = f"{g.rows}x{g.cols} r{scenario.num_robots} p{p} on {dev.name}"
    say = (lambda text: stage(f"{label}: {text}")) if stage is not None else None
    out: dict[str, Any] = {"device": dev.name, "fits": fits}
    if not fits:
        none = ("routed_kind", "routed_depth_kind", "routed_model", "routed_twoq", "routed_depth", "routed_twoq_depth",
                "duration_s", "esp", "esp_model", "esp_idle")  # fmt: skip
        return {**out, **dict.fromkeys(none)}
    if (total_gates if total_gates is not None else cx + one_qubit) > EXACT_MAX_GATES:
        summed = _window_sum(scenario, p, plan, device, say, context)
        if summed is not None:
            out["device"] = summed.device.name
            return {**out, **_summed_fields(summed, ESP_MODEL)}
        return {**out, **_bound_of_compiled(scenario, p, plan, dev, say)}
    # the unsized grid goes by name: compile may grow it while a section needs more free qubits
    result = compile_for_device(scenario, p, device if medial is not None else dev, plan, stage=say, context=context)
    routed = result.routed
    out["device"] = routed.device.name
    gc = count_gates(routed.circuit.gates, routed.circuit.num_qubits)
    return {
        **out,
        "routed_kind": "exact",
        "routed_depth_kind": "exact",
        "routed_model": COMPILE_MODEL,
        "routed_twoq": gc.two_qubit,
        "routed_depth": gc.depth,
        "routed_twoq_depth": gc.two_qubit_depth,
        "duration_s": duration_s(routed),
        "esp": esp(routed),
        "esp_model": ESP_MODEL,
        "esp_idle": esp_idle(routed),
    }


def _window_sum(
    scenario: Scenario, p: int, plan: Any, device: str, stage: Callable[[str], None] | None, context: RoutingContext
) -> Any:
    """The window sum where it is exact and affordable (a square grid holding the medial layout, at most
    :data:`~qcpp.estimators.window_classes.WHOLE_DEVICE_MAX_QUBITS` qubits, uniform error rates), else ``None``."""
    from qcpp.estimators.window_classes import WHOLE_DEVICE_MAX_QUBITS, routed_sum
    from qcpp.pipeline.device_compile import medial_device
    from qcpp.routing.options import DEFAULT_ROUTING

    dev = medial_device(scenario, device)
    if dev is None or dev.num_qubits > WHOLE_DEVICE_MAX_QUBITS:
        return None
    summed = routed_sum(scenario, p, plan, device, whole_device_work=WINDOW_SUM_WORK, stage=stage, context=context)
    if summed is None or not summed.exact or summed.log_esp is None:
        return None  # bounded windows, or per-qubit error rates: the ESP is not a sum over classes
    if summed.compiled_ops.get("cx", 0) <= DEFAULT_ROUTING.auto_compare_max_twoq:
        return None  # compile would also try the greedy layout on so few two-qubit gates
    return summed


def _summed_fields(summed: Any, esp_model: str) -> dict[str, Any]:
    """Row fields of a :class:`qcpp.estimators.window_classes.RoutedSum` with no bounded window."""
    return {
        "routed_kind": "exact",
        "routed_depth_kind": "bound",
        "routed_model": SUM_MODEL,
        "routed_twoq": summed.two_qubit,
        "routed_depth": summed.depth_bound,
        "routed_twoq_depth": summed.two_qubit_depth_bound,
        "duration_s": summed.duration_bound_s,
        "esp": summed.esp,
        "esp_model": esp_model,
        "esp_idle": None,
    }


def _bound_of_compiled(
    scenario: Scenario, p: int, plan: Any, device: Device, stage: Callable[[str], None] | None = None
) -> dict[str, Any]:
    """:func:`_bound` of the lowered counts of the circuit compile routes on ``device`` (unfused, its phase
    layout): where ``device`` holds the geometric layout, every two-qubit gate at its own distance in it
    (:func:`qcpp.estimators.layout_bound.layout_twoq_bound`); else the partial mixers' gates at :data:`MIXER_SPAN`
    where ``device`` holds the geometric layout (a section wants more free qubits than it has), the rest at
    :func:`diameter_bound`. ``stage``: called with each stage's name as it starts."""
    import dataclasses

    from qcpp.estimators.layout_bound import layout_twoq_bound
    from qcpp.pipeline.device_compile import layout_device
    from qcpp.pipeline.device_plan import device_plan_options
    from qcpp.plan.qaoa import qaoa_plan

    # compile --device routes the unfused circuit (every gadget a section) with the device's phase layout
    laid = qaoa_plan(scenario, p, dataclasses.replace(device_plan_options(plan, device), fuse=False))
    cost = laid.cost()
    placed = layout_twoq_bound(scenario, p, plan, device, stage=stage)
    if placed is not None:
        return _bound(device, cost.two_qubit, cost.single_qubit, scenario.num_variables, routed_twoq=placed,
                      model=LAYOUT_BOUND_MODEL)  # fmt: skip
    span = MIXER_SPAN.get(device.family) if layout_device(scenario, device) is not None else None
    mixer = p * laid.cost_by_part()["mixer"].two_qubit if span is not None else 0
    return _bound(device, cost.two_qubit, cost.single_qubit, scenario.num_variables, mixer, span)
