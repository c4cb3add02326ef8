"""Result rows and their text formats: rich table, Markdown, CSV, JSON and JSON lines, streamed where possible.

A row is a plain dict (:func:`make_row`) with

* the point and options: ``rows, cols, robots, p, rule, target, scenario``; ``first_phase`` (``False``) only in a
  row built without the first phase separator (:attr:`qcpp.plan.options.PlanOptions.first_phase`);
* exact counts of the lowered circuit, from the gadgets' costs: ``qubits, data_qubits, ancillas, gates, cx,
  single_qubit, two_qubit, t, rotations``; ``depth, two_qubit_depth, rotation_depth`` with ``depth_kind``
  (``exact``: computed on the compiled circuit; ``bound``: an upper bound, see :mod:`qcpp.estimators.estimate`;
  empty: not computed);
* the labelled fault-tolerant estimates (logical-AND model, :mod:`qcpp.estimators.fault_tolerant`): ``toffoli``
  (ANDs, their uncomputes and full Toffolis), ``ft_and``, ``ft_toffoli_full``, ``ft_measurements``,
  ``ft_rotations``, ``ft_t_per_rotation``, ``ft_epsilon``, ``ft_toffoli_t``, ``ft_t_logic``, ``ft_total_t``;
* with ``--physical``, the QDK resource estimator's figures (:mod:`qcpp.estimators.physical`): ``physical_qubits,
  physical_runtime_s, physical_algorithm_qubits, physical_t_factory_qubits, physical_t_factories,
  physical_t_states, physical_code_distance, physical_model`` (``qubit model / QEC scheme / error budget``) and
  ``physical_depth_kind``: the rotation depth they were computed from (``exact``; ``bound``: the upper bound of
  ``rotation_depth``; ``rotation_count``: the rotation count, with no depth computed);
* with ``compare_paper=True``, the paper's estimate (:mod:`qcpp.estimators.paper`): ``paper_qubits``,
  ``paper_data_qubits``, ``paper_cx``, ``paper_single_qubit`` and the ratios ``ratio_qubits``, ``ratio_cx``,
  ``ratio_single_qubit``;
* ``sections``: per-layer lowered costs of ``initial_state``, ``phase`` (one layer) and ``mixer`` (one layer).

Formats: ``table`` (rich, the main columns that fit the terminal, :func:`render`), ``md``, ``csv`` (every scalar
column plus ``section.<name>.<field>``), ``json`` and ``jsonl``; :func:`render_stream` yields text as rows arrive
for every format but ``table``.

In the formats read by people (``table``, ``md``, ``latex``) a figure that is an upper bound is marked in its cell,
``<=9087`` (:data:`BOUND_MARK`): the depths when ``depth_kind`` is ``bound``, the routed depths and the duration when
``routed_depth_kind`` is ``bound``, the routed two-qubit count when ``routed_kind`` is ``bound``
(:data:`BOUNDED_BY`), whether or not the kind column is shown; the ESP of such a row, computed from that bound of
gates, is a lower bound, ``>=1.2e-05`` (:data:`LOWER_BOUND_MARK`, :data:`LOWER_BOUNDED_BY`). An ESP below the
smallest double (``esp`` ``0.0``) is shown from its log, ``log10_esp`` (``2.818e-1235``). A physical figure
computed from a rotation depth that is not exact is neither exact nor a bound (a longer depth may lower it) and is
marked approximate, ``~81922666`` (:data:`APPROX_MARK`, :data:`APPROXIMATE_BY`). ``csv``, ``json`` and ``jsonl`` keep
the plain number and the kind field.

The default columns depend on the target: ``ft`` adds the fault-tolerant figures (:data:`FT_COLUMNS`).

Example:
    >>> from qcpp.estimators.estimate import Point, estimate_point
    >>> rows = make_rows([estimate_point(Point(2, 2, 1, 1))], compare_paper=True)
    >>> rows[0]["cx"], rows[0]["paper_cx"], rows[0]["ratio_cx"], rows[0]["depth_kind"]
    (10, 564, 0.0177, 'exact')
    >>> render(rows, "csv").splitlines()[0].split(",")[:7]
    ['rows', 'cols', 'robots', 'p', 'rule', 'target', 'scenario']
"""

from __future__ import annotations

import csv
import difflib
import io
import json
import math
import sys
import textwrap
from collections.abc import Iterable, Iterator, Sequence
from typing import Any, Literal

from qcpp.estimators.estimate import Estimate
from qcpp.estimators.paper import Doubling, paper_estimate
from qcpp.io.text import terminal_width
from qcpp.ir.cost import Cost

__all__ = [
    "APPROXIMATE_BY",
    "APPROX_MARK",
    "BOUNDED_BY",
    "BOUND_MARK",
    "DROP_ORDER",
    "FORMATS",
    "FT_COLUMNS",
    "FT_DROP_ORDER",
    "LATEX_HEADERS",
    "LOWER_BOUNDED_BY",
    "LOWER_BOUND_MARK",
    "MAIN_COLUMNS",
    "PAPER_COLUMNS",
    "PHYSICAL_COLUMNS",
    "PHYSICAL_DROP_ORDER",
    "Format",
    "latex_escape",
    "latex_header",
    "latex_number",
    "make_row",
    "make_rows",
    "render",
    "render_latex",
    "render_stream",
    "table_columns",
    "terminal_width",
]

Format = Literal["table", "md", "csv", "json", "jsonl", "latex"]
FORMATS: tuple[Format, ...] = ("table", "md", "csv", "json", "jsonl", "latex")

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
    "depth_kind",
)
"""Columns of the ``table`` and ``md`` formats (plus :data:`FT_COLUMNS` with the ``ft`` target,
:data:`PHYSICAL_COLUMNS` and :data:`PAPER_COLUMNS`)."""

FT_COLUMNS: tuple[str, ...] = ("ft_total_t", "ft_rotations", "rotation_depth")
"""Default columns added with the ``ft`` target: T count, rotations and rotation depth of the fault-tolerant model
(``ft_total_t`` and ``ft_rotations`` after ``t``, ``rotation_depth`` after ``two_qubit_depth``)."""

PAPER_COLUMNS: tuple[str, ...] = ("paper_qubits", "paper_cx", "paper_single_qubit", "ratio_cx")
PHYSICAL_COLUMNS: tuple[str, ...] = ("ft_total_t", "physical_qubits", "physical_runtime_s", "physical_t_factories")

BOUND_MARK = "<="
"""Prefix of a cell (``table``, ``md``; ``latex``: ``$\\leq$``) whose figure is an upper bound, not exact."""

BOUNDED_BY: dict[str, str] = {
    "depth": "depth_kind",
    "two_qubit_depth": "depth_kind",
    "rotation_depth": "depth_kind",
    "routed_depth": "routed_depth_kind",
    "routed_twoq_depth": "routed_depth_kind",
    "duration_s": "routed_depth_kind",
    "routed_twoq": "routed_kind",
}
"""Columns whose figure may be an upper bound, each with the row field saying which (``exact`` or ``bound``)."""

LOWER_BOUND_MARK = ">="
"""Prefix of a cell (``table``, ``md``; ``latex``: ``$\\geq$``) whose figure is a lower bound, not exact."""

LOWER_BOUNDED_BY: dict[str, str] = {
    f"{log}esp{idle}": "routed_kind" for log in ("", "log10_") for idle in ("", "_idle")
}
"""Columns whose figure may be a lower bound, each with the row field saying which: the ESP of a ``bound`` routing
is computed from an upper bound of its gates at the worst error rates (:mod:`qcpp.estimators.routed`), so the
routing it bounds succeeds at least that often."""

_FROM_LOG: dict[str, str] = {"esp": "log10_esp", "esp_idle": "log10_esp_idle"}
"""Columns shown from the row's base-10 log of them where the figure itself underflowed to ``0.0``."""

APPROX_MARK = "~"
"""Prefix of a cell (``table``, ``md``, ``latex``) whose figure is approximate: computed from a depth bound."""

APPROXIMATE_BY: dict[str, str] = {
    f"physical_{k}": "physical_depth_kind"
    for k in ("qubits", "runtime_s", "algorithm_qubits", "t_factory_qubits", "t_factories", "t_states",
              "code_distance")
}  # fmt: skip
"""Columns whose figure is approximate unless the row field named here is ``exact``."""

_SECTION_NAMES = ("initial_state", "phase", "mixer")
_SECTION_FIELDS = ("gates", "cx", "single_qubit", "t", "rotations")


def _ratio(ours: int, paper: int) -> float | None:
    return round(ours / paper, 4) if paper else None


def _section(c: Cost) -> dict[str, int]:
    return {"gates": c.total, **{k: getattr(c, k) for k in _SECTION_FIELDS[1:]}}


def make_row(est: Estimate, compare_paper: bool = False, doubling: Doubling = "partial-mixer") -> dict[str, Any]:
    """One estimate as a row dict (see the module docstring for the keys).

    Args:
        est: an estimate.
        compare_paper: add the paper's estimate and the ratios.
        doubling: the reading of the paper's doubling (:func:`qcpp.estimators.paper.paper_partial_mixer`).
    """
    pt, c, ft, d, plan = est.point, est.cost, est.fault_tolerant, est.depth, est.options.plan
    row: dict[str, Any] = {
        "rows": pt.rows,
        "cols": pt.cols,
        "robots": pt.robots,
        "p": pt.p,
        "rule": plan.rule,
        "target": plan.target,
        "scenario": "default" if pt.scenario_json is None else "custom",
        **({} if plan.first_phase else {"first_phase": False}),  # the default's rows keep their columns
        "qubits": est.qubits,
        "data_qubits": est.data_qubits,
        "ancillas": est.qubits - est.data_qubits,
        "gates": c.total,
        **{k: getattr(c, k) for k in ("cx", "single_qubit", "two_qubit", "t", "rotations")},
        **{k: getattr(d, k) if d else None for k in ("depth", "two_qubit_depth", "rotation_depth")},
        "depth_kind": d.kind if d else None,
        "toffoli": ft.toffoli,
        "ft_and": ft.and_compute,
        **{f"ft_{k}": getattr(ft, k) for k in ("toffoli_full", "measurements", "rotations", "t_per_rotation",
                                                "epsilon", "toffoli_t", "t_logic", "total_t")},
    }  # fmt: skip
    ph = est.physical
    if ph is not None:
        row["physical_qubits"] = ph.physical_qubits
        for k in ("runtime_s", "algorithm_qubits", "t_factory_qubits", "t_factories", "t_states", "code_distance"):
            row[f"physical_{k}"] = getattr(ph, k)
        row["physical_model"] = f"{ph.qubit_model} / {ph.qec_scheme} / budget {ph.error_budget:g}"
        row["physical_depth_kind"] = d.kind if d else "rotation_count"  # Estimate.logical_counts's rotation depth
    if compare_paper:
        paper = paper_estimate(pt.rows, pt.cols, pt.robots, pt.p, doubling)
        row.update({f"paper_{k}": getattr(paper, k) for k in ("qubits", "data_qubits", "cx", "single_qubit")})
        row.update({f"ratio_{k}": _ratio(row[k], row[f"paper_{k}"]) for k in ("qubits", "cx", "single_qubit")})
    row["sections"] = {name: _section(est.parts[name]) for name in _SECTION_NAMES if name in est.parts}
    return row


def make_rows(
    estimates: Iterable[Estimate], compare_paper: bool = False, doubling: Doubling = "partial-mixer"
) -> list[dict[str, Any]]:
    """:func:`make_row` of every estimate, in order."""
    return [make_row(e, compare_paper, doubling) for e in estimates]


def _columns(row: dict[str, Any] | None) -> list[str]:
    cols = list(MAIN_COLUMNS)
    if row and row.get("target") == "ft":
        cols[cols.index("t") + 1 : cols.index("t") + 1] = list(FT_COLUMNS[:2])
        cols.insert(cols.index("two_qubit_depth") + 1, FT_COLUMNS[2])
    if row and "physical_qubits" in row:
        cols += list(PHYSICAL_COLUMNS)
    if row and "paper_cx" in row:
        cols += list(PAPER_COLUMNS)
    if row and "routed_kind" in row:
        from qcpp.estimators.routed import ROUTED_COLUMNS

        cols += list(ROUTED_COLUMNS)
    return list(dict.fromkeys(cols))


def _cell(v: Any, col: str = "") -> str:
    """A value as text: a float to 4 significant digits, a base-10 log (``log10_...``) to 2 decimals (its integer
    part is the exponent, the decimals the digits).

    >>> _cell(0.123456), _cell(-3714.043208, "log10_esp"), _cell(None)
    ('0.1235', '-3714.04', '')
    """
    if v is None:
        return ""
    if isinstance(v, float):
        return f"{v:.2f}" if col.startswith("log10_") else f"{v:.4g}"
    return str(v)


def _is_bound(row: dict[str, Any], col: str) -> bool:
    """Whether ``row``'s ``col`` holds an upper bound rather than an exact figure (:data:`BOUNDED_BY`)."""
    kind = BOUNDED_BY.get(col)
    return kind is not None and row.get(col) is not None and row.get(kind) == "bound"


def _is_lower_bound(row: dict[str, Any], col: str) -> bool:
    """Whether ``row``'s ``col`` holds a lower bound rather than an exact figure (:data:`LOWER_BOUNDED_BY`)."""
    kind = LOWER_BOUNDED_BY.get(col)
    return kind is not None and row.get(col) is not None and row.get(kind) == "bound"


def _is_approximate(row: dict[str, Any], col: str) -> bool:
    """Whether ``row``'s ``col`` is approximate: computed from a depth that is not exact (:data:`APPROXIMATE_BY`)."""
    kind = APPROXIMATE_BY.get(col)
    return kind is not None and row.get(col) is not None and row.get(kind) != "exact"


def _mark(row: dict[str, Any], col: str, bound: str = BOUND_MARK, lower: str = LOWER_BOUND_MARK) -> str:
    """The prefix of ``row``'s ``col`` cell: ``bound`` for an upper bound, ``lower`` for a lower bound,
    :data:`APPROX_MARK` for an approximation."""
    if _is_bound(row, col):
        return bound
    return lower if _is_lower_bound(row, col) else APPROX_MARK if _is_approximate(row, col) else ""


def from_log(row: dict[str, Any], col: str) -> str | None:
    """``row``'s ``col`` written from its base-10 log (:data:`_FROM_LOG`) where the figure underflowed to ``0.0``
    and the log is known, else ``None``.

    >>> from_log({"esp": 0.0, "log10_esp": -1234.55}, "esp"), from_log({"esp": 0.5, "log10_esp": -0.3}, "esp")
    ('2.818e-1235', None)
    """
    log = row.get(_FROM_LOG.get(col, ""))
    if row.get(col) != 0.0 or not isinstance(log, (int, float)):
        return None
    exponent = math.floor(log)
    mantissa = f"{10 ** (log - exponent):.4g}"
    if mantissa == "10":  # rounded up to the next power of ten
        mantissa, exponent = "1", exponent + 1
    return f"{mantissa}e{exponent}"


def _shown(row: dict[str, Any], col: str) -> str:
    """The cell of ``row``'s ``col`` in the formats read by people: :func:`_cell` (or :func:`from_log`), marked by
    :func:`_mark`."""
    text = from_log(row, col)
    return _mark(row, col) + (text if text is not None else _cell(row.get(col), col))


def _any_bound(rows: Iterable[dict[str, Any]], cols: Sequence[str]) -> bool:
    return any(_is_bound(r, c) for r in rows for c in cols)


def _any_lower_bound(rows: Iterable[dict[str, Any]], cols: Sequence[str]) -> bool:
    return any(_is_lower_bound(r, c) for r in rows for c in cols)


LOWER_BOUND_NOTE = f"{LOWER_BOUND_MARK}N is a lower bound (the ESP of a bounded routing)"
"""What :data:`LOWER_BOUND_MARK` means, in the titles and the ``md`` footnote."""


def _any_approximate(rows: Iterable[dict[str, Any]], cols: Sequence[str]) -> bool:
    return any(_is_approximate(r, c) for r in rows for c in cols)


APPROX_NOTE = "~N: from a depth bound, not exact (--depth exact gives the exact figure)"
"""What :data:`APPROX_MARK` means, in the titles and the ``md`` footnote."""


FT_NOTE = "ft_*: fault-tolerant model estimates"
"""Said in the title when a shown column (``ft_...``) is an estimate of the fault-tolerant model, not a count."""


NO_FIRST_PHASE_NOTE = "without the first phase separator (--skip-first-phase)"
"""Said in the title (and under an ``md`` or LaTeX table) when a row counts ``p - 1`` phase separators."""


def _without_first_phase(rows: Iterable[dict[str, Any]]) -> bool:
    """Whether a row was counted without the first phase separator (its ``first_phase`` field is ``False``; rows of
    the default circuit carry no such field)."""
    return any(r.get("first_phase") is False for r in rows)


def _title(
    paper: bool, bound: bool, approximate: bool = False, ft: bool = False, no_first_phase: bool = False,
    lower: bool = False,
) -> str:
    """The title of the ``table`` format: every count exact, and the meaning of each mark a cell has (and of the
    ``ft_`` columns when ``ft``); a circuit without its first phase separator is named, so that a ratio to the
    paper's ``p`` phase separators is not read as like for like.

    Example:
        >>> _title(True, False, no_first_phase=True)
        'Exact resource counts (lowered circuit, without the first phase separator (--skip-first-phase)) vs the paper'
    """
    vs = " vs the paper" if paper else ""
    what = f"lowered circuit, {NO_FIRST_PHASE_NOTE}" if no_first_phase else "lowered circuit"
    notes = ([f"{BOUND_MARK}N is an upper bound"] if bound else []) + ([LOWER_BOUND_NOTE] if lower else [])
    notes += ([APPROX_NOTE] if approximate else []) + ([FT_NOTE] if ft else [])
    if notes:
        return f"Resource counts ({what}){vs}: exact; " + "; ".join(notes)
    return f"Exact resource counts ({what}){vs}"


def _marks_title(rows: Sequence[dict[str, Any]], cols: Sequence[str], paper: bool) -> str:
    """:func:`_title` of ``rows`` shown in ``cols``."""
    ft = any(c.startswith("ft_") for c in cols)
    return _title(paper, _any_bound(rows, cols), _any_approximate(rows, cols), ft, _without_first_phase(rows),
                  _any_lower_bound(rows, cols))


def _flat(row: dict[str, Any]) -> dict[str, Any]:
    out = {k: v for k, v in row.items() if k != "sections"}
    for name, sec in row.get("sections", {}).items():
        for f in _SECTION_FIELDS:
            out[f"section.{name}.{f}"] = sec[f]
    return out


def _chosen(columns: Sequence[str], known: Sequence[str]) -> list[str]:
    """``columns`` (each once, in order), checked against the ``known`` fields.

    Raises:
        ValueError: none, or an unknown name (with the closest known name, and where every name is listed).
    """
    if not columns:
        raise ValueError("--columns: name at least one column")
    for c in columns:
        if c not in known:
            close = difflib.get_close_matches(c, known, n=1)
            hint = f" (did you mean {close[0]}?)" if close else ""
            raise ValueError(f"--columns: no column {c!r}{hint}; --format csv's header lists them")
    return list(dict.fromkeys(columns))


def _csv_line(values: Iterable[Any]) -> str:
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow(list(values))
    return buf.getvalue()


def render_stream(
    rows: Iterable[dict[str, Any]],
    fmt: Format = "csv",
    *,
    width: int | None = None,
    columns: Sequence[str] | None = None,
    wide: bool = False,
) -> Iterator[str]:
    """Rows as text pieces, each yielded as soon as its row arrives (``table`` waits for every row).

    Args:
        rows: rows (any iterable, e.g. a generator over a sweep).
        fmt: one of :data:`FORMATS`.
        width, wide: the ``table`` format's options (:func:`render`).
        columns: exactly these columns, for ``table``, ``latex``, ``md`` and ``csv`` (``csv`` also takes the
            sections' flattened fields, ``section.<name>.<field>``).

    Yields:
        Text pieces whose concatenation is :func:`render` of the same rows.
    """
    if fmt not in FORMATS:
        raise ValueError(f"unknown format {fmt!r} (expected one of {', '.join(FORMATS)})")
    if fmt == "table":
        yield render(list(rows), "table", width=width, columns=columns, wide=wide)
        return
    if fmt == "latex":  # the column alignment depends on every row
        yield render_latex(list(rows), columns)
        return
    if columns is not None and fmt in ("json", "jsonl"):
        raise ValueError(f"--columns: {fmt} rows keep every field (as Estimate.to_dict()); choose the columns with "
                         "--format table, md, csv or latex")  # fmt: skip
    first = True
    approximate = False  # an md cell marked APPROX_MARK: the table ends with a footnote saying what it means
    lower = False  # an md cell marked LOWER_BOUND_MARK: a footnote too
    upper = False  # an md cell marked BOUND_MARK: a footnote saying what it means
    no_first_phase = False  # a row without the first phase separator: the md table ends saying so
    fields: list[str] = []
    cols: list[str] = []
    for row in rows:
        if fmt == "jsonl":
            yield json.dumps(row) + "\n"
        elif fmt == "json":
            body = "\n".join("  " + line for line in json.dumps(row, indent=2).splitlines())
            yield ("[\n" if first else ",\n") + body
        elif fmt == "csv":
            flat = _flat(row)
            if first:  # every scalar of the row, in order, then the sections' fields; or the chosen ones
                fields = list(flat) if columns is None else _chosen(columns, list(flat))
                yield _csv_line(fields)
            yield _csv_line(_cell(flat.get(k), k) if isinstance(flat.get(k), float) else flat.get(k, "")
                            for k in fields)  # fmt: skip
        else:  # md
            if first:
                cols = _columns(row) if columns is None else table_columns([row], columns=columns)[0]
                yield "| " + " | ".join(cols) + " |\n" + "|" + "|".join("---:" for _ in cols) + "|\n"
            yield "| " + " | ".join(_shown(row, c) for c in cols) + " |\n"
            approximate = approximate or _any_approximate([row], cols)
            lower = lower or _any_lower_bound([row], cols)
            upper = upper or any(_is_bound(row, c) for c in cols)
            no_first_phase = no_first_phase or _without_first_phase([row])
        first = False
    if fmt == "json":
        yield "[]\n" if first else "\n]\n"
    elif fmt == "md" and first:
        cols = _columns(None) if columns is None else table_columns([], columns=columns)[0]
        yield "| " + " | ".join(cols) + " |\n" + "|" + "|".join("---:" for _ in cols) + "|\n"
    elif fmt == "md":
        if upper and not lower:  # upper bounds alone (a bounded depth)
            yield "\n" + f"{BOUND_MARK}N is an upper bound" + "\n"
        if approximate:
            yield "\n" + APPROX_NOTE.replace("~", "\\~", 1) + "\n"
    if fmt == "md" and lower:  # the ESP's lower bound beside the figures' upper bounds: both marks said
        yield "\n" + f"{BOUND_MARK}N is an upper bound; {LOWER_BOUND_NOTE}" + "\n"
    if fmt == "md" and no_first_phase:
        yield "\nCounted " + NO_FIRST_PHASE_NOTE + ".\n"


_LATEX_SPECIAL = {
    "\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_", "{": r"\{", "}": r"\}",
    "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
}  # fmt: skip


def latex_escape(text: str) -> str:
    r"""``text`` with LaTeX's special characters escaped.

    >>> print(latex_escape("two_qubit & 50%"))
    two\_qubit \& 50\%
    """
    return "".join(_LATEX_SPECIAL.get(ch, ch) for ch in text)


def _is_number(v: Any) -> bool:
    return v is None or (isinstance(v, (int, float)) and not isinstance(v, bool))


LATEX_HEADERS: dict[str, str] = {
    "p": "$p$",
    "data_qubits": "data qubits",
    "cx": "CNOTs",
    "single_qubit": "1-qubit gates",
    "two_qubit": "2-qubit gates",
    "t": "T gates",
    "two_qubit_depth": "2-qubit depth",
    "rotation_depth": "rotation depth",
    "depth_kind": "depth kind",
    "toffoli": "Toffolis",
    "ft_total_t": "T (FT model)",
    "ft_rotations": "rotations (FT model)",
    "ft_and": "ANDs (FT model)",
    "ft_toffoli_full": "Toffolis (FT model)",
    "ft_measurements": "measurements (FT model)",
    "ft_t_per_rotation": "T per rotation (FT model)",
    "ft_epsilon": "$\\epsilon$ (FT model)",
    "ft_toffoli_t": "T per Toffoli (FT model)",
    "ft_t_logic": "T of logic (FT model)",
    "physical_qubits": "physical qubits",
    "physical_runtime_s": "runtime (s)",
    "physical_algorithm_qubits": "algorithm qubits (physical)",
    "physical_t_factory_qubits": "T-factory qubits (physical)",
    "physical_t_factories": "T factories",
    "physical_t_states": "T states",
    "physical_code_distance": "code distance",
    "physical_model": "physical model",
    "physical_depth_kind": "physical depth kind",
    "paper_qubits": "paper qubits",
    "paper_data_qubits": "paper data qubits",
    "paper_cx": "paper CNOTs",
    "paper_single_qubit": "paper 1-qubit gates",
    "ratio_qubits": "qubits / paper",
    "ratio_cx": "CNOTs / paper",
    "ratio_single_qubit": "1-qubit gates / paper",
    "duration_s": "duration (s)",
}
"""The ``latex`` format's header of a column, in LaTeX (:func:`latex_header`): what it counts, with its unit where it
is not a count (``runtime (s)``)."""


def latex_header(column: str) -> str:
    r"""The ``latex`` header of ``column``: :data:`LATEX_HEADERS`, else its name with spaces for underscores.

    >>> latex_header("physical_runtime_s"), latex_header("routed_twoq")
    ('runtime (s)', 'routed twoq')
    """
    return LATEX_HEADERS.get(column) or latex_escape(column.replace("_", " "))


def latex_number(v: Any) -> str:
    r"""A number as a ``latex`` cell: thousands grouped with ``{,}`` (plain LaTeX, no package), a float below
    1,000 to 4 significant digits; ``None`` is empty, anything else escaped text.

    >>> latex_number(13267530), latex_number(0.02615), latex_number(12345.6), latex_number(0.5), latex_number(None)
    ('13{,}267{,}530', '0.02615', '12{,}346', '0.5', '')
    """
    if v is None:
        return ""
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return latex_escape(str(v))
    text = f"{v:,}" if isinstance(v, int) else f"{v:,.0f}" if abs(v) >= 1000 else f"{v:.4g}"
    return text.replace(",", "{,}")


def _latex_cell(row: dict[str, Any], col: str) -> str:
    """``row``'s ``col`` as a ``latex`` cell without its mark: :func:`latex_number`, or :func:`from_log`."""
    text = from_log(row, col)
    if text is None and col.startswith("log10_") and isinstance(row.get(col), float):
        text = _cell(row.get(col), col)  # the decimals are the digits: not rounded to an integer
    return latex_number(row.get(col)) if text is None else text


def render_latex(rows: Sequence[dict[str, Any]], columns: Sequence[str] | None = None) -> str:
    r"""Rows as a LaTeX ``tabular`` with booktabs rules (``\usepackage{booktabs}``): the columns of the ``md``
    format (or ``columns``) under readable headers with units (:func:`latex_header`), numbers right-aligned with
    thousands grouped (:func:`latex_number`, plain LaTeX), text left-aligned, LaTeX's special characters escaped, an
    upper bound marked ``$\leq$`` in its cell and an approximate figure ``$\sim$``.

    Args:
        rows: rows from :func:`make_rows`.
        columns: exactly these columns (checked as :func:`table_columns` checks them).

    Returns:
        The text (ending with a newline).

    Example:
        >>> rows = [{"rows": 30, "cols": 30, "cx": 1379440, "depth_kind": "exact"}]
        >>> print(render_latex(rows, ["rows", "cx", "depth_kind"]), end="")
        % qcpp estimate: counts of the lowered circuit (exact; $\leq$N: an upper bound); needs \usepackage{booktabs}
        \begin{tabular}{rrl}
        \toprule
        rows & CNOTs & depth kind \\
        \midrule
        30 & 1{,}379{,}440 & exact \\
        \bottomrule
        \end{tabular}
        >>> print(render_latex([{"depth": 9087, "depth_kind": "bound"}], ["depth"]).splitlines()[5])
        $\leq$9{,}087 \\
    """
    cols = table_columns(rows, columns=columns)[0] if columns is not None else _columns(rows[0] if rows else None)
    align = "".join("r" if all(_is_number(r.get(c)) for r in rows) else "l" for c in cols)
    approx = "; " + latex_escape(APPROX_NOTE[1:]).join(["$\\sim$", ""]) if _any_approximate(rows, cols) else ""
    approx += "; " + latex_escape(NO_FIRST_PHASE_NOTE) if _without_first_phase(rows) else ""
    if _any_lower_bound(rows, cols):
        approx = r"; $\geq$N: a lower bound (the ESP of a bounded routing)" + approx
    out = [
        r"% qcpp estimate: counts of the lowered circuit (exact; $\leq$N: an upper bound"
        + approx
        + r"); needs \usepackage{booktabs}",
        r"\begin{tabular}{" + align + "}",
        r"\toprule",
        " & ".join(latex_header(c) for c in cols) + r" \\",
        r"\midrule",
    ]
    out += [" & ".join(_mark(r, c, r"$\leq$", r"$\geq$").replace(APPROX_MARK, r"$\sim$") + _latex_cell(r, c)
                       for c in cols) + r" \\" for r in rows]  # fmt: skip
    out += [r"\bottomrule", r"\end{tabular}"]
    return "\n".join(out) + "\n"


DROP_ORDER: tuple[str, ...] = (
    "physical_t_factories",
    "ft_total_t",
    "two_qubit_depth",
    "data_qubits",
    "ancillas",
    "paper_single_qubit",
    "paper_qubits",
    "depth_kind",
    "depth",
    "single_qubit",
    "t",
    "ratio_cx",
)
"""Columns the ``table`` format hides first, in order, when the terminal is too narrow for all of them."""

FT_DROP_ORDER: tuple[str, ...] = (
    *(c for c in DROP_ORDER if c not in ("ft_total_t", "ratio_cx")),
    "ft_rotations",
    "ratio_cx",
)
""":data:`DROP_ORDER` of the ``ft`` target: the fault-tolerant figures are hidden last (at 80 columns ``cx``,
``ft_total_t`` and ``rotation_depth`` stay). ``cx`` is never hidden (none of these lists holds it): the identity
columns, ``qubits``, ``cx`` and ``paper_cx`` are always shown."""


PHYSICAL_DROP_ORDER: tuple[str, ...] = ("ft_rotations", "rotation_depth", "ft_total_t", "physical_runtime_s")
"""Columns hidden after :data:`DROP_ORDER` (``ft``: :data:`FT_DROP_ORDER`) when the rows carry physical figures
and no paper comparison: ``physical_qubits`` is never hidden, ``physical_runtime_s`` last (at 80 columns the
scenario's columns, ``qubits``, ``cx`` and ``physical_qubits`` fit). A table that does not fit even so is printed
as records."""


def _rich_table(rows: Sequence[dict[str, Any]], cols: Sequence[str], paper: bool) -> Any:
    from rich.table import Table

    table = Table(title=_marks_title(rows, cols, paper))
    for c in cols:
        table.add_column(c, justify="right")
    for r in rows:
        table.add_row(*(_shown(r, c) for c in cols))
    return table


class _Text(io.StringIO):
    """A text buffer that tells rich which encoding the text is for (rich draws ASCII boxes for a non-UTF one)."""

    def __init__(self, encoding: str) -> None:
        super().__init__()
        self._encoding = encoding

    @property
    def encoding(self) -> str:  # type: ignore[override]
        return self._encoding


def stdout_encoding() -> str:
    """The encoding of standard output (``utf-8`` if it has none): what text drawn for it must fit."""
    return getattr(sys.stdout, "encoding", None) or "utf-8"


def draw(renderable: Any, width: int, encoding: str | None = None) -> str:
    """``renderable`` (a rich table, text, ...) as rich prints it on a ``width``-character plain console.

    Args:
        renderable: What to draw.
        width: Characters per line.
        encoding: The encoding the text will be written in (default :func:`stdout_encoding`): for one that is not
            UTF (the C locale's ``ascii``) rich draws boxes with ``+``, ``-`` and ``|``, as when it prints to such
            a stream itself.

    Example:
        >>> from rich.table import Table
        >>> t = Table("a")
        >>> draw(t, 10, "ascii").splitlines()[0]
        '+---+'
    """
    from rich.console import Console

    buf = _Text(encoding or stdout_encoding())
    Console(file=buf, width=width, force_terminal=False, color_system=None).print(renderable)
    return buf.getvalue()


def _natural_width(rows: Sequence[dict[str, Any]], cols: Sequence[str], paper: bool) -> int:
    text = draw(_rich_table(rows, cols, paper), 100_000)
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
        ``(shown, hidden)``: the default columns (:data:`MAIN_COLUMNS`, plus :data:`FT_COLUMNS` with the ``ft``
        target, :data:`PHYSICAL_COLUMNS` with physical figures and :data:`PAPER_COLUMNS` when comparing) minus
        those of :data:`DROP_ORDER` (``ft``: :data:`FT_DROP_ORDER`; then :data:`PHYSICAL_DROP_ORDER` with physical
        figures) that do not fit, and the hidden ones.

    Raises:
        ValueError: an unknown column name.
    """
    defaults = _columns(rows[0] if rows else None)
    if columns is not None:
        return _chosen(columns, [k for k in (rows[0] if rows else dict.fromkeys(defaults)) if k != "sections"]), []
    if wide:
        return defaults, []
    limit = terminal_width() if width is None else width
    paper = "paper_cx" in defaults
    shown = list(defaults)
    order = FT_DROP_ORDER if rows and rows[0].get("target") == "ft" else DROP_ORDER
    if "physical_qubits" in defaults and not paper:  # the logical figures go before the physical ones they feed
        order = (*order, *(c for c in PHYSICAL_DROP_ORDER if c not in order))
    for c in order:
        if _natural_width(rows, shown, paper) <= limit:
            break
        if c in shown:
            shown.remove(c)
    return shown, [c for c in defaults if c not in shown]


class TooNarrowError(ValueError):
    """Even the record layout needs more characters per line than the terminal has."""


def render_records(rows: Sequence[dict[str, Any]], cols: Sequence[str], width: int, *, paper: bool = False) -> str:
    """Rows as records, one field per line (the ``table`` format below the table's width; :func:`records`).

    Numbers are never cut: below the width of the longest name or value this raises instead of printing
    something unreadable.

    Args:
        rows: rows from :func:`make_rows`.
        cols: the fields of each record, in order.
        width: characters per line.
        paper: the title says "vs the paper".

    Returns:
        The text: a title, then per row ``row i of n`` and its fields, records separated by a blank line.

    Raises:
        TooNarrowError: ``width`` is below the longest name or value (the message says what to do).

    Example:
        >>> print(render_records([{"rows": 3, "cols": 3, "cx": 106}], ["rows", "cols", "cx"], 20), end="")
        Exact resource
        counts (lowered
        circuit)
        row 1 of 1
        rows   3
        cols   3
        cx   106
        >>> print(render_records([{"rows": 3, "paper_cx": 2332}], ["rows", "paper_cx"], 10), end="")
        Exact
        resource
        counts
        (lowered
        circuit)
        row 1 of 1
        rows
          3
        paper_cx
          2332
    """
    cells = [[_shown(r, c) for c in cols] for r in rows]
    title = _marks_title(rows, cols, paper)
    value_w = max((len(v) for row in cells for v in row), default=0)
    need = max(0, *map(len, cols), value_w + 2, len(f"row {len(cells)} of {len(cells)}"), *map(len, title.split()))
    if need > width:
        raise TooNarrowError(
            f"the terminal is {width} columns wide; the resource table needs {need} even one field per line "
            f"(set COLUMNS={need} or more, or use --format csv, json or md)"
        )
    return records(title, [list(zip(cols, row, strict=True)) for row in cells], width, numbered=True)


def records(
    title: str, blocks: Sequence[Sequence[tuple[str, str]]], width: int, *, sep: str = " ", numbered: bool = False,
    per_field: bool = False,
) -> str:
    """``(name, value)`` fields within ``width`` characters: the layout of every table too wide for the terminal.

    A field is ``name<sep>value`` (names padded, values right-aligned) when every field fits so (``per_field``:
    when it does), else its name with the value indented below; a value of several lines continues indented.

    Args:
        title: wrapped at spaces only (:func:`title_lines`).
        blocks: the records, each a sequence of fields, a blank line between two; ``numbered``: each opened by
            ``row i of n``.

    Example:
        >>> print(records("t", [[("qubits", "26"), ("cx", "320")]], 12, sep="  "), end="")
        t
        qubits   26
        cx      320
    """
    fields = [field for block in blocks for field in block]
    name_w = max((len(name) for name, _ in fields), default=0)
    value_w = max((len(part) for _, value in fields for part in value.split("\n")), default=0)
    all_fit = name_w + len(sep) + value_w <= width
    value_w = min(value_w, width - name_w - len(sep))
    out = title_lines(title, width)
    for i, block in enumerate(blocks):
        out += ([""] if i else []) + ([f"row {i + 1} of {len(blocks)}"] if numbered else [])
        for name, value in block:
            first, *rest = value.split("\n")
            if all_fit or (per_field and max(map(len, [first, *rest])) <= value_w):
                out.append(f"{name:<{name_w}}{sep}{first:>{value_w}}".rstrip())
                out += [" " * (name_w + len(sep)) + part for part in rest]
            else:
                out += [name, *("  " + part for part in value.split("\n"))]
    return "\n".join(out) + "\n"


def title_lines(title: str, width: int) -> list[str]:
    """``title`` wrapped to ``width`` at spaces only: a file name is never broken (a longer one stands alone)."""
    return textwrap.wrap(title, width, break_long_words=False, break_on_hyphens=False)


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
        fmt: ``table`` (rich), ``md``, ``csv``, ``json`` or ``jsonl``.
        width: ``table`` only: fit this many characters (default :func:`terminal_width`); columns of
            :data:`DROP_ORDER` are hidden until the table fits, and a note names them. No line is longer, and
            no number is cut: when even the narrowest table does not fit, the rows are printed as records (one
            field per line, :func:`render_records`), and below their width a :class:`TooNarrowError` says
            what to do.
        columns: show exactly these columns (:func:`table_columns`; ``md``, ``csv`` and ``latex`` too).
        wide: ``table`` only: show every default column, whatever the width.

    ``md``, ``csv``, ``json`` and ``jsonl`` stream (:func:`render_stream`); ``json`` and ``jsonl`` keep every field
    of every row (``columns`` with them is refused).

    Returns:
        The text (ending with a newline).

    Example:
        >>> rows = [{"rows": 3, "cols": 3, "robots": 1, "p": 1, "qubits": 26, "cx": 320}]
        >>> text = render(rows, "table", columns=["rows", "cols", "cx"])
        >>> [line.strip() for line in text.splitlines()][3]
        '┃ rows ┃ cols ┃  cx ┃'
    """
    if fmt != "table":
        return "".join(render_stream(rows, fmt, columns=columns))  # raises on an unknown format
    limit = terminal_width() if width is None else width
    shown, hidden = table_columns(rows, limit, columns, wide)
    paper = "paper_cx" in _columns(rows[0] if rows else None)
    natural = _natural_width(rows, shown, paper)
    if columns is None and not wide and natural > limit:  # a table this narrow would cut numbers
        return render_records(rows, _columns(rows[0] if rows else None), limit, paper=paper)
    table = _rich_table(rows, shown, paper)
    text_width = limit if columns is None and not wide else max(limit, natural)
    text = draw(table, text_width)
    if hidden:
        note = (
            f"hidden to fit {limit} columns: {', '.join(hidden)} (--wide or --columns to show them; "
            "--format md shows every table column, csv and json every field)"
        )
        text += draw(note, limit)
    return text
