"""What ``qcpp estimate`` does, as plain functions (the CLI only parses options and prints).

* :func:`points_from_options`: the ``--grid / --robots / -p / --scenario / --rule`` texts to sweep points;
* :func:`estimate_report`: sweep, rows, optional paper comparison and plot, rendered in one format;
* :func:`formula_report`: the closed-form formulas (:mod:`estimators.formulas`) as text.

Example:
    >>> [p.label for p in points_from_options("2x2..2x3", "1", "1")]
    ['2x2 r1 p1', '2x3 r1 p1']
    >>> text = estimate_report(points_from_options("2x2", "1", "1"), fmt="csv", use_cache=False, progress=False)
    >>> text.splitlines()[1].split(",")[:6]
    ['2', '2', '1', '1', 'exact', 'default']
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence

import sympy as sp

from gridcover.limits import check_layers
from gridcover.presets import MAX_DEFAULT_ROBOTS
from gridcover.sbf import RULES
from gridcover.scenario import load_scenario

from .fault_tolerant import DEFAULT_EPSILON
from .formulas import P_EXPR, QUANTITIES, V_EXPR, formula_table
from .paper import Doubling
from .plots import plot_rows
from .sweep import Point, grid_points, parse_grid_range, parse_int_range, sweep
from .tables import FORMATS, Format, make_rows, render

__all__ = ["DEFAULT_GRID", "estimate_report", "formula_report", "points_from_options"]

DEFAULT_GRID = "3x3"
FORMULA_DOMAIN = (
    "rows, cols >= 2; 1 <= robots <= 4 (default corner placement); p >= 1; exact rule; default objective; "
    "lowered circuit (cx x h rz t tdg s sdg, peephole on)"
)


def points_from_options(
    grid: str | None,
    robots: str | None,
    p: str,
    scenario: str | os.PathLike[str] | None = None,
    rule: str = "exact",
) -> list[Point]:
    """Sweep points from the CLI's option texts.

    Args:
        grid: ``3x4`` or ``AxB..CxD`` (every rows in A..C and cols in B..D); ``None`` means ``3x3``. Must be
            ``None`` with ``scenario``.
        robots: ``N`` or ``A..B`` (1 to 4); ``None`` means ``1``. Must be ``None`` with ``scenario``.
        p: ``N`` or ``A..B`` layers.
        scenario: a scenario file to estimate instead of the default scenarios.
        rule: SBF rule.

    Returns:
        The points.

    Raises:
        ValueError: a malformed range or an unknown rule (``gridcover.errors.ScenarioError`` for a bad file).
    """
    if rule not in RULES:
        raise ValueError(f"bad rule {rule!r}: expected one of {', '.join(RULES)}")
    layers = parse_int_range(p, "p", 1)
    for k in layers:
        check_layers(k)  # the same layer limit as every other command (--allow-large lifts it)
    if scenario is not None:
        if grid is not None or robots is not None:
            raise ValueError("--scenario gives the grid and the robots: do not combine it with --grid or --robots")
        s = load_scenario(scenario)
        return [Point.from_scenario(s, k, rule) for k in layers]
    grids = parse_grid_range(grid if grid is not None else DEFAULT_GRID)
    ks = parse_int_range(robots if robots is not None else "1", "robots", 1, MAX_DEFAULT_ROBOTS)
    return grid_points(grids, ks, layers, rule)


def estimate_report(
    points: Sequence[Point],
    fmt: Format = "table",
    compare_paper: bool = False,
    plot: str | os.PathLike[str] | None = None,
    use_cache: bool = True,
    jobs: int | None = None,
    epsilon: float = DEFAULT_EPSILON,
    doubling: Doubling = "partial-mixer",
    progress: bool = True,
    columns: Sequence[str] | None = None,
    wide: bool = False,
) -> str:
    """Estimate ``points`` and render the rows.

    Args:
        points: from :func:`points_from_options`.
        fmt: one of :data:`estimators.tables.FORMATS`.
        compare_paper: add the paper's estimates and ratios.
        plot: also write the comparison plot (PNG) here.
        use_cache: use the on-disk cache.
        jobs: worker processes (default: all cores).
        epsilon: rotation synthesis precision of the fault-tolerant columns.
        doubling: reading of the paper's doubling.
        progress: progress bar on stderr.
        columns, wide: the ``table`` format's columns (:func:`estimators.tables.render`).

    Returns:
        The rendered text.
    """
    if fmt not in FORMATS:
        raise ValueError(f"bad format {fmt!r}: expected one of {', '.join(FORMATS)}")
    results = sweep(points, jobs=jobs, use_cache=use_cache, progress=progress, epsilon=epsilon)
    rows = make_rows(results, compare_paper, doubling)
    if plot is not None:
        plot_rows(rows, plot)
    return render(rows, fmt, columns=columns, wide=wide)


def formula_report(fmt: Format = "table") -> str:
    """The formulas of :mod:`estimators.formulas` as text.

    ``table``: pretty-printed structured forms (with ``V`` and ``P``); ``md``: LaTeX in Markdown; ``csv``:
    ``name,expression`` (explicit forms); ``json``: ``{"domain", "abbreviations", "formulas", "structured"}``.

    Args:
        fmt: one of :data:`estimators.tables.FORMATS`.

    Returns:
        The text.

    >>> json.loads(formula_report("json"))["formulas"]["partial_mixers"]
    'p*robots*(cols - 1)*(rows - 1)'
    """
    explicit, structured = formula_table(), formula_table(structured=True)
    abbrev = {"V": sp.sstr(V_EXPR), "P": sp.sstr(P_EXPR)}
    if fmt == "json":
        data = {
            "domain": FORMULA_DOMAIN,
            "abbreviations": abbrev,
            "formulas": {k: sp.sstr(explicit[k]) for k in QUANTITIES},
            "structured": {k: sp.sstr(structured[k]) for k in QUANTITIES},
        }
        return json.dumps(data, indent=2) + "\n"
    if fmt == "csv":
        lines = ["name,expression"] + [f'{k},"{sp.sstr(explicit[k])}"' for k in QUANTITIES]
        return "\n".join(lines) + "\n"
    if fmt == "md":
        out = [f"Domain: {FORMULA_DOMAIN}.", "", f"$V = {sp.latex(V_EXPR)}$, $P = {sp.latex(P_EXPR)}$", ""]
        out += [f"* `{k}`: ${sp.latex(structured[k])}$" for k in QUANTITIES]
        return "\n".join(out) + "\n"
    if fmt == "table":
        out = [f"Domain: {FORMULA_DOMAIN}.", f"where V = {abbrev['V']} (edges per robot)"]
        out.append(f"      P = {abbrev['P']} (pairs of edges sharing a node)")
        for k in QUANTITIES:
            out += ["", f"{k} ="]
            out += ["    " + line for line in sp.pretty(structured[k], use_unicode=True, wrap_line=False).splitlines()]
        return "\n".join(out) + "\n"
    raise ValueError(f"bad format {fmt!r}: expected one of {', '.join(FORMATS)}")


