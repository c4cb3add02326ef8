"""Tables never cut a number: below their width they become records (one field per line), and below that the
estimate table says in one line what to do; titles break at spaces only, never inside a file name."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rich.table import Table

from qcpp.cli.render import table_text
from qcpp.estimators.estimate import Point, estimate_point
from qcpp.estimators.tables import TooNarrowError, make_rows, render, render_records

from .clirun import assert_one_line_error, run

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"


@pytest.fixture(scope="module")
def rows() -> list[dict]:
    points = [Point(3, 3, 1, 1), Point(6, 6, 3, 2)]
    return make_rows([estimate_point(pt) for pt in points], compare_paper=True)


def _values(rows: list[dict]) -> set[str]:
    """The text of every default column's value (what the table or the records must show)."""
    from qcpp.estimators.tables import _cell, _columns

    return {_cell(r.get(k)) for r in rows for k in _columns(r) if _cell(r.get(k))}


@settings(max_examples=25, deadline=None)
@given(width=st.integers(1, 140))
def test_estimate_table_never_cuts_a_number(rows: list[dict], width: int) -> None:
    """At every width: a whole table, or records holding every value whole, or one error naming the width."""
    try:
        text = render(rows, "table", width=width)
    except TooNarrowError as exc:
        assert str(width) in str(exc) and "--format" in str(exc) and "\n" not in str(exc)
        return
    assert "…" not in text
    assert max(len(line) for line in text.splitlines()) <= width
    if "row 1 of" in text:  # records: every value of every row, each on its own line, whole
        ends = {line.split()[-1] for line in text.splitlines() if line.strip()}
        assert _values(rows) <= ends
        assert all(line.split()[0] in ends or len(line.split()) > 1 for line in text.splitlines() if line.strip())


def test_records_keep_every_column(rows: list[dict]) -> None:
    from qcpp.estimators.tables import _columns

    text = render_records(rows, _columns(rows[0]), 60)
    for key in ("two_qubit_depth", "paper_single_qubit", "ratio_cx", "paper_cx"):
        assert any(line.startswith(key + " ") for line in text.splitlines())


@pytest.mark.parametrize("width, records", [("40", True), ("25", True), ("20", True), ("18", True), ("17", False),
                                            ("5", False)])
def test_the_issue_command_at_narrow_widths(width: str, records: bool) -> None:
    res = run_env(["estimate", "--grid", "3x3", "--compare", "paper"], width)
    if records:
        assert res.exit_code == 0, res.output
        assert "paper_cx" in res.stdout and "2332" in res.stdout.split() and "…" not in res.stdout
        assert max(len(line) for line in res.stdout.splitlines()) <= int(width)
    else:
        assert_one_line_error(res, f"{width} columns", "COLUMNS=", "--format csv")


def run_env(args: list[str], width: str):  # type: ignore[no-untyped-def]
    from typer.testing import CliRunner

    from qcpp.cli.app import app

    return CliRunner().invoke(app, args, env={"COLUMNS": width})


cells = st.text(alphabet="0123456789.,-e", min_size=1, max_size=14)


@settings(max_examples=60, deadline=None)
@given(
    headers=st.lists(st.text(alphabet="abcdefgh _()", min_size=1, max_size=20), min_size=1, max_size=7),
    data=st.data(),
    width=st.integers(8, 120),
)
def test_any_rich_table_keeps_every_cell_whole(headers: list[str], data: st.DataObject, width: int) -> None:
    table = Table(title="a title with examples/some_long_file_name.toml inside")
    for h in headers:
        table.add_column(h.strip() or "x", justify="right")
    body = data.draw(st.lists(st.lists(cells, min_size=len(headers), max_size=len(headers)), min_size=1,
                              max_size=4))
    for r in body:
        table.add_row(*r)
    text = table_text(table, width)
    assert "…" not in text
    tokens = {tok for line in text.splitlines() for tok in line.replace("│", " ").split()}
    assert {c for r in body for c in r} <= tokens
    assert "examples/some_long_file_name.toml" in tokens  # the title breaks at spaces only
    longest_item = max(len(x) for x in [*tokens, *(h for h in headers)])
    assert max(len(line) for line in text.splitlines()) <= max(width, longest_item + 2)


@pytest.mark.parametrize("width", ["30", "45"])
def test_command_tables_never_cut(width: str) -> None:
    """solve's cost table and compile's gate table and --explain at narrow terminals: no '…' anywhere."""
    ex = str(EXAMPLES / "two_robots_5x5.toml")
    for args in (["solve", ex, "-m", "cpsat"], ["compile", ex, "--explain"]):
        res = run_env(args, width)
        assert res.exit_code == 0, res.output
        assert "…" not in res.output
    res = run_env(["compile", ex, "--explain"], width)
    assert "two_robots_5x5.toml:" in res.output  # the title's file name whole


def test_the_run_helper_is_used() -> None:
    assert_one_line_error(run("estimate", "--grid", "0x0"), "grid")
