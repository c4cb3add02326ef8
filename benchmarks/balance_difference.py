"""The two-robot balance term as one register of the difference of the path lengths, against two registers.

Run: ``python benchmarks/balance_difference.py`` (a few seconds).

The balance term of two robots is ``c (G_1 - G_2)^2`` with ``G_r`` robot ``r``'s path length, a linear form over
its edge bits. The plan phases it by arithmetic (:class:`qcpp.gadgets.phase_sums.SumsPhase`) on two forms with the
matrix ``c ((1, -1), (-1, 1))``: two popcount registers, then RZ on their bits and RZZ on every pair of bits the
matrix couples (within each register and across). The same function is ``c D^2`` with the single form
``D = G_1 - G_2`` (robot 2's weights negated; the gadget flips those bits with X): one register, so fewer bit pairs
to phase, at the price of a few more adders and ancillas. Any balance matrix of rank one, ``c v v^T`` with
integer ``v``, folds the same way; three or more robots give a matrix of higher rank.

Per default two-robot scenario (and two with obstacles), the table prints the balance gadget both ways:
lowered CX, rotations and clean ancillas (exact: :meth:`SumsPhase.cost` is the lowered cost of the gates it emits,
which ``tests/compiler/phase_test.py`` checks), and the ``ft`` model's T count of the gadget
(:func:`qcpp.plan.phase_choice.ft_t_count`: AND 4 T, rotation 30 T). ``same function`` checks on 2,000 random bit
rows that the folded group evaluates to the balance group's values.

The folded form is not what the plan builds: on the medial and heavy-hex layouts each robot's popcount drifts to
its own sink where the robots' patches meet (:func:`qcpp.plan.phase_layout.balance_sinks`), which one form across
both robots' patches would lose. This script measures what the fold would save elsewhere (all-to-all, ``ft``).
"""

from __future__ import annotations

import numpy as np

from qcpp import default_scenario, grid_scenario
from qcpp.gadgets.phase_sums import SumsPhase
from qcpp.plan.phase_choice import ft_t_count
from qcpp.problem.feasible_cost import SumsGroup, feasible_cost
from qcpp.problem.scenario import Scenario


def folded(group: SumsGroup) -> SumsGroup | None:
    """``group`` as one form when its matrix is ``c v v^T`` with ``v = (1, -1)``, else ``None``."""
    m = group.matrix
    if len(group.forms) != 2 or not (m[0][0] == m[1][1] == -m[0][1] == -m[1][0] != 0):
        return None
    form = group.forms[0] + tuple((q, -w) for q, w in group.forms[1])
    return SumsGroup(group.name, (form,), ((m[0][0],),), group.integral, group.unit)


def gadget(group: SumsGroup) -> SumsPhase:
    """The arithmetic construction of ``group`` (the plan's ``arithmetic`` choice)."""
    forms = tuple(tuple((q, int(w)) for q, w in f) for f in group.forms)
    return SumsPhase("gamma", forms, group.matrix, (0.0,) * len(forms))


def row(name: str, scenario: Scenario) -> str:
    """One table row: the balance gadget with two forms and folded."""
    fc = feasible_cost(scenario)
    (group,) = fc.sums
    one = folded(group)
    assert one is not None, name
    rows = np.random.default_rng(0).integers(0, 2, size=(2_000, fc.num_variables))
    same = bool(np.allclose(group.evaluate(rows), one.evaluate(rows)))
    cells = [name]
    gads = (gadget(group), gadget(one))
    cells += [f"{g.cost().cx:,}" for g in gads]
    cells += [f"{g.cost().rotations:,}" for g in gads]
    cells += [f"{g.num_ancillas:,}" for g in gads]
    cells += [f"{ft_t_count(g.logical_cost()):,}" for g in gads]
    cells.append("yes" if same else "NO")
    return "| " + " | ".join(cells) + " |"


def main() -> None:
    cases = [(f"{n}x{n}/2", default_scenario(n, n, 2)) for n in (3, 4, 5, 6, 8, 10, 20)]
    cases += [("4x4/2, hard obstacle", grid_scenario(4, 4, robots=2, obstacles=[(1, 2)], hard_obstacles=True)),
              ("5x5/2, 2 soft obstacles", grid_scenario(5, 5, robots=2, obstacles=[(1, 3), (2, 2)]))]  # fmt: skip
    print("| scenario | CX two | CX one | rotations two | rotations one | ancillas two | ancillas one "
          "| T (ft) two | T (ft) one | same function |")  # fmt: skip
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for name, scenario in cases:
        print(row(name, scenario), flush=True)


if __name__ == "__main__":
    main()
