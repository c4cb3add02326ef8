"""Mixer-only warm start: the product state is the simulator's state at gammas 0, its objective and gradients are
the full simulator's, and gammas 0 is a stationary point of every objective (why the warm start cannot climb)."""

from __future__ import annotations

import numpy as np
import pytest

from qcpp.problem.scenario import scenario_from_dict
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.mixer_only import product_objective, robot_states, robot_states_gradient, train_mixer_only
from qcpp.training.objectives import OBJECTIVES, make_objective
from qcpp.training.training import cost_scale

TWO = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[1, 1]]},
                          "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}]})
THREE = scenario_from_dict({"grid": {"rows": 3, "cols": 3},
                            "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]},
                                       {"start": [1, 0], "goal": [1, 2]}]})


@pytest.fixture(scope="module", params=["two", "three"])
def qaoa(request: pytest.FixtureRequest) -> SubspaceQAOA:
    return SubspaceQAOA(TWO if request.param == "two" else THREE)


def _angles(betas: np.ndarray) -> np.ndarray:
    out = np.zeros(2 * len(betas))
    out[1::2] = betas
    return out


def test_product_of_robot_states_is_the_state_at_gammas_zero(qaoa: SubspaceQAOA) -> None:
    betas = np.array([0.7, 1.9, 0.4])
    prod = np.ones(())
    for x in robot_states(qaoa, betas):
        prod = np.multiply.outer(prod, x)
    assert np.allclose(prod, qaoa.state(_angles(betas)), atol=1e-12)


@pytest.mark.parametrize("name", OBJECTIVES)
def test_objective_and_beta_gradient_match_the_full_simulator(qaoa: SubspaceQAOA, name: str) -> None:
    obj = make_objective(name, cost_scale(qaoa))
    betas = np.array([0.9, 0.35])
    states = robot_states(qaoa, betas)
    value, mean, grads = product_objective(qaoa, [abs(x) ** 2 for x in states], obj)
    full_value, full_grad = qaoa.objective_and_gradient(_angles(betas), obj)
    assert value == pytest.approx(full_value, rel=1e-10, abs=1e-10)
    assert mean == pytest.approx(qaoa.expectation(_angles(betas)), rel=1e-10)
    assert np.allclose(robot_states_gradient(qaoa, betas, grads), full_grad[1::2], atol=1e-8)


def test_probability_gradient_matches_finite_differences() -> None:
    q = SubspaceQAOA(TWO)
    obj = make_objective("gibbs", cost_scale(q))
    rng = np.random.default_rng(3)
    probs = [rng.random(n) for n in q.dims]
    probs = [p / p.sum() for p in probs]
    _, _, grads = product_objective(q, probs, obj)
    eps = 1e-6
    for r in range(2):
        for k in (0, len(probs[r]) - 1):
            up = [p.copy() for p in probs]
            dn = [p.copy() for p in probs]
            up[r][k] += eps
            dn[r][k] -= eps
            fd = (product_objective(q, up, obj)[0] - product_objective(q, dn, obj)[0]) / (2 * eps)
            assert grads[r][k] == pytest.approx(fd, rel=1e-5, abs=1e-7)


@pytest.mark.parametrize("name", OBJECTIVES)
def test_gammas_zero_is_stationary_in_the_gammas(name: str) -> None:
    """F(gamma, beta) = F(-gamma, beta): complex conjugation maps (gamma, beta) to (-gamma, -beta) and the move
    graph is bipartite (a move toggles one plaquette), so its parity sign maps beta to -beta; both keep every
    probability. Hence dF/dgamma = 0 at gammas 0, and the mixer-only warm start is a critical point of the full
    training."""
    q = SubspaceQAOA(TWO)
    obj = make_objective(name, cost_scale(q))
    rng = np.random.default_rng(1)
    x = rng.uniform(-1.5, 1.5, 6)
    flipped = x.copy()
    flipped[0::2] *= -1
    value = q.objective_and_gradient(x, obj)[0]
    assert q.objective_and_gradient(flipped, obj)[0] == pytest.approx(value, rel=1e-10)
    flipped = x.copy()
    flipped[1::2] *= -1
    assert q.objective_and_gradient(flipped, obj)[0] == pytest.approx(value, rel=1e-10)
    zero_betas = x.copy()
    zero_betas[1::2] = 0.0
    assert np.allclose(q.objective_and_gradient(zero_betas, obj)[1][1::2], 0.0, atol=1e-10)
    x[0::2] = 0.0
    assert np.allclose(q.objective_and_gradient(x, obj)[1][0::2], 0.0, atol=1e-10)


def test_training_improves_and_is_reproducible() -> None:
    q = SubspaceQAOA(TWO)
    obj = make_objective("gibbs", cost_scale(q))
    runs = train_mixer_only(q, 3, maxiter=30)
    assert [w.p for w in runs] == [1, 2, 3]
    values = [w.value for w in runs]
    assert all(b <= a + 1e-9 for a, b in zip(values, values[1:]))
    assert runs[0].value <= min(runs[0].initial_value, product_objective(
        q, [abs(x) ** 2 for x in robot_states(q, [0.0])], obj)[0])
    for w in runs:
        assert w.value == pytest.approx(q.objective_and_gradient(list(w.angles), obj)[0], rel=1e-10)
    again = train_mixer_only(q, 3, maxiter=30)
    assert [w.betas for w in again] == [w.betas for w in runs]


def test_bad_arguments() -> None:
    q = SubspaceQAOA(TWO)
    with pytest.raises(ValueError, match="p must be"):
        train_mixer_only(q, 0)
    with pytest.raises(ValueError, match="maxiter"):
        train_mixer_only(q, 1, maxiter=-1)
