"""Multi-angle mixer-only QAOA: the product state against the compiled circuit, gradients, and the training."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from qcpp.ir.angles import mixer_symbol
from qcpp.lowering.passes import lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_circuit, qaoa_plan
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.problem.scenario_io import load_scenario
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.mixer_only import (
    bindings,
    mixer_sites,
    multi_robot_states,
    multi_robot_states_gradient,
    product_objective,
    robot_states,
    robot_states_gradient,
    train_multi_angle,
)
from qcpp.training.objectives import make_objective
from qcpp.training.training import cost_scale

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def make(rows: int, cols: int, robots: list[tuple[tuple[int, int], tuple[int, int]]]) -> Scenario:
    return scenario_from_dict({"grid": {"rows": rows, "cols": cols},
                               "robots": [{"start": list(a), "goal": list(b)} for a, b in robots]})


TWO_2x4 = make(2, 4, [((0, 0), (1, 0)), ((0, 3), (1, 3))])
TWO_3x3 = make(3, 3, [((0, 0), (2, 2)), ((0, 2), (2, 0))])


def _probs(states: list[np.ndarray]) -> list[np.ndarray]:
    return [v.real * v.real + v.imag * v.imag for v in states]


def test_the_compiled_multi_angle_circuit_prepares_the_product_state() -> None:
    """Gate-level state of ``PlanOptions(angles="multi")`` bound by :func:`bindings` == the outer product of the
    robots' vectors (distinct betas per partial mixer, so a mix-up of sites or layers shows)."""
    from qcpp.simulate.sparse import simulate_sparse

    q, p = SubspaceQAOA(TWO_2x4), 2
    betas = np.random.default_rng(3).uniform(0, 2 * np.pi, p * len(mixer_sites(q)))
    circ = qaoa_circuit(TWO_2x4, p, PlanOptions(angles="multi"))
    values = bindings(q, betas, p)
    assert set(circ.symbols) <= set(values)
    gate_level = simulate_sparse(circ, 0, values)
    v0, v1 = multi_robot_states(q, betas, p)
    mine = {q.data_index(q.assignment((a, b))): v0[a] * v1[b] for a in range(v0.size) for b in range(v1.size)}
    assert max(abs(gate_level.get(k, 0) - mine.get(k, 0)) for k in set(gate_level) | set(mine)) < 1e-10
    assert sum(abs(a) ** 2 for a in mine.values()) == pytest.approx(1.0)


def test_multi_angle_circuit_has_the_same_gates_and_one_symbol_per_partial_mixer() -> None:
    layer, multi = qaoa_circuit(TWO_3x3, 2), qaoa_circuit(TWO_3x3, 2, PlanOptions(angles="multi"))
    assert [g[:2] for g in lower(layer).gates] == [g[:2] for g in lower(multi).gates]
    assert qaoa_plan(TWO_3x3, 2, PlanOptions(angles="multi")).cost() == qaoa_plan(TWO_3x3, 2).cost()
    assert multi.symbols[0] == "gamma_0" and multi.symbols[1] == mixer_symbol(0, 0, 0)
    betas = [s for s in multi.symbols if s.startswith("beta_")]
    assert len(betas) == len(set(betas)) == 2 * 2 * len(TWO_3x3.grid.plaquettes)


def test_equal_betas_are_the_one_angle_mixer() -> None:
    q, p = SubspaceQAOA(TWO_3x3), 3
    layer_betas = [0.4, 1.9, -0.7]
    multi = multi_robot_states(q, np.repeat(layer_betas, len(mixer_sites(q))), p)
    for a, b in zip(multi, robot_states(q, layer_betas)):
        assert np.allclose(a, b, atol=1e-12)


def test_a_tied_betas_gradient_is_the_sum_over_its_sites() -> None:
    """One beta per layer is the multi-angle mixer with each layer's betas tied (one kernel serves both), so its
    derivative is the sum of that layer's per-site derivatives."""
    q, layer_betas = SubspaceQAOA(TWO_3x3), np.array([0.4, 1.9, -0.7])
    weights = [np.random.default_rng(r).normal(size=d) for r, d in enumerate(q.dims)]
    sites = robot_states_gradient(q, np.repeat(layer_betas[:, None], len(mixer_sites(q)), axis=1), weights)
    tied = robot_states_gradient(q, layer_betas, weights)
    assert sites.shape == (3, len(mixer_sites(q))) and np.allclose(tied, sites.sum(axis=1), atol=1e-12)
    assert np.abs(tied).max() > 1e-3


@pytest.mark.parametrize("name", ["gibbs", "expectation"])
def test_gradient_matches_finite_differences(name: str) -> None:
    q, p = SubspaceQAOA(TWO_3x3), 2
    obj = make_objective(name, cost_scale(q))  # type: ignore[arg-type]
    x = np.random.default_rng(1).uniform(0, 2 * np.pi, p * len(mixer_sites(q)))

    def f(v: np.ndarray) -> float:
        return product_objective(q, _probs(multi_robot_states(q, v, p)), obj)[0]

    grads = product_objective(q, _probs(multi_robot_states(q, x, p)), obj)[2]
    g = multi_robot_states_gradient(q, x, p, grads)
    h = 1e-6
    fd = np.array([(f(x + h * e) - f(x - h * e)) / (2 * h) for e in np.eye(x.size)])
    assert np.allclose(g, fd, atol=1e-6)
    assert np.abs(g).max() > 1e-3  # not trivially zero


def test_training_never_reads_the_optimum_and_reaches_it_on_two_robots_4x4(monkeypatch: pytest.MonkeyPatch) -> None:
    q = SubspaceQAOA(load_scenario(EXAMPLES / "two_robots_4x4.toml"))
    p_opt = q.optimum()[0], q.optimum()[1].copy()

    def forbidden() -> None:
        raise AssertionError("the training looked up the optimum")

    monkeypatch.setattr(q, "optimum", forbidden)
    res = train_multi_angle(q, 1, random_starts=0)
    v0, v1 = multi_robot_states(q, res.betas, 1)
    probability = sum(abs(v0[a] * v1[b]) ** 2 for a, b in zip(*np.unravel_index(p_opt[1], q.dims)))
    assert probability > 0.99 and res.value == pytest.approx(p_opt[0], abs=1e-6)
    assert res.num_parameters == len(mixer_sites(q)) and len(res.start_values) == 3


def test_a_zero_layer_keeps_the_previous_depth() -> None:
    q = SubspaceQAOA(TWO_3x3)
    one = train_multi_angle(q, 1, random_starts=1, seed=2)
    two = train_multi_angle(q, 2, random_starts=0, previous=one.betas)
    assert two.value <= one.value + 1e-9 and len(two.start_values) == 4


def test_bad_arguments() -> None:
    q = SubspaceQAOA(TWO_3x3)
    with pytest.raises(ValueError, match="layers x partial mixers"):
        multi_robot_states(q, [0.1, 0.2], 1)
    with pytest.raises(ValueError, match="finite"):
        multi_robot_states(q, [np.nan] * len(mixer_sites(q)), 1)
    with pytest.raises(ValueError, match="p must be"):
        train_multi_angle(q, 0)
    with pytest.raises(ValueError, match="angles: expected"):
        PlanOptions(angles="many")  # type: ignore[arg-type]


def test_the_solver_answers_with_the_product_state_and_bindings_of_the_compiled_circuit() -> None:
    """``solve_qaoa(optimizer="multi-angle")``: probability and P(optimum) of the product state; its bindings
    bind every symbol of the compiled multi-angle circuit and nothing else."""
    from qcpp.plan.compile import compile_scenario
    from qcpp.training.qaoa_solver import qaoa_to_dict, solve_qaoa

    res = solve_qaoa(TWO_2x4, p=2, optimizer="multi-angle")
    q = SubspaceQAOA(TWO_2x4)
    v0, v1 = multi_robot_states(q, res.angles, 2)
    assert res.probability == pytest.approx(float(np.max(np.abs(np.multiply.outer(v0, v1)) ** 2)))
    best = q.optimum()[1]
    assert res.p_optimum == pytest.approx(float(np.sum(np.abs(np.multiply.outer(v0, v1)).reshape(-1)[best] ** 2)))
    circuit = compile_scenario(TWO_2x4, 2, PlanOptions(angles="multi"), bindings=res.bindings).circuit
    assert circuit.symbols == () and set(res.bindings) >= set(
        compile_scenario(TWO_2x4, 2, PlanOptions(angles="multi")).circuit.symbols)
    out = qaoa_to_dict(TWO_2x4, res)
    assert out["optimizer"] == "multi-angle" and out["bindings"] == res.bindings
    # a gradient by the parameter-shift rule: 1 + 2 x parameters estimates, at least 13 per evaluation here
    assert out["circuit_estimates"] == res.estimates >= 13 * out["evaluations"]
