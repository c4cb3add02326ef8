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
grid size. Each distinct picture's cost is asked once (from a real gadget of that picture) and cached for every
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
