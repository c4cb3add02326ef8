"""The resource table fits the terminal: no line wider than ``COLUMNS``; ``--wide``/``--columns`` ask for more;
CSV, JSON and Markdown keep every column whatever the width."""

from __future__ import annotations

import csv
import io
import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from qcpp.cli.app import app
from qcpp.estimators.estimate import Point, estimate_point
from qcpp.estimators.tables import MAIN_COLUMNS, PAPER_COLUMNS, make_rows, render, table_columns

GOAL = ["estimate", "--grid", "3x3..6x6", "--robots", "1..3", "--compare", "paper"]


@pytest.fixture(scope="module")
def rows() -> list[dict]:
    points = [Point(r, c, k, 1) for r, c in [(2, 2), (3, 3), (4, 5)] for k in (1, 3)]
    return make_rows([estimate_point(pt) for pt in points], compare_paper=True)


def widths(text: str) -> list[int]:
    return [len(line) for line in text.splitlines()]


def test_the_issue_command_fits_100_columns() -> None:
    res = CliRunner().invoke(app, GOAL, env={"COLUMNS": "100"})
    assert res.exit_code == 0, res.stderr
    assert max(widths(res.stdout)) <= 100 and max(widths(res.stderr), default=0) <= 100
    header = next(line for line in res.stdout.splitlines() if "rows" in line)
    assert all(c in header for c in ("rows", "cols", "robots", "qubits", "cx", "paper_cx"))
    assert "hidden to fit 100 columns" in res.stdout and "--wide" in res.stdout
    assert len([line for line in res.stdout.splitlines() if line.startswith("│")]) == 16 * 3


@settings(max_examples=10, deadline=None)
@given(width=st.integers(40, 250))
def test_no_table_line_is_wider_than_the_width(rows: list[dict], width: int) -> None:
    text = render(rows, "table", width=width)
    assert max(widths(text)) <= width
    shown, hidden = table_columns(rows, width)
    assert set(shown) | set(hidden) == set(MAIN_COLUMNS) | set(PAPER_COLUMNS)
    assert {"rows", "cols", "robots", "p", "qubits", "cx", "paper_cx"} <= set(shown)


def test_wider_terminals_show_at_least_as_many_columns(rows: list[dict]) -> None:
    counts = [len(table_columns(rows, w)[0]) for w in range(60, 260, 10)]
    assert counts == sorted(counts) and counts[-1] == len(MAIN_COLUMNS) + len(PAPER_COLUMNS)


def test_wide_and_columns(rows: list[dict]) -> None:
    wide = render(rows, "table", width=60, wide=True)
    assert "two_qubit_depth" in wide and "paper_single_qubit" in wide and "hidden" not in wide
    picked = render(rows, "table", width=60, columns=["rows", "gates", "toffoli"])
    header = next(line for line in picked.splitlines() if "rows" in line)
    assert "gates" in header and "toffoli" in header and "qubits" not in header
    with pytest.raises(ValueError, match="no column 'nope'"):
        render(rows, "table", columns=["rows", "nope"])


def test_columns_choose_the_md_and_csv_columns_and_json_refuses_them(rows: list[dict]) -> None:
    """``--columns`` holds for every tabular format (``csv`` also takes a section's flattened field); JSON rows are
    ``Estimate.to_dict()`` whole, so choosing columns there is refused, never silently ignored."""
    md = render(rows, "md", columns=["cx", "rows"]).splitlines()
    assert md[0] == "| cx | rows |" and md[2] == f"| {rows[0]['cx']} | {rows[0]['rows']} |" and len(md) == len(rows) + 2
    csv_lines = render(rows, "csv", columns=["rows", "section.phase.cx"]).splitlines()
    assert csv_lines[0] == "rows,section.phase.cx"
    assert csv_lines[1] == f"{rows[0]['rows']},{rows[0]['sections']['phase']['cx']}"
    for fmt in ("md", "csv"):
        with pytest.raises(ValueError, match="no column 'nope'"):
            render(rows, fmt, columns=["rows", "nope"])
    for fmt in ("json", "jsonl"):
        with pytest.raises(ValueError, match=f"--columns: {fmt} rows keep every field"):
            render(rows, fmt, columns=["rows"])
    assert render(rows, "md", columns=["rows"]) != render(rows, "md")  # the choice shows


@pytest.mark.parametrize("fmt", ["csv", "json", "md"])
def test_machine_formats_keep_every_column_at_any_width(fmt: str) -> None:
    env = {"COLUMNS": "40"}
    narrow = CliRunner().invoke(app, ["estimate", "--grid", "3x3", "--compare", "paper", "--format", fmt], env=env)
    env["COLUMNS"] = "300"
    wide = CliRunner().invoke(app, ["estimate", "--grid", "3x3", "--compare", "paper", "--format", fmt], env=env)
    assert narrow.exit_code == wide.exit_code == 0
    assert narrow.stdout == wide.stdout
    if fmt == "csv":
        header = next(csv.reader(io.StringIO(narrow.stdout)))
        assert {"two_qubit_depth", "paper_single_qubit", "ft_total_t"} <= set(header)
    elif fmt == "json":
        assert "two_qubit_depth" in json.loads(narrow.stdout)[0]
    else:
        assert all(c in narrow.stdout.splitlines()[0] for c in (*MAIN_COLUMNS, *PAPER_COLUMNS))


@pytest.mark.parametrize("physical", [True, False])
@pytest.mark.parametrize("target", ["nisq", "ft"])
def test_cx_stays_in_the_table_at_80_columns(target: str, physical: bool) -> None:
    """docs/cli.md: the identity columns, ``qubits`` and ``cx`` are always shown; with ``--physical`` the
    logical figures give way first and ``physical_qubits`` stays too (a table, not one field per line), and the
    note names the rest (``physical_runtime_s`` among them at 80 columns)."""
    args = ["estimate", "--grid", "3x3,5x5", "--robots", "2", "--target", target] + (["--physical"] if physical else [])
    res = CliRunner().invoke(app, args, env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.stderr
    assert max(widths(res.stdout)) <= 80 and "row 1 of 2" not in res.stdout
    header = next(line for line in res.stdout.splitlines() if "rows" in line)
    assert all(f" {c} " in header for c in ("rows", "cols", "robots", "qubits", "cx"))
    hidden = res.stdout.split("hidden to fit 80 columns")[1]
    assert " cx," not in hidden
    if physical:
        assert "physical_qubits" in header and "physical_runtime_s" in hidden
    wide = CliRunner().invoke(app, args, env={"COLUMNS": "250"})
    assert "hidden" not in wide.stdout and (not physical or "physical_t_factories" in wide.stdout)
