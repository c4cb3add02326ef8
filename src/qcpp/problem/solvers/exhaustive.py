"""Exhaustive search: the exact optimum over every combination of the robots' simple paths.

Every robot's feasible paths are enumerated (:func:`qcpp.problem.paths.enumerate_paths`) and the cost is
split into unary vectors and pairwise matrices (:func:`qcpp.problem.cost.separable_cost`). The combinations
are then scored with numpy in blocks, in lexicographic order of the path index tuples:

* robot 0's paths are taken a slice at a time and :func:`~qcpp.problem.cost.separable_cost` is called on
  ``[slice, all of robot 1's paths, ...]``, so its pairwise matrices with robot 0 have ``slice`` rows instead
  of all of them (which bounds the memory of two robots on large grids);
* within a slice, the index tuples of robots ``0 .. R-2`` are walked a block at a time and for each block
  the costs of *all* paths of the last robot are computed as one ``(block, n_last)`` array.

Blocks and slices hold at most ``chunk_elements`` floats (pairwise matrices between robots ``1 .. R-1``
are whole, so three or more robots are only practical on small grids).

Ties: the lowest index tuple ``(i_0, i_1, ...)`` in lexicographic order wins; the number of assignments within
``1e-9`` of the optimum is reported in ``notes``.

Size: the search is exponential in the number of robots. :func:`dfs_paths` enumerates the paths under limits
(:data:`MAX_DFS_ASSIGNMENTS`, :data:`MAX_DFS_PATHS`, a memory budget): it first counts every robot's paths up to
:data:`PRECHECK_PATHS`, so a request that is far too large is refused at once with a :class:`DfsTooLargeError`
naming the predicted size (:class:`DfsSize`) instead of enumerating and running out of memory; :func:`dfs` takes
the enumerated lists.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> sol = dfs(s)
    >>> sol.paths_per_robot, sol.evaluated, sol.cost   # a Hamiltonian path: 8 free edges, every degree on target
    ((12,), 12, CostParts(c1=-8.0, c2=0.0, c3=0.0, total=-8.0))
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from qcpp.errors import QcppError
from qcpp.problem.cost import cost_parts, separable_cost
from qcpp.problem.cost_range import check_cost_range
from qcpp.problem.limits import format_duration
from qcpp.problem.paths import count_paths, enumerate_paths, iter_paths
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers.result import ProgressFn, Solution

TIE_TOLERANCE = 1e-9

DEFAULT_CHUNK_ELEMENTS = 1 << 23
"""Float64 elements of one scored block (64 MB)."""

MAX_DFS_ASSIGNMENTS = 1_000_000_000
"""Most assignments :func:`dfs_paths` allows by default: about two minutes of scoring."""

MAX_DFS_PATHS = 2_000_000
"""Most paths of one robot :func:`dfs_paths` enumerates by default (about 2 GB of path lists)."""

PRECHECK_PATHS = 4096
"""Every robot's paths are first counted up to this many (milliseconds) to refuse hopeless requests at once."""

ASSIGNMENTS_PER_SECOND = 8e6
"""Scoring speed used for the predicted time (a conservative figure for the numpy block scoring)."""

PATHS_PER_SECOND = 5e4
"""Path enumeration speed used for the predicted time."""

BASE_BYTES = 55_000_000
"""Peak resident memory of a ``qcpp solve --method dfs`` process on a tiny scenario (interpreter and imports)."""


@dataclass(frozen=True)
class DfsSize:
    """The predicted size of an exhaustive search.

    Attributes:
        paths_per_robot: Each robot's path count; a lower bound where ``complete`` is false.
        complete: Whether each count is exact (false: counting stopped there).
        edges_per_robot: Grid edges (bits of one path).
        nodes: Grid nodes.
        chunk_elements: Float64 elements of one scored block.
    """

    paths_per_robot: tuple[int, ...]
    complete: tuple[bool, ...]
    edges_per_robot: int
    nodes: int
    chunk_elements: int = DEFAULT_CHUNK_ELEMENTS

    @property
    def exact(self) -> bool:
        """Whether every count is exact (else every figure is a lower bound)."""
        return all(self.complete)

    @property
    def assignments(self) -> int:
        """Combinations to score: the product of the path counts."""
        return math.prod(self.paths_per_robot)

    @property
    def bytes(self) -> int:
        """Peak resident memory of a process running :func:`dfs`: :data:`BASE_BYTES`, the path lists with their
        bit and degree matrices (twice, for the temporaries), the whole pairwise matrices between robots 1..
        (three arrays each while they are summed), robot 0's slices of its pairwise matrices and the scored block
        (``tests/cli/guard_peaks_test.py`` checks it against measured peaks, within 1.5x)."""
        counts = self.paths_per_robot
        per_path = 9 * self.edges_per_robot + 8 * self.nodes + 60
        lists = 2 * sum(counts) * per_path
        rest = counts[1:]
        whole = sum(a * b for a, b in itertools.combinations(rest, 2))
        sliced = min(counts[0], max(1, self.chunk_elements // max(1, math.prod(rest)))) * sum(rest) if rest else 0
        return BASE_BYTES + lists + 24 * (whole + sliced) + 16 * min(self.chunk_elements, self.assignments)

    @property
    def seconds(self) -> float:
        """Predicted wall time: enumerating the paths and scoring every assignment."""
        return sum(self.paths_per_robot) / PATHS_PER_SECOND + self.assignments / ASSIGNMENTS_PER_SECOND

    def describe(self) -> str:
        """One phrase: paths per robot, assignments, memory and time (``at least`` where counting stopped).

        Example:
            >>> DfsSize((12, 178), (True, False), 12, 9).describe()
            'paths per robot 12 x at least 178 = at least 2,136 assignments (at least 0.1 GB, 0 s)'
        """
        at_least = "" if self.exact else "at least "
        paths = " x ".join(f"{'' if ok else 'at least '}{n:,}" for n, ok in zip(self.paths_per_robot, self.complete))
        return (
            f"paths per robot {paths} = {at_least}{self.assignments:,} assignments "
            f"({at_least}{self.bytes / 1e9:.1f} GB, {format_duration(self.seconds)})"
        )


class DfsTooLargeError(QcppError):
    """An exhaustive search over a limit of :func:`dfs_paths`; ``size`` is the prediction, the message one line."""

    def __init__(self, size: DfsSize, reason: str) -> None:
        super().__init__(f"exhaustive search of {size.describe()}: {reason}")
        self.size = size


def _check(
    size: DfsSize, max_assignments: int | None, max_paths: int | None, max_bytes: int | None, max_seconds: float | None
) -> None:
    if max_assignments is not None and size.assignments > max_assignments:
        raise DfsTooLargeError(size, f"over the limit of {max_assignments:,} assignments")
    if max_paths is not None and max(size.paths_per_robot) > max_paths:
        raise DfsTooLargeError(size, f"over the limit of {max_paths:,} paths per robot")
    if max_bytes is not None and size.bytes > max_bytes:
        raise DfsTooLargeError(size, f"over the {max_bytes / 1e9:.1f} GB of memory available")
    if max_seconds is not None and size.seconds > max_seconds:
        raise DfsTooLargeError(size, f"over the run-time limit of {format_duration(max_seconds)}")


def dfs_paths(
    scenario: Scenario,
    *,
    max_assignments: int | None = MAX_DFS_ASSIGNMENTS,
    max_paths: int | None = MAX_DFS_PATHS,
    max_bytes: int | None = None,
    max_seconds: float | None = None,
    chunk_elements: int = DEFAULT_CHUNK_ELEMENTS,
) -> list[list[int]]:
    """Every robot's paths for :func:`dfs`, refusing a search over the limits before doing it.

    Every robot's paths are first counted up to :data:`PRECHECK_PATHS` (a lower bound on the search); then
    robot by robot they are enumerated, each no further than what the limits leave for it. Work beyond the
    enumeration :func:`dfs` needs anyway: at most ``robots * PRECHECK_PATHS`` paths counted.

    Args:
        max_assignments: Most combinations allowed (``None``: no limit).
        max_paths: Most paths of one robot allowed (``None``: no limit).
        max_bytes: Memory budget of :attr:`DfsSize.bytes` (``None``: no limit); it also caps the paths
            enumerated for one robot (no more than their lists could hold).
        max_seconds: Longest predicted run time, :attr:`DfsSize.seconds` (``None``: no limit); it also caps the
            assignments.
        chunk_elements: As in :func:`dfs` (for the memory prediction).

    Returns:
        One list of paths per robot (:func:`qcpp.problem.paths.enumerate_paths` order).

    Raises:
        DfsTooLargeError: the predicted size (exact, or a lower bound) is over a limit.

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> [len(pl) for pl in dfs_paths(default_scenario(4, 4, 2))]
        [184, 184]
        >>> try:
        ...     dfs_paths(default_scenario(6, 6, 3))  # refused after counting 3 x 4,097 paths
        ... except DfsTooLargeError as exc:
        ...     print(exc.size.paths_per_robot, exc.size.exact, exc.size.assignments > MAX_DFS_ASSIGNMENTS)
        (4097, 4097, 4097) False True
    """
    robots = range(scenario.num_robots)
    e, v = scenario.edges_per_robot, scenario.grid.num_nodes

    def size(counts: Sequence[int], complete: Sequence[bool]) -> DfsSize:
        return DfsSize(tuple(counts), tuple(complete), e, v, chunk_elements)

    # enumeration stops where a limit is known to be passed: a robot's path list alone (with its temporaries)
    # must fit in max_bytes, and the assignments scored within max_seconds
    path_caps = [c for c in (max_paths, None if max_bytes is None else max_bytes // (2 * (9 * e + 8 * v + 60)))
                 if c is not None]  # fmt: skip
    assignment_caps = [c for c in (max_assignments,
                                   None if max_seconds is None else int(max_seconds * ASSIGNMENTS_PER_SECOND))
                       if c is not None]  # fmt: skip
    path_cap = min(path_caps) if path_caps else None
    assignment_cap = min(assignment_caps) if assignment_caps else None
    counts = [count_paths(scenario, r, PRECHECK_PATHS + 1) for r in robots]
    complete = [c <= PRECHECK_PATHS for c in counts]
    _check(size(counts, complete), max_assignments, max_paths, max_bytes, max_seconds)
    lists: list[list[int]] = []
    for r in robots:
        others = math.prod(counts[:r] + counts[r + 1 :])
        caps = [c for c in (path_cap, None if assignment_cap is None else assignment_cap // others) if c is not None]
        cap = min(caps) if caps else None
        pl = list(itertools.islice(iter_paths(scenario, r), None if cap is None else cap + 1))
        counts[r], complete[r] = len(pl), cap is None or len(pl) <= cap
        _check(size(counts, complete), max_assignments, max_paths, max_bytes, max_seconds)
        lists.append(pl)
    return lists


def budgeted_dfs_paths(scenario: Scenario) -> list[list[int]]:
    """:func:`dfs_paths` within the limits ``qcpp solve -m dfs`` and ``qcpp.solve(s, "dfs")`` keep: refused only if
    the search would not fit in the available memory (:func:`qcpp.problem.limits.available_memory`) or would run
    for more than :data:`qcpp.problem.limits.MAX_SECONDS`; nothing is refused inside
    :func:`qcpp.problem.limits.allow_large`.

    Raises:
        DfsTooLargeError: a search over the limits (before doing it).
    """
    from qcpp.problem.limits import MAX_SECONDS, available_memory, large_allowed

    if large_allowed():
        return dfs_paths(scenario, max_assignments=None, max_paths=None, max_bytes=None)
    return dfs_paths(
        scenario, max_assignments=None, max_paths=None, max_bytes=available_memory(), max_seconds=MAX_SECONDS
    )


def dfs(
    scenario: Scenario,
    *,
    chunk_elements: int = DEFAULT_CHUNK_ELEMENTS,
    progress: ProgressFn | None = None,
    paths: Sequence[Sequence[int]] | None = None,
) -> Solution:
    """The optimal assignment by exhaustive search (see the module docstring for the method and ties).

    Args:
        chunk_elements: Upper bound on the float64 elements of one scored block and of one robot-0 slice's
            pairwise matrices (default 8M = 64 MB).
        progress: Called as ``progress(done, total)`` in combinations after every block.
        paths: Every robot's paths in :func:`~qcpp.problem.paths.enumerate_paths` order (from :func:`dfs_paths`);
            default: enumerated here, without limits.

    Returns:
        A :class:`Solution` with ``evaluated`` = the product of the path counts and ``paths_per_robot``.

    Raises:
        ValueError: if ``chunk_elements`` is not positive.
        ScenarioError: weights outside :mod:`qcpp.problem.cost_range`'s range.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3},
        ...                         "robots": [{"start": [0, 0], "goal": [1, 2]}, {"start": [1, 0], "goal": [0, 2]}]})
        >>> dfs(s).evaluated
        16
    """
    if chunk_elements < 1:
        raise ValueError(f"chunk_elements must be positive, got {chunk_elements}")
    check_cost_range(scenario)  # float64 scores: refuse weights whose costs it cannot hold exactly
    t_start = time.perf_counter()
    if paths is None:
        lists = [enumerate_paths(scenario, r) for r in range(scenario.num_robots)]
    elif len(paths) != scenario.num_robots:
        raise ValueError(f"expected {scenario.num_robots} path lists, got {len(paths)}")
    else:
        lists = [pl if isinstance(pl, list) else list(pl) for pl in paths]
    counts = tuple(len(pl) for pl in lists)
    total = math.prod(counts)
    last = scenario.num_robots - 1
    n_last = counts[last]
    # robot 0 slice length: one slice's combinations fit in chunk_elements (one robot: the whole list)
    n_slice = max(1, chunk_elements // math.prod(counts[1:])) if last else counts[0]

    best_val = math.inf
    best_flat = -1  # in the full row-major index space of ``counts``
    n_best = 0
    done = 0
    block = np.empty(0)
    for lo0 in range(0, counts[0], n_slice):
        sub_counts = (min(n_slice, counts[0] - lo0), *counts[1:])
        sep = separable_cost(scenario, [lists[0][lo0 : lo0 + n_slice], *lists[1:]])
        prefix_counts = sub_counts[:last]
        n_prefix = math.prod(prefix_counts)
        rows = max(1, chunk_elements // n_last)
        inner = [(r, s, m) for (r, s), m in sep.pairwise.items() if s < last]
        to_last = [(r, m) for (r, s), m in sep.pairwise.items() if s == last]
        for lo in range(0, n_prefix, rows):
            hi = min(lo + rows, n_prefix)
            idx = np.unravel_index(np.arange(lo, hi), prefix_counts) if last else ()
            base = np.full(hi - lo, sep.const)
            for r in range(last):
                base += sep.unary[r][idx[r]]
            for r, s, m in inner:
                base += m[idx[r], idx[s]]
            if block.shape != (hi - lo, n_last):
                block = np.empty((hi - lo, n_last))
            np.add.outer(base, sep.unary[last], out=block)
            for r, m in to_last:
                # with two robots the prefix is robot 0 and its rows are contiguous: a view, no copy
                block += m[lo:hi] if last == 1 else m[idx[r]]
            k = int(np.argmin(block))
            v = float(block.flat[k])
            if v < best_val - TIE_TOLERANCE:
                n_best = 0
            if v < best_val:
                local = np.unravel_index(lo * n_last + k, sub_counts)
                best_val = v
                best_flat = int(np.ravel_multi_index((local[0] + lo0, *local[1:]), counts))
            n_best += int(np.count_nonzero(block <= best_val + TIE_TOLERANCE))
            done += block.size
            if progress is not None:
                progress(done, total)

    indices = np.unravel_index(best_flat, counts)
    masks = tuple(lists[r][int(i)] for r, i in enumerate(indices))
    return Solution(
        method="dfs",
        paths=masks,
        cost=cost_parts(scenario, masks),
        seconds=time.perf_counter() - t_start,
        evaluated=total,
        paths_per_robot=counts,
        notes=(
            f"path indices {tuple(int(i) for i in indices)} (enumerate_paths order; ties -> lowest index tuple)",
            f"{n_best} optimal assignment(s) within {TIE_TOLERANCE:g}",
        ),
    )
