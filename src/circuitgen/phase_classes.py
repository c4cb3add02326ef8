"""The phase separator's cost without planning it term by term: classes of nodes and edges on an open grid.

:func:`circuitgen.phase.phase_plan` builds the feasible cost (:func:`gridcover.feasible_cost.feasible_cost`)
variable by variable and prices every node's visit gadget: 0.1-1 s per scenario at 20x20-40x40, too slow for a
sweep of thousands of scenarios. On a grid without obstacles (and the uniform edge weights and lengths every
such grid has unless a length is overridden) the plan has few distinct parts:

* **node visits**: a node that ``m >= 2`` robots can pass (all robots that do not start or end there) gets a
  visit gadget whose kind depends only on the node's degree ``d`` and ``m``; so the visits cost
  ``sum over (d, m) classes of count x cost``, and a class's construction (visit bits or pairs) is the answer of
  :func:`circuitgen.phase_choice.visit_choice`, the very function the plan asks for each of its nodes;
* **balance**: one arithmetic gadget (:class:`~circuitgen.gadgets.phase_sums.SumsPhase`) over each robot's
  reduced path-length form: weight 1 on every edge, 0 on the edges at its own start and goal (collapsed to a
  constant), corner edges merged in pairs (a corner that is not an endpoint is a corridor);
* **linear**: one rotation per variable whose reduced coefficient is nonzero: ``alpha0 w`` plus the degree terms
  of its two end nodes plus the balance's linear part, reduced at the robot's endpoints and corners like the form
  (on the ``ft`` target, equal coefficients may be merged by Hamming-weight phasing, class by class).

Coefficients are vectors over one robot's edges (numpy), the endpoint and corner identities are applied by the
very function the feasible cost uses (:func:`gridcover.feasible_cost.reduce_on_paths`) on the few edges they
touch. Every construction is decided by :mod:`circuitgen.phase_choice` (the plan's own decisions), and
:func:`phase_layer` answers only where this picture is exact and no choice couples groups (every class picks a
gadget over couplings, and the balance's arithmetic is its first candidate and provably beats its couplings);
elsewhere it returns ``None`` and :meth:`circuitgen.qaoa.QaoaPlan.call_graph`, the one place that
decides, lists the planned gadgets instead. ``tests/circuitgen/phase_classes_test.py`` checks it against
:func:`~circuitgen.phase.phase_plan` (cost, logical cost, ancillas, gadget kinds) on default grids and on random
endpoints.

Example:
    >>> from gridcover.presets import default_scenario
    >>> from circuitgen.phase import phase_plan
    >>> s = default_scenario(12, 11, 3)
    >>> layer = phase_layer(s)
    >>> layer.cost() == phase_plan(s).cost(), layer.num_ancillas == phase_plan(s).num_ancillas
    (True, True)
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, replace
from functools import cached_property, lru_cache
from itertools import repeat

import numpy as np

from circuitgen.call_graph import Deferred, GadgetKind
from circuitgen.cost import Cost
from circuitgen.gadgets import Gadget
from circuitgen.gadgets.phase_ising import COEFFICIENT_TOLERANCE, IsingPhase
from circuitgen.gadgets.phase_sums import SumsPhase, SumsShape
from circuitgen.gadgets.phase_visits import VisitPhase
from circuitgen.phase import coupling_products
from circuitgen.phase_choice import ROTATION_T_COST, hamming_choice, score, sums_constructions, visit_choice
from gridcover.cost import balanced_pairs
from gridcover.feasible_cost import MAX_INTEGER_TOTAL, balance_matrix, length_unit, reduce_on_paths
from gridcover.grid import Grid
from gridcover.scenario import Scenario

__all__ = ["PhaseLayer", "phase_layer"]

_TOL = 1e-12  # gridcover.feasible_cost's zero


@dataclass(frozen=True, eq=False)
class PhaseLayer:
    """One layer's phase separator, as the plan would build it, with its parts counted by class.

    Attributes:
        parts: ``(representative gadget, count)`` per visit class and per Hamming-weight class.
        rotations: Data-qubit rotations (the plan's :class:`~circuitgen.gadgets.phase_ising.IsingPhase`).
        balance: The balance arithmetic, or ``None``.
        num_ancillas: Clean ancillas the largest part needs.
        num_variables: Data qubits.
    """

    parts: tuple[tuple[Gadget, int], ...]
    rotations: int
    balance: _Balance | None
    num_ancillas: int
    num_variables: int

    def cost(self) -> Cost:
        """Lowered cost (the same as :meth:`circuitgen.phase.PhasePlan.cost`)."""
        return self._costs[0]

    def logical_cost(self) -> Cost:
        """Logical cost (ANDs whole)."""
        return self._costs[1]

    @cached_property
    def _costs(self) -> tuple[Cost, Cost]:
        rz = Cost.of(rz=self.rotations)
        lowered = Cost.sum(n * g.cost() for g, n in self.parts) + rz
        logical = Cost.sum(n * g.logical_cost() for g, n in self.parts) + rz
        if self.balance is not None:
            lowered += self.balance.shape.cost()
            logical += self.balance.shape.logical_cost()
        return lowered, logical

    def kinds(self) -> list[tuple[GadgetKind, int]]:
        """``(kind, multiplicity)`` of every part (what :meth:`circuitgen.qaoa.QaoaPlan.call_graph` lists); the
        rotations and the balance as :class:`~circuitgen.call_graph.Deferred` gadgets (built only if emitted)."""
        anc = tuple(range(self.num_variables, self.num_variables + self.num_ancillas))
        out: list[tuple[GadgetKind, int]] = []
        if self.rotations:
            n = self.rotations
            rz = Cost.of(rz=n)

            def rotations() -> Gadget:
                return IsingPhase("gamma", tuple(zip(range(n), repeat(1.0))), ())

            out.append((GadgetKind.of(Deferred(("ising", n, 0), rz, rz, rotations)), 1))
        for g, count in self._placed_parts(anc):
            out.append((GadgetKind.of(g), count))
        if self.balance is not None:
            balance, shape = self.balance, self.balance.shape

            def arithmetic() -> Gadget:
                return replace(balance.gadget(), ancillas=anc)

            deferred = Deferred(
                ("sums", shape), shape.cost(), shape.logical_cost(), arithmetic, shape, shape.num_ancillas
            )
            out.append((GadgetKind.of(deferred), 1))
        return out

    def _placed_parts(self, anc: tuple[int, ...]) -> list[tuple[Gadget, int]]:
        out: list[tuple[Gadget, int]] = []
        for g, count in self.parts:
            if isinstance(g, VisitPhase):
                d = len(g.visitors[0])
                visitors = tuple(tuple(range(i * d, i * d + d)) for i in range(len(g.visitors)))
                out.append((replace(g, visitors=visitors, ancillas=anc), count))
            elif isinstance(g, SumsPhase):
                out.append((replace(g, ancillas=anc), count))
        return out


@dataclass(frozen=True, eq=False)
class _Balance:
    """The balance term's arithmetic: per robot the integer weight of each of its variables (0: not in the form)."""

    weights: tuple[np.ndarray, ...]
    matrix: tuple[tuple[float, ...], ...]

    @cached_property
    def shape(self) -> SumsShape:
        ws, negs = [], []
        for w in self.weights:
            vals, counts = np.unique(np.abs(w[w != 0]), return_counts=True)
            ws.append(tuple(zip(vals.tolist(), counts.tolist())))
            neg = w[w < 0]
            negs.append((len(neg), int(-neg.sum())))
        return SumsShape(tuple(ws), tuple(negs), self.matrix, (0.0,) * len(self.weights))

    def gadget(self) -> SumsPhase:
        forms = []
        for r, w in enumerate(self.weights):
            pos = np.nonzero(w)[0]
            forms.append(tuple(zip((r * len(w) + pos).tolist(), w[pos].tolist())))
        return SumsPhase("gamma", tuple(forms), self.matrix, (0.0,) * len(forms))


@dataclass(frozen=True)
class _Grid:
    """One robot's view of an open grid: per variable position its end nodes; per node its degree."""

    u: np.ndarray
    v: np.ndarray
    degree: np.ndarray
    corners: tuple[int, ...]


@lru_cache(maxsize=8)
def _grid(grid: Grid, edges: tuple[int, ...]) -> _Grid:
    u = np.array([grid.edge_nodes[e][0] for e in edges], dtype=np.int64)
    v = np.array([grid.edge_nodes[e][1] for e in edges], dtype=np.int64)
    degree = np.bincount(u, minlength=grid.num_nodes) + np.bincount(v, minlength=grid.num_nodes)
    return _Grid(u, v, degree, tuple(int(x) for x in np.nonzero(degree == 2)[0]))


def _at(g: _Grid, node: int) -> list[int]:
    """Edge positions at a node, ascending (as :func:`gridcover.feasible_cost.live_edges` lists them)."""
    return np.nonzero((g.u == node) | (g.v == node))[0].tolist()


@dataclass(frozen=True)
class _Local:
    """Where one robot's identities act: the edges at its endpoints (nodes 0 and 1 of ``at``) and at the corners
    that are not its endpoints (corridors), the only edges they touch on an open grid."""

    at: tuple[list[int], ...]
    touched: list[int]

    @classmethod
    def of(cls, g: _Grid, ends: tuple[int, int]) -> _Local:
        nodes = [ends[0], ends[1], *(c for c in g.corners if c not in ends)]
        at = tuple(_at(g, n) for n in nodes)
        return cls(at, sorted({k for edges in at for k in edges}))


def _reduce(values: np.ndarray, local: _Local) -> tuple[float, np.ndarray]:
    """:func:`~gridcover.feasible_cost.reduce_on_paths` of one robot's coefficient vector, applied where its
    identities act (``local``).

    Returns:
        ``(constant, coefficients)``; a zero marks a dropped term.
    """
    const, reduced = reduce_on_paths({k: float(values[k]) for k in local.touched}, local.at, (0, 1))
    out = values.copy()
    out[local.touched] = 0.0
    for k, val in reduced.items():
        out[k] = val
    out[np.abs(out) <= _TOL] = 0.0
    return const, out


@lru_cache(maxsize=64)  # the counts and the depth bound of a scenario both ask
def phase_layer(
    scenario: Scenario,
    target: str = "nisq",
    representation: str = "feasible",
    optimize: str = "cx",
    ancilla_budget: int | None = None,
) -> PhaseLayer | None:
    """The phase separator of one layer by classes (see the module docstring), or ``None`` where only the plan
    knows (obstacles, overridden lengths, the ``whole-space`` representation, or a choice the classes cannot make:
    a node or the balance whose construction is couplings, or the balance's arithmetic out of the budget). Each
    class's construction is the plan's own decision (:mod:`circuitgen.phase_choice`), asked once per class.

    Args:
        scenario: the scenario.
        target, representation, optimize, ancilla_budget: as :func:`circuitgen.phase.phase_plan`.

    Returns:
        The :class:`PhaseLayer`, or ``None``.
    """
    s, grid = scenario, scenario.grid
    ob = s.objective
    if (
        representation != "feasible" or s.obstacles or ob.edge_lengths
    ):  # fmt: skip
        return None
    ends = [(grid.node_index(rb.start), grid.node_index(rb.goal)) for rb in s.robots]
    if any(a == b for a, b in ends):
        return None
    g = _grid(grid, tuple(s.variable_edges))
    local = [_Local.of(g, e) for e in ends]
    n_r, v_per = s.num_robots, s.edges_per_robot
    a0, a1, a2 = ob.alpha
    parts: list[tuple[Gadget, int]] = []
    ancillas = 0
    # degree terms: a linear part per node, a visit class per (degree, passers)
    node_term = np.zeros(grid.num_nodes)
    if a2 != 0.0:
        t = np.asarray(s.degree_targets, dtype=float)
        e_v = np.zeros(grid.num_nodes, dtype=np.int64)
        for a, b in ends:
            e_v[a] += 1
            e_v[b] += 1
        counted = ~np.isnan(t)
        c = e_v - np.where(counted, t, 0.0)
        node_term = np.where(counted, a2 * (2 * c + 2), 0.0)
        passers = n_r - e_v
        classes = Counter(zip(g.degree[counted].tolist(), passers[counted].tolist()))
        for (degree, m), count in sorted(classes.items()):
            if m < 2:
                continue
            # no coupling exists yet when the visits are chosen (the balance is arithmetic, checked below)
            choice = visit_choice((degree,) * m, 8.0 * a2, m * (m - 1) // 2 * degree * degree, target, optimize,
                                  ancilla_budget)  # fmt: skip
            if choice.gadget is None:
                return None  # a coupling would change what the later groups' couplings cost
            parts.append((choice.gadget, count))
            ancillas = max(ancillas, choice.ancillas)
    lin = []
    for a, b in ends:
        own = node_term.copy()
        own[[a, b]] = 0.0
        lin.append(a0 * ob.free_weight + own[g.u] + own[g.v])
    # balance
    pairs = balanced_pairs(s) if a1 != 0.0 else []
    balance: _Balance | None = None
    within: int | None = None  # a lower bound on the couplings alternative's couplings, when it is one
    if pairs:
        unit = length_unit([ob.edge_length])
        if unit is None:
            return None
        ones = np.full(v_per, ob.edge_length)
        weights, consts = [], []
        for r in range(n_r):
            const, form = _reduce(ones, local[r])
            form = form / unit
            if np.any(np.abs(form - np.round(form)) > 1e-9) or np.abs(form).sum() > MAX_INTEGER_TOTAL:
                return None
            weights.append(np.round(form).astype(np.int64))
            consts.append(const / unit)
        scale = a1 * unit * unit
        m = balance_matrix(n_r, pairs, scale)
        sizes = [int(np.count_nonzero(w)) for w in weights]
        balance = _Balance(tuple(weights), tuple(tuple(float(x) for x in row) for row in m))
        shape = balance.shape
        # only the arithmetic is counted by classes: any other first variant is left to the plan
        candidates = sums_constructions(
            True, coupling_products(sizes, m), optimize, ancilla_budget,
            lambda variant: shape.num_ancillas if variant == "arithmetic" else 0,
        )  # fmt: skip
        if candidates[0] != "arithmetic":
            return None
        if "couplings" in candidates:
            # the plan also prices the balance as couplings; they interact with the visits, but the pairs within
            # one form meet no other term, so that plan has at least this many couplings (2 CX, 1 rotation each)
            within = sum(sizes[a] * (sizes[a] - 1) // 2 for a in range(n_r) if abs(m[a][a]) > 0)
        lin_g = 2 * m @ np.array(consts)
        for r, w in enumerate(weights):
            lin[r] = lin[r] + float(lin_g[r]) * w
        ancillas = max(ancillas, shape.num_ancillas)
    values = np.concatenate([_reduce(lin[r], local[r])[1] for r in range(n_r)]) if n_r else np.zeros(0)
    values = values[values != 0.0]
    if target == "ft":
        keep = np.ones(len(values), dtype=bool)
        rounded = np.round(values, 12)
        _, first, counts = np.unique(rounded, return_index=True, return_counts=True)
        for k, n in zip(first.tolist(), counts.tolist()):
            hw = hamming_choice(n, float(values[k]), target, optimize, ancilla_budget)
            if hw is not None:
                parts.append((hw, 1))
                ancillas = max(ancillas, hw.num_ancillas)
                keep &= rounded != rounded[k]
        values = values[keep]
    rotations = int(np.count_nonzero(np.abs(values / 2) > COEFFICIENT_TOLERANCE))
    layer = PhaseLayer(tuple(parts), rotations, balance, ancillas, s.num_variables)
    if within is not None:
        first = score(layer.cost(), layer.logical_cost(), target)[0]  # type: ignore[arg-type]
        if (ROTATION_T_COST if target == "ft" else 2) * within <= first:
            return None  # the couplings might win: only the plan knows
    return layer

