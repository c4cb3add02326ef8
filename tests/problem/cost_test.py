"""The objective c = alpha0*c1 + alpha1*c2 + alpha2*c3: hand-computed cases, a reference written from the
definitions with plain loops, and agreement of every evaluator (term-wise, quadratic, Ising, separable)."""

from __future__ import annotations

import itertools
from collections import deque
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.problem.cost import (
    CostParts,
    balanced_pairs,
    cost,
    cost_parts,
    cost_parts_bits,
    quadratic_cost,
    separable_cost,
)
from qcpp.problem.grid import Node
from qcpp.problem.hamiltonian import ising_hamiltonian
from qcpp.problem.paths import (
    assignment_bits,
    assignment_from_bits,
    edges_of,
    enumerate_paths,
    initial_path,
    mask_from_bits,
    path_from_nodes,
    path_to_nodes,
    paths_matrix,
    shortest_path,
)
from qcpp.problem.sbf import allowed_moves
from qcpp.problem.scenario import Scenario, scenario_from_dict, scenario_to_dict
from qcpp.problem.scenario_io import load_scenario

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


# ---------------------------------------------------------------- reference written from the definitions


def ref_targets(s: Scenario) -> dict[Node, float | None]:
    """Degree target per node from the documented rules (None = left out of c3)."""
    ends: dict[Node, int] = {}
    for rb in s.robots:
        for n in (rb.start, rb.goal):
            ends[n] = ends.get(n, 0) + 1
    out: dict[Node, float | None] = {}
    for r in range(s.grid.rows):
        for c in range(s.grid.cols):
            n = (r, c)
            if s.objective.degree_target == "paper":
                out[n] = None if n in ends else 2.0
            elif n in ends:
                out[n] = float(ends[n])
            elif n in s.obstacles:
                out[n] = 0.0
            else:
                out[n] = 2.0
    return out


def ref_cost(s: Scenario, masks: list[int]) -> tuple[float, float, float, float]:
    ob = s.objective
    lengths = {edge: d for edge, d in ob.edge_lengths}
    c1 = 0.0
    robot_length = []
    degree: dict[Node, int] = {}
    for mask in masks:
        total_length = 0.0
        for e in edges_of(mask):
            u, v = s.grid.edges[e]
            c1 += ob.obstacle_weight if (u in s.obstacles or v in s.obstacles) else ob.free_weight
            total_length += lengths.get((u, v), ob.edge_length)
            degree[u] = degree.get(u, 0) + 1
            degree[v] = degree.get(v, 0) + 1
        robot_length.append(total_length)
    n = len(masks)
    pairs = [(r, r + 1) for r in range(n - 1)] if ob.balance == "chain" else list(itertools.combinations(range(n), 2))
    c2 = sum((robot_length[r] - robot_length[t]) ** 2 for r, t in pairs)
    c3 = 0.0
    for node, target in ref_targets(s).items():
        if target is not None:
            c3 += (degree.get(node, 0) - target) ** 2
    a0, a1, a2 = ob.alpha
    return c1, c2, c3, a0 * c1 + a1 * c2 + a2 * c3


def close(a: float, b: float) -> bool:
    return abs(a - b) <= 1e-9 * max(1.0, abs(a), abs(b))


# ---------------------------------------------------------------- hand-computed cases


def test_hand_case_single_robot(build: Any) -> None:
    # 2x3 grid, soft obstacle at (1,1); robot (0,0) -> (0,2)
    s = build(2, 3, [((0, 0), (0, 2))], [(1, 1)])
    g = s.grid
    top = path_from_nodes(g, [(0, 0), (0, 1), (0, 2)])
    # two free edges: c1 = -2. exact targets: ends 1, obstacle 0, others 2.
    # degrees: (0,0)1 (0,1)2 (0,2)1 (1,0)0 (1,1)0 (1,2)0 -> c3 = 0+0+0+4+0+4 = 8
    assert cost_parts(s, [top]) == CostParts(-2.0, 0.0, 8.0, 6.0)
    around = path_from_nodes(g, [(0, 0), (1, 0), (1, 1), (1, 2), (0, 2)])
    # edges: (0,0)-(1,0) free, (1,0)-(1,1) obstacle, (1,1)-(1,2) obstacle, (1,2)-(0,2) free: c1 = -1+1+1-1 = 0
    # degrees: (0,0)1 (0,1)0 (0,2)1 (1,0)2 (1,1)2 (1,2)2 -> c3 = 0 + 4 + 0 + 0 + (2-0)^2 + 0 = 8
    assert cost_parts(s, [around]) == CostParts(0.0, 0.0, 8.0, 8.0)
    paper = build(2, 3, [((0, 0), (0, 2))], [(1, 1)], degree_target="paper")
    # paper targets: ends left out, everything else 2 (the obstacle too): top -> (0,1) 0, bottom row 4+4+4
    assert cost_parts(paper, [top]) == CostParts(-2.0, 0.0, 12.0, 10.0)


def test_hand_case_balance_chain_vs_all_pairs(build: Any) -> None:
    robots = [((0, 0), (0, 1)), ((1, 0), (1, 2)), ((2, 0), (0, 2))]
    paths = [
        [(0, 0), (0, 1)],  # length 1
        [(1, 0), (1, 1), (1, 2)],  # length 2
        [(2, 0), (2, 1), (2, 2), (1, 2), (0, 2)],  # length 4
    ]
    for balance, want in [("chain", (1 - 2) ** 2 + (2 - 4) ** 2), ("all-pairs", 1 + 4 + (1 - 4) ** 2)]:
        s = build(3, 3, robots, balance=balance, alpha=[0.0, 1.0, 0.0])
        masks = [path_from_nodes(s.grid, p) for p in paths]
        parts = cost_parts(s, masks)
        assert parts.c2 == want and parts.total == want
    s = build(3, 3, robots)
    assert balanced_pairs(s) == [(0, 1), (1, 2)]
    assert balanced_pairs(build(3, 3, robots, balance="all-pairs")) == [(0, 1), (0, 2), (1, 2)]
    assert balanced_pairs(build(3, 3, robots[:1])) == [] == balanced_pairs(build(3, 3, robots[:1], balance="all-pairs"))
    # edge lengths enter c2: make robot 0's edge 3 long -> chain (3-2)^2 + (2-4)^2 = 5
    s = build(3, 3, robots, alpha=[0.0, 1.0, 0.0], edge_lengths=[[[0, 1], [0, 0], 3.0]])
    assert cost_parts(s, [path_from_nodes(s.grid, p) for p in paths]).c2 == 5.0


def test_degree_targets_exact_and_paper(build: Any) -> None:
    # robot 0 ends where robot 1 starts; robot 2 shares robot 0's goal: that node is an endpoint 3 times
    robots = [((0, 0), (1, 1)), ((1, 1), (2, 2)), ((0, 2), (1, 1))]
    for target in ("exact", "paper"):
        s = build(3, 3, robots, [(2, 0)], degree_target=target)
        want = ref_targets(s)
        got = s.degree_targets
        for node, t in want.items():
            i = s.grid.node_index(node)
            assert (np.isnan(got[i]) and t is None) or got[i] == t
    exact = build(3, 3, robots, [(2, 0)]).degree_targets
    assert exact[4] == 3.0 and exact[0] == 1.0 and exact[6] == 0.0 and exact[1] == 2.0
    paper = build(3, 3, robots, [(2, 0)], degree_target="paper").degree_targets
    assert np.isnan(paper[4]) and np.isnan(paper[0]) and paper[6] == 2.0


def test_wrong_number_of_paths(build: Any) -> None:
    s = build(2, 2, [((0, 0), (1, 1)), ((0, 1), (1, 0))])
    with pytest.raises(ValueError, match="expected 2 paths"):
        cost_parts(s, [initial_path(s, 0)])
    with pytest.raises(ValueError, match="expected 2 path lists"):
        separable_cost(s, [[initial_path(s, 0)]])


# ---------------------------------------------------------------- all evaluators agree


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_evaluators_agree_on_random_bits(data: st.DataObject, random_scenarios: Any) -> None:
    s = data.draw(random_scenarios(max_size=5, max_robots=4))
    n = s.num_variables
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1), label="seed"))
    density = data.draw(st.sampled_from([0.1, 0.3, 0.5, 0.9]), label="density")
    bits = np.vstack([np.zeros(n), np.ones(n), rng.random((4, n)) < density]).astype(np.uint8)
    parts = cost_parts_bits(s, bits)
    quad, ising = quadratic_cost(s), ising_hamiltonian(s)
    q, h = quad.evaluate(bits), ising.evaluate(bits)
    # The two forms sum large terms that cancel (a cost of 0 from terms of 1e4), so their rounding error scales
    # with the sum of |coefficients|, not with the cost: a tolerance relative to the cost alone fails by chance.
    q_scale = abs(quad.const) + np.abs(quad.linear).sum() + np.abs(quad.quad).sum()
    h_scale = abs(ising.c0) + np.abs(ising.h).sum() + np.abs(ising.J).sum()
    for row, p, qv, hv in zip(bits, parts, q, h, strict=True):
        masks = list(assignment_from_bits(s, row))
        want = ref_cost(s, masks)
        assert all(close(a, b) for a, b in zip(p, want, strict=True)), (p, want)
        assert abs(qv - p[3]) <= 1e-12 * max(1.0, q_scale), (qv, p[3], q_scale)
        assert abs(hv - p[3]) <= 1e-12 * max(1.0, h_scale), (hv, p[3], h_scale)
        assert close(cost(s, masks), p[3])
        assert tuple(cost_parts_bits(s, row)) == tuple(p)  # one row -> a vector


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_separable_cost_agrees(data: st.DataObject, random_scenarios: Any) -> None:
    s = data.draw(random_scenarios(max_size=4, max_robots=3))
    v = s.edges_per_robot
    lists = []
    for r in range(s.num_robots):
        # candidates: the initial and a shortest path plus arbitrary edge sets (the decomposition is algebra)
        extra = data.draw(st.lists(st.lists(st.integers(0, 1), min_size=v, max_size=v), max_size=3))
        cands = [initial_path(s, r), shortest_path(s, r)]
        cands += [mask_from_bits(s, b) for b in extra]
        lists.append(cands)
    sep = separable_cost(s, lists)
    tensor = sep.full_tensor()
    assert tensor.shape == tuple(len(c) for c in lists)
    for idx in itertools.product(*(range(len(c)) for c in lists)):
        masks = [lists[r][i] for r, i in enumerate(idx)]
        want = ref_cost(s, masks)[3]
        assert close(sep.evaluate(idx), want)
        assert close(float(tensor[idx]), want)


def test_quadratic_form_shape(build: Any) -> None:
    s = build(3, 3, [((0, 0), (2, 2)), ((2, 0), (0, 2))], [(1, 1)], mode="hard")
    q = quadratic_cost(s)
    n = s.num_variables
    assert q.linear.shape == (n,) and q.quad.shape == (n, n)
    assert np.array_equal(q.quad, np.triu(q.quad, 1))  # strictly upper triangular
    # exhaustive over all assignments of one robot's variables (the other robot fixed to its initial path)
    other = initial_path(s, 1)
    v = s.edges_per_robot
    all_bits = ((np.arange(1 << v)[:, None] >> np.arange(v)) & 1).astype(np.uint8)
    rows = np.hstack([all_bits, np.tile(assignment_bits(s, [0, other])[v:], (len(all_bits), 1))])
    got = q.evaluate(rows)
    for row, val in zip(rows[::37], got[::37], strict=True):
        assert close(val, ref_cost(s, list(assignment_from_bits(s, row)))[3])


# ---------------------------------------------------------------- the bundled paper example


def test_paper_3x3_example_has_an_interesting_optimum() -> None:
    """examples/paper_3x3.toml: the unique optimal path avoids both obstacles, visits every free node, is
    not the initial path (which crosses the wall), lies four SBF moves from it, and is also the minimum over
    all 2^12 bit strings (so the feasible optimum is the unconstrained one)."""
    s = load_scenario(EXAMPLES / "paper_3x3.toml")
    g = s.grid
    paths = enumerate_paths(s, 0)
    costs = cost_parts_bits(s, paths_matrix(s, paths))[:, 3]
    best = float(costs.min())
    winners = [p for p, c in zip(paths, costs, strict=True) if c == best]
    assert len(winners) == 1
    opt = winners[0]
    nodes = path_to_nodes(g, opt, s.robots[0].start)
    assert not set(nodes) & s.obstacle_set
    assert set(nodes) == set(g.nodes) - s.obstacle_set
    init = initial_path(s, 0)
    assert opt != init and set(path_to_nodes(g, init, s.robots[0].start)) & s.obstacle_set
    # SBF distance (exact rule) by BFS
    dist = {init: 0}
    queue = deque([init])
    while queue:
        m = queue.popleft()
        for qi in allowed_moves(s, 0, m):
            y = m ^ g.plaquettes[qi].edge_mask
            if y not in dist:
                dist[y] = dist[m] + 1
                queue.append(y)
    assert dist[opt] == 4
    all_bits = ((np.arange(1 << s.num_variables)[:, None] >> np.arange(s.num_variables)) & 1).astype(np.uint8)
    assert cost_parts_bits(s, all_bits)[:, 3].min() == best


def test_paper_degree_targets_pull_paths_through_obstacles() -> None:
    """The paper's c3 asks degree 2 of every node, obstacles included. On examples/paper_3x3.toml that
    makes every optimal path visit both obstacles (and the optimum is no longer unique); the ``exact``
    targets (obstacles 0) give the unique detour."""
    base = load_scenario(EXAMPLES / "paper_3x3.toml")
    optima = {}
    for target in ("exact", "paper"):
        d = scenario_to_dict(base)
        d["objective"]["degree_target"] = target
        s = scenario_from_dict(d)
        paths = enumerate_paths(s, 0)
        costs = cost_parts_bits(s, paths_matrix(s, paths))[:, 3]
        optima[target] = [set(path_to_nodes(s.grid, p, s.robots[0].start))
                          for p, c in zip(paths, costs, strict=True) if c == costs.min()]
    assert len(optima["exact"]) == 1 and not optima["exact"][0] & base.obstacle_set
    assert len(optima["paper"]) > 1
    assert all(base.obstacle_set <= nodes for nodes in optima["paper"])
