"""The mixer's cost without building its partial mixers: counts of local *signatures*, one gadget per signature.

A partial mixer's logic program (:func:`gridcover.sbf.sbf_logic`) depends only on the plaquette's local
picture: whether each corner is an endpoint of the robot, how many variable outer edges each corner has, whether
start and goal are the plaquette's diagonal, and whether every plaquette edge is a variable. Equal pictures give
equal programs up to the edges' names, hence equal gadget kinds and costs
(:func:`circuitgen.gadgets.partial_mixer.partial_mixer`). On a grid without obstacles the picture of a plaquette
that touches neither endpoint of a robot depends only on whether its rows and columns lie on the boundary
(corner degree 2, 3 or 4: outer edges = degree - 2), so one robot's mixer is

    base counts of the grid (at most 9 classes, counted arithmetically)
    - the classes of the <= 8 plaquettes around its start and goal + their own pictures,

and the whole mixer is a sum over robots of ``O(1)`` corrections: ``O(robots)`` work per scenario, whatever the
grid size.

Consecutive partial mixers are fused at their boundary (:mod:`circuitgen.gadgets.junction`), so the layer costs
the partial mixers minus one *junction saving* per ordered pair of consecutive partial mixers. A pair's saving
depends on the two pictures and on where the second plaquette lies relative to the first (its offset
``(di, dj)``; plaquettes more than two rows or columns apart, or of different robots, share only the temporaries:
``far``), so the pairs are counted the same way: the horizontal neighbours ``(i, j) -> (i, j + 1)`` and the row
wraps ``(i, cols - 2) -> (i + 1, 0)`` of the plain grid by classes of rows and columns, minus the pairs next to
a robot's endpoints plus their own, plus one pair between consecutive robots.

Each distinct picture's cost is asked once (from a real gadget of that picture) and cached for every
later scenario. ``tests/estimators/mixer_count_test.py`` checks :func:`mixer_layer` against
:meth:`circuitgen.qaoa.QaoaPlan.cost_by_section` on every grid up to 8x8 with 1..8 robots, both rules and
targets; scenarios with obstacles use the plan itself (:func:`estimators.estimate.layer_costs`).

Example:
    >>> from gridcover.presets import default_scenario
    >>> from circuitgen.qaoa import qaoa_plan
    >>> s = default_scenario(6, 5, 3)
    >>> mixer_layer(s).cost == qaoa_plan(s, 1).cost_by_section()["mixer"]
    True
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable
from dataclasses import dataclass
from functools import lru_cache

from circuitgen.angles import Angle
from circuitgen.cost import Cost
from circuitgen.gadgets.junction import MixerJunction
from circuitgen.gadgets.partial_mixer import mixer_work_need, partial_mixer
from gridcover.scenario import Scenario

__all__ = ["MixerLayer", "mixer_layer"]

_BETA = Angle.symbol("beta_0")  # symbolic, as in the circuit: a numeric 0 would let the lowering drop rotations
Node = tuple[int, int]
Signature = tuple[Hashable, ...]


@dataclass(frozen=True)
class MixerLayer:
    """One layer's mixer.

    Attributes:
        cost: lowered cost.
        logical: logical cost (ANDs and Toffolis whole).
        logic_width: ``logic`` ancillas the largest partial mixer needs.
        work_need: ``work`` ancillas its largest multi-controlled X needs.
        kinds: ``(robot, (i, j), count)`` per signature: a representative partial mixer (robot and plaquette
            ``(i, j)``) and how many partial mixers of the layer share its signature.
        signatures: the signature of each entry of ``kinds`` (a key for per-kind figures such as depth).
    """

    cost: Cost
    logical: Cost
    logic_width: int
    work_need: int
    kinds: tuple[tuple[int, tuple[int, int], int], ...] = ()
    signatures: tuple[Signature, ...] = ()

    def gadgets(self, scenario: Scenario, rule: str = "exact", target: str = "nisq") -> list[tuple[object, int]]:
        """``(representative gadget, count)`` per signature (for per-kind figures such as depth)."""
        out = []
        for robot, (i, j), n in self.kinds:
            plaq = scenario.grid.plaquettes[i * (scenario.grid.cols - 1) + j]
            g = partial_mixer(scenario, robot, plaq, _BETA, scenario.num_variables, rule, target)  # type: ignore[arg-type]
            if g is not None:
                out.append((g, n))
        return out


def _corners(i: int, j: int) -> tuple[Node, Node, Node, Node]:
    return (i, j), (i, j + 1), (i + 1, j + 1), (i + 1, j)


def _outer(node: Node, rows: int, cols: int) -> int:
    r, c = node
    return 2 - (r == 0) - (r == rows - 1) - (c == 0) - (c == cols - 1)


@lru_cache(maxsize=1 << 16)  # a sweep asks about the same few pictures again and again
def _signature(i: int, j: int, rows: int, cols: int, start: Node | None, goal: Node | None) -> Signature:
    corners = _corners(i, j)
    ends = (start, goal)
    diagonal = {start, goal} in ({corners[0], corners[2]}, {corners[1], corners[3]})
    return (
        tuple(c in ends for c in corners),
        tuple(_outer(c, rows, cols) for c in corners),
        diagonal,
    )


def _axis_classes(n: int) -> list[tuple[int, int]]:
    """``(representative index, count)`` of plaquette rows (or columns) by which of their two node rows lie
    on the boundary: both (``n == 2``), the first, the last, neither."""
    if n == 2:
        return [(0, 1)]
    out = [(0, 1), (n - 2, 1)]
    if n > 3:
        out.append((1, n - 3))
    return out


def _touching(node: Node, rows: int, cols: int) -> list[tuple[int, int]]:
    r, c = node
    return [(i, j) for i in (r - 1, r) for j in (c - 1, c) if 0 <= i < rows - 1 and 0 <= j < cols - 1]


@lru_cache(maxsize=4096)
def _kind_cost(sig: Signature, rule: str, target: str, scenario: Scenario, robot: int, pindex: int) -> tuple:
    """Cost, logical cost, temporaries and work need of the partial mixer of ``sig`` (one representative)."""
    del sig  # the cache key; the representative realises it
    plaq = scenario.grid.plaquettes[pindex]
    g = partial_mixer(scenario, robot, plaq, _BETA, scenario.num_variables, rule, target)  # type: ignore[arg-type]
    if g is None:
        return Cost(), Cost(), 0, 0
    return g.cost(), g.logical_cost(), g.num_temps, mixer_work_need([g])


_KIND_CACHE: dict[tuple[Signature, str, str], tuple] = {}


def _kind(sig: Signature, rule: str, target: str, scenario: Scenario, robot: int, ij: tuple[int, int]) -> tuple:
    key = (sig, rule, target)
    hit = _KIND_CACHE.get(key)
    if hit is None:
        pindex = ij[0] * (scenario.grid.cols - 1) + ij[1]
        hit = _KIND_CACHE[key] = _kind_cost(sig, rule, target, scenario, robot, pindex)
    return hit


@lru_cache(maxsize=64)
def mixer_layer(scenario: Scenario, rule: str = "exact", target: str = "nisq") -> MixerLayer:
    """One layer's mixer cost by signature counting (see the module docstring; cached: the counts and the depth
    bound of a scenario both ask).

    Args:
        scenario: a scenario without obstacles.
        rule: SBF rule.
        target: ``nisq`` or ``ft``.

    Returns:
        The :class:`MixerLayer`.

    Raises:
        ValueError: the scenario has obstacles.
    """
    if scenario.obstacles:
        raise ValueError("signature counting needs a grid without obstacles")
    g = scenario.grid
    rows, cols = g.rows, g.cols
    base: Counter[Signature] = Counter()
    where: dict[Signature, tuple[int, int]] = {}
    for i, ni in _axis_classes(rows):
        for j, nj in _axis_classes(cols):
            sig = _signature(i, j, rows, cols, None, None)
            base[sig] += ni * nj
            where.setdefault(sig, (i, j))
    counts: Counter[Signature] = Counter()
    reps: dict[Signature, tuple[int, tuple[int, int]]] = {}
    for robot, rb in enumerate(scenario.robots):
        counts.update(base)
        touched = set(_touching(rb.start, rows, cols)) | set(_touching(rb.goal, rows, cols))
        for i, j in touched:
            plain = _signature(i, j, rows, cols, None, None)
            own = _signature(i, j, rows, cols, rb.start, rb.goal)
            counts[plain] -= 1
            counts[own] += 1
            reps.setdefault(own, (robot, (i, j)))
        for sig, ij in where.items():  # a plain representative this robot does not touch
            if sig not in reps and ij not in touched:
                reps[sig] = (robot, ij)
    cost: Counter[str] = Counter()
    logical: Counter[str] = Counter()
    if rule == "exact":  # only the parity-basis partial mixers are fused (see circuitgen.gadgets.junction)
        for key, n in _junction_counts(scenario, rule, target).items():
            if n:
                saving, logical_saving = _saving(key, rule, target, scenario)
                for name, k in saving.items:
                    cost[name] -= n * k
                for name, k in logical_saving.items:
                    logical[name] -= n * k
    width = work = 0
    kinds = []
    sigs = []
    for sig, n in counts.items():
        if n <= 0:
            continue
        if sig not in reps:  # every robot touches the class's first plaquette: find another of that class
            reps[sig] = _find(scenario, sig)
        robot, ij = reps[sig]
        c, lc, temps, need = _kind(sig, rule, target, scenario, robot, ij)
        for name, k in c.items:
            cost[name] += n * k
        for name, k in lc.items:
            logical[name] += n * k
        if c.total:
            width, work = max(width, temps), max(work, need)
            kinds.append((robot, ij, n))
            sigs.append(sig)
    return MixerLayer(Cost.of(cost), Cost.of(logical), width, work, tuple(kinds), tuple(sigs))


def _find(scenario: Scenario, sig: Signature) -> tuple[int, tuple[int, int]]:
    g = scenario.grid
    for robot, rb in enumerate(scenario.robots):
        for i in range(g.rows - 1):
            for j in range(g.cols - 1):
                if _signature(i, j, g.rows, g.cols, rb.start, rb.goal) == sig:
                    return robot, (i, j)
    raise AssertionError(f"no plaquette has the signature {sig}")  # pragma: no cover - counts come from these


# --- junctions between consecutive partial mixers ---------------------------------------------------------------
Pair = tuple[Signature, Signature, Hashable]
"""A junction class: the two pictures and the offset of the second plaquette (or ``far``)."""


def _relation(a: tuple[int, int], b: tuple[int, int]) -> Hashable:
    di, dj = b[0] - a[0], b[1] - a[1]
    return (di, dj) if abs(di) <= 2 and abs(dj) <= 2 else "far"


def _pair_classes(n: int) -> list[tuple[int, int]]:
    """``(representative index, count)`` of the ``n - 1`` consecutive index pairs ``(k, k + 1)`` of ``0..n-1``, by
    whether ``k`` is the first pair and whether it is the last (what the two pictures depend on)."""
    pairs = n - 1
    if pairs <= 0:
        return []
    out = [(0, 1)]
    if pairs > 1:
        out.append((pairs - 1, 1))
    if pairs > 2:
        out.append((1, pairs - 2))
    return out


def _plain_pair(a: tuple[int, int], b: tuple[int, int], rows: int, cols: int) -> Pair:
    return (
        _signature(*a, rows, cols, None, None),
        _signature(*b, rows, cols, None, None),
        _relation(a, b),
    )


def _junction_counts(scenario: Scenario, rule: str, target: str) -> Counter[tuple[Pair, tuple]]:
    """How many junctions of each class one layer has, with a realisation of each: ``((class, realisation),
    count)``, a realisation being ``(robot_a, (i, j)_a, robot_b, (i, j)_b)``."""
    g = scenario.grid
    rows, cols = g.rows, g.cols
    prow, pcol = rows - 1, cols - 1  # plaquettes per column and per row
    total = prow * pcol

    def at(k: int) -> tuple[int, int]:
        return divmod(k, pcol)

    # one robot's plain pairs: horizontal neighbours and row wraps, by classes
    base: Counter[Pair] = Counter()
    where: dict[Pair, tuple[tuple[int, int], tuple[int, int]]] = {}
    for i, ni in _axis_classes(rows):
        for j, nj in _pair_classes(pcol):
            key = _plain_pair((i, j), (i, j + 1), rows, cols)
            base[key] += ni * nj
            where.setdefault(key, ((i, j), (i, j + 1)))
    for i, ni in _pair_classes(prow):
        key = _plain_pair((i, pcol - 1), (i + 1, 0), rows, cols)
        base[key] += ni
        where.setdefault(key, ((i, pcol - 1), (i + 1, 0)))

    def present(robot: int, ij: tuple[int, int]) -> bool:
        rb = scenario.robots[robot]
        sig = _signature(*ij, rows, cols, rb.start, rb.goal)
        return bool(_kind(sig, rule, target, scenario, robot, ij)[0].total)

    counts: Counter[tuple[Pair, tuple]] = Counter()
    plain_counts: Counter[Pair] = Counter()
    used: dict[Pair, tuple] = {}  # a realisation of each plain class by an untouched pair
    ends: list[tuple[int, int] | None] = []  # per robot: first and last present plaquette index
    firsts: list[int | None] = []
    for robot, rb in enumerate(scenario.robots):
        plain_counts.update(base)
        touched = {i * pcol + j for node in (rb.start, rb.goal) for i, j in _touching(node, rows, cols)}
        affected = sorted({a for k in touched for a in (k - 1, k) if 0 <= a < total - 1})
        for a in affected:
            plain_counts[_plain_pair(at(a), at(a + 1), rows, cols)] -= 1
        # the actual pairs over each run of affected pairs (absent partial mixers skipped)
        run: list[int] = []
        for a in [*affected, None]:
            if a is not None and (not run or a == run[-1] + 1):
                run.append(a)
                continue
            if run:
                nodes = [k for k in range(run[0], run[-1] + 2) if k not in touched or present(robot, at(k))]
                for u, v in zip(nodes, nodes[1:], strict=False):
                    sa = _signature(*at(u), rows, cols, rb.start, rb.goal)
                    sb = _signature(*at(v), rows, cols, rb.start, rb.goal)
                    counts[((sa, sb, _relation(at(u), at(v))), (robot, at(u), robot, at(v)))] += 1
            run = [a] if a is not None else []
        for key, (pa, pb) in where.items():
            if key not in used and not {pa[0] * pcol + pa[1], pb[0] * pcol + pb[1]} & touched:
                used[key] = (robot, pa, robot, pb)
        first = next((k for k in range(total) if k not in touched or present(robot, at(k))), None)
        last = next((k for k in reversed(range(total)) if k not in touched or present(robot, at(k))), None)
        firsts.append(first)
        ends.append(None if first is None else (first, last))  # type: ignore[arg-type]
    for key, n in plain_counts.items():
        if n > 0:
            counts[(key, used.get(key) or _find_pair(scenario, key))] += n
    # one junction between consecutive robots (skipping robots with no partial mixer)
    prev: tuple[int, int] | None = None
    for robot, span in enumerate(ends):
        if span is None:
            continue
        if prev is not None:
            ra, ka = prev
            rba, rbb = scenario.robots[ra], scenario.robots[robot]
            sa = _signature(*at(ka), rows, cols, rba.start, rba.goal)
            sb = _signature(*at(span[0]), rows, cols, rbb.start, rbb.goal)
            counts[((sa, sb, "far"), (ra, at(ka), robot, at(span[0])))] += 1
        prev = (robot, span[1])
    return counts


def _find_pair(scenario: Scenario, key: Pair) -> tuple:
    """A realisation of a plain junction class by a pair neither of whose plaquettes touches its robot's
    endpoints (every robot touched the class's first pair)."""
    g = scenario.grid
    rows, cols, pcol = g.rows, g.cols, g.cols - 1
    for robot, rb in enumerate(scenario.robots):
        touched = {(i, j) for node in (rb.start, rb.goal) for i, j in _touching(node, rows, cols)}
        for k in range((rows - 1) * pcol - 1):
            a, b = divmod(k, pcol), divmod(k + 1, pcol)
            if a not in touched and b not in touched and _plain_pair(a, b, rows, cols) == key:
                return (robot, a, robot, b)
    raise AssertionError(f"no pair realises the junction class {key}")  # pragma: no cover


_SAVING_CACHE: dict[tuple, tuple[Cost, Cost]] = {}


def _saving(item: tuple[Pair, tuple], rule: str, target: str, scenario: Scenario) -> tuple[Cost, Cost]:
    """Saving and logical saving of a junction class (from its realisation, cached for every later scenario)."""
    key, (ra, a, rb, b) = item
    hit = _SAVING_CACHE.get((key, rule, target))
    if hit is None:
        g = scenario.grid
        n = scenario.num_variables

        def gadget(robot: int, ij: tuple[int, int]):  # type: ignore[no-untyped-def]
            plaq = g.plaquettes[ij[0] * (g.cols - 1) + ij[1]]
            return partial_mixer(scenario, robot, plaq, _BETA, n, rule, target)  # type: ignore[arg-type]

        j = MixerJunction(gadget(ra, a), gadget(rb, b))
        hit = _SAVING_CACHE[(key, rule, target)] = (j.saving(), j.logical_saving())
    return hit
