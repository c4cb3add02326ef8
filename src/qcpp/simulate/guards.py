"""Size guards of the simulators, shared by the command line (``qcpp simulate``, ``qcpp solve -m qaoa``) and the
Python API (``qcpp.simulate_qaoa``, ``qcpp.train_qaoa``): refuse, before any state is built, work the machine cannot
hold or would run for hours, in one line naming the prediction, the limit and how to lift it.

The predictions are :mod:`qcpp.simulate.footprint`'s (peak memory and time from measured per-assignment costs); the
check is :func:`qcpp.problem.limits.check_need` against the available memory. Inside
:func:`qcpp.problem.limits.allow_large` (the CLI's ``--allow-large``) nothing is refused.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> check_simulation_size(default_scenario(3, 3, 1), "3x3")
    >>> check_training_size(default_scenario(3, 3, 1), "3x3")
"""

from __future__ import annotations

from collections.abc import Callable

from qcpp.problem.limits import SizeError, check_need, large_allowed
from qcpp.problem.scenario import Scenario

__all__ = ["check_simulation_size", "check_training_size"]


def check_simulation_size(
    scenario: Scenario, where: str, override: str = "", *, p: int = 1, method: str = "subspace"
) -> None:
    """Refuse a simulation predicted to need more memory than is available or to run for hours
    (:func:`qcpp.simulate.footprint.simulate_need`).

    Args:
        where: What the message starts with (the scenario file, or ``scenario``).
        override: How to lift the guard, for the message (default: the CLI's ``pass --allow-large``).
        p: QAOA layers.
        method: The simulator (``subspace``, ``statevector``, ...).

    Raises:
        qcpp.problem.limits.SizeError: one line naming the prediction, the limit and ``override``.
    """
    from qcpp.simulate.footprint import simulate_need

    if not large_allowed():
        check_need(simulate_need(scenario, p, method), field=where, override=override)


def check_training_size(
    scenario: Scenario,
    where: str,
    override: str = "",
    alternatives: str = "use --method cpsat or anneal",
    stage: Callable[[str], None] | None = None,
    *,
    p: int = 1,
) -> None:
    """Refuse a QAOA training whose subspace simulator would not fit in the available memory
    (:func:`qcpp.simulate.footprint.training_need`; no time model: the optimiser decides how long it runs).

    Args:
        where: What the message starts with (the scenario file, or ``scenario``).
        override: How to lift the guard, for the message (default: the CLI's ``pass --allow-large``).
        alternatives: What else to do, for the message.
        stage: Called with the stage (``counting feasible assignments``) for a progress display.
        p: QAOA layers.

    Raises:
        qcpp.problem.limits.SizeError: one line naming the prediction, the limit, ``override`` and
            ``alternatives``.
    """
    from qcpp.simulate.footprint import training_need

    if large_allowed():
        return
    if stage is not None:
        stage("counting feasible assignments")
    need = training_need(scenario, p)
    try:
        check_need(need, field=where, override=override)
    except SizeError as exc:
        raise SizeError("", f"{exc}, or {alternatives}") from None
