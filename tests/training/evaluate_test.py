"""qcpp.training.evaluate (method dispatch) and qcpp.training.qaoa_solver (QAOA read as a solver)."""

from __future__ import annotations

import numpy as np
import pytest

from qcpp.plan.options import INITIAL_STATES
from qcpp.problem.cost import cost
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.problem.solvers import dfs, solution_to_dict
from qcpp.simulate.subspace import SubspaceQAOA
from qcpp.training.evaluate import MAX_STATEVECTOR_QUBITS, evaluate, resolve_angles
from qcpp.training.qaoa_solver import qaoa_method, qaoa_to_dict, solve_qaoa
from qcpp.training.training import initial_angles


def small() -> Scenario:
    """One robot on 2x3 with a soft obstacle: 12 qubits once compiled, a cost with several levels."""
    return scenario_from_dict(
        {"grid": {"rows": 2, "cols": 3, "obstacles": [[0, 1]]}, "robots": [{"start": [0, 0], "goal": [0, 2]}]}
    )


def wall_3x3() -> Scenario:
    return scenario_from_dict(
        {"grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1]]}, "robots": [{"start": [0, 0], "goal": [0, 2]}]}
    )


def test_subspace_and_statevector_agree() -> None:
    s = small()
    angles = [0.37, 1.3, -0.2, 0.8]
    a = evaluate(s, 2, "subspace", angles=angles)
    b = evaluate(s, 2, "statevector", angles=angles)
    assert b.expectation == pytest.approx(a.expectation, abs=1e-9)
    assert b.p_optimum == pytest.approx(a.p_optimum, abs=1e-9)
    assert a.amplitudes_held == 1.0 and b.amplitudes_held == pytest.approx(1.0, abs=1e-10)
    assert a.qubits is None and b.qubits is not None and b.basis_states == 1 << b.qubits
    assert a.angles == b.angles == tuple(angles) and a.p == b.p == 2


def test_subspace_numbers_from_their_definitions() -> None:
    s = small()
    angles = [0.5, 0.9]
    q = SubspaceQAOA(s)
    probs = q.probabilities(angles).reshape(-1)
    costs = np.array([cost(s, [m]) for m in q.bases[0]])
    best = min(cost(s, [m]) for m in enumerate_paths(s, 0))
    ev = evaluate(s, 1, "subspace", angles=angles)
    assert ev.expectation == pytest.approx(float(probs @ costs))
    assert ev.p_optimum == pytest.approx(float(probs[costs == best].sum()))
    assert 0 < ev.p_optimum < 1


def test_statevector_measures_what_leaves_the_feasible_set() -> None:
    # start and goal adjacent on 2x3: the paper rule's flips are not reversible there (see qcpp.simulate.subspace)
    s = scenario_from_dict({"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 0], "goal": [0, 1]}]})
    with pytest.raises(ValueError):
        SubspaceQAOA(s, rule="paper")  # not unitary on the data register: no subspace state exists
    ev = evaluate(s, 3, "statevector", seed=1, rule="paper")
    assert ev.amplitudes_held < 0.9
    exact = evaluate(s, 3, "statevector", seed=1, rule="exact")
    assert exact.amplitudes_held == pytest.approx(1.0, abs=1e-10)


def test_random_angles_are_seeded_and_shared_by_the_methods() -> None:
    s = small()
    a = resolve_angles(s, 2, seed=5)
    assert np.array_equal(a, resolve_angles(s, 2, seed=5))
    assert not np.array_equal(a, resolve_angles(s, 2, seed=6))
    assert np.array_equal(a, initial_angles(SubspaceQAOA(s), 2, "random", 5))
    assert evaluate(s, 2, "subspace", seed=5).angles == tuple(a)


def split_3x4() -> Scenario:
    """One robot on 3x4 with a hard obstacle at (1, 1): SBF moves split its paths into two components, so the four
    initial states are four different states (14 qubits once compiled)."""
    return scenario_from_dict({"grid": {"rows": 3, "cols": 4, "obstacles": [[1, 1]]},
                               "objective": {"obstacles": "hard"},
                               "robots": [{"start": [0, 0], "goal": [2, 3]}]})  # fmt: skip


@pytest.mark.xdist_group("quimb")  # runs the tensor backend: one worker compiles quimb's kernels (tests/conftest.py)
@pytest.mark.parametrize("initial", INITIAL_STATES)
def test_every_method_evaluates_the_given_initial_state(initial: str) -> None:
    """The subspace simulator starts from ``initial`` and the gate-level methods compile its preparation: the
    three agree (P(optimum) of the scenario's optimum, which only ``representatives`` reaches here), and differ
    from the default start where the state does."""
    s = split_3x4()
    angles = [0.37, 1.3, -0.2, 0.8]
    sub, sv, tn = (evaluate(s, 2, m, angles=angles, initial=initial) for m in ("subspace", "statevector", "tensor"))  # type: ignore[arg-type]
    for other in (sv, tn):
        assert other.p_optimum == pytest.approx(sub.p_optimum, abs=1e-9)
        assert other.expectation == pytest.approx(sub.expectation, abs=1e-8)
        assert other.amplitudes_held == pytest.approx(1.0, abs=1e-10)
    default = evaluate(s, 2, "subspace", angles=angles)
    assert (sub.expectation == pytest.approx(default.expectation, abs=1e-9)) == (initial == "initial_path")


def test_trained_angles_simulate_to_the_trained_probability_from_the_trained_state() -> None:
    """``qcpp solve -m qaoa --initial X`` reports P(optimum) from X: ``simulate --initial X`` at its angles gives
    the same, the default start another."""
    import qcpp

    s = split_3x4()
    trained = qcpp.train_qaoa(s, 1, initial="representatives", maxiter=30)
    same = qcpp.simulate_qaoa(s, 1, angles=list(trained.angles), initial="representatives")
    assert same.p_optimum == pytest.approx(trained.p_optimum, abs=1e-9)
    other = qcpp.simulate_qaoa(s, 1, angles=list(trained.angles))
    assert abs(other.p_optimum - trained.p_optimum) > 1e-3


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"method": "dense"}, "unknown method"),
        ({"rule": "fuzzy"}, "unknown SBF rule"),
        ({"angles": [0.1, 0.2, 0.3]}, "needs 2 angles"),
        ({"angles": [0.1, float("nan")]}, "finite"),
        ({"initial": "uniform"}, "unknown initial state 'uniform'"),
    ],
)
def test_bad_input(kwargs: dict[str, object], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        evaluate(small(), 1, **kwargs)  # type: ignore[arg-type]


def test_too_many_qubits_for_the_statevector() -> None:
    s = scenario_from_dict({"grid": {"rows": 4, "cols": 4}, "robots": [{"start": [0, 0], "goal": [3, 3]}]})
    with pytest.raises(ValueError, match=f"more than {MAX_STATEVECTOR_QUBITS}"):
        evaluate(s, 1, "statevector", angles=[0.1, 0.2])
    with pytest.raises(ValueError, match="p must be"):
        evaluate(s, 0, "subspace")


# ---------------------------------------------------------------- QAOA as a solver


def test_solve_qaoa_finds_the_optimum_of_the_paper_scenario() -> None:
    s = wall_3x3()
    res = solve_qaoa(s, p=1, seed=0)
    best = dfs(s)
    assert res.solution.paths == best.paths and res.solution.cost == best.cost
    assert res.probability > 0.9 and res.p_optimum == pytest.approx(res.probability)
    assert res.optimizer == "layerwise" and res.schedule is not None
    assert res.solution.trace == res.trace == res.schedule.trace and res.training is res.schedule.best
    assert res.solution.evaluated == res.num_evaluations == res.schedule.num_evaluations
    single = solve_qaoa(s, p=1, optimizer="nesterov", objective="expectation", maxiter=100, seed=0)
    assert len(single.trace) == 101 and single.schedule is None  # nesterov: start + 100 steps
    assert single.solution.evaluated == single.training.num_evaluations
    assert single.circuit_estimates == single.training.num_evaluations + 4 * single.training.num_gradients
    q = SubspaceQAOA(s)
    assert q.probabilities(res.angles)[q.index_of(res.solution.paths)] == pytest.approx(res.probability)
    again = solve_qaoa(s, p=1, seed=0)
    assert again.angles == res.angles


def test_qaoa_json_has_the_solver_keys_and_the_qaoa_ones() -> None:
    s = wall_3x3()
    res = solve_qaoa(s, p=2, optimizer="lbfgsb", maxiter=20, seed=1)
    d = qaoa_to_dict(s, res)
    base = solution_to_dict(s, res.solution, include_trace=False)
    assert {k: d[k] for k in base} == base
    assert d["p"] == 2 and len(d["angles"]) == 4 and d["trace"] == list(res.trace)
    assert d["probability"] == res.probability and d["optimizer"] == "lbfgsb"


def test_qaoa_method_has_the_uniform_signature() -> None:
    s = wall_3x3()
    sol = qaoa_method(p=1, optimizer="cobyla", maxiter=30)(s, seed=3, rule="exact", progress=None)
    assert sol.method == "qaoa" and sol.seed == 3 and sol.rule == "exact"
    calls: list[tuple[int, int]] = []
    solve_qaoa(s, p=1, optimizer="lbfgsb", maxiter=2, progress=lambda d, t: calls.append((d, t)))
    assert calls == [(0, 1), (1, 1)]
    calls.clear()
    solve_qaoa(s, p=2, maxiter=2, progress=lambda d, t: calls.append((d, t)))
    assert calls == [(0, 2), (1, 2), (2, 2)]
    with pytest.raises(ValueError, match="unknown optimizer"):
        solve_qaoa(s, optimizer="adam")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="unknown init"):
        solve_qaoa(s, init="zeros")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="unknown objective"):
        solve_qaoa(s, objective="median")  # type: ignore[arg-type]


@pytest.mark.slow
@pytest.mark.xdist_group("quimb")
def test_tensor_amplitudes_agree_with_subspace() -> None:
    pytest.importorskip("qcpp.simulate.tensor")
    s = small()
    angles = [0.37, 1.3]
    a = evaluate(s, 1, "subspace", angles=angles)
    t = evaluate(s, 1, "tensor", angles=angles)
    assert t.expectation == pytest.approx(a.expectation, abs=1e-9)
    assert t.p_optimum == pytest.approx(a.p_optimum, abs=1e-9)
    assert t.amplitudes_held == pytest.approx(1.0, abs=1e-9)
    assert t.basis_states == len(enumerate_paths(s, 0))


def test_qaoa_says_when_its_initial_state_cannot_reach_the_optimum() -> None:
    """On a split move graph whose optimum lies outside the start's component, the answer reports P(optimum) 0 and
    says why, naming the start that reaches it; from that start neither."""
    s = split_3x4()
    stuck = solve_qaoa(s, p=1, maxiter=20)
    assert stuck.p_optimum == 0.0 and stuck.solution.cost.total > stuck.optimum
    assert any("starts in none of the move-graph components" in n for n in stuck.solution.notes)
    freed = solve_qaoa(s, p=1, maxiter=20, initial="representatives")
    assert freed.p_optimum > 0 and not any("move-graph components" in n for n in freed.solution.notes)
