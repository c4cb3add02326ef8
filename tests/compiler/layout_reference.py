"""The place-aware layout code as it was before it was made near-linear (commit c6ba873), kept verbatim as the
reference the fast code must match gate for gate (``phase_sums_selection_test.py``):

* the local-first popcount: every bit keeps its tightest triple, refreshed by rescanning its whole column, and
  the next adder is a minimum over every bit's entry. With ``next_triple`` switched off it also gives the passes
  along the curve with a sink (what local first replaced);
* :func:`reference_spatial_phase`: the visit gadgets' ancillas chosen by sorting the whole pool for every node.
"""

from __future__ import annotations

import dataclasses
import heapq
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence

from qcpp.gadgets import Gadget
from qcpp.gadgets.phase_sums import (
    Sink,
    Site,
    SumsPhase,
    hilbert_key,
    manhattan,
    star_full_adder,
    star_half_adder,
)
from qcpp.gadgets.phase_visits import VisitPhase
from qcpp.ir.gates import Gate, cx, x
from qcpp.plan.phase_layout import NEW_HOME_PENALTY, placed_sums, variable_sites
from qcpp.problem.scenario import Scenario

_Bit = tuple[int, Site]


class _LocalFirst:
    """The columns of a popcount reduced local first (see :func:`spatial_popcount_layout`): every bit keeps its
    tightest triple (itself and its two nearest bits of its column, by distance then curve position) with that
    triple's score (diameter, then farther from the sink, then curve position), refreshed only where a full
    adder removed one of its bits or put a carry nearer than its second-nearest bit, so choosing the next adder
    is a minimum over the bits, not a search over every triple."""

    def __init__(self, cols: dict[int, list[_Bit]], sink: Sink, key: Callable[[_Bit], tuple[int, int]]) -> None:
        self.cols, self.sink, self.key = cols, sink, key
        self.best: dict[int, tuple[tuple, int, list[_Bit]]] = {}  # qubit -> (score, column, triple)
        for k, col in cols.items():
            for it in col:
                self._refresh(it, k)

    def _refresh(self, it: _Bit, k: int) -> None:
        col = self.cols[k]
        if len(col) < 3:
            self.best.pop(it[0], None)
            return
        others = (o for o in col if o[0] != it[0])
        near = heapq.nsmallest(2, others, key=lambda o: (manhattan(o[1], it[1]), self.key(o)))
        span = max(manhattan(it[1], near[0][1]), manhattan(it[1], near[1][1]), manhattan(near[0][1], near[1][1]))
        self.best[it[0]] = ((span, -manhattan(self.sink, it[1]), self.key(it)), k, [it, *near])

    def next_triple(self, column: int | None = None) -> tuple[int, list[_Bit]] | None:
        """``(column, triple)`` of the best full adder (in ``column`` only, if given), ``None`` if there is none."""
        found = [v for v in self.best.values() if column is None or v[1] == column]
        if not found:
            return None
        _, k, triple = min(found, key=lambda v: (v[0], v[1]))
        return k, triple

    def update(self, k: int, removed: set[int], carry: _Bit) -> None:
        """Bits ``removed`` left column ``k``; ``carry`` joined column ``k + 1``."""
        for q in removed:
            self.best.pop(q, None)
        col = self.cols[k]
        for it in col:
            v = self.best.get(it[0])
            if len(col) < 3 or v is None or any(o[0] in removed for o in v[2]):
                self._refresh(it, k)
        col = self.cols[k + 1]
        for it in col:
            v = self.best.get(it[0])
            if it is carry or v is None:
                self._refresh(it, k + 1)
                continue
            second = v[2][2]
            if (manhattan(carry[1], it[1]), self.key(carry)) < (manhattan(second[1], it[1]), self.key(second)):
                self._refresh(it, k + 1)


def _sink_adder(cols: dict[int, list[_Bit]], k: int, triple: list[_Bit], sink: Sink,
                key: Callable[[_Bit], tuple[int, int]], ancillas: Iterator[int], gates: list[Gate],
                home: dict[int, Site]) -> tuple[set[int], _Bit]:  # fmt: skip
    """One :func:`star_full_adder` on ``triple`` of column ``k``: the sum stays on the bit nearest the sink, the
    carry (a fresh ancilla sited with it) joins column ``k + 1``. Returns the bits that left column ``k`` and the
    carry."""
    j = min(range(3), key=lambda j_: (manhattan(sink, triple[j_][1]), key(triple[j_])))
    mid = triple[j]
    (a, _), (c, _) = (triple[j_] for j_ in range(3) if j_ != j)
    t = next(ancillas)
    home[t] = mid[1]
    gates += star_full_adder(a, mid[0], c, t)
    cols[k] = [it for it in cols[k] if it[0] not in (a, c)]
    carry = (t, mid[1])
    cols.setdefault(k + 1, []).append(carry)
    return {a, c}, carry


def reference_popcount_layout(
    form: tuple[tuple[int, int], ...], ancillas: Iterator[int], sites: Mapping[int, Site], sink: Sink | None = None
) -> tuple[list[Gate], list[int | None], dict[int, Site]]:
    """The old :func:`qcpp.gadgets.phase_sums.spatial_popcount_layout`, verbatim but for a memo of the curve
    positions (the same keys, computed once per site)."""
    order = 1
    while order <= max((max(sites[q]) for q, _ in form), default=0):
        order <<= 1

    curve: dict[Site, int] = {}  # a site's place on the curve: computed once (the search asks millions of times)

    def key(item: tuple[int, Site]) -> tuple[int, int]:
        site = item[1]
        if site not in curve:
            curve[site] = hilbert_key(site[0], site[1], order)
        return curve[site], item[0]

    home: dict[int, Site] = {}
    gates: list[Gate] = [x(q) for q, w in form if w < 0]
    cols: dict[int, list[tuple[int, Site]]] = {}
    for q, w in form:
        w, k, first = abs(w), 0, True
        while w:
            if w & 1:
                if first:
                    cols.setdefault(k, []).append((q, sites[q]))
                    first = False
                else:
                    a = next(ancillas)
                    home[a] = sites[q]
                    gates.append(cx(q, a))
                    cols.setdefault(k, []).append((a, sites[q]))
            w >>= 1
            k += 1
    local = None
    if sink is not None:  # local first: the tightest triple of any column, until no column has three bits
        local = _LocalFirst(cols, sink, key)
        while (found := local.next_triple()) is not None:
            k, triple = found
            local.update(k, *_sink_adder(cols, k, triple, sink, key, ancillas, gates, home))
    reg: list[int | None] = []
    k = 0
    while cols and k <= max(cols):
        col = sorted(cols.get(k, []), key=key)
        while local is not None and (found := local.next_triple(k)) is not None:
            local.update(k, *_sink_adder(cols, k, found[1], sink, key, ancillas, gates, home))
            col = sorted(cols[k], key=key)
        while len(col) >= 3:
            nxt: list[tuple[int, Site]] = []
            full = len(col) // 3
            for i in range(full):
                triple = col[3 * i : 3 * i + 3]
                j = 1 if sink is None else min(range(3), key=lambda j_: (manhattan(sink, triple[j_][1]), j_ != 1, j_))
                mid = triple[j]
                (a, _), (c, _) = (triple[j_] for j_ in range(3) if j_ != j)
                b = mid[0]
                t = next(ancillas)
                home[t] = mid[1]
                gates += star_full_adder(a, b, c, t)
                nxt.append(mid)
                cols.setdefault(k + 1, []).append((t, mid[1]))
            col = sorted(nxt + col[3 * full :], key=key)
        if len(col) == 2:
            if sink is not None and manhattan(sink, col[1][1]) < manhattan(sink, col[0][1]):
                col.reverse()  # the sum stays on the bit nearer the sink
            (a, site), (b, _) = col
            t = next(ancillas)
            home[t] = site
            gates += star_half_adder(a, b, t)
            col = [(a, site)]
            cols.setdefault(k + 1, []).append((t, site))
            if local is not None:  # the carry may give the next column a third bit
                cols[k] = col
                local.update(k, {b}, (t, site))
        reg.append(col[0][0] if col else None)
        k += 1
    return gates, reg, home


def reference_spatial_phase(
    gadgets: Sequence[Gadget], scenario: Scenario, pool: Iterable[int], sinks: bool = False
) -> tuple[Gadget, ...]:
    """The old :func:`qcpp.plan.phase_layout.spatial_phase`, verbatim."""
    sites = variable_sites(scenario)
    pool = tuple(pool)
    out = list(placed_sums(gadgets, scenario, sinks))
    home: dict[int, Site] = {}
    for g in out:
        if isinstance(g, SumsPhase):
            home.update(g.ancilla_sites())
    borrowed: dict[int, int] = dict.fromkeys(pool, 0)
    for i, g in enumerate(out):
        if not isinstance(g, VisitPhase) or not g.ancillas:
            continue
        edge_sites = [sites[q] for v in g.visitors for q in v]
        at = (sum(s[0] for s in edge_sites) / len(edge_sites), sum(s[1] for s in edge_sites) / len(edge_sites))
        usable = [a for a in pool if a in borrowed]

        def rank(a: int, at: tuple[float, float] = at) -> tuple[float, int]:
            far = manhattan(at, home[a]) if a in home else float("inf")
            return far + NEW_HOME_PENALTY * borrowed[a], a

        chosen = tuple(sorted(usable, key=rank)[: len(g.ancillas)])
        for a in chosen:
            borrowed[a] += 1
            home.setdefault(a, (round(at[0]), round(at[1])))
        out[i] = dataclasses.replace(g, ancillas=chosen)
    return tuple(out)
