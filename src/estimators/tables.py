"""Result rows and their text formats: rich table, Markdown, CSV and JSON.

A row is a plain dict (:func:`make_row`) with at least ``rows, cols, robots, p, rule, qubits, data_qubits,
ancillas, gates, cx, single_qubit, two_qubit, t, depth, two_qubit_depth`` (exact counts of the lowered circuit),
``toffoli`` and the labelled fault-tolerant estimates ``ft_t_toffoli7, ft_t_logical_and, ft_rotations,
ft_t_per_rotation, ft_epsilon``, and ``sections`` (section name -> counts, see :mod:`estimators.counts`). With
``compare_paper=True`` it also has the paper's estimate (:mod:`estimators.paper`): ``paper_qubits`` (``re + 8r``),
``paper_data_qubits`` (``re``), ``paper_cx``, ``paper_single_qubit`` and the ratios ours / paper
``ratio_qubits``, ``ratio_cx``, ``ratio_single_qubit``.

Formats: ``table`` (rich, the main columns that fit the terminal width, see :func:`render`), ``md`` (the same
columns as a Markdown table), ``csv`` (every scalar column plus ``section.<name>.<field>`` columns), ``json`` (a
list of row objects, sections nested).

Example:
    >>> from estimators.sweep import Point, sweep
    >>> rows = make_rows(sweep([Point(2, 2, 1, 1)], use_cache=False, progress=False), compare_paper=True)
    >>> rows[0]["cx"], rows[0]["paper_cx"], rows[0]["ratio_cx"]
    (52, 564, 0.0922)
    >>> render(rows, "csv").splitlines()[0].split(",")[:7]
    ['rows', 'cols', 'robots', 'p', 'rule', 'scenario', 'qubits']
"""

from __future__ import annotations

import csv
import io
import json
import shutil
from collections.abc import Iterable, Sequence
from typing import Any, Literal

from .paper import Doubling, paper_estimate
from .sweep import PointResult

__all__ = [
    "DROP_ORDER",
    "FORMATS",
    "MAIN_COLUMNS",
    "PAPER_COLUMNS",
    "Format",
    "make_row",
    "make_rows",
    "render",
    "table_columns",
    "terminal_width",
]

Format = Literal["table", "md", "csv", "json"]
FORMATS: tuple[Format, ...] = ("table", "md", "csv", "json")

MAIN_COLUMNS: tuple[str, ...] = (
    "rows",
    "cols",
    "robots",
    "p",
    "qubits",
    "data_qubits",
    "ancillas",
    "cx",
    "single_qubit",
    "t",
    "depth",
    "two_qubit_depth",
)
"""Columns of the ``table`` and ``md`` formats (plus :data:`PAPER_COLUMNS` when comparing)."""

PAPER_COLUMNS: tuple[str, ...] = ("paper_qubits", "paper_cx", "paper_single_qubit", "ratio_cx")

_SECTION_FIELDS = ("size", "cx", "single_qubit", "t", "depth", "two_qubit_depth")


def _ratio(ours: int, paper: int) -> float | None:
    return round(ours / paper, 4) if paper else None


def make_row(result: PointResult, compare_paper: bool = False, doubling: Doubling = "partial-mixer") -> dict[str, Any]:
    """One result as a row dict (see the module docstring for the keys).

    Args:
        result: a sweep result.
        compare_paper: add the paper's estimate and the ratios.
        doubling: the reading of the paper's doubling (:func:`estimators.paper.paper_partial_mixer`).

    Returns:
        The row.
    """
    pt, c, ft = result.point, result.counts, result.fault_tolerant
    row: dict[str, Any] = {
        "rows": pt.rows,
        "cols": pt.cols,
        "robots": pt.robots,
        "p": pt.p,
        "rule": pt.rule,
        "scenario": "default" if pt.scenario is None else "file",
        "qubits": c.qubits,
        "data_qubits": c.data_qubits,
        "ancillas": c.ancillas,
        "gates": c.size,
        "cx": c.cx,
        "single_qubit": c.single_qubit,
        "two_qubit": c.two_qubit,
        "t": c.t,
        "depth": c.depth,
        "two_qubit_depth": c.two_qubit_depth,
        "toffoli": ft.toffoli,
        "ft_t_toffoli7": ft.t_toffoli7,
        "ft_t_logical_and": ft.t_logical_and,
        "ft_rotations": ft.rotations,
        "ft_t_per_rotation": ft.t_per_rotation,
        "ft_epsilon": ft.epsilon,
        "ft_total_t_toffoli7": ft.total_t_toffoli7,
        "ft_total_t_logical_and": ft.total_t_logical_and,
    }
    if compare_paper:
        est = paper_estimate(pt.rows, pt.cols, pt.robots, pt.p, doubling)
        row.update(
            paper_qubits=est.qubits,
            paper_data_qubits=est.data_qubits,
            paper_cx=est.cx,
            paper_single_qubit=est.single_qubit,
            ratio_qubits=_ratio(c.qubits, est.qubits),
            ratio_cx=_ratio(c.cx, est.cx),
            ratio_single_qubit=_ratio(c.single_qubit, est.single_qubit),
        )
    row["sections"] = {name: s.to_dict() for name, s in c.sections.items()}
    return row


def make_rows(
    results: Iterable[PointResult], compare_paper: bool = False, doubling: Doubling = "partial-mixer"
) -> list[dict[str, Any]]:
    """:func:`make_row` of every result, in order."""
    return [make_row(r, compare_paper, doubling) for r in results]


def _columns(rows: Sequence[dict[str, Any]]) -> list[str]:
    cols = list(MAIN_COLUMNS)
    if rows and "paper_cx" in rows[0]:
        cols += list(PAPER_COLUMNS)
    return cols


def _cell(v: Any) -> str:
    if v is None:
        return ""
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def _flat(row: dict[str, Any]) -> dict[str, Any]:
    out = {k: v for k, v in row.items() if k != "sections"}
    for name, sec in row.get("sections", {}).items():
        for f in _SECTION_FIELDS:
            out[f"section.{name}.{f}"] = sec[f]
    return out


DROP_ORDER: tuple[str, ...] = (
    "two_qubit_depth",
    "data_qubits",
    "ancillas",
    "paper_single_qubit",
    "paper_qubits",
    "depth",
    "single_qubit",
    "t",
    "ratio_cx",
)
"""Columns the ``table`` format hides first, in order, when the terminal is too narrow for all of them."""


def terminal_width() -> int:
    """``$COLUMNS`` if set, else the width of the terminal on stdout, else 80."""
    return shutil.get_terminal_size((80, 24)).columns


def _rich_table(rows: Sequence[dict[str, Any]], cols: Sequence[str], paper: bool) -> Any:
    from rich.table import Table

    table = Table(title="Exact resource counts (lowered circuit)" + (" vs the paper" if paper else ""))
    for c in cols:
        table.add_column(c, justify="right")
    for r in rows:
        table.add_row(*(_cell(r.get(c)) for c in cols))
    return table


def _text(renderable: Any, width: int) -> str:
    from rich.console import Console

    buf = io.StringIO()
    Console(file=buf, width=width, force_terminal=False, color_system=None).print(renderable)
    return buf.getvalue()


def _natural_width(rows: Sequence[dict[str, Any]], cols: Sequence[str], paper: bool) -> int:
    text = _text(_rich_table(rows, cols, paper), 100_000)
    return max((len(line.rstrip()) for line in text.splitlines()), default=0)


def table_columns(
    rows: Sequence[dict[str, Any]],
    width: int | None = None,
    columns: Sequence[str] | None = None,
    wide: bool = False,
) -> tuple[list[str], list[str]]:
    """The columns of the ``table`` format and the default columns it hides.

    Args:
        rows: rows from :func:`make_rows`.
        width: characters available (default :func:`terminal_width`).
        columns: exactly these columns (any row key except ``sections``); overrides ``wide`` and ``width``.
        wide: every default column, however wide the table gets.

    Returns:
        ``(shown, hidden)``: the default columns (:data:`MAIN_COLUMNS`, plus :data:`PAPER_COLUMNS` when
        comparing) minus those of :data:`DROP_ORDER` that do not fit, and the hidden ones.

    Raises:
        ValueError: an unknown column name.
    """
    defaults = _columns(rows)
    if columns is not None:
        if not columns:
            raise ValueError("--columns: name at least one column")
        known = [k for k in (rows[0] if rows else dict.fromkeys(defaults)) if k != "sections"]
        for c in columns:
            if c not in known:
                raise ValueError(f"--columns: unknown column {c!r} (choose from {', '.join(known)})")
        return list(dict.fromkeys(columns)), []
    if wide:
        return defaults, []
    limit = terminal_width() if width is None else width
    paper = "paper_cx" in defaults
    shown = list(defaults)
    for c in DROP_ORDER:
        if _natural_width(rows, shown, paper) <= limit:
            break
        if c in shown:
            shown.remove(c)
    return shown, [c for c in defaults if c not in shown]


def render(
    rows: Sequence[dict[str, Any]],
    fmt: Format = "table",
    *,
    width: int | None = None,
    columns: Sequence[str] | None = None,
    wide: bool = False,
) -> str:
    """Rows as text in one of :data:`FORMATS`.

    Args:
        rows: rows from :func:`make_rows`.
        fmt: ``table`` (rich), ``md``, ``csv`` or ``json``.
        width: ``table`` only: fit this many characters (default :func:`terminal_width`); columns of
            :data:`DROP_ORDER` are hidden until the table fits, and a note names them. No line is longer.
        columns: ``table`` only: show exactly these columns (see :func:`table_columns`).
        wide: ``table`` only: show every default column, whatever the width.

    ``md``, ``csv`` and ``json`` always keep all their columns.

    Returns:
        The text (ending with a newline).

    Example:
        >>> rows = [{"rows": 3, "cols": 3, "robots": 1, "p": 1, "qubits": 26, "cx": 320}]
        >>> text = render(rows, "table", columns=["rows", "cols", "cx"])
        >>> [line.strip() for line in text.splitlines()][3]
        '┃ rows ┃ cols ┃  cx ┃'
    """
    if fmt == "json":
        return json.dumps(list(rows), indent=2) + "\n"
    if fmt == "csv":
        flat = [_flat(r) for r in rows]
        fields: list[str] = []
        for r in flat:
            fields.extend(k for k in r if k not in fields)
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        for r in flat:
            w.writerow({k: _cell(r.get(k)) if isinstance(r.get(k), float) else r.get(k, "") for k in fields})
        return buf.getvalue()
    if fmt == "md":
        cols = _columns(rows)
        lines = ["| " + " | ".join(cols) + " |", "|" + "|".join("---:" for _ in cols) + "|"]
        lines += ["| " + " | ".join(_cell(r.get(c)) for c in cols) + " |" for r in rows]
        return "\n".join(lines) + "\n"
    if fmt == "table":
        limit = terminal_width() if width is None else width
        shown, hidden = table_columns(rows, limit, columns, wide)
        paper = "paper_cx" in _columns(rows)
        table = _rich_table(rows, shown, paper)
        text_width = limit if columns is None and not wide else max(limit, _natural_width(rows, shown, paper))
        text = _text(table, text_width)
        if hidden:
            note = f"hidden to fit {limit} columns: {', '.join(hidden)} (--wide or --columns to show them; " \
                   "--format csv/json/md keep every column)"
            text += _text(note, limit)
        return text
    raise ValueError(f"unknown format {fmt!r} (expected one of {', '.join(FORMATS)})")
