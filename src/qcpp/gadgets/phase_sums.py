"""Phases of quadratic functions of integer sums, by arithmetic: compute the sums, phase the registers, uncompute.

The gadget applies ``exp(-i gamma (g - c0))`` with ``g = sum_{a,b} M_ab G_a G_b + sum_a m_a G_a`` and
``G_a = sum_j w_aj x_j`` integer linear forms over bits held on qubits (each qubit in at most one form). It

1. flips (X) every qubit with a negative weight, so ``w x = |w| (NOT x) - |w|``: all weights positive;
2. puts each bit in the columns of its weight's binary digits (a weight with ``d`` set digits costs ``d - 1``
   copies into clean ancillas, 1 CX each);
3. reduces every form's columns, lowest first, to one bit per column with a carry-save tree (a Wallace tree
   popcount): while a column holds three bits a full adder (``cx a b; cx a c; and b c t; cx a t; cx b c;
   cx a c``: 5 CX + one AND into a clean ancilla ``t``, 8 CX) leaves their sum in ``c`` and sends the carry
   ``t`` to the next column; two bits left go through a half adder (``and a b t; cx a b``: 4 CX);
4. applies the phase of ``g`` on the resulting register bits (``H_a = sum_k 2^k b_ak``): one RZ per bit and
   one RZZ per pair of bits with a nonzero product coefficient (:func:`~.phase_ising.ising_form`);
5. uncomputes steps 3, 2, 1 with the exact mirror: every ancilla returns to |0> on every input.

With ``F`` full adders, ``A`` half adders, ``P`` copies and ``B`` register bits the lowered cost is
``CX = 16 F + 8 A + 2 P + 2 J`` and ``F + A`` ANDs (+ their mirrors), rotations ``B + J`` (``J`` the
nonzero bit pairs, at most ``C(B, 2)``); ancillas ``F + A + P``. For one unit-weight form of ``n`` bits
``F + A <= n``, ``B = floor(log2 n) + 1``: ``O(n)`` CX against the ``O(n^2)`` of pairwise couplings.
With ``M = 0`` and one form of equal-angle rotations this is Hamming-weight phasing (Gidney 2018): ``n``
rotations become ``B`` rotations and ``n - B``-ish ANDs.

Example:
    >>> g = SumsPhase("gamma_0", (((0, 1), (1, 1), (2, 1)),), ((1.0,),), (0.0,), tuple(range(3, 10)))
    >>> g.adders(), g.num_ancillas
    ((1, 0, 0), 1)
    >>> g.cost().cx, g.cost().rotations
    (18, 3)
"""

from __future__ import annotations

import heapq
from collections import Counter, deque
from collections.abc import Callable, Hashable, Iterator, Mapping
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import NamedTuple

from qcpp.gadgets.buckets import bucket, ring
from qcpp.gadgets.phase_ising import IsingPhase, ising_form
from qcpp.gadgets.phase_visits import AND_COST, AND_DG_COST, with_ands
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate, and_, cx, x

__all__ = [
    "Sink",
    "Site",
    "SumsKind",
    "SumsPhase",
    "SumsShape",
    "column_counts",
    "hilbert_key",
    "manhattan",
    "spatial_popcount_layout",
]


def column_counts(weights: list[int] | Mapping[int, int]) -> tuple[int, int, int, tuple[bool, ...]]:
    """Full adders, half adders, copies and which columns keep a bit, for one form's absolute weights.

    The same reduction :class:`SumsPhase` emits, counted without building a gate.

    Args:
        weights: The absolute weights, or a mapping ``weight -> how many terms have it``.
    """
    cols: dict[int, int] = {}
    copies = 0
    counted = weights if isinstance(weights, Mapping) else Counter(weights)
    for w, times in counted.items():  # forms repeat few weights (1 and 2 on a grid)
        k, first = 0, True
        while w:
            if w & 1:
                cols[k] = cols.get(k, 0) + times
                copies += 0 if first else times
                first = False
            w >>= 1
            k += 1
    fa = ha = 0
    present: list[bool] = []
    k = 0
    while cols and k <= max(cols):
        n = cols.get(k, 0)
        f = (n - 1) // 2 if n >= 3 else 0
        n -= 2 * f
        h = 1 if n == 2 else 0
        n -= h
        if f + h:
            cols[k + 1] = cols.get(k + 1, 0) + f + h
        fa += f
        ha += h
        present.append(n == 1)
        k += 1
    return fa, ha, copies, tuple(present)


def popcount_layout(form: tuple[tuple[int, int], ...], ancillas: Iterator[int]) -> tuple[list[Gate], list[int | None]]:
    """Gates computing ``sum |w| b`` of one form into one bit per column (steps 1-3 of the module docstring).

    Args:
        form: ``(qubit, integer weight)`` pairs.
        ancillas: Clean ancillas, drawn as needed (copies, then one carry per adder).

    Returns:
        ``(gates, register)``: ``register[k]`` is the qubit holding column ``k`` (``None``: column empty).
    """
    gates: list[Gate] = [x(q) for q, w in form if w < 0]
    cols: dict[int, deque[int]] = {}
    for q, w in form:
        w, k, first = abs(w), 0, True
        while w:
            if w & 1:
                if first:
                    cols.setdefault(k, deque()).append(q)
                    first = False
                else:
                    a = next(ancillas)
                    gates.append(cx(q, a))
                    cols.setdefault(k, deque()).append(a)
            w >>= 1
            k += 1
    reg: list[int | None] = []
    k = 0
    while cols and k <= max(cols):
        col = cols.get(k, deque())
        while len(col) >= 3:
            a, b, c = col.popleft(), col.popleft(), col.popleft()
            t = next(ancillas)
            gates += [cx(a, b), cx(a, c), and_(b, c, t), cx(a, t), cx(b, c), cx(a, c)]
            col.append(c)
            cols.setdefault(k + 1, deque()).append(t)
        if len(col) == 2:
            a, b = col.popleft(), col.popleft()
            t = next(ancillas)
            gates += [and_(a, b, t), cx(a, b)]
            col.append(b)
            cols.setdefault(k + 1, deque()).append(t)
        reg.append(col[0] if col else None)
        k += 1
    return gates, reg


def hilbert_key(y: int, x: int, order: int = 1 << 16) -> int:
    """Position of the lattice point ``(y, x)`` along a Hilbert curve over ``order x order`` points (a power of
    two): points close on the curve are close in the plane, so consecutive runs of a sorted list are compact
    regions of the grid at every scale.

    >>> [hilbert_key(y, x, 2) for y, x in ((0, 0), (1, 0), (1, 1), (0, 1))]
    [0, 1, 2, 3]
    """
    d = 0
    s = order >> 1
    while s:
        rx = 1 if x & s else 0
        ry = 1 if y & s else 0
        d += s * s * ((3 * rx) ^ ry)
        if ry == 0:  # rotate the quadrant so the curve stays continuous
            if rx == 1:
                x, y = s - 1 - (x & (s - 1)), s - 1 - (y & (s - 1))
            x, y = y, x
        s >>= 1
    return d


Site = tuple[int, int]
"""A point of the problem grid's doubled lattice: node ``(r, c)`` at ``(2r, 2c)``, an edge at its midpoint."""


def star_full_adder(a: int, b: int, c: int, t: int) -> list[Gate]:
    """A full adder whose every gate touches the clean ancilla ``t``: the sum lands on ``b``, the carry on ``t``.

    ``cx c t; cx a t`` (``t = a^c``), ``cx t b`` (``b = a^b^c``, the sum), ``cx b t`` (``t = b``), ``cx t a;
    cx t c`` (``a^b``, ``b^c``), ``and a c t`` (``t = b ^ (a^b)(b^c)``, the majority): 6 CX and one AND, one
    CX more than the gadget's in-line adder, found by a shortest-path search over circuits whose gates all act
    on ``t``. On a device the adder is a star around ``t`` (no gate between two data bits, which a geometric
    layout never puts side by side). The AND's target is not clean here: its lowering is then a Toffoli up to
    a diagonal phase, which the gadget's exact mirror undoes (compute, diagonal phase, inverse: the phases
    cancel), so the gadget stays exact.

    >>> [(g.name, g.qubits) for g in star_full_adder(0, 1, 2, 3)][-2:]
    [('cx', (3, 2)), ('and', (0, 2, 3))]
    """
    return [cx(c, t), cx(a, t), cx(t, b), cx(b, t), cx(t, a), cx(t, c), and_(a, c, t)]


def star_half_adder(a: int, b: int, t: int) -> list[Gate]:
    """A half adder around the clean ancilla ``t``: ``cx b t; cx t a`` (``a = a^b``, the sum), then ``and a b t``
    (``t = b ^ (a^b) b = ab``, the carry; the target is not clean, see :func:`star_full_adder`). 2 CX and one AND
    (one CX more than the in-line half adder), every gate on ``t``.

    >>> [(g.name, g.qubits) for g in star_half_adder(0, 1, 2)]
    [('cx', (1, 2)), ('cx', (2, 0)), ('and', (0, 1, 2))]
    """
    return [cx(b, t), cx(t, a), and_(a, b, t)]


Sink = tuple[float, float]
"""A point of the doubled lattice (fractional allowed) that a popcount's partial sums drift towards."""


def manhattan(a: Site | Sink, b: Site | Sink) -> float:
    """Manhattan distance on the doubled lattice (between two sites, or a site and a sink).

    >>> manhattan((0, 0), (2, 1)), manhattan((1.5, 0.0), (0, 0))
    (3, 1.5)
    """
    return abs(a[0] - b[0]) + abs(a[1] - b[1])


_Bit = tuple[int, Site]


_CELL = 2
"""Side of the buckets (lattice units) the local-first index files each column's bits in: about two bits of a
robot's edge column per bucket (edge midpoints fill half the doubled lattice), so a bit's two nearest bits are
usually found in the 3 x 3 buckets around it."""


class _LocalFirst:
    """The columns of a popcount reduced local first (see :func:`spatial_popcount_layout`), with what choosing the
    next full adder needs kept up to date in time that does not grow with the columns.

    Every bit of a column of at least three bits keeps its tightest triple (itself and its two nearest bits of the
    column, by distance then curve key) and that triple's score (diameter, then farther from the sink, then curve
    key); the next adder is the least score of a column (or of any column: then the least ``(score, column)``).
    It makes the same choice as rescanning every bit, in time that does not grow with the columns: bits are
    filed in buckets of :data:`_CELL` lattice units (nearest bits searched ring by ring), an adder updates only
    the bits whose triple it touched or whose second-nearest bit lies farther than its carry (a second index by
    that distance), and the scores sit in one lazily pruned heap per column.

    Args:
        cols: Column -> qubit -> site, changed in place by :meth:`remove` and :meth:`add`.
        sink: Where the sums drift (the score's second key).
        keys: Qubit -> curve key ``(Hilbert position, qubit)``; the caller adds every new qubit's.
    """

    def __init__(self, cols: dict[int, dict[int, Site]], sink: Sink, keys: dict[int, tuple[int, int]]) -> None:
        self.cols, self.sink, self.keys = cols, sink, keys
        self.cells: dict[int, dict[tuple[int, int], set[int]]] = {}  # column -> bucket -> qubits
        self.best: dict[int, tuple[tuple, int, int]] = {}  # qubit -> (score, nearest, second nearest)
        self.heaps: dict[int, list[tuple[tuple, int]]] = {}  # column -> (score, qubit), stale entries included
        self.holders: dict[int, set[int]] = {}  # qubit -> the bits whose triple holds it
        self.reach: dict[int, dict[int, dict[tuple[int, int], set[int]]]] = {}  # column -> class -> bucket -> bits
        self.filed: dict[int, tuple[int, int, tuple[int, int]]] = {}  # qubit -> (column, class, bucket) in reach
        for k, col in cols.items():
            for q, (y, x_) in col.items():
                self.cells.setdefault(k, {}).setdefault(bucket(y, x_, _CELL), set()).add(q)
        for k, col in cols.items():
            if len(col) >= 3:
                for q in col:
                    self._refresh(k, q)

    def _nearest_two(self, k: int, q: int) -> tuple[int, int]:
        """The two bits of column ``k`` nearest bit ``q`` (distance, then curve key), ``q`` excluded."""
        col, keys, cells = self.cols[k], self.keys, self.cells[k]
        y, x_ = col[q]
        cy, cx = bucket(y, x_, _CELL)
        found: list[tuple[float, tuple[int, int]]] = []
        rho = 0
        while True:
            if (2 * rho + 1) ** 2 > len(col):  # more buckets than bits: scan the column
                found = [(abs(s[0] - y) + abs(s[1] - x_), keys[o]) for o, s in col.items() if o != q]
                break
            for cell in ring(cy, cx, rho):
                for o in cells.get(cell, ()):
                    if o != q:
                        s = col[o]
                        found.append((abs(s[0] - y) + abs(s[1] - x_), keys[o]))
            # a bucket of ring rho + 1 or beyond lies more than rho * _CELL away
            if len(found) >= 2 and heapq.nsmallest(2, found)[1][0] <= rho * _CELL:
                break
            rho += 1
        a, b = heapq.nsmallest(2, found)
        return a[1][1], b[1][1]

    def _drop(self, q: int) -> None:
        """Forget bit ``q``'s triple (removed, or its column fell below three bits, or about to be refreshed)."""
        v = self.best.pop(q, None)
        if v is None:
            return
        for o in v[1:]:
            held = self.holders.get(o)
            if held is not None:
                held.discard(q)
        k, j, cell = self.filed.pop(q)
        filed = self.reach[k][j]
        filed[cell].discard(q)
        if not filed[cell]:
            del filed[cell]

    def _refresh(self, k: int, q: int) -> None:
        col = self.cols[k]
        n0, n1 = self._nearest_two(k, q)
        s, s0, s1 = col[q], col[n0], col[n1]
        span = max(manhattan(s, s0), manhattan(s, s1), manhattan(s0, s1))
        score = (span, -manhattan(self.sink, s), self.keys[q])
        self._drop(q)
        self.best[q] = (score, n0, n1)
        self.holders.setdefault(n0, set()).add(q)
        self.holders.setdefault(n1, set()).add(q)
        j = int(manhattan(s, s1)).bit_length()  # the second nearest bit lies below 2^j away
        cell = bucket(*s, 1 << j)
        self.reach.setdefault(k, {}).setdefault(j, {}).setdefault(cell, set()).add(q)
        self.filed[q] = (k, j, cell)
        heapq.heappush(self.heaps.setdefault(k, []), (score, q))

    def next_triple(self, column: int | None = None) -> tuple[int, list[_Bit]] | None:
        """``(column, triple)`` of the best full adder (in ``column`` only, if given), ``None`` if there is none."""
        top: tuple[tuple, int, int] | None = None
        for k in (column,) if column is not None else tuple(self.heaps):
            heap = self.heaps.get(k)
            while heap:
                v = self.best.get(heap[0][1])
                if v is not None and v[0] == heap[0][0]:
                    break
                heapq.heappop(heap)
            if heap and (top is None or (heap[0][0], k) < top[:2]):
                top = (heap[0][0], k, heap[0][1])
        if top is None:
            return None
        _, k, q = top
        _, n0, n1 = self.best[q]
        col = self.cols[k]
        return k, [(q, col[q]), (n0, col[n0]), (n1, col[n1])]

    def remove(self, k: int, gone: tuple[int, ...]) -> None:
        """Bits ``gone`` leave column ``k``."""
        col, cells = self.cols[k], self.cells[k]
        stale: set[int] = set()
        for q in gone:
            stale |= self.holders.pop(q, set())
            self._drop(q)
            cell = bucket(*col.pop(q), _CELL)
            cells[cell].discard(q)
            if not cells[cell]:
                del cells[cell]
        if len(col) < 3:
            for q in col:
                self._drop(q)
            return
        for q in stale:
            if q in col:
                self._refresh(k, q)

    def add(self, k: int, q: int, site: Site) -> None:
        """Bit ``q`` (its key already in :attr:`keys`) joins column ``k`` at ``site``."""
        col = self.cols.setdefault(k, {})
        col[q] = site
        self.cells.setdefault(k, {}).setdefault(bucket(*site, _CELL), set()).add(q)
        if len(col) == 3:
            for o in col:
                self._refresh(k, o)
        elif len(col) > 3:
            for o in self._nearer_than_second(k, q):
                self._refresh(k, o)
            self._refresh(k, q)

    def _nearer_than_second(self, k: int, q: int) -> list[int]:
        """The bits of column ``k`` to which the new bit ``q`` is nearer (distance, then curve key) than their
        second nearest bit: the bits whose triple it changes."""
        col, keys, best = self.cols[k], self.keys, self.best
        y, x_ = col[q]
        out = []
        for j, grid in self.reach.get(k, {}).items():
            cy, cx = bucket(y, x_, 1 << j)
            for dy in (-1, 0, 1):
                for dx in (-1, 0, 1):
                    for o in grid.get((cy + dy, cx + dx), ()):
                        s, second = col[o], best[o][2]
                        s2 = col[second]
                        if (abs(s[0] - y) + abs(s[1] - x_), keys[q]) < (manhattan(s2, s), keys[second]):
                            out.append(o)
        return out


def _sink_adder(local: _LocalFirst, k: int, triple: list[_Bit], ancillas: Iterator[int], gates: list[Gate],
                home: dict[int, Site], key_of: Callable[[int, Site], tuple[int, int]]) -> None:  # fmt: skip
    """One :func:`star_full_adder` on ``triple`` of column ``k``: the sum stays on the bit nearest the sink, the
    carry (a fresh ancilla sited with it) joins column ``k + 1``."""
    keys, sink = local.keys, local.sink
    j = min(range(3), key=lambda j_: (manhattan(sink, triple[j_][1]), keys[triple[j_][0]]))
    mid = triple[j]
    (a, _), (c, _) = (triple[j_] for j_ in range(3) if j_ != j)
    t = next(ancillas)
    home[t] = mid[1]
    gates += star_full_adder(a, mid[0], c, t)
    keys[t] = key_of(t, mid[1])
    local.remove(k, (a, c))
    local.add(k + 1, t, mid[1])


def spatial_popcount_layout(
    form: tuple[tuple[int, int], ...], ancillas: Iterator[int], sites: Mapping[int, Site], sink: Sink | None = None
) -> tuple[list[Gate], list[int | None], dict[int, Site]]:
    """:func:`popcount_layout` with the adders chosen by place and shaped for a device: the same numbers of full
    adders, half adders and copies, the same register columns, but every full adder takes three bits that are
    neighbours along a Hilbert curve over the grid, and is a star around its carry ancilla.

    Each column is sorted by the Hilbert key of its bits' sites and reduced in passes: consecutive triples go
    through :func:`star_full_adder` (sum on the middle bit, carry on a fresh ancilla sited with it, joining the
    next column), so pass ``k`` adds up compact regions of about ``3^k`` bits and only ``O(log)`` partial sums
    travel far. Each adder costs one CX more than :func:`popcount_layout`'s: no gate joins two data bits.

    A full adder is symmetric in its three inputs, so any of them may keep the sum: without a ``sink`` the middle
    one (along the curve) does. With a ``sink`` (the ``medial`` layout) the adders are chosen *local first*: the
    next full adder is always the tightest triple of any column that holds three bits (a bit and its two nearest
    bits of the same column, of least diameter; on ties the one farther from the sink), the input nearest the sink
    keeps the sum and the carry joins the next column where it was made; then the columns are finished in order,
    a half adder keeping its sum on the bit nearer the sink. Small neighbourhoods are added up first, so the
    partial sums and the register bits drift towards the sink, which
    :func:`qcpp.plan.phase_layout.balance_sinks` puts where the robots whose registers are phased together meet.
    The counts per column stay :func:`column_counts`' whatever the order.

    Args:
        form: ``(qubit, integer weight)`` pairs.
        ancillas: Clean ancillas, drawn as needed (copies, then one carry per adder).
        sites: Lattice site of every qubit of the form.
        sink: Where the sums should end (``None``: passes along the curve, the middle bit of every triple keeps
            its sum).

    Returns:
        ``(gates, register, ancilla sites)``: as :func:`popcount_layout`, plus the site given to each ancilla.

    Example:
        >>> form = tuple((q, 1) for q in range(6))
        >>> gates, reg, home = spatial_popcount_layout(form, iter(range(6, 10)), {q: (0, 2 * q) for q in range(6)})
        >>> reg, home  # 6 = 110b: columns 0, 1, 2 end on qubits 1, 8, 9
        ([1, 8, 9], {6: (0, 2), 7: (0, 8), 8: (0, 2), 9: (0, 2)})
        >>> sum(1 for g in gates if g.name == "and"), column_counts([1] * 6)[:3]
        (4, (3, 1, 0))
    """
    order = 1
    while order <= max((max(sites[q]) for q, _ in form), default=0):
        order <<= 1
    keys: dict[int, tuple[int, int]] = {}

    def key_of(q: int, site: Site) -> tuple[int, int]:
        return hilbert_key(site[0], site[1], order), q

    def carry(k: int, t: int, site: Site) -> None:
        keys[t] = key_of(t, site)
        cols.setdefault(k, {})[t] = site

    home: dict[int, Site] = {}
    gates: list[Gate] = [x(q) for q, w in form if w < 0]
    cols: dict[int, dict[int, Site]] = {}  # column -> qubit -> site
    for q, w in form:
        w, k, first = abs(w), 0, True
        while w:
            if w & 1:
                if first:
                    cols.setdefault(k, {})[q] = sites[q]
                    keys[q] = key_of(q, sites[q])
                    first = False
                else:
                    a = next(ancillas)
                    home[a] = sites[q]
                    gates.append(cx(q, a))
                    carry(k, a, sites[q])
            w >>= 1
            k += 1
    local = None
    if sink is not None:  # local first: the tightest triple of any column, until no column has three bits
        local = _LocalFirst(cols, sink, keys)
        while (found := local.next_triple()) is not None:
            _sink_adder(local, *found, ancillas, gates, home, key_of)
    reg: list[int | None] = []
    k = 0
    while cols and k <= max(cols):
        while local is not None and (found := local.next_triple(k)) is not None:
            _sink_adder(local, *found, ancillas, gates, home, key_of)
        col = sorted(cols.get(k, {}).items(), key=lambda it: keys[it[0]])
        while len(col) >= 3:  # the passes along the curve (without a sink): the middle bit keeps the sum
            nxt: list[_Bit] = []
            full = len(col) // 3
            for i in range(full):
                (a, _), mid, (c, _) = col[3 * i : 3 * i + 3]
                t = next(ancillas)
                home[t] = mid[1]
                gates += star_full_adder(a, mid[0], c, t)
                nxt.append(mid)
                carry(k + 1, t, mid[1])
            col = sorted(nxt + col[3 * full :], key=lambda it: keys[it[0]])
        if len(col) == 2:
            if sink is not None and manhattan(sink, col[1][1]) < manhattan(sink, col[0][1]):
                col.reverse()  # the sum stays on the bit nearer the sink
            (a, site), (b, _) = col
            t = next(ancillas)
            home[t] = site
            gates += star_half_adder(a, b, t)
            col = [(a, site)]
            if local is None:
                carry(k + 1, t, site)
            else:  # the carry may give the next column a third bit
                keys[t] = key_of(t, site)
                local.remove(k, (b,))
                local.add(k + 1, t, site)
        reg.append(col[0][0] if col else None)
        k += 1
    return gates, reg, home


@lru_cache(maxsize=64)  # an entry holds every register coupling (up to ~1 MB at 40x40/8): a sweep reuses few
def _abstract_phase(
    gamma: str,
    presents: tuple[tuple[bool, ...], ...],
    offs: tuple[int, ...],
    matrix: tuple[tuple[float, ...], ...],
    linear: tuple[float, ...],
) -> tuple[float, IsingPhase]:
    """The phase on abstract register labels ``(form, column)``: it depends on the registers' shape only, which
    many gadgets share (memoised: a sweep prices thousands). Pure memo: ``_abstract_phase.cache_clear()`` empties it."""
    registers = [[(a, k) if p else None for k, p in enumerate(pr)] for a, pr in enumerate(presents)]
    return _register_phase(gamma, registers, list(offs), matrix, linear)  # type: ignore[arg-type]


def _register_phase(
    gamma: str,
    registers: list[list[int | None]],
    offs: list[int],
    matrix: tuple[tuple[float, ...], ...],
    linear: tuple[float, ...],
) -> tuple[float, IsingPhase]:
    """``(c0, the RZ/RZZ gadget)`` of ``g = sum M_ab G_a G_b + sum m_a G_a`` on the register bits, where
    ``G_a = H_a - offs_a`` and ``H_a = sum_k 2^k register[a][k]``."""
    n = len(registers)
    const = 0.0
    lin_h = [float(linear[a]) for a in range(n)]
    for a in range(n):
        const -= linear[a] * offs[a]
        for b in range(n):
            mab = matrix[a][b]
            const += mab * offs[a] * offs[b]
            lin_h[a] -= 2 * mab * offs[b]
    lin: dict[object, float] = {}
    quad: dict[tuple[object, object], float] = {}
    for a in range(n):
        bits_a = [(k, q) for k, q in enumerate(registers[a]) if q is not None]
        if not bits_a:
            continue
        for k, q in bits_a:
            v = lin_h[a] * (1 << k) + matrix[a][a] * (1 << (2 * k))
            if v:
                lin[q] = lin.get(q, 0.0) + v
        if matrix[a][a]:
            for i, (k, q) in enumerate(bits_a):
                for l_, p in bits_a[i + 1 :]:
                    # higher column first: never the same qubit pair, in the same order, as a copy's CX
                    quad[(p, q)] = 2 * matrix[a][a] * (1 << (k + l_))
        for b in range(a + 1, n):
            mab = matrix[a][b] + matrix[b][a]
            if not mab:
                continue
            for k, q in bits_a:
                for l_, p in enumerate(registers[b]):
                    if p is not None:
                        quad[(q, p)] = mab * (1 << (k + l_))
    c0, h, j = ising_form(lin, quad, constant=const)  # type: ignore[arg-type]
    return c0, IsingPhase(gamma, tuple(h.items()), tuple((a, b, v) for (a, b), v in j.items()))  # type: ignore[misc]


@dataclass(frozen=True)
class SumsShape:
    """What a :class:`SumsPhase` costs depends on: per form the multiset of its weights, the matrix and the
    linear coefficients (not the qubits, nor the order of the terms). Hashable, so costs are memoised per shape.

    Attributes:
        weights: Per form, ``(absolute weight, how many terms)`` pairs, ascending.
        negatives: Per form, ``(number of negative weights, minus their sum)``.
        matrix, linear: As :class:`SumsPhase`.

    Example:
        >>> SumsShape((((1, 3),),), ((0, 0),), ((1.0,),), (0.0,)).cost().cx
        18
    """

    weights: tuple[tuple[tuple[int, int], ...], ...]
    negatives: tuple[tuple[int, int], ...]
    matrix: tuple[tuple[float, ...], ...]
    linear: tuple[float, ...]
    star: bool = False

    @classmethod
    def of(
        cls, forms: tuple[tuple[tuple[int, int], ...], ...], matrix: tuple[tuple[float, ...], ...],
        linear: tuple[float, ...], star: bool = False,
    ) -> SumsShape:
        """The shape of a gadget's forms (``star``: the adders are :func:`star_full_adder` and
        :func:`star_half_adder`, one CX more each way)."""
        weights, negatives = [], []
        for f in forms:
            ws = [w for _, w in f]
            weights.append(tuple(sorted(Counter(map(abs, ws)).items())))
            neg = [w for w in ws if w < 0]
            negatives.append((len(neg), -sum(neg)))
        return cls(tuple(weights), tuple(negatives), matrix, linear, star)

    @cached_property
    def counts(self) -> tuple[tuple[int, int, int, tuple[bool, ...]], ...]:
        """:func:`column_counts` per form."""
        return tuple(column_counts(dict(ws)) for ws in self.weights)

    @property
    def presents(self) -> tuple[tuple[bool, ...], ...]:
        """Per form, which register columns hold a bit."""
        return tuple(c[3] for c in self.counts)

    @property
    def offsets(self) -> tuple[int, ...]:
        """Per form, ``G_a = H_a - offsets[a]`` (the complemented negative-weight bits)."""
        return tuple(s for _, s in self.negatives)

    @property
    def _phase(self) -> IsingPhase:  # not kept on the shape: shapes are kind keys, kept by the cost cache
        return _abstract_phase("gamma", self.presents, self.offsets, self.matrix, self.linear)[1]

    @cached_property
    def _phase_cost(self) -> Cost:
        return self._phase.cost()

    @cached_property
    def active(self) -> tuple[bool, ...]:
        """Forms whose register bits some phase term touches; the others are not computed at all (their bits
        carry no phase, so computing them would only be undone again)."""
        ph = self._phase
        touched = {q for q, _ in ph.linear} | {q for a, b, _ in ph.couplings for q in (a, b)}
        return tuple(any((a, k) in touched for k in range(len(c[3]))) for a, c in enumerate(self.counts))

    def adders(self) -> tuple[int, int, int]:
        """``(full adders, half adders, copies)`` over the computed forms."""
        act = [c for c, on in zip(self.counts, self.active) if on]
        return (sum(c[0] for c in act), sum(c[1] for c in act), sum(c[2] for c in act))

    @property
    def num_ancillas(self) -> int:
        """Clean ancillas needed: one per adder carry and per copy."""
        return sum(self.adders())

    def _compute_cost(self) -> tuple[int, int, int, int]:
        fa, ha, cp = self.adders()
        neg = sum(n for (n, _), on in zip(self.negatives, self.active) if on)
        return fa, ha, cp, neg

    @cached_property
    def _costs(self) -> tuple[Cost, Cost]:
        fa, ha, cp, neg = self._compute_cost()
        ands = fa + ha
        arithmetic = Cost.of(cx=2 * (5 * fa + ha + cp + (fa + ha if self.star else 0)), x=2 * neg)
        return with_ands(ands, arithmetic + self._phase_cost)

    def cost(self) -> Cost:
        """Lowered cost."""
        return self._costs[0]

    def logical_cost(self) -> Cost:
        """The same with ANDs kept whole."""
        return self._costs[1]

    def halves(self) -> tuple[tuple[Cost, Cost], ...]:
        """Per computed form, the lowered cost of computing its sum and of uncomputing it. The forms' trees act on
        disjoint qubits (each form its own bits and fresh ancillas), so they run side by side: the gadget's depth
        is at most the largest compute half's gate count, plus :meth:`phase_cost`'s, plus the largest uncompute
        half's. ``sum(halves) + phase_cost() == cost()``.
        """
        out = []
        for (fa, ha, cp, _), (neg, _), on in zip(self.counts, self.negatives, self.active):
            if on:
                arithmetic = Cost.of(cx=5 * fa + ha + cp + (fa + ha if self.star else 0), x=neg)
                out.append(((fa + ha) * AND_COST + arithmetic, (fa + ha) * AND_DG_COST + arithmetic))
        return tuple(out)

    def phase_cost(self) -> Cost:
        """Lowered cost of the phase on the registers (between the two halves)."""
        return self._phase_cost


class SumsKind(NamedTuple):
    """Kind key of :class:`SumsPhase` (and of the plan's deferred balance arithmetic): the cost depends on the
    shape only.

    Attributes:
        gadget: ``"sums"``.
        shape: the :class:`SumsShape`.
    """

    gadget: str
    shape: SumsShape


@dataclass(frozen=True)
class SumsPhase:
    """Compute integer sums into registers, phase a quadratic function of them, uncompute.

    Attributes:
        gamma: Symbol name of the layer's angle.
        forms: Per form, ``(qubit, integer weight)`` pairs (nonzero weights; each qubit in one form only).
        matrix: ``M`` (rows; symmetric).
        linear: ``m`` (one per form).
        ancillas: Clean ancillas, at least :attr:`num_ancillas` of them.
        sites: ``(qubit, y, x)``: where each form qubit sits on the problem grid's doubled lattice. Given, the
            adder trees pair bits by place with star-shaped adders (:func:`spatial_popcount_layout`: one CX more
            per adder each way, a kind of its own); empty (default), in the forms' order (:func:`popcount_layout`).
        sinks: With :attr:`sites`, per form the point its partial sums drift towards (``None`` or empty: none;
            :func:`spatial_popcount_layout`). Which qubit keeps which sum only: the cost and the kind are the same.
    """

    gamma: str
    forms: tuple[tuple[tuple[int, int], ...], ...]
    matrix: tuple[tuple[float, ...], ...]
    linear: tuple[float, ...]
    ancillas: tuple[int, ...] = ()
    sites: tuple[tuple[int, int, int], ...] = ()
    sinks: tuple[Sink | None, ...] = ()

    @property
    def kind(self) -> SumsKind:
        return SumsKind("sums", self.shape)  # the cost depends on the shape only (qubits and term order aside)

    @cached_property
    def shape(self) -> SumsShape:
        """What the cost depends on (:class:`SumsShape`)."""
        return SumsShape.of(self.forms, self.matrix, self.linear, star=bool(self.sites))

    @property
    def _active(self) -> tuple[bool, ...]:
        return self.shape.active

    def adders(self) -> tuple[int, int, int]:
        """``(full adders, half adders, copies)`` over the computed forms."""
        return self.shape.adders()

    @property
    def num_ancillas(self) -> int:
        """Clean ancillas needed: one per adder carry and per copy."""
        return self.shape.num_ancillas

    def needs(self) -> tuple[int, int]:
        """``(num_ancillas, 0)``: clean ancillas, no work ancillas."""
        return self.num_ancillas, 0

    def phase(self, registers: list[list[int | None]] | None = None) -> tuple[float, IsingPhase]:
        """``(c0, the RZ/RZZ gadget)`` of ``g`` on the register bits (abstract labels when not given)."""
        sh = self.shape
        if registers is None:
            return _abstract_phase(self.gamma, sh.presents, sh.offsets, self.matrix, self.linear)
        return _register_phase(self.gamma, registers, list(sh.offsets), self.matrix, self.linear)

    @property
    def constant(self) -> float:
        """``c0``: the gadget applies ``exp(-i gamma (g - c0))``."""
        return self.phase()[0]

    def cost(self) -> Cost:
        return self.shape.cost()

    def logical_cost(self) -> Cost:
        return self.shape.logical_cost()

    def _layout(self) -> tuple[list[Gate], list[list[int | None]]]:
        """The compute gates and each form's register (qubit per column, ``None`` for an empty column)."""
        gates, registers, _ = self._placed_layout()
        return gates, registers

    def ancilla_sites(self) -> dict[int, Site]:
        """Where each ancilla the adder trees use sits (the site of the bits it adds up); empty without
        :attr:`sites`."""
        return dict(self._placed_layout()[2]) if self.sites else {}

    def _placed_layout(self) -> tuple[list[Gate], list[list[int | None]], dict[int, Site]]:
        """The layout; with :attr:`sites` built once (:func:`~qcpp.plan.phase_layout.spatial_phase` asks for
        the ancilla sites, then the circuit for the gates: the place-aware adders are the plan's costliest part
        to lay out). Callers only read it."""
        return self._kept_layout if self.sites else self._build_layout()

    @cached_property
    def _kept_layout(self) -> tuple[list[Gate], list[list[int | None]], dict[int, Site]]:
        return self._build_layout()

    def _build_layout(self) -> tuple[list[Gate], list[list[int | None]], dict[int, Site]]:
        anc = iter(self.ancillas)
        where = {q: (y, x_) for q, y, x_ in self.sites}
        home: dict[int, Site] = {}
        gates: list[Gate] = []
        registers: list[list[int | None]] = []
        seen: set[int] = set()
        sinks = self.sinks or (None,) * len(self.forms)
        for form, on, sink in zip(self.forms, self._active, sinks, strict=True):
            for q, _ in form:
                if q in seen:
                    raise ValueError(f"qubit {q} appears in two terms")
                seen.add(q)
            if not on:
                registers.append([])
                continue
            if where:
                g, reg, placed = spatial_popcount_layout(form, anc, where, sink)
                home.update(placed)
            else:
                g, reg = popcount_layout(form, anc)
            gates += g
            registers.append(reg)
        return gates, registers, home

    def emit(self) -> list[Gate]:
        compute, registers = self._layout()
        _, ph = self.phase(registers)
        return [*compute, *ph.emit(), *(g.inverse() for g in reversed(compute))]


@dataclass(frozen=True)
class SumsRegister:
    """Copy one form's sum into a clean register, leaving nothing else behind (Bennett's compute-copy-uncompute).

    ``register[j]`` receives (XOR) column ``k`` of the sum for the ``j``-th nonempty column ``k``; the tree's
    ancillas are back at |0> when the gadget ends, so several forms' registers can be held at once while only
    one tree's ancillas exist. The gadget is its own inverse: applied again it clears the register. Cost
    ``CX = 16 F + 8 A + 2 P + B`` with ``F + A`` ANDs and their mirrors (``B`` copied bits).

    Attributes:
        form: ``(qubit, integer weight)`` pairs.
        register: One clean qubit per nonempty column (:func:`column_counts`).
        ancillas: Clean ancillas for the tree (``F + A + P``).
    """

    form: tuple[tuple[int, int], ...]
    register: tuple[int, ...]
    ancillas: tuple[int, ...] = ()

    @property
    def kind(self) -> Hashable:
        return ("sums-register", tuple(w for _, w in self.form))

    @cached_property
    def _count(self) -> tuple[int, int, int, tuple[bool, ...]]:
        return column_counts([abs(w) for _, w in self.form])

    @property
    def num_ancillas(self) -> int:
        """Tree ancillas (the register is separate)."""
        return sum(self._count[:3])

    def needs(self) -> tuple[int, int]:
        """``(num_ancillas, 0)``: clean ancillas, no work ancillas."""
        return self.num_ancillas, 0

    @property
    def width(self) -> int:
        """Register qubits needed."""
        return sum(self._count[3])

    def _costs(self) -> tuple[int, Cost]:
        fa, ha, cp, present = self._count
        neg = sum(1 for _, w in self.form if w < 0)
        return fa + ha, Cost.of(cx=2 * (5 * fa + ha + cp) + sum(present), x=2 * neg)

    def cost(self) -> Cost:
        return with_ands(*self._costs())[0]

    def logical_cost(self) -> Cost:
        return with_ands(*self._costs())[1]

    def emit(self) -> list[Gate]:
        compute, reg = popcount_layout(self.form, iter(self.ancillas))
        bits = [q for q in reg if q is not None]
        if len(bits) != len(self.register):
            raise ValueError(f"the register needs {len(bits)} qubits, got {len(self.register)}")
        copy = [cx(q, r) for q, r in zip(bits, self.register)]
        return [*compute, *copy, *(g.inverse() for g in reversed(compute))]


def _adder_gates(acc: tuple[int, ...], chunk: list[int | None], carries: tuple[int, ...]) -> list[Gate]:
    """``acc += chunk`` (little-endian bit lists; ``None``: a zero bit), carries in clean ancillas, no overflow.

    Ripple carry with one AND per carry (``c' = (a xor c)(x xor c) xor c``) and the mirror that writes the sum
    bit while it returns each carry to |0> (the uncompute needs no Toffoli on data).
    """
    b = len(acc)
    xs = [chunk[i] if i < len(chunk) else None for i in range(b)]
    present = [i for i, q in enumerate(xs) if q is not None]
    if not present:
        return []
    low = present[0]
    c = {i: carries[i - low - 1] for i in range(low + 1, b)}
    out: list[Gate] = []
    for i in range(low, b - 1):
        xq = xs[i]
        if i == low:
            assert xq is not None
            out.append(and_(acc[i], xq, c[i + 1]))
        elif xq is not None:
            out += [cx(c[i], acc[i]), cx(c[i], xq), and_(acc[i], xq, c[i + 1]), cx(c[i], c[i + 1])]
        else:
            out.append(and_(acc[i], c[i], c[i + 1]))
    top = b - 1
    if xs[top] is not None:
        out.append(cx(xs[top], acc[top]))  # type: ignore[arg-type]
    if top > low:
        out.append(cx(c[top], acc[top]))
    for i in range(b - 2, low - 1, -1):
        xq = xs[i]
        if i == low:
            assert xq is not None
            out += [and_(acc[i], xq, c[i + 1]).inverse(), cx(xq, acc[i])]
        elif xq is not None:
            out += [cx(c[i], c[i + 1]), and_(acc[i], xq, c[i + 1]).inverse(), cx(c[i], xq), cx(xq, acc[i])]
        else:
            out += [and_(acc[i], c[i], c[i + 1]).inverse(), cx(c[i], acc[i])]
    return out


def _adder_counts(width: int, chunk_present: tuple[bool, ...]) -> tuple[int, int]:
    """``(ANDs, CX)`` of :func:`_adder_gates` (each AND has its mirror too)."""
    xs = [i < len(chunk_present) and chunk_present[i] for i in range(width)]
    present = [i for i, p in enumerate(xs) if p]
    if not present:
        return 0, 0
    low = present[0]
    ands = cxs = 0
    for i in range(low, width - 1):
        ands += 1
        if i != low:
            cxs += 3 if xs[i] else 0
    cxs += (1 if xs[width - 1] else 0) + (1 if width - 1 > low else 0)
    for i in range(width - 2, low - 1, -1):
        cxs += 1 if i == low else (3 if xs[i] else 1)
    return ands, cxs


@dataclass(frozen=True)
class SumsAccumulate:
    """Add one chunk's sum into an accumulator register (or subtract it): the low-ancilla balance arithmetic.

    The chunk's popcount tree (:func:`popcount_layout`) runs, a ripple-carry adder adds its bits into the
    accumulator (``B`` bits, carries in ``B - 1`` clean ancillas), and the tree is undone: only the
    accumulator changes. With ``subtract`` the adder runs backwards. A form of ``n`` bits cut into chunks of
    ``c`` needs ``c``-ish tree ancillas and ``B - 1`` carries instead of ``n``; it costs about ``16 c + 12 B``
    CX per chunk against ``8 c`` for the tree alone (twice that over the add and the subtract).

    Attributes:
        chunk: ``(qubit, integer weight)`` pairs.
        accumulator: The register, little-endian (its sum must stay below ``2^B``).
        ancillas: Clean ancillas: the tree's, then ``B - 1`` carries.
        subtract: Subtract instead of add.
    """

    chunk: tuple[tuple[int, int], ...]
    accumulator: tuple[int, ...]
    ancillas: tuple[int, ...] = ()
    subtract: bool = False

    @property
    def kind(self) -> Hashable:
        return ("sums-accumulate", tuple(w for _, w in self.chunk), len(self.accumulator), self.subtract)

    @cached_property
    def _count(self) -> tuple[int, int, int, tuple[bool, ...]]:
        return column_counts([abs(w) for _, w in self.chunk])

    @property
    def num_ancillas(self) -> int:
        """Tree ancillas plus carries."""
        return sum(self._count[:3]) + max(len(self.accumulator) - 1, 0)

    def needs(self) -> tuple[int, int]:
        """``(num_ancillas, 0)``: clean ancillas, no work ancillas."""
        return self.num_ancillas, 0

    def _costs(self) -> tuple[int, Cost]:
        fa, ha, cp, present = self._count
        neg = sum(1 for _, w in self.chunk if w < 0)
        add_ands, add_cx = _adder_counts(len(self.accumulator), present)
        return fa + ha + add_ands, Cost.of(cx=2 * (5 * fa + ha + cp) + add_cx, x=2 * neg)

    def cost(self) -> Cost:
        return with_ands(*self._costs())[0]

    def logical_cost(self) -> Cost:
        return with_ands(*self._costs())[1]

    def emit(self) -> list[Gate]:
        tree = sum(self._count[:3])
        compute, reg = popcount_layout(self.chunk, iter(self.ancillas[:tree]))
        carries = self.ancillas[tree : tree + max(len(self.accumulator) - 1, 0)]
        add = _adder_gates(self.accumulator, reg, carries)
        if self.subtract:
            add = [g.inverse() for g in reversed(add)]
        return [*compute, *add, *(g.inverse() for g in reversed(compute))]
