"""The cost as a binary quadratic model (BQM / QUBO) for annealers, in two forms.

A :class:`Bqm` is plain Python data (labels, linear and quadratic coefficients over 0/1 variables, an offset):
``E(b) = offset + sum_i linear[i] b_i + sum_k quad_val[k] b_{quad_i[k]} b_{quad_j[k]}``. Nothing here needs
dimod; :func:`to_dimod` converts when asked (``pip install 'qcpp[annealing]'``).

Variable labels (any tool can decode them):

* ``x{r}:{r1},{c1}-{r2},{c2}`` -- robot ``r`` uses the edge between nodes ``(r1, c1)`` and ``(r2, c2)``, the
  row-major smaller node first. These come first, in qcpp's variable order (index ``r * V + k``, see
  :mod:`qcpp.problem.scenario`), so ``b[:num_edge_variables]`` is an ordinary qcpp bit string.
* ``y{r}:{row},{col}`` -- auxiliary (``per-robot`` form only): robot ``r`` visits node ``(row, col)``.

The two forms:

* ``paper``: exactly qcpp's cost, :func:`qcpp.problem.cost.quadratic_cost`. Its degree term counts a node's
  edges over all robots, so with two or more robots its ground state can be infeasible (docs/qubo.md).
* ``per-robot`` (default): the ``paper`` cost plus per-robot degree penalties with visit bits,
  ``P (S_rv - 2 y_rv)^2`` at every node ``v`` that is not an end of robot ``r`` and ``P (S_rv - 1)^2`` at its
  start and goal (``S_rv`` = robot ``r``'s edges at ``v``): zero exactly when every robot has degree 1 at its
  ends and 0 or 2 elsewhere, so on every feasible assignment the energy is the cost. A path plus separate cycles
  also has zero penalty (degrees cannot see connectivity); decoders drop the cycles.

With ``P`` from :func:`penalty_rule` every assignment with a non-zero penalty has energy above the optimum.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> m = per_robot_bqm(s, penalty=5.0)
    >>> m.labels[0], m.labels[m.num_edge_variables], m.form
    ('x0:0,0-0,1', 'y0:0,1', 'per-robot')
    >>> from qcpp.problem.paths import initial_path, assignment_bits
    >>> from qcpp.problem.cost import cost
    >>> p = (initial_path(s, 0),)
    >>> m.energy(best_auxiliaries(m, assignment_bits(s, p))) == cost(s, p)
    True
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from qcpp.problem.cost import cost, quadratic_cost
from qcpp.problem.grid import Node
from qcpp.problem.paths import assignment_from_bits, initial_path
from qcpp.problem.scenario import Scenario

__all__ = [
    "FORMS",
    "Bqm",
    "PenaltyRule",
    "best_auxiliaries",
    "bqm_for",
    "decode_edges",
    "edge_label",
    "paper_bqm",
    "parse_label",
    "penalty_rule",
    "per_robot_bqm",
    "to_dimod",
    "to_ising",
    "visit_label",
]

Form = Literal["paper", "per-robot"]
FORMS: tuple[Form, ...] = ("per-robot", "paper")
"""The BQM forms, the default first."""

RULE_ANNEAL_ITERATIONS = 1000
"""Iterations of the SBF annealing run whose cost is :func:`penalty_rule`'s default upper bound."""

RULE_MARGIN = 1.0
"""Added to :func:`penalty_rule`'s ``P`` so that infeasible degree patterns are strictly worse (by at least this)."""

_LABEL = re.compile(r"^x(\d+):(\d+),(\d+)-(\d+),(\d+)$")
_VISIT = re.compile(r"^y(\d+):(\d+),(\d+)$")


def edge_label(robot: int, u: Node, v: Node) -> str:
    """The label of robot ``robot``'s edge ``u``-``v`` (smaller node first, whatever the argument order).

    Example:
        >>> edge_label(1, (2, 3), (1, 3))
        'x1:1,3-2,3'
    """
    a, b = (u, v) if u <= v else (v, u)
    return f"x{robot}:{a[0]},{a[1]}-{b[0]},{b[1]}"


def visit_label(robot: int, node: Node) -> str:
    """The label of the auxiliary bit "robot ``robot`` visits ``node``".

    Example:
        >>> visit_label(0, (2, 1))
        'y0:2,1'
    """
    return f"y{robot}:{node[0]},{node[1]}"


def parse_label(label: str) -> tuple[str, int, tuple[Node, ...]]:
    """Split a label into its kind (``x`` or ``y``), robot and node(s).

    Raises:
        ValueError: if ``label`` is neither an edge nor a visit label.

    Example:
        >>> parse_label("x0:1,2-1,3")
        ('x', 0, ((1, 2), (1, 3)))
    """
    if m := _LABEL.match(label):
        r, a, b, c, d = map(int, m.groups())
        return "x", r, ((a, b), (c, d))
    if m := _VISIT.match(label):
        r, a, b = map(int, m.groups())
        return "y", r, ((a, b),)
    raise ValueError(f"not a qcpp BQM label: {label!r}")


@dataclass(frozen=True, eq=False)
class Bqm:
    """A binary quadratic model over 0/1 variables, as plain data.

    ``E(b) = offset + sum_i linear[i] b_i + sum_k quad_val[k] b[quad_i[k]] b[quad_j[k]]`` (``quad_i < quad_j``,
    each pair once).

    Attributes:
        labels: Variable labels (module docstring); the first :attr:`num_edge_variables` are the edge variables
            in qcpp's variable order.
        linear: ``(n,)`` linear coefficients.
        quad_i: Row indices of the quadratic terms.
        quad_j: Column indices (``quad_i < quad_j``).
        quad_val: Their coefficients.
        offset: Constant energy.
        form: ``paper`` or ``per-robot``.
        penalty: The degree-penalty weight ``P`` (``None`` for ``paper``).
        num_edge_variables: Number of edge variables (``scenario.num_variables``).
    """

    labels: tuple[str, ...]
    linear: np.ndarray
    quad_i: np.ndarray
    quad_j: np.ndarray
    quad_val: np.ndarray
    offset: float
    form: Form
    penalty: float | None
    num_edge_variables: int

    @property
    def num_variables(self) -> int:
        return len(self.labels)

    @property
    def num_interactions(self) -> int:
        return len(self.quad_val)

    def energy(self, bits: np.ndarray) -> np.ndarray | float:
        """Energy of one ``(n,)`` or many ``(N, n)`` 0/1 rows."""
        b = np.asarray(bits, dtype=float)
        single = b.ndim == 1
        b = np.atleast_2d(b)
        val = self.offset + b @ self.linear + (b[:, self.quad_i] * b[:, self.quad_j]) @ self.quad_val
        return float(val[0]) if single else val

    def linear_terms(self) -> dict[str, float]:
        """``label -> coefficient`` of every variable (zeros included, so every variable is listed)."""
        return {lab: float(c) for lab, c in zip(self.labels, self.linear.tolist(), strict=True)}

    def quadratic_terms(self) -> list[tuple[str, str, float]]:
        """``(label_i, label_j, coefficient)`` of every interaction (``i < j`` in variable order)."""
        lab = self.labels
        return [
            (lab[i], lab[j], float(v))
            for i, j, v in zip(self.quad_i.tolist(), self.quad_j.tolist(), self.quad_val.tolist(), strict=True)
        ]

    def to_ising(self) -> tuple[dict[str, float], dict[tuple[str, str], float], float]:
        """``(h, J, offset)`` of the same energies in qcpp's spins ``x = (1 - Z)/2`` (:func:`to_ising`)."""
        return to_ising(self)

    def to_dimod(self) -> Any:
        """The model as a ``dimod.BinaryQuadraticModel`` (:func:`to_dimod`; needs dimod)."""
        return to_dimod(self)


def _edge_labels(s: Scenario) -> list[str]:
    g = s.grid
    return [edge_label(r, *g.edges[e]) for r in range(s.num_robots) for e in s.variable_edges]


def _from_terms(
    labels: list[str],
    linear: np.ndarray,
    quad: dict[tuple[int, int], float],
    offset: float,
    form: Form,
    penalty: float | None,
    num_edge: int,
) -> Bqm:
    keys = sorted(k for k, v in quad.items() if v != 0.0)
    qi = np.array([k[0] for k in keys], dtype=np.int64)
    qj = np.array([k[1] for k in keys], dtype=np.int64)
    qv = np.array([quad[k] for k in keys], dtype=float)
    return Bqm(tuple(labels), linear, qi, qj, qv, float(offset), form, penalty, num_edge)


def _paper_terms(s: Scenario) -> tuple[np.ndarray, dict[tuple[int, int], float], float]:
    q = quadratic_cost(s)
    ii, jj = np.nonzero(q.quad)
    quad = {(int(i), int(j)): float(q.quad[i, j]) for i, j in zip(ii.tolist(), jj.tolist(), strict=True)}
    return q.linear.astype(float).copy(), quad, float(q.const)


def paper_bqm(scenario: Scenario) -> Bqm:
    """The ``paper`` form: exactly :func:`qcpp.problem.cost.quadratic_cost` on the edge variables.

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> paper_bqm(default_scenario(3, 3, 2)).num_variables
        24
    """
    linear, quad, offset = _paper_terms(scenario)
    return _from_terms(_edge_labels(scenario), linear, quad, offset, "paper", None, scenario.num_variables)


def _robot_node_edges(s: Scenario) -> list[list[tuple[Node, list[int], bool]]]:
    """Per robot: ``(node, variable indices of its edges at the node, node is one of the robot's ends)``."""
    g = s.grid
    pos = {e: k for k, e in enumerate(s.variable_edges)}
    v = s.edges_per_robot
    out = []
    for r, rb in enumerate(s.robots):
        rows = []
        for node in g.nodes:
            ks = [pos[e] for e in g.incident_edges[g.node_index(node)] if e in pos]
            if ks:
                rows.append((node, [r * v + k for k in ks], node in (rb.start, rb.goal)))
        out.append(rows)
    return out


def per_robot_bqm(scenario: Scenario, penalty: float | None = None) -> Bqm:
    """The ``per-robot`` form: the cost plus per-robot degree penalties with visit bits (module docstring).

    Args:
        penalty: The weight ``P`` (``None``: :func:`penalty_rule`'s).

    Returns:
        The model; its labels are the edge variables, then one visit bit per robot and non-end node that has
        an edge variable.

    Raises:
        ValueError: if ``penalty`` is not a positive finite number (or the rule does not apply, see
            :func:`penalty_rule`).
    """
    if penalty is None:
        penalty = penalty_rule(scenario).penalty
    if not (isinstance(penalty, (int, float)) and math.isfinite(penalty) and penalty > 0):
        raise ValueError(f"the degree penalty must be a positive finite number, got {penalty!r}")
    p = float(penalty)
    linear, quad, offset = _paper_terms(scenario)
    labels = _edge_labels(scenario)
    lin = list(linear)

    def add_quad(i: int, j: int, c: float) -> None:
        key = (i, j) if i < j else (j, i)
        quad[key] = quad.get(key, 0.0) + c

    for r, rows in enumerate(_robot_node_edges(scenario)):
        for node, ks, is_end in rows:
            # (S - c)^2 = S + 2 sum_{a<b} x_a x_b - 2 c S + c^2 with S = sum x (x^2 = x)
            for a_i, a in enumerate(ks):
                for b in ks[a_i + 1 :]:
                    add_quad(a, b, 2 * p)
            if is_end:
                for a in ks:
                    lin[a] += p - 2 * p
                offset += p
            else:
                y = len(lin)
                labels.append(visit_label(r, node))
                lin.append(4 * p)  # (2y)^2 = 4y
                for a in ks:
                    lin[a] += p
                    add_quad(a, y, -4 * p)
    return _from_terms(labels, np.array(lin), quad, offset, "per-robot", p, scenario.num_variables)


def bqm_for(scenario: Scenario, form: str = "per-robot", penalty: float | None = None) -> Bqm:
    """The model of ``form`` (``per-robot`` or ``paper``); ``penalty`` applies to ``per-robot`` only.

    Raises:
        ValueError: on an unknown form, or a penalty given with ``paper``.
    """
    if form == "paper":
        if penalty is not None:
            raise ValueError("a degree penalty applies to the per-robot form only")
        return paper_bqm(scenario)
    if form == "per-robot":
        return per_robot_bqm(scenario, penalty)
    raise ValueError(f"unknown BQM form {form!r} (expected one of {', '.join(FORMS)})")


def best_auxiliaries(model: Bqm, edge_bits: np.ndarray) -> np.ndarray:
    """Complete edge bits with the visit bits that minimise the energy (``y_rv = 1`` iff ``S_rv >= 2``).

    Each visit bit appears only in its own penalty ``P (S - 2y)^2``, which is smallest at ``y = 1`` for
    ``S >= 2`` and ``y = 0`` for ``S <= 1`` (a tie at ``S = 1``).

    Args:
        model: A model from :func:`bqm_for`.
        edge_bits: ``(num_edge_variables,)`` or ``(N, num_edge_variables)`` 0/1 edge bits.

    Returns:
        The full bit rows (``(n,)`` or ``(N, n)``, uint8).
    """
    x = np.asarray(edge_bits, dtype=np.uint8)
    single = x.ndim == 1
    x = np.atleast_2d(x)
    n_e = model.num_edge_variables
    aux = model.labels[n_e:]
    if not aux:
        return x[0] if single else x
    # the visit bit's coupling partners are exactly its robot's edges at the node
    out = np.zeros((len(x), model.num_variables), dtype=np.uint8)
    out[:, :n_e] = x
    deg = np.zeros((len(x), len(aux)), dtype=np.int64)
    for i, j in zip(model.quad_i.tolist(), model.quad_j.tolist(), strict=True):
        if j >= n_e > i:
            deg[:, j - n_e] += x[:, i]
    out[:, n_e:] = deg >= 2
    return out[0] if single else out


def decode_edges(scenario: Scenario, model: Bqm, bits: np.ndarray) -> tuple[int, ...]:
    """One grid-edge mask per robot from a sample's bits (auxiliary bits ignored).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> from qcpp.problem.paths import assignment_from_bits, initial_path
        >>> s = default_scenario(2, 3, 1)
        >>> m = per_robot_bqm(s, penalty=1.0)
        >>> bits = best_auxiliaries(m, [1, 0, 1, 0, 0, 0, 1])
        >>> decode_edges(s, m, bits) == (0b1000101,)
        True
    """
    return assignment_from_bits(scenario, np.asarray(bits)[: model.num_edge_variables])


@dataclass(frozen=True)
class PenaltyRule:
    """The degree-penalty weight of :func:`penalty_rule` and the numbers it is made of.

    Attributes:
        penalty: ``P = upper_bound - lower_bound + local_gain + RULE_MARGIN``.
        upper_bound: ``UB``, the cost of a feasible assignment (so ``UB >= optimum``).
        lower_bound: ``LB``, a lower bound of every assignment's energy counting zero-penalty nodes only.
        local_gain: ``G``, the most one node's share of the energy can drop by breaking its degree rule.
    """

    penalty: float
    upper_bound: float
    lower_bound: float
    local_gain: float


def _subset_minima(half_weights: Sequence[float]) -> list[float]:
    """``m[k]`` = the smallest sum of ``k`` of the values (``k = 0 .. len``)."""
    srt = sorted(half_weights)
    return [float(sum(srt[:k])) for k in range(len(srt) + 1)]


def _node_minima(s: Scenario) -> list[tuple[float, float]]:
    """Per node with edge variables: (min share over valid local configurations, min share over invalid ones).

    A node's share of the cost is ``alpha0 * sum_{r, e at v} w_e x_re / 2 + alpha2 (D_v - t_v)^2``. A robot's
    local configuration is its degree ``k`` at the node (``k`` edges cheapest first gives the minimum); valid:
    ``k = 1`` at its own ends, ``k`` in ``{0, 2}`` elsewhere.
    """
    g = s.grid
    a0, _, a2 = s.objective.alpha
    t = s.degree_targets
    pos = set(s.variable_edges)
    out = []
    for idx, node in enumerate(g.nodes):
        es = [e for e in g.incident_edges[idx] if e in pos]
        if not es:
            continue
        m = _subset_minima([a0 * float(s.edge_weights[e]) / 2 for e in es])
        # dp[(D, any_invalid)] = min c1 share over the robots so far
        dp: dict[tuple[int, bool], float] = {(0, False): 0.0}
        for rb in s.robots:
            valid = {1} if node in (rb.start, rb.goal) else {0, 2}
            nxt: dict[tuple[int, bool], float] = {}
            for (d, bad), val in dp.items():
                for k in range(len(es) + 1):
                    key = (d + k, bad or k not in valid)
                    cand = val + m[k]
                    if cand < nxt.get(key, math.inf):
                        nxt[key] = cand
            dp = nxt
        c3 = (lambda d: 0.0) if math.isnan(t[idx]) else (lambda d, tt=float(t[idx]): a2 * (d - tt) ** 2)
        good = min((v + c3(d) for (d, bad), v in dp.items() if not bad), default=math.inf)
        worst = min((v + c3(d) for (d, bad), v in dp.items() if bad), default=math.inf)
        out.append((good, worst))
    return out


def penalty_rule(scenario: Scenario, upper_bound: float | None = None) -> PenaltyRule:
    """The degree penalty ``P = UB - LB + G + 1`` under which no infeasible degree pattern beats the optimum.

    Proof. Split the energy of any assignment as ``alpha1 c2 + sum_v (phi_v + P pen_v)``: ``phi_v`` is node
    ``v``'s share of the cost (half of each incident edge's ``alpha0 w_e`` per robot plus its degree term
    ``alpha2 (D_v - t_v)^2``), ``pen_v = sum_r`` of the robots' degree penalties at ``v``, an integer, at least
    1 exactly when some robot's degree at ``v`` is invalid (with the best visit bits). ``alpha1 c2 >= 0``. At a
    node whose degrees are all valid, ``phi_v >= good_v``; at any other, ``phi_v + P pen_v >= bad_v + P``, where
    ``good_v`` / ``bad_v`` are the smallest shares over valid / invalid local configurations (each robot's
    degree at ``v``, cheapest edges first: :func:`_node_minima`). With ``LB = sum_v good_v`` and
    ``G = max(0, max_v (good_v - bad_v))``, an assignment with ``m >= 1`` invalid nodes has energy at least
    ``LB + m (P - G) >= LB + P - G = UB + 1 > optimum`` (as ``P >= G``). Valid degrees with a wrong visit bit
    only add penalty. So every assignment with a non-zero penalty has energy ``>= UB + 1`` (:data:`RULE_MARGIN`),
    while every feasible one has energy equal to its cost. ``tests/problem/qubo_test.py`` checks this
    exhaustively on small grids.

    Args:
        upper_bound: The cost of any feasible assignment (smaller gives a smaller ``P``); ``None``: the best
            of the initial paths and a short SBF annealing run (:data:`RULE_ANNEAL_ITERATIONS` iterations, seed 0,
            deterministic).

    Returns:
        The rule's numbers.

    Raises:
        ValueError: if ``alpha1`` or ``alpha2`` is negative (the balance and degree terms could then be
            unbounded below; give the penalty explicitly).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> r = penalty_rule(default_scenario(3, 3, 2))
        >>> r.penalty == r.upper_bound - r.lower_bound + r.local_gain + RULE_MARGIN, r.upper_bound, r.lower_bound
        (True, -4.0, -7.0)
    """
    _, a1, a2 = scenario.objective.alpha
    if a1 < 0 or a2 < 0:
        raise ValueError("the penalty rule needs alpha1, alpha2 >= 0; give the degree penalty explicitly")
    if upper_bound is None:
        from qcpp.problem.solvers.annealing import anneal

        start = cost(scenario, [initial_path(scenario, r) for r in range(scenario.num_robots)])
        found = anneal(scenario, seed=0, iterations=RULE_ANNEAL_ITERATIONS, components="initial").cost.total
        upper_bound = min(start, found)
    minima = _node_minima(scenario)
    lb = float(sum(good for good, _ in minima))
    gain = max([0.0, *(good - bad for good, bad in minima if math.isfinite(bad))])
    p = float(upper_bound) - lb + gain + RULE_MARGIN
    return PenaltyRule(penalty=p, upper_bound=float(upper_bound), lower_bound=lb, local_gain=gain)


def to_ising(model: Bqm) -> tuple[dict[str, float], dict[tuple[str, str], float], float]:
    """``(h, J, offset)`` with ``E = offset + sum h_i Z_i + sum J_ij Z_i Z_j`` under qcpp's ``x = (1 - Z)/2``.

    ``Z = +1`` is bit 0 and ``Z = -1`` bit 1 (as in :mod:`qcpp.problem.hamiltonian`). dimod's spin ``s = 2x - 1``
    is ``-Z``: for ``dimod.from_ising`` negate ``h`` (``J`` and the offset stay).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> from qcpp.problem.hamiltonian import ising_hamiltonian
        >>> s = default_scenario(2, 2, 1)
        >>> h, J, c0 = to_ising(paper_bqm(s))
        >>> abs(c0 - ising_hamiltonian(s).c0) < 1e-12
        True
    """
    h = {lab: -float(c) / 2 for lab, c in zip(model.labels, model.linear.tolist(), strict=True)}
    offset = model.offset + float(model.linear.sum()) / 2 + float(model.quad_val.sum()) / 4
    J: dict[tuple[str, str], float] = {}
    for a, b, q in model.quadratic_terms():
        h[a] -= q / 4
        h[b] -= q / 4
        J[(a, b)] = q / 4
    return h, J, offset


def to_dimod(model: Bqm) -> Any:
    """The model as a ``dimod.BinaryQuadraticModel`` (``BINARY`` vartype, same labels and energies).

    Raises:
        ModuleNotFoundError: without dimod (``pip install 'qcpp[annealing]'``).
    """
    import dimod

    return dimod.BinaryQuadraticModel(
        model.linear_terms(), {(a, b): q for a, b, q in model.quadratic_terms()}, model.offset, dimod.BINARY
    )
