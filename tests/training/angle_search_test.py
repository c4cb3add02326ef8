"""The expensive search for the best P(optimum): exact gradient, never below its warm starts, monotone in p,
zero below the reach bound, deterministic."""

from __future__ import annotations

import numpy as np
import pytest

from qcpp.problem.ensembles import random_scenario
from qcpp.problem.scenario import scenario_from_dict
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.angle_search import SearchBudget, search_p_optimum
from qcpp.training.layerwise import train_layerwise

SMALL = SearchBudget(random_starts=2, hops=1, maxiter=25)


@pytest.fixture(scope="module")
def qaoa() -> SubspaceQAOA:
    # the first instance of the 3x3/1 ensemble: the optimum needs two layers to carry amplitude
    return SubspaceQAOA(random_scenario(3, 3, 1, 0.1, seed=0, index=0))


def test_gradient_of_p_optimum_matches_finite_differences() -> None:
    q = SubspaceQAOA(scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1]]},
                                         "robots": [{"start": [0, 0], "goal": [0, 2]}, {"start": [2, 0],
                                                                                        "goal": [2, 2]}]}))
    x = np.array([0.3, 0.7, 0.1, 1.9])
    v, g = q.p_optimum_and_gradient(x)
    h = 1e-6
    numeric = [(q.p_optimum(x + h * e) - q.p_optimum(x - h * e)) / (2 * h) for e in np.eye(4)]
    assert v == pytest.approx(q.p_optimum(x), abs=1e-14)
    assert np.allclose(g, numeric, atol=1e-6) and np.abs(g).max() > 1e-3


def test_search_beats_its_warm_starts_and_never_drops_with_depth(qaoa: SubspaceQAOA) -> None:
    default = train_layerwise(qaoa, 2, maxiter=30)
    levels = search_p_optimum(qaoa, 2, warm=[lv.angles for lv in default.levels], budget=SMALL)
    assert [lv.p for lv in levels] == [1, 2]
    for lv, d in zip(levels, default.levels):
        assert lv.p_optimum >= d.p_optimum - 1e-12
        assert qaoa.p_optimum(lv.angles) == pytest.approx(lv.p_optimum, abs=1e-12)
        assert len(lv.angles) == 2 * lv.p and lv.evaluations >= lv.runs
    assert all(b.p_optimum >= a.p_optimum - 1e-12 for a, b in zip(levels, levels[1:]))


def test_ceiling_is_zero_below_the_reach_bound(qaoa: SubspaceQAOA) -> None:
    levels = search_p_optimum(qaoa, 2, budget=SMALL)
    assert levels[0].reach_layers == 2
    assert levels[0].ceiling_upper == 0.0 and levels[0].p_optimum == pytest.approx(0.0, abs=1e-12)
    assert levels[1].ceiling_upper == 1.0 and levels[1].p_optimum > 0.1


def test_a_reached_ceiling_ends_the_search() -> None:
    q = SubspaceQAOA(scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1]]},
                                         "robots": [{"start": [0, 0], "goal": [0, 2]}]}))
    levels = search_p_optimum(q, 3, budget=SMALL)
    assert levels[0].p_optimum > 0.999
    assert [lv.start for lv in levels[1:]] == ["reached", "reached"] and levels[2].angles[2:] == (0.0,) * 4


def test_the_search_is_deterministic(qaoa: SubspaceQAOA) -> None:
    tiny = SearchBudget(random_starts=1, hops=1, maxiter=10)
    a = search_p_optimum(qaoa, 2, budget=tiny, seed=3)
    b = search_p_optimum(qaoa, 2, budget=tiny, seed=3)
    assert [(lv.p_optimum, lv.angles) for lv in a] == [(lv.p_optimum, lv.angles) for lv in b]


@pytest.mark.parametrize(("kwargs", "match"), [({"warm": [[0.1]]}, "warm"), ({"budget": SearchBudget(hops=-1)}, "hops"),
                                               ({"budget": SearchBudget(maxiter=0)}, "maxiter")])
def test_bad_arguments(qaoa: SubspaceQAOA, kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        search_p_optimum(qaoa, 1, **kwargs)
