"""The result every solver returns, and its JSON form.

A :class:`Solution` is a frozen value: the chosen path of every robot (edge masks, robot order), the cost
parts recomputed with :func:`qcpp.problem.cost.cost_parts` (never the solver's internal running value), the
wall-clock time, how many assignments were scored, and method-specific diagnostics (the best-so-far cost
trace of the local searches, path counts of exhaustive search, which move-graph components were visited).

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.problem.paths import initial_path
    >>> from qcpp.problem.cost import cost_parts
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
    >>> p = (initial_path(s, 0),)
    >>> sol = Solution("manual", p, cost_parts(s, p), seconds=0.0, evaluated=1)
    >>> solution_to_dict(s, sol)["paths"]
    [[[0, 0], [0, 1], [1, 1]]]
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from qcpp.problem.cost import CostParts
from qcpp.problem.grid import Node
from qcpp.problem.paths import path_to_nodes
from qcpp.problem.scenario import Scenario

ProgressFn = Callable[[int, int | None], None]
"""Progress callback ``progress(done, total)`` that solvers call now and then (units are solver-specific; ``total``
``None`` where it is not known: CP-SAT counts the improving solutions it finds)."""


@dataclass(frozen=True)
class Solution:
    """One solver run's answer.

    Attributes:
        method: Solver name (``dfs``, ``anneal``, ``genetic``, ...).
        paths: One edge mask per robot (robot order); every one a feasible path.
        cost: The cost parts of ``paths`` (recomputed with :func:`qcpp.problem.cost.cost_parts`).
        seconds: Wall-clock time of the run (including path enumeration / component analysis).
        evaluated: Number of assignments whose cost was looked up (exhaustive search: all of them; local
            searches: every scored candidate, repeats included).
        trace: Best-so-far total cost after each iteration (anneal) or generation (genetic); empty for dfs.
        paths_per_robot: Number of feasible paths of each robot (dfs; empty otherwise).
        num_components: Per robot, the number of move-graph components of its feasible paths under the
            solver's SBF rule (empty when the solver did not analyse them).
        components_visited: Per robot, the indices (into :func:`qcpp.problem.sbf.move_components`) of the
            components the search visited.
        seed: The random seed (stochastic solvers), else ``None``.
        rule: The SBF rule used for moves (local searches), else ``None``.
        notes: Free-text remarks (tie-breaking, skipped moves, ...).
        details: The method's own JSON-ready fields as ``(name, value)`` pairs, in output order, which
            :func:`solution_to_dict` adds (``cpsat``: ``proven_optimal``, ``bound``, ``gap``, ``status``; ``qaoa``:
            :func:`qcpp.training.qaoa_solver.qaoa_details`); ``dict(sol.details)`` reads them. Pairs rather than a
            dict keep the value immutable at its top level; the values may be lists (angles, levels).
        stopped: ``None`` for a run that ended on its own; else why it ended early with the best found so far:
            ``"time limit"`` or ``"interrupted"`` (:mod:`qcpp.problem.solvers.stopping`). Such an answer is no
            optimum, whatever its cost.
    """

    method: str
    paths: tuple[int, ...]
    cost: CostParts
    seconds: float
    evaluated: int
    trace: tuple[float, ...] = ()
    paths_per_robot: tuple[int, ...] = ()
    num_components: tuple[int, ...] = ()
    components_visited: tuple[tuple[int, ...], ...] = ()
    seed: int | None = None
    rule: str | None = None
    notes: tuple[str, ...] = ()
    details: tuple[tuple[str, Any], ...] = field(default=(), hash=False)  # values may be lists: not hashable
    stopped: str | None = None

    def node_paths(self, scenario: Scenario) -> tuple[tuple[Node, ...], ...]:
        """Each robot's path as its ``(row, col)`` nodes from start to goal (``paths`` holds edge masks).

        Args:
            scenario: The scenario the solution belongs to.

        Example:
            >>> from qcpp.problem.presets import grid_scenario
            >>> from qcpp.problem.solvers.exhaustive import dfs
            >>> s = grid_scenario(2, 3, robots=[((0, 0), (0, 2))])
            >>> dfs(s).node_paths(s)
            (((0, 0), (0, 1), (1, 1), (1, 2), (0, 2)),)
        """
        return tuple(
            tuple(path_to_nodes(scenario.grid, m, rb.start)) for m, rb in zip(self.paths, scenario.robots, strict=True)
        )

    def to_dict(self, scenario: Scenario, *, include_trace: bool = False) -> dict[str, Any]:
        """What ``qcpp solve --json`` prints for this solution, but its ``scenario`` field (the file or flags the
        command was given): :func:`solution_to_dict`. Timing (``seconds``) differs from run to run."""
        return solution_to_dict(scenario, self, include_trace=include_trace)


def solution_to_dict(scenario: Scenario, sol: Solution, *, include_trace: bool = False) -> dict[str, Any]:
    """JSON-ready dict of ``sol``: paths as ``[row, col]`` node lists from start to goal. The one builder of the
    object ``qcpp solve --json`` prints (after its ``scenario`` field) and :meth:`Solution.to_dict` returns.

    Args:
        scenario: The scenario the solution belongs to (needed to walk the paths).
        include_trace: Whether to include the (possibly long) ``trace`` list (``trace_length`` is always there
            when the trace is not empty).

    Returns:
        A fresh dict with ``method``, ``paths``, ``cost``, ``cost_parts`` (``c1``, ``c2``, ``c3``), ``seconds``,
        ``evaluated``, ``stopped`` (only for a run that stopped early), every non-empty optional field of
        :class:`Solution`, the method's ``details`` and ``trace_length``.
    """
    out: dict[str, Any] = {
        "method": sol.method,
        "paths": [
            [list(n) for n in nodes] for nodes in sol.node_paths(scenario)
        ],
        "cost": sol.cost.total,
        "cost_parts": {"c1": sol.cost.c1, "c2": sol.cost.c2, "c3": sol.cost.c3},
        "seconds": sol.seconds,
        "evaluated": sol.evaluated,
    }
    if sol.stopped is not None:
        out["stopped"] = sol.stopped
    if sol.paths_per_robot:
        out["paths_per_robot"] = list(sol.paths_per_robot)
    if sol.num_components:
        out["num_components"] = list(sol.num_components)
    if sol.components_visited:
        out["components_visited"] = [list(c) for c in sol.components_visited]
    if sol.seed is not None:
        out["seed"] = sol.seed
    if sol.rule is not None:
        out["rule"] = sol.rule
    if include_trace and sol.trace:
        out["trace"] = list(sol.trace)
    if sol.notes:
        out["notes"] = list(sol.notes)
    out.update(copy.deepcopy(dict(sol.details)))  # a fresh copy: the caller may edit its dict
    if sol.trace:
        out["trace_length"] = len(sol.trace)
    return out
