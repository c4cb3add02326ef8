"""Estimates over ranges of (rows, cols, robots, p): range parsing, the points, and a streaming sweep.

Each point costs one lookup in the plan's layer costs (:func:`qcpp.estimators.estimate.layer_costs`, cached per
scenario, so the ``p`` values of one grid and robot count share one plan), so a sweep runs in this process, in
order, yielding each estimate as soon as it is ready (no circuit is built, so no process pool or disk cache).

Grids too small for a robot count (the default placement hosts ``2 (rows + cols) - 4`` robots, see
:mod:`qcpp.problem.presets`) are left out of :func:`grid_points`; :func:`skipped_points` counts them so that the
caller can say so once.

Range syntax (:func:`parse_grid_range`, :func:`parse_int_range`): ``3x4`` is one grid; ``AxB..CxD`` is every
``rows`` in ``A..C`` and every ``cols`` in ``B..D`` (rectangles included: ``2x2..4x4`` is 9 grids);
``1..4`` is 1, 2, 3, 4; either takes a comma list of items (``3x3,5x5``; ``1,4..6``).

Example:
    >>> [e.cost.cx for e in sweep(grid_points([(2, 2)], [1, 5], [1]))]
    [10]
    >>> skipped_points([(2, 2)], [1, 5], [1])
    1
"""

from __future__ import annotations

import gc
import re
from collections.abc import Iterable, Iterator

from qcpp.errors import OptionError, check_count
from qcpp.estimators.estimate import DEFAULT_OPTIONS, Estimate, EstimateOptions, Point, estimate_point
from qcpp.problem.limits import check_grid_size
from qcpp.problem.presets import check_grid_shape, max_default_robots

__all__ = ["grid_points", "parse_grid_range", "parse_int_range", "skipped_points", "sweep"]


# --- range parsing ---------------------------------------------------------------------------------------------
_GRID_RE = re.compile(r"^\s*(\d+)\s*[xX]\s*(\d+)\s*$")


def _grid(text: str, name: str) -> tuple[int, int]:
    m = _GRID_RE.match(text)
    if not m:
        raise OptionError(name, f"expected ROWSxCOLS such as 3x4, got {text.strip()!r}")
    r, c = int(m.group(1)), int(m.group(2))
    check_grid_shape(r, c, name)
    return r, c


def parse_grid_range(text: str, name: str = "grid") -> list[tuple[int, int]]:
    """Grids of ``3x4``, ``AxB..CxD`` (every rows in A..C, every cols in B..D, rows-major order), or a
    comma-separated list of either (``3x3,4x4,5x5``; duplicates dropped, first occurrence kept).

    Args:
        text: the range text.
        name: the option named first in every error (the command line's ``--grid``).

    Returns:
        ``(rows, cols)`` pairs.

    Raises:
        qcpp.errors.OptionError: malformed text or an empty range (``--grid: expected ROWSxCOLS such as 3x4,
            got '3'``).
        qcpp.problem.errors.ScenarioError: a grid below 2x2, as every command words it
            (:func:`qcpp.problem.presets.check_grid_shape`).

    >>> parse_grid_range("2x3..3x4")
    [(2, 3), (2, 4), (3, 3), (3, 4)]
    >>> parse_grid_range("3x3,5x5,3x3")
    [(3, 3), (5, 5)]
    >>> parse_grid_range("0x6", "--grid")
    Traceback (most recent call last):
    ...
    qcpp.problem.errors.ScenarioError: --grid: the grid must be at least 2x2, got 0x6
    """
    if "," in text:
        grids = [g for item in text.split(",") for g in parse_grid_range(item.strip(), name)]
        return list(dict.fromkeys(grids))
    parts = text.split("..")
    if len(parts) == 1:
        return [_grid(parts[0], name)]
    if len(parts) != 2:
        raise OptionError(name, f"expected AxB or AxB..CxD, got {text!r}")
    (r0, c0), (r1, c1) = _grid(parts[0], name), _grid(parts[1], name)
    if r1 < r0 or c1 < c0:
        raise OptionError(name, f"the range is empty (its second grid is smaller than its first), got {text!r}")
    return [(r, c) for r in range(r0, r1 + 1) for c in range(c0, c1 + 1)]


def parse_int_range(text: str, name: str = "value", low: int = 0, high: int | None = None) -> list[int]:
    """Integers of ``N``, ``A..B`` (inclusive) or a comma-separated list of either (``2,4..6,8``).

    Args:
        text: the range text.
        name: the option named first in every error (``-p/--layers``, ``--robots``).
        low: smallest allowed value (checked by :func:`qcpp.errors.check_count`, as every command checks a count).
        high: largest allowed value, if any.

    Returns:
        The integers, ascending, each once.

    Raises:
        qcpp.errors.OptionError: malformed text, out of bounds, or an empty range.

    >>> parse_int_range("1..3", "robots", 1, 4)
    [1, 2, 3]
    >>> parse_int_range("8,2..3,2", "--robots", 1)
    [2, 3, 8]
    >>> parse_int_range("0", "-p/--layers", 1)
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: -p/--layers: must be at least 1, got 0
    """
    if "," in text:
        return sorted({k for item in text.split(",") for k in _int_range(item, text, name, low, high)})
    return _int_range(text, text, name, low, high)


def _int_range(item: str, text: str, name: str, low: int, high: int | None) -> list[int]:
    """The integers of one ``N`` or ``A..B`` item of ``text`` (:func:`parse_int_range`)."""
    m = re.match(r"^\s*(\d+)\s*(?:\.\.\s*(\d+)\s*)?$", item)
    if not m:
        raise OptionError(name, f"expected N, A..B or a comma list of them, got {text.strip()!r}")
    a = int(m.group(1))
    b = int(m.group(2)) if m.group(2) is not None else a
    if b < a:
        raise OptionError(name, f"the range is empty (its end is below its start), got {item.strip()!r}")
    check_count(a, name, low)
    if high is not None and b > high:
        raise OptionError(name, f"must be at most {high}, got {b}")
    return list(range(a, b + 1))


def grid_points(grids: Iterable[tuple[int, int]], robots: Iterable[int], ps: Iterable[int]) -> list[Point]:
    """The cross product as default-scenario points (grid-major, then robots, then p), leaving out the robot
    counts a grid cannot host (:func:`skipped_points` counts them).

    >>> [p.label for p in grid_points([(2, 2)], [1, 2], [1])]
    ['2x2 r1 p1', '2x2 r2 p1']
    """
    grids, robots, ps = list(grids), list(robots), list(ps)
    for r, c in grids:
        check_grid_size(r, c)  # before any scenario of a huge grid is built
    return [Point(r, c, k, p) for r, c in grids for k in robots if k <= max_default_robots(r, c) for p in ps]


def skipped_points(grids: Iterable[tuple[int, int]], robots: Iterable[int], ps: Iterable[int]) -> int:
    """How many points of the cross product :func:`grid_points` leaves out (grid too small for the robots)."""
    robots, n_p = list(robots), len(list(ps))
    return sum(n_p for r, c in grids for k in robots if k > max_default_robots(r, c))


SWEEP_GC_THRESHOLD = (50_000, 50, 100)
"""The cyclic garbage collector's thresholds while :func:`sweep` runs (CPython's default is ``(700, 10, 10)``)."""


def sweep(points: Iterable[Point], options: EstimateOptions = DEFAULT_OPTIONS) -> Iterator[Estimate]:
    """Estimate ``points`` in order, lazily (each estimate is yielded as soon as it is ready).

    Args:
        points: the points.
        options: what to estimate.

    Yields:
        One :class:`~qcpp.estimators.estimate.Estimate` per point.
    """
    # A row allocates tens of thousands of short-lived, acyclic objects next to long-lived cost caches; at
    # CPython's default threshold the cyclic collector runs every 700 allocations, scans them and the caches and
    # finds nothing, so it runs less often while sweeping (reference counting frees the rows).
    threshold = gc.get_threshold()
    gc.set_threshold(*SWEEP_GC_THRESHOLD)
    try:
        for pt in points:
            yield estimate_point(pt, options)
    finally:
        gc.set_threshold(*threshold)
