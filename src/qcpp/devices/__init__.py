"""Devices: coupling maps, native gates and calibration data (:mod:`qcpp.devices.device`; data files in ``data/``).

The package itself is callable: ``qcpp.devices()`` gives the names of the shipped devices (the public API's
``devices()``; a function of that name could not live beside this package in :mod:`qcpp`, since importing the
package sets the attribute ``qcpp.devices``).

Example:
    >>> import qcpp.devices
    >>> qcpp.devices()
    ('google_willow', 'ibm_fez', 'ibm_torino', 'quantinuum_helios')
"""

from __future__ import annotations

import sys
from types import ModuleType


class _Package(ModuleType):
    """This package's module type: calling it lists the shipped devices."""

    def __call__(self) -> tuple[str, ...]:
        """The names of the devices qcpp ships (:func:`qcpp.devices.device.device_names`); the families
        ``grid[:RxC]``, ``heavy-hex[:D]`` and ``all-to-all[:N]`` take any size besides."""
        from qcpp.devices.device import device_names

        return device_names()


sys.modules[__name__].__class__ = _Package
