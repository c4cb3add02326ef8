"""Default scenarios for resource estimates: a grid size and a robot count, nothing else.

Placement rule (documented, stable). Every robot starts on a boundary node and travels to the node opposite
it through the grid's centre (the point reflection ``(r, c) -> (rows-1-r, cols-1-c)``, which maps the boundary
onto itself). Robots 0-3 start in the corners, in the order

====== ================= =================
robot  start             goal
====== ================= =================
0      top-left          bottom-right
1      top-right         bottom-left
2      bottom-left       top-right
3      bottom-right      top-left
====== ================= =================

Robots ``4, 5, ...`` start on the non-corner boundary nodes, spread evenly: walking the boundary clockwise from
the top-left corner, the ``M = 2(rows + cols) - 8`` non-corner nodes are numbered ``0..M-1`` and the ``k = robots -
4`` extra robots take nodes ``floor((i + 1/2) M / k)``. Starts (and goals) are distinct, and a grid hosts up to
:func:`max_default_robots` ``= 2(rows + cols) - 4`` robots. No obstacles; default objective.

Example:
    >>> s = default_scenario(3, 4, 2)
    >>> [(r.start, r.goal) for r in s.robots]
    [((0, 0), (2, 3)), ((0, 3), (2, 0))]
    >>> [(r.start, r.goal) for r in default_scenario(3, 3, 6).robots][4:]
    [((1, 2), (1, 0)), ((1, 0), (1, 2))]
    >>> max_default_robots(3, 3), max_default_robots(40, 40)
    (8, 156)
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import Grid
from qcpp.problem.scenario import Robot, Scenario, scenario_from_dict

__all__ = [
    "MAX_DEFAULT_ROBOTS",
    "boundary_nodes",
    "check_grid_shape",
    "default_scenario",
    "grid_scenario",
    "max_default_robots",
]

MAX_DEFAULT_ROBOTS = 4
"""Robots placed in the corners; more go to the other boundary nodes."""

Node = tuple[int, int]


def boundary_nodes(rows: int, cols: int) -> list[Node]:
    """Boundary nodes clockwise from the top-left corner (each once).

    >>> boundary_nodes(2, 3)
    [(0, 0), (0, 1), (0, 2), (1, 2), (1, 1), (1, 0)]
    """
    top = [(0, c) for c in range(cols)]
    right = [(r, cols - 1) for r in range(1, rows)]
    bottom = [(rows - 1, c) for c in range(cols - 2, -1, -1)]
    left = [(r, 0) for r in range(rows - 2, 0, -1)]
    return top + right + bottom + left


def max_default_robots(rows: int, cols: int) -> int:
    """How many robots the default placement can host on a ``rows x cols`` grid: one per boundary node."""
    return 2 * (rows + cols) - 4


def check_grid_shape(rows: int, cols: int, field: str = "grid") -> None:
    """Refuse a grid smaller than 2x2: the one check (and message) of every grid given by its size.

    Args:
        rows, cols: the grid size.
        field: the field or option named in the error (``grid``, ``--grid``).

    Raises:
        ScenarioError: ``<field>: the grid must be at least 2x2, got 0x3``.

    >>> check_grid_shape(0, 3, "--grid")
    Traceback (most recent call last):
    ...
    qcpp.problem.errors.ScenarioError: --grid: the grid must be at least 2x2, got 0x3
    """
    if rows < 2 or cols < 2:
        raise ScenarioError(field, f"the grid must be at least 2x2, got {rows}x{cols}")


def default_scenario(rows: int, cols: int, robots: int) -> Scenario:
    """The default scenario for a ``rows x cols`` grid and ``robots`` robots (see the module docstring).

    Args:
        rows: grid rows (at least 2).
        cols: grid columns (at least 2).
        robots: number of robots, ``1 .. max_default_robots(rows, cols)``.

    Raises:
        ScenarioError: fewer than 1 robot, more than the grid's boundary nodes, a grid smaller than 2x2, or rows
            or cols not an integer.
    """
    for name, value in (("grid.rows", rows), ("grid.cols", cols)):
        if isinstance(value, bool) or not isinstance(value, int):
            raise ScenarioError(name, f"expected an integer, got {value!r}")
    check_grid_shape(rows, cols)
    limit = max_default_robots(rows, cols)
    if not isinstance(robots, int) or isinstance(robots, bool) or not 1 <= robots <= limit:
        raise ScenarioError(
            "robots", f"the default placement fits 1 to {limit} robots on a {rows}x{cols} grid, got {robots}"
        )
    corners = [(0, 0), (0, cols - 1), (rows - 1, 0), (rows - 1, cols - 1)]
    starts = corners[: min(robots, MAX_DEFAULT_ROBOTS)]
    extra = robots - len(starts)
    if extra:
        others = [n for n in boundary_nodes(rows, cols) if n not in corners]
        m = len(others)
        starts += [others[(2 * i + 1) * m // (2 * extra)] for i in range(extra)]
    placed = tuple(Robot(s, (rows - 1 - s[0], cols - 1 - s[1])) for s in starts)
    return Scenario(Grid(rows, cols), placed, name=f"default {rows}x{cols}, {robots} robot(s)")


def grid_scenario(
    rows: int,
    cols: int,
    *,
    robots: int | Sequence[tuple[Node, Node]] | None = None,
    obstacles: Iterable[Node] = (),
    hard_obstacles: bool = False,
) -> Scenario:
    """A scenario on a ``rows x cols`` grid: the one builder behind ``qcpp.grid_scenario`` and the command line's
    ``--grid RxC --robots N --obstacle R,C --hard-obstacles``.

    With an integer ``robots`` (or ``None``: one robot) and no obstacles this is :func:`default_scenario`
    itself; obstacles are added to the default placement, and every objective setting is the default except
    ``obstacles = "hard"`` with ``hard_obstacles``.

    Args:
        rows: Grid rows (at least 2).
        cols: Grid columns (at least 2).
        robots: A robot count (the default placement of the module docstring), or ``(start, goal)`` pairs of
            ``(row, col)`` nodes, one per robot.
        obstacles: Obstacle nodes ``(row, col)``, in any order.
        hard_obstacles: Remove the edges touching an obstacle from the variables (``soft``, the paper's, keeps
            them as variables that only cost).

    Returns:
        The scenario (validated).

    Raises:
        ScenarioError: naming the argument: a robot or obstacle off the grid (``robots[1].goal: (5, 0) is outside
            the 3x3 grid``, ``obstacles[0]: (3, 3) is outside the 3x3 grid``), an obstacle on a robot's endpoint,
            more robots than the default placement holds, ...

    Example:
        >>> import qcpp
        >>> qcpp.grid_scenario(3, 4, robots=2) == qcpp.default_scenario(3, 4, 2)
        True
        >>> s = qcpp.grid_scenario(3, 3, robots=[((0, 0), (2, 2))], obstacles=[(1, 1)])
        >>> s.obstacles, s.objective.obstacles
        (((1, 1),), 'soft')
        >>> qcpp.grid_scenario(3, 3, robots=[((0, 0), (3, 0))])
        Traceback (most recent call last):
        ...
        qcpp.problem.errors.ScenarioError: robots[0].goal: (3, 0) is outside the 3x3 grid
    """
    try:
        return _grid_scenario(rows, cols, robots, obstacles, hard_obstacles)
    except ScenarioError as exc:
        field = _ARGUMENT_OF_FIELD.get(exc.field, exc.field)
        if field.startswith("grid.obstacles["):
            field = field.removeprefix("grid.")
        if field == exc.field:
            raise
        raise type(exc)(field, exc.reason) from None


_ARGUMENT_OF_FIELD = {"grid.rows": "rows", "grid.cols": "cols", "grid.obstacles": "obstacles"}
"""Scenario fields :func:`grid_scenario` takes as its own arguments: its errors name the argument."""


def _grid_scenario(
    rows: int, cols: int, robots: int | Sequence[tuple[Node, Node]] | None, obstacles: Iterable[Node],
    hard_obstacles: bool,
) -> Scenario:  # fmt: skip
    count = 1 if robots is None else robots
    blocked = _nodes(obstacles, "grid.obstacles")
    if isinstance(count, int) and not isinstance(count, bool):
        placed = default_scenario(rows, cols, count)
        if not blocked and not hard_obstacles:
            return placed
        pairs = [(rb.start, rb.goal) for rb in placed.robots]
        name = f"{rows}x{cols}, {count} robot(s)"
    elif isinstance(count, (str, bytes)) or not isinstance(count, Sequence):
        raise ScenarioError("robots", f"expected a robot count or (start, goal) pairs, got {robots!r}")
    else:
        pairs = []
        for i, pair in enumerate(count):
            if isinstance(pair, (str, bytes)) or not isinstance(pair, Sequence) or len(pair) != 2:
                raise ScenarioError(f"robots[{i}]", f"expected a (start, goal) pair of (row, col) nodes, got {pair!r}")
            pairs.append((pair[0], pair[1]))
        name = f"{rows}x{cols}, {len(pairs)} robot(s)"
    if blocked:
        name += f", {len(blocked)} obstacle(s)"
    data = {
        "name": name,
        "grid": {"rows": rows, "cols": cols, "obstacles": blocked},
        "robots": [{"start": _plain(start), "goal": _plain(goal)} for start, goal in pairs],
        "objective": {"obstacles": "hard" if hard_obstacles else "soft"},
    }
    return scenario_from_dict(data)


def _plain(node: Any) -> Any:
    """A node as the file format's list (anything else as given, for the scenario's own message)."""
    return list(node) if isinstance(node, tuple) else node


def _nodes(nodes: Iterable[Node], field: str) -> list[Any]:
    if isinstance(nodes, (str, bytes)) or not isinstance(nodes, Iterable):
        raise ScenarioError(field, f"expected (row, col) nodes, got {nodes!r}")
    return [_plain(n) for n in nodes]
