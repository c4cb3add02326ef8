"""Sweep: range parsing, parallel results equal serial ones, the on-disk cache and its invalidation."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from circuitgen.lowering import lower
from circuitgen.qaoa import qaoa_circuit
from estimators import sweep as sweep_mod
from estimators.counts import count
from estimators.sweep import (
    Point,
    PointResult,
    estimate_point,
    grid_points,
    parse_grid_range,
    parse_int_range,
    source_version,
    sweep,
)
from gridcover.errors import ScenarioError
from gridcover.presets import default_scenario


def test_parse_grid_range() -> None:
    assert parse_grid_range("3x4") == [(3, 4)]
    assert parse_grid_range(" 2X2..3x3 ") == [(2, 2), (2, 3), (3, 2), (3, 3)]
    assert len(parse_grid_range("2x2..8x8")) == 49
    for bad in ["3", "3x", "x3", "1x3", "3x4..2x5", "2x2..3x3..4x4", "axb", "3x3..", ""]:
        with pytest.raises(ValueError):
            parse_grid_range(bad)


def test_parse_int_range() -> None:
    assert parse_int_range("2") == [2]
    assert parse_int_range("1..4", "robots", 1, 4) == [1, 2, 3, 4]
    for bad, lo, hi in [("0", 1, 4), ("1..5", 1, 4), ("3..1", 1, None), ("a", 0, None), ("1...2", 0, None)]:
        with pytest.raises(ValueError):
            parse_int_range(bad, "robots", lo, hi)


def test_grid_points_order_and_validation() -> None:
    pts = grid_points([(2, 2), (2, 3)], [1, 2], [1, 2])
    assert [p.label for p in pts[:3]] == ["2x2 r1 p1", "2x2 r1 p2", "2x2 r2 p1"]
    assert len(pts) == 8
    with pytest.raises(ScenarioError):
        grid_points([(2, 2)], [5], [1])
    with pytest.raises(ValueError):
        grid_points([(2, 2)], [1], [1], rule="fast")


def test_point_result_equals_direct_count_and_round_trips() -> None:
    res = estimate_point(Point(3, 3, 1, 1))
    assert res.counts == count(lower(qaoa_circuit(default_scenario(3, 3, 1), 1)))
    again = PointResult.from_dict(json.loads(json.dumps(res.to_dict())), cached=True)
    assert again.counts == res.counts and again.fault_tolerant == res.fault_tolerant and again.cached
    assert set(res.timings) == {"build", "lower", "count", "fault_tolerant"}


def test_parallel_sweep_equals_serial_and_keeps_order(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("QCPP_CACHE_DIR", str(tmp_path))  # the default cache directory: must stay empty
    pts = grid_points([(2, 3), (3, 3), (2, 2)], [1, 2], [1])
    par = sweep(pts, jobs=2, use_cache=False, progress=False)
    ser = sweep(list(reversed(pts)), jobs=1, use_cache=False, progress=False)
    assert [r.point for r in par] == pts
    assert [r.counts for r in par] == [r.counts for r in reversed(ser)]
    assert not any(tmp_path.iterdir())


def test_cache_is_written_read_and_skipped_with_no_cache(tmp_path: Path) -> None:
    pts = [Point(2, 3, 2, 1), Point(2, 2, 1, 2)]
    first = sweep(pts, cache=tmp_path, progress=False)
    files = sorted(tmp_path.glob("*.json"))
    assert len(files) == 2 and not any(f.name.startswith(".tmp") for f in tmp_path.iterdir())
    assert not any(r.cached for r in first)
    second = sweep(pts, cache=tmp_path, progress=False)
    assert all(r.cached for r in second)
    assert [r.counts for r in second] == [r.counts for r in first]
    # --no-cache: computed afresh, nothing read or written
    for f in files:
        f.write_text("{not json")
    fresh = sweep(pts, cache=tmp_path, use_cache=False, progress=False)
    assert not any(r.cached for r in fresh)
    assert all(f.read_text() == "{not json" for f in files)
    # a corrupt cache file is recomputed and rewritten
    again = sweep(pts, cache=tmp_path, progress=False)
    assert not any(r.cached for r in again)
    assert all(json.loads(f.read_text())["point"] for f in files)


def test_cache_key_depends_on_point_options_and_version(monkeypatch: pytest.MonkeyPatch) -> None:
    key = sweep_mod._cache_key
    base = key(Point(3, 3, 1, 1), {"epsilon": 1e-3})
    assert key(Point(3, 3, 1, 1), {"epsilon": 1e-3}) == base
    assert key(Point(3, 3, 1, 2), {"epsilon": 1e-3}) != base
    assert key(Point(3, 3, 1, 1, "paper"), {"epsilon": 1e-3}) != base
    assert key(Point(3, 3, 1, 1), {"epsilon": 1e-4}) != base
    monkeypatch.setattr(sweep_mod, "source_version", lambda: "0" * 16)
    assert key(Point(3, 3, 1, 1), {"epsilon": 1e-3}) != base


def test_source_version_covers_the_three_packages() -> None:
    v = source_version()
    assert len(v) == 16 and int(v, 16) >= 0
    assert sweep_mod._PACKAGES == ("circuitgen", "gridcover", "estimators")


def test_scenario_point_and_cache_dir_env(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    s = default_scenario(2, 3, 1)
    pt = Point.from_scenario(s, 1)
    assert (pt.rows, pt.cols, pt.robots) == (2, 3, 1)
    assert pt.build_scenario() == s
    assert estimate_point(pt).counts == estimate_point(Point(2, 3, 1, 1)).counts
    monkeypatch.setenv("QCPP_CACHE_DIR", str(tmp_path / "c"))
    assert sweep_mod.cache_dir() == tmp_path / "c"
    monkeypatch.delenv("QCPP_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert sweep_mod.cache_dir() == tmp_path / "qcpp" / "estimates"


def test_on_result_callback_sees_every_point(tmp_path: Path) -> None:
    seen: list[Point] = []
    pts = [Point(2, 2, 1, 1), Point(2, 2, 2, 1)]
    sweep(pts, cache=tmp_path, progress=False, on_result=lambda r: seen.append(r.point))
    sweep(pts, cache=tmp_path, progress=False, on_result=lambda r: seen.append(r.point))
    assert sorted(seen, key=lambda p: p.robots) == sorted(pts * 2, key=lambda p: p.robots)
