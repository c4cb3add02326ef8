"""Routed figures for ``qcpp estimate --device NAME``: exact where affordable, otherwise a labelled bound.

:func:`routed_fields` adds to an estimate row ``device`` (a family without a size is the member
``qcpp compile --device`` picks: :func:`qcpp.pipeline.device_compile.layout_device` for ``grid`` and ``heavy-hex``,
else the smallest member with the row's qubits), ``fits`` (the device's largest connected component holds the
row's qubits; for the bound also every section of the circuit compile routes), ``routed_twoq``, ``routed_depth``,
``routed_twoq_depth``, ``duration_s``, ``esp``, ``esp_model``, ``esp_idle`` (ESP with idle decoherence,
:func:`qcpp.routing.native.esp_idle`; exact rows on devices with T1 / T2 only, else ``None``), ``log10_esp`` and
``log10_esp_idle`` (the same two summed in log space, :func:`qcpp.routing.native.log_esp`: finite where the ESP
itself underflows to ``0.0``, below about ``1e-308``), and ``routed_kind`` (of the two-qubit count and the ESP)
and ``routed_depth_kind`` (of the depths and the duration), each ``exact`` (what ``qcpp compile --device``
writes) or ``bound``. Of a ``bound`` row the two-qubit count, the depths and the duration are upper bounds, and
its ESP, from those gates at the worst error rates, a lower bound. ``routed_model`` names the first way that applies:

1. ``compile``: at most :data:`EXACT_MAX_GATES` lowered gates; compiled and routed as ``qcpp compile --device``
   does, every figure exact (``compile --effort quick`` where the row's routing settings are
   :data:`qcpp.routing.options.QUICK_ROUTING`).
2. ``window sum``: a square grid that holds the medial layout, a circuit of more two-qubit gates than compile's
   ``auto`` compares (:func:`qcpp.pipeline.device_compile.auto_tries_greedy`), and windows needing the whole device
   within :data:`WINDOW_SUM_WORK`: :func:`qcpp.estimators.window_classes.routed_sum`, compile's counts and ESP
   (exact) without routing the circuit; depth and duration the sums of the windows' own (a bound).
3. ``bound``: :func:`qcpp.estimators.layout_bound.layout_twoq_bound`, every two-qubit gate of the circuit compile
   routes charged a SWAP chain to its partner and back in one placement (the geometric layout where the device
   holds it); six native one-qubit gates per two-qubit gate, gates in sequence, worst error rates. It bounds a
   routing compile could write, not SABRE's: it answers "is it hopeless", not "what will it cost".

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
from qcpp.routing.native import log10_figure
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions

__all__ = [
    "BALL_BOUND_MODEL",
    "EXACT_MAX_GATES",
    "LAYOUT_BOUND_MODEL",
    "ROUTED_COLUMNS",
    "SUM_MODEL",
    "WINDOW_SUM_WORK",
    "routed_fields",
]

EXACT_MAX_GATES = 60_000
"""Lowered circuits up to this many gates are routed exactly by ``estimate --device``."""

WINDOW_SUM_WORK = 100_000
"""The window sum answers only while its windows that need the whole device times the device's qubits stay
within this (each is one SABRE run on the whole device, as in compile; with several robots every visit gadget)."""

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

_BOUND_MODEL = (
    "bound: the circuit compile --device routes (phase layout as the device compile sets it), data qubits at {}, "
    "each section's ancillas on the free qubits nearest their partners, each two-qubit gate routed by a SWAP chain "
    "along a shortest path and back (1 + 6 (d - 1) two-qubit gates at its distance d in that placement; on "
    "heavy-hex the length of a path), 6 native one-qubit gates per two-qubit gate, gates in sequence, worst gate "
    "and readout errors: bounds that routing, not SABRE's"
)
LAYOUT_BOUND_MODEL = _BOUND_MODEL.format("their homes in the geometric layout")
"""``routed_model`` of the bound on a device that holds the geometric layout."""
BALL_BOUND_MODEL = _BOUND_MODEL.format("the qubits nearest the device's middle qubit (breadth first)")
"""``routed_model`` of the bound on any other device."""

COMPILE_MODEL = "compile: the circuit qcpp compile --device writes, routed"
COMPILE_QUICK_MODEL = "compile --effort quick: the circuit qcpp compile --device --effort quick writes, routed"
"""``routed_model`` of an exact row routed with ``--effort quick``
(:data:`qcpp.routing.options.QUICK_ROUTING`)."""
SUM_MODEL = (
    "window sum: the medial layout's windows (one gadget each, routed home) summed by classes of equal gates and "
    "neighbourhood, one representative each allocated, relayed and routed as compile does it; counts and ESP "
    "exact, depth and "
    "duration the sum of the windows' own (windows in sequence: an upper bound)"
)
_NONE = ("routed_kind", "routed_depth_kind", "routed_model", "routed_twoq", "routed_depth", "routed_twoq_depth",
         "duration_s", "esp", "esp_model", "esp_idle", "log10_esp", "log10_esp_idle")  # fmt: skip


def _largest_component(device: Device) -> int:
    from scipy.sparse.csgraph import connected_components

    if device.is_all_to_all or not device.coupling:
        return device.num_qubits if device.coupling else 1
    _, labels = connected_components(device.graph(), directed=False)
    return int(np.bincount(labels).max())



def _worst(values: Any) -> float:
    return max(values, default=0.0)


def _bound(device: Device, twoq: int, one_qubit: int, data_qubits: int, model: str) -> dict[str, Any]:
    """The bound's fields: ``twoq`` routed two-qubit gates, each with six native one-qubit gates, and three per
    lowered one-qubit gate, in sequence at the worst error rates and durations."""
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
        "log10_esp": log10_figure(log_esp),
        "log10_esp_idle": None,
    }


def routed_fields(
    scenario: Scenario,
    p: int,
    plan: Any,
    device: str | Device,
    qubits: int,
    cx: int,
    one_qubit: int,
    total_gates: int | None = None,
    stage: Callable[[str], None] | None = None,
    context: RoutingContext | None = None,
    routing: RoutingOptions = DEFAULT_ROUTING,
) -> dict[str, Any]:
    """The routed figures of one estimate row (see the module docs).

    Args:
        scenario: The row's scenario.
        p: QAOA layers.
        plan: The row's :class:`qcpp.estimators.estimate.PlanOptions`.
        device: A device name or :class:`Device` (:func:`qcpp.hardware.device.get_device`).
        qubits, cx, one_qubit: The row's lowered counts (``cx + one_qubit`` picks the way unless ``total_gates``
            is given; the bound recounts the circuit compile routes, whose phase layout may differ from the row's).
        total_gates: The row's lowered gate count (default ``cx + one_qubit``), for the exact/bound choice.
        stage: Called with each stage of the routing as it starts (``3x3 r1 p1 on grid:5x5: routing 6 windows``),
            and with ``""`` when the row is done: progress inside a row that takes long.
        context: The routing memos of the run (:class:`qcpp.routing.context.RoutingContext`; default: a fresh one),
            shared by the rows of one estimate.
        routing: The routing settings of an exact row's compile (:func:`qcpp.routing.options.effort_routing`;
            ``routed_model`` names the quick effort). The window sum and the bound route as they always do: the
            effort drops a choice made on circuits small enough to be compiled whole only.

    Returns:
        The fields to add to the row.
    """
    context = RoutingContext() if context is None else context
    try:
        return _routed_fields(scenario, p, plan, device, qubits, cx, one_qubit, total_gates, stage, context,
                              routing)  # fmt: skip
    finally:
        if stage is not None:
            stage("")


def _routed_fields(
    scenario: Scenario, p: int, plan: Any, device: str | Device, qubits: int, cx: int, one_qubit: int,
    total_gates: int | None, stage: Callable[[str], None] | None, context: RoutingContext, routing: RoutingOptions,
) -> dict[str, Any]:  # fmt: skip
    from qcpp.estimators.layout_bound import bound_plan
    from qcpp.pipeline.device_compile import ESP_MODEL, compile_for_device, layout_device
    from qcpp.routing.native import duration_s, esp_figures

    # the unsized grid and heavy-hex are sized for the geometric layout, as compile sizes them
    medial = layout_device(scenario, device) if device in ("grid", "heavy-hex") else None
    dev = medial if medial is not None else get_device(device, min_qubits=qubits)
    fits = _largest_component(dev) >= qubits
    g = scenario.grid
    label = f"{g.rows}x{g.cols} r{scenario.num_robots} p{p} on {dev.name}"
    say = (lambda text: stage(f"{label}: {text}")) if stage is not None else None
    out: dict[str, Any] = {"device": dev.name, "fits": fits}
    if not fits:
        return {**out, **dict.fromkeys(_NONE)}
    if (total_gates if total_gates is not None else cx + one_qubit) > EXACT_MAX_GATES:
        summed = _window_sum(scenario, p, plan, device, say, context)
        if summed is not None:
            return {**out, "device": summed.device.name, **_summed_fields(summed, ESP_MODEL)}
        laid = bound_plan(scenario, p, plan, dev)
        return {**out, **_bound_of_compiled(laid, dev, device in ("grid", "heavy-hex"), say, context)}
    # the unsized grid goes by name: compile may grow it while a section needs more free qubits
    result = compile_for_device(scenario, p, device if medial is not None else dev, plan, stage=say, context=context,
                                routing=routing)  # fmt: skip
    routed = result.routed
    gc = count_gates(routed.circuit.gates, routed.circuit.num_qubits)
    figures = esp_figures(routed)
    return {
        **out,
        "device": routed.device.name,
        "routed_kind": "exact",
        "routed_depth_kind": "exact",
        "routed_model": COMPILE_QUICK_MODEL if result.effort == "quick" else COMPILE_MODEL,
        "routed_twoq": gc.two_qubit,
        "routed_depth": gc.depth,
        "routed_twoq_depth": gc.two_qubit_depth,
        "duration_s": duration_s(routed),
        "esp": figures["esp"],
        "esp_model": ESP_MODEL,
        "esp_idle": figures["esp_idle"],
        "log10_esp": figures["log10_esp"],
        "log10_esp_idle": figures["log10_esp_idle"],
    }


def _window_sum(
    scenario: Scenario, p: int, plan: Any, device: str | Device, stage: Callable[[str], None] | None,
    context: RoutingContext,
) -> Any:
    """The window sum where it predicts compile (the ``auto`` layout is the medial one) within
    :data:`WINDOW_SUM_WORK` and the ESP is a sum over classes (uniform error rates), else ``None``."""
    from qcpp.estimators.window_classes import WHOLE_DEVICE_MAX_QUBITS, routed_sum
    from qcpp.pipeline.device_compile import auto_tries_greedy, medial_device

    dev = medial_device(scenario, device)
    if dev is None or dev.num_qubits > WHOLE_DEVICE_MAX_QUBITS:
        return None  # its whole-device windows could not be routed: not worth summing the others
    summed = routed_sum(scenario, p, plan, device, whole_device_work=WINDOW_SUM_WORK, stage=stage, context=context)
    if summed is None or summed.log_esp is None or auto_tries_greedy(summed.compiled_ops.get("cx", 0)):
        return None
    return summed


def _summed_fields(summed: Any, esp_model: str) -> dict[str, Any]:
    """Row fields of a :class:`qcpp.estimators.window_classes.RoutedSum`."""
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
        "log10_esp": log10_figure(summed.log_esp),
        "log10_esp_idle": None,
    }


def _bound_of_compiled(
    plan: Any, device: Device, grows: bool = False, stage: Callable[[str], None] | None = None,
    context: RoutingContext | None = None,
) -> dict[str, Any]:  # fmt: skip
    """:func:`_bound` of the circuit compile routes on ``device`` (``plan``:
    :func:`qcpp.estimators.layout_bound.bound_plan`), every two-qubit gate at its distance in
    :func:`qcpp.estimators.layout_bound.layout_twoq_bound`'s placement (on an all-to-all device, one). ``grows``:
    ``device`` is the member of an unsized family, grown as compile grows it while a section lacks free qubits;
    otherwise such a row does not fit (compile would not route it)."""
    from qcpp.estimators.layout_bound import layout_twoq_bound
    from qcpp.layout.medial import medial_placement
    from qcpp.pipeline.device_compile import grown_device

    context = RoutingContext() if context is None else context
    cost = plan.cost()
    twoq = cost.two_qubit if device.is_all_to_all else layout_twoq_bound(plan, device, context, stage)
    while twoq is None and grows:
        device = grown_device(device)
        twoq = layout_twoq_bound(plan, device, context, stage)
    if twoq is None:
        return {"fits": False, **dict.fromkeys(_NONE)}
    scenario = plan.scenario
    geometric = not device.is_all_to_all and medial_placement(scenario, device) is not None
    model = LAYOUT_BOUND_MODEL if geometric else BALL_BOUND_MODEL
    return {"device": device.name,
            **_bound(device, twoq, cost.single_qubit, scenario.num_variables, model)}  # fmt: skip
