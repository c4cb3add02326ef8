"""Simultaneous Bit Flip (SBF) moves and the logic functions that allow them.

An SBF move flips the four edges of one plaquette in one robot's path (``mask ^ plaquette.edge_mask``).
Whether it may be applied is a boolean function of the robot's edges near the plaquette: its four edges
``ab, bc, cd, da`` and its corners' outer edges. Two rules are provided:

``paper``
    ``f = f1 AND f2 AND f3`` exactly as the paper writes them: f1 = some plaquette edge is set; f2 = the
    plaquette edges are not ``1010`` or ``0101``; f3 = no corner has both of its outer edges set (a corner
    with fewer than two outer edges contributes nothing).

``exact``
    Allows a flip of a feasible path exactly when it can be shown from the plaquette's neighbourhood that
    the result is feasible. With ``q_v`` the number of plaquette edges at corner ``v`` in the path:

    * no plaquette edge set: never (the flip adds a closed 4-cycle);
    * two opposite plaquette edges (``1010``/``0101``): whether the flip leaves a loop depends on the order in
      which the path visits them, which no local function can see; allowed only when the robot's start and
      goal are diagonal corners of the plaquette (then it is always feasible);
    * otherwise: every corner with ``q_v = 0`` must be free (not the robot's start or goal and no outer
      edge set), because the flip gives it two new edges.

    On every feasible path this is "the flip is feasible" except for the opposite-edges case, where feasible
    flips are missed (the tests show both exhaustively on small grids).

Each rule is compiled, per robot and plaquette, into a :class:`SbfLogic`: a straight-line program of "XOR an
AND of literals into a bit" steps (what multi-controlled X gates compute), with everything known at compile time
(boundary corners, fixed edges, the robot's endpoints) folded in.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.problem.paths import initial_path
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> p = initial_path(s, 0)
    >>> [sbf_logic(s, 0, q).evaluate(p) for q in s.grid.plaquettes]
    [True, True, False, True]
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Literal as TypingLiteral
from typing import NamedTuple

from qcpp.problem.grid import Plaquette
from qcpp.problem.paths import enumerate_paths, initial_path
from qcpp.problem.scenario import Scenario

Rule = TypingLiteral["exact", "paper"]
RULES: tuple[Rule, ...] = ("exact", "paper")

# corner -> its two plaquette edges, as positions in (ab, bc, cd, da)
_CORNER_EDGES = ((0, 3), (0, 1), (1, 2), (2, 3))


@dataclass(frozen=True)
class Lit:
    """One literal: ``signal == value``, or ``signal XOR xor == value`` when ``xor`` is set.

    ``signal >= 0`` is a grid edge of the robot's path; ``signal < 0`` is the temporary bit ``~signal`` (so ``-1``
    is temporary 0). ``xor``, when not ``None``, is a second grid edge: the literal then reads the parity of two
    edges (the exact rule reads corner parities, which the circuit holds on a qubit after a CX ladder)."""

    signal: int
    value: bool
    xor: int | None = None

    @property
    def is_temp(self) -> bool:
        return self.signal < 0

    @property
    def temp(self) -> int:
        return ~self.signal

    @property
    def edges(self) -> tuple[int, ...]:
        """The grid edges the literal reads (none for a temporary)."""
        if self.signal < 0:
            return ()
        return (self.signal,) if self.xor is None else (self.signal, self.xor)


@dataclass(frozen=True)
class XorStep:
    """``temps[target] ^= AND(literals)``; no literals means ``temps[target] ^= 1``."""

    target: int
    literals: tuple[Lit, ...]


@dataclass(frozen=True)
class SbfLogic:
    """A compiled logic function for one robot and one plaquette.

    Attributes:
        rule: ``exact`` or ``paper``.
        plaquette: Plaquette index.
        num_temps: Temporary bits used (ancillas in the circuit); all start at 0.
        output: The temporary holding the result.
        steps: The program; run it forwards to compute, backwards to uncompute.
    """

    rule: Rule
    robot: int
    plaquette: int
    num_temps: int
    output: int
    steps: tuple[XorStep, ...]

    @property
    def never(self) -> bool:
        """True when the move is never allowed (the partial mixer is folded away)."""
        return not any(s.target == self.output for s in self.steps)

    def evaluate(self, mask: int) -> bool:
        """Run the program on the robot's path ``mask``."""
        temps = [False] * self.num_temps
        for s in self.steps:
            if all(_lit_value(lit, temps, mask) == lit.value for lit in s.literals):
                temps[s.target] = not temps[s.target]
        return temps[self.output]


def _lit_value(lit: Lit, temps: Sequence[bool], mask: int) -> bool:
    if lit.signal < 0:
        return temps[~lit.signal]
    v = (mask >> lit.signal) & 1
    if lit.xor is not None:
        v ^= (mask >> lit.xor) & 1
    return bool(v)


def apply_sbf(mask: int, plaquette: Plaquette) -> int:
    """Flip the plaquette's four edges in ``mask``.

    Example:
        >>> from qcpp.problem.grid import Grid
        >>> q = Grid(2, 2).plaquettes[0]
        >>> apply_sbf(q.edge_mask, q)
        0
    """
    return mask ^ plaquette.edge_mask


# ---------------------------------------------------------------- compilation


def sbf_logic(scenario: Scenario, robot: int, plaquette: Plaquette, rule: Rule = "exact") -> SbfLogic:
    """Compile the rule's logic function for ``robot`` on ``plaquette``, specialised to the scenario.

    Args:
        scenario: The scenario (obstacle mode and endpoints are folded in).
        rule: ``exact`` (default) or ``paper``.

    Returns:
        The :class:`SbfLogic`; ``.never`` when no flip can be allowed (e.g. a plaquette edge touches an
        obstacle in hard mode).
    """
    if rule not in RULES:
        raise ValueError(f"unknown SBF rule {rule!r} (expected one of {', '.join(RULES)})")
    return _sbf_logic_cached(scenario, robot, plaquette.index, rule)


@lru_cache(maxsize=65536)
def _sbf_logic_cached(scenario: Scenario, robot: int, pindex: int, rule: Rule) -> SbfLogic:
    """Pure memo: ``_sbf_logic_cached.cache_clear()`` empties it."""
    plaq = scenario.grid.plaquettes[pindex]
    local = _neighbourhood(scenario, robot, plaq)
    if local is None:
        return SbfLogic(rule, robot, pindex, 1, 0, ())
    endpoints, outer, diagonal = local
    if rule == "paper":
        return _paper_logic(robot, pindex, plaq.edges, outer)
    return _exact_logic(robot, pindex, plaq.edges, outer, endpoints, diagonal)


class LocalPicture(NamedTuple):
    """What the SBF rules read of a plaquette for one robot, up to the edges' names: equal pictures give equal
    logic programs (the one definition; the compiler counts plaquettes by it, the formulas name classes by it; a
    named tuple, so that the class counts hash it at C speed).

    Attributes:
        endpoints: per corner ``a, b, c, d``, whether it is the robot's start or goal.
        outer: per corner, how many variable outer edges it has (0 to 2).
        diagonal: whether start and goal are diagonal corners of the plaquette.
    """

    endpoints: tuple[bool, bool, bool, bool]
    outer: tuple[int, int, int, int]
    diagonal: bool

    @classmethod
    def of(
        cls, corners: Sequence[tuple[int, int]], start: object, goal: object, outer: Sequence[int]
    ) -> LocalPicture:
        """The picture of a plaquette with ``corners`` (``a, b, c, d``) for a robot from ``start`` to ``goal``
        (``None`` for a robot that has no endpoint here) with ``outer[v]`` variable outer edges at corner ``v``."""
        ends = (start, goal)
        diagonal = {start, goal} in ({corners[0], corners[2]}, {corners[1], corners[3]})
        return cls(tuple(c in ends for c in corners), tuple(outer), diagonal)  # type: ignore[arg-type]

    @property
    def label(self) -> str:
        """Per corner ``E`` (endpoint), ``B`` (two outer edges) or ``N``, then ``D`` if diagonal: ``"EBBN"``."""
        corners = "".join("E" if e else ("B" if o == 2 else "N") for e, o in zip(self.endpoints, self.outer))
        return corners + ("D" if self.diagonal else "")


def _neighbourhood(
    scenario: Scenario, robot: int, plaq: Plaquette
) -> tuple[tuple[bool, ...], tuple[tuple[int, ...], ...], bool] | None:
    """What a rule reads of the scenario at ``plaq``: its :class:`LocalPicture` (endpoints and diagonal) and each
    corner's variable outer edges; ``None`` when a plaquette edge is not a variable (no flip can be allowed)."""
    vmask = scenario.variable_mask
    if any(not (vmask >> e) & 1 for e in plaq.edges):
        return None
    rb = scenario.robots[robot]
    outer = tuple(tuple(e for e in oe if (vmask >> e) & 1) for oe in plaq.outer_edges)
    picture = LocalPicture.of(plaq.corners, rb.start, rb.goal, [len(o) for o in outer])
    return picture.endpoints, outer, picture.diagonal


def _exact_logic(
    robot: int,
    pindex: int,
    pedges: tuple[int, int, int, int],
    outer: tuple[tuple[int, ...], ...],
    endpoints: tuple[bool, ...],
    diagonal: bool,
) -> SbfLogic:
    """The exact rule in the parity basis (equal to the rule on every feasible path; see the module docstring).

    With ``s_v`` the parity of corner ``v``'s two plaquette edges (on a feasible path 1 iff ``v`` has exactly
    one plaquette edge) and ``o_v`` a corner's first variable outer edge:

    * ``blocked[v] = NOT s_v AND o_v`` for every non-endpoint corner with two variable outer edges (B): on a
      feasible path a non-endpoint corner without plaquette edges has 0 or 2 outer edges set, so ``o_v`` tells
      whether it is busy, and a corner with two plaquette edges has none set;
    * ``equal = (ab XOR cd == 0) AND (bc XOR da == 0)``: all four ``s_v`` equal, i.e. the pattern is 0000,
      1111, 1010 or 0101 (dropped when start and goal are diagonal corners: the opposite patterns are then
      always feasible, and 0000/1111 are excluded by the endpoints);
    * ``out = AND(s_v for each endpoint corner v) AND NOT blocked[v] ... AND NOT equal``: an endpoint has
      degree 1 on a feasible path, so it needs exactly one plaquette edge.

    Every literal reads a corner parity, an outer edge or a temporary, never a single plaquette edge, so the
    function is unchanged by the flip: the circuit computes it once, rotates and uncomputes.
    ``tests/problem/sbf_test.py`` checks it against :func:`exact_rule_value` on every feasible path.
    """
    steps: list[XorStep] = []
    final: list[Lit] = []
    for v, (i, j) in enumerate(_CORNER_EDGES):
        parity = (pedges[i], pedges[j])
        if endpoints[v]:
            final.append(Lit(parity[0], True, parity[1]))
        elif len(outer[v]) == 2:
            t = len(steps)
            steps.append(XorStep(t, (Lit(parity[0], False, parity[1]), Lit(outer[v][0], True))))
            final.append(Lit(~t, False))
    if not diagonal:
        ab, bc, cd, da = pedges
        t = len(steps)
        steps.append(XorStep(t, (Lit(ab, False, cd), Lit(bc, False, da))))
        final.append(Lit(~t, False))
    out = len(steps)
    steps.append(XorStep(out, tuple(final)))
    return SbfLogic("exact", robot, pindex, out + 1, out, tuple(steps))


def _paper_logic(
    robot: int, pindex: int, pedges: tuple[int, int, int, int], outer: tuple[tuple[int, ...], ...]
) -> SbfLogic:
    ab, bc, cd, da = pedges
    f1, f2 = 0, 1
    steps = [
        XorStep(f1, ()),
        XorStep(f1, (Lit(ab, False), Lit(bc, False), Lit(cd, False), Lit(da, False))),
        XorStep(f2, ()),
        XorStep(f2, (Lit(ab, True), Lit(bc, False), Lit(cd, True), Lit(da, False))),
        XorStep(f2, (Lit(ab, False), Lit(bc, True), Lit(cd, False), Lit(da, True))),
    ]
    corner_temps = []
    for oe in outer:
        if len(oe) == 2:  # a corner with fewer than two outer edges cannot be passed through
            t = 2 + len(corner_temps)
            corner_temps.append(t)
            steps.append(XorStep(t, (Lit(oe[0], True), Lit(oe[1], True))))
    out = 2 + len(corner_temps)
    final = [Lit(~f1, True), Lit(~f2, True)] + [Lit(~t, False) for t in corner_temps]
    steps.append(XorStep(out, tuple(final)))
    return SbfLogic("paper", robot, pindex, out + 1, out, tuple(steps))


def direct_exact_logic(scenario: Scenario, robot: int, plaquette: Plaquette) -> SbfLogic:
    """The exact rule as a network on plain edges (without the parity basis), for comparisons only.

    It reads the plaquette edges themselves (``blocked[v] = NOT e1 AND NOT e2 [AND o_v]``, a 4-literal pattern
    test) instead of corner parities, which is what a circuit without the parity basis (the paper's structure:
    multi-controlled X gates into ancillas, then the controlled XXXX rotation) computes. On every feasible path
    it equals :func:`sbf_logic` with ``rule="exact"``; the benchmarks build the paper-structured comparison
    circuit from it. The three levels:

    * ``blocked[v] = (corner v has no plaquette edge) AND (v is busy)`` for every corner that can be busy:
      the robot's endpoints (always busy) and non-endpoint corners with two variable outer edges. On a
      feasible path a non-endpoint corner without plaquette edges has 0 or 2 outer edges set, so its first
      outer edge alone tells whether it is busy; corners with fewer outer edges are never busy.
    * ``pattern = NOT (0000 OR 1010 OR 0101)`` on ``ab, bc, cd, da``; the 0000 term is dropped when an
      endpoint corner already blocks it, the opposite terms when start and goal are diagonal.
    * ``out = pattern AND NOT blocked[v] for all v``.

    Returns:
        The program (``.never`` when a plaquette edge is not a variable).
    """
    local = _neighbourhood(scenario, robot, plaquette)
    if local is None:
        return SbfLogic("exact", robot, plaquette.index, 1, 0, ())
    endpoints, outer, diagonal = local
    pedges = plaquette.edges
    ab, bc, cd, da = pedges
    steps: list[XorStep] = []
    blocked: list[int] = []
    for v, (i, j) in enumerate(_CORNER_EDGES):
        if endpoints[v]:
            lits: tuple[Lit, ...] = (Lit(pedges[i], False), Lit(pedges[j], False))
        elif len(outer[v]) == 2:
            lits = (Lit(pedges[i], False), Lit(pedges[j], False), Lit(outer[v][0], True))
        else:
            continue
        blocked.append(len(blocked))
        steps.append(XorStep(blocked[-1], lits))
    excluded = []
    if not any(endpoints):
        excluded.append((False, False, False, False))
    if not diagonal:
        excluded += [(True, False, True, False), (False, True, False, True)]
    final = [Lit(~t, False) for t in blocked]
    if excluded:
        g = len(blocked)
        steps.append(XorStep(g, ()))
        for pat in excluded:
            steps.append(XorStep(g, tuple(Lit(e, val) for e, val in zip((ab, bc, cd, da), pat))))
        final.insert(0, Lit(~g, True))
    out = len(blocked) + (1 if excluded else 0)
    steps.append(XorStep(out, tuple(final)))
    return SbfLogic("exact", robot, plaquette.index, out + 1, out, tuple(steps))


def exact_rule_value(
    pbits: Sequence[int], outer_counts: Sequence[int], endpoints: Sequence[bool], diagonal: bool
) -> bool:
    """The ``exact`` rule on one local configuration (the specification :func:`sbf_logic` compiles).

    Args:
        pbits: Bits of ``ab, bc, cd, da``.
        outer_counts: Number of set outer edges at corners ``a, b, c, d``.
        endpoints: Whether each corner is the robot's start or goal.
        diagonal: Whether start and goal are diagonal corners of the plaquette.
    """
    k = sum(pbits)
    if k == 0 or k == 4:
        return False
    if k == 2 and pbits[0] == pbits[2]:
        return diagonal
    for v, (e1, e2) in enumerate(_CORNER_EDGES):
        if pbits[e1] + pbits[e2] == 0 and (endpoints[v] or outer_counts[v] > 0):
            return False
    return True


# ---------------------------------------------------------------- the move graph


def allowed_moves(scenario: Scenario, robot: int, mask: int, rule: Rule = "exact") -> list[int]:
    """Indices of the plaquettes whose flip the rule allows on ``mask``."""
    return [
        q.index for q in scenario.grid.plaquettes if sbf_logic(scenario, robot, q, rule).evaluate(mask)
    ]


def reachable_paths(
    scenario: Scenario, robot: int, rule: Rule = "exact", start: int | None = None
) -> list[int]:
    """All paths reachable from ``start`` (default: :func:`~qcpp.problem.paths.initial_path`) by allowed SBF
    moves, in breadth-first order. With the ``paper`` rule this can include infeasible edge sets."""
    return _breadth_first(initial_path(scenario, robot) if start is None else start,
                          _moves(scenario, robot, rule), set())


def _moves(scenario: Scenario, robot: int, rule: Rule) -> Callable[[int], Iterator[int]]:
    """``moves(mask)``: the masks one allowed flip away, plaquettes ascending."""
    flips = [(q.edge_mask, sbf_logic(scenario, robot, q, rule)) for q in scenario.grid.plaquettes]
    return lambda m: (m ^ edges for edges, logic in flips if logic.evaluate(m))


def _breadth_first(start: int, moves: Callable[[int], Iterable[int]], seen: set[int]) -> list[int]:
    """``start`` and every mask reached from it by ``moves`` and not in ``seen``, breadth first (``seen`` grows)."""
    order = [start]
    seen.add(start)
    queue = deque(order)
    while queue:
        for n in moves(queue.popleft()):
            if n not in seen:
                seen.add(n)
                order.append(n)
                queue.append(n)
    return order


def move_components(scenario: Scenario, robot: int, rule: Rule = "exact") -> list[list[int]]:
    """Split all feasible paths of a robot into the connected components of the move graph.

    The component holding :func:`~qcpp.problem.paths.initial_path` comes first; the others follow in the
    order of their first path in :func:`~qcpp.problem.paths.enumerate_paths`. Each component lists its paths in
    breadth-first order from its first path (its representative). Moves that leave the feasible set (the
    ``paper`` rule's failures) are not followed.
    """
    paths = enumerate_paths(scenario, robot)
    feasible = set(paths)
    step = _moves(scenario, robot, rule)
    init = initial_path(scenario, robot)
    assigned: set[int] = set()
    return [_breadth_first(seed, lambda m: (n for n in step(m) if n in feasible), assigned)
            for seed in [init, *(p for p in paths if p != init)] if seed not in assigned]


def representatives(scenario: Scenario, robot: int, rule: Rule = "exact") -> tuple[int, ...]:
    """One path per move-graph component (the initial path's component first)."""
    return tuple(c[0] for c in move_components(scenario, robot, rule))
