"""Argument checks of the public API, shared with the command line where it checks the same thing.

Every check raises a :class:`~qcpp.errors.QcppError` subclass whose message names the argument as Python spells
it (``p``, ``rule``) and gives the reason the command line gives after its flag (``-p/--layers``, ``--rule``).

Example:
    >>> check_layers_arg(2)
    2
    >>> check_layers_arg(0)
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: p: must be at least 1, got 0
    >>> plan_options_arg({"rule": "paper"}).rule
    'paper'
    >>> plan_options_arg({"colour": "red"})
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: colour: unknown plan option (known: rule, initial, target, phase, optimize, \
ancilla_budget, fuse, phase_layout, angles, first_phase)
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import fields
from typing import Any

from qcpp.api.scenarios import Scenario
from qcpp.errors import OptionError, check_count
from qcpp.plan.options import PlanOptions
from qcpp.problem.limits import API_OVERRIDE, check_layers

__all__ = ["PLAN_OPTION_NAMES", "check_angles_arg", "check_layers_arg", "check_scenario_arg", "plan_options_arg"]

PLAN_OPTION_NAMES: tuple[str, ...] = tuple(f.name for f in fields(PlanOptions))
"""The keyword arguments ``**plan_options`` of ``qcpp.estimate`` and ``qcpp.compile`` accept (the fields of
:class:`~qcpp.plan.options.PlanOptions`)."""


def check_layers_arg(p: object, name: str = "p") -> int:
    """``p`` if it is a layer count the command line accepts too (an integer from 1 to
    :data:`qcpp.problem.limits.MAX_LAYERS`, unless :func:`qcpp.problem.limits.allow_large` is in effect).

    Raises:
        qcpp.errors.OptionError: not an integer, or below 1.
        qcpp.problem.limits.SizeError: over the layer limit.
    """
    layers = check_count(p, name, 1)
    check_layers(layers, name, API_OVERRIDE)
    return layers


def plan_options_arg(options: Mapping[str, Any]) -> PlanOptions:
    """The :class:`~qcpp.plan.options.PlanOptions` of keyword arguments (``rule="paper"``, ...).

    Raises:
        qcpp.errors.OptionError: an unknown name (listing the known ones) or a bad value (naming the option, with
            the reason ``qcpp compile`` and ``qcpp estimate`` give for the flag).
    """
    for name in options:
        if name not in PLAN_OPTION_NAMES:
            raise OptionError(name, f"unknown plan option (known: {', '.join(PLAN_OPTION_NAMES)})")
    return PlanOptions(**options)


def check_scenario_arg(scenario: object, name: str = "scenario") -> Scenario:
    """``scenario`` if it is a :class:`~qcpp.problem.scenario.Scenario`.

    Raises:
        qcpp.errors.OptionError: anything else (a file name: load it with ``qcpp.load_scenario`` first).
    """
    if not isinstance(scenario, Scenario):
        raise OptionError(
            name, f"expected a Scenario (qcpp.grid_scenario or qcpp.load_scenario), got {type(scenario).__name__}"
        )
    return scenario


def check_angles_arg(angles: object, layers: int, name: str = "angles") -> list[float] | None:
    """``angles`` as a list of ``2 * layers`` finite floats ``[gamma_0, beta_0, ...]`` (``None`` stays ``None``).

    Raises:
        qcpp.errors.OptionError: not a sequence of numbers, a value that is not finite, or the wrong length.

    Example:
        >>> check_angles_arg((0.1, 2), 1)
        [0.1, 2.0]
        >>> check_angles_arg([0.1], 1)
        Traceback (most recent call last):
        ...
        qcpp.errors.OptionError: angles: p = 1 needs 2 angles (g0,b0,...), got 1
    """
    if angles is None:
        return None
    if isinstance(angles, (str, bytes)) or not isinstance(angles, Sequence):
        raise OptionError(name, f"expected a sequence of numbers, got {angles!r}")
    values = []
    for a in angles:
        if isinstance(a, bool) or not isinstance(a, (int, float)) or not math.isfinite(a):
            raise OptionError(name, f"{a!r} is not a finite number")
        values.append(float(a))
    if len(values) != 2 * layers:
        raise OptionError(name, f"p = {layers} needs {2 * layers} angles (g0,b0,...), got {len(values)}")
    return values


def check_context_arg(context: object, device: object) -> Any:
    """``context`` as the API's ``context=`` takes it: ``None``, or a :class:`qcpp.RoutingContext` with a
    ``device`` (it holds routing searches; there is nothing to route without one).

    Raises:
        OptionError: anything else, naming ``context``.
    """
    from qcpp.routing.context import RoutingContext

    if context is not None and not isinstance(context, RoutingContext):
        raise OptionError("context", f"expected a qcpp.RoutingContext or None, got {type(context).__name__}")
    if context is not None and device is None:
        raise OptionError("context", "applies with a device only (no device given)")
    return context
