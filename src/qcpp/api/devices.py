"""Devices in the public API: their names, and one device by name.

Example:
    >>> "ibm_fez" in devices()
    True
    >>> device("grid:3x3").num_qubits
    9
"""

from __future__ import annotations

from qcpp.hardware.device import Device, DeviceError, device_names, get_device

__all__ = ["Device", "DeviceError", "device", "devices"]


def devices() -> tuple[str, ...]:
    """The names of the devices qcpp ships (calibration data files); besides these, the families ``grid[:RxC]``,
    ``heavy-hex[:D]`` and ``all-to-all[:N]`` take any size."""
    return device_names()


def device(name: str) -> Device:
    """The device ``name``: a shipped device, a family member such as ``grid:5x5``, or a device file's path (ends
    in ``.json`` or contains ``/``; the format: the hardware guide's "Device files").

    Raises:
        DeviceError: an unknown name or a malformed device file, with the message ``qcpp compile --device``
            prints (a file's names the file and the field).
    """
    if not isinstance(name, str):
        raise DeviceError(f"expected a device name or a device file's path, got {type(name).__name__}")
    return get_device(name)
