"""The feasible-subspace QAOA simulator against an independent dense 2^n reference.

The reference knows nothing of bases or pairs: it keeps the full state vector over all data qubits (index
``sum_i x_i 2^i``), applies the phase from ``ising_hamiltonian(...).evaluate`` on every basis state, and each
partial mixer as the explicit map "if allowed(x): |x> -> cos(b/2)|x> - i sin(b/2)|x^P>" on every basis state,
with ``allowed`` from ``sbf_logic(...).evaluate`` on the masks decoded by ``mask_from_bits``.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from qcpp.plan.options import PlanOptions
from qcpp.plan.phase import phase_plan
from qcpp.problem.cost import cost, separable_cost
from qcpp.problem.hamiltonian import ising_hamiltonian
from qcpp.problem.paths import assignment_bits, enumerate_paths, initial_path, is_feasible, mask_from_bits, path_bits
from qcpp.problem.sbf import SbfLogic, XorStep, move_components, reachable_paths, representatives, sbf_logic
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.simulate.subspace import NonUnitaryMixerError, SubspaceQAOA, evaluate_logic, robot_basis, split_angles
from qcpp.training.objectives import make_objective
from qcpp.training.training import cost_scale


def make(rows: int, cols: int, robots: list[tuple[tuple[int, int], tuple[int, int]]], **extra: object) -> Scenario:
    d: dict[str, object] = {
        "grid": {"rows": rows, "cols": cols, "obstacles": extra.pop("obstacles", [])},
        "robots": [{"start": list(a), "goal": list(b)} for a, b in robots],
    }
    d.update(extra)
    return scenario_from_dict(d)


SINGLE_2x2 = make(2, 2, [((0, 0), (1, 1))])
SINGLE_2x3 = make(2, 3, [((0, 0), (1, 2))])
SINGLE_3x3 = make(3, 3, [((0, 0), (2, 2))], obstacles=[[1, 1]])
SINGLE_3x3_SIDE = make(3, 3, [((0, 0), (0, 2))])
TWO_2x3 = make(2, 3, [((0, 0), (1, 2)), ((1, 0), (0, 2))])
THREE_2x2 = make(2, 2, [((0, 0), (1, 1)), ((0, 1), (1, 0)), ((1, 1), (0, 1))])  # 12 qubits, 2 paths each
# hard obstacle that splits the move graph of the exact rule into several components
HARD_3x4 = make(3, 4, [((0, 0), (2, 3))], obstacles=[[1, 1]], objective={"obstacles": "hard"})
# the local_search warm start moves away from the initial paths here (2 steps each)
SINGLE_3x3_CORNERS = make(3, 3, [((0, 0), (2, 2))])
TWO_2x4 = make(2, 4, [((0, 0), (1, 0)), ((0, 3), (1, 3))])


# ---------------------------------------------------------------- the dense reference


def _allowed_table(s: Scenario, robot: int, q: int, rule: str) -> np.ndarray:
    """allowed[local] for every one of the robot's 2^V local bit patterns."""
    v = s.edges_per_robot
    logic = sbf_logic(s, robot, s.grid.plaquettes[q], rule)  # type: ignore[arg-type]
    out = np.zeros(1 << v, dtype=bool)
    for local in range(1 << v):
        bits = [(local >> k) & 1 for k in range(v)]
        out[local] = logic.evaluate(mask_from_bits(s, bits))
    return out


def dense_reference(
    s: Scenario, angles: list[float], rule: str = "exact", initial: str = "initial_path", offset: float | None = None
) -> np.ndarray:
    n = s.num_variables
    v = s.edges_per_robot
    assert n <= 14
    dim = 1 << n
    idx = np.arange(dim)
    allbits = ((idx[:, None] >> np.arange(n)) & 1).astype(np.uint8)
    ham = ising_hamiltonian(s)
    energy = ham.evaluate(allbits)
    # the whole-space Hamiltonian as the phase operator (exact on every bit string), offset by the constant the
    # subspace simulator leaves out by default: the feasible plan's reference constant
    off = phase_plan(s).reference_constant if offset is None else offset
    # initial state
    per_robot = []
    for r in range(s.num_robots):
        starts = [initial_path(s, r)] if initial == "initial_path" else list(representatives(s, r, rule))  # type: ignore[arg-type]
        vec = np.zeros(1 << v)
        for m in starts:
            local = sum(int(b) << k for k, b in enumerate(path_bits(s, m)))
            vec[local] = 1.0
        per_robot.append(vec / np.linalg.norm(vec))
    psi = np.zeros(dim, dtype=complex)
    locals_ = [(idx >> (r * v)) & ((1 << v) - 1) for r in range(s.num_robots)]
    psi[:] = 1.0
    for r in range(s.num_robots):
        psi *= per_robot[r][locals_[r]]
    # layers
    for g, b in zip(angles[0::2], angles[1::2]):
        psi = psi * np.exp(-1j * g * (energy - off))
        c, sn = np.cos(b / 2), np.sin(b / 2)
        for r in range(s.num_robots):
            for q, plaq in enumerate(s.grid.plaquettes):
                allowed = _allowed_table(s, r, q, rule)[locals_[r]]
                pbits = sum(1 << (r * v + k) for k, e in enumerate(s.variable_edges) if (plaq.edge_mask >> e) & 1)
                flipped = idx ^ pbits
                # column by column, as the circuit acts on |x>: |x> -> c|x> - i s|x^P> when allowed(x)
                new = np.where(allowed, c * psi, psi)
                new[flipped[allowed]] += -1j * sn * psi[allowed]  # x -> x^P is a bijection: no repeats
                psi = new
    return psi


def subspace_as_dense(q: SubspaceQAOA, angles: list[float]) -> np.ndarray:
    """Map the subspace state to 2^n using qcpp.problem's own assignment_bits (independent of dense_state)."""
    n = q.scenario.num_variables
    out = np.zeros(1 << n, dtype=complex)
    psi = q.state(angles)
    for idx in np.ndindex(*q.dims):
        bits = assignment_bits(q.scenario, q.assignment(idx))
        out[int(sum(int(b) << i for i, b in enumerate(bits)))] = psi[idx]
    return out


CASES = [
    ("2x2", SINGLE_2x2, [0.7, 1.3]),
    ("2x3", SINGLE_2x3, [0.4, 0.9, -0.3, 2.1]),
    ("3x3-obstacle", SINGLE_3x3, [0.21, 1.1, 0.13, 0.6]),
    ("3x3-side", SINGLE_3x3_SIDE, [0.3, 2.5]),
    ("2x3-two-robots", TWO_2x3, [0.11, 1.7, 0.05, 0.8]),
    ("2x2-three-robots", THREE_2x2, [0.09, 1.3]),
]


@pytest.mark.parametrize(("name", "s", "angles"), CASES, ids=[c[0] for c in CASES])
def test_matches_dense_reference(name: str, s: Scenario, angles: list[float]) -> None:
    q = SubspaceQAOA(s)
    ref = dense_reference(s, angles)
    sub = subspace_as_dense(q, angles)
    assert np.abs(sub - ref).max() < 1e-10
    # no weight outside the reachable feasible subspace: the reference's support is inside ours
    outside = np.ones(ref.size, dtype=bool)
    outside[np.abs(sub) > 0] = False
    assert np.abs(ref[outside]).max(initial=0.0) < 1e-10
    assert np.allclose(q.dense_state(angles), sub, atol=1e-12)
    assert abs(np.linalg.norm(ref) - 1) < 1e-10


def test_matches_dense_reference_with_plain_phase() -> None:
    angles = [0.37, 0.8]
    q = SubspaceQAOA(TWO_2x3, phase_offset=0.0)
    assert np.abs(subspace_as_dense(q, angles) - dense_reference(TWO_2x3, angles, offset=0.0)).max() < 1e-10


def test_representatives_on_split_move_graph() -> None:
    comps = move_components(HARD_3x4, 0, "exact")
    assert len(comps) > 1  # the scenario really splits
    q0 = SubspaceQAOA(HARD_3x4)
    q1 = SubspaceQAOA(HARD_3x4, initial="representatives")
    assert q0.dims == (len(comps[0]),)
    assert sorted(q1.bases[0]) == sorted(enumerate_paths(HARD_3x4, 0))
    angles = [0.3, 1.2, 0.2, 0.5]
    ref = dense_reference(HARD_3x4, angles, initial="representatives")
    assert np.abs(subspace_as_dense(q1, angles) - ref).max() < 1e-10
    # initial state: uniform over the representatives, real positive
    psi0 = q1.initial_state()
    reps = [q1.index_of([m])[0] for m in representatives(HARD_3x4, 0, "exact")]
    assert np.allclose(psi0[reps], 1 / np.sqrt(len(comps)))
    assert np.isclose(np.abs(psi0).sum(), len(comps) / np.sqrt(len(comps)))


def _hard_3x4_scenarios() -> list[Scenario]:
    """One robot, every start and goal on 3x4's boundary, one hard obstacle anywhere inside the grid."""
    out = []
    boundary = [(r, c) for r in range(3) for c in range(4) if r in (0, 2) or c in (0, 3)]
    for start, goal in itertools.combinations(boundary, 2):
        for obstacle in [(1, 1), (1, 2)]:
            try:
                out.append(scenario_from_dict({"grid": {"rows": 3, "cols": 4, "obstacles": [list(obstacle)]},
                                               "objective": {"obstacles": "hard"},
                                               "robots": [{"start": list(start), "goal": list(goal)}]}))  # fmt: skip
            except ValueError:
                continue  # the obstacle cuts the goal off
    return out


def test_the_optimum_is_the_scenario_s_even_where_the_start_does_not_reach_it() -> None:
    """Over every one-robot 3x4 scenario with a hard obstacle: :meth:`optimum` is the exhaustive search's optimum
    from every start, P(optimum) counts only basis assignments of that cost, and where the start's component lacks
    it (it does on some of these scenarios) P(optimum) is 0, not the best reachable assignment's probability."""
    from qcpp.problem.solvers import dfs

    unreached = 0
    for s in _hard_3x4_scenarios():
        truth = dfs(s).cost.total
        for initial, rule in itertools.product(("initial_path", "representatives", "local_search"), ("exact", "paper")):
            try:
                q = SubspaceQAOA(s, rule=rule, initial=initial)  # type: ignore[arg-type]
            except NonUnitaryMixerError:
                continue  # the paper rule leaves the feasible set here: no subspace state
            best, flat = q.optimum()
            assert best == pytest.approx(truth, abs=1e-9)
            (feasible,) = q.feasible  # the paper rule's basis may hold infeasible edge sets: never optimal
            costs = np.where(feasible, q.cost_diagonal(), np.inf)
            assert sorted(flat.tolist()) == [i for i, c in enumerate(costs) if abs(c - truth) <= 1e-9]
            if len(flat) == 0:
                unreached += 1
                assert costs.min() > truth + 1e-9  # the basis's own optimum: what P(optimum) no longer counts
                assert q.p_optimum([0.3, 1.1]) == 0.0
                assert not q.reaches_every_path() and initial != "representatives"
    assert unreached > 0


# ---------------------------------------------------------------- structural properties


def test_basis_is_the_reachable_feasible_set() -> None:
    for s in (SINGLE_3x3, SINGLE_3x3_SIDE, TWO_2x3):
        q = SubspaceQAOA(s)
        for r, paths in enumerate(q.bases):
            assert paths[0] == initial_path(s, r)
            assert all(is_feasible(s, r, m) for m in paths)
            assert sorted(paths) == sorted(move_components(s, r, "exact")[0])
        for b in q.robot_bases:
            for pq, i, j in b.pairs:
                mask = s.grid.plaquettes[pq].edge_mask
                assert np.all(i < j)
                assert all(b.paths[a] ^ mask == b.paths[c] for a, c in zip(i, j))
                assert len(set(i.tolist()) | set(j.tolist())) == 2 * len(i)  # disjoint pairs


def test_basis_order_and_vectorised_logic_match_gridcover() -> None:
    for s, rule in ((SINGLE_3x3, "exact"), (TWO_2x3, "exact"), (make(3, 3, [((0, 0), (2, 2))]), "paper")):
        q = SubspaceQAOA(s, rule=rule)  # type: ignore[arg-type]
        for r in range(s.num_robots):
            assert list(q.bases[r]) == reachable_paths(s, r, rule)  # type: ignore[arg-type]
            masks = enumerate_paths(s, r)
            for plaq in s.grid.plaquettes:
                lg = sbf_logic(s, r, plaq, rule)  # type: ignore[arg-type]
                got = evaluate_logic(lg, np.array(masks, dtype=object))
                assert got.tolist() == [lg.evaluate(m) for m in masks]


def test_cost_levels_reproduce_the_separable_tensor() -> None:
    q = SubspaceQAOA(TWO_2x3)
    levels = q.cost_levels()
    assert levels is not None
    values, lev = levels
    assert np.all(np.diff(values) > 0) and lev.shape == q.dims
    full = separable_cost(TWO_2x3, q.bases).full_tensor()
    assert np.allclose(values[lev], full, rtol=0, atol=1e-9)
    assert np.array_equal(q.cost_diagonal(), values[lev])


def test_cost_diagonal_matches_ising_and_cost() -> None:
    q = SubspaceQAOA(TWO_2x3)
    ham = ising_hamiltonian(TWO_2x3)
    diag = q.cost_diagonal()
    assert not diag.flags.writeable
    for idx in np.ndindex(*q.dims):
        masks = q.assignment(idx)
        assert np.isclose(diag[idx], cost(TWO_2x3, masks))
        assert np.isclose(diag[idx], ham.evaluate(assignment_bits(TWO_2x3, masks)))


def test_local_search_starts_on_the_descent_paths() -> None:
    from qcpp.problem.solvers.descent import local_search

    for s in (SINGLE_3x3_CORNERS, TWO_2x4):
        warm = local_search(s)
        assert warm.steps > 0  # really a different start from the initial paths
        q = SubspaceQAOA(s, initial="local_search")
        q0 = SubspaceQAOA(s)
        assert [sorted(b) for b in q.bases] == [sorted(b) for b in q0.bases]  # same component, another order
        psi0 = q.initial_state()
        assert psi0[q.index_of(warm.paths)] == 1.0 and np.abs(psi0).sum() == 1.0
        assert q.expectation([]) == pytest.approx(warm.cost)


def test_local_search_mix_starts_on_the_initial_and_descent_paths_in_equal_superposition() -> None:
    """Per robot ``(|initial path> + |descent path>) / sqrt 2`` (one path where the descent leaves the robot
    where it was), the product over robots; every basis state with weight is a feasible assignment."""
    from qcpp.problem.solvers.descent import local_search

    for s in (SINGLE_3x3_CORNERS, TWO_2x4, TWO_2x3):
        warm = local_search(s)
        q = SubspaceQAOA(s, initial="local_search_mix")
        psi0 = q.initial_state()
        support = [np.unravel_index(k, q.dims) for k in np.flatnonzero(psi0)]
        per_robot = [sorted({initial_path(s, r), warm.paths[r]}) for r in range(s.num_robots)]
        assert sorted(q.assignment(i) for i in support) == sorted(itertools.product(*per_robot))
        assert np.allclose(np.abs(psi0[tuple(np.array(support).T)]), 1 / np.sqrt(len(support)))
        assert all(is_feasible(s, r, m) for i in support for r, m in enumerate(q.assignment(i)))
        assert [sorted(b) for b in q.bases] == [sorted(b) for b in SubspaceQAOA(s).bases]
    assert len(set(local_search(TWO_2x4).paths) - {initial_path(TWO_2x4, r) for r in range(2)}) == 2


def test_zero_layers_is_the_initial_state() -> None:
    q = SubspaceQAOA(HARD_3x4, initial="representatives")
    assert np.array_equal(q.state([]), q.initial_state())
    assert np.array_equal(q.gradient([]), np.zeros(0))


FRACTIONAL_2x3 = make(
    2,
    3,
    [((0, 0), (1, 2)), ((1, 0), (0, 2))],
    obstacles=[[0, 1]],
    objective={"alpha": [1.0, 0.37, 0.5], "obstacle_weight": 0.3, "free_weight": -0.45, "edge_length": 1.7},
)


def test_non_integer_costs_use_the_distinct_value_table() -> None:
    q = SubspaceQAOA(FRACTIONAL_2x3)
    levels = q.cost_levels()
    assert levels is not None
    values, lev = levels
    full = separable_cost(FRACTIONAL_2x3, q.bases).full_tensor()
    assert not np.allclose(values, np.rint(values))  # really the general path
    assert np.array_equal(np.unique(values[lev]), values)  # exactly the distinct values
    assert np.allclose(values[lev], full, rtol=0, atol=1e-9)
    angles = [0.21, 1.3, 0.4, 0.7]
    assert np.abs(subspace_as_dense(q, angles) - dense_reference(FRACTIONAL_2x3, angles)).max() < 1e-10


def test_float_diagonal_fallback() -> None:
    """Too many distinct costs for a level table: the float64 diagonal is used, with the same results."""
    import qcpp.simulate.subspace as sub

    assert sub._compress(np.array([0.5, 1.5, 2.25, 0.5]), 2) is None
    assert sub._compress(np.array([0.5, 1.5, 2.25, 0.5]), 3) is not None
    for s in (FRACTIONAL_2x3, TWO_2x3):
        q = SubspaceQAOA(s, max_levels=2)
        assert q.cost_levels() is None
        angles = np.array([0.21, 1.3, 0.4, 0.7])
        assert np.abs(subspace_as_dense(q, list(angles)) - dense_reference(s, list(angles))).max() < 1e-10
        ref = SubspaceQAOA(s)
        assert ref.cost_levels() is not None
        assert np.isclose(q.expectation(angles), ref.expectation(angles), rtol=1e-12)
        assert np.allclose(q.gradient(angles), ref.gradient(angles), rtol=1e-10, atol=1e-12)
        assert np.array_equal(q.cost_diagonal(), ref.cost_diagonal())
        assert cost_scale(q) == pytest.approx(cost_scale(ref), rel=1e-12)
    with pytest.raises(ValueError, match="max_levels"):
        SubspaceQAOA(TWO_2x3, max_levels=sub.MAX_LEVELS + 1)


def test_norm_is_preserved() -> None:
    rng = np.random.default_rng(5)
    q = SubspaceQAOA(TWO_2x3)
    for p in (1, 2, 3):
        angles = rng.uniform(-3, 3, 2 * p)
        assert abs(np.linalg.norm(q.state(angles)) - 1) < 1e-12
        assert abs(q.probabilities(angles).sum() - 1) < 1e-12


@pytest.mark.parametrize("offset", [None, 0.0, 2.5])
def test_beta_zero_only_phases_the_initial_path(offset: float | None) -> None:
    s = SINGLE_3x3
    q = SubspaceQAOA(s, phase_offset=offset)
    off = phase_plan(s).reference_constant if offset is None else offset
    assert q.phase_offset == off
    gamma = 0.37
    psi = q.state([gamma, 0.0])
    c_init = cost(s, [initial_path(s, 0)])
    assert q.index_of([initial_path(s, 0)]) == (0,)
    assert np.isclose(psi[0], np.exp(-1j * gamma * (c_init - off)), atol=1e-12)
    assert np.abs(psi[1:]).max() == 0.0
    assert np.isclose(q.expectation([gamma, 0.0]), c_init)


def test_gamma_zero_mixer_is_independent_of_the_offset() -> None:
    a, b = SubspaceQAOA(SINGLE_3x3), SubspaceQAOA(SINGLE_3x3, phase_offset=0.0)
    angles = [0.3, 0.9, 0.2, 1.4]
    # the offset is a global phase: probabilities agree, amplitudes differ by one phase factor
    assert np.allclose(a.probabilities(angles), b.probabilities(angles), atol=1e-12)
    ratio = a.state(angles)[0] / b.state(angles)[0]
    assert np.allclose(a.state(angles), ratio * b.state(angles), atol=1e-12)


def test_split_angles_validates() -> None:
    with pytest.raises(ValueError, match="even"):
        split_angles([0.1, 0.2, 0.3])
    assert [g.size for g in split_angles([])] == [0, 0]  # p = 0: the initial state
    with pytest.raises(ValueError, match="finite"):
        split_angles([0.1, float("nan")])


def test_bad_options() -> None:
    with pytest.raises(ValueError, match="rule"):
        SubspaceQAOA(SINGLE_2x2, rule="nope")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="initial"):
        SubspaceQAOA(SINGLE_2x2, initial="nope")  # type: ignore[arg-type]


# ---------------------------------------------------------------- the paper rule


def test_paper_rule_symmetric_case_is_simulated() -> None:
    s = make(3, 3, [((0, 0), (2, 2))])  # corner endpoints: the paper rule's reachable set stays feasible
    q = SubspaceQAOA(s, rule="paper")
    assert all(f.all() for f in q.feasible)
    angles = [0.2, 1.0, 0.1, 0.7]
    assert np.abs(subspace_as_dense(q, angles) - dense_reference(s, angles, rule="paper")).max() < 1e-10


def test_paper_rule_leaving_the_feasible_set_is_refused() -> None:
    s = make(3, 3, [((0, 1), (2, 1))])  # mid-side endpoints: a flip gives the start two new edges
    with pytest.raises(NonUnitaryMixerError, match="not unitary"):
        SubspaceQAOA(s, rule="paper")
    # ... and that is a real non-unitarity of the explicit map, not a simulator limitation: the dense map
    # "if allowed(x): rotate (x, x^P)" loses norm on this scenario
    ref = dense_reference(s, [0.0, 1.3, 0.0, 0.9, 0.0, 1.7], rule="paper")
    assert abs(np.linalg.norm(ref) - 1) > 1e-3
    # the exact rule is fine here
    assert SubspaceQAOA(s).dims[0] == len(enumerate_paths(s, 0))


def test_robot_basis_reports_unitarity_per_robot() -> None:
    s = make(2, 3, [((0, 0), (1, 2)), ((0, 1), (1, 0))])
    robot_basis(s, 0, "paper")
    with pytest.raises(NonUnitaryMixerError, match="robot 1"):
        robot_basis(s, 1, "paper")


def test_infeasible_basis_states_are_ordinary_basis_states(monkeypatch: pytest.MonkeyPatch) -> None:
    """A symmetric rule that leaves the feasible set (here: every flip always allowed, patched into both the
    simulator and the reference) is simulated exactly, the infeasible edge sets flagged and kept out of the
    optimum."""
    import qcpp.simulate.subspace as sub

    def always(scenario: Scenario, robot: int, plaquette: object, rule: str = "exact") -> SbfLogic:
        return SbfLogic(rule, robot, plaquette.index, 1, 0, (XorStep(0, ()),))  # type: ignore[arg-type, attr-defined]

    monkeypatch.setattr(sub, "sbf_logic", always)
    monkeypatch.setitem(globals(), "sbf_logic", always)
    s = SINGLE_3x3_SIDE
    q = SubspaceQAOA(s, rule="paper")
    start = initial_path(s, 0)
    span = {start}
    for pl in s.grid.plaquettes:
        span |= {m ^ pl.edge_mask for m in span}
    assert set(q.bases[0]) == span and len(span) == 16
    flags = q.feasible[0]
    assert flags.tolist() == [is_feasible(s, 0, m) for m in q.bases[0]] and not flags.all()
    angles = [0.4, 0.9, -0.3, 2.1]
    assert np.abs(subspace_as_dense(q, angles) - dense_reference(s, angles, rule="paper")).max() < 1e-10
    best = min(cost(s, [m]) for m, ok in zip(q.bases[0], flags) if ok)
    assert q.optimum()[0] == pytest.approx(best)
    assert all(is_feasible(s, 0, m[0]) for m in q.optimal_assignments())
    probs = q.probabilities(angles)
    assert q.p_optimum(angles) == pytest.approx(
        sum(probs[i] for i, m in enumerate(q.bases[0]) if flags[i] and np.isclose(cost(s, [m]), best))
    )


# ---------------------------------------------------------------- read-outs


def test_p_optimum_amplitude_and_state_dict() -> None:
    s = TWO_2x3
    q = SubspaceQAOA(s)
    angles = [0.3, 1.1, 0.2, 0.4]
    probs = q.probabilities(angles)
    costs = {idx: cost(s, q.assignment(idx)) for idx in np.ndindex(*q.dims)}
    best = min(costs.values())
    expected = sum(probs[i] for i, c in costs.items() if np.isclose(c, best))
    assert np.isclose(q.p_optimum(angles), expected, atol=1e-12)
    assert q.optimum()[0] == pytest.approx(best)
    assert set(q.optimal_assignments()) == {q.assignment(i) for i, c in costs.items() if np.isclose(c, best)}
    assert np.isclose(q.expectation(angles), sum(probs[i] * c for i, c in costs.items()))
    psi = q.state(angles)
    idx = (1, 2)
    masks = q.assignment(idx)
    assert q.amplitude(angles, masks) == psi[idx]
    assert q.amplitude(angles, (0, 0)) == 0j
    by_masks = q.state_dict(angles, key="masks")
    by_index = q.state_dict(angles, key="index")
    by_bits = q.state_dict(angles, key="bits")
    dense = q.dense_state(angles)
    assert by_masks[masks] == psi[idx]
    assert len(by_masks) == len(by_index) == len(by_bits) == np.count_nonzero(psi)
    for k, amp in by_index.items():
        assert dense[k] == amp
    for bits, amp in by_bits.items():
        masks_b = tuple(
            mask_from_bits(s, [int(ch) for ch in bits[r * s.edges_per_robot : (r + 1) * s.edges_per_robot]])
            for r in range(2)
        )
        assert by_masks[masks_b] == amp


def test_sampling_is_seeded_and_matches_probabilities() -> None:
    q = SubspaceQAOA(SINGLE_3x3)
    angles = [0.25, 1.2, 0.15, 0.8]
    shots = 20000
    a = q.sample(angles, shots, seed=7)
    assert a == q.sample(angles, shots, seed=7)
    assert a != q.sample(angles, shots, seed=8)
    probs = q.probabilities(angles)
    counts = np.zeros(q.dims)
    for m in a:
        counts[q.index_of(m)] += 1
    assert counts.sum() == shots
    keep = probs > 0
    assert counts[~keep].sum() == 0
    expected = probs[keep] * shots
    chi2 = float((((counts[keep] - expected) ** 2) / expected).sum())
    dof = int(keep.sum()) - 1
    # chi-square with dof degrees of freedom: mean dof, sd sqrt(2 dof); 6 sd is a very loose bound
    assert chi2 < dof + 6 * np.sqrt(2 * dof)


# ---------------------------------------------------------------- gradient


@pytest.mark.parametrize(("s", "p"), [(SINGLE_3x3, 2), (TWO_2x3, 2), (HARD_3x4, 1)])
def test_gradient_matches_finite_differences(s: Scenario, p: int) -> None:
    q = SubspaceQAOA(s, initial="representatives")
    rng = np.random.default_rng(11)
    angles = rng.uniform(0.1, 1.5, 2 * p)
    energy, grad = q.value_and_gradient(angles)
    assert np.isclose(energy, q.expectation(angles), rtol=1e-12)
    h = 1e-5
    fd = np.array([(q.expectation(angles + h * e) - q.expectation(angles - h * e)) / (2 * h) for e in np.eye(2 * p)])
    assert np.allclose(grad, fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max())
    assert np.array_equal(q.gradient(angles), grad)


def test_buffer_size_does_not_change_results() -> None:
    angles = [0.3, 1.1, 0.2, 0.4]
    for s in (TWO_2x3, THREE_2x2):
        a = SubspaceQAOA(s)
        b = SubspaceQAOA(s, buffer=1)  # one leading index per block of the transposed buffer
        assert np.allclose(a.state(angles), b.state(angles), atol=1e-14)
        assert np.allclose(a.gradient(angles), b.gradient(angles), atol=1e-12)


@pytest.mark.parametrize(
    ("s", "rule", "initial"),
    [(TWO_2x3, "exact", "initial_path"), (HARD_3x4, "exact", "representatives"), (SINGLE_2x3, "paper", "initial_path"),
     (SINGLE_3x3_CORNERS, "exact", "local_search"), (TWO_2x4, "exact", "local_search"),
     (SINGLE_3x3_CORNERS, "exact", "local_search_mix"), (TWO_2x4, "exact", "local_search_mix")],
    ids=["two-robots", "representatives", "paper-rule", "local-search", "local-search-two-robots", "mix",
         "mix-two-robots"],
)
def test_state_dict_matches_the_compiled_circuit(s: Scenario, rule: str, initial: str) -> None:
    """The data-register amplitudes of the compiled circuit (ancillas back in |0>, above the data qubits)."""
    from qcpp.plan.qaoa import qaoa_circuit
    from qcpp.simulate.sparse import simulate_sparse

    angles = [0.3, 1.1, 0.17, 0.6]
    circ = qaoa_circuit(s, 2, PlanOptions(rule=rule, initial=initial))  # type: ignore[arg-type]
    bindings = {"gamma_0": angles[0], "beta_0": angles[1], "gamma_1": angles[2], "beta_1": angles[3]}
    gate_level = simulate_sparse(circ, 0, bindings)
    mine = SubspaceQAOA(s, rule=rule, initial=initial).state_dict(angles, key="index")  # type: ignore[arg-type]
    for k in set(gate_level) | set(mine):
        assert abs(gate_level.get(k, 0) - mine.get(k, 0)) < 1e-10


def test_doctests() -> None:
    import doctest

    import qcpp.simulate.subspace

    result = doctest.testmod(qcpp.simulate.subspace)
    assert result.attempted > 0 and result.failed == 0


def test_phase_offset_names_the_compiled_representation() -> None:
    s = TWO_2x3
    assert SubspaceQAOA(s, phase_offset="whole-space").phase_offset == ising_hamiltonian(s).c0
    assert SubspaceQAOA(s, phase_offset="feasible").phase_offset == phase_plan(s).reference_constant
    assert SubspaceQAOA(s).phase_offset == phase_plan(s).reference_constant
    with pytest.raises(ValueError, match="phase_offset"):
        SubspaceQAOA(s, phase_offset="half")  # type: ignore[arg-type]


@pytest.mark.parametrize("parallel", [False, True])
@pytest.mark.parametrize("s", [SINGLE_3x3, TWO_2x3, THREE_2x2, make(3, 3, [((0, 0), (2, 2)), ((0, 2), (2, 0))])])
def test_numba_and_blas_kernels_agree(s: Scenario, parallel: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    """The lane-blocked numba kernels (every axis position: first, middle, last; line counts that leave a partial
    last block of lanes; single-threaded and parallel) give the BLAS path's state, expectation and gradient."""
    from qcpp.simulate import subspace_kernels

    if not subspace_kernels.AVAILABLE:
        pytest.skip("numba is not importable")
    monkeypatch.setattr(subspace_kernels, "PARALLEL_MIN", 1 if parallel else 1 << 40)
    fast, ref = SubspaceQAOA(s, kernels="numba"), SubspaceQAOA(s, kernels="blas")
    assert fast.kernels == "numba" and ref.kernels == "blas"
    angles = np.array([0.3, 1.1, 0.7, 0.4, 0.2, 2.0])
    assert np.allclose(fast.state(angles), ref.state(angles), atol=1e-13)
    e1, g1 = fast.value_and_gradient(angles)
    e2, g2 = ref.value_and_gradient(angles)
    assert e1 == pytest.approx(e2, rel=1e-12) and np.allclose(g1, g2, rtol=1e-10, atol=1e-12)
    psi = ref.state(angles)
    assert np.allclose(fast.level_probabilities(psi), ref.level_probabilities(psi), rtol=1e-12, atol=1e-15)
    gibbs = make_objective("gibbs", cost_scale(ref))
    f1, h1 = fast.objective_and_gradient(angles, gibbs)
    f2, h2 = ref.objective_and_gradient(angles, gibbs)
    assert f1 == pytest.approx(f2, rel=1e-12) and np.allclose(h1, h2, rtol=1e-10, atol=1e-12)
    with pytest.raises(ValueError, match="kernels"):
        SubspaceQAOA(s, kernels="gpu")  # type: ignore[arg-type]


@pytest.mark.slow
def test_parallel_kernels_on_a_state_of_many_blocks() -> None:
    """171,396 amplitudes: above the parallel threshold and several phase blocks; numba and BLAS agree."""
    from qcpp.problem.presets import default_scenario
    from qcpp.simulate import subspace_kernels

    if not subspace_kernels.AVAILABLE:
        pytest.skip("numba is not importable")
    s = default_scenario(3, 6, 2)
    fast, ref = SubspaceQAOA(s, kernels="numba"), SubspaceQAOA(s, kernels="blas")
    assert fast.dimension > 2 * subspace_kernels.PARALLEL_MIN
    angles = np.array([0.03, 1.1, 0.05, 0.4])
    e1, g1 = fast.value_and_gradient(angles)
    e2, g2 = ref.value_and_gradient(angles)
    assert e1 == pytest.approx(e2, rel=1e-12) and np.allclose(g1, g2, rtol=1e-9, atol=1e-12)



@pytest.mark.parametrize("parallel", [False, True])
@pytest.mark.parametrize("shape", [(1, 7, 5), (4, 7, 1), (3, 7, 4), (2, 7, 9), (5, 7, 3), (1, 7, 1)])
def test_lane_kernels_against_numpy_rotations(
    shape: tuple[int, int, int], parallel: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The lane-blocked kernels equal pair-by-pair numpy rotations along axis 1 on random states, for line counts
    ``pre * post`` that fill whole blocks of four lanes, leave a partial last block, or are smaller than one;
    the adjoint kernel undoes the forward one and returns ``sum_k Im <y|G_k|x>`` taken before each pair."""
    from qcpp.simulate import subspace_kernels as kern

    if not kern.AVAILABLE:
        pytest.skip("numba is not importable")
    monkeypatch.setattr(kern, "PARALLEL_MIN", 1 if parallel else 1 << 40)
    rng = np.random.default_rng(sum(shape) + parallel)
    ii, jj = np.array([0, 2, 1, 0, 5], dtype=np.intp), np.array([1, 3, 4, 6, 6], dtype=np.intp)
    c, s = float(np.cos(0.35)), complex(-1j * np.sin(0.35))
    x = rng.normal(size=shape) + 1j * rng.normal(size=shape)
    ref = x.copy()
    for i, j in zip(ii, jj):
        u, v = ref[:, i, :].copy(), ref[:, j, :].copy()
        ref[:, i, :], ref[:, j, :] = c * u + s * v, s * u + c * v
    out = x.copy()
    kern.mixer(out, ii, jj, c, s)
    assert np.allclose(out, ref, rtol=0, atol=1e-13)

    y = rng.normal(size=shape) + 1j * rng.normal(size=shape)
    ox, oy, z_ref = out.copy(), y.copy(), 0.0
    for i, j in zip(ii[::-1], jj[::-1]):
        z_ref += float(np.vdot(oy[:, i, :], ox[:, j, :]).imag + np.vdot(oy[:, j, :], ox[:, i, :]).imag)
        for a in (ox, oy):
            u, v = a[:, i, :].copy(), a[:, j, :].copy()
            a[:, i, :], a[:, j, :] = c * u - s * v, -s * u + c * v
    z = kern.mixer_adjoint(out, y, ii, jj, c, -s)
    assert z == pytest.approx(z_ref, rel=1e-12, abs=1e-12)
    assert np.allclose(out, x, rtol=0, atol=1e-13) and np.allclose(out, ox, atol=1e-13) and np.allclose(y, oy)
