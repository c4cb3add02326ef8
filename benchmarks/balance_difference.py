"""The balance term as one register per balanced pair (the difference of two path lengths), against one register
per robot.

Run: ``python benchmarks/balance_difference.py`` (a few seconds).

The balance term is ``sum_ab M_ab G_a G_b`` with ``G_r`` robot ``r``'s path length, a linear form over its edge
bits; on two robots it is ``c (G_1 - G_2)^2``. Its arithmetic construction
(:class:`qcpp.gadgets.phase_sums.SumsPhase`) can take one form per robot: a popcount register each, then RZ on
their bits and RZZ on every pair of bits the matrix couples (within each register and across). Or it can take the
same function as ``sum_(a<b) w_ab (G_a - G_b)^2`` (:meth:`qcpp.problem.feasible_cost.SumsGroup.folded`): one
gadget per balanced pair, each on the single form ``G_a - G_b`` (robot ``b``'s weights negated, its bits flipped
with X), run one after the other. One register per pair has far fewer bit pairs to phase, and only one pair's
ancillas are needed at a time; the price is more adders (a robot in two pairs is summed twice) and one tree per
pair where the robots' trees ran side by side.

Per scenario, the table prints the balance both ways: lowered CX, rotations and clean ancillas (exact:
:meth:`SumsPhase.cost` is the lowered cost of the gates it emits, which ``tests/compiler/phase_test.py`` checks),
the depth of the lowered gates (ASAP layers, :func:`qcpp.estimators.counts.count`; grids up to 10x10), and the
``ft`` model's T count (:func:`qcpp.plan.phase_choice.ft_t_count`: AND 4 T, rotation 30 T). ``same function``
checks on 2,000 random bit rows that the pairs' groups sum to the balance group's values.

What the plan does with it (:func:`qcpp.plan.phase_choice.prefer_folded`): on the ``ft`` target it folds wherever
the T count is lower; under ``nisq`` it keeps a form per robot (the fold saves a few CX on two robots, costs CX on
more, and deepens the circuit); the ``spatial`` and ``medial`` layouts keep a form per robot on either target, as
they place each robot's sum on its own edges.
"""

from __future__ import annotations

import argparse

import numpy as np

from qcpp import default_scenario, grid_scenario
from qcpp.estimators.counts import count
from qcpp.gadgets.phase_sums import SumsPhase
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import lower
from qcpp.plan.phase_choice import ft_t_count
from qcpp.problem.feasible_cost import SumsGroup, feasible_cost
from qcpp.problem.scenario import Scenario, scenario_from_dict

DEPTH_UP_TO = 10
"""Largest grid side whose gadgets are lowered for their depth (the 20x20 gadgets have tens of thousands of gates)."""


def gadget(group: SumsGroup, first_ancilla: int) -> SumsPhase:
    """The arithmetic construction of ``group`` (the plan's ``arithmetic`` choice), ancillas from ``first_ancilla``."""
    forms = tuple(tuple((q, int(w)) for q, w in f) for f in group.forms)
    g = SumsPhase("gamma", forms, group.matrix, (0.0,) * len(forms))
    return SumsPhase(g.gamma, g.forms, g.matrix, g.linear, tuple(range(first_ancilla, first_ancilla + g.num_ancillas)))


def depth(gadgets: list[SumsPhase], n: int) -> str:
    """ASAP depth of the gadgets' lowered gates, one after the other, on ``n`` data qubits and their ancillas."""
    width = n + max(g.num_ancillas for g in gadgets)
    circuit = Circuit([("q", width)], [Section("balance", tuple(g.emit())) for g in gadgets])
    return f"{count(lower(circuit)).depth:,}"


def row(name: str, scenario: Scenario) -> str:
    """One table row: the balance with a form per robot and folded per pair."""
    fc = feasible_cost(scenario)
    (group,) = fc.sums
    parts = group.folded()
    assert parts is not None, name
    rows = np.random.default_rng(0).integers(0, 2, size=(2_000, fc.num_variables))
    same = bool(np.allclose(group.evaluate(rows), sum(p.evaluate(rows) for p in parts)))
    n = fc.num_variables
    ways = ([gadget(group, n)], [gadget(p, n) for p in parts])
    costs = [Cost.sum(g.cost() for g in way) for way in ways]
    cells = [name, str(len(parts))]
    cells += [f"{c.cx:,}" for c in costs]
    cells += [f"{c.rotations:,}" for c in costs]
    cells += [f"{max(g.num_ancillas for g in way):,}" for way in ways]
    small = max(scenario.grid.rows, scenario.grid.cols) <= DEPTH_UP_TO
    cells += [depth(way, n) if small else "" for way in ways]
    cells += [f"{ft_t_count(Cost.sum(g.logical_cost() for g in way)):,}" for way in ways]
    cells.append("yes" if same else "NO")
    return "| " + " | ".join(cells) + " |"


def all_pairs(rows: int, cols: int, robots: int) -> Scenario:
    """The default scenario with every pair of robots balanced (``objective.balance = "all-pairs"``)."""
    d = default_scenario(rows, cols, robots)
    robots_ = [{"start": list(r.start), "goal": list(r.goal)} for r in d.robots]
    spec = {"grid": {"rows": rows, "cols": cols}, "robots": robots_, "objective": {"balance": "all-pairs"}}
    return scenario_from_dict(spec)


def main() -> None:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    cases = [(f"{n}x{n}/2", default_scenario(n, n, 2)) for n in (3, 4, 5, 6, 8, 10, 20)]
    cases += [("4x4/2, hard obstacle", grid_scenario(4, 4, robots=2, obstacles=[(1, 2)], hard_obstacles=True)),
              ("5x5/2, 2 soft obstacles", grid_scenario(5, 5, robots=2, obstacles=[(1, 3), (2, 2)]))]  # fmt: skip
    cases += [(f"{r}x{r}/{k}", default_scenario(r, r, k)) for r, k in ((4, 3), (6, 3), (8, 3), (10, 4), (20, 4))]
    cases += [(f"{r}x{r}/{k}, all pairs", all_pairs(r, r, k)) for r, k in ((4, 3), (6, 4))]
    print("| scenario | pairs | CX robots | CX pairs | rotations robots | rotations pairs | ancillas robots "
          "| ancillas pairs | depth robots | depth pairs | T (ft) robots | T (ft) pairs | same function |")  # fmt: skip
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for name, scenario in cases:
        print(row(name, scenario), flush=True)


if __name__ == "__main__":
    main()
