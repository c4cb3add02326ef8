"""qcpp: circuit compiler and resource estimator for QAOA multi-robot coverage path planning.

The importable libraries are ``qcpp.problem`` (problem model and classical solvers), ``qcpp`` (QAOA
circuits), ``simulate`` and ``estimators``; this package is the command line on top of them
(:mod:`qcpp.cli.app`, commands in :mod:`qcpp.cli.commands`). Run ``qcpp --help`` or ``python -m qcpp --help``.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("qcpp")
except PackageNotFoundError:  # pragma: no cover - running from a source tree that is not installed
    __version__ = "0+unknown"
