"""What ``qcpp estimate`` does, as plain functions (the CLI only parses options and prints).

* :func:`points_from_options`: the ``--grid / --robots / -p / --scenario`` texts to points (and how many grid and
  robot-count pairs were skipped because the grid cannot host the robots);
* :func:`estimate_report`: estimates, rows, optional paper comparison and plot, rendered in one format, as a
  stream of text pieces (rows appear as soon as they are computed, except in the ``table`` format);
* :func:`formula_report`: the closed-form formulas (:mod:`qcpp.estimators.formulas`) as text.

Example:
    >>> pts = points_from_options("2x2..2x3", "1", "1")
    >>> [p.label for p in pts.points], pts.skipped
    (['2x2 r1 p1', '2x3 r1 p1'], 0)
    >>> text = "".join(estimate_report(points_from_options("2x2", "1", "1").points, fmt="csv"))
    >>> text.splitlines()[1].split(",")[:7]
    ['2', '2', '1', '1', 'exact', 'nisq', 'default']
"""

from __future__ import annotations

import json
import os
import textwrap
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from qcpp.estimators.estimate import DEFAULT_OPTIONS, Estimate, EstimateOptions, Point
from qcpp.estimators.paper import Doubling
from qcpp.estimators.plots import plot_rows
from qcpp.estimators.sweep import grid_points, parse_grid_range, parse_int_range, skipped_points, sweep
from qcpp.estimators.tables import FORMATS, Format, latex_escape, make_row, render_stream, terminal_width
from qcpp.hardware.device import Device, device_arg
from qcpp.problem.errors import ScenarioError
from qcpp.problem.limits import check_grid_size, check_layers
from qcpp.problem.presets import grid_scenario, max_default_robots
from qcpp.problem.scenario_io import load_scenario
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions

__all__ = ["DEFAULT_GRID", "PointSet", "estimate_report", "estimate_rows", "formula_report", "points_from_options"]

DEFAULT_GRID = "3x3"


@dataclass(frozen=True)
class PointSet:
    """Points to estimate and the number of (grid, robots, p) combinations left out.

    Attributes:
        points: the points, grid-major.
        skipped: combinations whose grid cannot host the robot count (default placement).
    """

    points: list[Point]
    skipped: int


def points_from_options(
    grid: str | None,
    robots: str | None,
    p: str,
    scenario: str | os.PathLike[str] | None = None,
    obstacles: Sequence[tuple[int, int]] = (),
    hard_obstacles: bool = False,
    endpoints: Sequence[tuple[tuple[int, int], tuple[int, int]]] = (),
    *,
    scenario_named: str = "--scenario",
) -> PointSet:
    """Points from the CLI's option texts.

    Args:
        grid: ``3x4``, ``AxB..CxD`` (every rows in A..C and cols in B..D) or a comma list; ``None`` means
            ``3x3``. Must be ``None`` with ``scenario``.
        robots: ``N``, ``A..B`` or a comma list of them; ``None`` means ``1``. Must be ``None`` with ``scenario``.
        p: ``N``, ``A..B`` or a comma list of them: the layers.
        scenario: a scenario file to estimate instead of the default scenarios.
        obstacles: obstacles on every grid of the range (``--obstacle``): each point is then the scenario
            :func:`qcpp.problem.presets.grid_scenario` builds (``scenario: "custom"`` in its row, as a scenario
            file's), not a default one.
        hard_obstacles: the obstacles remove the edges touching them from the variables (``--hard-obstacles``;
            a non-default scenario even without obstacles).
        endpoints: each robot's ``(start, goal)`` on every grid of the range (``--robot``), instead of ``robots``.
        scenario_named: how the messages name the scenario file as the user gave it (``--scenario``, or
            ``the scenario file 'a.toml'`` for a positional file).

    Raises:
        ValueError: a malformed range (``qcpp.problem.errors.ScenarioError`` for a bad file, or when no grid of the
            range can host the robots).
    """
    layers = parse_int_range(p, "-p/--layers", 1)  # each error names the option as every command names it
    for k in layers:
        check_layers(k, "-p/--layers")  # the same layer limit as every other command (--allow-large lifts it)
    if endpoints and robots is not None:
        raise ValueError("--robot gives the robots one by one: do not give --robots too")
    if scenario is not None:
        if endpoints:
            raise ValueError(f"{scenario_named} gives the robots: do not combine it with --robot")
        if grid is not None or robots is not None:
            raise ValueError(
                f"{scenario_named} gives the grid and the robots: do not combine it with --grid or --robots"
            )
        if obstacles or hard_obstacles:
            flag = "--obstacle" if obstacles else "--hard-obstacles"
            raise ValueError(f"{scenario_named} gives the obstacles: do not combine it with {flag}")
        s = load_scenario(scenario, check_range=True)
        return PointSet([Point.from_scenario(s, k) for k in layers], 0)
    grids = parse_grid_range(grid if grid is not None else DEFAULT_GRID, "--grid")
    for r, c in grids:
        check_grid_size(r, c, "--grid")  # before any scenario of a huge grid is built
    if endpoints:  # the robots' own endpoints on every grid: not bound by the default placement's capacity
        points, skipped = [Point(r, c, len(endpoints), k) for r, c in grids for k in layers], 0
    else:
        ks = parse_int_range(robots if robots is not None else "1", "--robots", 1)
        points, skipped = grid_points(grids, ks, layers), skipped_points(grids, ks, layers)
        if not points:
            most = max(max_default_robots(r, c) for r, c in grids)
            raise ScenarioError(
                "--robots",
                f"{grid or DEFAULT_GRID} hosts at most {most} (one per boundary node), got {min(ks)}; "
                "use --robot or --scenario",
            )
    if obstacles or hard_obstacles or endpoints:  # every point's own scenario, built as qcpp.grid_scenario builds it
        points = [
            Point.from_scenario(
                grid_scenario(
                    pt.rows, pt.cols, robots=list(endpoints) or pt.robots, obstacles=obstacles,
                    hard_obstacles=hard_obstacles,
                ),
                pt.p,
            )
            for pt in points
        ]
    return PointSet(points, skipped)


def estimate_report(
    points: Iterable[Point],
    fmt: Format = "table",
    options: EstimateOptions = DEFAULT_OPTIONS,
    compare_paper: bool = False,
    plot: str | os.PathLike[str] | None = None,
    doubling: Doubling = "partial-mixer",
    columns: Sequence[str] | None = None,
    wide: bool = False,
    device: str | Device | None = None,
    stage: Callable[[str], None] | None = None,
    metric: str = "cx",
    routing: RoutingOptions = DEFAULT_ROUTING,
) -> Iterator[str]:
    """Estimate ``points`` and render the rows, as a stream of text pieces.

    Args:
        points: from :func:`points_from_options` (any iterable: it is consumed lazily, in order).
        fmt: one of :data:`qcpp.estimators.tables.FORMATS`.
        options: what to estimate.
        compare_paper: add the paper's estimates and ratios.
        plot: also write the plot of ``metric`` here (:func:`qcpp.estimators.plots.plot_rows`; with the paper's
            curves when ``compare_paper``). The rows are then estimated before any is rendered (the plot needs
            them all), and the plot is written after the last piece is yielded, so a plot that cannot be written
            (a full disk) fails after the consumer has every row.
        doubling: reading of the paper's doubling.
        columns, wide: the columns shown (:func:`qcpp.estimators.tables.render`).
        device: add the routed figures on this device (:func:`qcpp.estimators.routed.routed_fields`).
        stage: called with the stage of a row's routing as it starts (progress inside a long row; ``""`` when the
            row is done), and with ``drawing the plot`` before the plot is drawn.
        metric: the column the plot shows (:data:`qcpp.estimators.plots.PLOT_METRICS`).
        routing: the routing settings of the rows' compiles on ``device`` (:func:`estimate_rows`).

    Yields:
        Text pieces (see :func:`qcpp.estimators.tables.render_stream`).
    """
    if fmt not in FORMATS:
        raise ValueError(f"bad format {fmt!r}: expected one of {', '.join(FORMATS)}")
    rows = estimate_rows(points, options, compare_paper, doubling, device, stage, routing=routing)
    if plot is None:
        yield from render_stream(rows, fmt, columns=columns, wide=wide)
        return
    kept = list(rows)  # a plot needs every row
    yield from render_stream(kept, fmt, columns=columns, wide=wide)
    if stage is not None:
        stage("drawing the plot")
    plot_rows(kept, plot, metric, compare_paper=compare_paper)


def estimate_rows(
    points: Iterable[Point],
    options: EstimateOptions = DEFAULT_OPTIONS,
    compare_paper: bool = False,
    doubling: Doubling = "partial-mixer",
    device: str | Device | None = None,
    stage: Callable[[str], None] | None = None,
    context: RoutingContext | None = None,
    routing: RoutingOptions = DEFAULT_ROUTING,
) -> Iterator[dict[str, Any]]:
    """The rows of ``qcpp estimate`` (:func:`qcpp.estimators.tables.make_row`, plus the routed fields with a
    ``device``), one per point, lazily: what :func:`estimate_report` renders and ``qcpp.estimate`` returns.

    Args:
        points: The points (consumed lazily, in order).
        options: What to estimate.
        compare_paper: Add the paper's estimates and ratios.
        doubling: Reading of the paper's doubling.
        device: Add the routed figures on this device.
        stage: Called with the stage of a row's routing as it starts (``""`` when the row is done).
        context: The routing memos the rows share (default: a fresh one for this sweep, keeping no whole compile:
            its rows do not repeat).
        routing: The routing settings of the rows' compiles on ``device`` (``qcpp estimate --effort``:
            :func:`qcpp.routing.options.effort_routing`; :func:`qcpp.estimators.routed.routed_fields`).

    Yields:
        One row per point, in order.
    """
    if context is None and device is not None:  # one run: later rows reuse the routing memos
        context = RoutingContext(compiles_kept=0)
    device = None if device is None else device_arg(device)  # a device file read once for every row
    for est in sweep(points, options):
        yield _row(est, compare_paper, doubling, device, stage, context, routing)


def _row(
    est: Estimate, compare_paper: bool, doubling: Doubling, device: str | Device | None,
    stage: Callable[[str], None] | None = None, context: RoutingContext | None = None,
    routing: RoutingOptions = DEFAULT_ROUTING,
) -> dict[str, Any]:  # fmt: skip
    row = make_row(est, compare_paper, doubling)
    if device is None:
        return row
    from qcpp.estimators.routed import routed_fields

    c = est.cost
    extra = routed_fields(
        est.point.build_scenario(), est.point.p, est.options.plan, device, qubits=est.qubits, cx=c.two_qubit,
        one_qubit=c.single_qubit, total_gates=c.total, stage=stage, context=context, routing=routing,
    )  # fmt: skip
    return {**row, **extra}


def formula_report(fmt: Format = "table", width: int | None = None) -> str:
    """The formulas of :mod:`qcpp.estimators.formulas` as text.

    ``table``: pretty-printed structured forms (data qubits with ``V``); ``md``: LaTeX in Markdown; ``csv``:
    ``name,expression`` (explicit forms); ``json``: ``{"domain", "abbreviations", "formulas", "structured"}``;
    ``latex``: an ``align*`` environment of the structured forms.

    Args:
        fmt: one of :data:`qcpp.estimators.tables.FORMATS`.
        width: ``table`` only: the characters per line (default :func:`qcpp.io.text.terminal_width`);
            a longer formula continues on the next lines, as sympy's pretty printer breaks it.

    >>> json.loads(formula_report("json"))["formulas"]["partial_mixers"]
    'p*robots*(cols - 1)*(rows - 1)'
    """
    import sympy as sp  # slow to import: only the formulas need it, not the estimates

    from qcpp.estimators.formulas import FORMULA_DOMAIN, QUANTITIES, V_EXPR, formula_table

    explicit, structured = formula_table(), formula_table(structured=True)
    abbrev = {"V": sp.sstr(V_EXPR)}
    if fmt in ("json", "jsonl"):
        data = {
            "domain": FORMULA_DOMAIN,
            "abbreviations": abbrev,
            "formulas": {k: sp.sstr(explicit[k]) for k in QUANTITIES},
            "structured": {k: sp.sstr(structured[k]) for k in QUANTITIES},
        }
        return json.dumps(data, indent=2 if fmt == "json" else None) + "\n"
    if fmt == "csv":
        lines = ["name,expression"] + [f'{k},"{sp.sstr(explicit[k])}"' for k in QUANTITIES]
        return "\n".join(lines) + "\n"
    if fmt == "md":
        out = [f"Domain: {FORMULA_DOMAIN}.", "", f"$V = {sp.latex(V_EXPR)}$", ""]
        out += [f"* `{k}`: ${sp.latex(structured[k])}$" for k in QUANTITIES]
        return "\n".join(out) + "\n"
    if fmt == "latex":
        lines = [f"V &= {sp.latex(V_EXPR)}"]
        lines += [rf"\mathrm{{{latex_escape(k)}}} &= {sp.latex(structured[k])}" for k in QUANTITIES]
        body = " \\\\\n".join(lines)
        return "\n".join([f"% Domain: {FORMULA_DOMAIN}.", r"\begin{align*}", body, r"\end{align*}"]) + "\n"
    if fmt == "table":
        limit = max(terminal_width() if width is None else width, 20)
        out = textwrap.wrap(f"Domain: {FORMULA_DOMAIN}.", limit, break_long_words=False, break_on_hyphens=False)
        out += textwrap.wrap(f"where V = {abbrev['V']} (edges per robot)", limit, break_on_hyphens=False)
        for k in QUANTITIES:
            text = sp.pretty(structured[k], use_unicode=True, wrap_line=True, num_columns=limit - 4)
            out += ["", f"{k} ="] + ["    " + line.rstrip() for line in text.splitlines()]
        return "\n".join(out) + "\n"
    raise ValueError(f"bad format {fmt!r}: expected one of {', '.join(FORMATS)}")
