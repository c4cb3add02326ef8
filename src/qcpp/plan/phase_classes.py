"""The phase separator's call graph without planning it term by term: classes of nodes and edges on an open grid.

:func:`qcpp.plan.phase.phase_plan` prices every term group variable by variable (too slow for a sweep over
large grids). On a grid without obstacles and with uniform edge lengths the plan has few
distinct parts:

* **node visits**: a node that ``m >= 2`` robots can pass (all robots that do not start or end there) gets a
  visit gadget whose kind depends only on the node's degree ``d`` and ``m``; so the visits cost
  ``sum over (d, m) classes of count x cost``, and a class's construction (visit bits or pairs) is the answer of
  :func:`qcpp.plan.phase_choice.visit_choice`, the very function the plan asks for each of its nodes; on the
  ``ft`` target a class's visit pairs go in Hamming-weight batches
  (:func:`~qcpp.plan.phase_choice.visit_batches`, as the plan batches nodes of one kind);
* **balance**: one arithmetic gadget (:class:`~qcpp.gadgets.phase_sums.SumsPhase`) over each robot's
  reduced path-length form: weight 1 on every edge, 0 on the edges at its own start and goal (collapsed to a
  constant), corner edges merged in pairs (a corner that is not an endpoint is a corridor); or, where the plan
  folds it (:func:`qcpp.plan.phase_choice.prefer_folded`), one gadget per balanced pair over the difference of
  the two robots' forms;
* **linear**: one rotation per variable whose reduced coefficient is nonzero: ``alpha0 w`` plus the degree terms
  of its two end nodes plus the balance's linear part, reduced at the robot's endpoints and corners like the form
  (on the ``ft`` target, equal coefficients may be merged by Hamming-weight phasing, class by class).

The endpoint and corner identities are applied by the feasible cost's own function
(:func:`qcpp.problem.feasible_cost.reduce_on_paths`), every construction is the plan's own decision
(:mod:`qcpp.plan.phase_choice`), and :func:`phase_layer` answers only where no choice couples groups; elsewhere
it returns ``None`` and :meth:`qcpp.plan.qaoa.QaoaPlan.call_graph` lists the planned gadgets instead.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from collections import Counter
    >>> from qcpp.plan.phase import phase_plan
    >>> s = default_scenario(12, 11, 3)
    >>> layer, plan = phase_layer(s), phase_plan(s)
    >>> Counter({k.key: n for k, n in layer.kinds()}) == Counter(g.kind for g in plan.gadgets("gamma"))
    True
    >>> layer.num_ancillas == plan.num_ancillas
    True
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, replace
from functools import cached_property, lru_cache, partial
from itertools import repeat

import numpy as np

from qcpp.gadgets import Gadget
from qcpp.gadgets.phase_ising import COEFFICIENT_TOLERANCE, IsingKind, IsingPhase, ising_cost
from qcpp.gadgets.phase_sums import SumsKind, SumsPhase, SumsShape
from qcpp.gadgets.phase_visits import VisitPhase
from qcpp.gadgets.visit_batch import VisitBatch, visit_batch_ancillas
from qcpp.ir.cost import Cost
from qcpp.plan.call_graph import SCENARIOS_KEPT, Deferred, GadgetKind
from qcpp.plan.mixer_classes import Count, boundary, class_counts
from qcpp.plan.options import Optimize
from qcpp.plan.phase import coupling_products, phase_plan
from qcpp.plan.phase_choice import (
    couplings_floor,
    hamming_groups,
    plan_score,
    prefer_folded,
    sums_constructions,
    visit_batches,
    visit_choice,
)
from qcpp.problem.cost import balanced_pairs
from qcpp.problem.feasible_cost import (
    MAX_INTEGER_TOTAL,
    balance_matrix,
    difference_pairs,
    length_unit,
    reduce_on_paths,
)
from qcpp.problem.grid import Grid
from qcpp.problem.scenario import Scenario

__all__ = ["IsingCount", "PhaseLayer", "ising_count", "phase_layer"]

_TOL = 1e-12  # qcpp.problem.feasible_cost's zero

@dataclass(frozen=True, eq=False)
class PhaseLayer:
    """One layer's phase separator, as the plan would build it, counted by classes.

    Attributes:
        parts: ``(kind, multiplicity)``: the data-qubit rotations (and couplings) and the balance arithmetic as
            :class:`~qcpp.plan.call_graph.Deferred` gadgets (built only if emitted), a placed representative per
            visit class and per Hamming-weight class.
        num_ancillas: clean ancillas the largest part needs.
    """

    parts: tuple[tuple[GadgetKind, int], ...]
    num_ancillas: int

    def kinds(self) -> list[tuple[GadgetKind, int]]:
        """``(kind, multiplicity)`` of every part (what :meth:`qcpp.plan.qaoa.QaoaPlan.call_graph` lists)."""
        return list(self.parts)


def _layer(
    s: Scenario, rotations: int, couplings: int, parts: list[tuple[Gadget, int, int]],
    balance: tuple[_Balance, ...] = (), whole_space: bool = False,
) -> PhaseLayer:
    """The :class:`PhaseLayer` of ``rotations`` data-qubit rotations and ``couplings`` (``whole_space``: those of
    ``s``'s Ising Hamiltonian), ``(gadget on abstract qubits, count, ancillas)`` per class, and the balance's
    arithmetic gadgets (one, or one per balanced pair when folded), in order."""
    # the ancillas as a range: each part gets a tuple of only what it uses (tuples of thousands of ints made
    # per scenario fragment the allocator's arenas and inflate a long sweep's peak memory)
    num_ancillas = max([0, *(need for _, _, need in parts), *(b.shape.num_ancillas for b in balance)])
    pool = range(s.num_variables, s.num_variables + num_ancillas)
    out = [(GadgetKind.of(replace(g, ancillas=tuple(pool[:need]))), count) for g, count, need in parts]  # type: ignore[type-var]
    if rotations or couplings:
        rz = ising_cost(rotations, couplings)

        def ising() -> Gadget:
            if whole_space:  # the couplings' placement is the Hamiltonian's: the plan builds it
                return phase_plan(s, representation="whole-space").gadgets("gamma")[0]
            return IsingPhase("gamma", tuple(zip(range(rotations), repeat(1.0))), ())

        out.insert(0, (GadgetKind.of(Deferred(IsingKind("ising", rotations, couplings), rz, rz, ising)), 1))
    for part in balance:
        shape = part.shape
        arithmetic = partial(_arithmetic, part, pool)  # the pool's tuple only if emitted
        kind = SumsKind("sums", shape)
        deferred = Deferred(kind, shape.cost(), shape.logical_cost(), arithmetic, shape, shape.num_ancillas)
        out.append((GadgetKind.of(deferred), 1))
    return PhaseLayer(tuple(out), num_ancillas)


def _batched(
    parts: list[tuple[Gadget, int, int]], pool: int, n: int, optimize: Optimize, budget: int | None
) -> list[tuple[Gadget, int, int]]:
    """The ``ft`` layer's visit classes in Hamming-weight batches as the plan batches its nodes
    (:func:`qcpp.plan.phase_choice.visit_batches` per kind, in the ``pool`` ancillas): per class, its full batches,
    the last smaller one, and the nodes left with their own gadgets (a part per class and colour). A batch's
    example puts node ``i``'s edges after node ``i - 1``'s: its nodes, of one colour, share no edge, and they
    fit in the ``n`` data qubits as the real nodes do."""
    out: list[tuple[Gadget, int, int]] = []
    for g, count, need in parts:
        if not (isinstance(g, VisitPhase) and g.products):
            out.append((g, count, need))
            continue
        sizes = tuple(len(v) for v in g.visitors)
        batches = Counter(visit_batches(sizes, g.coefficient, count, pool, "ft", optimize, budget))
        for size, times in batches.items():
            batch = replace(VisitBatch.of_kind(sizes, size, g.coefficient), gamma=g.gamma)
            assert size * sum(sizes) <= n, (size, sizes, n)  # as many disjoint nodes as the real ones, who fit
            out.append((batch, times, visit_batch_ancillas(sizes, size)))
        left = count - sum(size * times for size, times in batches.items())
        if left:
            out.append((g, left, need))
    return out


def _arithmetic(balance: _Balance, pool: range) -> Gadget:
    """The balance's gadget on the layer's ancilla pool (what a :class:`Deferred` part builds when emitted)."""
    return replace(balance.gadget(), ancillas=tuple(pool))


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

    def folded(self) -> tuple[_Balance, ...] | None:
        """The term as one form per balanced pair, over both robots' variables, as
        :meth:`qcpp.problem.feasible_cost.SumsGroup.folded` folds the plan's group (same forms, terms in the same
        order), or ``None``."""
        pairs = difference_pairs(self.matrix)
        if pairs is None:
            return None
        out = []
        for a, b, w in pairs:
            form = np.concatenate([x if r == a else -x if r == b else 0 * x for r, x in enumerate(self.weights)])
            if np.abs(form).sum() > MAX_INTEGER_TOTAL:
                return None
            out.append(_Balance((form,), ((w,),)))
        return tuple(out)

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
    """Pure memo: ``_grid.cache_clear()`` empties it."""
    u = np.array([grid.edge_nodes[e][0] for e in edges], dtype=np.int64)
    v = np.array([grid.edge_nodes[e][1] for e in edges], dtype=np.int64)
    degree = np.bincount(u, minlength=grid.num_nodes) + np.bincount(v, minlength=grid.num_nodes)
    return _Grid(u, v, degree, tuple(int(x) for x in np.nonzero(degree == 2)[0]))


Local = tuple[tuple[list[int], ...], list[int]]


def _local(g: _Grid, ends: tuple[int, int]) -> Local:
    """Where one robot's identities act: the edge positions (ascending, as
    :func:`qcpp.problem.feasible_cost.live_edges` lists them) at its endpoints (nodes 0 and 1) and at the corners that
    are not its endpoints (corridors), the only edges they touch on an open grid; and all of those edges."""
    nodes = [*ends, *(c for c in g.corners if c not in ends)]
    at = tuple(np.nonzero((g.u == n) | (g.v == n))[0].tolist() for n in nodes)
    return at, sorted({k for edges in at for k in edges})


def _reduce(values: np.ndarray, local: Local) -> tuple[float, np.ndarray]:
    """:func:`~qcpp.problem.feasible_cost.reduce_on_paths` of one robot's coefficient vector where its identities act:
    ``(constant, coefficients)``, a zero marking a dropped term."""
    at, touched = local
    const, reduced = reduce_on_paths({k: float(values[k]) for k in touched}, at, (0, 1))
    out = values.copy()
    out[touched] = 0.0
    for k, val in reduced.items():
        out[k] = val
    out[np.abs(out) <= _TOL] = 0.0
    return const, out


@lru_cache(maxsize=SCENARIOS_KEPT)  # the counts and the depth bound of a scenario both ask
def phase_layer(
    scenario: Scenario,
    target: str = "nisq",
    representation: str = "feasible",
    optimize: str = "cx",
    ancilla_budget: int | None = None,
) -> PhaseLayer | None:
    """The phase separator of one layer by classes (see the module docstring), or ``None`` where only the plan
    knows (obstacles, overridden lengths, a node or balance whose construction is couplings, or the balance's
    arithmetic out of the budget).

    Args:
        scenario: the scenario.
        target, representation, optimize, ancilla_budget: as :func:`qcpp.plan.phase.phase_plan`.

    Returns:
        The :class:`PhaseLayer`, or ``None``.

    Pure memo: ``phase_layer.cache_clear()`` empties it."""
    s, grid = scenario, scenario.grid
    ob = s.objective
    if representation == "whole-space":  # one IsingPhase, whatever the other options
        count = ising_count(s)
        if count is None:
            return None
        return _layer(s, count.linear, count.couplings, [], whole_space=True)
    if s.obstacles or ob.edge_lengths:
        return None
    ends = [(grid.node_index(rb.start), grid.node_index(rb.goal)) for rb in s.robots]
    if any(a == b for a, b in ends):
        return None
    g = _grid(grid, tuple(s.variable_edges))
    local = [_local(g, e) for e in ends]
    n_r, v_per = s.num_robots, s.edges_per_robot
    a0, a1, a2 = ob.alpha
    parts: list[tuple[Gadget, int, int]] = []
    # degree terms: a linear part per node, a visit class per (degree, passers)
    node_term = np.zeros(grid.num_nodes)
    if a2 != 0.0:
        t = np.asarray(s.degree_targets, dtype=float)
        e_v = np.bincount(np.ravel(np.array(ends, dtype=np.int64)), minlength=grid.num_nodes)  # endpoints per node
        counted = ~np.isnan(t)
        c = e_v - np.where(counted, t, 0.0)
        node_term = np.where(counted, a2 * (2 * c + 2), 0.0)
        passers = n_r - e_v
        # on ft the nodes of each colour go in batches of their own (phase_choice.visit_batches), as the plan's
        colour = np.indices((grid.rows, grid.cols)).sum(axis=0).ravel() % 2 if target == "ft" else 0 * node_term
        classes = Counter(zip(g.degree[counted].tolist(), passers[counted].tolist(), colour[counted].tolist()))
        for (degree, m, _), count in sorted(classes.items()):
            if m < 2:
                continue
            # no coupling exists yet when the visits are chosen (the balance is arithmetic, checked below)
            choice = visit_choice((degree,) * m, 8.0 * a2, m * (m - 1) // 2 * degree * degree, target, optimize,
                                  ancilla_budget)  # fmt: skip
            if choice.gadget is None:
                return None  # a coupling would change what the later groups' couplings cost
            parts.append((choice.gadget, count, choice.ancillas))
    lin = []
    for a, b in ends:
        own = node_term.copy()
        own[[a, b]] = 0.0
        lin.append(a0 * ob.free_weight + own[g.u] + own[g.v])
    # balance
    pairs = balanced_pairs(s) if a1 != 0.0 else []
    balance: tuple[_Balance, ...] = ()
    floor: int | None = None  # a lower bound on the couplings alternative's score, when it is one
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
        whole = _Balance(tuple(weights), tuple(tuple(float(x) for x in row) for row in m))
        balance = (whole,)
        folded = whole.folded()
        if folded is not None:
            two = (whole.shape.cost(), whole.shape.logical_cost(), whole.shape.num_ancillas)

            def one() -> tuple[Cost, Cost, int]:
                assert folded is not None
                return (Cost.sum(b.shape.cost() for b in folded), Cost.sum(b.shape.logical_cost() for b in folded),
                        max(b.shape.num_ancillas for b in folded))  # fmt: skip

            if prefer_folded(two, one, target, ancilla_budget):  # type: ignore[arg-type]
                balance = folded  # as the plan folds it (its other variants are the plan's to price)
        need = max(b.shape.num_ancillas for b in balance)
        # only the arithmetic is counted by classes: any other first variant is left to the plan
        candidates = sums_constructions(
            True, coupling_products(sizes, m), optimize, ancilla_budget,
            lambda variant: need if variant == "arithmetic" else 0,
        )  # fmt: skip
        if candidates[0] != "arithmetic":
            return None
        if "couplings" in candidates:
            # the plan also prices the balance as couplings; they interact with the visits, but not below this
            floor = couplings_floor(sizes, [m[a][a] for a in range(n_r)], target)  # type: ignore[arg-type]
        lin_g = 2 * m @ np.array(consts)
        for r, w in enumerate(weights):
            lin[r] = lin[r] + float(lin_g[r]) * w
    values = np.concatenate([_reduce(lin[r], local[r])[1] for r in range(n_r)]) if n_r else np.zeros(0)
    values = values[values != 0.0]
    if target == "ft":  # no coupling exists: every rotation may be merged
        groups = hamming_groups(enumerate(values.tolist()), target, optimize, ancilla_budget)
        parts += [(hw, 1, hw.num_ancillas) for hw, _ in groups]
        values = np.delete(values, [q for _, qs in groups for q in qs])
        pool = max([0, *(need for _, _, need in parts), *(b.shape.num_ancillas for b in balance)])
        parts = _batched(parts, pool, s.num_variables, optimize, ancilla_budget)  # type: ignore[arg-type]
    rotations = int(np.count_nonzero(np.abs(values / 2) > COEFFICIENT_TOLERANCE))
    layer = _layer(s, rotations, 0, parts, balance)
    if floor is not None and floor <= plan_score(layer.kinds(), target)[0]:  # type: ignore[arg-type]
        return None  # the couplings might win: only the plan knows
    return layer


# ----------------------------------------------------------------------------- whole-space (Ising) phase separator


@dataclass(frozen=True)
class IsingCount:
    """The whole-space phase separator's terms (:class:`~qcpp.gadgets.phase_ising.IsingPhase`), counted.

    Attributes:
        linear: nonzero ``h_i`` (one RZ each).
        couplings: nonzero ``J_ij`` (one RZZ each).
    """

    linear: Count
    couplings: Count


_NodeClass = tuple[int, bool, float]  # (variable edges at the node, counted by the degree term, its target)


def _pairs(n: Count) -> Count:
    """``C(n, 2)`` of a count (exact division for a symbolic one)."""
    return n * (n - 1) // 2 if isinstance(n, int) else n * (n - 1) / 2


def ising_count(scenario: Scenario, sizes: tuple[Count, Count] | None = None) -> IsingCount | None:
    """The whole-space phase separator's terms on an open grid, counted by classes of nodes and edges.

    With uniform edge weights and lengths (an open grid unless overridden) the Ising coefficients of the cost
    (:func:`qcpp.problem.hamiltonian.ising_hamiltonian`) depend only on classes: ``h`` of robot ``r``'s edge ``e`` is
    ``-alpha0 w / 2 + alpha2 sum_{i in e, counted} (t_i - robots deg_i / 2)`` (the balance's linear part cancels:
    each balanced pair adds ``+1`` and ``-1`` to a robot's row), and ``J`` of ``(r, e), (s, f)`` is
    ``(alpha1 d^2 B_rs + alpha2 shared(e, f)) / 2`` with ``B`` the balance's robot matrix and ``shared`` the
    counted nodes ``e`` and ``f`` have in common (0, 1, or 2 when ``e = f``). So the counts are sums over node
    classes (degree, counted, target) and edge classes (the classes of its two ends) of ``count x [coefficient !=
    0]``: the plain grid's classes (counted arithmetically, ``sizes`` may be symbolic) with the edges at the
    robots' endpoints moved to their own classes.

    Args:
        scenario: the scenario (for symbolic ``sizes``, a representative grid whose boundary and endpoint classes
            are those of every grid of the case).
        sizes: count for a grid of ``(rows, cols)`` nodes (sympy expressions, for :mod:`qcpp.estimators.formulas`)
            instead of the scenario's own.

    Returns:
        The :class:`IsingCount`, or ``None`` (obstacles, overridden lengths, a robot whose start is its goal).

    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.problem.hamiltonian import ising_hamiltonian
    >>> s = default_scenario(5, 4, 3)
    >>> n, h = ising_count(s), ising_hamiltonian(s)
    >>> (n.linear, n.couplings) == (len(list(h.linear_terms(1e-12))), h.num_quadratic_terms(1e-12))
    True
    """
    s, grid = scenario, scenario.grid
    ob = s.objective
    if s.obstacles or ob.edge_lengths or any(rb.start == rb.goal for rb in s.robots):
        return None
    rows, cols = grid.rows, grid.cols
    size_r, size_c = sizes if sizes is not None else (rows, cols)
    n_r = s.num_robots
    a0, a1, a2 = ob.alpha
    targets = s.degree_targets
    ends = {grid.node_index(rb.start) for rb in s.robots} | {grid.node_index(rb.goal) for rb in s.robots}

    def degree(node: tuple[int, int]) -> int:
        return 4 - boundary(*node, rows, cols)

    def plain(node: tuple[int, int]) -> _NodeClass:
        return degree(node), True, 2.0  # every node but an endpoint has target 2 (exact and paper)

    def real(node: tuple[int, int]) -> _NodeClass:
        t = float(targets[grid.node_index(node)])
        return degree(node), not np.isnan(t), 0.0 if np.isnan(t) else t

    def edge(a: _NodeClass, b: _NodeClass) -> tuple[_NodeClass, _NodeClass]:
        return (a, b) if a <= b else (b, a)

    nodes = class_counts((rows, cols), (size_r, size_c), lambda i, j: plain((i, j)))
    edges = class_counts((rows, cols - 1), (size_r, size_c - 1), lambda i, k: edge(plain((i, k)), plain((i, k + 1))))
    down = class_counts((rows - 1, cols), (size_r - 1, size_c), lambda k, j: edge(plain((k, j)), plain((k + 1, j))))
    edges.update(down)
    for node in ends:  # endpoints and the edges at them move to their own classes
        xy = grid.nodes[node]
        nodes[plain(xy)] -= 1
        nodes[real(xy)] += 1
    for e in range(grid.num_edges):
        u, v = (grid.nodes[k] for k in grid.edge_nodes[e])
        if grid.edge_nodes[e][0] in ends or grid.edge_nodes[e][1] in ends:
            edges[edge(plain(u), plain(v))] -= 1
            edges[edge(real(u), real(v))] += 1

    def nonzero(value: float) -> int:
        return int(abs(value / 2) > COEFFICIENT_TOLERANCE)

    def pull(c: _NodeClass) -> float:  # a counted node's share of h
        deg, counted, t = c
        return t - n_r * deg / 2 if counted else 0.0

    weight = ob.free_weight
    linear = n_r * sum((n * nonzero(-a0 * weight + 2 * a2 * (pull(u) + pull(v))) for (u, v), n in edges.items()), 0)
    total = sum(edges.values(), 0)  # edges per robot
    pairs = sum((n * (c[0] * (c[0] - 1) // 2) for c, n in nodes.items() if c[1]), 0)  # sharing a counted node
    both = sum((n for (u, v), n in edges.items() if u[1] and v[1]), 0)
    one = sum((n for (u, v), n in edges.items() if u[1] != v[1]), 0)
    m = balance_matrix(n_r, balanced_pairs(s) if a1 != 0.0 else [], a1 * ob.edge_length**2)
    couplings: Count = 0
    for r in range(n_r):
        b = float(m[r][r])
        couplings += (_pairs(total) - pairs) * nonzero(b) + pairs * nonzero(b + a2)
        for q in range(r + 1, n_r):
            b = float(m[r][q])
            across = (one + 2 * pairs, both)
            couplings += (total * total - across[0] - across[1]) * nonzero(b) + across[0] * nonzero(b + a2)
            couplings += across[1] * nonzero(b + 2 * a2)
    return IsingCount(linear, couplings)
