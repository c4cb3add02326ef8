"""qcpp: circuit compiler and resource estimator for QAOA multi-robot coverage path planning.

The importable libraries are ``gridcover`` (problem model and classical solvers), ``circuitgen`` (QAOA
circuits), ``simulate`` and ``estimators``; this package is the command line on top of them
(:mod:`qcpp.cli`, commands in :mod:`qcpp.commands`). Run ``qcpp --help`` or ``python -m qcpp --help``.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("qcpp")
except PackageNotFoundError:  # pragma: no cover - running from a source tree that is not installed
    __version__ = "0+unknown"
