"""Routed figures for ``qcpp estimate --device NAME``: exact where routing is affordable, otherwise a labelled bound.

:func:`routed_fields` adds to an estimate row:

* ``device`` (its name; a family without a size is the member ``qcpp compile --device`` picks: for ``grid`` the
  smallest square grid that holds the medial layout, :func:`circuitgen.hardware.medial_device`, otherwise the
  smallest member with the row's qubits), ``fits``
  (the device's largest connected component has the row's qubits);
* ``routed_twoq``, ``routed_depth``, ``routed_twoq_depth``, ``duration_s``, ``esp`` and ``esp_model``;
* ``routed_kind``: ``exact`` (the circuit is compiled and routed exactly as ``qcpp compile --device`` does, and
  the numbers are those of the circuit it writes; when the lowered circuit has at most :data:`EXACT_MAX_GATES`
  gates) or ``bound`` (larger circuits; no circuit is built): every two-qubit gate of the lowered count is
  charged a SWAP chain to its partner and back along a shortest path, at most ``1 + 6 (D - 1)`` two-qubit
  gates for a device of diameter at most ``D``, each native two-qubit gate costs six native one-qubit gates,
  and the gates run one after another. So ``routed_twoq``, ``routed_depth``, ``routed_twoq_depth`` and
  ``duration_s`` are upper bounds and ``esp`` (worst gate and readout errors of the device) a lower bound of
  what that routing gives. They are loose; they answer "is it hopeless", not "what will it cost".

Rows that do not fit get ``None`` for every routed figure.

Example:
    >>> from gridcover.presets import default_scenario
    >>> from estimators.estimate import DEFAULT_PLAN
    >>> f = routed_fields(default_scenario(3, 3, 1), 1, DEFAULT_PLAN, "grid", qubits=15, cx=106, one_qubit=180)
    >>> f["device"], f["fits"], f["routed_kind"], f["routed_twoq"] > 106
    ('grid:5x5', True, 'exact', True)
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from circuitgen.devices import Device, get_device
from gridcover.scenario import Scenario

from .counts import count_gates

__all__ = ["EXACT_MAX_GATES", "ROUTED_COLUMNS", "diameter_bound", "routed_fields"]

EXACT_MAX_GATES = 60_000
"""Lowered circuits up to this many gates are routed exactly by ``estimate --device``."""

ROUTED_COLUMNS: tuple[str, ...] = (
    "device",
    "fits",
    "routed_kind",
    "routed_twoq",
    "routed_twoq_depth",
    "duration_s",
    "esp",
)
"""Columns the ``table`` format adds with ``--device``."""

BOUND_MODEL = (
    "bound: each two-qubit gate routed by a SWAP chain along a shortest path and back (<= 1 + 6 (D - 1) "
    "two-qubit gates, D = a bound on the device's diameter), 6 native one-qubit gates per two-qubit gate, "
    "gates in sequence, worst gate and readout errors"
)


def diameter_bound(device: Device) -> int:
    """An upper bound on the coupling graph's diameter: twice the eccentricity of qubit 0 (1 if all-to-all)."""
    if device.is_all_to_all:
        return 1
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import breadth_first_order

    n = device.num_qubits
    a, b = np.array(device.coupling).T
    graph = csr_matrix((np.ones(len(a)), (a, b)), shape=(n, n))
    order, pred = breadth_first_order(graph, 0, directed=False, return_predecessors=True)
    depth = np.zeros(n, dtype=int)
    for v in order[1:]:
        depth[v] = depth[pred[v]] + 1
    return 2 * int(depth.max())


def _largest_component(device: Device) -> int:
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components

    n = device.num_qubits
    if device.is_all_to_all or not device.coupling:
        return n if device.coupling else 1
    a, b = np.array(device.coupling).T
    _, labels = connected_components(csr_matrix((np.ones(len(a)), (a, b)), shape=(n, n)), directed=False)
    return int(np.bincount(labels).max())


def _worst(values: Any) -> float:
    return max(values, default=0.0)


def _bound(device: Device, cx: int, one_qubit: int, data_qubits: int) -> dict[str, Any]:
    per = 1 + 6 * (diameter_bound(device) - 1)
    twoq = cx * per
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
        "routed_twoq": twoq,
        "routed_depth": twoq + ones,
        "routed_twoq_depth": twoq,
        "duration_s": duration,
        "esp": math.exp(log_esp),
        "esp_model": BOUND_MODEL,
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
) -> dict[str, Any]:
    """The routed figures of one estimate row (see the module docs).

    Args:
        scenario: The row's scenario.
        p: QAOA layers.
        plan: The row's :class:`estimators.estimate.PlanOptions`.
        device: A device name (:func:`circuitgen.devices.get_device`).
        qubits, cx, one_qubit: The row's lowered counts.
        total_gates: The row's lowered gate count (default ``cx + one_qubit``), for the exact/bound choice.

    Returns:
        The fields to add to the row.
    """
    from circuitgen.hardware import ESP_MODEL, compile_for_device, medial_device
    from circuitgen.routing import duration_s, esp

    medial = medial_device(scenario, device) if device == "grid" else None
    dev = medial if medial is not None else get_device(device, min_qubits=qubits)
    fits = _largest_component(dev) >= qubits
    out: dict[str, Any] = {"device": dev.name, "fits": fits}
    if not fits:
        none = ("routed_kind", "routed_twoq", "routed_depth", "routed_twoq_depth", "duration_s", "esp", "esp_model")
        return {**out, **dict.fromkeys(none)}
    if (total_gates if total_gates is not None else cx + one_qubit) > EXACT_MAX_GATES:
        return {**out, **_bound(dev, cx, one_qubit, scenario.num_variables)}
    # the unsized grid goes by name: compile may grow it while a section needs more free qubits
    result = compile_for_device(scenario, p, device if medial is not None else dev, plan)
    routed = result.routed
    out["device"] = routed.device.name
    gc = count_gates(routed.circuit.gates, routed.circuit.num_qubits)
    return {
        **out,
        "routed_kind": "exact",
        "routed_twoq": gc.two_qubit,
        "routed_depth": gc.depth,
        "routed_twoq_depth": gc.two_qubit_depth,
        "duration_s": duration_s(routed),
        "esp": esp(routed),
        "esp_model": ESP_MODEL,
    }
