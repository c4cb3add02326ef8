"""Node visit terms phased in Hamming-weight batches (``ft``, pooled layout): exact, cheaper, no qubit added.

* the ``ft`` plan of 3x3/2 holds a batch, and its lowered phase separator applies ``exp(-i gamma (C - K))`` on
  every feasible assignment (and keeps its ancillas clean on random non-feasible inputs); samples of 4x4/3 and of
  4x4/2 with interior endpoints around a hard obstacle likewise;
* every batch fits in the ancillas the plan's other gadgets need anyway, and it scores better under ``ft`` than
  its nodes' own gadgets;
* ``nisq`` and the ``spatial`` layout never batch; the class count batches as the plan does
  (``balance_fold_test.py`` compares the kinds);
* a batch's lowered cost is its gates' (``check_gadget``), with nodes that share edges.
"""

from __future__ import annotations

import itertools
from collections import Counter

import numpy as np
import pytest

from qcpp.estimators.crosscheck import interior_endpoints
from qcpp.gadgets.phase_visits import VisitPhase
from qcpp.gadgets.visit_batch import VisitBatch, visit_batch_ancillas
from qcpp.plan.gadget_examples import check_gadget
from qcpp.plan.options import PlanOptions
from qcpp.plan.phase import phase_plan
from qcpp.plan.phase_choice import score, visit_batches
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario

from .phase_test import check_states, lowered, sample_combos


def _batches(plan: object) -> list[VisitBatch]:
    return [g for g in plan.gadgets("gamma_0") if isinstance(g, VisitBatch)]  # type: ignore[attr-defined]


def test_every_feasible_assignment_of_3x3_2_gets_its_phase() -> None:
    s = default_scenario(3, 3, 2)
    plan = phase_plan(s, target="ft")
    assert _batches(plan)
    combos = list(itertools.product(*(enumerate_paths(s, r) for r in range(s.num_robots))))
    others = [np.random.default_rng(i).integers(0, 2, s.num_variables).tolist() for i in range(4)]
    check_states(s, plan, lowered(plan, s.num_variables), combos, others)


@pytest.mark.parametrize("which", ["4x4/3", "4x4/2 interior, hard obstacle"])
def test_sampled_assignments_get_their_phase(which: str) -> None:
    s = default_scenario(4, 4, 3) if which == "4x4/3" else interior_endpoints(4, 4, "hard")
    plan = phase_plan(s, target="ft")
    assert _batches(plan)
    others = [np.random.default_rng(i).integers(0, 2, s.num_variables).tolist() for i in range(3)]
    check_states(s, plan, lowered(plan, s.num_variables), sample_combos(s, 10), others)


@pytest.mark.parametrize("shape", [(3, 3, 2), (4, 4, 3), (6, 6, 3), (10, 10, 4)])
def test_batches_fit_in_the_ancillas_the_plan_has_and_are_cheaper(shape: tuple[int, int, int]) -> None:
    plan = phase_plan(default_scenario(*shape), target="ft")
    gadgets = plan.gadgets("gamma_0")
    others = max(g.needs()[0] for g in gadgets if not isinstance(g, VisitBatch))
    for b in _batches(plan):
        assert b.needs()[0] == visit_batch_ancillas(b.kind.sizes, len(b.nodes)) <= others
        alone = VisitPhase("gamma", b.coefficient, b.nodes[0], (), True)
        n = len(b.nodes)
        assert score(b.cost(), b.logical_cost(), "ft") < score(n * alone.cost(), n * alone.logical_cost(), "ft")
        assert check_gadget(b) == []


def test_nisq_and_the_spatial_layout_keep_a_gadget_per_node() -> None:
    s = default_scenario(4, 4, 3)
    assert not _batches(phase_plan(s)) and not _batches(phase_plan(s, target="ft", pooled=False))
    plan = qaoa_plan(s, 1, PlanOptions(target="ft", phase_layout="spatial"))
    assert not any(isinstance(g, VisitBatch) for _, g in plan.sections())
    assert visit_batches((4, 4), 8.0, 10, 1_000, "nisq", "cx", None) == ()


def test_batch_sizes_follow_the_pool_and_the_budget() -> None:
    sizes = (4, 4, 4, 4)
    assert visit_batches(sizes, 8.0, 10, visit_batch_ancillas(sizes, 3), "ft", "cx", None) == (3, 3, 3, 1)
    assert visit_batches((2, 2), 8.0, 10, visit_batch_ancillas((2, 2), 3), "ft", "cx", None) == (3, 3, 3)
    assert visit_batches(sizes, 8.0, 10, 1_000, "ft", "cx", visit_batch_ancillas(sizes, 2)) == (2, 2, 2, 2, 2)
    assert visit_batches(sizes, 8.0, 10, 0, "ft", "cx", None) == ()
    assert visit_batches(sizes, 0.0, 10, 1_000, "ft", "cx", None) == ()
    batches = visit_batches(sizes, 8.0, 100, 400, "ft", "cx", None)
    assert sum(batches) <= 100 and Counter(batches).most_common(1)[0][0] == max(batches)


def test_a_batch_refuses_nodes_that_share_an_edge() -> None:
    with pytest.raises(ValueError, match="share no edge"):
        VisitBatch("gamma", 8.0, (((0, 1), (2, 3)), ((1, 4), (5, 6))), ())
    with pytest.raises(ValueError, match="same visitor sizes"):
        VisitBatch("gamma", 8.0, (((0, 1), (2, 3)), ((4, 5, 6), (7, 8))), ())


def test_the_plan_batches_nodes_of_one_colour() -> None:
    s = default_scenario(6, 6, 3)
    colour = {tuple(v): sum(divmod(g.node, s.grid.cols)) % 2 for g in _groups(s) for v in [g.visitors]}
    for b in _batches(phase_plan(s, target="ft")):
        assert len({colour[tuple(node)] for node in b.nodes}) == 1


def _groups(s: Scenario) -> tuple:
    from qcpp.problem.feasible_cost import feasible_cost

    return feasible_cost(s).visits
