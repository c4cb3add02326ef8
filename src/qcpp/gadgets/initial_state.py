"""Initial states: each robot on its initial path, a classical warm start, or a uniform superposition of paths.

``initial_path`` (default, the paper's): an X gate on every data qubit whose edge lies on the robot's
:func:`~qcpp.problem.paths.initial_path`.

``representatives``: when SBF moves split a robot's feasible paths into several components (hard
obstacles), one path per component (:func:`~qcpp.problem.sbf.representatives`) is put in uniform superposition
``sum_k |s_k> / sqrt(K)``, robot by robot, so the mixer can reach every component. The state-preparation
circuit is a binary decision tree over the qubits (the sparse form of Grover-Rudolph state preparation):

* ``prepare(S, C)`` for the set of bit strings ``S`` on the branch selected by the conditions ``C``
  (qubit = value pairs fixed by earlier rotations): set every not-yet-fixed qubit on which all of ``S``
  agree (X controlled on ``C``); if ``|S| > 1``, take the lowest qubit ``q`` on which ``S`` splits into
  ``S0`` (bit 0) and ``S1`` (bit 1), rotate it with ``RY(2 acos(sqrt(|S0|/|S|)))`` controlled on ``C``, then
  ``prepare(S0, C + {q: 0})`` and ``prepare(S1, C + {q: 1})``.
* A gate controlled on one condition uses ``cx``/``cry`` (X-conjugated for a 0 condition); on two or more, the
  conjunction is computed into one clean ``logic`` ancilla with an ``mcx``, used, and uncomputed.

With ``K = 1`` this is just the X gates of the single path.

``local_search``: a classical warm start. Every robot on its path of the local minimum that steepest descent
over allowed SBF flips reaches from the initial paths (:func:`qcpp.problem.solvers.descent.local_search`): one
basis state, prepared like ``initial_path`` by X gates.

``local_search_mix``: per robot ``(|initial path> + |descent path>) / sqrt 2`` (one path where they agree), the
product over robots: the descent's low cost beside the initial paths' weight, which the mixer can still move.
Prepared by the decision tree with two strings (X, one RY(pi/2), CNOTs; no ancilla).

Example:
    >>> [g.name for g in superposition_gates([0b01, 0b10], [0, 1], ancilla=2)]
    ['ry', 'mcx']
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from qcpp.ir.gates import Gate, cry, mcx, ry, x
from qcpp.plan.options import INITIAL_STATES
from qcpp.problem.paths import edges_of, initial_path, path_bits
from qcpp.problem.sbf import Rule, representatives
from qcpp.problem.scenario import Scenario


def _conditioned(
    gate_on: int, conditions: list[tuple[int, int]], ancilla: int | None, kind: str, theta: float = 0.0
) -> list[Gate]:
    """X (``kind='x'``) or RY(theta) (``kind='ry'``) on ``gate_on`` controlled on all ``(qubit, value)``."""
    if not conditions:
        return [x(gate_on)] if kind == "x" else [ry(theta, gate_on)]
    if kind == "x":
        qs = [q for q, _ in conditions]
        return [mcx(qs, gate_on, "".join(str(v) for _, v in conditions))]
    if len(conditions) == 1:
        (q, v), = conditions
        flip = [] if v else [x(q)]
        return [*flip, cry(theta, q, gate_on), *flip]
    if ancilla is None:
        raise ValueError("a controlled rotation with several conditions needs an ancilla")
    qs = [q for q, _ in conditions]
    flag = mcx(qs, ancilla, "".join(str(v) for _, v in conditions))
    return [flag, cry(theta, ancilla, gate_on), flag]


def superposition_gates(strings: Sequence[int], qubits: Sequence[int], ancilla: int | None = None) -> list[Gate]:
    """Gates preparing ``sum_k |strings[k]> / sqrt(K)`` from |0...0> (see the module docstring).

    Args:
        strings: Distinct bit strings; bit ``i`` of each belongs to ``qubits[i]``.
        qubits: The qubits, in bit order.
        ancilla: A clean qubit, needed only when a rotation has two or more conditions.
    """
    if len(set(strings)) != len(strings) or not strings:
        raise ValueError("need a non-empty list of distinct bit strings")
    n = len(qubits)
    if len(strings) == 1:  # one basis state: an X on each set bit, in bit order (what the recursion below gives)
        bits = bin(strings[0])[:1:-1]
        return [x(qubits[i]) for i, b in enumerate(bits) if b == "1"]
    out: list[Gate] = []

    def prepare(group: list[int], conditions: list[tuple[int, int]], fixed: set[int]) -> None:
        split = None
        for i in range(n):
            if i in fixed:
                continue
            bits = {(s >> i) & 1 for s in group}
            if len(bits) == 1:
                if bits == {1}:
                    out.extend(_conditioned(qubits[i], conditions, ancilla, "x"))
                fixed = fixed | {i}
            elif split is None:
                split = i
        if split is None:
            return
        zeros = [s for s in group if not (s >> split) & 1]
        ones = [s for s in group if (s >> split) & 1]
        theta = 2 * math.acos(math.sqrt(len(zeros) / len(group)))
        out.extend(_conditioned(qubits[split], conditions, ancilla, "ry", theta))
        fixed = fixed | {split}
        prepare(zeros, [*conditions, (qubits[split], 0)], fixed)
        prepare(ones, [*conditions, (qubits[split], 1)], fixed)

    prepare(list(strings), [], set())
    return out


Count = Any  # an int, or a sympy expression in the closed forms (qcpp.estimators.formulas)


def initial_path_count(scenario: Scenario, sizes: tuple[Count, Count] | None = None) -> Count:
    """X gates of the ``initial_path`` state on a grid without obstacles: per robot the edges of its L-shaped
    :func:`~qcpp.problem.paths.initial_path`, ``|row step| + |column step|`` (every edge of an open grid is a
    variable, so the L is always the path). What :meth:`qcpp.plan.qaoa.QaoaPlan.call_graph` lists as the state
    preparation, and, with symbolic ``sizes``, the closed forms' (:mod:`qcpp.estimators.formulas`).

    Args:
        scenario: a scenario without obstacles.
        sizes: count for a grid of ``(rows, cols)`` nodes (sympy expressions) instead of the scenario's own: a
            coordinate in the far half of a side of ``n`` nodes is read as the same distance from the end of a
            side of ``size`` nodes (the scenario stands for every grid with its endpoints near the same corners).

    Returns:
        The number of X gates.

    Raises:
        ValueError: the scenario has obstacles.

    >>> import sympy as sp
    >>> from qcpp.problem.presets import default_scenario
    >>> s = default_scenario(6, 6, 2)
    >>> initial_path_count(s), initial_path_count(s, sp.symbols("rows cols"))
    (20, 2*cols + 2*rows - 4)
    """
    if scenario.obstacles:
        raise ValueError("the initial path is an L only on a grid without obstacles")
    sides = (scenario.grid.rows, scenario.grid.cols)

    def at(k: int, axis: int) -> Count:  # a coordinate on the grid of ``sizes``
        n = sides[axis]
        return k if sizes is None or 2 * k < n else sizes[axis] - (n - k)

    total: Count = 0
    for rb in scenario.robots:
        for axis in (0, 1):
            a, b = sorted((rb.start[axis], rb.goal[axis]))
            total += at(b, axis) - at(a, axis)
    return total


def start_paths(scenario: Scenario, robot: int, initial: str, rule: Rule = "exact") -> tuple[int, ...]:
    """The paths (edge masks) whose uniform superposition is ``robot``'s part of the initial state ``initial``:
    what :func:`initial_state_gates` prepares and the subspace simulator (:func:`qcpp.simulate.subspace.robot_basis`)
    starts from.

    Args:
        initial: One of :data:`qcpp.plan.options.INITIAL_STATES` (see the module docstring).
        rule: SBF rule deciding the move-graph components (``representatives``) or the allowed flips of the
            descent (``local_search``, ``local_search_mix``).

    Returns:
        The distinct paths, in the order the preparation reads them.

    >>> from qcpp.problem.presets import default_scenario
    >>> start_paths(default_scenario(3, 3, 1), 0, "initial_path") == (initial_path(default_scenario(3, 3, 1), 0),)
    True
    """
    if initial not in INITIAL_STATES:
        raise ValueError(f"unknown initial state {initial!r} (expected one of {', '.join(INITIAL_STATES)})")
    if initial == "representatives":
        return tuple(representatives(scenario, robot, rule))
    if initial == "initial_path":
        return (initial_path(scenario, robot),)
    from qcpp.problem.solvers.descent import local_search  # the solvers package is heavier than this module

    descent = local_search(scenario, rule).paths[robot]
    return (descent,) if initial == "local_search" else tuple(dict.fromkeys((initial_path(scenario, robot), descent)))


def initial_state_gates(
    scenario: Scenario,
    initial: str = "initial_path",
    rule: Rule = "exact",
    ancilla: int | None = None,
) -> list[Gate]:
    """The initial-state preparation on the data qubits (variable ``i`` on qubit ``i``).

    Args:
        initial: ``initial_path``, ``representatives``, ``local_search`` or ``local_search_mix`` (see the
            module docstring).
        rule: SBF rule deciding the move-graph components (``representatives``) or the allowed flips of the
            descent (``local_search``, ``local_search_mix``).
        ancilla: Clean qubit for multiply-controlled rotations (``representatives`` only).
    """
    v = scenario.edges_per_robot
    out: list[Gate] = []
    for r in range(scenario.num_robots):
        masks = start_paths(scenario, r, initial, rule)
        if initial in ("initial_path", "local_search"):  # one basis state: an X on each variable of its path
            out += [x(q) for q in sorted(scenario.variable_index(r, e) for e in edges_of(masks[0]))]
            continue
        strings = [int("".join(map(str, path_bits(scenario, m)[::-1])), 2) for m in masks]
        out.extend(superposition_gates(strings, list(range(r * v, (r + 1) * v)), ancilla))
    return out
