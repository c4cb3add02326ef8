"""The mixer's call graph without building its partial mixers: counts of local pictures on an open grid.

A partial mixer's kind depends only on its plaquette's local picture (:class:`qcpp.problem.sbf.LocalPicture`). On a
grid without obstacles the picture of a plaquette that touches no endpoint of its robot depends only on whether its
row and column are the first, the last or neither, so one robot's partial mixers are the plain grid's classes
(:func:`class_counts`) with the <= 8 plaquettes around its start and goal moved to their own pictures:
``O(robots)`` work per scenario, whatever the grid size. The junctions between consecutive partial mixers
(:mod:`qcpp.gadgets.junction`) are counted the same way: a junction's kind depends on the two pictures and
on the second plaquette's offset (``far`` beyond two rows or columns, or across robots). Each picture's partial
mixer and each junction class's kind is built once, on a real plaquette, and kept for every later scenario in
named tables of the process cache :data:`qcpp.gadgets.pricing.COSTS` (``COSTS.clear()`` forgets them).

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> layer = mixer_part(default_scenario(6, 5, 3))
    >>> sum(n for _, n in layer.kinds) == 3 * 4 * 5 * 2 + 1   # rotations, junctions between them, two ends
    True
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from functools import lru_cache
from itertools import groupby, pairwise
from typing import Any

from qcpp.gadgets.junction import MixerJunction, MixerRotation
from qcpp.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer, partial_mixer
from qcpp.gadgets.pricing import COSTS
from qcpp.ir.angles import Angle
from qcpp.plan.call_graph import SCENARIOS_KEPT, GadgetKind
from qcpp.problem.sbf import LocalPicture
from qcpp.problem.scenario import Robot, Scenario

__all__ = ["MixerPart", "boundary", "class_counts", "index_classes", "mixer_part"]

_BETA = Angle.symbol("beta_0")  # symbolic, as in the circuit: a numeric 0 would let the lowering drop rotations
Count = Any  # an int, or a sympy expression in the closed forms (qcpp.estimators.formulas)
Mixer = ParityPartialMixer | McxPartialMixer


@dataclass(frozen=True)
class MixerPart:
    """One layer's mixer as gadget kinds.

    Attributes:
        kinds: ``(kind, multiplicity)`` pairs (a kind may appear more than once: the call graph merges them).
    """

    kinds: tuple[tuple[GadgetKind, Count], ...]

    @property
    def logic_width(self) -> int:
        """``logic`` ancillas the largest partial mixer needs."""
        return max((k.temporaries for k, _ in self.kinds), default=0)

    @property
    def work_need(self) -> int:
        """``work`` ancillas its largest multi-controlled X needs."""
        return max((k.work for k, _ in self.kinds), default=0)


def index_classes(n: int, size: Count | None = None) -> list[tuple[int, Count]]:
    """``(representative, count)`` of the indices ``0 .. n-1`` by whether each is the first, the last or neither
    (all a local picture on an open grid reads of a position along a side), counted for ``size`` indices
    (default ``n``; a sympy expression in the closed forms of :mod:`qcpp.estimators.formulas`).

    >>> index_classes(5), index_classes(2), index_classes(1)
    ([(0, 1), (4, 1), (1, 3)], [(0, 1), (1, 1)], [(0, 1)])
    """
    out: list[tuple[int, Count]] = [(0, 1)] if n > 0 else []
    if n > 1:
        out.append((n - 1, 1))
    if n > 2:
        out.append((1, (n if size is None else size) - 2))
    return out


def class_counts(
    dims: tuple[int, int], sizes: tuple[Count, Count], key: Callable[[int, int], Hashable]
) -> Counter[Hashable]:
    """The one class-signature mechanism: how many positions ``(i, j)`` of a ``dims`` array have each class
    ``key(i, j)`` (a key that reads only whether ``i`` and ``j`` are first, last or neither), counted for an array
    of ``sizes``.

    >>> class_counts((3, 4), (3, 4), lambda i, j: (i == 0, j == 0))[(False, False)]
    6
    """
    counts: Counter[Hashable] = Counter()
    for i, ni in index_classes(dims[0], sizes[0]):
        for j, nj in index_classes(dims[1], sizes[1]):
            counts[key(i, j)] += ni * nj
    return counts


def boundary(r: int, c: int, rows: int, cols: int) -> int:
    """How many sides of the grid node ``(r, c)`` lies on: its degree on an open grid is ``4 - boundary``."""
    return (r == 0) + (r == rows - 1) + (c == 0) + (c == cols - 1)


@lru_cache(maxsize=1 << 16)  # a sweep asks about the same few pictures again and again
def _signature(k: int, rows: int, cols: int, robot: Robot | None) -> LocalPicture:
    """The local picture of plaquette ``k`` (row-major) on an open grid (``robot``: whose endpoints it shows).
    Pure memo: ``_signature.cache_clear()`` empties it."""
    i, j = divmod(k, cols - 1)
    corners = (i, j), (i, j + 1), (i + 1, j + 1), (i + 1, j)
    ends = (None, None) if robot is None else (robot.start, robot.goal)
    return LocalPicture.of(corners, *ends, [2 - boundary(*c, rows, cols) for c in corners])


def _touched(robot: Robot, rows: int, cols: int) -> set[int]:
    """The plaquettes (row-major) with a corner at the robot's start or goal."""
    return {i * (cols - 1) + j for r, c in (robot.start, robot.goal) for i in (r - 1, r) for j in (c - 1, c)
            if 0 <= i < rows - 1 and 0 <= j < cols - 1}  # fmt: skip


# Names of the per-kind tables of the process cache COSTS (qcpp.gadgets.pricing; COSTS.clear() forgets them):
_REPRESENTATIVE = "mixer representative"  # (picture, rule, target) -> partial mixer (None: no flip ever allowed)
_KINDS = "mixer kinds"  # partial-mixer kind -> (kind, rotation, opening junction, closing junction)
_JUNCTION = "mixer junction"  # (junction class, rule, target) -> kind, from the class's first realisation


def _kinds_of(m: Mixer) -> tuple[GadgetKind, GadgetKind, GadgetKind, GadgetKind]:
    """A representative's kinds: itself, its rotation, the layer's opening junction into it and the closing one
    out of it (kept per partial-mixer kind)."""
    kinds = COSTS.table(_KINDS).get(m.kind)
    if kinds is None:
        parity = isinstance(m, ParityPartialMixer)
        pieces = (m, MixerRotation(m), MixerJunction(None, m), MixerJunction(m, None)) if parity else (m,) * 4
        kinds = tuple(GadgetKind.of(g) for g in pieces)
        COSTS.remember(_KINDS, m.kind, kinds)
    return kinds  # type: ignore[no-any-return]


def _placed(scenario: Scenario, robot: int, k: int, rule: str, target: str) -> Mixer | None:
    """The partial mixer of ``robot`` on plaquette ``k`` of this scenario (on its qubits)."""
    return partial_mixer(scenario, robot, scenario.grid.plaquettes[k], _BETA, scenario.num_variables, rule, target)  # type: ignore[arg-type]


def _mixer(
    scenario: Scenario, sig: Hashable, rule: str, target: str, where: tuple[int, int] | None,
    plain: Callable[[int], Hashable] | None = None,
) -> Mixer | None:
    """The partial mixer of the picture ``sig`` (``None``: no flip is ever allowed), built the first time on
    ``where = (robot, plaquette)`` of this scenario (``None``: a plaquette whose plain picture it is) and kept for
    every later scenario."""
    known = COSTS.table(_REPRESENTATIVE)
    if (sig, rule, target) not in known:
        robot, k = where or _realise(scenario, sig, plain, 1)  # type: ignore[arg-type]
        COSTS.remember(_REPRESENTATIVE, (sig, rule, target), _placed(scenario, robot, k, rule, target))
    return known[sig, rule, target]  # type: ignore[no-any-return]


def _realise(scenario: Scenario, key: Hashable, plain: Callable[[int], Hashable], span: int) -> tuple[int, int]:
    """A robot and a plaquette index ``k`` whose plain class ``plain(k)`` is ``key`` and whose ``span`` plaquettes
    from ``k`` on (1: a plaquette, 2: a junction's pair) touch none of the robot's endpoints."""
    g = scenario.grid
    for robot, rb in enumerate(scenario.robots):
        touched = _touched(rb, g.rows, g.cols)
        for k in range((g.rows - 1) * (g.cols - 1) - span + 1):
            if touched.isdisjoint(range(k, k + span)) and plain(k) == key:
                return robot, k
    raise AssertionError(f"no plaquette realises the class {key}")  # pragma: no cover - counts come from these


@lru_cache(maxsize=SCENARIOS_KEPT)
def mixer_part(
    scenario: Scenario,
    rule: str = "exact",
    target: str = "nisq",
    fuse: bool = True,
    sizes: tuple[Count, Count] | None = None,
) -> MixerPart:
    """One layer's mixer as gadget kinds by counting local pictures (see the module docstring).

    Args:
        scenario: a scenario without obstacles.
        target: ``nisq`` or ``ft``.
        fuse: list rotations and junctions (the circuit's default), or the partial mixers themselves.
        sizes: count the classes for a grid of ``sizes = (rows, cols)`` nodes (sympy expressions, for the
            closed forms of :mod:`qcpp.estimators.formulas`): the scenario then stands for every grid with the same
            endpoints near its corners (sides of at least 5 nodes where symbolic).

    Raises:
        ValueError: the scenario has obstacles.

    Pure memo: ``mixer_part.cache_clear()`` empties it."""
    if scenario.obstacles:
        raise ValueError("signature counting needs a grid without obstacles")
    rows, cols = scenario.grid.rows, scenario.grid.cols
    sizes = sizes if sizes is not None else (rows, cols)

    def plain(k: int) -> LocalPicture:
        return _signature(k, rows, cols, None)

    base = class_counts((rows - 1, cols - 1), (sizes[0] - 1, sizes[1] - 1), lambda i, j: plain(i * (cols - 1) + j))
    counts: Counter[Hashable] = Counter()
    at: dict[Hashable, tuple[int, int]] = {}  # where a touched plaquette's own picture is
    for robot, rb in enumerate(scenario.robots):
        counts.update(base)
        for k in _touched(rb, rows, cols):
            own = _signature(k, rows, cols, rb)
            counts[plain(k)] -= 1
            counts[own] += 1
            at.setdefault(own, (robot, k))
    fused = rule == "exact" and fuse  # only the parity-basis partial mixers are fused (qcpp.gadgets.junction)
    kinds: list[tuple[GadgetKind, Count]] = []
    for sig, n in counts.items():  # (never negative: corrections remove members of a class)
        m = _mixer(scenario, sig, rule, target, at.get(sig), plain) if n != 0 else None
        if m is not None:
            kind, rotation, _, _ = _kinds_of(m)
            kinds.append((rotation if fused else kind, n))
    if fused:
        kinds += _junction_kinds(scenario, rule, target, sizes)
    return MixerPart(tuple(kinds))


def _relation(a: int, b: int, cols: int) -> Hashable:
    (ia, ja), (ib, jb) = divmod(a, cols - 1), divmod(b, cols - 1)
    return (ib - ia, jb - ja) if abs(ib - ia) <= 2 and abs(jb - ja) <= 2 else "far"


def _junction_kinds(
    scenario: Scenario, rule: str, target: str, sizes: tuple[Count, Count]
) -> list[tuple[GadgetKind, Count]]:
    """The junctions of one layer as kinds: one per ordered pair of consecutive partial mixers (the plain grid's
    horizontal neighbours and row wraps, those next to a robot's endpoints replaced by its own, one between
    consecutive robots), and the two open ends (the first compute, the last uncompute)."""
    rows, cols = scenario.grid.rows, scenario.grid.cols
    pcol, total = cols - 1, (rows - 1) * (cols - 1)

    def plain(k: int) -> Hashable:  # the plain class of the pair (k, k + 1)
        return _signature(k, rows, cols, None), _signature(k + 1, rows, cols, None), _relation(k, k + 1, cols)

    def mixer(robot: int, k: int) -> Mixer | None:
        return _mixer(scenario, _signature(k, rows, cols, scenario.robots[robot]), rule, target, (robot, k))

    def present(robot: int, k: int) -> bool:
        return mixer(robot, k) is not None

    # one robot's plain pairs: horizontal neighbours and row wraps
    base = class_counts((rows - 1, pcol - 1), (sizes[0] - 1, sizes[1] - 2), lambda i, j: plain(i * pcol + j))
    base.update(class_counts((rows - 2, 1), (sizes[0] - 2, 1), lambda i, _: plain(i * pcol + pcol - 1)))
    counts: Counter[tuple[Hashable, tuple[int, int, int, int] | None]] = Counter()  # (class, realisation or None)
    ends: list[tuple[int, int, int]] = []  # per robot with partial mixers: (robot, first, last) present plaquette
    for robot, rb in enumerate(scenario.robots):
        counts.update({(key, None): n for key, n in base.items()})
        touched = _touched(rb, rows, cols)
        affected = sorted({a for k in touched for a in (k - 1, k) if 0 <= a < total - 1})
        for a in affected:
            counts[(plain(a), None)] -= 1
        for _, group in groupby(enumerate(affected), lambda t: t[1] - t[0]):  # runs of consecutive affected pairs
            run = [a for _, a in group]  # their actual pairs, absent partial mixers skipped:
            nodes = [k for k in range(run[0], run[-1] + 2) if k not in touched or present(robot, k)]
            for u, v in pairwise(nodes):
                pair = (_signature(u, rows, cols, rb), _signature(v, rows, cols, rb), _relation(u, v, cols))
                counts[(pair, (robot, u, robot, v))] += 1
        first_k = next((k for k in range(total) if k not in touched or present(robot, k)), None)
        if first_k is not None:
            last_k = next(k for k in reversed(range(total)) if k not in touched or present(robot, k))
            ends.append((robot, first_k, last_k))
    for (ra, _, ka), (rb, kb, _) in pairwise(ends):  # one junction between consecutive robots
        pair = (_signature(ka, rows, cols, scenario.robots[ra]), _signature(kb, rows, cols, scenario.robots[rb]))
        counts[((*pair, "far"), (ra, ka, rb, kb))] += 1
    out = []
    for (key, at), n in counts.items():
        if n == 0:
            continue
        kind = COSTS.table(_JUNCTION).get((key, rule, target))
        if kind is None:
            if at is None:  # a plain class, realised by a pair no robot's endpoint touches
                robot, k = _realise(scenario, key, plain, 2)
                at = (robot, k, robot, k + 1)
            ra, a, rb, b = at
            junction = MixerJunction(_placed(scenario, ra, a, rule, target), _placed(scenario, rb, b, rule, target))
            kind = GadgetKind.of(junction)
            COSTS.remember(_JUNCTION, (key, rule, target), kind)
        out.append((kind, n))
    if ends:
        out.append((_kinds_of(mixer(*ends[0][:2]))[2], 1))  # type: ignore[arg-type]
        out.append((_kinds_of(mixer(ends[-1][0], ends[-1][2]))[3], 1))  # type: ignore[arg-type]
    return out
