"""QAOA training on the feasible-subspace simulator: optimisers, initialisations, reproducibility."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from qcpp.problem.cost import cost
from qcpp.problem.paths import enumerate_paths, initial_path
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.problem.scenario_io import load_scenario
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.training import (
    TrainingResult,
    cost_scale,
    initial_angles,
    interp_angles,
    most_probable,
    train,
)

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "paper_3x3.toml"


def paper_3x3() -> Scenario:
    if EXAMPLE.exists():
        return load_scenario(EXAMPLE)
    return scenario_from_dict(  # the same scenario, should the example file move
        {
            "grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1]]},
            "robots": [{"start": [0, 0], "goal": [0, 2]}],
        }
    )


@pytest.fixture(scope="module")
def qaoa() -> SubspaceQAOA:
    return SubspaceQAOA(paper_3x3())


def test_the_scenario_is_a_real_test(qaoa: SubspaceQAOA) -> None:
    s = qaoa.scenario
    costs = {m: cost(s, [m]) for m in enumerate_paths(s, 0)}
    best = min(costs.values())
    assert costs[initial_path(s, 0)] > best  # the initial state has no optimal weight
    assert qaoa.optimum()[0] == best
    assert sorted(qaoa.bases[0]) == sorted(costs)  # the move graph is connected here


def test_nesterov_finds_the_optimum_and_is_reproducible(qaoa: SubspaceQAOA) -> None:
    a = train(qaoa, p=1, optimizer="nesterov", init="random", seed=4, maxiter=40)
    assert qaoa.p_optimum([0.0, 0.0]) == 0.0  # the QAOA initial state has no weight on the optimum
    assert a.p_optimum > max(0.9, a.initial_p_optimum)
    assert a.expectation < a.initial_expectation
    assert a.trace[0] == a.initial_expectation and a.trace[-1] == pytest.approx(a.expectation, abs=1e-12)
    assert len(a.trace) == 41
    assert a.num_gradients == 40 and a.num_evaluations == 2 + 40 + 40
    b = train(qaoa, p=1, optimizer="nesterov", init="random", seed=4, maxiter=40)
    assert a.trace == b.trace and a.angles == b.angles and a.initial_angles == b.initial_angles
    c = train(qaoa, p=1, optimizer="nesterov", init="random", seed=5, maxiter=40)
    assert c.initial_angles != a.initial_angles and c.trace != a.trace


def test_nesterov_on_the_raw_cost_is_the_plain_update(qaoa: SubspaceQAOA) -> None:
    """normalize=False is x <- x - a, a <- m a + eta grad E(x - m a), checked step by step."""
    res = train(qaoa, p=1, init="linear-ramp", maxiter=3, normalize=False, step=0.01, momentum=0.5)
    x = np.array(res.initial_angles)
    a = np.zeros(2)
    for k in range(3):
        a = 0.5 * a + 0.01 * qaoa.gradient(x - 0.5 * a)
        x = x - a
        assert res.trace[k + 1] == pytest.approx(qaoa.expectation(x), rel=1e-12)
    assert np.allclose(res.angles, x, rtol=1e-12)
    norm = train(qaoa, p=1, init="linear-ramp", maxiter=1, step=0.01, momentum=0.5)
    x1 = np.array(res.initial_angles) - 0.01 / cost_scale(qaoa) * qaoa.gradient(np.array(res.initial_angles))
    assert np.allclose(norm.angles, x1, rtol=1e-12)


@pytest.mark.parametrize("optimizer", ["cobyla", "lbfgsb"])
def test_scipy_optimisers_lower_the_expectation(qaoa: SubspaceQAOA, optimizer: str) -> None:
    res = train(qaoa, p=2, optimizer=optimizer, init="linear-ramp", maxiter=60)  # type: ignore[arg-type]
    assert res.expectation < res.initial_expectation - 1.0
    assert res.p_optimum > res.initial_p_optimum
    assert res.trace[0] == res.initial_expectation
    if optimizer == "cobyla":  # the trace is every evaluation; COBYLA returns the best one
        assert res.num_gradients == 0
        assert len(res.trace) <= 60
        assert min(res.trace) == pytest.approx(res.expectation, abs=1e-12)
    else:  # the trace is the start and every iterate
        assert res.num_gradients > 0
        assert len(res.trace) > 2
        assert res.trace[-1] == pytest.approx(res.expectation, abs=1e-12)
    again = train(qaoa, p=2, optimizer=optimizer, init="linear-ramp", maxiter=60)  # type: ignore[arg-type]
    assert again.trace == res.trace and again.angles == res.angles


def test_interp_trains_level_by_level(qaoa: SubspaceQAOA) -> None:
    res = train(qaoa, p=3, optimizer="lbfgsb", init="interp", maxiter=20)
    assert [s.p for s in res.stages] == [1, 2]
    assert all(not s.stages for s in res.stages)
    assert res.stages[0].initial_angles == tuple(initial_angles(qaoa, 1, "linear-ramp"))
    assert np.allclose(res.stages[1].initial_angles, interp_angles(res.stages[0].angles))
    assert np.allclose(res.initial_angles, interp_angles(res.stages[1].angles))
    own = res.num_evaluations - sum(s.num_evaluations for s in res.stages)
    assert own >= 2 and all(s.num_evaluations >= 2 for s in res.stages)
    assert res.seconds >= sum(s.seconds for s in res.stages)
    json.dumps(res.as_dict())  # JSON-ready


def test_interp_formula() -> None:
    # Zhou et al.: v'_i = (i-1)/p v_{i-1} + (p-i+1)/p v_i, 1-based, zero-padded
    g, b = np.array([0.3, 0.6, 0.9]), np.array([1.2, 0.8, 0.4])
    x = np.empty(6)
    x[0::2], x[1::2] = g, b
    out = interp_angles(x)
    p = 3
    for vec, got in ((g, out[0::2]), (b, out[1::2])):
        pad = [0.0, *vec, 0.0]
        want = [(i - 1) / p * pad[i - 1] + (p - i + 1) / p * pad[i] for i in range(1, p + 2)]
        assert np.allclose(got, want)
    assert np.allclose(interp_angles([0.5, 0.25]), [0.5, 0.25, 0.5, 0.25])


def test_initial_angles(qaoa: SubspaceQAOA) -> None:
    sigma = cost_scale(qaoa)
    probs = np.bincount(qaoa.cost_levels()[1].reshape(-1)) / qaoa.dimension  # type: ignore[index]
    values = qaoa.cost_levels()[0]  # type: ignore[index]
    assert sigma == pytest.approx(np.sqrt(probs @ values**2 - (probs @ values) ** 2))
    r = initial_angles(qaoa, 50, "random", seed=1)
    assert np.array_equal(r, initial_angles(qaoa, 50, "random", seed=1))
    assert np.all((r[0::2] >= 0) & (r[0::2] < np.pi / sigma)) and np.all((r[1::2] >= 0) & (r[1::2] < np.pi))
    ramp = initial_angles(qaoa, 4, "linear-ramp")
    assert np.all(np.diff(ramp[0::2]) > 0) and np.all(np.diff(ramp[1::2]) < 0)
    assert ramp[0] + ramp[-2] == pytest.approx(0.75 / sigma)  # t_k + t_{p-1-k} = 1
    assert ramp[1] + ramp[-1] == pytest.approx(1.5)


def test_most_probable(qaoa: SubspaceQAOA) -> None:
    res = train(qaoa, p=1, optimizer="lbfgsb", init="linear-ramp", maxiter=50)
    masks, prob = most_probable(qaoa, res.angles)
    probs = qaoa.probabilities(res.angles)
    assert prob == pytest.approx(probs.max())
    assert probs[qaoa.index_of(masks)] == prob
    assert res.p_optimum > 0.5 and masks in qaoa.optimal_assignments()


def test_explicit_init_and_errors(qaoa: SubspaceQAOA) -> None:
    res = train(qaoa, p=1, optimizer="nesterov", init=[0.1, 0.2], maxiter=0)
    assert res.init == "explicit" and res.angles == (0.1, 0.2) and res.trace == (res.initial_expectation,)
    assert isinstance(res, TrainingResult)
    with pytest.raises(ValueError, match="optimizer"):
        train(qaoa, 1, optimizer="adam")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="init"):
        train(qaoa, 1, init="zeros")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="p must be"):
        train(qaoa, 0)
    with pytest.raises(ValueError, match="expected 4"):
        train(qaoa, 2, init=[0.1, 0.2])
    with pytest.raises(ValueError, match="interp"):
        initial_angles(qaoa, 2, "interp")


def test_two_robots_train() -> None:
    s = scenario_from_dict(
        {
            "grid": {"rows": 3, "cols": 3},
            "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}],
        }
    )
    q = SubspaceQAOA(s)
    res = train(q, p=2, optimizer="nesterov", init="linear-ramp", maxiter=30)
    assert res.expectation < res.initial_expectation - 0.1 * cost_scale(q)


def test_doctests() -> None:
    import doctest

    import qcpp.training.training

    result = doctest.testmod(qcpp.training.training)
    assert result.attempted > 0 and result.failed == 0
