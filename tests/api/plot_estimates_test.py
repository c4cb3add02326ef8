"""``qcpp.plot_estimates``: the figure of ``qcpp estimate --plot`` from Python estimates; bad input named."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

import qcpp
from qcpp.estimators.plots import draw_rows
from tests.cli.clirun import run


def _curves(fig) -> list[tuple[str, str, list[float], list[float]]]:  # type: ignore[no-untyped-def]
    return [
        (ax.get_title(), line.get_label(), list(line.get_xdata()), list(line.get_ydata()))
        for ax in fig.axes if ax.get_visible() for line in ax.lines
    ]  # fmt: skip


@pytest.mark.heavy
def test_the_python_plot_is_the_command_lines(tmp_path: Path) -> None:
    ests = [
        qcpp.estimate(qcpp.grid_scenario(r, c, robots=k), p=p, depth="none", compare_paper=True)
        for r, c in ((2, 2), (3, 3)) for k in (1, 2) for p in (1, 2)
    ]  # fmt: skip
    res = run("estimate", "--grid", "2x2,3x3", "--robots", "1..2", "-p", "1..2", "--depth", "none",
              "--compare", "paper", "--json")  # fmt: skip
    assert res.exit_code == 0, res.output
    cli_rows = json.loads(res.stdout)
    out = tmp_path / "cx.png"
    fig = qcpp.plot_estimates(ests, "cx", compare_paper=True, path=out)
    assert _curves(fig) == _curves(draw_rows(cli_rows, "cx", compare_paper=True))
    assert {t for t, *_ in _curves(fig)} == {"p = 1", "p = 2"}
    assert out.read_bytes()[:4] == b"\x89PNG" and [p.name for p in tmp_path.iterdir()] == ["cx.png"]


def test_bad_input_is_named() -> None:
    est = qcpp.estimate(qcpp.grid_scenario(2, 2), depth="none")
    with pytest.raises(qcpp.OptionError, match=r"^metric: expected qubits or .*, got 'cnot'$"):
        qcpp.plot_estimates([est], "cnot")
    with pytest.raises(ValueError, match=r"no row has a value for physical_qubits .*--physical"):
        qcpp.plot_estimates([est], "physical_qubits")
    with pytest.raises(ValueError, match="no rows"):
        qcpp.plot_estimates([], "cx")


def test_the_legend_covers_no_point() -> None:
    """The legend sits beside the panels, so no point or curve lies under it (inside an axes, matplotlib's
    ``best`` spot half covered the largest grid's one-robot point of the README's command)."""
    ests = [
        qcpp.estimate(qcpp.grid_scenario(n, n, robots=k), depth="none", compare_paper=True)
        for n in (3, 4, 5, 6) for k in (1, 2, 3)
    ]  # fmt: skip
    fig = qcpp.plot_estimates(ests, "cx", compare_paper=True)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    (legend,) = [*fig.legends, *(ax.get_legend() for ax in fig.axes if ax.get_legend() is not None)]
    box = legend.get_window_extent(canvas.get_renderer())
    points = [ax.transData.transform(xy) for ax in fig.axes for line in ax.lines for xy in line.get_xydata()]
    assert len(points) == 24
    assert not [xy for xy in points if box.contains(*xy)]
    assert not [ax for ax in fig.axes if ax.get_visible() and box.overlaps(ax.bbox)]  # beside, not over, the data


def test_a_stack_of_points_is_named_by_what_sets_it_apart() -> None:
    """Scenarios of one grid (here other hard obstacles) stack at one ``x`` as grids of one size do; the axis label
    names each kind it holds, and never calls scenarios of one grid grids of one size."""
    fields = [qcpp.grid_scenario(4, 4, robots=1, obstacles=obs, hard_obstacles=True) for obs in ([(1, 1)], [(2, 2)])]
    same_grid = [qcpp.estimate(s, depth="none") for s in fields]
    shapes = [qcpp.estimate(qcpp.grid_scenario(r, c), depth="none") for r, c in ((3, 4), (4, 3))]

    def label(ests: list[qcpp.Estimate]) -> str:
        return qcpp.plot_estimates(ests, "cx").axes[0].get_xlabel()

    assert label(same_grid) == "robots\nseveral scenarios of one grid: a point each"
    assert label([*shapes, *same_grid]).endswith("\nseveral grids of one size or scenarios of one grid: a point each")
