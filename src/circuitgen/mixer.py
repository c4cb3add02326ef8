"""Constrained SBF mixers: partial mixers (one robot, one plaquette) and the full mixer.

A partial mixer for robot ``r`` and plaquette ``q`` is, in time order:

1. *compute*: the steps of the SBF logic network (:func:`gridcover.sbf.sbf_logic`) as multi-controlled X
   gates from the robot's data qubits (and earlier temporaries) into the ``logic`` ancillas;
2. ``csbf(beta)``: the SBF rotation ``exp(-i beta X_ab X_bc X_cd X_da / 2)`` controlled by the output ancilla;
3. *uncompute*: the same steps in reverse order, returning every ``logic`` ancilla to |0>.

Logic that is decided at compile time is folded away in the network itself (boundary corners, known
endpoints, hard-mode obstacle edges); a plaquette whose flip can never be allowed emits nothing.

The full mixer applies the partial mixers robot-major (robot 0 first), plaquettes row-major within a robot.
Robots act on disjoint data qubits (only the clean ``logic`` ancillas are shared), so the robot order does not
change the unitary; the plaquette order does, and is part of the definition.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> from circuitgen.angles import Angle
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
    >>> gates = partial_mixer_gates(s, 0, s.grid.plaquettes[0], Angle.symbol("beta_0"), logic_offset=4)
    >>> [g.name for g in gates]
    ['mcx', 'mcx', 'ccx', 'csbf', 'ccx', 'mcx', 'mcx']
"""

from __future__ import annotations

from collections.abc import Iterator

from gridcover.grid import Plaquette
from gridcover.sbf import Rule, SbfLogic, XorStep, sbf_logic
from gridcover.scenario import Scenario

from .angles import Param
from .gates import Gate, csbf, mcx


def logic_width(scenario: Scenario, rule: Rule = "exact") -> int:
    """Number of ``logic`` ancillas the full mixer needs (the largest network; they are reused)."""
    widths = [
        lg.num_temps
        for r in range(scenario.num_robots)
        for q in scenario.grid.plaquettes
        if not (lg := sbf_logic(scenario, r, q, rule)).never
    ]
    return max(widths, default=0)


def _step_gate(scenario: Scenario, robot: int, step: XorStep, logic_offset: int) -> Gate:
    controls = []
    state = []
    for lit in step.literals:
        if lit.is_temp:
            controls.append(logic_offset + lit.temp)
        else:
            controls.append(scenario.variable_index(robot, lit.signal))
        state.append("1" if lit.value else "0")
    return mcx(controls, logic_offset + step.target, "".join(state))


def logic_gates(scenario: Scenario, logic: SbfLogic, logic_offset: int) -> list[Gate]:
    """The compute half of a partial mixer: one (multi-)controlled X per network step."""
    return [_step_gate(scenario, logic.robot, st, logic_offset) for st in logic.steps]


def partial_mixer_gates(
    scenario: Scenario,
    robot: int,
    plaquette: Plaquette,
    beta: Param,
    logic_offset: int,
    rule: Rule = "exact",
) -> list[Gate]:
    """Gates of one partial mixer (empty when the flip is never allowed).

    Args:
        scenario: The scenario.
        robot: Robot index.
        plaquette: The plaquette.
        beta: The mixing angle (usually ``Angle.symbol("beta_k")``).
        logic_offset: Qubit index of the first ``logic`` ancilla.
        rule: SBF rule, ``exact`` or ``paper``.

    Returns:
        compute gates, ``csbf``, uncompute gates.
    """
    logic = sbf_logic(scenario, robot, plaquette, rule)
    if logic.never:
        return []
    compute = logic_gates(scenario, logic, logic_offset)
    data = [scenario.variable_index(robot, e) for e in plaquette.edges]
    rotation = csbf(beta, logic_offset + logic.output, *data)
    return [*compute, rotation, *reversed(compute)]


def full_mixer_gates(
    scenario: Scenario, beta: Param, logic_offset: int, rule: Rule = "exact"
) -> Iterator[Gate]:
    """All partial mixers, robot-major, plaquettes row-major (see the module docstring)."""
    for r in range(scenario.num_robots):
        for q in scenario.grid.plaquettes:
            yield from partial_mixer_gates(scenario, r, q, beta, logic_offset, rule)
