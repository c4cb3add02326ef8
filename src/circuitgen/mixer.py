"""Constrained SBF mixers as gate lists: partial mixers (one robot, one plaquette) and the full mixer.

The constructions live in :mod:`circuitgen.gadgets.partial_mixer` (each partial mixer is a gadget that knows its
cost); this module gives their gates. A partial mixer applies ``exp(-i beta/2 X_ab X_bc X_cd X_da)`` to the
robot's plaquette edges when the SBF rule allows the flip and the identity otherwise, and returns every
``logic`` ancilla to |0>. A plaquette whose flip can never be allowed emits nothing.

The full mixer applies the partial mixers robot-major (robot 0 first), plaquettes row-major within a robot.
Robots act on disjoint data qubits (only the clean ``logic`` ancillas are shared), so the robot order does not
change the unitary; the plaquette order does, and is part of the definition.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> from circuitgen.angles import Angle
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
    >>> gates = partial_mixer_gates(s, 0, s.grid.plaquettes[0], Angle.symbol("beta_0"), logic_offset=4)
    >>> sorted({g.name for g in gates})
    ['cx', 'h', 'rz']
"""

from __future__ import annotations

from collections.abc import Iterator

from gridcover.grid import Plaquette
from gridcover.sbf import Rule
from gridcover.scenario import Scenario

from .angles import Param
from .cost import Target
from .gadgets.partial_mixer import logic_width, partial_mixer
from .gates import Gate

__all__ = ["full_mixer_gates", "logic_width", "partial_mixer_gates"]


def partial_mixer_gates(
    scenario: Scenario,
    robot: int,
    plaquette: Plaquette,
    beta: Param,
    logic_offset: int,
    rule: Rule = "exact",
    target: Target = "nisq",
) -> list[Gate]:
    """Gates of one partial mixer (empty when the flip is never allowed).

    Args:
        scenario: The scenario.
        robot: Robot index.
        plaquette: The plaquette.
        beta: The mixing angle (usually ``Angle.symbol("beta_k")``).
        logic_offset: Qubit index of the first ``logic`` ancilla.
        rule: SBF rule, ``exact`` or ``paper``.
        target: ``nisq`` or ``ft``.

    Returns:
        compute gates, the controlled rotation, uncompute gates.
    """
    m = partial_mixer(scenario, robot, plaquette, beta, logic_offset, rule, target)
    return [] if m is None else m.emit()


def full_mixer_gates(
    scenario: Scenario, beta: Param, logic_offset: int, rule: Rule = "exact", target: Target = "nisq"
) -> Iterator[Gate]:
    """All partial mixers, robot-major, plaquettes row-major (see the module docstring)."""
    for r in range(scenario.num_robots):
        for q in scenario.grid.plaquettes:
            yield from partial_mixer_gates(scenario, r, q, beta, logic_offset, rule, target)
