"""Exact resource counts over ranges of (rows, cols, robots, p), in parallel, with an on-disk cache.

A :class:`Point` is one circuit: the default scenario (:func:`gridcover.presets.default_scenario`) of a grid
and robot count, or a given scenario, with ``p`` layers and an SBF rule. :func:`estimate_point` builds it
(:func:`circuitgen.qaoa.qaoa_circuit`), lowers it (:func:`circuitgen.lowering.lower`), counts it
(:func:`estimators.counts.count`) and adds the fault-tolerant estimates
(:func:`estimators.fault_tolerant.fault_tolerant_estimate`). :func:`sweep` does that for many points on all
local cores (``concurrent.futures.ProcessPoolExecutor``, largest points first), shows a ``rich`` progress bar on
stderr and keeps one JSON file per point in a cache directory, keyed by a hash of the point, the options and a
version string derived from the source of the ``circuitgen``, ``gridcover`` and ``estimators`` packages (so any
code change invalidates the cache).

Cache directory: ``$QCPP_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/qcpp/estimates`` (default
``~/.cache/qcpp/estimates``).

Range syntax (:func:`parse_grid_range`, :func:`parse_int_range`): ``3x4`` is one grid; ``AxB..CxD`` is every
``rows`` in ``A..C`` and every ``cols`` in ``B..D`` (rectangles included: ``2x2..4x4`` is 9 grids);
``1..4`` is 1, 2, 3, 4.

Example:
    >>> res = sweep([Point(2, 2, 1, 1)], use_cache=False, progress=False)
    >>> res[0].counts.qubits, res[0].counts.cx
    (7, 52)
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import signal
import time
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import asdict, dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from circuitgen._perf import gc_paused  # the cyclic GC rescans millions of acyclic gate tuples
from circuitgen.lowering import lower
from circuitgen.qaoa import qaoa_circuit
from gridcover.atomic import atomic_open
from gridcover.errors import ScenarioError
from gridcover.limits import check_grid_size
from gridcover.presets import MAX_DEFAULT_ROBOTS, default_scenario
from gridcover.sbf import RULES
from gridcover.scenario import Scenario, scenario_from_dict, scenario_to_dict

from .counts import GateCount, ResourceCount, count, count_gates
from .fault_tolerant import DEFAULT_EPSILON, FaultTolerantEstimate, SynthesisModel, fault_tolerant_estimate

__all__ = [
    "CACHE_SCHEMA",
    "Point",
    "PointResult",
    "cache_dir",
    "estimate_point",
    "grid_points",
    "parse_grid_range",
    "parse_int_range",
    "source_version",
    "sweep",
]

CACHE_SCHEMA = 1
_PACKAGES = ("circuitgen", "gridcover", "estimators")


@dataclass(frozen=True)
class Point:
    """One circuit to estimate.

    Attributes:
        rows, cols, robots: the grid and robot count (of the default scenario, or of ``scenario``).
        p: number of QAOA layers.
        rule: SBF rule, ``exact`` or ``paper``.
        scenario: canonical JSON of a given scenario (:func:`gridcover.scenario.scenario_to_dict`), or ``None`` for
            the default scenario of ``rows x cols`` with ``robots`` robots.
    """

    rows: int
    cols: int
    robots: int
    p: int
    rule: str = "exact"
    scenario: str | None = None

    def build_scenario(self) -> Scenario:
        """The scenario of this point."""
        if self.scenario is not None:
            return scenario_from_dict(json.loads(self.scenario))
        return default_scenario(self.rows, self.cols, self.robots)

    @classmethod
    def from_scenario(cls, scenario: Scenario, p: int, rule: str = "exact") -> Point:
        """A point for a given scenario."""
        text = json.dumps(scenario_to_dict(scenario), sort_keys=True)
        g = scenario.grid
        return cls(g.rows, g.cols, scenario.num_robots, p, rule, text)

    @property
    def size_hint(self) -> int:
        """Rough work estimate (the phase separator dominates): ``(robots * edges)^2 * p``."""
        edges = self.rows * (self.cols - 1) + self.cols * (self.rows - 1)
        return (self.robots * edges) ** 2 * max(self.p, 1) + 1

    @property
    def label(self) -> str:
        """Short text such as ``3x4 r2 p1``."""
        return f"{self.rows}x{self.cols} r{self.robots} p{self.p}" + ("" if self.rule == "exact" else f" {self.rule}")


@dataclass(frozen=True)
class PointResult:
    """Exact counts and estimates of one point.

    Attributes:
        point: the point.
        counts: exact counts of the lowered circuit (:class:`~estimators.counts.ResourceCount`).
        high_level: counts of the circuit before lowering (``mcx``, ``csbf``, ``rzz``, ...).
        fault_tolerant: the Clifford+T estimates.
        timings: CPU seconds (of the computing process) spent in ``build``, ``lower``, ``count`` and
            ``fault_tolerant``; CPU time, not wall-clock, so that they mean the same on a busy machine.
        cached: whether the result came from the cache.
    """

    point: Point
    counts: ResourceCount
    high_level: GateCount
    fault_tolerant: FaultTolerantEstimate
    timings: dict[str, float] = field(default_factory=dict)
    cached: bool = False

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (what the cache stores)."""
        return {
            "point": asdict(self.point),
            "counts": self.counts.to_dict(),
            "high_level": self.high_level.to_dict(),
            "fault_tolerant": self.fault_tolerant.to_dict(),
            "timings": dict(self.timings),
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any], cached: bool = False) -> PointResult:
        """Inverse of :meth:`to_dict`."""
        return cls(
            Point(**d["point"]),
            ResourceCount.from_dict(d["counts"]),
            GateCount.from_dict(d["high_level"]),
            FaultTolerantEstimate(**d["fault_tolerant"]),
            {k: float(v) for k, v in d["timings"].items()},
            cached,
        )


# --- range parsing ---------------------------------------------------------------------------------------------
_GRID_RE = re.compile(r"^\s*(\d+)\s*[xX]\s*(\d+)\s*$")


def _grid(text: str) -> tuple[int, int]:
    m = _GRID_RE.match(text)
    if not m:
        raise ValueError(f"bad grid {text!r}: expected ROWSxCOLS such as 3x4")
    r, c = int(m.group(1)), int(m.group(2))
    if r < 2 or c < 2:
        raise ValueError(f"bad grid {text!r}: rows and cols must be at least 2")
    return r, c


def parse_grid_range(text: str) -> list[tuple[int, int]]:
    """Grids of ``3x4``, ``AxB..CxD`` (every rows in A..C, every cols in B..D, rows-major order), or a
    comma-separated list of either (``3x3,4x4,5x5``; duplicates dropped, first occurrence kept).

    Args:
        text: the range text.

    Returns:
        ``(rows, cols)`` pairs.

    Raises:
        ValueError: malformed text, a size below 2, or an empty range.

    >>> parse_grid_range("2x3..3x4")
    [(2, 3), (2, 4), (3, 3), (3, 4)]
    >>> parse_grid_range("3x3,5x5,3x3")
    [(3, 3), (5, 5)]
    """
    if "," in text:
        grids = [g for item in text.split(",") for g in parse_grid_range(item.strip())]
        return list(dict.fromkeys(grids))
    parts = text.split("..")
    if len(parts) == 1:
        return [_grid(parts[0])]
    if len(parts) != 2:
        raise ValueError(f"bad grid range {text!r}: expected AxB or AxB..CxD")
    (r0, c0), (r1, c1) = _grid(parts[0]), _grid(parts[1])
    if r1 < r0 or c1 < c0:
        raise ValueError(f"bad grid range {text!r}: empty (the second grid must not be smaller)")
    return [(r, c) for r in range(r0, r1 + 1) for c in range(c0, c1 + 1)]


def parse_int_range(text: str, name: str = "value", low: int = 0, high: int | None = None) -> list[int]:
    """Integers of ``N`` or ``A..B`` (inclusive).

    Args:
        text: the range text.
        name: what the numbers are (for error messages).
        low: smallest allowed value.
        high: largest allowed value, if any.

    Returns:
        The integers, ascending.

    Raises:
        ValueError: malformed text, out of bounds, or an empty range.

    >>> parse_int_range("1..3", "robots", 1, 4)
    [1, 2, 3]
    """
    m = re.match(r"^\s*(\d+)\s*(?:\.\.\s*(\d+)\s*)?$", text)
    if not m:
        raise ValueError(f"bad {name} {text!r}: expected N or A..B")
    a = int(m.group(1))
    b = int(m.group(2)) if m.group(2) is not None else a
    if b < a:
        raise ValueError(f"bad {name} range {text!r}: empty")
    if a < low or (high is not None and b > high):
        bound = f"{low}..{high}" if high is not None else f">= {low}"
        raise ValueError(f"bad {name} {text!r}: must be in {bound}")
    return list(range(a, b + 1))


def grid_points(
    grids: Iterable[tuple[int, int]], robots: Iterable[int], ps: Iterable[int], rule: str = "exact"
) -> list[Point]:
    """The cross product as default-scenario points (grid-major, then robots, then p).

    >>> [p.label for p in grid_points([(2, 2)], [1, 2], [1])]
    ['2x2 r1 p1', '2x2 r2 p1']
    """
    if rule not in RULES:
        raise ValueError(f"unknown rule {rule!r} (expected one of {', '.join(RULES)})")
    grids, robots, ps = list(grids), list(robots), list(ps)
    for r, c in grids:
        check_grid_size(r, c)  # here, in this process: before any worker builds a huge grid
    for k in robots:
        if not 1 <= k <= MAX_DEFAULT_ROBOTS:
            raise ScenarioError("robots", f"the default placement supports 1 to {MAX_DEFAULT_ROBOTS} robots, got {k}")
    return [Point(r, c, k, p, rule) for r, c in grids for k in robots for p in ps]


# --- one point ---------------------------------------------------------------------------------------------------
def estimate_point(
    point: Point, epsilon: float = DEFAULT_EPSILON, synthesis: SynthesisModel = "ross-selinger"
) -> PointResult:
    """Build, lower, count and estimate one point (no cache).

    Args:
        point: the point.
        epsilon: rotation synthesis precision for the fault-tolerant estimate.
        synthesis: rotation synthesis model.

    Returns:
        The :class:`PointResult`. The cyclic garbage collector is paused meanwhile.
    """
    with gc_paused():
        return _estimate_point(point, epsilon, synthesis)


def _estimate_point(point: Point, epsilon: float, synthesis: SynthesisModel) -> PointResult:
    clock = time.process_time
    t0 = clock()
    scenario = point.build_scenario()
    circuit = qaoa_circuit(scenario, point.p, rule=point.rule)  # type: ignore[arg-type]
    t1 = clock()
    lowered = lower(circuit)
    t2 = clock()
    counts = count(lowered)
    high = count_gates(circuit.gates, circuit.num_qubits)
    t3 = clock()
    ft = fault_tolerant_estimate(circuit, lowered, epsilon, synthesis)
    t4 = clock()
    timings = {"build": t1 - t0, "lower": t2 - t1, "count": t3 - t2, "fault_tolerant": t4 - t3}
    return PointResult(point, counts, high, ft, timings)


# --- cache -------------------------------------------------------------------------------------------------------
def cache_dir() -> Path:
    """The default cache directory (see the module docstring)."""
    env = os.environ.get("QCPP_CACHE_DIR")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "qcpp" / "estimates"


@lru_cache(maxsize=1)
def source_version() -> str:
    """Hash of the source files of ``circuitgen``, ``gridcover`` and ``estimators`` (16 hex digits)."""
    import importlib

    h = hashlib.sha256()
    for name in _PACKAGES:
        mod = importlib.import_module(name)
        root = Path(mod.__file__).parent  # type: ignore[arg-type]
        for path in sorted(root.rglob("*.py")):
            h.update(f"{name}/{path.relative_to(root).as_posix()}\0".encode())
            h.update(path.read_bytes())
            h.update(b"\0")
    return h.hexdigest()[:16]


def _cache_key(point: Point, options: dict[str, Any]) -> str:
    payload = {"schema": CACHE_SCHEMA, "point": asdict(point), "options": options, "version": source_version()}
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()[:32]


def _read_cache(path: Path) -> PointResult | None:
    try:
        return PointResult.from_dict(json.loads(path.read_text()), cached=True)
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _write_cache(path: Path, result: PointResult) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_open(path) as f:
        json.dump(result.to_dict(), f)


# --- sweep -------------------------------------------------------------------------------------------------------
def _leave_sigint_to_parent() -> None:
    """Pool worker initializer: Ctrl-C reaches the whole process group; the parent alone handles it."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _stop_pool(pool: ProcessPoolExecutor) -> None:
    """Cancel the queued points and end the running ones now (``shutdown(wait=True)`` would wait for each)."""
    procs = list((getattr(pool, "_processes", None) or {}).values())  # no public terminate() before Python 3.14
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in procs:
        proc.terminate()
    for proc in procs:
        proc.join(timeout=1.0)


def _progress(total: int, enabled: bool) -> Any:
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    return Progress(
        TextColumn("estimating"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TextColumn("{task.fields[last]}"),
        console=Console(stderr=True),
        transient=True,
        disable=not enabled,
    )


def sweep(
    points: Sequence[Point],
    *,
    jobs: int | None = None,
    use_cache: bool = True,
    cache: Path | str | None = None,
    progress: bool = True,
    epsilon: float = DEFAULT_EPSILON,
    synthesis: SynthesisModel = "ross-selinger",
    on_result: Callable[[PointResult], None] | None = None,
) -> list[PointResult]:
    """Estimate many points in parallel, with the on-disk cache.

    Args:
        points: the points (duplicates are computed once).
        jobs: worker processes (default: ``os.cpu_count()``); ``1`` computes in this process.
        use_cache: read and write the cache (``--no-cache`` turns both off).
        cache: cache directory (default :func:`cache_dir`).
        progress: show a progress bar on stderr.
        epsilon: rotation synthesis precision.
        synthesis: rotation synthesis model.
        on_result: called with each result as it arrives (cached ones first).

    Returns:
        Results in the order of ``points``.

    Interruption (Ctrl-C, SIGTERM) or an error cancels the queued points and terminates the workers at once;
    every result finished before is already in the cache (written atomically), so a rerun resumes from there.
    """
    options = {"epsilon": epsilon, "synthesis": synthesis}
    folder = Path(cache) if cache is not None else cache_dir()
    unique = list(dict.fromkeys(points))
    done: dict[Point, PointResult] = {}
    todo: list[Point] = []
    for pt in unique:
        hit = _read_cache(folder / f"{_cache_key(pt, options)}.json") if use_cache else None
        if hit is not None:
            done[pt] = hit
            if on_result:
                on_result(hit)
        else:
            todo.append(pt)
    todo.sort(key=lambda pt: pt.size_hint, reverse=True)
    workers = max(1, min(jobs or os.cpu_count() or 1, len(todo)))

    def finish(res: PointResult) -> None:
        done[res.point] = res
        if use_cache:
            _write_cache(folder / f"{_cache_key(res.point, options)}.json", res)
        if on_result:
            on_result(res)

    with _progress(len(todo), progress and bool(todo)) as bar:
        task = bar.add_task("estimating", total=len(todo), last="")
        if workers == 1:
            for pt in todo:
                finish(estimate_point(pt, epsilon, synthesis))
                bar.update(task, advance=1, last=pt.label)
        else:
            with ProcessPoolExecutor(max_workers=workers, initializer=_leave_sigint_to_parent) as pool:
                try:
                    futures = {pool.submit(estimate_point, pt, epsilon, synthesis): pt for pt in todo}
                    for fut in as_completed(futures):
                        finish(fut.result())
                        bar.update(task, advance=1, last=futures[fut].label)
                except BaseException:  # Ctrl-C, SIGTERM or a failed point: stop now, keep what is cached
                    _stop_pool(pool)
                    raise
    return [done[pt] for pt in points]
