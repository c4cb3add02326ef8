"""The balance folded into one form per balanced pair: the same function, chosen where it is cheaper, kept per
robot where the layout needs it.

* hypothesis: a group whose matrix is symmetric with rows summing to zero (any weighted robot graph, as
  :func:`qcpp.problem.feasible_cost.balance_matrix` builds) folds into one ``w (G_a - G_b)^2`` group per coupled
  pair, and their sum evaluates to the group's values on random bit rows; a matrix whose rows do not sum to zero
  does not fold;
* the ``ft`` plan takes the fold (one form over both robots' edges per pair, fewer T) and its lowered phase
  separator applies ``exp(-i gamma (C - K))`` on every feasible assignment of 3x3/2, on samples of 4x4/2 with a
  hard obstacle and of three robots in a chain and in all pairs; ``nisq`` keeps a form per robot;
* the class count (:func:`qcpp.plan.phase_classes.phase_layer`) folds exactly where the plan does;
* the ``spatial`` and ``medial`` layouts keep a form per robot on ``ft`` too (their sinks and trees are per robot).
"""

from __future__ import annotations

import itertools
from collections import Counter

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp import grid_scenario
from qcpp.gadgets.phase_sums import SumsPhase
from qcpp.plan.options import PlanOptions
from qcpp.plan.phase import phase_plan
from qcpp.plan.phase_classes import phase_layer
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.feasible_cost import SumsGroup, balance_matrix, difference_pairs
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict

from .phase_test import check_states, lowered, sample_combos


def _balance(g: object) -> bool:
    """A balance gadget (the ``ft`` target's Hamming-weight phasing is a one-form SumsPhase with ``M = 0``)."""
    return isinstance(g, SumsPhase) and any(x for row in g.matrix for x in row)


def _sums(plan: object) -> list[SumsPhase]:
    return [g for g in plan.gadgets("gamma_0") if _balance(g)]  # type: ignore[attr-defined]


@settings(max_examples=80, deadline=None)
@given(
    sizes=st.lists(st.integers(1, 6), min_size=2, max_size=4),
    couplings=st.lists(st.sampled_from([0.0, 0.0, 0.5, 1.0, 3.0, -2.0]), min_size=6, max_size=6),
    perturb=st.booleans(),
    seed=st.integers(0, 2**16),
)
def test_a_balance_matrix_folds_into_pair_differences_of_the_same_function(
    sizes: list[int], couplings: list[float], perturb: bool, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    k = len(sizes)
    pairs = [(a, b) for a in range(k) for b in range(a + 1, k)]
    m = np.zeros((k, k))
    for (a, b), w in zip(pairs, couplings):
        m[a, a] += w
        m[b, b] += w
        m[a, b] -= w
        m[b, a] -= w
    if perturb:
        m[0, 0] += 1.0  # its row no longer sums to zero
    qubits = iter(range(sum(sizes)))
    forms = tuple(tuple((next(qubits), float(rng.integers(-3, 4) or 1)) for _ in range(n)) for n in sizes)
    group = SumsGroup("balance", forms, tuple(tuple(float(x) for x in row) for row in m), True)
    folded = group.folded()
    coupled = [(a, b, w) for (a, b), w in zip(pairs, couplings) if w]
    assert (folded is not None) == (not perturb and bool(coupled))
    if folded is None:
        return
    assert [f.matrix for f in folded] == [((w,),) for _, _, w in coupled]
    assert [len(f.forms[0]) for f in folded] == [sizes[a] + sizes[b] for a, b, _ in coupled]
    rows = rng.integers(0, 2, size=(200, sum(sizes)))
    assert np.allclose(group.evaluate(rows), sum(f.evaluate(rows) for f in folded))


def test_a_balance_of_three_robots_folds_per_pair() -> None:
    assert difference_pairs(balance_matrix(3, [(0, 1), (1, 2)], 1.0)) == ((0, 1, 1.0), (1, 2, 1.0))
    assert difference_pairs(balance_matrix(3, [(0, 2)], 2.0)) == ((0, 2, 2.0),)
    assert difference_pairs(balance_matrix(3, [], 2.0)) is None


@pytest.mark.parametrize("rows", [3, 4, 5])
def test_ft_folds_the_two_robot_balance_and_nisq_does_not(rows: int) -> None:
    s = default_scenario(rows, rows, 2)
    ft, kept = phase_plan(s, target="ft"), phase_plan(s, target="ft", pooled=False)
    (one,) = _sums(ft)
    assert len(one.forms) == 1 and len(one.forms[0]) == sum(len(f) for f in _sums(kept)[0].forms)
    assert ft.score() < kept.score()  # the fold is taken because it is cheaper under ft
    assert [len(g.forms) for g in _sums(phase_plan(s))] in ([2], [])  # nisq: a form per robot (or couplings)
    assert any("folded" in row["group"] for row in ft.explain())


def _hard_obstacle() -> Scenario:
    return grid_scenario(4, 4, robots=[((0, 0), (3, 3)), ((3, 0), (0, 3))], obstacles=[(1, 2)], hard_obstacles=True)


def test_the_folded_phase_is_exact_on_every_feasible_assignment() -> None:
    s = default_scenario(3, 3, 2)
    plan = phase_plan(s, target="ft")
    assert [len(g.forms) for g in _sums(plan)] == [1]
    combos = list(itertools.product(*(enumerate_paths(s, r) for r in range(s.num_robots))))
    others = [np.random.default_rng(i).integers(0, 2, s.num_variables).tolist() for i in range(3)]
    check_states(s, plan, lowered(plan, s.num_variables), combos, others)


def test_the_folded_phase_is_exact_with_a_hard_obstacle() -> None:
    s = _hard_obstacle()
    plan = phase_plan(s, target="ft")
    assert [len(g.forms) for g in _sums(plan)] == [1]
    check_states(s, plan, lowered(plan, s.num_variables), sample_combos(s, 12))


def _three_robots(balance: str) -> Scenario:
    return scenario_from_dict({
        "grid": {"rows": 3, "cols": 4},
        "robots": [{"start": [0, 0], "goal": [2, 3]}, {"start": [2, 0], "goal": [0, 3]},
                   {"start": [0, 1], "goal": [2, 2]}],
        "objective": {"balance": balance},
    })  # fmt: skip


@pytest.mark.parametrize("balance", ["chain", "all-pairs"])
def test_three_robots_fold_into_one_gadget_per_pair_and_stay_exact(balance: str) -> None:
    s = _three_robots(balance)
    plan = phase_plan(s, target="ft")
    pairs = 2 if balance == "chain" else 3
    assert [len(g.forms) for g in _sums(plan)] == [1] * pairs
    kept = phase_plan(s, target="ft", pooled=False)
    assert plan.score() < kept.score() and plan.num_ancillas <= kept.num_ancillas
    check_states(s, plan, lowered(plan, s.num_variables), sample_combos(s, 12))


@pytest.mark.parametrize("shape", [(4, 4, 2), (5, 5, 2), (6, 5, 2), (5, 5, 3), (8, 8, 3), (10, 10, 4)])
@pytest.mark.parametrize("budget", [None, 40, 120])
def test_the_class_count_folds_where_the_plan_does(shape: tuple[int, int, int], budget: int | None) -> None:
    s = default_scenario(*shape)
    layer = phase_layer(s, "ft", "feasible", "cx", budget)
    plan = phase_plan(s, target="ft", ancilla_budget=budget)
    if layer is None:  # the plan decides there (a variant other than the arithmetic)
        return
    counted: Counter = Counter()
    for kind, n in layer.kinds():
        counted[kind.key] += n
    assert counted == Counter(g.kind for g in plan.gadgets("gamma"))
    assert layer.num_ancillas == plan.num_ancillas


@pytest.mark.parametrize("layout", ["spatial", "medial"])
def test_the_place_aware_layouts_keep_a_form_per_robot(layout: str) -> None:
    s = default_scenario(4, 4, 2)
    plan = qaoa_plan(s, 1, PlanOptions(target="ft", phase_layout=layout))  # type: ignore[arg-type]
    sums = [g for name, g in plan.sections() if name == "phase_0" and _balance(g)]
    assert [len(g.forms) for g in sums] == [2] and all(g.sites for g in sums)
    pooled = qaoa_plan(s, 1, PlanOptions(target="ft", phase_layout="pooled"))
    assert [len(g.forms) for name, g in pooled.sections() if name == "phase_0" and _balance(g)] == [1]
