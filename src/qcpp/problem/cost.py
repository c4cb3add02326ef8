"""The paper's objective ``c = alpha0*c1 + alpha1*c2 + alpha2*c3`` and exact ways to evaluate it.

With ``x[r, e]`` the decision variables, ``w_e`` the edge weights, ``d_e`` the edge lengths,
``L_r = sum_e d_e x[r, e]`` robot ``r``'s path length and ``D_i = sum_r sum_{e at i} x[r, e]`` the degree of
node ``i`` summed over robots:

* ``c1 = sum_{r, e} w_e x[r, e]`` (obstacles and coverage);
* ``c2 = sum_{(r, s)} (L_r - L_s)^2`` over the balanced pairs: ``chain`` = ``(r, r+1)``, ``all-pairs`` =
  every ``r < s`` (zero for one robot);
* ``c3 = sum_i (D_i - t_i)^2`` over the nodes with a target degree ``t_i``
  (:attr:`qcpp.problem.scenario.Scenario.degree_targets`).

Three evaluators share one definition of the terms:

* :func:`cost_parts` on one assignment (one edge mask per robot), term by term;
* :func:`quadratic_cost` -- the same cost as a quadratic polynomial in the bits (the input of the Ising
  Hamiltonian);
* :func:`separable_cost` -- the cost over lists of candidate paths as unary vectors plus pairwise matrices
  (what exhaustive search and the feasible-subspace simulator need), and :func:`assignment_costs`, its sum as
  one array over every assignment of those paths.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.problem.paths import initial_path
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
    >>> cost_parts(s, [initial_path(s, 0)])
    CostParts(c1=-2.0, c2=0.0, c3=4.0, total=2.0)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from qcpp.problem.paths import paths_matrix
from qcpp.problem.scenario import Scenario


class CostParts(NamedTuple):
    """The objective's parts (unweighted) and the weighted total."""

    c1: float
    c2: float
    c3: float
    total: float


def balanced_pairs(scenario: Scenario) -> list[tuple[int, int]]:
    """The robot pairs whose path lengths are balanced by ``c2``."""
    n = scenario.num_robots
    if scenario.objective.balance == "chain":
        return [(r, r + 1) for r in range(n - 1)]
    return [(r, s) for r in range(n) for s in range(r + 1, n)]


def _incidence(scenario: Scenario) -> np.ndarray:
    """``(edges_per_robot, nodes)`` 0/1 matrix: variable edge k touches node i."""
    g = scenario.grid
    inc = np.zeros((scenario.edges_per_robot, g.num_nodes))
    for k, e in enumerate(scenario.variable_edges):
        a, b = g.edge_nodes[e]
        inc[k, a] = inc[k, b] = 1.0
    return inc


def _robot_vectors(scenario: Scenario) -> tuple[np.ndarray, np.ndarray]:
    """Per-variable-edge weights and lengths (length ``edges_per_robot``)."""
    ve = np.array(scenario.variable_edges, dtype=np.int64)
    return scenario.edge_weights[ve], scenario.edge_lengths[ve]


def cost_parts_bits(scenario: Scenario, bits: np.ndarray) -> np.ndarray:
    """Cost parts of many assignments at once.

    Args:
        bits: ``(N, num_variables)`` 0/1 array (variable-index order), or one such row.

    Returns:
        ``(N, 4)`` float array of ``c1, c2, c3, total`` (or a length-4 vector for one row).
    """
    x = np.asarray(bits, dtype=float)
    single = x.ndim == 1
    x = np.atleast_2d(x)
    n_r, v = scenario.num_robots, scenario.edges_per_robot
    xr = x.reshape(len(x), n_r, v)
    w, d = _robot_vectors(scenario)
    c1 = (xr @ w).sum(axis=1)
    lengths = xr @ d
    c2 = np.zeros(len(x))
    for r, s in balanced_pairs(scenario):
        c2 += (lengths[:, r] - lengths[:, s]) ** 2
    deg = (xr @ _incidence(scenario)).sum(axis=1)
    t = scenario.degree_targets
    keep = ~np.isnan(t)
    c3 = ((deg[:, keep] - t[keep]) ** 2).sum(axis=1)
    a0, a1, a2 = scenario.objective.alpha
    out = np.stack([c1, c2, c3, a0 * c1 + a1 * c2 + a2 * c3], axis=1)
    return out[0] if single else out


def cost_parts(scenario: Scenario, masks: Sequence[int]) -> CostParts:
    """The objective of one assignment (one edge mask per robot, in robot order)."""
    if len(masks) != scenario.num_robots:
        raise ValueError(f"expected {scenario.num_robots} paths, got {len(masks)}")
    bits = np.concatenate([paths_matrix(scenario, [m])[0] for m in masks])
    c1, c2, c3, total = (float(v) for v in cost_parts_bits(scenario, bits))
    return CostParts(c1, c2, c3, total)


def cost(scenario: Scenario, masks: Sequence[int]) -> float:
    """The weighted total of :func:`cost_parts`."""
    return cost_parts(scenario, masks).total


@dataclass(frozen=True, eq=False)
class QuadraticCost:
    """``cost(x) = const + linear . x + sum_{i<j} quad[i, j] x_i x_j`` over 0/1 variables.

    Attributes:
        const: Constant term.
        linear: ``(n,)`` coefficients.
        quad: ``(n, n)`` strictly upper-triangular coefficients.
    """

    const: float
    linear: np.ndarray
    quad: np.ndarray

    def evaluate(self, bits: np.ndarray) -> np.ndarray | float:
        """Evaluate on one ``(n,)`` or many ``(N, n)`` 0/1 rows."""
        x = np.asarray(bits, dtype=float)
        val = self.const + x @ self.linear + np.einsum("...i,ij,...j->...", x, self.quad, x)
        return float(val) if np.ndim(val) == 0 else val


def quadratic_cost(scenario: Scenario) -> QuadraticCost:
    """The objective as a quadratic polynomial in the decision variables (``x^2 = x`` folded into linear).

    Each squared term ``(a . x - b)^2`` (one per balanced pair and one per node with a degree target)
    expands to ``x^T a a^T x - 2 b a . x + b^2``; the rows ``a`` are stacked and multiplied once with numpy.
    """
    n_r, v = scenario.num_robots, scenario.edges_per_robot
    n = n_r * v
    a0, a1, a2 = scenario.objective.alpha
    w, d = _robot_vectors(scenario)
    rows: list[np.ndarray] = []
    targets: list[float] = []
    scales: list[float] = []
    for r, s in balanced_pairs(scenario):
        a = np.zeros(n)
        a[r * v : (r + 1) * v] = d
        a[s * v : (s + 1) * v] = -d
        rows.append(a)
        targets.append(0.0)
        scales.append(a1)
    inc = _incidence(scenario)
    t = scenario.degree_targets
    for i in range(scenario.grid.num_nodes):
        if np.isnan(t[i]):
            continue
        rows.append(np.tile(inc[:, i], n_r))
        targets.append(float(t[i]))
        scales.append(a2)
    linear = a0 * np.tile(w, n_r)
    const = 0.0
    quad_full = np.zeros((n, n))
    if rows:
        a_mat = np.array(rows)
        b = np.array(targets)
        sc = np.array(scales)
        quad_full = (a_mat * sc[:, None]).T @ a_mat
        linear = linear + np.diag(quad_full) - 2 * (a_mat.T @ (sc * b))
        const = float(np.sum(sc * b * b))
    quad = 2 * np.triu(quad_full, 1)
    return QuadraticCost(const, linear, quad)


@dataclass(frozen=True, eq=False)
class SeparableCost:
    """The total cost over per-robot path lists: ``const + sum_r unary[r][i_r] + sum_{r<s} pair[(r, s)][i_r, i_s]``.

    Attributes:
        const: Constant part.
        unary: One vector per robot (length = that robot's number of candidate paths).
        pairwise: Matrices for the coupled robot pairs ``(r, s)``, ``r < s``.
    """

    const: float
    unary: tuple[np.ndarray, ...]
    pairwise: dict[tuple[int, int], np.ndarray]

    def evaluate(self, indices: Sequence[int]) -> float:
        """Total cost of choosing path ``indices[r]`` for every robot ``r``."""
        val = self.const + sum(float(u[i]) for u, i in zip(self.unary, indices, strict=True))
        for (r, s), m in self.pairwise.items():
            val += float(m[indices[r], indices[s]])
        return val

    def full_tensor(self) -> np.ndarray:
        """The cost of every combination as a dense array of shape ``(n_0, n_1, ...)`` (small cases)."""
        n_r = len(self.unary)
        out = np.full(tuple(len(u) for u in self.unary), self.const)
        for r, u in enumerate(self.unary):
            shape = [1] * n_r
            shape[r] = len(u)
            out = out + u.reshape(shape)
        for (r, s), m in self.pairwise.items():
            shape = [1] * n_r
            shape[r], shape[s] = m.shape
            out = out + m.reshape(shape)
        return out


def separable_cost(scenario: Scenario, path_lists: Sequence[Sequence[int]]) -> SeparableCost:
    """Decompose the weighted total over candidate paths (one list of edge masks per robot).

    Args:
        path_lists: For each robot, its candidate paths (e.g. :func:`~qcpp.problem.paths.enumerate_paths`).

    Returns:
        A :class:`SeparableCost`; ``evaluate(i)`` equals :func:`cost` of the chosen paths.
    """
    if len(path_lists) != scenario.num_robots:
        raise ValueError(f"expected {scenario.num_robots} path lists, got {len(path_lists)}")
    a0, a1, a2 = scenario.objective.alpha
    w, d = _robot_vectors(scenario)
    inc = _incidence(scenario)
    t = scenario.degree_targets
    keep = ~np.isnan(t)
    tk = t[keep]
    mats = [paths_matrix(scenario, pl).astype(float) for pl in path_lists]
    lengths = [m @ d for m in mats]
    degs = [(m @ inc)[:, keep] for m in mats]
    unary = [a0 * (m @ w) + a2 * ((dg**2).sum(axis=1) - 2 * dg @ tk) for m, dg in zip(mats, degs, strict=True)]
    const = a2 * float(tk @ tk)
    pairwise: dict[tuple[int, int], np.ndarray] = {}
    for r, s in balanced_pairs(scenario):
        unary[r] = unary[r] + a1 * lengths[r] ** 2
        unary[s] = unary[s] + a1 * lengths[s] ** 2
        pairwise[(r, s)] = -2 * a1 * np.outer(lengths[r], lengths[s])
    for r in range(scenario.num_robots):
        for s in range(r + 1, scenario.num_robots):
            m = 2 * a2 * degs[r] @ degs[s].T
            pairwise[(r, s)] = pairwise[(r, s)] + m if (r, s) in pairwise else m
    return SeparableCost(const, tuple(unary), pairwise)


def assignment_costs(scenario: Scenario, path_lists: Sequence[Sequence[int]]) -> np.ndarray:
    """The cost of every assignment of one path per robot from ``path_lists`` (edge masks): the sum of
    :func:`separable_cost`'s parts, built in place (for two robots the pairwise matrix becomes the result, so the
    peak holds one full-size array; :meth:`SeparableCost.full_tensor` adds into new arrays).

    Returns:
        A writable float64 array of shape ``(len(paths) for paths in path_lists)``.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> from qcpp.problem.paths import enumerate_paths
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3},
        ...                         "robots": [{"start": [0, 0], "goal": [1, 2]}, {"start": [1, 0], "goal": [0, 2]}]})
        >>> lists = [enumerate_paths(s, r) for r in range(2)]
        >>> costs = assignment_costs(s, lists)
        >>> costs.shape, bool(np.allclose(costs, separable_cost(s, lists).full_tensor()))
        ((4, 4), True)
    """
    sep = separable_cost(scenario, path_lists)
    dims = tuple(len(paths) for paths in path_lists)
    nr = len(dims)
    unary, pairwise, const = sep.unary, dict(sep.pairwise), sep.const
    del sep
    if nr == 2 and (0, 1) in pairwise:
        costs = np.require(pairwise.pop((0, 1)), dtype=np.float64, requirements=["C", "W", "O"])
        costs += const
    else:
        costs = np.full(dims, const, dtype=np.float64)
    for r, u in enumerate(unary):
        shape = [1] * nr
        shape[r] = dims[r]
        costs += u.reshape(shape)
    for (r, s), m in pairwise.items():
        shape = [1] * nr
        shape[r], shape[s] = dims[r], dims[s]
        costs += m.reshape(shape)
    return costs
