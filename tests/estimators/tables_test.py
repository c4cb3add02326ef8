"""Rows, text formats (streamed and whole) and the plot."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest

from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.estimators.paper import paper_estimate
from qcpp.estimators.plots import plot_rows
from qcpp.estimators.tables import FORMATS, MAIN_COLUMNS, make_row, make_rows, render, render_stream

REQUIRED = {
    "rows", "cols", "robots", "p", "rule", "target", "qubits", "data_qubits", "ancillas", "gates", "cx",
    "single_qubit", "t", "rotations", "depth", "two_qubit_depth", "rotation_depth", "depth_kind", "ft_total_t",
    "sections",
}  # fmt: skip
PAPER = {"paper_qubits", "paper_cx", "paper_single_qubit", "ratio_qubits", "ratio_cx", "ratio_single_qubit"}


@pytest.fixture(scope="module")
def results():  # type: ignore[no-untyped-def]
    return [estimate_point(pt) for pt in (Point(2, 2, 1, 1), Point(2, 3, 2, 1), Point(3, 3, 1, 2))]


def test_rows_have_the_required_keys(results) -> None:  # type: ignore[no-untyped-def]
    plain, compared = make_rows(results), make_rows(results, compare_paper=True)
    for row in plain:
        assert set(row) >= REQUIRED and not PAPER & set(row) and "physical_qubits" not in row
    for row, est in zip(compared, results):
        assert set(row) >= REQUIRED | PAPER
        paper = paper_estimate(row["rows"], row["cols"], row["robots"], row["p"])
        assert (row["paper_qubits"], row["paper_cx"]) == (paper.qubits, paper.cx)
        assert row["ratio_cx"] == round(est.cost.cx / paper.cx, 4)
        assert row["cx"] == est.cost.cx and row["depth"] == est.depth.depth and row["depth_kind"] == "exact"
        assert set(row["sections"]) == {"initial_state", "phase", "mixer"}
        layer = row["sections"]["phase"]["cx"] + row["sections"]["mixer"]["cx"]
        assert row["cx"] == row["sections"]["initial_state"]["cx"] + row["p"] * layer


def test_physical_columns() -> None:
    row = make_row(estimate_point(Point(2, 3, 1, 1), EstimateOptions(physical=True)))
    assert row["physical_qubits"] > row["qubits"] and row["physical_runtime_s"] > 0
    assert "qubit_gate_ns_e3" in row["physical_model"] and "surface_code" in row["physical_model"]
    table = render([row], "table")
    assert "physical_qubits" in table


def test_json_and_jsonl(results) -> None:  # type: ignore[no-untyped-def]
    rows = make_rows(results, compare_paper=True)
    assert json.loads(render(rows, "json")) == rows
    assert [json.loads(line) for line in render(rows, "jsonl").splitlines()] == rows
    assert json.loads(render([], "json")) == [] and render([], "jsonl") == ""


def test_csv_has_every_scalar_and_section_column(results) -> None:  # type: ignore[no-untyped-def]
    rows = make_rows(results)
    parsed = list(csv.DictReader(io.StringIO(render(rows, "csv"))))
    assert len(parsed) == 3
    assert int(parsed[0]["cx"]) == rows[0]["cx"]
    assert int(parsed[2]["section.mixer.cx"]) == rows[2]["sections"]["mixer"]["cx"]
    assert parsed[1]["depth_kind"] == "exact"


def test_csv_keeps_columns_added_to_the_rows(results) -> None:  # type: ignore[no-untyped-def]
    """``estimate --device`` adds the routed figures to each row: CSV keeps them, as JSON does."""
    rows = [{**row, "device": "grid:3x3", "routed_twoq": 7 + i} for i, row in enumerate(make_rows(results))]
    parsed = list(csv.DictReader(io.StringIO(render(rows, "csv"))))
    assert [int(r["routed_twoq"]) for r in parsed] == [7, 8, 9] and parsed[0]["device"] == "grid:3x3"
    assert list(parsed[0])[-1].startswith("section.")


def test_streaming_yields_each_row_before_the_next_is_made(results) -> None:  # type: ignore[no-untyped-def]
    made: list[int] = []

    def rows():  # type: ignore[no-untyped-def]
        for i, est in enumerate(results):
            made.append(i)
            yield make_row(est)

    for fmt in ("csv", "jsonl", "json", "md"):
        made.clear()
        stream = render_stream(rows(), fmt)  # type: ignore[arg-type]
        next(stream)
        assert made == [0], fmt
        list(stream)
    whole = render(make_rows(results), "csv")
    assert "".join(render_stream(iter(make_rows(results)), "csv")) == whole


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
    assert set(FORMATS) == {"table", "md", "csv", "json", "jsonl", "latex"}
    latex = render(rows, "latex").splitlines()
    assert latex[3].startswith("rows & cols &")
    assert latex[5].split(" & ")[MAIN_COLUMNS.index("cx")] == str(rows[0]["cx"])


def test_plot_is_written_atomically(results, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "sub" / "plot.png"
    path.parent.mkdir()  # output folders are never created (qcpp.io.atomic)
    assert plot_rows(make_rows(results), path) == str(path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert [p.name for p in path.parent.iterdir()] == ["plot.png"]  # no temporary file left behind
    with pytest.raises(ValueError):
        plot_rows([], tmp_path / "empty.png")
    assert not (tmp_path / "empty.png").exists()
