"""The scenario given inline on the command line: ``--grid RxC --robots N --obstacle R,C ... --hard-obstacles``.

``qcpp compile`` and ``qcpp scenario`` take these flags instead of a scenario file, and ``qcpp estimate`` takes
``--obstacle`` and ``--hard-obstacles`` beside its ``--grid``/``--robots`` ranges; all of them build the scenario
with :func:`qcpp.problem.presets.grid_scenario`, the builder of ``qcpp.grid_scenario``, so a scenario typed on the
command line is the one the Python API builds from the same numbers.

Example:
    >>> s = inline_scenario("4x5", 2, ["1,1", "2,3"], hard=False)
    >>> (s.grid.rows, s.grid.cols), s.num_robots, s.obstacles
    ((4, 5), 2, ((1, 1), (2, 3)))
    >>> parse_obstacle("2;1")
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: --obstacle: expected ROW,COL such as 2,1, got '2;1'
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import Annotated

import typer

from qcpp.errors import OptionError
from qcpp.problem.presets import grid_scenario
from qcpp.problem.scenario import Scenario

__all__ = [
    "GridFlag",
    "HardObstaclesFlag",
    "ObstacleFlag",
    "RobotCountFlag",
    "check_inline_only",
    "inline_scenario",
    "parse_grid",
    "parse_obstacle",
    "parse_obstacles",
]

GridFlag = Annotated[
    str | None,
    typer.Option(
        "--grid",
        help="ROWSxCOLS: give the scenario inline instead of a file (see 'qcpp scenario').",
        show_default=False,
    ),
]
RobotCountFlag = Annotated[
    int | None,
    typer.Option(
        "--robots",
        help="With --grid: robots in the default placement (corners, then the other boundary nodes); default 1.",
        show_default=False,
    ),
]
ObstacleFlag = Annotated[
    list[str] | None,
    typer.Option("--obstacle", help="ROW,COL: an obstacle node (repeat for more).", show_default=False),
]
HardObstaclesFlag = Annotated[
    bool,
    typer.Option(
        "--hard-obstacles",
        help="Obstacles remove their edges (default: soft, the paper's: they cost).",
    ),
]

_GRID = re.compile(r"^\s*(\d+)\s*[xX]\s*(\d+)\s*$")
_NODE = re.compile(r"^\s*(\d+)\s*,\s*(\d+)\s*$")


def parse_grid(text: str) -> tuple[int, int]:
    """``"4x5"`` -> ``(4, 5)``.

    Raises:
        qcpp.errors.OptionError: naming ``--grid``, for anything but one ``ROWSxCOLS``.
    """
    m = _GRID.match(text)
    if m is None:
        raise OptionError("--grid", f"expected ROWSxCOLS such as 3x4, got {text!r}")
    return int(m.group(1)), int(m.group(2))


def parse_obstacle(text: str) -> tuple[int, int]:
    """``"2,1"`` -> ``(2, 1)``.

    Raises:
        qcpp.errors.OptionError: naming ``--obstacle``, for anything but ``ROW,COL``.
    """
    m = _NODE.match(text)
    if m is None:
        raise OptionError("--obstacle", f"expected ROW,COL such as 2,1, got {text!r}")
    return int(m.group(1)), int(m.group(2))


def parse_obstacles(texts: Sequence[str] | None) -> list[tuple[int, int]]:
    """Every ``--obstacle`` value, parsed (:func:`parse_obstacle`)."""
    return [parse_obstacle(t) for t in texts or ()]


def inline_scenario(grid: str, robots: int | None, obstacles: Sequence[str] | None, hard: bool) -> Scenario:
    """The scenario of ``--grid``, ``--robots``, ``--obstacle`` and ``--hard-obstacles``
    (:func:`qcpp.problem.presets.grid_scenario`).

    Raises:
        qcpp.errors.OptionError: a malformed ``--grid`` or ``--obstacle``.
        qcpp.problem.errors.ScenarioError: a scenario that cannot be (an obstacle off the grid or on a robot's
            start or goal, more robots than the default placement holds), naming the field.
    """
    rows, cols = parse_grid(grid)
    return grid_scenario(rows, cols, robots=1 if robots is None else robots, obstacles=parse_obstacles(obstacles),
                         hard_obstacles=hard)  # fmt: skip


def check_inline_only(grid: str | None, robots: object, obstacles: Sequence[str] | None, hard: bool) -> None:
    """Refuse ``--robots``, ``--obstacle`` or ``--hard-obstacles`` without ``--grid`` (they would be ignored).

    Raises:
        qcpp.errors.OptionError: naming the flag.
    """
    if grid is not None:
        return
    for flag, given in (("--robots", robots is not None), ("--obstacle", bool(obstacles)), ("--hard-obstacles", hard)):
        if given:
            raise OptionError(flag, "applies with --grid only (no --grid given)")
