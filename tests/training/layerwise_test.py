"""Layer-by-layer training: warm starts that never lose ground, the counts, reproducibility, the schedule."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from qcpp.problem.scenario import scenario_from_dict
from qcpp.problem.scenario_io import load_scenario
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.layerwise import SHOTS_PER_ESTIMATE, extend_angles, train_layerwise
from qcpp.training.objectives import make_objective
from qcpp.training.training import cost_scale, initial_angles, interp_angles, train

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
TWO_3x3 = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[1, 1]]},
                              "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}]})


@pytest.fixture(scope="module")
def two() -> SubspaceQAOA:
    return SubspaceQAOA(TWO_3x3)


def test_extended_angles_give_the_same_state(two: SubspaceQAOA) -> None:
    x = np.array([0.04, 0.8, 0.09, 0.3])
    assert np.allclose(two.state(extend_angles(x)), two.state(x), atol=1e-13)


@pytest.mark.parametrize("objective", ["gibbs", "cvar", "expectation"])
def test_each_level_is_at_least_as_good_as_the_last(two: SubspaceQAOA, objective: str) -> None:
    res = train_layerwise(two, 4, objective, maxiter=40)  # type: ignore[arg-type]
    values = [lv.value for lv in res.levels]
    assert [lv.p for lv in res.levels] == [1, 2, 3, 4]
    assert all(b <= a + 1e-9 * max(1.0, abs(a)) for a, b in zip(values, values[1:]))
    assert res.objective == objective and all(lv.objective == objective for lv in res.levels)
    assert res.best.value == pytest.approx(
        make_objective(objective, cost_scale(two))(two.cost_distribution_index()[0],  # type: ignore[arg-type]
                                                   two.level_probabilities(two.state(res.angles)))[0])
    assert res.p_optimum == pytest.approx(two.p_optimum(res.angles))


def test_starts_and_counts(two: SubspaceQAOA) -> None:
    res = train_layerwise(two, 2, random_starts=1, seed=7, maxiter=30)
    assert res.runs == 2 + 4  # ramp + 1 random at p = 1; interp, extended, ramp + 1 random at p = 2
    # the kept p = 1 run is one of the two starts, reproduced by a direct call
    obj = make_objective("gibbs", cost_scale(two))
    direct = [train(two, 1, "lbfgsb", init=x0, maxiter=30, objective=obj)
              for x0 in (initial_angles(two, 1, "linear-ramp"), initial_angles(two, 1, "random", seed=7))]
    kept = min(direct, key=lambda r: r.value)
    assert res.levels[0].angles == kept.angles and res.levels[0].trace == kept.trace
    second = [train(two, 2, "lbfgsb", init=x0, maxiter=30, objective=obj)
              for x0 in (interp_angles(kept.angles), extend_angles(kept.angles), initial_angles(two, 2, "linear-ramp"),
                         initial_angles(two, 2, "random", seed=7 + 2000))]
    assert res.levels[1].angles == min(second, key=lambda r: r.value).angles
    single = train_layerwise(two, 2, random_starts=1, seed=7, maxiter=30, restart_every_level=False)
    assert single.runs == 2 + 2 and single.levels[0].angles == kept.angles  # interp + extended only at p = 2
    assert single.levels[1].angles == min(second[:2], key=lambda r: r.value).angles
    runs = [*direct, *second]
    assert res.num_evaluations == sum(r.num_evaluations for r in runs)
    assert res.num_gradients == sum(r.num_gradients for r in runs)
    assert res.circuit_estimates == sum(r.num_evaluations + 4 * r.p * r.num_gradients for r in runs)
    assert res.shots() == res.circuit_estimates * SHOTS_PER_ESTIMATE
    assert res.trace == res.levels[0].trace + res.levels[1].trace
    again = train_layerwise(two, 2, random_starts=1, seed=7, maxiter=30)
    assert again.angles == res.angles and again.trace == res.trace
    json.dumps(res.as_dict())


def test_paper_3x3_is_solved() -> None:
    res = train_layerwise(SubspaceQAOA(load_scenario(EXAMPLES / "paper_3x3.toml")), 1)
    assert res.p_optimum > 0.9


def test_gibbs_beats_cvar_on_the_optimum_of_3x3() -> None:
    """CVaR_0.2 stops rewarding once 20% sits on the optimum; the Gibbs objective keeps going (issue #19)."""
    s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    q = SubspaceQAOA(s)
    gibbs, cvar = train_layerwise(q, 3, "gibbs"), train_layerwise(q, 3, "cvar")
    assert gibbs.p_optimum > cvar.p_optimum + 0.1


def test_bad_arguments(two: SubspaceQAOA) -> None:
    for kwargs, match in (({"p": 0}, "p must be"), ({"p": 1, "random_starts": -1}, "random_starts"),
                          ({"p": 1, "maxiter": -1}, "maxiter"), ({"p": 1, "objective": "median"}, "objective")):
        with pytest.raises(ValueError, match=match):
            train_layerwise(two, **kwargs)  # type: ignore[arg-type]


def test_doctests() -> None:
    import doctest

    import qcpp.training.layerwise

    assert doctest.testmod(qcpp.training.layerwise).failed == 0


@pytest.mark.heavy  # about 20 s on 2 cores
def test_issue_19_goal_on_two_robots_4x4() -> None:
    """The single-start schedule (docs/experiments.md section 5) puts at least 0.2 on the optimum of two_robots_4x4
    at some p <= 8 (here p = 5), where training on <C> never leaves the initial paths."""
    q = SubspaceQAOA(load_scenario(EXAMPLES / "two_robots_4x4.toml"))
    res = train_layerwise(q, 5, restart_every_level=False, eta=5 / cost_scale(q))
    assert res.p_optimum >= 0.2
    assert train_layerwise(q, 2, "expectation").p_optimum < 1e-10


def test_mixer_warm_option_adds_one_start_per_level_and_counts_it(two: SubspaceQAOA) -> None:
    plain = train_layerwise(two, 2, maxiter=20)
    warm = train_layerwise(two, 2, maxiter=20, mixer_warm=True)
    assert warm.runs == plain.runs + 2 and plain.mixer_evaluations == 0 < warm.mixer_evaluations
    assert warm.levels[0].value <= plain.levels[0].value + 1e-12  # level 1's starts are a superset
    values = [lv.value for lv in warm.levels]
    assert all(b <= a + 1e-9 * max(1.0, abs(a)) for a, b in zip(values, values[1:]))
    assert warm.as_dict()["mixer_evaluations"] == warm.mixer_evaluations
