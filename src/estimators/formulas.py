"""Closed-form resource counts of qcpp's own construction (default placement, whole-space phase separator).

Symbols: ``rows``, ``cols`` (>= 2), ``robots`` (1..4, :func:`gridcover.presets.default_scenario`) and ``p`` (>= 1).
Every expression equals the exact count of
``lower(qaoa_circuit(default_scenario(rows, cols, robots), p, phase="whole-space"))``: the mixer part is a sum over
partial-mixer gadget kinds, the phase part counts the Ising Hamiltonian's terms. The default phase separator
(``feasible``: arithmetic on path lengths, visit bits, chosen per term group) has no closed form here, so the
formulas are restricted to the whole-space form; ``qcpp estimate`` always sums the gadgets actually compiled
(``tests/estimators/formulas_test.py`` checks every quantity on every grid from 2x2 to 8x8, 1-4 robots, p = 1,
and p = 2, 3 on a subset). Depth and two-qubit depth have no closed form here: ASAP layering of the phase
separator and of the chain of partial mixers (which share the ``logic``/``work`` ancillas) does not decompose
into per-part sums, so only the exact counter (:mod:`estimators.counts`) gives them.

How the formulas are derived (see ``docs/resource-estimates.md`` for the full derivation):

* ``V = rows (cols-1) + cols (rows-1)`` edges per robot; data qubits ``robots V``.
* Initial state: one X per edge of each robot's initial path, ``robots (rows + cols - 2)``.
* Phase separator: one RZ per qubit (no linear coefficient vanishes with the default objective) and one RZZ
  (lowered: ``cx, rz, cx``) per nonzero ZZ coefficient. With ``P`` = number of pairs of edges sharing a node,
  the ZZ coefficient of ``x_{r,e} x_{s,f}`` is ``alpha1 * c2 part + alpha2 * c3 part``: within one robot it is
  nonzero for every pair when ``robots >= 2`` (c2 couples all edges of a robot) and only for the ``P`` pairs
  sharing a node when ``robots = 1`` (c2 vanishes); between consecutive robots c2 gives ``-2 d d`` and c3
  gives ``+2`` for edges sharing a node and ``+4`` for the same edge, so ``V^2 - 2P`` pairs remain (the ``2P``
  ordered pairs sharing a node cancel exactly); between non-consecutive robots only c3 acts: ``V + 2P``.
* Mixer: each (robot, plaquette) partial mixer's logic network is fixed by its corners' classes: an endpoint
  of that robot (E, always a grid corner), an interior node (B: may be busy, two outer edges) or neither (N:
  grid corner that is not an endpoint, or boundary node). The class of each corner depends only on whether
  the plaquette's row index is first / middle / last (or the only one, for 2 rows), likewise its column,
  and on the robot's diagonal (top-left/bottom-right for robots 0 and 3, top-right/bottom-left for robots 1
  and 2). So the mixer is a sum over (row class, column class) of ``count(row class) * count(col class) *
  cost(type)``, with counts ``1, rows - 3, 1`` (or ``1`` for 2 rows). ``cost(type)`` is the lowered gate
  count of one representative partial mixer of that type, compiled alone (every partial mixer is its own
  section, so the peephole pass never works across two of them): :func:`partial_mixer_types`.
* Ancillas: ``logic`` = the largest network (6 temporaries once some plaquette has four interior corners,
  i.e. rows, cols >= 4), ``work`` = largest multi-controlled X minus 2.

Example:
    >>> f = formula_table()
    >>> f["data_qubits"]
    robots*(2*cols*rows - cols - rows)
    >>> evaluate(3, 3, 1, 1)["cx"]
    152
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from circuitgen.angles import Angle
from circuitgen.gadgets.partial_mixer import mixer_work_need, partial_mixer
from gridcover.presets import default_scenario

__all__ = [
    "FORMULA_DOMAIN",
    "GATE_NAMES",
    "P_EXPR",
    "QUANTITIES",
    "V_EXPR",
    "MixerType",
    "P",
    "V",
    "cols",
    "evaluate",
    "formula_table",
    "p",
    "partial_mixer_types",
    "robots",
    "rows",
]

FORMULA_DOMAIN = (
    "rows, cols >= 2; 1 <= robots <= 4 (default corner placement); p >= 1; exact rule; nisq target; default "
    "objective; whole-space (Ising) phase separator, i.e. --phase whole-space (the default feasible-subspace phase "
    "separator has no closed form here); lowered circuit (cx x h rz t tdg s sdg, peephole on)"
)
"""Where :func:`formula_table` holds."""

rows, cols, robots, p = sp.symbols("rows cols robots p", integer=True, positive=True)

GATE_NAMES: tuple[str, ...] = ("cx", "x", "h", "rz", "t", "tdg", "s", "sdg")
"""Gate names of the lowered basis; each has a formula ``gate_<name>``."""

QUANTITIES: tuple[str, ...] = (
    "data_qubits",
    "logic_qubits",
    "work_qubits",
    "ancillas",
    "qubits",
    "gates",
    "cx",
    "two_qubit",
    "single_qubit",
    "t_count",
    "toffoli",
    "rotations",
    "nonzero_zz",
    "partial_mixers",
    *(f"gate_{g}" for g in GATE_NAMES),
)
"""Every published quantity (keys of :func:`formula_table`)."""

# Row (or column) classes of a plaquette's first index: the representative grid size and index, and the count.
_SMALL = (("only", 2, 0),)  # 2 rows: one plaquette row, both of its node rows on the boundary
_LARGE = (("first", 4, 0), ("middle", 4, 1), ("last", 4, 2))
_ROBOT_CLASSES = (("main", 0), ("anti", 1))  # robots 0, 3: TL <-> BR; robots 1, 2: TR <-> BL


def _class_count(cls: str, n: sp.Expr) -> sp.Expr:
    return n - 3 if cls == "middle" else sp.Integer(1)


@dataclass(frozen=True)
class MixerType:
    """One partial-mixer type and its lowered cost.

    Attributes:
        key: corner classes of ``a, b, c, d`` (``E`` endpoint, ``B`` interior, ``N`` neither), plus ``D`` when
            the robot's start and goal are diagonal corners of the plaquette.
        robot_class: ``main`` (start/goal top-left/bottom-right) or ``anti`` (top-right/bottom-left).
        row_class, col_class: ``only``, ``first``, ``middle`` or ``last``.
        ops: lowered gate counts of one partial mixer of this type, compiled alone.
        toffoli: Toffolis after multi-controlled-X lowering (before the Clifford+T step).
        logic_qubits: temporaries of its logic network.
        work_qubits: work ancillas its largest multi-controlled X needs.
    """

    key: str
    robot_class: str
    row_class: str
    col_class: str
    ops: Mapping[str, int]
    toffoli: int
    logic_qubits: int
    work_qubits: int


@lru_cache(maxsize=1)
def partial_mixer_types() -> tuple[MixerType, ...]:
    """Cost of every (robot class, row class, column class) partial mixer, from one representative each.

    The representative is plaquette ``(i, j)`` of ``default_scenario(R, C, 2)`` with ``R = 2, i = 0`` for the
    ``only`` class and ``R = 4, i = 0, 1, 2`` for ``first, middle, last`` (same for columns): its corners have
    exactly the classes of every plaquette of that class in every grid. Its cost is the partial-mixer gadget's
    own (:func:`circuitgen.gadgets.partial_mixer.partial_mixer`, default ``exact`` rule and ``nisq`` target),
    computed from its kind without emitting a gate.

    Returns:
        All types (2 robot classes x 16 row/column class pairs).

    >>> t = {(m.robot_class, m.row_class, m.col_class): m for m in partial_mixer_types()}
    >>> t["main", "middle", "middle"].key, t["main", "middle", "middle"].toffoli
    ('BBBB', 16)
    """
    out = []
    beta = Angle.symbol("beta_0")
    for rc, robot in _ROBOT_CLASSES:
        for row_classes in (_SMALL, _LARGE):
            for col_classes in (_SMALL, _LARGE):
                for rcls, nr, i in row_classes:
                    for ccls, nc, j in col_classes:
                        s = default_scenario(nr, nc, 2)
                        plaq = next(q for q in s.grid.plaquettes if q.corners[0] == (i, j))
                        out.append(_mixer_type(s, robot, plaq, rc, rcls, ccls, beta))
    return tuple(out)


def _mixer_type(s, robot, plaq, rc, rcls, ccls, beta) -> MixerType:  # type: ignore[no-untyped-def]
    rb = s.robots[robot]
    key = ""
    for v, corner in enumerate(plaq.corners):
        key += "E" if corner in (rb.start, rb.goal) else ("B" if len(plaq.outer_edges[v]) == 2 else "N")
    if {rb.start, rb.goal} in ({plaq.corners[0], plaq.corners[2]}, {plaq.corners[1], plaq.corners[3]}):
        key += "D"
    gadget = partial_mixer(s, robot, plaq, beta, s.num_variables)
    if gadget is None:  # the flip is never allowed: nothing is emitted
        return MixerType(key, rc, rcls, ccls, dict.fromkeys(GATE_NAMES, 0), 0, 0, 0)
    ops, logical = gadget.cost(), gadget.logical_cost()
    toffoli = logical["and"] + logical["and_dg"] + logical["ccx"]
    work = mixer_work_need([gadget])
    return MixerType(key, rc, rcls, ccls, {g: ops[g] for g in GATE_NAMES}, toffoli, gadget.num_temps, work)


def _mixer_sum(metric: Callable[[MixerType], int], small_rows: bool, small_cols: bool, robot_class: str) -> sp.Expr:
    """Sum of ``metric`` over the plaquettes of one robot of ``robot_class``, for one grid case."""
    rcls = {c for c, _, _ in (_SMALL if small_rows else _LARGE)}
    ccls = {c for c, _, _ in (_SMALL if small_cols else _LARGE)}
    total = sp.Integer(0)
    for m in partial_mixer_types():
        if m.robot_class == robot_class and m.row_class in rcls and m.col_class in ccls:
            total += _class_count(m.row_class, rows) * _class_count(m.col_class, cols) * metric(m)
    return sp.expand(total)


_GRID_CASES = (
    (True, True, sp.And(sp.Eq(rows, 2), sp.Eq(cols, 2))),
    (True, False, sp.Eq(rows, 2)),
    (False, True, sp.Eq(cols, 2)),
    (False, False, True),
)


def _per_robot_mixer(metric: Callable[[MixerType], int], robot_class: str = "main") -> sp.Expr:
    """One robot's full mixer (one layer): a Piecewise over the grid cases (or one polynomial)."""
    pieces = [(sp.factor(_mixer_sum(metric, r, c, robot_class)), cond) for r, c, cond in _GRID_CASES]
    if all(sp.expand(e - pieces[-1][0]) == 0 for e, _ in pieces):
        return pieces[-1][0]
    # drop a case when the pieces after it (those kept) already give its value there
    kept = [pieces[-1]]
    for e, c in reversed(pieces[:-1]):
        later = sp.Piecewise(*kept).subs(_case_subs(c))
        if sp.expand(e - later) != 0:
            kept.insert(0, (e, c))
    return sp.Piecewise(*kept) if len(kept) > 1 else kept[0][0]


N_ANTI = sp.Min(robots - 1, 2)
"""Robots on the anti-diagonal (robots 1 and 2 of the default placement, 1 <= robots <= 4)."""


def _all_robots_mixer(metric: Callable[[MixerType], int]) -> sp.Expr:
    """Every robot's mixer (one layer): ``(robots - N_ANTI) main + N_ANTI anti`` (``robots * main`` when the
    mirror-image robots cost the same)."""
    main, anti = _per_robot_mixer(metric, "main"), _per_robot_mixer(metric, "anti")
    if sp.simplify(main - anti) == 0:
        return robots * main
    return (robots - N_ANTI) * main + N_ANTI * anti


def _case_subs(cond: sp.Basic) -> dict[sp.Symbol, int]:
    if cond == sp.Eq(rows, 2):
        return {rows: 2}
    if cond == sp.Eq(cols, 2):
        return {cols: 2}
    return {rows: 2, cols: 2}


_SIZE_CLASSES = {2: {"only"}, 3: {"first", "last"}, 4: {"first", "middle", "last"}}  # 4 stands for >= 4


def _widest(*metrics: Callable[[MixerType], int]) -> sp.Expr:
    """Largest value over the partial mixers present (both robot classes), as a Piecewise in the smaller and the
    larger side ``lo = Min(rows, cols)``, ``hi = Max(rows, cols)`` each ``2``, ``3`` or ``>= 4`` (the sum of the
    maxima when several metrics are given). The value is checked to be symmetric in rows and cols."""
    values: dict[tuple[int, int], int] = {}
    for nr, rset in _SIZE_CLASSES.items():
        for nc, cset in _SIZE_CLASSES.items():
            present = [m for m in partial_mixer_types() if m.row_class in rset and m.col_class in cset]
            values[nr, nc] = sum(max((f(m) for m in present), default=0) for f in metrics)
    if any(values[a, b] != values[b, a] for a, b in values):  # pragma: no cover - the default placement is symmetric
        raise AssertionError("ancilla widths are not symmetric in rows and cols")
    lo, hi = sp.Min(rows, cols), sp.Max(rows, cols)
    pieces = []
    for a, b in [(2, 2), (2, 3), (2, 4), (3, 3), (3, 4)]:
        cond = sp.And(sp.Eq(lo, a), sp.Eq(hi, b) if b < 4 else hi >= 4)
        pieces.append((values[a, b], cond))
    last = values[4, 4]
    if all(v == last for v, _ in pieces):
        return sp.Integer(last)
    return sp.Piecewise(*pieces, (last, True), evaluate=False)


V, P = sp.symbols("V P", integer=True, positive=True)
"""Abbreviations of the structured formulas: edges per robot, and pairs of edges sharing a node."""
V_EXPR = 2 * rows * cols - rows - cols
"""``V = rows (cols - 1) + cols (rows - 1)``."""
P_EXPR = 6 * rows * cols - 6 * rows - 6 * cols + 4
"""``P = sum over nodes of C(deg, 2) = 4*1 + 3*2((rows-2) + (cols-2)) + 6 (rows-2)(cols-2)``."""


@lru_cache(maxsize=2)
def formula_table(structured: bool = False) -> dict[str, sp.Expr]:
    """Every quantity of :data:`QUANTITIES` as a sympy expression in ``rows, cols, robots, p``.

    Valid for ``rows, cols >= 2``, ``1 <= robots <= 4``, ``p >= 1``, the ``exact`` rule, the whole-space phase
    separator, default objective and
    the default placement. Gate counts are for the lowered circuit (basis ``cx x h rz t tdg s sdg``, peephole
    on); ``toffoli`` counts Toffolis after multi-controlled-X lowering; ``rotations`` counts arbitrary-angle
    RZ (all of them are symbolic); ``t_count`` is ``t + tdg``. Each gate count is written as
    ``initial state + p * (phase separator + robots * one robot's mixer)``.

    Args:
        structured: keep the abbreviations :data:`V` and :data:`P` (see :data:`V_EXPR`, :data:`P_EXPR`)
            instead of substituting them.

    Returns:
        name -> expression.
    """
    zz = sp.Piecewise(
        (P, sp.Eq(robots, 1)),
        (
            robots * V * (V - 1) / 2  # within each robot: every pair (c2 couples all its edges)
            + (robots - 1) * (V**2 - 2 * P)  # consecutive robots: edges sharing a node cancel
            + (robots - 1) * (robots - 2) * (V + 2 * P) / 2,  # other pairs of robots: c3 only
            True,
        ),
    )
    init_x = robots * (rows + cols - 2)
    mixer = {g: _all_robots_mixer(lambda m, g=g: m.ops[g]) for g in GATE_NAMES}

    def mixer_of(gate_names: tuple[str, ...]) -> sp.Expr:
        return _all_robots_mixer(lambda m: sum(m.ops[g] for g in gate_names))

    gate: dict[str, sp.Expr] = {}
    for g in GATE_NAMES:
        if g == "cx":
            gate[g] = p * (2 * zz + mixer[g])
        elif g == "rz":
            gate[g] = p * (robots * V + zz + mixer[g])
        elif g == "x":
            gate[g] = init_x + p * mixer[g]
        else:
            gate[g] = p * mixer[g]

    logic = _widest(lambda m: m.logic_qubits)
    work = _widest(lambda m: m.work_qubits)
    ancillas = _widest(lambda m: m.logic_qubits, lambda m: m.work_qubits)
    singles = tuple(g for g in GATE_NAMES if g != "cx")
    table: dict[str, sp.Expr] = {
        "data_qubits": robots * V,
        "logic_qubits": logic,
        "work_qubits": work,
        "ancillas": ancillas,
        "qubits": robots * V + ancillas,
        "gates": init_x + p * (robots * V + 3 * zz + mixer_of(GATE_NAMES)),
        "cx": gate["cx"],
        "two_qubit": gate["cx"],
        "single_qubit": init_x + p * (robots * V + zz + mixer_of(singles)),
        "t_count": p * mixer_of(("t", "tdg")),
        "toffoli": p * _all_robots_mixer(lambda m: m.toffoli),
        "rotations": gate["rz"],
        "nonzero_zz": zz,
        "partial_mixers": p * robots * (rows - 1) * (cols - 1),
    }
    table.update({f"gate_{g}": gate[g] for g in GATE_NAMES})
    if not structured:
        table = {k: sp.sympify(e).subs({V: V_EXPR, P: P_EXPR}) for k, e in table.items()}
    return {name: table[name] for name in QUANTITIES}


@lru_cache(maxsize=1)
def _compiled() -> dict[str, Callable[..., object]]:
    return {
        name: sp.lambdify((rows, cols, robots, p), expr, modules=[{"Min": min, "Max": max}, "math"])
        for name, expr in formula_table().items()
    }


def evaluate(n_rows: int, n_cols: int, n_robots: int, layers: int) -> dict[str, int]:
    """Evaluate every formula at one point.

    Args:
        n_rows, n_cols: grid size (>= 2 each).
        n_robots: 1 to 4.
        layers: ``p >= 1``.

    Returns:
        name -> integer value.

    >>> evaluate(2, 2, 1, 1)["qubits"]
    4
    """
    if n_rows < 2 or n_cols < 2 or not 1 <= n_robots <= 4 or layers < 1:
        raise ValueError("formulas hold for rows, cols >= 2, 1 <= robots <= 4 and p >= 1")
    out = {}
    for name, fn in _compiled().items():
        value = fn(n_rows, n_cols, n_robots, layers)
        iv = round(float(value))  # type: ignore[arg-type]
        if abs(float(value) - iv) > 1e-6:  # type: ignore[arg-type]
            raise ArithmeticError(f"formula {name} is not an integer at {n_rows}x{n_cols}, {n_robots}, {layers}")
        out[name] = iv
    return out
