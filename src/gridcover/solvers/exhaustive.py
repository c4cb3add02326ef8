"""Exhaustive search: the exact optimum over every combination of the robots' simple paths.

Every robot's feasible paths are enumerated (:func:`gridcover.paths.enumerate_paths`) and the cost is
split into unary vectors and pairwise matrices (:func:`gridcover.cost.separable_cost`). The combinations
are then scored with numpy in blocks, in lexicographic order of the path index tuples:

* robot 0's paths are taken a slice at a time and :func:`~gridcover.cost.separable_cost` is called on
  ``[slice, all of robot 1's paths, ...]``, so its pairwise matrices with robot 0 have ``slice`` rows instead
  of all of them (for two robots on 5x5 that is what keeps memory at a few hundred MB instead of several
  copies of a 72-million-entry matrix);
* within a slice, the index tuples of robots ``0 .. R-2`` are walked a block at a time and for each block
  the costs of *all* paths of the last robot are computed as one ``(block, n_last)`` array.

Blocks and slices hold at most ``chunk_elements`` floats (pairwise matrices between robots ``1 .. R-1``
are whole, so three or more robots are only practical on small grids).

Ties: among assignments whose computed total is exactly the minimum, the one with the lowest index tuple
``(i_0, i_1, ...)`` in lexicographic order (robot 0 most significant; indices in
:func:`~gridcover.paths.enumerate_paths` order) is returned. The number of assignments within ``1e-9`` of
the optimum is reported in ``notes``.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> sol = dfs(s)
    >>> sol.paths_per_robot, sol.evaluated, sol.cost   # a Hamiltonian path: 8 free edges, every degree on target
    ((12,), 12, CostParts(c1=-8.0, c2=0.0, c3=0.0, total=-8.0))
"""

from __future__ import annotations

import math
import time

import numpy as np

from gridcover.cost import cost_parts, separable_cost
from gridcover.cost_range import check_cost_range
from gridcover.paths import enumerate_paths
from gridcover.scenario import Scenario
from gridcover.solvers.result import ProgressFn, Solution

TIE_TOLERANCE = 1e-9


def dfs(scenario: Scenario, *, chunk_elements: int = 1 << 23, progress: ProgressFn | None = None) -> Solution:
    """The optimal assignment by exhaustive search (see the module docstring for the method and ties).

    Args:
        scenario: The scenario.
        chunk_elements: Upper bound on the float64 elements of one scored block and of one robot-0 slice's
            pairwise matrices (default 8M = 64 MB).
        progress: Called as ``progress(done, total)`` in combinations after every block.

    Returns:
        A :class:`Solution` with ``evaluated`` = the product of the path counts and ``paths_per_robot``.

    Raises:
        ValueError: if ``chunk_elements`` is not positive.
        ScenarioError: weights outside :mod:`gridcover.cost_range`'s range.

    Example:
        >>> from gridcover.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3},
        ...                         "robots": [{"start": [0, 0], "goal": [1, 2]}, {"start": [1, 0], "goal": [0, 2]}]})
        >>> dfs(s).evaluated
        16
    """
    if chunk_elements < 1:
        raise ValueError(f"chunk_elements must be positive, got {chunk_elements}")
    check_cost_range(scenario)  # float64 scores: refuse weights whose costs it cannot hold exactly
    t_start = time.perf_counter()
    lists = [enumerate_paths(scenario, r) for r in range(scenario.num_robots)]
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
