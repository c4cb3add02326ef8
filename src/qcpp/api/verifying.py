"""``qcpp.verify`` and ``qcpp.is_feasible``: whether a scenario's compiled circuit preserves feasibility, and whether
one edge set is a feasible path.

The checks are :mod:`qcpp.verification`'s (the command ``qcpp verify``) and :func:`qcpp.problem.paths.is_feasible`'s;
this module takes the circuit's construction as keywords (``rule="paper"``, ``target="ft"``), as ``qcpp.compile``
and ``qcpp.estimate`` do, and checks every argument first, so bad input raises one line naming it.

Example:
    >>> import qcpp
    >>> leak = qcpp.grid_scenario(2, 3, robots=[((0, 2), (1, 1))])
    >>> qcpp.verify(leak, p=1).holds, qcpp.verify(leak, p=1, rule="paper").holds
    (True, False)
"""

from __future__ import annotations

from typing import Any

from qcpp.api.checks import check_scenario_arg, plan_options_arg
from qcpp.api.progress import ProgressArg, check_progress_arg, reporting
from qcpp.errors import OptionError, check_count
from qcpp.plan.options import PlanOptions
from qcpp.problem import paths
from qcpp.verification import DEFAULT_SAMPLES, VerifyReport
from qcpp.verification import verify as _verify

__all__ = ["is_feasible", "verify"]


def verify(
    scenario: Any,
    p: int = 1,
    *,
    method: str = "auto",
    samples: int = DEFAULT_SAMPLES,
    seed: int = 0,
    progress: ProgressArg = None,
    options: PlanOptions | None = None,
    **plan_options: Any,
) -> VerifyReport:
    """Check that the compiled QAOA circuit of ``scenario`` keeps every feasible superposition feasible (the command
    ``qcpp verify``; the methods are described in :mod:`qcpp.verification`).

    Args:
        scenario: The scenario (``qcpp.grid_scenario``, ``qcpp.load_scenario``).
        p: QAOA layers (>= 1).
        method: ``state`` (the lowered circuit run on every feasible input of every part, or a seeded sample of
            ``samples`` where there are more), ``gadgets`` (every gadget kind on each of its local inputs, any size)
            or ``auto`` (``state`` where every input fits ``samples``, else ``gadgets``).
        samples: ``state``: most feasible inputs per part.
        seed: Seed of the angles and of any sample.
        progress: ``True`` for progress lines on stderr, or a function ``progress(done, total)``
            (:mod:`qcpp.api.progress`) called while checking: the checks done (gadget method) or the inputs run
            (state method). Nothing is printed without it (the state method can take tens of seconds).
        options: The construction as one ``PlanOptions`` value (instead of keywords).
        **plan_options: How the circuit is built, as for ``qcpp.compile``: ``rule`` (``exact``, the default, or
            ``paper``), ``target`` (``nisq`` or ``ft``), ``fuse``, ``initial``, ``phase``, ...

    Returns:
        The :class:`~qcpp.verification.report.VerifyReport`: ``holds``, the ``checks`` that ran, and where the
        circuit leaves the feasible space a ``counterexample`` (an input and what came out).

    Raises:
        qcpp.OptionError: not a Scenario, an unknown method or plan option, a bad value (naming it), ``p`` or
            ``samples`` not an integer of at least 1, or both ``options`` and keywords.
        qcpp.SizeError: ``p`` over the layer limit outside ``qcpp.allow_large()``.
        ValueError: ``method="state"`` on a circuit wider than 62 qubits.
    """
    s = check_scenario_arg(scenario)
    if options is not None:
        if plan_options:
            raise OptionError("options", f"give options or plan options as keywords ({', '.join(plan_options)}), "
                                         "not both")  # fmt: skip
        if not isinstance(options, PlanOptions):
            raise OptionError("options", f"expected a PlanOptions, got {type(options).__name__}")
    else:
        options = plan_options_arg(plan_options)
    check_progress_arg(progress)
    task = f"verify p={p} on {s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s)"
    with reporting(progress, task, unit="checks") as bar:
        return _verify(s, p, options.rule, method, samples, seed, bar and bar.update, options)  # type: ignore[arg-type]


def is_feasible(scenario: Any, robot: int, mask: int) -> bool:
    """Whether the edge set ``mask`` is a feasible path of robot ``robot``: one simple path from its start to its
    goal (connected, no loop, no node or edge twice) and, with hard obstacles, no edge touching an obstacle.

    Args:
        scenario: The scenario.
        robot: The robot's index, ``0 .. scenario.num_robots - 1``.
        mask: The edge set as bits: bit ``e`` set means the path uses ``scenario.grid.edges[e]`` (the order of
            the circuit's data qubits of one robot).

    Returns:
        ``True`` for a feasible path.

    Raises:
        qcpp.OptionError: not a Scenario, ``robot`` not one of the scenario's robots, ``mask`` not an integer of
            at least 0.

    Example:
        >>> import qcpp
        >>> s = qcpp.grid_scenario(2, 2, robots=[((0, 0), (1, 1))])
        >>> edges = s.grid.edges
        >>> right_down = sum(1 << edges.index(e) for e in (((0, 0), (0, 1)), ((0, 1), (1, 1))))
        >>> qcpp.is_feasible(s, 0, right_down), qcpp.is_feasible(s, 0, 0)
        (True, False)
    """
    s = check_scenario_arg(scenario)
    check_count(robot, "robot", 0)
    if robot >= s.num_robots:
        raise OptionError("robot", f"the scenario has robots 0 .. {s.num_robots - 1}, got {robot}")
    check_count(mask, "mask", 0)
    return paths.is_feasible(s, robot, mask)
