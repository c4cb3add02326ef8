"""Which construction each term group of the phase separator gets: one decision per group shape and options.

The phase separator implements every term group of the feasible cost with the cheapest exact construction under
the target's cost model (:func:`score`). The decision depends only on the group's *shape* and the plan options,
so it is made here, once, and asked both by :func:`qcpp.plan.phase.phase_plan` (group by group) and by
:func:`qcpp.plan.phase_classes.phase_layer` (once per class of nodes): :func:`visit_choice` for a node several
robots can pass, :func:`visit_batches` for how the ``ft`` target batches such nodes, :func:`hamming_choice` for
equal rotations on the ``ft`` target, :func:`sums_constructions` for a balance group (whose couplings interact
with the visits', so the plan compares its candidates as whole plans by :func:`plan_score`) and
:func:`prefer_folded` for whether it is taken per balanced pair.

Example:
    >>> c = visit_choice((4, 4, 4), 8.0, new_couplings=48, target="nisq", optimize="cx", budget=None)
    >>> c.construction, c.costs["couplings"][0].cx, c.costs["visit bits"][0].cx
    ('visit bits', 96, 42)
    >>> visit_choice((2, 2), 8.0, 4, "nisq", "cx", None).construction   # one RZZ on the visit bits: 2 CX, not 8
    'visit bits'
    >>> visit_choice((2, 2), 8.0, 0, "nisq", "cx", None).construction   # its products merge with couplings
    'couplings'
    >>> hamming_choice(12, 0.5, "ft", "cx", None) is not None, hamming_choice(12, 0.5, "nisq", "cx", None)
    (True, None)
    >>> sums_constructions(True, 40_000, "cx", 3, {"arithmetic": 9, "registers": 5, "accumulator": 3}.__getitem__)
    ('accumulator',)
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from itertools import accumulate
from typing import Any, Literal

from qcpp.gadgets.phase_ising import COEFFICIENT_TOLERANCE
from qcpp.gadgets.phase_sums import SumsPhase
from qcpp.gadgets.phase_visits import VisitPhase, visit_ancillas
from qcpp.gadgets.visit_batch import VisitBatch, visit_batch_ancillas
from qcpp.ir.cost import Cost, Target
from qcpp.plan.options import Optimize

__all__ = [
    "EXACT_EXPANSION_LIMIT",
    "ROTATION_T_COST",
    "SUMS_VARIANTS",
    "VisitChoice",
    "coupling_cost",
    "couplings_floor",
    "ft_t_count",
    "hamming_choice",
    "hamming_groups",
    "plan_score",
    "prefer_folded",
    "score",
    "sums_constructions",
    "visit_batches",
    "visit_choice",
]

ROTATION_T_COST = 30
"""T gates per arbitrary rotation in the ``ft`` cost model, for choosing only: ``ceil(3 log2(1/eps))`` at ``eps =
1e-3``, :func:`qcpp.estimators.fault_tolerant.rotation_t_cost` with its defaults (a test keeps the two equal)."""

EXACT_EXPANSION_LIMIT = 30_000
"""A balance group with at most this many products is expanded to price its couplings exactly (products that
merge with others' or cancel cost nothing); larger ones are priced at one coupling per product."""

SUMS_VARIANTS: tuple[str, ...] = ("arithmetic", "registers", "accumulator")
"""A balance group's arithmetic constructions, fewest CX first (each needs fewer ancillas than the one before)."""

VisitName = Literal["visit bits", "visit pairs", "couplings"]


def ft_t_count(logical: Cost) -> int:
    """T count of a logical cost in the ``ft`` model: AND 4, its uncompute 0, Toffoli 7, T 1, rotation
    :data:`ROTATION_T_COST`.

    >>> ft_t_count(Cost.of({"and": 2, "and_dg": 2, "rz": 1}))
    38
    """
    return 4 * logical["and"] + 7 * logical["ccx"] + logical.t + ROTATION_T_COST * logical.rotations


def score(cost: Cost, logical: Cost, target: Target) -> tuple[int, ...]:
    """Sort key of a construction under the target's cost model (smaller is cheaper).

    >>> score(Cost.of(cx=2, rz=1), Cost.of(cx=2, rz=1), "ft")
    (30, 2, 3)
    """
    if target == "ft":
        return (ft_t_count(logical), cost.cx, cost.total)
    return (cost.cx, cost.rotations, cost.total)


def plan_score(parts: Iterable[tuple[Any, int]], target: Target) -> tuple[int, ...]:
    """:func:`score` of gadgets (or gadget kinds) with multiplicities, their costs summed: how candidate plans of
    the phase separator are compared (a sort key, never a reported count).

    >>> from qcpp.gadgets.phase_ising import IsingPhase
    >>> plan_score([(IsingPhase("gamma", ((0, 1.0),), ((0, 1, 1.0),)), 2)], "nisq")
    (4, 4, 8)
    """
    parts = list(parts)
    return score(Cost.sum(n * g.cost() for g, n in parts), Cost.sum(n * g.logical_cost() for g, n in parts), target)


def coupling_cost(products: int) -> Cost:
    """Estimated price of ``products`` extra couplings: one RZZ each (their linear parts land on qubits that
    carry an RZ anyway).

    >>> coupling_cost(3).to_dict()
    {'cx': 6, 'rz': 3}
    """
    return Cost.of(cx=2 * products, rz=products)


def couplings_floor(sizes: Sequence[int], diagonal: Sequence[float], target: Target) -> int:
    """A lower bound on the first entry of :func:`plan_score` of any plan that expands a balance group into
    couplings: the products within one form (one robot's edges) meet no other term, so each stays an RZZ.

    Args:
        sizes: the group's forms' numbers of terms.
        diagonal: the group's matrix diagonal ``M_aa`` (a form's own products exist where it is not zero).
        target: the plan's target.

    Returns:
        The bound (CX for ``nisq``, T for ``ft``).

    >>> couplings_floor([3, 2], [1.0, 0.0], "nisq")
    6
    """
    within = sum(n * (n - 1) // 2 for n, m in zip(sizes, diagonal, strict=True) if abs(m) > 0)
    return (ROTATION_T_COST if target == "ft" else 2) * within


@dataclass(frozen=True)
class VisitChoice:
    """The construction of one node's visit term.

    Attributes:
        construction: ``visit bits``, ``visit pairs`` or ``couplings``.
        gadget: the chosen :class:`~qcpp.gadgets.phase_visits.VisitPhase` on abstract qubits (the visitors'
            edges numbered from 0 on, no ancillas; place it with :func:`dataclasses.replace`), or ``None`` for the
            couplings.
        costs: ``(cost, logical cost)`` of every construction, chosen or not (what ``--explain`` lists).
        ancillas: clean ancillas the chosen construction needs.
    """

    construction: VisitName
    gadget: VisitPhase | None
    costs: Mapping[str, tuple[Cost, Cost]]
    ancillas: int


@lru_cache(maxsize=4096)
def visit_choice(
    sizes: tuple[int, ...],
    coefficient: float,
    new_couplings: int,
    target: Target,
    optimize: Optimize,
    budget: int | None,
) -> VisitChoice:
    """The plan's construction for the visit term of a node (see the module docstring).

    Args:
        sizes: per visitor, its usable edges at the node (2 to 4).
        coefficient: the factor of ``sum_{a<b} y_a y_b``.
        new_couplings: couplings that expanding the term into products of edge bits would add to the couplings
            already chosen (net of those it cancels).
        target, optimize, budget: the plan's options (``budget``: most clean ancillas, ``None``: no limit).

    Returns:
        The :class:`VisitChoice`: in the order couplings, visit bits, visit pairs, a visit gadget (only for
        ``optimize="cx"`` and within the budget) replaces the pick so far when it scores no worse and costs differ.

    Pure memo: ``visit_choice.cache_clear()`` empties it."""
    coup = coupling_cost(new_couplings)
    costs: dict[str, tuple[Cost, Cost]] = {}
    pick: tuple[VisitName, tuple[Cost, Cost], VisitPhase | None] = ("couplings", (coup, coup), None)
    edges = tuple(tuple(range(end - n, end)) for n, end in zip(sizes, accumulate(sizes), strict=True))
    for name, products in (("visit bits", False), ("visit pairs", True)):
        gad = VisitPhase("gamma", coefficient, edges, (), products)
        c = (gad.cost(), gad.logical_cost())
        costs[name] = c
        if optimize != "cx" or (budget is not None and visit_ancillas(sizes, products) > budget):
            continue
        if score(*c, target) <= score(*pick[1], target) and c != pick[1]:
            pick = (name, c, gad)  # type: ignore[assignment]
    costs["couplings"] = (coup, coup)
    name, _, gadget = pick
    ancillas = 0 if gadget is None else visit_ancillas(sizes, gadget.products)
    return VisitChoice(name, gadget, costs, ancillas)


@lru_cache(maxsize=1024)
def visit_batches(
    sizes: tuple[int, ...], coefficient: float, count: int, pool: int, target: Target, optimize: Optimize,
    budget: int | None,
) -> tuple[int, ...]:
    """How the plan batches ``count`` nodes whose visit gadgets compute pair products (the ``visit pairs``
    construction) with visitors of these sizes and this coefficient (:class:`~qcpp.gadgets.visit_batch.VisitBatch`).

    Only on the ``ft`` target with ``optimize="cx"`` and a nonzero coefficient. A batch holds every node's
    ancillas at once, so it takes as many nodes as fit in ``pool`` (the clean ancillas the phase separator has
    anyway: its other gadgets' largest need) and in the budget: batching never adds a qubit. The nodes go in
    batches of that size, in order; the last, smaller one only where it scores better than its nodes' own gadgets.

    Args:
        sizes: per visitor, its usable edges at each node (2 to 4).
        coefficient: the factor of each node's ``sum_{a<b} y_a y_b``.
        count: nodes of this kind.
        pool: clean ancillas the batches may use.
        target, optimize, budget: the plan's options.

    Returns:
        Nodes per batch, in order (empty: no batch); the nodes after them keep their own gadgets.

    >>> visit_batches((4, 4, 4, 4), 8.0, 10, 80, "ft", "cx", None)
    (4, 4, 2)
    >>> visit_batches((4, 4), 8.0, 10, 80, "nisq", "cx", None)
    ()

    Pure memo: ``visit_batches.cache_clear()`` empties it."""
    if target != "ft" or optimize != "cx" or abs(coefficient) <= COEFFICIENT_TOLERANCE or count < 1:
        return ()
    room = pool if budget is None else min(pool, budget)
    lo, hi = 0, count  # the most nodes whose batch fits: visit_batch_ancillas grows with the nodes
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if visit_batch_ancillas(sizes, mid) <= room:
            lo = mid
        else:
            hi = mid - 1
    single = VisitPhase("gamma", coefficient, tuple(tuple(range(k)) for k in sizes), (), True)

    def better(nodes: int) -> bool:
        batch = VisitBatch.of_kind(sizes, nodes, coefficient)
        return score(batch.cost(), batch.logical_cost(), target) < score(
            nodes * single.cost(), nodes * single.logical_cost(), target
        )

    if lo < 1 or not better(lo):
        return ()
    out = [lo] * (count // lo)
    if count % lo and better(count % lo):
        out.append(count % lo)
    return tuple(out)


@lru_cache(maxsize=1024)
def hamming_choice(
    n: int, coefficient: float, target: Target, optimize: Optimize, budget: int | None
) -> SumsPhase | None:
    """Hamming-weight phasing of ``n`` equal rotations ``RZ(2 gamma coefficient)`` of uncoupled qubits, when the
    plan prefers it to the rotations: ``ft`` target, ``optimize="cx"``, ``n >= 3``, within the budget and scoring
    no worse than the rotations.

    Returns:
        The gadget on qubits ``0 .. n - 1`` (no ancillas; place it with :func:`dataclasses.replace`), or ``None``.

    Pure memo: ``hamming_choice.cache_clear()`` empties it."""
    if target != "ft" or optimize != "cx" or n < 3:
        return None
    hw = SumsPhase("gamma", (tuple((q, 1) for q in range(n)),), ((0.0,),), (coefficient,))
    alt = Cost.of(rz=n)
    fits = budget is None or hw.num_ancillas <= budget
    return hw if fits and score(hw.cost(), hw.logical_cost(), target) <= score(alt, alt, target) else None


def hamming_groups(
    coefficients: Iterable[tuple[int, float]], target: Target, optimize: Optimize, budget: int | None
) -> list[tuple[SumsPhase, list[int]]]:
    """The equal-angle rotations of uncoupled qubits ``(qubit, coefficient)`` the plan merges: per class of equal
    nonzero coefficients (to 12 decimals, in order of first appearance) that :func:`hamming_choice` takes, its
    gadget and the class's qubits.

    >>> [(qs, hw.num_ancillas) for hw, qs in hamming_groups([(0, 0.5), (1, 0.2), (4, 0.5), (7, 0.5)], "ft", "cx", 9)]
    [([0, 4, 7], 1)]
    """
    classes: dict[float, tuple[float, list[int]]] = {}
    for q, v in coefficients:
        if abs(v) > COEFFICIENT_TOLERANCE:
            classes.setdefault(round(v, 12), (v, []))[1].append(q)
    groups = [(hamming_choice(len(qs), v, target, optimize, budget), qs) for v, qs in classes.values()]
    return [(hw, qs) for hw, qs in groups if hw is not None]


def prefer_folded(
    two: tuple[Cost, Cost, int], one: Callable[[], tuple[Cost, Cost, int]], target: Target, budget: int | None
) -> bool:
    """Whether a balance construction takes its group folded into difference forms (``one``,
    :meth:`qcpp.problem.feasible_cost.SumsGroup.folded`: one gadget per balanced pair) rather than as the group's
    own forms (``two``).

    Only on the ``ft`` target, and there the one that fits the ancilla budget, then the lower :func:`score`, then
    fewer ancillas; a tie keeps the forms. The fold's gain is in rotations (one register per pair has far fewer
    bit pairs to phase than registers coupled bit by bit), which the ``ft`` model prices at
    :data:`ROTATION_T_COST` T each. Under ``nisq`` it saves a few CX on two robots, or costs some (a robot in two
    pairs has its sum computed twice), while the robots' adder trees, which ran side by side on their own
    registers, become one tree per pair: the circuit gets deeper (``benchmarks/balance_difference.py``).

    Args:
        two: ``(lowered cost, logical cost, clean ancillas)`` of the construction on the group's own forms.
        one: gives the same of the folded construction (summed over the pairs' gadgets, the ancillas of the
            largest); called only where the fold is considered (the ``ft`` target), so other targets price nothing.
        target, budget: the plan's options.

    Returns:
        ``True`` to fold.

    >>> two = (Cost.of(cx=554, rz=45), Cost.of(cx=554, rz=45), 32)
    >>> one = lambda: (Cost.of(cx=542, rz=21), Cost.of(cx=542, rz=21), 34)
    >>> prefer_folded(two, one, "ft", None), prefer_folded(two, one, "ft", 33), prefer_folded(two, one, "nisq", None)
    (True, False, False)
    """
    if target != "ft":
        return False

    def key(c: tuple[Cost, Cost, int]) -> tuple[bool, tuple[int, ...], int]:
        return budget is not None and c[2] > budget, score(c[0], c[1], target), c[2]

    return key(one()) < key(two)


def sums_constructions(
    integral: bool, products: int, optimize: Optimize, budget: int | None, ancillas: Callable[[str], int]
) -> tuple[str, ...]:
    """The constructions the plan compares for a balance group: the first arithmetic variant of
    :data:`SUMS_VARIANTS` that fits the budget (integer weights and ``optimize="cx"`` only), and ``couplings``
    when its products can be expanded (at most :data:`EXACT_EXPANSION_LIMIT`) or nothing else is possible.

    Args:
        integral: the group's weights are integers.
        products: products of two variables its expansion has (:func:`qcpp.plan.phase.coupling_products`).
        optimize, budget: the plan's options.
        ancillas: clean ancillas of an arithmetic variant (asked only when there is a budget).

    Returns:
        The candidates, in the plan's order.
    """
    out: list[str] = []
    if integral and optimize == "cx":
        for variant in SUMS_VARIANTS:
            if budget is None or ancillas(variant) <= budget:
                out.append(variant)
                break
    if products <= EXACT_EXPANSION_LIMIT or not out:
        out.append("couplings")
    return tuple(out)
