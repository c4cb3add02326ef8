"""The mixer's call graph without building its partial mixers: counts of local *signatures* on an open grid.

A partial mixer's logic program (:func:`gridcover.sbf.sbf_logic`) depends only on the plaquette's local
picture (:class:`gridcover.sbf.LocalPicture`): whether each corner is an endpoint of the robot, how many variable
outer edges each corner has, and whether start and goal are the plaquette's diagonal. Equal pictures give equal
programs up to the edges' names, hence equal gadget kinds (:func:`circuitgen.gadgets.partial_mixer.partial_mixer`).
On a grid without obstacles the picture of a plaquette that touches neither endpoint of a robot depends only on
whether its rows and columns lie on the boundary (corner degree 2, 3 or 4: outer edges = degree - 2), so one
robot's partial mixers are

    base counts of the grid (at most 9 classes, counted arithmetically)
    - the classes of the <= 8 plaquettes around its start and goal + their own pictures,

and the whole layer is a sum over robots of ``O(1)`` corrections: ``O(robots)`` work per scenario, whatever the
grid size.

The parity-basis partial mixers of a layer are cut at their rotations (:mod:`circuitgen.gadgets.junction`): the
layer is one rotation per partial mixer, one junction per ordered pair of consecutive partial mixers, and the
two open ends. A junction's kind depends on the two pictures and on where the second plaquette lies relative to
the first (its offset ``(di, dj)``; plaquettes more than two rows or columns apart, or of different robots, share
only the temporaries: ``far``), so the pairs are counted the same way: the horizontal neighbours
``(i, j) -> (i, j + 1)`` and the row wraps ``(i, cols - 2) -> (i + 1, 0)`` of the plain grid by classes of rows
and columns, minus the pairs next to a robot's endpoints plus their own, plus one pair between consecutive robots.

Each signature's partial mixer and each junction class's kind is built once (from a real plaquette) and kept
for every later scenario. :meth:`circuitgen.qaoa.QaoaPlan.call_graph` uses this on grids without obstacles;
``tests/circuitgen/call_graph_test.py`` checks it against the call graph of the emitted gadgets.

Example:
    >>> from gridcover.presets import default_scenario
    >>> s = default_scenario(6, 5, 3)
    >>> layer = mixer_part(s)
    >>> sum(n for _, n in layer.kinds) == 3 * 4 * 5 * 2 + 1   # rotations, junctions between them, two ends
    True
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from gridcover.sbf import LocalPicture
from gridcover.scenario import Scenario

from .angles import Angle
from .call_graph import SCENARIOS_KEPT, GadgetKind
from .gadgets.junction import MixerJunction, MixerRotation
from .gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer, partial_mixer

__all__ = ["MixerPart", "index_classes", "mixer_part"]

_BETA = Angle.symbol("beta_0")  # symbolic, as in the circuit: a numeric 0 would let the lowering drop rotations
Node = tuple[int, int]
Signature = LocalPicture
Count = Any  # an int, or a sympy expression in the closed forms (estimators.formulas)


@dataclass(frozen=True)
class MixerPart:
    """One layer's mixer as gadget kinds.

    Attributes:
        kinds: ``(kind, multiplicity)`` pairs (a kind may appear more than once: the call graph merges them).
        logic_width: ``logic`` ancillas the largest partial mixer needs.
        work_need: ``work`` ancillas its largest multi-controlled X needs.
    """

    kinds: tuple[tuple[GadgetKind, Count], ...]
    logic_width: int
    work_need: int


def _corners(i: int, j: int) -> tuple[Node, Node, Node, Node]:
    return (i, j), (i, j + 1), (i + 1, j + 1), (i + 1, j)


def _outer(node: Node, rows: int, cols: int) -> int:
    r, c = node
    return 2 - (r == 0) - (r == rows - 1) - (c == 0) - (c == cols - 1)


@lru_cache(maxsize=1 << 16)  # a sweep asks about the same few pictures again and again
def _signature(i: int, j: int, rows: int, cols: int, start: Node | None, goal: Node | None) -> Signature:
    """The :class:`~gridcover.sbf.LocalPicture` of plaquette ``(i, j)`` on an open grid."""
    corners = _corners(i, j)
    return LocalPicture.of(corners, start, goal, [_outer(c, rows, cols) for c in corners])


def index_classes(n: int, size: Count | None = None) -> list[tuple[int, Count]]:
    """``(representative, count)`` of the indices ``0 .. n-1`` by whether each is the first, the last or neither
    (all a local picture on an open grid reads of a position along a side: plaquette rows, nodes, consecutive
    pairs); the counts for ``size`` indices (default ``n``; a sympy expression in the closed forms of
    :mod:`estimators.formulas`).

    >>> index_classes(5), index_classes(2), index_classes(1)
    ([(0, 1), (4, 1), (1, 3)], [(0, 1), (1, 1)], [(0, 1)])
    """
    out: list[tuple[int, Count]] = [(0, 1)] if n > 0 else []
    if n > 1:
        out.append((n - 1, 1))
    if n > 2:
        out.append((1, (n if size is None else size) - 2))
    return out


def _touching(node: Node, rows: int, cols: int) -> list[tuple[int, int]]:
    r, c = node
    return [(i, j) for i in (r - 1, r) for j in (c - 1, c) if 0 <= i < rows - 1 and 0 <= j < cols - 1]


Mixer = ParityPartialMixer | McxPartialMixer
_REPRESENTATIVE: dict[tuple[Signature, str, str], Mixer | None] = {}
"""A partial mixer per signature, rule and target (``None``: no flip is ever allowed), for every later scenario."""


_KINDS: dict[Hashable, tuple[GadgetKind, GadgetKind, GadgetKind, GadgetKind]] = {}


def _kinds_of(m: Mixer) -> tuple[GadgetKind, GadgetKind, GadgetKind, GadgetKind]:
    """A representative's kinds: itself, its rotation, the layer's opening junction into it and the closing one
    out of it (kept per partial-mixer kind: a sweep meets the same few again and again)."""
    hit = _KINDS.get(m.kind)
    if hit is None:
        rotation = MixerRotation(m) if isinstance(m, ParityPartialMixer) else m
        opening = MixerJunction(None, m) if isinstance(m, ParityPartialMixer) else m
        closing = MixerJunction(m, None) if isinstance(m, ParityPartialMixer) else m
        hit = _KINDS[m.kind] = tuple(GadgetKind.of(g) for g in (m, rotation, opening, closing))  # type: ignore[assignment]
    return hit  # type: ignore[return-value]


def _representative(
    sig: Signature, rule: str, target: str, scenario: Scenario, robot: int, ij: tuple[int, int]
) -> Mixer | None:
    key = (sig, rule, target)
    if key not in _REPRESENTATIVE:
        plaq = scenario.grid.plaquettes[ij[0] * (scenario.grid.cols - 1) + ij[1]]
        _REPRESENTATIVE[key] = partial_mixer(scenario, robot, plaq, _BETA, scenario.num_variables, rule, target)  # type: ignore[arg-type]
    return _REPRESENTATIVE[key]


@lru_cache(maxsize=SCENARIOS_KEPT)
def mixer_part(
    scenario: Scenario,
    rule: str = "exact",
    target: str = "nisq",
    fuse: bool = True,
    sizes: tuple[Count, Count] | None = None,
) -> MixerPart:
    """One layer's mixer as gadget kinds by signature counting (see the module docstring).

    Args:
        scenario: a scenario without obstacles.
        rule: SBF rule.
        target: ``nisq`` or ``ft``.
        fuse: cut the parity-basis partial mixers at their rotations (junctions and rotations; the circuit's
            default), or list the partial mixers themselves.
        sizes: count the classes for a grid of ``sizes = (rows, cols)`` nodes (sympy expressions, for the
            closed forms of :mod:`estimators.formulas`) rather than the scenario's: the scenario then stands for
            every grid with the same endpoints near its corners (sides of at least 5 nodes where symbolic).

    Returns:
        The :class:`MixerPart`.

    Raises:
        ValueError: the scenario has obstacles.
    """
    if scenario.obstacles:
        raise ValueError("signature counting needs a grid without obstacles")
    g = scenario.grid
    rows, cols = g.rows, g.cols
    base: Counter[Signature] = Counter()
    where: dict[Signature, tuple[int, int]] = {}
    size_r, size_c = sizes if sizes is not None else (rows, cols)
    for i, ni in index_classes(rows - 1, size_r - 1):  # plaquette rows and columns
        for j, nj in index_classes(cols - 1, size_c - 1):
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
    fused = rule == "exact" and fuse  # only the parity-basis partial mixers are fused (circuitgen.gadgets.junction)
    kinds: list[tuple[GadgetKind, Count]] = []
    width = work = 0
    for sig, n in counts.items():
        if n == 0:  # (never negative: corrections remove members of a class)
            continue
        if sig not in reps:  # every robot touches the class's first plaquette: find another of that class
            reps[sig] = _find(scenario, sig)
        robot, ij = reps[sig]
        m = _representative(sig, rule, target, scenario, robot, ij)
        if m is None:
            continue
        kind, rotation, _, _ = _kinds_of(m)
        width, work = max(width, kind.temporaries), max(work, kind.work)
        kinds.append((rotation if fused else kind, n))
    if fused:
        kinds += _junction_kinds(scenario, rule, target, (size_r, size_c))
    return MixerPart(tuple(kinds), width, work)


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


def _plain_pair(a: tuple[int, int], b: tuple[int, int], rows: int, cols: int) -> Pair:
    return (
        _signature(*a, rows, cols, None, None),
        _signature(*b, rows, cols, None, None),
        _relation(a, b),
    )


def _junction_counts(
    scenario: Scenario, rule: str, target: str, sizes: tuple[Count, Count]
) -> tuple[Counter[tuple[Pair, tuple]], tuple[int, tuple[int, int]] | None, tuple[int, tuple[int, int]] | None]:
    """How many junctions of each class one layer has, with a realisation of each: ``((class, realisation),
    count)``, a realisation being ``(robot_a, (i, j)_a, robot_b, (i, j)_b)``; and the layer's first and last
    partial mixer ``(robot, (i, j))`` (``None`` if it has none)."""
    g = scenario.grid
    rows, cols = g.rows, g.cols
    prow, pcol = rows - 1, cols - 1  # plaquettes per column and per row
    total = prow * pcol

    def at(k: int) -> tuple[int, int]:
        return divmod(k, pcol)

    # one robot's plain pairs: horizontal neighbours and row wraps, by classes
    base: Counter[Pair] = Counter()
    where: dict[Pair, tuple[tuple[int, int], tuple[int, int]]] = {}
    for i, ni in index_classes(prow, sizes[0] - 1):
        for j, nj in index_classes(pcol - 1, sizes[1] - 2):
            key = _plain_pair((i, j), (i, j + 1), rows, cols)
            base[key] += ni * nj
            where.setdefault(key, ((i, j), (i, j + 1)))
    for i, ni in index_classes(prow - 1, sizes[0] - 2):
        key = _plain_pair((i, pcol - 1), (i + 1, 0), rows, cols)
        base[key] += ni
        where.setdefault(key, ((i, pcol - 1), (i + 1, 0)))

    def present(robot: int, ij: tuple[int, int]) -> bool:
        rb = scenario.robots[robot]
        sig = _signature(*ij, rows, cols, rb.start, rb.goal)
        return _representative(sig, rule, target, scenario, robot, ij) is not None

    counts: Counter[tuple[Pair, tuple]] = Counter()
    plain_counts: Counter[Pair] = Counter()
    used: dict[Pair, tuple] = {}  # a realisation of each plain class by an untouched pair
    ends: list[tuple[int, int] | None] = []  # per robot: first and last present plaquette index
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
        ends.append(None if first is None else (first, last))  # type: ignore[arg-type]
    for key, n in plain_counts.items():
        if n != 0:
            counts[(key, used.get(key) or _find_pair(scenario, key))] += n
    # one junction between consecutive robots (skipping robots with no partial mixer)
    prev: tuple[int, int] | None = None
    head: tuple[int, tuple[int, int]] | None = None
    for robot, span in enumerate(ends):
        if span is None:
            continue
        if prev is not None:
            ra, ka = prev
            rba, rbb = scenario.robots[ra], scenario.robots[robot]
            sa = _signature(*at(ka), rows, cols, rba.start, rba.goal)
            sb = _signature(*at(span[0]), rows, cols, rbb.start, rbb.goal)
            counts[((sa, sb, "far"), (ra, at(ka), robot, at(span[0])))] += 1
        else:
            head = (robot, at(span[0]))
        prev = (robot, span[1])
    return counts, head, None if prev is None else (prev[0], at(prev[1]))


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


_JUNCTION: dict[tuple[Pair, str, str], GadgetKind] = {}
"""The kind of each junction class, rule and target (from its first realisation), for every later scenario."""


def _junction_kinds(
    scenario: Scenario, rule: str, target: str, sizes: tuple[Count, Count]
) -> list[tuple[GadgetKind, Count]]:
    """The junctions of one layer as kinds: one per ordered pair of consecutive partial mixers, and the two open
    ends (the first compute, the last uncompute)."""
    g = scenario.grid
    counts, head, tail = _junction_counts(scenario, rule, target, sizes)

    def mixer(robot: int, ij: tuple[int, int]) -> Mixer | None:
        rb = scenario.robots[robot]
        return _representative(_signature(*ij, g.rows, g.cols, rb.start, rb.goal), rule, target, scenario, robot, ij)

    def placed(robot: int, ij: tuple[int, int]) -> Mixer | None:  # on this scenario's qubits: the overlap counts
        plaq = g.plaquettes[ij[0] * (g.cols - 1) + ij[1]]
        return partial_mixer(scenario, robot, plaq, _BETA, scenario.num_variables, rule, target)  # type: ignore[arg-type]

    out = []
    for (key, (ra, a, rb, b)), n in counts.items():
        kind = _JUNCTION.get((key, rule, target))
        if kind is None:
            kind = _JUNCTION[(key, rule, target)] = GadgetKind.of(MixerJunction(placed(ra, a), placed(rb, b)))  # type: ignore[arg-type]
        out.append((kind, n))
    if head is not None and tail is not None:
        out.append((_kinds_of(mixer(*head))[2], 1))  # type: ignore[arg-type]
        out.append((_kinds_of(mixer(*tail))[3], 1))  # type: ignore[arg-type]
    return out
