"""Training objectives: values by their definitions, derivatives in the probabilities and, through the adjoint
sweep, in the angles (against central finite differences), on one and two robots and without a level table."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.objectives import OBJECTIVES, CVaR, Expectation, Gibbs, make_objective
from qcpp.training.training import cost_scale

ONE_3x3 = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[1, 1]]},
                              "robots": [{"start": [0, 0], "goal": [2, 2]}]})
TWO_3x3 = scenario_from_dict({"grid": {"rows": 3, "cols": 3},
                              "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}]})


def _distribution(draw_values: list[float], draw_weights: list[float]) -> tuple[np.ndarray, np.ndarray]:
    v = np.array(sorted(set(draw_values)), dtype=float)
    w = np.array(draw_weights[: v.size] + [1.0] * max(0, v.size - len(draw_weights)), dtype=float)
    return v, w / w.sum()


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.integers(-20, 40), min_size=1, max_size=8),
    st.lists(st.floats(0.01, 1.0), min_size=1, max_size=8),
    st.floats(0.05, 1.0),
)
def test_values_by_definition(vals: list[int], weights: list[float], alpha: float) -> None:
    v, w = _distribution([float(x) for x in vals], weights)
    assert Expectation()(v, w)[0] == pytest.approx(float(v @ w))
    # CVaR: the mean of the cheapest alpha of the mass, by sorting a fine sample of the distribution
    fine = np.repeat(v, np.round(w * 100_000).astype(int))
    k = max(1, round(alpha * fine.size))
    assert CVaR(alpha)(v, w)[0] == pytest.approx(fine[:k].mean(), abs=1e-3 * (1 + np.abs(v).max()))
    eta = 0.3
    assert Gibbs(eta)(v, w)[0] == pytest.approx(-np.log(float(w @ np.exp(-eta * v))) / eta, rel=1e-9, abs=1e-9)
    # limits: Gibbs tends to <C> for small eta and to the cheapest cost for large eta
    assert Gibbs(1e-7)(v, w)[0] == pytest.approx(float(v @ w), abs=1e-4)
    assert Gibbs(1e4)(v, w)[0] == pytest.approx(float(v[0]), abs=1e-2)
    assert CVaR(1.0)(v, w)[0] == pytest.approx(float(v @ w))


@pytest.mark.parametrize("name", OBJECTIVES)
def test_derivative_in_the_probabilities(name: str) -> None:
    v = np.array([-2.0, 0.0, 3.0, 7.0, 8.0])
    w = np.array([0.07, 0.21, 0.3, 0.12, 0.3])
    obj = make_objective(name, sigma=3.0)  # type: ignore[arg-type]
    _, g = obj(v, w)
    h = 1e-7
    for k in range(v.size):
        e = np.zeros(v.size)
        e[k] = h
        fd = (obj(v, w + e)[0] - obj(v, w - e)[0]) / (2 * h)
        assert g[k] == pytest.approx(fd, rel=1e-5, abs=1e-6)


@pytest.mark.parametrize("s", [ONE_3x3, TWO_3x3])
@pytest.mark.parametrize("name", OBJECTIVES)
def test_angle_gradient_matches_finite_differences(s: Scenario, name: str) -> None:
    q = SubspaceQAOA(s)
    obj = make_objective(name, sigma=cost_scale(q))  # type: ignore[arg-type]
    rng = np.random.default_rng(5)
    angles = rng.uniform(0.05, 1.2, 6) * np.tile([1 / cost_scale(q), 1.0], 3)

    def f(x: np.ndarray) -> float:
        values, _ = q.cost_distribution_index()
        return obj(values, q.level_probabilities(q.state(x)))[0]

    value, grad = q.objective_and_gradient(angles, obj)
    assert value == pytest.approx(f(angles), rel=1e-12)
    h = 1e-6
    fd = np.array([(f(angles + h * e) - f(angles - h * e)) / (2 * h) for e in np.eye(angles.size)])
    assert np.allclose(grad, fd, rtol=1e-5, atol=1e-6 * np.abs(fd).max())
    if name == "expectation":
        assert np.allclose(grad, q.gradient(angles), rtol=1e-10, atol=1e-12)


def test_without_a_level_table() -> None:
    """The float-diagonal fallback builds its own cost table and gives the same objective and gradient."""
    ref = SubspaceQAOA(TWO_3x3)
    assert ref.cost_levels() is not None
    q = SubspaceQAOA(TWO_3x3, max_levels=2)
    assert q.cost_levels() is None
    obj = Gibbs(0.2)
    angles = [0.05, 0.9, 0.1, 0.4]
    a, b = q.objective_and_gradient(angles, obj), ref.objective_and_gradient(angles, obj)
    assert a[0] == pytest.approx(b[0], rel=1e-12) and np.allclose(a[1], b[1], rtol=1e-10, atol=1e-12)


def test_bad_parameters() -> None:
    with pytest.raises(ValueError, match="alpha"):
        CVaR(0.0)
    with pytest.raises(ValueError, match="eta"):
        Gibbs(-1.0)
    with pytest.raises(ValueError, match="unknown objective"):
        make_objective("variance")  # type: ignore[arg-type]


def test_doctests() -> None:
    import doctest

    import qcpp.training.objectives

    assert doctest.testmod(qcpp.training.objectives).failed == 0
