"""Scenarios in the public API: build one on a grid, load and save files (the one place the API imports them).

Example:
    >>> s = grid_scenario(4, 4, robots=2, obstacles=[(1, 2)])
    >>> [(r.start, r.goal) for r in s.robots], s.obstacles
    ([((0, 0), (3, 3)), ((0, 3), (3, 0))], ((1, 2),))
    >>> len(ensemble(3, 3, robots=2, density=0.1, count=30, seed=0))   # seeded random instances of one cell
    30
"""

from __future__ import annotations

from qcpp.problem.ensembles import ensemble, random_scenario
from qcpp.problem.errors import ScenarioError
from qcpp.problem.presets import default_scenario, grid_scenario
from qcpp.problem.scenario import Scenario
from qcpp.problem.scenario_io import load_scenario, save_scenario

__all__ = [
    "Scenario",
    "ScenarioError",
    "default_scenario",
    "ensemble",
    "grid_scenario",
    "load_scenario",
    "random_scenario",
    "save_scenario",
]
