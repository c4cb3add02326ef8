"""Seeded random ensembles of scenarios: many instances of one grid size, robot count and obstacle density.

A study that reports one hand-picked scenario cannot tell the method from the example. An ensemble cell is fixed
by ``(rows, cols, robots, density)``; :func:`random_scenario` draws instance ``index`` of it from a seed:

* **endpoints**: ``2 * robots`` distinct nodes drawn uniformly without replacement; robot ``r`` goes from the
  ``2r``-th to the ``2r+1``-th (so no two robots share a start, a goal, or a start with another's goal);
* **obstacles**: ``round(density * rows * cols)`` distinct nodes drawn uniformly from the remaining ones;
* **feasibility**: every robot must have at least one simple start-goal path (:func:`qcpp.problem.paths.count_paths`,
  which honours ``hard`` obstacles); a draw that fails is rejected and the next draw of the same stream is tried.
  With the paper's ``soft`` obstacles (the default) every draw is feasible; with ``hard`` ones, obstacles that cut
  a robot off its goal are redrawn.

Every other objective setting is the default. The draw depends on ``(seed, rows, cols, robots, density, index)``
only (:class:`numpy.random.SeedSequence`), so a seed names the same instances on every machine and in any order,
and instance ``index`` does not change when more instances are asked for.

Example:
    >>> a = ensemble(3, 3, robots=2, density=0.1, count=3, seed=7)
    >>> a == ensemble(3, 3, robots=2, density=0.1, count=3, seed=7), len(set(a))
    (True, 3)
    >>> [len(s.obstacles) for s in a], a[0].name
    ([1, 1, 1], 'random 3x3/2 density 0.1 seed 7 #0')
"""

from __future__ import annotations

import numpy as np

from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import Grid, Node
from qcpp.problem.paths import count_paths
from qcpp.problem.scenario import Objective, ObstacleMode, Robot, Scenario

__all__ = ["MAX_DRAWS", "ensemble", "obstacle_count", "random_scenario"]

MAX_DRAWS = 1000
"""Draws tried per instance before giving up (only ``hard`` obstacles can reject a draw)."""


def obstacle_count(rows: int, cols: int, robots: int, density: float) -> int:
    """Obstacles of a cell: ``round(density * rows * cols)``.

    Raises:
        ScenarioError: ``density`` outside ``[0, 1)``; ``robots`` whose endpoints alone do not fit on the grid;
            ``density`` where the obstacles leave too few nodes for the endpoints.

    Example:
        >>> obstacle_count(4, 4, 2, 0.1), obstacle_count(3, 3, 1, 0.0)
        (2, 0)
        >>> obstacle_count(3, 3, 5, 0.0)
        Traceback (most recent call last):
        ...
        qcpp.problem.errors.ScenarioError: robots: 5 robots need 10 distinct endpoints, a 3x3 grid has 9 nodes
    """
    if isinstance(density, bool) or not isinstance(density, (int, float)) or not 0 <= density < 1:
        raise ScenarioError("density", f"must be a number in [0, 1), got {density!r}")
    k, nodes = round(density * rows * cols), rows * cols
    if 2 * robots > nodes:
        raise ScenarioError(
            "robots", f"{robots} robots need {2 * robots} distinct endpoints, a {rows}x{cols} grid has {nodes} nodes"
        )
    if k + 2 * robots > nodes:
        raise ScenarioError(
            "density", f"{k} obstacles and {2 * robots} endpoints do not fit on the {nodes} nodes of a {rows}x{cols} "
            "grid"
        )
    return k


def _check_cell(rows: int, cols: int, robots: int) -> None:
    for name, value, low in (("rows", rows, 2), ("cols", cols, 2), ("robots", robots, 1)):
        if isinstance(value, bool) or not isinstance(value, int) or value < low:
            raise ScenarioError(name, f"must be an integer >= {low}, got {value!r}")


def random_scenario(
    rows: int, cols: int, robots: int, density: float = 0.0, *, seed: int = 0, index: int = 0,
    obstacles: ObstacleMode = "soft",
) -> Scenario:
    """Instance ``index`` of the ensemble cell ``(rows, cols, robots, density)`` under ``seed`` (module docstring).

    Args:
        rows: Grid rows (>= 2).
        cols: Grid columns (>= 2).
        robots: Robots (>= 1; ``2 * robots`` endpoints plus the obstacles must fit on the grid).
        density: Fraction of the grid's nodes that are obstacles, in ``[0, 1)``.
        seed: The ensemble's seed (a non-negative integer).
        index: The instance's number in the ensemble (a non-negative integer).
        obstacles: ``soft`` (the paper's, default) or ``hard``.

    Returns:
        A feasible scenario named ``random RxC/N density D seed S #I``.

    Raises:
        ScenarioError: a bad argument, or no feasible draw in :data:`MAX_DRAWS` tries.

    Example:
        >>> import qcpp
        >>> s = qcpp.random_scenario(4, 4, 1, 0.2, seed=1, index=5, obstacles="hard")
        >>> len(s.obstacles), s.objective.obstacles, s == qcpp.random_scenario(4, 4, 1, 0.2, seed=1, index=5,
        ...                                                                obstacles="hard")
        (3, 'hard', True)
    """
    _check_cell(rows, cols, robots)
    for name, value in (("seed", seed), ("index", index)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            raise ScenarioError(name, f"must be a non-negative integer, got {value!r}")
    if obstacles not in ("soft", "hard"):
        raise ScenarioError("obstacles", f"expected 'soft' or 'hard', got {obstacles!r}")
    k = obstacle_count(rows, cols, robots, density)
    grid = Grid(rows, cols)
    nodes: list[Node] = [(r, c) for r in range(rows) for c in range(cols)]
    # the density enters the stream as an integer (per mille) so that the same float always names the same stream
    rng = np.random.default_rng(np.random.SeedSequence([seed, rows, cols, robots, round(density * 1000), index]))
    label = f"random {rows}x{cols}/{robots} density {density:g} seed {seed} #{index}"
    for _ in range(MAX_DRAWS):
        pick = rng.permutation(len(nodes))[: 2 * robots + k]
        ends, blocked = pick[: 2 * robots], pick[2 * robots :]
        placed = tuple(Robot(nodes[ends[2 * r]], nodes[ends[2 * r + 1]]) for r in range(robots))
        try:  # the constructor itself rejects hard obstacles that cut a robot off its goal
            scenario = Scenario(grid, placed, tuple(sorted(nodes[i] for i in blocked)),
                                Objective(obstacles=obstacles), name=label)
        except ScenarioError:
            continue
        if all(count_paths(scenario, r, cap=1) for r in range(robots)):
            return scenario
    raise ScenarioError("density", f"no feasible draw of {label} in {MAX_DRAWS} tries")  # pragma: no cover


def ensemble(
    rows: int, cols: int, robots: int, density: float = 0.0, *, count: int, seed: int = 0,
    obstacles: ObstacleMode = "soft",
) -> tuple[Scenario, ...]:
    """Instances ``0 .. count-1`` of a cell (:func:`random_scenario`); a prefix of any larger ensemble.

    Args:
        rows: The grid's rows.
        cols: The grid's columns.
        robots: Robots per instance (>= 1).
        density: Fraction of the grid's nodes that are obstacles, in ``[0, 1)`` (:func:`random_scenario`).
        count: Instances (at least 1).
        seed: The ensemble's seed: the same arguments give the same instances on every machine.
        obstacles: ``soft`` (the paper's: weights) or ``hard`` (edges touching an obstacle are not variables).

    Returns:
        The scenarios, instance ``i`` at position ``i``.

    Raises:
        ScenarioError: ``count < 1`` or a bad cell (see :func:`random_scenario`).

    Example:
        >>> import qcpp
        >>> small = qcpp.ensemble(4, 4, 1, 0.1, count=2, seed=3)
        >>> small == qcpp.ensemble(4, 4, 1, 0.1, count=5, seed=3)[:2]
        True
    """
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ScenarioError("count", f"must be a positive integer, got {count!r}")
    return tuple(random_scenario(rows, cols, robots, density, seed=seed, index=i, obstacles=obstacles)
                 for i in range(count))

