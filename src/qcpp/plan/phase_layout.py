"""The phase separator laid out by place: adder trees over neighbouring edges, node gadgets with nearby ancillas.

On a nearest-neighbour device it matters which bits an adder takes and which ancilla a node's visit gadget
borrows: the ``pooled`` layout (as planned) adds each robot's edges in variable order, joining bits from far
apart rows, and hands out the pool's ancillas round robin, so a router moves qubits across the device for every
such gate.

:func:`spatial_phase` is a pass over the planned gadgets (``phase_layout="spatial"`` in
:class:`~qcpp.plan.options.PlanOptions`) that changes which qubits play which role and the shape of the adders:

* every :class:`~qcpp.gadgets.phase_sums.SumsPhase` gets the site of each data qubit (the midpoint of its
  edge on the doubled lattice: node ``(r, c)`` at ``(2r, 2c)``) and reduces each column of its popcount along a
  Hilbert curve (:func:`~qcpp.gadgets.phase_sums.spatial_popcount_layout`), each adder a star around its carry
  ancilla so no gate joins two data qubits (one CX more per adder each way, a kind of its own);
* every :class:`~qcpp.gadgets.phase_visits.VisitPhase` borrows the pool ancillas whose home (the region
  of the adder that uses them, or the node that first borrowed them) is nearest its node, preferring ancillas no
  other node borrowed (same gates).

The plan itself (which construction each term group gets, how many ancillas) is unchanged: it is chosen on the
all-to-all count.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.plan.phase import phase_plan
    >>> s = default_scenario(4, 4, 2)
    >>> plan = phase_plan(s)
    >>> n = s.num_variables
    >>> pooled = plan.gadgets("gamma_0")
    >>> local = spatial_phase(pooled, s, range(n, n + plan.num_ancillas))
    >>> [type(g).__name__ for g in local] == [type(g).__name__ for g in pooled]
    True
    >>> sum(g.cost().cx for g in pooled), sum(g.cost().cx for g in local)  # 2 CX more per adder
    (770, 834)
"""

from __future__ import annotations

import dataclasses
import heapq
from collections.abc import Iterable, Sequence

from qcpp.gadgets import Gadget
from qcpp.gadgets.buckets import bucket, ring
from qcpp.gadgets.phase_sums import Sink, Site, SumsPhase, manhattan
from qcpp.gadgets.phase_visits import VisitPhase
from qcpp.problem.scenario import Scenario

__all__ = ["balance_sinks", "placed_sums", "spatial_phase", "tiling", "variable_sites"]

NEW_HOME_PENALTY = 4
"""Lattice units (two per grid step) an ancilla another node already borrowed counts as farther away: a node
takes a fresh ancilla up to two grid steps farther rather than share one with a distant node."""


def variable_sites(scenario: Scenario) -> dict[int, Site]:
    """Qubit -> site of every data qubit: the midpoint of its edge on the doubled lattice (both robots' copies of
    an edge share the site).

    >>> from qcpp.problem.presets import default_scenario
    >>> sorted(variable_sites(default_scenario(2, 2, 1)).items())
    [(0, (0, 1)), (1, (1, 0)), (2, (1, 2)), (3, (2, 1))]
    """
    sites = scenario.grid.edge_sites
    return {i: sites[scenario.variable_of(i)[1]] for i in range(scenario.num_variables)}


def tiling(k: int, patch: tuple[int, int]) -> tuple[int, int]:
    """Patches per row and column for ``k`` patches of shape ``patch``: the near-square arrangement
    ``(down, across)`` of smallest bounding square, then smallest area (the robots' copies of the grid in the
    medial layout, :mod:`qcpp.layout.medial`, and the balance sinks of :func:`balance_sinks`).

    >>> tiling(2, (5, 5)), tiling(3, (5, 5)), tiling(3, (1, 1))
    ((2, 1), (2, 2), (2, 2))
    """
    best: tuple[tuple[int, int], tuple[int, int]] | None = None
    for across in range(1, k + 1):
        down = -(-k // across)
        h, w = down * patch[0], across * patch[1]
        key = (max(h, w), h * w)
        if best is None or key < best[0]:
            best = (key, (down, across))
    assert best is not None
    return best[1]


def placed_sums(gadgets: Sequence[Gadget], scenario: Scenario, sinks: bool = False) -> tuple[Gadget, ...]:
    """The gadgets with every :class:`~qcpp.gadgets.phase_sums.SumsPhase` given its data qubits' sites (star
    adders placed along the Hilbert curve), the rest as given: the kinds and costs of :func:`spatial_phase`'s
    output without choosing the visit gadgets' ancillas (what the estimators need; no gate is built). ``sinks``:
    also give each form its sink (:func:`balance_sinks`; the ``medial`` layout; same kinds and costs)."""
    sites = variable_sites(scenario)

    def placed(g: SumsPhase) -> SumsPhase:
        robots = [scenario.variable_of(f[0][0])[0] if f else -1 for f in g.forms]
        return dataclasses.replace(
            g,
            sites=tuple((q, *sites[q]) for f in g.forms for q, _ in f),
            sinks=balance_sinks(scenario, robots, g.matrix) if sinks else (),
        )

    return tuple(placed(g) if isinstance(g, SumsPhase) else g for g in gadgets)


def balance_sinks(
    scenario: Scenario, robots: Sequence[int], matrix: Sequence[Sequence[float]]
) -> tuple[Sink | None, ...]:
    """Per form of a balance gadget (``robots[a]``: the robot whose edges form ``a`` sums, ``-1`` for none), the
    point of that robot's copy of the grid (doubled lattice) its popcount's sums should drift to: where its
    patch of the medial layout's tiling (:func:`tiling`) is nearest the centre of the patches
    of itself and the robots whose sums ``matrix`` couples with it. On two robots that is the middle of the side
    their patches share, so their registers, which the register phase couples bit by bit, end next to each
    other. ``None`` for a form coupled with no other robot (one robot: no sink).

    >>> from qcpp.problem.presets import default_scenario
    >>> balance_sinks(default_scenario(4, 4, 2), [0, 1], ((1.0, -1.0), (-1.0, 1.0)))  # patches one above the other
    ((6.0, 3.0), (0.0, 3.0))
    """
    g = scenario.grid
    patch = (2 * g.rows - 1, 2 * g.cols - 1)
    _, across = tiling(scenario.num_robots, patch)

    def corner(r: int) -> tuple[int, int]:
        dr, dc = divmod(r, across)
        return dr * patch[0], dc * patch[1]

    out: list[Sink | None] = []
    for a, r in enumerate(robots):
        group = [robots[b] for b in range(len(robots)) if robots[b] >= 0 and (b == a or matrix[a][b] or matrix[b][a])]
        if r < 0 or len(group) < 2:
            out.append(None)
            continue
        cy = sum(corner(x)[0] for x in group) / len(group) + (patch[0] - 1) / 2
        cx_ = sum(corner(x)[1] for x in group) / len(group) + (patch[1] - 1) / 2
        oy, ox = corner(r)
        out.append((min(max(cy - oy, 0.0), patch[0] - 1.0), min(max(cx_ - ox, 0.0), patch[1] - 1.0)))
    return tuple(out)


def spatial_phase(
    gadgets: Sequence[Gadget], scenario: Scenario, pool: Iterable[int], sinks: bool = False
) -> tuple[Gadget, ...]:
    """The same gadgets with place-aware adder trees and node-local ancillas (see the module docs).

    Args:
        gadgets: The phase plan's gadgets (:meth:`qcpp.plan.phase.PhasePlan.gadgets`), variable ``i`` on
            qubit ``i``.
        scenario: Their scenario (where each variable's edge lies).
        pool: The plan's clean ancillas (its ``num_ancillas`` qubits).
        sinks: Give each balance form its sink (:func:`balance_sinks`): ``phase_layout="medial"``.

    Returns:
        The gadgets in the same order and of the same classes: the balance gadgets with placed star-shaped
        adder trees, the visit gadgets with nearby ancillas (same kinds), the rest as given.
    """
    sites = variable_sites(scenario)
    out = list(placed_sums(gadgets, scenario, sinks))
    home: dict[int, Site] = {}
    for g in out:
        if isinstance(g, SumsPhase):
            home.update(g.ancilla_sites())
    homes = _Homes(tuple(pool), home)
    for i, g in enumerate(out):
        if not isinstance(g, VisitPhase) or not g.ancillas:
            continue
        edge_sites = [sites[q] for v in g.visitors for q in v]
        at = (sum(s[0] for s in edge_sites) / len(edge_sites), sum(s[1] for s in edge_sites) / len(edge_sites))
        out[i] = dataclasses.replace(g, ancillas=homes.borrow(at, len(g.ancillas)))
    return tuple(out)


class _Homes:
    """The pool's ancillas by home, for :func:`spatial_phase`'s choice: a node borrows the ancillas of least
    ``(distance from its home + NEW_HOME_PENALTY * times borrowed, ancilla)`` (no home: infinitely far, so
    least ancilla first), and an ancilla borrowed without a home gets the node's. The homes sit in buckets
    (:mod:`qcpp.gadgets.buckets`) searched ring by ring until no farther ring can hold a better ancilla, so a
    choice looks at the ancillas near the node, not at the whole pool (which made 30x30/8's choice quadratic).

    Args:
        pool: The plan's clean ancillas.
        home: Ancilla -> home (the adders' sites); the ones borrowed without a home are added to it.
    """

    SIZE = 4
    """Bucket side in lattice units (two grid steps)."""

    def __init__(self, pool: tuple[int, ...], home: dict[int, Site]) -> None:
        self.home = home
        self.borrowed = dict.fromkeys(pool, 0)
        self.homeless = sorted(a for a in pool if a not in home)  # taken from the front, least first
        self.cells: dict[tuple[int, int], list[int]] = {}
        self.homed = 0
        for a in pool:
            if a in home:
                self._file(a)

    def _file(self, a: int) -> None:
        self.cells.setdefault(bucket(*self.home[a], self.SIZE), []).append(a)
        self.homed += 1

    def _rank(self, a: int, at: tuple[float, float]) -> float:
        return manhattan(at, self.home[a]) + NEW_HOME_PENALTY * self.borrowed[a]

    def borrow(self, at: tuple[float, float], count: int) -> tuple[int, ...]:
        """The ``count`` ancillas a node at ``at`` borrows (fewer if the pool is smaller), best first."""
        want = min(count, self.homed)
        found: list[tuple[float, int]] = []
        if want:
            cy, cx = bucket(*at, self.SIZE)
            rho = 0
            while True:
                if (2 * rho + 1) ** 2 > self.homed:  # more buckets than ancillas: look at every one
                    found = [(self._rank(a, at), a) for c in self.cells.values() for a in c]
                    break
                found += [(self._rank(a, at), a) for c in ring(cy, cx, rho) for a in self.cells.get(c, ())]
                # every ancilla of ring rho + 1 or beyond ranks more than rho * SIZE
                if len(found) >= want and heapq.nsmallest(want, found)[-1][0] <= rho * self.SIZE:
                    break
                rho += 1
        chosen = [a for _, a in heapq.nsmallest(want, found)]
        chosen += self.homeless[: count - want]
        del self.homeless[: count - want]
        for a in chosen:
            self.borrowed[a] += 1
            if a not in self.home:
                self.home[a] = (round(at[0]), round(at[1]))
                self._file(a)
        return tuple(chosen)
