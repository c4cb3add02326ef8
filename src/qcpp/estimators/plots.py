"""Plots of estimate rows: one metric (a numeric column of ``qcpp estimate``'s row) against the grid, ``p`` or robots.

What the plot shows depends on what the rows vary (the reading that needs no legend to decode):

* several grid sizes: the metric against the grid's number of nodes ``rows * cols`` (log axis when the sizes span
  a factor of 8 or more), one curve per robot count, **one panel per p** (panels share the y axis, so the growth
  with ``p`` reads across them);
* one grid size and several ``p``: the metric against ``p``, one curve per robot count, one panel;
* one grid and one ``p``: the metric against the robot count.

Every row is its own point; a point that is not exact (a bound: a ``bound`` depth, the routed figures of a bounded
routing, its ESP a lower bound; or a physical figure computed from a depth bound: what the table marks ``<=``,
``>=`` or ``~``) is drawn hollow, and the legend says so (:data:`BOUND_LABEL`). Grids of one size but different
shapes (``2x6``, ``3x4``, ``4x3``) need different circuits, so a curve that holds several of them is drawn as points
alone, without a line (it would zigzag between the shapes), and the axis label says so; so are several scenarios of
one grid (other obstacles or endpoints), which the label names as such.

The paper's estimates (:mod:`qcpp.estimators.paper`) are drawn only when asked (``compare_paper=True``), as dashed
lines in the colour of the same robot count; the paper estimates qubits, data qubits, CNOTs and single-qubit gates
only, so for any other metric the plot shows ours alone (with a warning). The y axis names the metric, its column
and its unit (log scale when the values span a factor of 20 or more), the legend the column and the unit, the
title the metric and what the rows hold fixed. Rows without a value for the metric (``depth`` with ``--depth
none``, ``duration_s`` on a device without gate times) are left out.

Example:
    >>> import tempfile, os
    >>> from qcpp.estimators.estimate import Point, estimate_point
    >>> from qcpp.estimators.tables import make_rows
    >>> rows = make_rows([estimate_point(Point(2, 2, 1, 1)), estimate_point(Point(2, 3, 1, 1))], True)
    >>> path = os.path.join(tempfile.mkdtemp(), "plot.png")
    >>> plot_rows(rows, path, metric="t") == path, os.path.getsize(path) > 1000
    (True, True)
    >>> plot_metric("cnots")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: metric: expected qubits or data_qubits or ... or esp_idle, got 'cnots'
"""

from __future__ import annotations

import os
import warnings
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

from qcpp.errors import check_choice
from qcpp.estimators.paper import paper_estimate
from qcpp.io.atomic import save_figure_atomic
from qcpp.io.caches import use_writable_matplotlib_config

__all__ = ["BOUND_LABEL", "PLOT_METRICS", "PlotMetric", "draw_rows", "not_exact", "plot_metric", "plot_rows"]

BOUND_LABEL = "hollow: a bound, not exact"
"""The legend entry of the hollow markers: points that are bounds or computed from a depth bound
(:func:`not_exact`; the table marks the same cells ``<=``, ``>=`` or ``~``)."""

Needs = Literal["physical", "device", "depth"]


@dataclass(frozen=True)
class PlotMetric:
    """A column of the estimate row that a plot can show.

    Attributes:
        column: the row's column (``cx``).
        label: what it counts, for the axis (``CNOT gates``).
        unit: its unit (``gates``, ``qubits``, ``s``; empty for a probability).
        needs: what must be estimated for the column to exist: ``physical`` (``--physical``), ``device``
            (``--device``) or ``depth`` (a ``--depth`` other than ``none``); ``None``: always there.
        paper: the column of the paper's estimate of the same quantity (``paper_cx``), if the paper gives one.
    """

    column: str
    label: str
    unit: str
    needs: Needs | None = None
    paper: str | None = None

    @property
    def axis_label(self) -> str:
        """``CNOT gates: cx [gates]``: what, which column, which unit."""
        return f"{self.label}: {self.column}" + (f" [{self.unit}]" if self.unit else "")


PLOT_METRICS: dict[str, PlotMetric] = {
    m.column: m
    for m in (
        PlotMetric("qubits", "logical qubits", "qubits", paper="paper_qubits"),
        PlotMetric("data_qubits", "data qubits", "qubits", paper="paper_data_qubits"),
        PlotMetric("ancillas", "ancilla qubits", "qubits"),
        PlotMetric("gates", "gates (lowered)", "gates"),
        PlotMetric("cx", "CNOT gates", "gates", paper="paper_cx"),
        PlotMetric("single_qubit", "single-qubit gates", "gates", paper="paper_single_qubit"),
        PlotMetric("two_qubit", "two-qubit gates", "gates"),
        PlotMetric("t", "T gates (lowered)", "gates"),
        PlotMetric("rotations", "arbitrary-angle rotations", "gates"),
        PlotMetric("depth", "circuit depth", "layers", needs="depth"),
        PlotMetric("two_qubit_depth", "two-qubit depth", "layers", needs="depth"),
        PlotMetric("rotation_depth", "rotation depth", "layers", needs="depth"),
        PlotMetric("toffoli", "Toffoli-class gates", "gates"),
        PlotMetric("ft_total_t", "T gates, fault-tolerant model", "gates"),
        PlotMetric("physical_qubits", "physical qubits", "qubits", needs="physical"),
        PlotMetric("physical_runtime_s", "physical runtime", "s", needs="physical"),
        PlotMetric("physical_t_factories", "T factories", "factories", needs="physical"),
        PlotMetric("routed_twoq", "two-qubit gates after routing", "gates", needs="device"),
        PlotMetric("routed_depth", "depth after routing", "layers", needs="device"),
        PlotMetric("routed_twoq_depth", "two-qubit depth after routing", "layers", needs="device"),
        PlotMetric("duration_s", "duration on the device", "s", needs="device"),
        PlotMetric("esp", "estimated success probability", "", needs="device"),
        PlotMetric("esp_idle", "estimated success probability with idle decoherence", "", needs="device"),
    )
}
"""The metrics a plot can show, by column name (the columns are described in :mod:`qcpp.estimators.tables`)."""


def plot_metric(name: str, flag: str = "metric") -> PlotMetric:
    """The metric of that name.

    Raises:
        qcpp.errors.OptionError: an unknown name, naming ``flag`` and listing :data:`PLOT_METRICS`.
    """
    check_choice(name, PLOT_METRICS, flag)
    return PLOT_METRICS[name]


def _paper_value(row: dict[str, Any], column: str) -> float:
    if column in row:
        return float(row[column])
    est = paper_estimate(row["rows"], row["cols"], row["robots"], row["p"])
    return float(getattr(est, column.removeprefix("paper_")))


def _series(
    rows: Sequence[dict[str, Any]], x: str, value: Any, column: str | None = None
) -> dict[int, tuple[list[float], list[float], list[bool]]]:
    """robots -> (xs, ys, from_bound): ``value(row)`` against ``x`` (``nodes``, ``p`` or ``robots``), one point per
    row, in order of ``x`` (then of the grid's rows: ``2x6`` before ``3x4``); ``from_bound`` says which points of
    ``column`` are not exact (:func:`not_exact`)."""
    acc: dict[int, list[tuple[float, int, float, bool]]] = defaultdict(list)
    for r in rows:
        y = value(r)
        if y is None:
            continue
        key = 0 if x == "robots" else r["robots"]  # against robots: one curve
        at = r["rows"] * r["cols"] if x == "nodes" else r[x]
        acc[key].append((at, r["rows"], float(y), column is not None and not_exact(r, column)))
    points = {k: sorted(v) for k, v in sorted(acc.items())}
    return {k: ([a for a, _, _, _ in v], [y for _, _, y, _ in v], [b for *_, b in v]) for k, v in points.items()}


def not_exact(row: dict[str, Any], column: str) -> bool:
    """Whether ``row``'s ``column`` is not exact: an upper bound (a ``bound`` depth, the routed figures of a bounded
    routing), a lower bound (that routing's ESP) or a physical figure computed from a depth bound; drawn as a
    hollow marker, the cells the table marks.

    >>> not_exact({"physical_qubits": 9, "physical_depth_kind": "bound"}, "physical_qubits")
    True
    >>> not_exact({"routed_twoq": 90, "routed_kind": "bound"}, "routed_twoq"), not_exact({"esp": 0.2, "routed_kind":
    ...     "bound"}, "esp")
    (True, True)
    >>> not_exact({"depth": 9, "depth_kind": "exact"}, "depth"), not_exact({"cx": 9}, "cx")
    (False, False)
    """
    from qcpp.estimators.tables import APPROXIMATE_BY, BOUNDED_BY, LOWER_BOUNDED_BY

    if row.get(column) is None:
        return False
    for kinds in (BOUNDED_BY, LOWER_BOUNDED_BY):
        if column in kinds:
            return row.get(kinds[column]) == "bound"
    return column in APPROXIMATE_BY and row.get(APPROXIMATE_BY[column]) != "exact"


def _shares_x(xs: Sequence[float]) -> bool:
    """Two points at one ``x`` (grids of one size: module docs)."""
    return len(set(xs)) < len(xs)


def _shared_x_note(rows: Sequence[dict[str, Any]], x: str) -> str:
    """The axis label's note where points of one curve share an ``x``, naming what sets them apart.

    Points of one curve (one robot count) at one ``x`` are grids of one size but other shapes (``3x4``, ``4x3``),
    or scenarios of one grid (other obstacles or endpoints, which the rows do not name): the note says which, so
    that a stack of points is not read as something it is not.

    Args:
        rows: the rows of one panel that have a value for the plotted metric.
        x: the axis, as :func:`_series` takes it (``nodes``, ``p`` or ``robots``).

    Returns:
        ``""`` when no two points of a curve share an ``x``, else a second label line.

    Example:
        >>> a = {"rows": 3, "cols": 4, "robots": 1, "p": 1}
        >>> _shared_x_note([a, {**a, "rows": 4, "cols": 3}], "nodes")
        '\\nseveral grids of one size: a point each'
        >>> _shared_x_note([a, a], "robots"), _shared_x_note([a], "p")
        ('\\nseveral scenarios of one grid: a point each', '')
    """
    at: dict[tuple[int, int], list[tuple[int, int]]] = defaultdict(list)
    for r in rows:
        key = 0 if x == "robots" else r["robots"]
        at[key, r["rows"] * r["cols"] if x == "nodes" else r[x]].append((r["rows"], r["cols"]))
    stacks = [grids for grids in at.values() if len(grids) > 1]
    kinds = [
        kind
        for kind, seen in (
            ("grids of one size", any(len(set(g)) > 1 for g in stacks)),
            ("scenarios of one grid", any(len(set(g)) < len(g) for g in stacks)),
        )
        if seen
    ]
    return f"\nseveral {' or '.join(kinds)}: a point each" if kinds else ""


def _style(xs: Sequence[float], line: str) -> str:
    """``line`` (``o-``), or its marker alone where two points share an ``x`` (:func:`_shares_x`)."""
    return line.rstrip("-") if _shares_x(xs) else line


def _robots(k: int) -> str:
    return f"{k} robot{'s' if k != 1 else ''}"


def draw_rows(
    rows: Sequence[dict[str, Any]],
    metric: str = "cx",
    *,
    compare_paper: bool = False,
    figsize: tuple[float, float] | None = None,
) -> Any:
    """Draw ``metric`` of ``rows`` (the layout of the module docstring) on a new matplotlib figure.

    Args:
        rows: rows of ``qcpp estimate`` (:func:`qcpp.estimators.tables.make_row`, ``Estimate.to_dict()``), of
            one SBF rule (the first row's; others are left out).
        metric: one of :data:`PLOT_METRICS`.
        compare_paper: also draw the paper's estimates of the metric (computed if the rows lack them).
        figsize: the figure's size in inches (default: about 5.5 by 4 per panel).

    Returns:
        The ``matplotlib.figure.Figure`` (not attached to pyplot: nothing to close).

    Raises:
        qcpp.errors.OptionError: an unknown metric.
        ValueError: no rows, or no row with a value for the metric (naming the option it needs).
    """
    m = plot_metric(metric)
    if not rows:
        raise ValueError("nothing to plot: no rows")
    rule = rows[0].get("rule", "exact")
    sel = [r for r in rows if r.get("rule", "exact") == rule]
    if not any(r.get(m.column) is not None for r in sel):
        need = {"physical": " (estimate with --physical, or physical=True in Python)",
                "device": " (estimate with --device, or device= in Python)",
                "depth": " (the depth was not computed: --depth none?)"}.get(m.needs or "", "")  # fmt: skip
        raise ValueError(f"nothing to plot: no row has a value for {m.column}{need}")
    paper = m.paper if compare_paper else None
    if compare_paper and m.paper is None:
        warnings.warn(f"the paper gives no estimate of {m.column}: the plot shows ours only", stacklevel=2)

    use_writable_matplotlib_config()  # before matplotlib picks its folders
    from matplotlib.figure import Figure
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    nodes = {r["rows"] * r["cols"] for r in sel}
    layers = sorted({r["p"] for r in sel})
    x = "nodes" if len(nodes) > 1 else "p" if len(layers) > 1 else "robots"
    panels = layers if x == "nodes" else [None]
    ncols = min(len(panels), 3)
    nrows = -(-len(panels) // ncols)
    fig = Figure(figsize=figsize or (1.9 + 4.4 * ncols, 0.5 + 3.6 * nrows), layout="constrained")
    grid = fig.subplots(nrows, ncols, sharey=True, squeeze=False)
    axes = list(grid.flat)
    for spare in axes[len(panels):]:
        spare.set_visible(False)
    colours = [f"C{i}" for i in range(10)]
    values = [float(r[m.column]) for r in sel if r.get(m.column) is not None]
    if paper is not None:
        values += [_paper_value(r, paper) for r in sel]
    positive = [v for v in values if v > 0]
    log_y = bool(positive) and len(positive) == len(values) and max(positive) >= 20 * min(positive)
    approximate = False  # a hollow marker drawn: the legend says what it means
    for ax, p in zip(axes, panels):
        here = [r for r in sel if p is None or r["p"] == p]
        ours = _series(here, x, lambda r: r.get(m.column), m.column)
        theirs = _series(here, x, lambda r: _paper_value(r, paper)) if paper is not None else {}
        for i, (k, (xs, ys, bound)) in enumerate(ours.items()):
            colour = colours[i % len(colours)]
            who = _robots(k) if x != "robots" else ""
            ours_label = ", ".join(filter(None, ("ours" if paper else "", who))) or "qcpp"
            ax.plot(xs, ys, _style(xs, "o-"), ms=4, color=colour, label=ours_label)
            if any(bound):  # not exact: hollow markers over the filled ones
                bx = [a for a, b in zip(xs, bound) if b]
                by = [y for y, b in zip(ys, bound) if b]
                ax.plot(bx, by, "o", ms=4, color=colour, markerfacecolor="white", zorder=3)
                approximate = True
            if k in theirs:
                pxs, pys, _ = theirs[k]
                ax.plot(pxs, pys, _style(pxs, "x--"), ms=5, color=colour, alpha=0.75,
                        label=", ".join(filter(None, ("paper", who))))
        apart = _shared_x_note([r for r in here if r.get(m.column) is not None], x)
        if x == "nodes":
            log_x = max(nodes) >= 8 * min(nodes)
            if log_x:
                ax.set_xscale("log")
                ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
                ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
                ax.xaxis.set_minor_formatter(NullFormatter())
            ax.set_xlabel("grid nodes (rows x cols)" + (", log scale" if log_x else "") + apart)
        else:
            ax.set_xlabel(("QAOA layers p" if x == "p" else "robots") + apart)
            ticks = sorted({r[x] for r in here})
            ax.set_xticks(ticks if len(ticks) <= 12 else ticks[:: -(-len(ticks) // 12)])
        if log_y:
            ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        if p is not None and len(panels) > 1:
            ax.set_title(f"p = {p}", fontsize=10)
    for row in grid:
        row[0].set_ylabel(m.axis_label + (", log scale" if log_y else ""))
    legend_title = m.column + (f" [{m.unit}]" if m.unit else "")
    # beside the panels, never over a point (inside, matplotlib's "best" spot still covers points in a corner)
    handles, labels = axes[0].get_legend_handles_labels()
    if approximate:
        from matplotlib.lines import Line2D

        handles.append(Line2D([], [], ls="", marker="o", ms=4, color="0.3", markerfacecolor="white"))
        labels.append(BOUND_LABEL)
    fig.legend(handles, labels, loc="outside right upper", fontsize=7, title=legend_title, title_fontsize=7,
               ncol=2 if len(handles) > 16 else 1)  # fmt: skip
    fig.suptitle(f"{m.label}{_where(sel, x, layers)}" + (f", rule {rule}" if rule != "exact" else ""))
    return fig


def _where(rows: Sequence[dict[str, Any]], x: str, layers: list[int]) -> str:
    """The fixed part of the rows, for the title: the grid when it does not vary, ``p`` when one."""
    parts = []
    if x != "nodes":
        grids = sorted({f"{r['rows']}x{r['cols']}" for r in rows})
        parts.append(f"{', '.join(grids)} grid")
    if len(layers) == 1:
        parts.append(f"p = {layers[0]}")
    return (", " + ", ".join(parts)) if parts else ""


def plot_rows(
    rows: Sequence[dict[str, Any]],
    path: str | os.PathLike[str],
    metric: str = "cx",
    *,
    compare_paper: bool = False,
) -> str:
    """Draw ``metric`` of ``rows`` (:func:`draw_rows`) and save it atomically (temporary file + ``os.replace``;
    the format from the suffix, default PNG).

    Args:
        rows: rows of ``qcpp estimate``.
        path: output file (its folder must exist).
        metric: one of :data:`PLOT_METRICS`.
        compare_paper: also draw the paper's estimates.

    Returns:
        The path written, as a string.

    Raises:
        ValueError: as :func:`draw_rows`.
    """
    fig = draw_rows(rows, metric, compare_paper=compare_paper)
    target = os.fspath(path)
    save_figure_atomic(fig, target, dpi=120)  # the folder must exist (qcpp.io.atomic: one rule for every output)
    return target
