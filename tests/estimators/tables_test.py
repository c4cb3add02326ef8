"""Rows, text formats (streamed and whole) and the plots."""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import pytest

from qcpp.errors import OptionError
from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.estimators.paper import paper_estimate
from qcpp.estimators.plots import PLOT_METRICS, draw_rows, plot_rows
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
    assert latex[3].startswith("rows & cols & robots & $p$ & qubits & data qubits & ancillas & CNOTs &")
    assert latex[5].split(" & ")[MAIN_COLUMNS.index("cx")] == f"{rows[0]['cx']:,}".replace(",", "{,}")


def test_plot_is_written_atomically(results, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "sub" / "plot.png"
    path.parent.mkdir()  # output folders are never created (qcpp.io.atomic)
    assert plot_rows(make_rows(results), path) == str(path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert [p.name for p in path.parent.iterdir()] == ["plot.png"]  # no temporary file left behind
    with pytest.raises(ValueError):
        plot_rows([], tmp_path / "empty.png")
    assert not (tmp_path / "empty.png").exists()


def _lines(fig) -> list[tuple[str, str, list[float], list[float]]]:  # type: ignore[no-untyped-def]
    """(panel title, curve label, xs, ys) of every curve of a figure's visible panels."""
    return [
        (ax.get_title(), line.get_label(), list(line.get_xdata()), list(line.get_ydata()))
        for ax in fig.axes if ax.get_visible() for line in ax.lines
    ]  # fmt: skip


@pytest.fixture(scope="module")
def sweep_rows() -> list[dict]:  # type: ignore[type-arg]
    points = [Point(r, c, k, p) for r, c in ((2, 2), (2, 3), (3, 3)) for k in (1, 2) for p in (1, 2)]
    return make_rows([estimate_point(pt, EstimateOptions(depth="none")) for pt in points if k_fits(pt)], True)


def k_fits(pt: Point) -> bool:
    return pt.robots <= 2 * (pt.rows + pt.cols) - 4


def test_plot_draws_every_p_in_its_own_panel_and_the_paper_only_when_asked(sweep_rows) -> None:  # type: ignore[no-untyped-def]
    fig = draw_rows(sweep_rows, "cx")
    curves = _lines(fig)
    assert {title for title, *_ in curves} == {"p = 1", "p = 2"}
    assert not any("paper" in label for _, label, *_ in curves)  # ours only, unless asked
    for title, label, xs, ys in curves:
        p, robots = int(title.split("= ")[1]), int(label.split()[0])
        want = {r["rows"] * r["cols"]: r["cx"] for r in sweep_rows if r["p"] == p and r["robots"] == robots}
        assert dict(zip(xs, ys)) == want  # every point of that p and robot count, at its node count
    assert "cx" in fig.axes[0].get_ylabel() and "gates" in fig.axes[0].get_ylabel()
    compared = _lines(draw_rows(sweep_rows, "qubits", compare_paper=True))
    paper = [curve for curve in compared if curve[1].startswith("paper, ")]
    assert len(paper) == 4  # one dashed curve per robot count and panel
    for title, label, xs, ys in paper:
        p, robots = int(title.split("= ")[1]), int(label.split()[1])
        want = {r["rows"] * r["cols"]: r["paper_qubits"] for r in sweep_rows if r["p"] == p and r["robots"] == robots}
        assert dict(zip(xs, ys)) == want


def test_plot_of_one_grid_is_against_p_and_names_the_metric(sweep_rows) -> None:  # type: ignore[no-untyped-def]
    rows = [r for r in sweep_rows if (r["rows"], r["cols"]) == (3, 3)]
    fig = draw_rows(rows, "t")
    (ax,) = [a for a in fig.axes if a.get_visible()]
    assert ax.get_xlabel() == "QAOA layers p" and ax.get_ylabel().startswith("T gates (lowered): t [gates]")
    assert {label for label in (line.get_label() for line in ax.lines)} == {"1 robot", "2 robots"}
    with pytest.warns(UserWarning, match="no estimate of t"):
        draw_rows(rows, "t", compare_paper=True)


def test_plot_refuses_unknown_metrics_and_missing_columns(sweep_rows) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(OptionError, match=r"metric: expected qubits or .* or esp_idle, got 'cnots'"):
        draw_rows(sweep_rows, "cnots")
    with pytest.raises(ValueError, match=r"no row has a value for depth .*--depth none"):
        draw_rows(sweep_rows, "depth")  # estimated with depth="none"
    with pytest.raises(ValueError, match=r"routed_twoq .*--device"):
        draw_rows(sweep_rows, "routed_twoq")
    for name, metric in PLOT_METRICS.items():  # the metrics name real columns (and real paper columns)
        assert metric.needs in ("physical", "device") or name in sweep_rows[0], name
        assert metric.paper is None or metric.paper in sweep_rows[0], name


def test_grids_of_one_size_keep_their_own_points_and_draw_no_line() -> None:
    """2x6, 3x4, 4x3 and 6x2 need different circuits: each keeps its count (none averaged away), the curve that
    holds them is points alone, and the axis label says why; a curve of distinct sizes keeps its line."""
    grids = ((2, 6), (3, 4), (4, 3), (6, 2), (3, 3))
    rows = make_rows([estimate_point(Point(r, c, 1, 1), EstimateOptions(depth="none")) for r, c in grids], True)
    ((_, _, xs, ys),) = _lines(fig := draw_rows(rows, "cx"))
    assert sorted(zip(xs, ys)) == sorted((r["rows"] * r["cols"], r["cx"]) for r in rows)
    (line,) = fig.axes[0].lines
    assert line.get_linestyle() == "None" and "a point each" in fig.axes[0].get_xlabel()
    square = [r for r in rows if r["rows"] * r["cols"] != 12]
    rows_2 = make_rows([estimate_point(Point(2, 2, 1, 1), EstimateOptions(depth="none"))], True) + square
    (line,) = draw_rows(rows_2, "cx").axes[0].lines
    assert line.get_linestyle() == "-"


@pytest.fixture(scope="module")
def bound_row() -> dict:
    """One row whose depths are bounds (``depth="bound"``), next to the exact figures of the same point."""
    pt = Point(3, 3, 1, 1)
    bound = make_row(estimate_point(pt, EstimateOptions(depth="bound")))
    exact = make_row(estimate_point(pt))
    assert bound["depth_kind"] == "bound" and exact["depth_kind"] == "exact"
    return bound


@pytest.mark.parametrize("width", [40, 80, 200])
def test_the_table_marks_a_bound_depth_and_never_titles_it_exact(bound_row, width: int) -> None:  # type: ignore[no-untyped-def]
    text = render([bound_row], "table", width=width)
    assert f"<={bound_row['depth']}" in text  # whether or not depth_kind fits
    assert "Exact resource counts" not in text and "upper bound" in text


def test_exact_depths_are_unmarked_under_the_exact_title(results) -> None:  # type: ignore[no-untyped-def]
    text = render(make_rows(results), "table", width=200)
    assert "<=" not in text and "Exact resource counts (lowered circuit)" in text


def test_md_and_latex_mark_a_bound_csv_and_json_keep_the_number(bound_row) -> None:  # type: ignore[no-untyped-def]
    d, d2 = bound_row["depth"], bound_row["two_qubit_depth"]
    md = render([bound_row], "md", columns=["rows", "depth", "two_qubit_depth"])
    assert md.splitlines()[2] == f"| 3 | <={d} | <={d2} |"
    assert md.rstrip().splitlines()[-1] == "<=N is an upper bound"  # the footnote says what the mark means
    assert "upper bound" not in render([bound_row], "md", columns=["rows", "cx"])  # no mark shown, no footnote
    latex = render([bound_row], "latex", columns=["rows", "depth"])
    assert rf"3 & $\leq${d:,} \\".replace(",", "{,}") in latex and "see depth_kind" not in latex
    row = next(csv.DictReader(io.StringIO(render([bound_row], "csv"))))
    assert (row["depth"], row["depth_kind"]) == (str(d), "bound")
    assert json.loads(render([bound_row], "json"))[0]["depth"] == d


def test_the_hidden_columns_note_says_what_each_format_keeps(results) -> None:  # type: ignore[no-untyped-def]
    rows = make_rows(results)
    note = " ".join(render(rows, "table", width=60).split())
    assert "--format md shows every table column, csv and json every field" in note
    md_header = render(rows, "md").splitlines()[0].strip("| ").split(" | ")
    assert md_header == list(MAIN_COLUMNS)  # every table column, no more
    assert len(next(csv.reader(io.StringIO(render(rows, "csv"))))) > len(MAIN_COLUMNS)


def test_plot_draws_points_that_are_not_exact_hollow_and_says_so() -> None:
    """A physical figure computed from a depth bound is approximate, a bounded routing's count an upper bound and
    its ESP a lower one: hollow marker, legend entry; exact rows have neither."""
    from qcpp.estimators.plots import BOUND_LABEL, draw_rows

    def rows(kinds: list[str]) -> list[dict]:
        return [{"rows": n, "cols": n, "robots": 1, "p": 1, "rule": "exact", "physical_qubits": 1000 * n,
                 "physical_depth_kind": kind} for n, kind in zip((3, 6, 10), kinds, strict=True)]  # fmt: skip

    def hollow_and_legend(fig) -> tuple[int, list[str]]:  # type: ignore[no-untyped-def]
        ax = fig.axes[0]
        hollow = sum(len(line.get_xdata()) for line in ax.get_lines() if line.get_markerfacecolor() == "white")
        return hollow, [t.get_text() for t in fig.legends[0].get_texts()]

    hollow, legend = hollow_and_legend(draw_rows(rows(["exact", "bound", "bound"]), "physical_qubits"))
    assert hollow == 2 and BOUND_LABEL in legend
    hollow, legend = hollow_and_legend(draw_rows(rows(["exact"] * 3), "physical_qubits"))
    assert hollow == 0 and BOUND_LABEL not in legend
    routed = [{"rows": n, "cols": n, "robots": 1, "p": 1, "rule": "exact", "routed_twoq": 100 * n, "esp": 0.5 / n,
               "routed_kind": kind} for n, kind in ((3, "exact"), (6, "bound"), (10, "bound"))]  # fmt: skip
    for column in ("routed_twoq", "esp"):  # a bounded routing's count (upper bound) and ESP (lower bound)
        hollow, legend = hollow_and_legend(draw_rows(routed, column))
        assert hollow == 2 and BOUND_LABEL in legend, column


def test_a_table_without_the_first_phase_separator_says_so() -> None:
    """Rows counted with ``p - 1`` phase separators are named in the table title, under an md table and in the LaTeX
    comment (so a ratio to the paper's ``p`` is not read as like for like); the default circuit's tables are not."""
    from qcpp.plan.options import PlanOptions

    point = Point(3, 3, 2, 1)
    skipped = make_rows([estimate_point(point, EstimateOptions(plan=PlanOptions(first_phase=False)))], True)
    default = make_rows([estimate_point(point)], True)
    assert skipped[0]["first_phase"] is False and "first_phase" not in default[0]
    assert skipped[0]["cx"] < default[0]["cx"]
    note = "without the first phase separator"
    for fmt in ("table", "md", "latex"):
        assert note in render(skipped, fmt, width=200), fmt
        assert note not in render(default, fmt, width=200), fmt
    assert note in "".join(render_stream(iter(skipped), "md"))


@pytest.fixture(scope="module")
def routed_bound_row() -> dict:
    """A row of a 12x20 field routed by the bound (``routed_kind`` ``bound``): its ESP underflows to 0.0."""
    from qcpp.estimators import routed
    from qcpp.hardware.device import get_device

    row = make_row(estimate_point(Point(3, 3, 1, 1)))
    bound = routed._bound(get_device("heavy-hex:9"), 1_629_850, 120_000, 400, routed.LAYOUT_BOUND_MODEL)
    return {**row, "device": "heavy-hex:9", "fits": True, **bound}


ROUTED = ["rows", "routed_twoq", "routed_kind", "esp", "log10_esp", "duration_s"]


@pytest.mark.parametrize("fmt", ["table", "md", "latex"])
def test_every_routed_bound_is_marked_the_esp_as_a_lower_bound(routed_bound_row, fmt: str) -> None:  # type: ignore[no-untyped-def]
    """``routed_twoq`` of a bound routing is an upper bound like its duration; its ESP, computed from those gates at
    the worst error rates, a lower bound; an ESP below the smallest double is shown from its log, not as 0."""
    r = routed_bound_row
    text = render([r], fmt, columns=ROUTED, width=200)
    le, ge = (r"$\leq$", r"$\geq$") if fmt == "latex" else ("<=", ">=")
    twoq = f"{r['routed_twoq']:,}".replace(",", "{,}") if fmt == "latex" else str(r["routed_twoq"])
    exponent = math.floor(r["log10_esp"])
    mantissa = f"{10 ** (r['log10_esp'] - exponent):.4g}"
    assert f"{le}{twoq}" in text and f"{ge}{mantissa}e{exponent}" in text and f"{le}{r['duration_s']:.4g}" in text
    assert "lower bound" in text and "upper bound" in text


def test_routed_bounds_keep_their_numbers_in_csv_and_json(routed_bound_row) -> None:  # type: ignore[no-untyped-def]
    r = routed_bound_row
    row = next(csv.DictReader(io.StringIO(render([r], "csv", columns=ROUTED))))
    assert (row["routed_twoq"], row["routed_kind"], row["esp"]) == (str(r["routed_twoq"]), "bound", "0")
    assert float(row["log10_esp"]) == pytest.approx(r["log10_esp"], abs=0.005)
    out = json.loads(render([r], "json"))[0]
    assert (out["routed_twoq"], out["esp"], out["log10_esp"]) == (r["routed_twoq"], 0.0, r["log10_esp"])


def test_an_exact_routing_is_unmarked(routed_bound_row) -> None:  # type: ignore[no-untyped-def]
    r = {**routed_bound_row, "routed_kind": "exact", "routed_depth_kind": "exact", "esp": 0.25, "log10_esp": -0.602}
    text = render([r], "md", columns=ROUTED)
    assert "<=" not in text and ">=" not in text and "| 0.25 |" in text
