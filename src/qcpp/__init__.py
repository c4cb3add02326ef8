"""qcpp: a gate-level circuit compiler and resource estimator for QAOA multi-robot coverage path planning.

The public Python API is the names of this module (:data:`__all__`); the command line ``qcpp`` (``python -m qcpp``)
is built on the same code, so both give the same numbers and the same one-line errors.

Example:
    >>> import qcpp
    >>> s = qcpp.grid_scenario(3, 3, robots=1, obstacles=[(1, 1)])
    >>> est = qcpp.estimate(s, p=1)
    >>> est.qubits, est.cx
    (15, 106)
    >>> c = qcpp.compile(s, p=1, lowered=True)
    >>> c.counts()["cx"] == est.cx
    True
    >>> qcpp.estimate(s, p=0)
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: p: must be at least 1, got 0

The names load on first use (:pep:`562`): ``import qcpp`` and the command line's start-up stay light.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    __version__: str
    from qcpp.api.compiling import Compiled, compile
    from qcpp.api.decoding import DecodedCounts, decode_counts
    from qcpp.api.devices import Device, DeviceError, device, devices
    from qcpp.api.estimates import Estimate, estimate, plot_estimates
    from qcpp.api.noisy import simulate_noisy
    from qcpp.api.qubos import qubo_model, write_qubo
    from qcpp.api.scenarios import (
        Scenario,
        ScenarioError,
        default_scenario,
        ensemble,
        grid_scenario,
        load_scenario,
        random_scenario,
        save_scenario,
    )
    from qcpp.api.solving import simulate_qaoa, solve, train_qaoa
    from qcpp.api.validating import validate
    from qcpp.api.verifying import is_feasible, verify
    from qcpp.errors import OptionError, QcppError
    from qcpp.io.atomic import OutputError
    from qcpp.ir.angles import UnboundParameterError
    from qcpp.lowering.qasm_profiles import QasmProfileError
    from qcpp.plan.options import PlanOptions
    from qcpp.problem.limits import SizeError, allow_large
    from qcpp.problem.solvers import Solution
    from qcpp.qubo.model import Bqm
    from qcpp.routing.context import RoutingContext
    from qcpp.simulate.noisy import NoisyResult
    from qcpp.simulate.validate import ValidationReport
    from qcpp.verification import VerifyReport

_EXPORTS: dict[str, str] = {
    "Compiled": "qcpp.api.compiling",
    "compile": "qcpp.api.compiling",
    "DecodedCounts": "qcpp.api.decoding",
    "decode_counts": "qcpp.api.decoding",
    "Device": "qcpp.api.devices",
    "DeviceError": "qcpp.api.devices",
    "device": "qcpp.api.devices",
    "devices": "qcpp.api.devices",
    "Estimate": "qcpp.api.estimates",
    "estimate": "qcpp.api.estimates",
    "plot_estimates": "qcpp.api.estimates",
    "simulate_noisy": "qcpp.api.noisy",
    "qubo_model": "qcpp.api.qubos",
    "write_qubo": "qcpp.api.qubos",
    "Bqm": "qcpp.qubo.model",
    "RoutingContext": "qcpp.routing.context",
    "Scenario": "qcpp.api.scenarios",
    "ScenarioError": "qcpp.api.scenarios",
    "default_scenario": "qcpp.api.scenarios",
    "grid_scenario": "qcpp.api.scenarios",
    "ensemble": "qcpp.api.scenarios",
    "random_scenario": "qcpp.api.scenarios",
    "load_scenario": "qcpp.api.scenarios",
    "save_scenario": "qcpp.api.scenarios",
    "simulate_qaoa": "qcpp.api.solving",
    "solve": "qcpp.api.solving",
    "train_qaoa": "qcpp.api.solving",
    "validate": "qcpp.api.validating",
    "OptionError": "qcpp.errors",
    "OutputError": "qcpp.io.atomic",
    "QasmProfileError": "qcpp.lowering.qasm_profiles",
    "PlanOptions": "qcpp.plan.options",
    "Solution": "qcpp.problem.solvers",
    "QcppError": "qcpp.errors",
    "UnboundParameterError": "qcpp.ir.angles",
    "SizeError": "qcpp.problem.limits",
    "allow_large": "qcpp.problem.limits",
    "is_feasible": "qcpp.api.verifying",
    "NoisyResult": "qcpp.simulate.noisy",
    "ValidationReport": "qcpp.simulate.validate",
    "VerifyReport": "qcpp.verification",
    "verify": "qcpp.api.verifying",
}
"""Public name -> the module that defines it."""

__all__ = [
    "Bqm",
    "Compiled",
    "DecodedCounts",
    "Device",
    "DeviceError",
    "Estimate",
    "NoisyResult",
    "OptionError",
    "OutputError",
    "PlanOptions",
    "QasmProfileError",
    "QcppError",
    "RoutingContext",
    "Scenario",
    "ScenarioError",
    "SizeError",
    "Solution",
    "UnboundParameterError",
    "ValidationReport",
    "VerifyReport",
    "__version__",
    "allow_large",
    "compile",
    "decode_counts",
    "default_scenario",
    "device",
    "devices",
    "ensemble",
    "estimate",
    "grid_scenario",
    "is_feasible",
    "load_scenario",
    "plot_estimates",
    "qubo_model",
    "random_scenario",
    "save_scenario",
    "simulate_noisy",
    "simulate_qaoa",
    "solve",
    "train_qaoa",
    "validate",
    "verify",
    "write_qubo",
]
"""The public API (the command line is ``qcpp``, :mod:`qcpp.cli.app`)."""


def _version() -> str:
    """The installed distribution's version (read on first use: :mod:`importlib.metadata` is slow to import, and
    the console script imports this package before it can install its signal handling)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("qcpp")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree that is not installed
        return "0+unknown"


def __getattr__(name: str) -> Any:
    if name == "__version__":
        globals()[name] = value = _version()
        return value
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'qcpp' has no attribute {name!r}")
    loaded = importlib.import_module(module)
    value = getattr(loaded, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The public API (:data:`__all__`) and the module's dunders; not the helpers it imports."""
    return sorted({*__all__, *(name for name in globals() if name.startswith("__") and name.endswith("__"))})
