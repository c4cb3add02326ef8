"""The two-robot balance term as one register of the difference of the path lengths, against two registers.

Run: ``python benchmarks/balance_difference.py`` (a few seconds).

The balance term of two robots is ``c (G_1 - G_2)^2`` with ``G_r`` robot ``r``'s path length, a linear form over
its edge bits. Its arithmetic construction (:class:`qcpp.gadgets.phase_sums.SumsPhase`) can take the two forms
with the matrix ``c ((1, -1), (-1, 1))``: two popcount registers, then RZ on their bits and RZZ on every pair of
bits the matrix couples (within each register and across). Or it can take the single form ``D = G_1 - G_2``
(:meth:`qcpp.problem.feasible_cost.SumsGroup.folded`: robot 2's weights negated, the gadget flips those bits
with X): one register, so fewer bit pairs to phase, at the price of a few more adders and ancillas, and of one
adder tree where the two registers' trees ran side by side.

Per default two-robot scenario (and two with obstacles), the table prints the balance gadget both ways:
lowered CX, rotations and clean ancillas (exact: :meth:`SumsPhase.cost` is the lowered cost of the gates it emits,
which ``tests/compiler/phase_test.py`` checks), the depth of its lowered gates (ASAP layers,
:func:`qcpp.estimators.counts.count`; up to 10x10), and the ``ft`` model's T count of the gadget
(:func:`qcpp.plan.phase_choice.ft_t_count`: AND 4 T, rotation 30 T). ``same function`` checks on 2,000 random
bit rows that the folded group evaluates to the balance group's values.

What the plan does with it (:func:`qcpp.plan.phase_choice.prefer_folded`): on the ``ft`` target it folds wherever
the T count is lower; under ``nisq`` it keeps a form per robot (the fold saves a few CX or none, and the gadget
gets deeper); the ``spatial`` and ``medial`` layouts keep a form per robot on either target, as they place each
robot's sum on its own edges.
"""

from __future__ import annotations

import numpy as np

from qcpp import default_scenario, grid_scenario
from qcpp.estimators.counts import count
from qcpp.gadgets.phase_sums import SumsPhase
from qcpp.ir.circuit import Circuit, Section
from qcpp.lowering.passes import lower
from qcpp.plan.phase_choice import ft_t_count
from qcpp.problem.feasible_cost import SumsGroup, feasible_cost
from qcpp.problem.scenario import Scenario

DEPTH_UP_TO = 10
"""Largest grid side whose gadgets are lowered for their depth (the 20x20 gadget has tens of thousands of gates)."""


def gadget(group: SumsGroup, first_ancilla: int) -> SumsPhase:
    """The arithmetic construction of ``group`` (the plan's ``arithmetic`` choice), ancillas from ``first_ancilla``."""
    forms = tuple(tuple((q, int(w)) for q, w in f) for f in group.forms)
    g = SumsPhase("gamma", forms, group.matrix, (0.0,) * len(forms))
    return SumsPhase(g.gamma, g.forms, g.matrix, g.linear, tuple(range(first_ancilla, first_ancilla + g.num_ancillas)))


def depth(g: SumsPhase, n: int) -> str:
    """ASAP depth of the gadget's lowered gates on ``n`` data qubits and its ancillas."""
    circuit = Circuit([("q", n + g.num_ancillas)], [Section("balance", tuple(g.emit()))])
    return f"{count(lower(circuit)).depth:,}"


def row(name: str, scenario: Scenario) -> str:
    """One table row: the balance gadget with two forms and folded."""
    fc = feasible_cost(scenario)
    (group,) = fc.sums
    one = group.folded()
    assert one is not None, name
    rows = np.random.default_rng(0).integers(0, 2, size=(2_000, fc.num_variables))
    same = bool(np.allclose(group.evaluate(rows), one.evaluate(rows)))
    n = fc.num_variables
    gads = (gadget(group, n), gadget(one, n))
    cells = [name]
    cells += [f"{g.cost().cx:,}" for g in gads]
    cells += [f"{g.cost().rotations:,}" for g in gads]
    cells += [f"{g.num_ancillas:,}" for g in gads]
    small = max(scenario.grid.rows, scenario.grid.cols) <= DEPTH_UP_TO
    cells += [depth(g, n) if small else "" for g in gads]
    cells += [f"{ft_t_count(g.logical_cost()):,}" for g in gads]
    cells.append("yes" if same else "NO")
    return "| " + " | ".join(cells) + " |"


def main() -> None:
    cases = [(f"{n}x{n}/2", default_scenario(n, n, 2)) for n in (3, 4, 5, 6, 8, 10, 20)]
    cases += [("4x4/2, hard obstacle", grid_scenario(4, 4, robots=2, obstacles=[(1, 2)], hard_obstacles=True)),
              ("5x5/2, 2 soft obstacles", grid_scenario(5, 5, robots=2, obstacles=[(1, 3), (2, 2)]))]  # fmt: skip
    print("| scenario | CX two | CX one | rotations two | rotations one | ancillas two | ancillas one "
          "| depth two | depth one | T (ft) two | T (ft) one | same function |")  # fmt: skip
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for name, scenario in cases:
        print(row(name, scenario), flush=True)


if __name__ == "__main__":
    main()
