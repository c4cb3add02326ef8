"""HTML tables for notebooks: what the reports' ``_repr_html_`` show (an estimate, a verification, a validation).

Example:
    >>> html_table("a <b>", ("name", "n"), [("x&y", "3")], align=(None, "right"))
    "<table><caption>a &lt;b&gt;</caption><tr><th>name</th><th>n</th></tr><tr><td>x&amp;y</td><td \
style='text-align:right'>3</td></tr></table>"
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from html import escape

__all__ = ["html_table"]


def html_table(
    caption: str, headers: Sequence[str], rows: Iterable[Sequence[str]], align: Sequence[str | None] = ()
) -> str:
    """One HTML table: ``caption``, a header row, then ``rows`` (every text escaped).

    Args:
        caption: The caption (the report's verdict or title).
        headers: The column headers.
        rows: The cells of each row, as text.
        align: Per column, ``left``, ``right`` or ``None`` (no style); missing columns get ``None``.

    Returns:
        ``<table>...</table>``.
    """
    styles = [f" style='text-align:{a}'" if a else "" for a in align]
    styles += [""] * (len(headers) - len(styles))
    head = "".join(f"<th>{escape(h)}</th>" for h in headers)
    body = "".join(
        "<tr>" + "".join(f"<td{s}>{escape(cell)}</td>" for s, cell in zip(styles, row, strict=True)) + "</tr>"
        for row in rows
    )
    return f"<table><caption>{escape(caption)}</caption><tr>{head}</tr>{body}</table>"
