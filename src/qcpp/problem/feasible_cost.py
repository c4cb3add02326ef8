"""The cost as a cheap representation that is exact on every feasible assignment (not on the whole space).

The constrained mixer only ever holds feasible states (every robot on a simple start-goal path), on which many
terms of the cost are constant, linear or products of few things. Facts used (``r`` a robot, ``v`` a node,
``S_rv`` the number of robot ``r``'s edges at ``v``):

* **Dead edges.** A non-endpoint node has ``S_rv`` 0 or 2, so an edge whose other end is a non-endpoint node
  with no other usable edge is never used; pruning such leaves repeatedly gives :attr:`FeasibleCost.dead`.
* **Endpoints.** ``S_rv = 1`` at the robot's start and goal: ``sum_{e at v} x_e = 1``. In a linear form, the
  edges at an endpoint with equal coefficient ``p`` collapse to the constant ``p`` (unequal ones keep
  ``a_e - p``).
* **Corridors.** A non-endpoint node with exactly two usable edges has ``x_a = x_b``: their coefficients merge.
* **Degree terms.** With ``E_v`` robots ending at ``v``, ``R_v`` the others that can pass ``v`` and
  ``y_rv = S_rv / 2`` in {0, 1} (``r`` visits ``v``), ``D_v = E_v + 2 sum_{r in R_v} y_rv`` and, with
  ``c = E_v - t_v``, ``(D_v - t_v)^2 = c^2 + (2c + 2) sum_{r in R_v} S_rv + 8 sum_{r<s in R_v} y_rv y_sv``: a
  linear part plus one :class:`VisitGroup` per node that two or more robots can pass (nothing quadratic at all
  for one robot).
* **Balance.** ``(L_r - L_s)^2`` with the lengths reduced as above; when every edge length is an integer
  multiple of one unit ``u`` the reduced forms are integer (``L_r = u (c_r + G_r)``) and the whole balance term
  is one :class:`SumsGroup` ``sum_ab M_ab G_a G_b`` (its linear and constant parts are folded into
  :attr:`FeasibleCost.linear` and :attr:`FeasibleCost.constant`). Otherwise the group keeps real weights.

Nothing here builds the ``O((re)^2)`` whole-space Hamiltonian: building this representation is linear in the
number of variables.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> import numpy as np
    >>> from qcpp.problem.paths import enumerate_paths, path_bits
    >>> from qcpp.problem.cost import cost
    >>> s = default_scenario(3, 3, 2)
    >>> f = feasible_cost(s)
    >>> [len(g.forms) for g in f.sums], f.sums[0].integral
    ([2], True)
    >>> p0, p1 = enumerate_paths(s, 0)[3], enumerate_paths(s, 1)[5]
    >>> bits = np.concatenate([path_bits(s, p0), path_bits(s, p1)])
    >>> abs(f.evaluate(bits) - cost(s, [p0, p1])) < 1e-9
    True
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from qcpp.problem.cost import balanced_pairs
from qcpp.problem.scenario import Scenario

__all__ = [
    "FeasibleCost",
    "SumsGroup",
    "VisitGroup",
    "balance_matrix",
    "difference_pairs",
    "feasible_cost",
    "length_unit",
    "live_edges",
    "reduce_on_paths",
]

#: Largest total integer weight of one form for which a balance group is called integral.
MAX_INTEGER_TOTAL = 1 << 20
_TOL = 1e-12


@dataclass(frozen=True)
class VisitGroup:
    """``coefficient * sum_{a<b} y_a y_b`` at one node, ``y_a = (sum of visitor a's edge bits) / 2``.

    On feasible assignments each visitor's edges at the node hold 0 or 2 set bits, so ``y_a`` is 0 or 1 and
    equals the OR of all but one of its edges.

    Attributes:
        node: Grid node index.
        coefficient: The factor (``8 * alpha2`` for a degree term).
        visitors: Per visiting robot, the variable indices of its usable edges at the node (2 to 4 of them).
        colour: The node's colour on the grid's checkerboard, ``(row + col) % 2``: two nodes of one colour are
            never neighbours, so their groups share no variable.
    """

    node: int
    coefficient: float
    visitors: tuple[tuple[int, ...], ...]
    colour: int = 0

    def evaluate(self, x: np.ndarray) -> np.ndarray:
        """Value on ``(N, n)`` 0/1 rows."""
        ys = [x[:, list(v)].sum(axis=1) / 2 for v in self.visitors]
        out = np.zeros(len(x))
        for a in range(len(ys)):
            for b in range(a + 1, len(ys)):
                out += ys[a] * ys[b]
        return self.coefficient * out


@dataclass(frozen=True)
class SumsGroup:
    """``sum_{a,b} M_ab G_a G_b`` over linear forms ``G_a = sum_j w_aj x_j``.

    Attributes:
        name: What the group is (``balance``).
        forms: Per form, ``(variable, weight)`` pairs (weights nonzero; integers when :attr:`integral`).
        matrix: The symmetric matrix ``M`` (rows of floats).
        integral: Every weight is an integer (arithmetic on a register is exact).
        unit: The length unit the integer weights count (1 when not integral).
    """

    name: str
    forms: tuple[tuple[tuple[int, float], ...], ...]
    matrix: tuple[tuple[float, ...], ...]
    integral: bool
    unit: float = 1.0

    def evaluate(self, x: np.ndarray) -> np.ndarray:
        """Value on ``(N, n)`` 0/1 rows."""
        g = np.stack([_form_value(f, x) for f in self.forms], axis=1) if self.forms else np.zeros((len(x), 0))
        m = np.array(self.matrix, dtype=float).reshape(len(self.forms), len(self.forms))
        return np.einsum("na,ab,nb->n", g, m, g)

    def expanded(self) -> tuple[dict[int, float], dict[tuple[int, int], float]]:
        """The group as ``linear . x + sum_{i<j} quad_ij x_i x_j`` (``x_i^2 = x_i``): the coupling fallback.

        Returns:
            ``(linear, quad)`` dicts.
        """
        lin: dict[int, float] = {}
        quad: dict[tuple[int, int], float] = {}
        n = len(self.forms)
        for a in range(n):
            for b in range(n):
                mab = self.matrix[a][b]
                if abs(mab) <= _TOL:
                    continue
                for i, wi in self.forms[a]:
                    for j, wj in self.forms[b]:
                        c = mab * wi * wj
                        if i == j:
                            lin[i] = lin.get(i, 0.0) + c
                        else:
                            key = (i, j) if i < j else (j, i)
                            quad[key] = quad.get(key, 0.0) + c
        return lin, quad

    def folded(self) -> tuple[SumsGroup, ...] | None:
        """The same function as a sum of one-form groups, ``sum_(a<b) w_ab (G_a - G_b)^2`` with ``w_ab = -M_ab``,
        when ``M`` is symmetric and every row sums to zero (a balance matrix, :func:`balance_matrix`); else ``None``.

        One register of a difference ``G_a - G_b`` has far fewer bit pairs to phase than two registers coupled bit
        by bit, and the gadgets of different pairs run one after the other, so they need only one pair's ancillas
        at a time; a robot in several pairs has its sum computed once per pair. Only integral groups fold (the
        fold serves the arithmetic constructions), and only while each difference's total weight stays at most
        :data:`MAX_INTEGER_TOTAL`.

        Returns:
            Per pair ``(a, b)`` with ``M_ab != 0``, in order, the group ``w_ab D^2`` over the one form ``D = G_a -
            G_b`` (``G_b``'s weights negated; same name, unit and integrality), or ``None``.

        Example:
            >>> g = SumsGroup("balance", (((0, 1.0), (1, 1.0)), ((2, 1.0),)), ((2.0, -2.0), (-2.0, 2.0)), True)
            >>> [(f.forms, f.matrix) for f in g.folded()]
            [((((0, 1.0), (1, 1.0), (2, -1.0)),), ((2.0,),))]
            >>> x = np.array([[1, 0, 1], [1, 1, 0], [0, 0, 1]])
            >>> bool(np.allclose(g.evaluate(x), sum(f.evaluate(x) for f in g.folded())))
            True
        """
        pairs = difference_pairs(self.matrix) if self.integral else None
        if pairs is None:
            return None
        out = []
        for a, b, w in pairs:
            form = self.forms[a] + tuple((q, -x) for q, x in self.forms[b])
            if sum(abs(x) for _, x in form) > MAX_INTEGER_TOTAL:
                return None
            out.append(SumsGroup(self.name, (form,), ((w,),), True, self.unit))
        return tuple(out)


def difference_pairs(matrix: Sequence[Sequence[float]]) -> tuple[tuple[int, int, float], ...] | None:
    """``(a, b, w_ab)`` for ``a < b`` with ``M_ab != 0`` and ``w_ab = -M_ab``, when ``M`` is symmetric and every
    row sums to zero, so that ``sum_ab M_ab G_a G_b = sum_(a<b) w_ab (G_a - G_b)^2``; else ``None`` (also when no
    pair is coupled): when a balance matrix folds into difference forms (:meth:`SumsGroup.folded`).

    >>> difference_pairs(balance_matrix(3, [(0, 1), (1, 2)], 2.0))
    ((0, 1, 2.0), (1, 2, 2.0))
    >>> difference_pairs(((1.0, 0.0), (0.0, 1.0))) is None
    True
    """
    n = len(matrix)
    tol = _TOL * max([1.0, *(abs(float(x)) for row in matrix for x in row)])
    if any(abs(matrix[a][b] - matrix[b][a]) > tol for a in range(n) for b in range(a)):
        return None
    if any(abs(sum(float(x) for x in row)) > tol * n for row in matrix):
        return None
    pairs = tuple((a, b, -float(matrix[a][b])) for a in range(n) for b in range(a + 1, n) if abs(matrix[a][b]) > tol)
    return pairs or None


def _form_value(form: Sequence[tuple[int, float]], x: np.ndarray) -> np.ndarray:
    if not form:
        return np.zeros(len(x))
    idx = np.array([i for i, _ in form])
    w = np.array([w for _, w in form], dtype=float)
    return x[:, idx] @ w


@dataclass(frozen=True, eq=False)
class FeasibleCost:
    """``constant + linear . x + sum quadratic + sum visits + sum sums``, exact on feasible assignments.

    Attributes:
        num_variables: Number of decision variables.
        constant: Constant part.
        linear: ``(variable, coefficient)`` pairs, ascending variable, nonzero coefficients.
        visits: Node groups (:class:`VisitGroup`).
        sums: Squared-sum groups (:class:`SumsGroup`).
        dead: Variables that are 0 on every feasible assignment (they appear nowhere else).
    """

    num_variables: int
    constant: float
    linear: tuple[tuple[int, float], ...]
    visits: tuple[VisitGroup, ...]
    sums: tuple[SumsGroup, ...]
    dead: frozenset[int]
    _scenario: Scenario | None = None

    def evaluate(self, bits: np.ndarray) -> np.ndarray | float:
        """Value on one ``(n,)`` or many ``(N, n)`` 0/1 rows (meaningful on feasible rows only)."""
        x = np.asarray(bits, dtype=float)
        single = x.ndim == 1
        x = np.atleast_2d(x)
        out = np.full(len(x), self.constant)
        if self.linear:
            out += _form_value(self.linear, x)
        for g in self.visits:
            out += g.evaluate(x)
        for s in self.sums:
            out += s.evaluate(x)
        return float(out[0]) if single else out



def live_edges(scenario: Scenario, robot: int) -> list[list[int]]:
    """Per node, the positions ``k`` (in :attr:`Scenario.variable_edges`) of the edges robot ``robot`` can use.

    An edge is dropped when one of its ends is not the robot's start or goal and has no other usable edge
    (a path through a node uses two of its edges); dropping repeats until nothing changes.
    """
    s, g = scenario, scenario.grid
    rb = s.robots[robot]
    ends = {g.node_index(rb.start), g.node_index(rb.goal)}
    nodes_of = [g.edge_nodes[e] for e in s.variable_edges]
    at: list[set[int]] = [set() for _ in range(g.num_nodes)]
    for k, (a, b) in enumerate(nodes_of):
        at[a].add(k)
        at[b].add(k)
    stack = [v for v in range(g.num_nodes) if v not in ends and len(at[v]) == 1]
    while stack:
        v = stack.pop()
        if v in ends or len(at[v]) != 1:
            continue
        (k,) = at[v]
        for w in nodes_of[k]:
            at[w].discard(k)
            if w not in ends and len(at[w]) == 1:
                stack.append(w)
    return [sorted(a) for a in at]


def reduce_on_paths(
    coeffs: dict[int, float], at: Sequence[Sequence[int]], ends: Sequence[int]
) -> tuple[float, dict[int, float]]:
    """Apply the endpoint and corridor identities to ``sum coeffs[k] x_k`` (``k`` edge positions of one robot).

    Args:
        coeffs: ``k -> coefficient`` (only these edges take part).
        at: Per node (any indexing), the robot's usable edge positions there; only its endpoints and the
            corridor nodes (two usable edges) matter, so a caller may pass just those nodes.
        ends: The robot's start and goal, as indices into ``at``.

    Returns:
        ``(constant, coefficients)`` with the same value on every feasible path of the robot (coefficients
        below ``1e-12`` dropped).
    """
    c = dict(coeffs)
    const = 0.0
    for v in ends:
        edges = at[v]
        if not edges:
            continue
        vals = [c.get(k, 0.0) for k in edges]
        # the most common coefficient (ties: the first) becomes the constant
        p = Counter(round(x, 12) for x in vals).most_common(1)[0][0]
        p = next(x for x in vals if round(x, 12) == p)
        const += p
        for k in edges:
            c[k] = c.get(k, 0.0) - p
    # corridors: a non-endpoint node with two usable edges forces them equal; union-find onto the lower position
    parent: dict[int, int] = {}

    def find(k: int) -> int:
        while parent.get(k, k) != k:
            k = parent[k]
        return k

    endset = set(ends)
    for v, edges in enumerate(at):
        if v in endset or len(edges) != 2:
            continue
        a, b = find(edges[0]), find(edges[1])
        if a != b:
            parent[max(a, b)] = min(a, b)
    out: dict[int, float] = {}
    for k, val in c.items():
        r = find(k)
        out[r] = out.get(r, 0.0) + val
    return const, {k: v for k, v in out.items() if abs(v) > _TOL}


def balance_matrix(robots: int, pairs: Sequence[tuple[int, int]], scale: float) -> np.ndarray:
    """``M`` with ``sum_ab M_ab G_a G_b = scale * sum_{(r, q) in pairs} (G_r - G_q)^2``.

    >>> balance_matrix(3, [(0, 1), (1, 2)], 1.0).tolist()
    [[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]]
    """
    m = np.zeros((robots, robots))
    for r, q in pairs:
        m[r, r] += scale
        m[q, q] += scale
        m[r, q] -= scale
        m[q, r] -= scale
    return m


def length_unit(lengths: Sequence[float]) -> float | None:
    """The largest ``u`` with every length an integer multiple of it (``None`` if there is none worth using)."""
    fr = []
    for d in lengths:
        f = Fraction(d).limit_denominator(10**6)
        if abs(float(f) - d) > 1e-12 * max(1.0, abs(d)) or f <= 0:
            return None
        fr.append(f)
    if not fr:
        return 1.0
    num = 0
    den = 1
    for f in fr:
        den = den * f.denominator // math.gcd(den, f.denominator)
    for f in fr:
        num = math.gcd(num, f.numerator * (den // f.denominator))
    return num / den


def feasible_cost(scenario: Scenario) -> FeasibleCost:
    """Build the feasible-subspace representation of the scenario's cost (see the module docstring).

    Returns:
        A :class:`FeasibleCost` equal to :func:`qcpp.problem.cost.cost` on every feasible assignment.
    """
    s, g = scenario, scenario.grid
    n_r, v_per = s.num_robots, s.edges_per_robot
    a0, a1, a2 = s.objective.alpha
    ve = s.variable_edges
    w = s.edge_weights[list(ve)] if ve else np.zeros(0)
    d = s.edge_lengths[list(ve)] if ve else np.zeros(0)
    lives = [live_edges(s, r) for r in range(n_r)]
    ends = [(g.node_index(rb.start), g.node_index(rb.goal)) for rb in s.robots]
    alive = [sorted({k for a in at for k in a}) for at in lives]
    dead = frozenset(r * v_per + k for r in range(n_r) for k in set(range(v_per)) - set(alive[r]))
    const = 0.0
    lin = [dict.fromkeys(alive[r], 0.0) for r in range(n_r)]
    for r in range(n_r):
        for k in alive[r]:
            lin[r][k] += a0 * float(w[k])
    # degree terms
    visits: list[VisitGroup] = []
    t = s.degree_targets
    if a2 != 0.0:
        for vtx in range(g.num_nodes):
            if np.isnan(t[vtx]):
                continue
            e_v = sum(1 for r in range(n_r) if vtx in ends[r])
            passers = [r for r in range(n_r) if vtx not in ends[r] and len(lives[r][vtx]) >= 2]
            c = e_v - float(t[vtx])
            const += a2 * c * c
            for r in passers:
                for k in lives[r][vtx]:
                    lin[r][k] += a2 * (2 * c + 2)
            if len(passers) >= 2:
                visitors = tuple(tuple(r * v_per + k for k in lives[r][vtx]) for r in passers)
                visits.append(VisitGroup(vtx, 8.0 * a2, visitors, sum(g.nodes[vtx]) % 2))
    # balance
    sums: list[SumsGroup] = []
    pairs = balanced_pairs(s) if a1 != 0.0 else []
    if pairs:
        used = sorted({k for r in range(n_r) for k in alive[r]})
        unit = length_unit([float(d[k]) for k in used])
        forms_c: list[float] = []
        forms: list[dict[int, float]] = []
        for r in range(n_r):
            cst, co = reduce_on_paths({k: float(d[k]) for k in alive[r]}, lives[r], ends[r])
            forms_c.append(cst)
            forms.append(co)
        integral = unit is not None
        if integral:
            assert unit is not None
            scaled = [{k: round(v / unit) for k, v in f.items()} for f in forms]
            too_big = any(sum(abs(x) for x in f.values()) > MAX_INTEGER_TOTAL for f in scaled)
            inexact = any(
                abs(sv * unit - f[k]) > 1e-9 * max(1.0, abs(f[k]))
                for f, sf in zip(forms, scaled)
                for k, sv in sf.items()
            )
            if too_big or inexact:
                integral = False
        if integral:
            assert unit is not None
            forms = [{k: float(v) for k, v in f.items() if v} for f in scaled]
            forms_c = [cst / unit for cst in forms_c]
            scale = a1 * unit * unit
        else:
            unit = 1.0
            scale = a1
        m = balance_matrix(n_r, pairs, scale)
        cvec = np.array(forms_c)
        const += float(cvec @ m @ cvec)
        lin_g = 2 * m @ cvec  # coefficient of G_a in the linear part
        for r in range(n_r):
            for k, wv in forms[r].items():
                lin[r][k] = lin[r].get(k, 0.0) + float(lin_g[r]) * wv
        sums.append(
            SumsGroup(
                "balance",
                tuple(tuple((r * v_per + k, wv) for k, wv in sorted(forms[r].items())) for r in range(n_r)),
                tuple(tuple(float(x) for x in row) for row in m),
                integral,
                float(unit),
            )
        )
    # the linear part, reduced per robot with the same identities
    linear: list[tuple[int, float]] = []
    for r in range(n_r):
        cst, co = reduce_on_paths(lin[r], lives[r], ends[r])
        const += cst
        linear.extend((r * v_per + k, val) for k, val in sorted(co.items()))
    return FeasibleCost(s.num_variables, const, tuple(linear), tuple(visits), tuple(sums), dead, _scenario=s)
