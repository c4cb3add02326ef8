"""Default scenarios for resource estimates: a grid size and a robot count, nothing else.

Placement rule (documented, stable): robots start in the grid's corners and travel to the opposite corner,
in the order

====== ================= =================
robot  start             goal
====== ================= =================
0      top-left          bottom-right
1      top-right         bottom-left
2      bottom-left       top-right
3      bottom-right      top-left
====== ================= =================

so every start is distinct for up to four robots on any grid of at least 2x2. No obstacles; every objective
setting is the default (:class:`gridcover.scenario.Objective`).

Example:
    >>> s = default_scenario(3, 4, 2)
    >>> [(r.start, r.goal) for r in s.robots]
    [((0, 0), (2, 3)), ((0, 3), (2, 0))]
"""

from __future__ import annotations

from gridcover.errors import ScenarioError
from gridcover.grid import Grid
from gridcover.scenario import Robot, Scenario

MAX_DEFAULT_ROBOTS = 4


def default_scenario(rows: int, cols: int, robots: int) -> Scenario:
    """The default scenario for a ``rows x cols`` grid and ``robots`` robots (see the module docstring).

    Raises:
        ScenarioError: for fewer than 1 or more than 4 robots, or a grid smaller than 2x2.
    """
    if not isinstance(robots, int) or not 1 <= robots <= MAX_DEFAULT_ROBOTS:
        raise ScenarioError("robots", f"the default placement supports 1 to {MAX_DEFAULT_ROBOTS} robots, got {robots}")
    corners = [(0, 0), (0, cols - 1), (rows - 1, 0), (rows - 1, cols - 1)]
    opposite = [(rows - 1, cols - 1), (rows - 1, 0), (0, cols - 1), (0, 0)]
    placed = tuple(Robot(corners[i], opposite[i]) for i in range(robots))
    return Scenario(Grid(rows, cols), placed, name=f"default {rows}x{cols}, {robots} robot(s)")
