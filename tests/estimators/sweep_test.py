"""Sweep: range parsing, skipped grids, lazy in-order streaming, and equality with single-point estimates."""

from __future__ import annotations

import itertools

import pytest

from qcpp.estimators import estimate as estimate_mod
from qcpp.estimators.estimate import Point, estimate_point
from qcpp.estimators.sweep import grid_points, parse_grid_range, parse_int_range, skipped_points, sweep


def test_parse_grid_range() -> None:
    assert parse_grid_range("3x4") == [(3, 4)]
    assert parse_grid_range(" 2X2..3x3 ") == [(2, 2), (2, 3), (3, 2), (3, 3)]
    assert len(parse_grid_range("2x2..8x8")) == 49
    assert len(parse_grid_range("2x2..40x40")) == 1521
    for bad in ["3", "3x", "x3", "1x3", "3x4..2x5", "2x2..3x3..4x4", "axb", "3x3..", ""]:
        with pytest.raises(ValueError):
            parse_grid_range(bad)


def test_parse_int_range() -> None:
    assert parse_int_range("2") == [2]
    assert parse_int_range("1..8", "robots", 1) == list(range(1, 9))
    for bad, lo, hi in [("0", 1, 4), ("1..5", 1, 4), ("3..1", 1, None), ("a", 0, None), ("1...2", 0, None)]:
        with pytest.raises(ValueError):
            parse_int_range(bad, "robots", lo, hi)


def test_parse_int_range_takes_comma_lists_of_counts_and_ranges() -> None:
    assert parse_int_range("2,8", "--robots", 1) == [2, 8]
    assert parse_int_range("8, 2..4,3", "--robots", 1) == [2, 3, 4, 8]
    with pytest.raises(ValueError, match=r"^--robots: expected N, A\.\.B or a comma list of them, got '2,,8'$"):
        parse_int_range("2,,8", "--robots", 1)
    with pytest.raises(ValueError, match=r"^-p/--layers: must be at least 1, got 0$"):
        parse_int_range("2,0", "-p/--layers", 1)


def test_grid_points_skip_grids_too_small_for_the_robots() -> None:
    pts = grid_points([(2, 2), (2, 3)], [1, 5], [1, 2])
    assert [p.label for p in pts] == ["2x2 r1 p1", "2x2 r1 p2", "2x3 r1 p1", "2x3 r1 p2", "2x3 r5 p1", "2x3 r5 p2"]
    assert skipped_points([(2, 2), (2, 3)], [1, 5], [1, 2]) == 2  # 2x2 hosts four robots
    grids = parse_grid_range("2x2..40x40")
    total = len(grids) * 8 * 5
    kept = len(grid_points(grids, range(1, 9), range(1, 6)))
    assert total == 60_840 and kept + skipped_points(grids, range(1, 9), range(1, 6)) == total


def test_sweep_is_lazy_and_in_order(monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[Point] = []
    real = estimate_mod.estimate_point

    def spy(pt, options=estimate_mod.DEFAULT_OPTIONS):  # type: ignore[no-untyped-def]
        seen.append(pt)
        return real(pt, options)

    monkeypatch.setattr("qcpp.estimators.sweep.estimate_point", spy)
    pts = grid_points([(2, 3), (3, 3)], [1, 2], [1, 2])
    stream = sweep(pts)
    first = list(itertools.islice(stream, 2))
    assert seen == pts[:2] and [e.point for e in first] == pts[:2]  # nothing computed ahead of the consumer
    rest = list(stream)
    assert [e.point for e in first + rest] == pts


def test_sweep_equals_single_points() -> None:
    pts = grid_points([(2, 2), (3, 4)], [1, 3], [1, 3])
    for est in sweep(pts):
        alone = estimate_point(est.point)
        assert (est.cost, est.logical, est.registers, est.depth) == (
            alone.cost,
            alone.logical,
            alone.registers,
            alone.depth,
        )


def test_the_sweep_restores_the_collectors_thresholds_when_done_or_closed() -> None:
    import gc

    from qcpp.estimators.sweep import SWEEP_GC_THRESHOLD

    before = gc.get_threshold()
    rows = sweep(grid_points([(2, 2), (3, 3)], [1], [1]))
    next(rows)
    assert gc.get_threshold() == SWEEP_GC_THRESHOLD  # while sweeping
    rows.close()  # a consumer that stops early (Ctrl-C, --limit)
    assert gc.get_threshold() == before
    assert len(list(sweep(grid_points([(2, 2)], [1], [1])))) == 1
    assert gc.get_threshold() == before
