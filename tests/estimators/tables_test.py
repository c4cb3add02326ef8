"""Rows, text formats and the plot."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest

from estimators.paper import paper_estimate
from estimators.plots import plot_rows
from estimators.sweep import Point, sweep
from estimators.tables import FORMATS, MAIN_COLUMNS, make_rows, render

REQUIRED = {
    "rows", "cols", "robots", "p", "qubits", "data_qubits", "ancillas", "cx", "single_qubit", "t", "depth",
    "two_qubit_depth", "sections",
}  # fmt: skip
PAPER = {"paper_qubits", "paper_cx", "paper_single_qubit", "ratio_qubits", "ratio_cx", "ratio_single_qubit"}


@pytest.fixture(scope="module")
def results():  # type: ignore[no-untyped-def]
    return sweep([Point(2, 2, 1, 1), Point(2, 3, 2, 1), Point(3, 3, 1, 2)], use_cache=False, progress=False)


def test_rows_have_the_required_keys(results) -> None:  # type: ignore[no-untyped-def]
    plain, compared = make_rows(results), make_rows(results, compare_paper=True)
    for row in plain:
        assert set(row) >= REQUIRED and not PAPER & set(row)
    for row, res in zip(compared, results):
        assert set(row) >= REQUIRED | PAPER
        est = paper_estimate(row["rows"], row["cols"], row["robots"], row["p"])
        assert (row["paper_qubits"], row["paper_cx"]) == (est.qubits, est.cx)
        assert row["ratio_cx"] == round(res.counts.cx / est.cx, 4)
        assert row["cx"] == res.counts.cx and row["depth"] == res.counts.depth
        assert set(row["sections"]) == set(res.counts.sections)
    assert set(compared[2]["sections"]) == {"initial_state", "phase_0", "mixer_0", "phase_1", "mixer_1"}


def test_json_is_a_list_of_row_objects(results) -> None:  # type: ignore[no-untyped-def]
    rows = make_rows(results, compare_paper=True)
    data = json.loads(render(rows, "json"))
    assert isinstance(data, list) and len(data) == 3
    assert data[1]["sections"]["phase_0"]["cx"] == rows[1]["sections"]["phase_0"]["cx"]


def test_csv_has_every_scalar_and_section_column(results) -> None:  # type: ignore[no-untyped-def]
    rows = make_rows(results)
    parsed = list(csv.DictReader(io.StringIO(render(rows, "csv"))))
    assert len(parsed) == 3
    assert int(parsed[0]["cx"]) == rows[0]["cx"]
    assert int(parsed[2]["section.mixer_1.depth"]) == rows[2]["sections"]["mixer_1"]["depth"]
    assert parsed[0]["section.mixer_1.depth"] == ""  # p = 1 has no second layer


def test_markdown_and_table(results) -> None:  # type: ignore[no-untyped-def]
    rows = make_rows(results, compare_paper=True)
    md = render(rows, "md").splitlines()
    assert md[0].startswith("| rows | cols |") and "paper_cx" in md[0]
    assert len(md) == 2 + 3
    assert md[2].split("|")[1 + MAIN_COLUMNS.index("cx")].strip() == str(rows[0]["cx"])
    table = render(rows, "table")
    assert "paper_cx" in table and str(rows[1]["cx"]) in table
    with pytest.raises(ValueError):
        render(rows, "xml")  # type: ignore[arg-type]
    assert set(FORMATS) == {"table", "md", "csv", "json"}


def test_plot_is_written_atomically(results, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "sub" / "plot.png"
    path.parent.mkdir()  # output folders are never created (gridcover.atomic)
    assert plot_rows(make_rows(results), path) == str(path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert [p.name for p in path.parent.iterdir()] == ["plot.png"]  # no temporary file left behind
    with pytest.raises(ValueError):
        plot_rows([], tmp_path / "empty.png")
    assert not (tmp_path / "empty.png").exists()
