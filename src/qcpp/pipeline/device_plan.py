"""The plan options a device settles: what a compile routed onto a device builds, decided in one place.

The plan (:mod:`qcpp.plan`) knows nothing of devices: :attr:`PlanOptions.phase_layout
<qcpp.plan.options.PlanOptions.phase_layout>` ``"auto"`` means "let the device decide", and the plan itself
builds ``auto`` as ``pooled``. :func:`device_plan_options` is the one function that settles ``auto`` for a device;
:func:`qcpp.pipeline.device_compile.compile_for_device` compiles with its answer, and every estimator that predicts
what that compile routes (the window-class sum, the layout bound, the routed bound) asks it too, so all of them
count the same circuit.

Example:
    >>> from qcpp.plan.options import PlanOptions
    >>> [device_plan_options(PlanOptions(), d).phase_layout for d in ("grid", "heavy-hex:5", "all-to-all", "ibm_fez")]
    ['medial', 'medial', 'pooled', 'spatial']
"""

from __future__ import annotations

from dataclasses import replace

from qcpp.hardware.device import Device, get_device
from qcpp.layout.heavy_hex import CELL_PHASE_LAYOUT, is_hex_lattice
from qcpp.plan.options import PlanOptions

__all__ = ["device_plan_options"]


def device_plan_options(options: PlanOptions, device: str | Device, layout_method: str = "medial") -> PlanOptions:
    """``options`` with ``phase_layout="auto"`` settled for a compile routed onto ``device``; an explicit choice
    stays.

    * a heavy-hex lattice with a geometric layout (``layout_method`` not ``greedy``): the cells' balance sinks
      (:data:`qcpp.layout.heavy_hex.CELL_PHASE_LAYOUT`);
    * a square-grid device: ``medial`` (:mod:`qcpp.layout.medial` tiles the robots' patches, so the balance sums
      have somewhere to drift to);
    * any other device that does not couple every pair of its qubits: ``spatial`` (the balance sinks assume the
      medial tiling, which a greedy layout does not keep);
    * an all-to-all device: ``pooled`` (the fewest CX).

    Args:
        options: The requested plan options.
        device: The device (a spec for :func:`qcpp.hardware.device.get_device`, or a :class:`Device`; a family
            without a size is known by its smallest member, every member being of the same kind).
        layout_method: How compile lays the circuit out (:data:`qcpp.plan.options.LAYOUT_METHODS`): ``greedy``
            places no cells, so a heavy-hex lattice gets ``spatial``.

    Returns:
        The settled options.

    Example:
        >>> from qcpp.plan.options import PlanOptions
        >>> device_plan_options(PlanOptions(), "heavy-hex:5", layout_method="greedy").phase_layout
        'spatial'
        >>> device_plan_options(PlanOptions(phase_layout="pooled"), "grid").phase_layout
        'pooled'
    """
    if options.phase_layout != "auto":
        return options
    if layout_method != "greedy" and is_hex_lattice(device):
        return replace(options, phase_layout=CELL_PHASE_LAYOUT)
    dev = device if isinstance(device, Device) else get_device(device, min_qubits=4)
    layout = "pooled" if dev.is_all_to_all else "medial" if dev.family == "grid" else "spatial"
    return replace(options, phase_layout=layout)
