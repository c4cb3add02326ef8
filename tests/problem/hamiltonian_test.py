"""The Ising Hamiltonian: coefficients against a symbolic (sympy) expansion of the cost written from the
paper's definitions, energies against the classical cost, and the paper's x = 1 - Z mapping."""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.problem.cost import QuadraticCost, cost_parts_bits
from qcpp.problem.hamiltonian import IsingHamiltonian, ising_from_quadratic, ising_hamiltonian
from qcpp.problem.scenario import Scenario


def symbolic_cost(s: Scenario, xs: list[sp.Symbol]) -> sp.Expr:
    """The objective as a sympy polynomial, written from the definitions (exact rationals)."""
    ob = s.objective
    g = s.grid
    rat = sp.Rational
    lengths = {edge: d for edge, d in ob.edge_lengths}
    ends: dict[tuple[int, int], int] = {}
    for rb in s.robots:
        for n in (rb.start, rb.goal):
            ends[n] = ends.get(n, 0) + 1
    c1 = sp.Integer(0)
    robot_len = []
    node_sum: dict[tuple[int, int], sp.Expr] = {n: sp.Integer(0) for n in g.nodes}
    for r in range(s.num_robots):
        length = sp.Integer(0)
        for e, (u, v) in enumerate(g.edges):
            touches = u in s.obstacles or v in s.obstacles
            if touches and ob.obstacles == "hard":
                continue  # not a variable
            x = xs[s.variable_index(r, e)]
            c1 += rat(ob.obstacle_weight if touches else ob.free_weight) * x
            length += rat(lengths.get((u, v), ob.edge_length)) * x
            node_sum[u] += x
            node_sum[v] += x
        robot_len.append(length)
    n = s.num_robots
    pairs = [(r, r + 1) for r in range(n - 1)] if ob.balance == "chain" else list(itertools.combinations(range(n), 2))
    c2 = sum(((robot_len[a] - robot_len[b]) ** 2 for a, b in pairs), sp.Integer(0))
    c3 = sp.Integer(0)
    for node in g.nodes:
        if ob.degree_target == "paper":
            if node in ends:
                continue
            t = 2
        else:
            t = ends.get(node, 0 if node in s.obstacles else 2)
        c3 += (node_sum[node] - t) ** 2
    a0, a1, a2 = (rat(a) for a in ob.alpha)
    return a0 * c1 + a1 * c2 + a2 * c3


def ising_coefficients(expr: sp.Expr, xs: list[sp.Symbol], scale: int = 2) -> tuple[sp.Expr, dict, dict]:
    """Substitute ``x = (1 - Z) / 2`` (``scale=2``; ``scale=1`` is the paper's ``x = 1 - Z``), expand, and
    reduce ``Z^2 = 1``. Returns ``(c0, {i: h_i}, {(i, j): J_ij})``."""
    zs = sp.symbols(f"z0:{len(xs)}")
    poly = sp.Poly(sp.expand(expr.subs({x: (1 - z) / scale for x, z in zip(xs, zs, strict=True)})), *zs)
    reduced: dict[tuple[int, ...], sp.Expr] = {}
    for monom, coeff in poly.terms():
        key = tuple(i for i, p in enumerate(monom) if p % 2)
        reduced[key] = reduced.get(key, 0) + coeff
    assert all(len(k) <= 2 for k, v in reduced.items() if v != 0)
    c0 = reduced.get((), sp.Integer(0))
    h = {k[0]: v for k, v in reduced.items() if len(k) == 1}
    J = {k: v for k, v in reduced.items() if len(k) == 2}
    return c0, h, J


SYMBOLIC_CASES = [
    # (rows, cols, robots, obstacles, mode, objective)
    (2, 2, [((0, 0), (1, 1))], [], "soft", {}),
    (2, 2, [((0, 0), (1, 1)), ((0, 1), (1, 0)), ((1, 1), (0, 0))], [], "soft", {"balance": "all-pairs"}),
    (2, 3, [((0, 0), (1, 2))], [(0, 1)], "soft", {"alpha": [0.5, 2.0, 1.5], "obstacle_weight": 3.0}),
    (2, 3, [((0, 0), (0, 2)), ((1, 0), (0, 2))], [(1, 1)], "soft", {"edge_lengths": [[[0, 0], [0, 1], 2.5]]}),
    (2, 3, [((0, 0), (0, 2)), ((1, 2), (1, 0))], [(1, 1)], "hard", {"degree_target": "paper", "free_weight": -0.25}),
    (2, 3, [((0, 0), (1, 2)), ((0, 2), (1, 0))], [], "soft", {"degree_target": "paper", "alpha": [1.0, 0.75, 2.0]}),
]


@pytest.mark.parametrize(("rows", "cols", "robots", "obstacles", "mode", "objective"), SYMBOLIC_CASES)
def test_coefficients_match_sympy(
    build: Any, rows: int, cols: int, robots: Any, obstacles: Any, mode: str, objective: Any
) -> None:
    s = build(rows, cols, robots, obstacles, mode=mode, **objective)
    xs = list(sp.symbols(f"x0:{s.num_variables}"))
    c0, h, J = ising_coefficients(symbolic_cost(s, xs), xs)
    H = ising_hamiltonian(s)
    assert H.num_qubits == s.num_variables
    assert abs(H.c0 - float(c0)) < 1e-9
    for i in range(s.num_variables):
        assert abs(H.h[i] - float(h.get(i, 0))) < 1e-9, i
    for i in range(s.num_variables):
        assert H.J[i, i] == 0
        for j in range(s.num_variables):
            want = float(J.get((i, j), 0)) if i < j else 0.0
            assert abs(H.J[i, j] - want) < 1e-9, (i, j)
    # the symbolic cost itself agrees with the classical evaluator on a few bit strings
    rng = np.random.default_rng(1)
    for bits in rng.integers(0, 2, size=(5, s.num_variables)):
        val = float(symbolic_cost(s, xs).subs(dict(zip(xs, map(int, bits), strict=True))))
        assert abs(val - cost_parts_bits(s, bits)[3]) < 1e-9


def test_paper_mapping_x_equals_1_minus_z_evaluates_the_cost_at_2x(build: Any) -> None:
    """With the paper's ``x = 1 - Z`` the diagonal energy of basis state x is cost(2x), not cost(x):
    linear terms doubled, quadratic terms quadrupled (so J is 4x too large)."""
    s = build(2, 3, [((0, 0), (1, 2))], [(0, 1)])
    xs = list(sp.symbols(f"x0:{s.num_variables}"))
    expr = symbolic_cost(s, xs)
    c0, h, J = ising_coefficients(expr, xs, scale=1)
    H = ising_hamiltonian(s)
    for (i, j), v in J.items():
        assert abs(float(v) - 4 * H.J[i, j]) < 1e-9
    differs = 0
    for bits in itertools.product((0, 1), repeat=s.num_variables):
        z = [1 - 2 * b for b in bits]
        e_paper = float(c0 + sum(v * z[i] for i, v in h.items()) + sum(v * z[i] * z[j] for (i, j), v in J.items()))
        assert abs(e_paper - float(expr.subs({x: 2 * b for x, b in zip(xs, bits, strict=True)}))) < 1e-9
        differs += abs(e_paper - H.evaluate(np.array(bits))) > 1e-9
    assert differs > 0


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_energy_equals_cost(data: st.DataObject, random_scenarios: Any) -> None:
    _assert_energy_equals_cost(data, random_scenarios)


@pytest.mark.heavy
@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_energy_equals_cost_on_more_scenarios(data: st.DataObject, random_scenarios: Any) -> None:
    """The default run's property on 100 scenarios."""
    _assert_energy_equals_cost(data, random_scenarios)


def _assert_energy_equals_cost(data: st.DataObject, random_scenarios: Any) -> None:
    s = data.draw(random_scenarios(max_size=6, max_robots=4))
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1), label="seed"))
    bits = (rng.random((8, s.num_variables)) < 0.4).astype(np.uint8)
    H = ising_hamiltonian(s)
    energies = H.evaluate(bits)
    costs = cost_parts_bits(s, bits)[:, 3]
    for e, c in zip(energies, costs, strict=True):
        assert abs(e - c) <= 1e-9 * max(1.0, abs(c))
    assert abs(H.evaluate(bits[0]) - costs[0]) <= 1e-9 * max(1.0, abs(costs[0]))


@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_ising_from_quadratic_brute_force(data: st.DataObject) -> None:
    n = data.draw(st.integers(1, 6))
    num = st.floats(-5, 5, allow_nan=False)
    k = data.draw(num)
    lin = np.array(data.draw(st.lists(num, min_size=n, max_size=n)))
    quad = np.triu(np.array(data.draw(st.lists(num, min_size=n * n, max_size=n * n))).reshape(n, n), 1)
    q = QuadraticCost(k, lin, quad)
    H = ising_from_quadratic(q)
    for bits in itertools.product((0, 1), repeat=n):
        x = np.array(bits, dtype=float)
        want = k + lin @ x + sum(quad[i, j] * x[i] * x[j] for i in range(n) for j in range(i + 1, n))
        assert abs(H.evaluate(x) - want) < 1e-9
        assert abs(q.evaluate(x) - want) < 1e-9


def test_term_listings() -> None:
    H = IsingHamiltonian(1.0, np.array([0.0, -2.0, 1e-12, 3.0]), np.triu(np.arange(16.0).reshape(4, 4) - 8, 1))
    assert list(H.linear_terms()) == [(1, -2.0), (2, 1e-12), (3, 3.0)]
    assert list(H.linear_terms(tol=1e-9)) == [(1, -2.0), (3, 3.0)]
    quads = list(H.quadratic_terms())
    assert quads == [(i, j, H.J[i, j]) for i in range(4) for j in range(i + 1, 4) if H.J[i, j] != 0]
    assert H.num_quadratic_terms() == len(quads)
    assert H.num_quadratic_terms(tol=2.5) == sum(1 for *_, v in quads if abs(v) > 2.5)


def test_couplings_are_not_only_between_consecutive_robots(build: Any) -> None:
    """The paper's final form writes its quadratic terms as Z_{r,i} Z_{r+1,j}. The exact expansion also
    couples edges of the same robot (L_r^2 in c2, the node sums in c3), and with ``all-pairs`` robots r and
    r+2."""
    s = build(2, 3, [((0, 0), (1, 2)), ((0, 2), (1, 0)), ((1, 1), (0, 1))], balance="all-pairs")
    H = ising_hamiltonian(s)
    v = s.edges_per_robot
    block = [[np.count_nonzero(np.abs(H.J[r * v : (r + 1) * v, t * v : (t + 1) * v]) > 1e-12) for t in range(3)]
             for r in range(3)]
    assert all(block[r][r] > 0 for r in range(3))  # same robot
    assert block[0][2] > 0  # robots 0 and 2
    chain = ising_hamiltonian(build(2, 3, [((0, 0), (1, 2)), ((0, 2), (1, 0)), ((1, 1), (0, 1))]))
    # chain: robots 0 and 2 only share c3 (edges at a common node), far fewer terms than all-pairs
    assert np.count_nonzero(np.abs(chain.J[:v, 2 * v :]) > 1e-12) < block[0][2]


def test_ten_by_ten_with_four_robots_builds(build: Any) -> None:
    robots = [((0, 0), (9, 9)), ((0, 9), (9, 0)), ((9, 0), (0, 9)), ((9, 9), (0, 0))]
    s = build(10, 10, robots, [(4, 4), (5, 5)], balance="all-pairs")
    H = ising_hamiltonian(s)
    n = 4 * (10 * 9 + 10 * 9)
    assert H.num_qubits == s.num_variables == n
    assert H.J.shape == (n, n) and np.array_equal(H.J, np.triu(H.J, 1))
    bits = (np.random.default_rng(5).random((3, n)) < 0.3).astype(np.uint8)
    got, want = H.evaluate(bits), cost_parts_bits(s, bits)[:, 3]
    assert np.allclose(got, want, rtol=1e-9, atol=1e-9)
