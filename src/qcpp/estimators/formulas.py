"""Closed-form resource counts of qcpp's own construction (default placement, whole-space phase separator).

Symbols: ``rows``, ``cols`` (>= 2), ``robots`` (1..4, :func:`qcpp.problem.presets.default_scenario`) and ``p`` (>= 1).
Every expression equals the exact count of
``lower(qaoa_circuit(default_scenario(rows, cols, robots), p, phase="whole-space"))``, and is the call graph's own
counting (:func:`part_terms`) run with symbolic sides, as Qualtran's ``build_call_graph`` returns
``{And(): n - 1}``: nothing here describes the circuit a second time. The default (``feasible``) phase separator
costs bit lengths of path-length sums, which have no polynomial form, and ASAP depth does not decompose into
per-part sums, so neither has a formula.

* A side of 2, 3 or 4 nodes is its own case; a side of ``>= 5`` nodes is read from a representative side of 6
  whose classes (first, last, between: :func:`qcpp.plan.mixer_classes.index_classes`) are those of every longer
  side, the "between" class counted as ``rows - 2`` (nodes), ``rows - 3`` (consecutive pairs) and so on.
* Robots: each part of ``default_scenario(R, C, k)`` for ``k = 1..4``, written with indicators of
  ``robots >= k`` (:func:`_case_layer`); the cases joined in one Piecewise (:func:`_layer`).
* Ancillas: the largest need over the mixer's kinds (:func:`_widest`).

Example:
    >>> f = formula_table()
    >>> f["data_qubits"]
    robots*(2*cols*rows - cols - rows)
    >>> evaluate(3, 3, 1, 1)["cx"]
    150
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from qcpp.gadgets.initial_state import initial_path_count
from qcpp.gadgets.phase_ising import ising_cost
from qcpp.ir.cost import Cost
from qcpp.plan.mixer_classes import MixerPart, mixer_part
from qcpp.plan.phase_classes import ising_count
from qcpp.problem.presets import default_scenario

__all__ = [
    "FORMULA_DOMAIN",
    "GATE_NAMES",
    "QUANTITIES",
    "V_EXPR",
    "Term",
    "V",
    "cols",
    "evaluate",
    "formula_table",
    "p",
    "part_terms",
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

@dataclass(frozen=True)
class Term:
    """Gate counts of one gadget kind: lowered ``ops``, ``toffoli`` (ANDs, their uncomputes and Toffolis of the
    logical basis) and ``zz`` (Ising couplings it holds)."""

    ops: Mapping[str, int]
    toffoli: int
    zz: int = 0

    @classmethod
    def of(cls, cost: Cost, logical: Cost, zz: int = 0) -> Term:
        """From a lowered and a logical cost."""
        return cls({g: cost[g] for g in GATE_NAMES}, logical["and"] + logical["and_dg"] + logical["ccx"], zz)


Metric = Callable[[Term], int]
Counted = tuple[tuple[sp.Expr, Term], ...]
"""``(count, term)`` pairs."""
_CASES = (2, 3, 4, 5)  # a side of 2, 3, 4 nodes, or 5 standing for >= 5
_REPRESENTATIVE = {2: 2, 3: 3, 4: 4, 5: 6}  # the grid side each case is read from (6: every class occurs)


LAYER = ("phase", "mixer")
"""The parts of one layer (:func:`part_terms`); the state preparation is ``("initial_state",)``."""

N_ANTI = sp.Min(robots - 1, 2)
"""Robots on the anti-diagonal (robots 1 and 2 of the default placement, 1 <= robots <= 4)."""


@lru_cache(maxsize=256)
def part_terms(part: str, rows_case: int, cols_case: int, num_robots: int) -> Counted:
    """One part of ``default_scenario(R, C, num_robots)``'s call graph as its counting lists it, the counts
    symbolic in ``rows``, ``cols`` where a case stands for sides of ``>= 5`` nodes: the same counting the
    estimates use (:meth:`qcpp.plan.qaoa.QaoaPlan.call_graph`), run with symbolic sides.

    * ``initial_state``: one X per edge of each robot's initial path
      (:func:`qcpp.gadgets.initial_state.initial_path_count`);
    * ``phase`` (one layer, whole-space): the nonzero Ising terms by classes of nodes and edges
      (:func:`qcpp.plan.phase_classes.ising_count`), priced by :func:`qcpp.gadgets.phase_ising.ising_cost`
      (one rotation, one coupling);
    * ``mixer`` (one layer): rotations, junctions and the two open ends by classes of plaquettes
      (:func:`qcpp.plan.mixer_classes.mixer_part`).

    Args:
        part: ``initial_state``, ``phase`` or ``mixer``.
        rows_case, cols_case: ``2``, ``3``, ``4`` or ``5`` (``>= 5``).
        num_robots: ``1`` to ``4`` (default placement).

    Returns:
        ``(count, term)`` pairs; a count is a sympy expression in ``rows``, ``cols``.

    Pure memo: ``part_terms.cache_clear()`` empties it."""
    nr, nc = _REPRESENTATIVE[rows_case], _REPRESENTATIVE[cols_case]
    sizes = (rows if rows_case == 5 else sp.Integer(nr), cols if cols_case == 5 else sp.Integer(nc))
    s = default_scenario(nr, nc, num_robots)
    if part == "initial_state":
        x = Cost.of(x=1)
        return ((sp.sympify(initial_path_count(s, sizes)), Term.of(x, x)),)
    if part == "mixer":
        return tuple((sp.sympify(n), Term.of(k.cost(), k.logical_cost())) for k, n in mixer_part(s, sizes=sizes).kinds)
    count = ising_count(s, sizes=sizes)
    assert count is not None  # an open grid, uniform lengths, distinct endpoints
    rotation, coupling = ising_cost(1, 0), ising_cost(0, 1)
    return (
        (sp.sympify(count.linear), Term.of(rotation, rotation)),
        (sp.sympify(count.couplings), Term.of(coupling, coupling, zz=1)),
    )


def _case_layer(metric: Metric, parts: tuple[str, ...], rows_case: int, cols_case: int) -> sp.Expr:
    """The ``parts`` (every robot) in one grid case, from the call graphs of 1..4 robots: the first robot's plus
    what each further robot adds (its partial mixers and the junction joining it, its rotations and couplings,
    its initial path), written with indicators of ``robots >= k`` (one multiple of ``robots - 1`` when every
    further robot adds the same)."""
    f = []
    for k in (1, 2, 3, 4):
        by_count: dict[sp.Expr, int] = {}  # few distinct counts: add the numbers first, multiply once
        for n, t in (term for part in parts for term in part_terms(part, rows_case, cols_case, k)):
            by_count[n] = by_count.get(n, 0) + metric(t)
        f.append(sp.expand(sum((n * v for n, v in by_count.items()), sp.Integer(0))))
    g = [f[0], f[1] - f[0], f[2] - f[1], f[3] - f[2]]
    if g[0] == g[1] == g[2] == g[3]:
        out = robots * g[0]
    elif g[1] == g[2] == g[3]:
        out = g[0] + (robots - 1) * g[1]
    elif g[1] == g[2]:  # robots 2 and 3 of the default placement are the anti-diagonal ones
        out = g[0] + N_ANTI * g[1] + (robots - 1 - N_ANTI) * g[3]
    else:
        at_least = [sp.Min(robots - 1, 1), sp.Max(sp.Min(robots - 2, 1), 0), sp.Max(robots - 3, 0)]
        out = g[0] + sum((gk * ind for gk, ind in zip(g[1:], at_least, strict=True)), sp.Integer(0))
    subs = {side: case for side, case in ((rows, rows_case), (cols, cols_case)) if case < 5}
    return sp.factor(out.subs(subs)) if subs else out


def _layer(metric: Metric, parts: tuple[str, ...] = LAYER) -> sp.Expr:
    """The ``parts`` (default: one layer, phase separator and mixer; every robot) as a Piecewise over the grid
    cases (sides of 2, 3, 4 or >= 5 nodes), a case kept only where the pieces after it would give another value."""
    general = _case_layer(metric, parts, 5, 5)
    by_rows = {a: _case_layer(metric, parts, a, 5) for a in _CASES[:-1]}
    by_cols = {b: _case_layer(metric, parts, 5, b) for b in _CASES[:-1]}
    kept_rows = {a: e for a, e in by_rows.items() if sp.expand(e - general.subs(rows, a)) != 0}
    kept_cols = {b: e for b, e in by_cols.items() if sp.expand(e - general.subs(cols, b)) != 0}
    pieces = []
    for a in _CASES[:-1]:
        for b in _CASES[:-1]:
            e = _case_layer(metric, parts, a, b)
            fallback = (
                kept_rows[a].subs(cols, b)
                if a in kept_rows
                else kept_cols[b].subs(rows, a) if b in kept_cols else general.subs({rows: a, cols: b})
            )
            if sp.expand(e - fallback) != 0:
                pieces.append((e, sp.And(sp.Eq(rows, a), sp.Eq(cols, b))))
    pieces += [(e, sp.Eq(rows, a)) for a, e in kept_rows.items()]
    pieces += [(e, sp.Eq(cols, b)) for b, e in kept_cols.items()]
    if not pieces:
        return general
    return sp.Piecewise(*pieces, (general, True))


def _widest(width: Callable[[MixerPart], int]) -> sp.Expr:
    """A register width of the call graph (the largest need over the mixer's kinds, :func:`mixer_part`) as a
    Piecewise in the smaller and the larger side ``lo = Min(rows, cols)``, ``hi = Max(rows, cols)`` each ``2``,
    ``3`` or ``>= 4`` (read from a side of 4, where every class of plaquette occurs; both diagonals' robots). The
    value is checked to be symmetric in rows and cols."""
    values = {(a, b): width(mixer_part(default_scenario(a, b, 2))) for a in (2, 3, 4) for b in (2, 3, 4)}
    if any(values[a, b] != values[b, a] for a, b in values):  # pragma: no cover - the default placement is symmetric
        raise AssertionError("ancilla widths are not symmetric in rows and cols")
    lo, hi = sp.Min(rows, cols), sp.Max(rows, cols)
    cases = [(2, 2), (2, 3), (2, 4), (3, 3), (3, 4)]
    pieces = [(values[a, b], sp.And(sp.Eq(lo, a), sp.Eq(hi, b) if b < 4 else hi >= 4)) for a, b in cases]
    last = values[4, 4]
    if all(v == last for v, _ in pieces):
        return sp.Integer(last)
    return sp.Piecewise(*pieces, (last, True), evaluate=False)


V = sp.Symbol("V", integer=True, positive=True)
"""Abbreviation of the structured formulas: edges per robot."""
V_EXPR = 2 * rows * cols - rows - cols
"""``V = rows (cols - 1) + cols (rows - 1)``."""


@lru_cache(maxsize=2)
def formula_table(structured: bool = False) -> dict[str, sp.Expr]:
    """Every quantity of :data:`QUANTITIES` as a sympy expression in ``rows, cols, robots, p``.

    Valid on :data:`FORMULA_DOMAIN`. ``toffoli`` counts Toffolis after multi-controlled-X lowering;
    ``rotations`` counts arbitrary-angle RZ (all of them symbolic); ``t_count`` is ``t + tdg``. Each gate count is
    ``initial state + p * layer`` (:func:`part_terms`).

    Args:
        structured: write the data qubits with the abbreviation :data:`V` (see :data:`V_EXPR`).

    Returns:
        name -> expression.

    Pure memo: ``formula_table.cache_clear()`` empties it."""

    def circuit(metric: Metric) -> sp.Expr:  # the state preparation once, then p layers
        return _layer(metric, ("initial_state",)) + p * _layer(metric)

    def gates(names: tuple[str, ...]) -> sp.Expr:
        return circuit(lambda t: sum(t.ops[g] for g in names))

    gate = {g: gates((g,)) for g in GATE_NAMES}
    logic = _widest(lambda m: m.logic_width)
    work = _widest(lambda m: m.work_need)
    ancillas = _widest(lambda m: m.logic_width + m.work_need)
    singles = tuple(g for g in GATE_NAMES if g != "cx")
    data = robots * V if structured else robots * V_EXPR
    table: dict[str, sp.Expr] = {
        "data_qubits": data,
        "logic_qubits": logic,
        "work_qubits": work,
        "ancillas": ancillas,
        "qubits": data + ancillas,
        "gates": gates(GATE_NAMES),
        "cx": gate["cx"],
        "two_qubit": gate["cx"],
        "single_qubit": gates(singles),
        "t_count": gates(("t", "tdg")),
        "toffoli": circuit(lambda t: t.toffoli),
        "rotations": gate["rz"],
        "nonzero_zz": _layer(lambda t: t.zz),
        "partial_mixers": p * robots * (rows - 1) * (cols - 1),
    }
    table.update({f"gate_{g}": gate[g] for g in GATE_NAMES})
    return {name: table[name] for name in QUANTITIES}


@lru_cache(maxsize=1)
def _compiled() -> dict[str, Callable[..., object]]:
    """Pure memo: ``_compiled.cache_clear()`` empties it."""
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
