"""Size guards of the simulators, shared by the command line (``qcpp simulate``, ``qcpp solve -m qaoa``) and the
Python API (``qcpp.simulate_qaoa``, ``qcpp.train_qaoa``): refuse, before any state is built, a feasible subspace
the machine cannot hold, in one line naming the size, the limit and how to lift it.

Each check counts the feasible assignments first (:func:`qcpp.simulate.validate.validate_size`, stopping early once
over the limit) and compares with :data:`qcpp.simulate.validate.MAX_VALIDATE_ASSIGNMENTS` or the memory budget
(:func:`qcpp.problem.limits.memory_budget`: half the available memory). Inside
:func:`qcpp.problem.limits.allow_large` (the CLI's ``--allow-large``) nothing is refused.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> check_simulation_size(default_scenario(3, 3, 1), "3x3")
    >>> check_training_size(default_scenario(3, 3, 1), "3x3")
"""

from __future__ import annotations

from collections.abc import Callable

from qcpp.problem.limits import OVERRIDE_FLAG, SizeError, large_allowed, memory_budget
from qcpp.problem.scenario import Scenario

__all__ = ["STATE_BYTES_PER_ASSIGNMENT", "check_simulation_size", "check_training_size"]

STATE_BYTES_PER_ASSIGNMENT = 16
"""One complex128 amplitude per feasible assignment: the least one QAOA state of the subspace simulator holds."""

CLI_OVERRIDE = f"pass {OVERRIDE_FLAG}"
"""How the command line lifts the guards (the default ``override`` of the checks)."""


def check_simulation_size(scenario: Scenario, where: str, override: str = CLI_OVERRIDE) -> None:
    """Refuse simulating a feasible subspace over :data:`~qcpp.simulate.validate.MAX_VALIDATE_ASSIGNMENTS`
    assignments or over the memory budget.

    Args:
        scenario: The scenario.
        where: What the message starts with (the scenario file, or ``scenario``).
        override: How to lift the guard, for the message.

    Raises:
        qcpp.problem.limits.SizeError: one line naming the size, the limit and ``override``.
    """
    from qcpp.simulate.validate import MAX_VALIDATE_ASSIGNMENTS, validate_size

    if large_allowed():
        return
    size = validate_size(scenario, max_assignments=MAX_VALIDATE_ASSIGNMENTS)
    budget = memory_budget()
    if size.assignments > MAX_VALIDATE_ASSIGNMENTS or (budget is not None and size.bytes > budget):
        limit = (
            f"the limit of {MAX_VALIDATE_ASSIGNMENTS:,} feasible assignments"
            if size.assignments > MAX_VALIDATE_ASSIGNMENTS
            else f"the memory budget of {budget / 1e9:.1f} GB"  # type: ignore[operator]
        )
        raise SizeError("", f"{where}: simulating {size.describe()}: over {limit}; {override} to try anyway")


def check_training_size(
    scenario: Scenario,
    where: str,
    override: str = CLI_OVERRIDE,
    alternatives: str = "use --method cpsat or anneal",
    stage: Callable[[str], None] | None = None,
) -> None:
    """Refuse a QAOA training whose feasible subspace cannot hold even one state in the memory budget (without
    it 3 robots on 5x5 ran out of memory after the path enumeration, and 3 robots on 6x6 enumerated paths for
    minutes first).

    Args:
        scenario: The scenario.
        where: What the message starts with (the scenario file, or ``scenario``).
        override: How to lift the guard, for the message.
        alternatives: What else to do, for the message.
        stage: Called with the stage (``counting feasible assignments``) for a progress display.

    Raises:
        qcpp.problem.limits.SizeError: one line naming the size, the budget, ``override`` and ``alternatives``.
    """
    from qcpp.simulate.validate import validate_size

    budget = memory_budget()
    if large_allowed() or budget is None:
        return
    if stage is not None:
        stage("counting feasible assignments")
    size = validate_size(scenario, max_assignments=budget // STATE_BYTES_PER_ASSIGNMENT)
    need = size.assignments * STATE_BYTES_PER_ASSIGNMENT
    if need > budget:
        counted = " x ".join(f"{n:,}" for n in size.paths_per_robot)
        raise SizeError(
            "",
            f"{where}: training QAOA on {'at least ' if not size.exact else ''}{size.assignments:,} feasible "
            f"assignments (paths counted: {counted}): one state needs at least {need / 1e9:.1f} GB, over the memory "
            f"budget of {budget / 1e9:.1f} GB; {override} to try anyway, or {alternatives}",
        )
