"""The scenario given inline on the command line: ``--grid RxC --robots N --obstacle R,C ... --hard-obstacles``,
or the robots' own endpoints with ``--robot R,C:R,C`` (repeatable) instead of ``--robots N``.

Every command that reads one scenario (``compile``, ``solve``, ``simulate``, ``validate``, ``verify``, ``decode``,
``export``) takes these flags instead of its scenario file (:func:`given_scenario`), ``qcpp scenario`` prints the
file they stand for, and ``qcpp estimate`` takes ``--obstacle`` and ``--hard-obstacles`` beside its
``--grid``/``--robots`` ranges; all of them build the scenario with :func:`qcpp.problem.presets.grid_scenario`,
the builder of ``qcpp.grid_scenario``, so a scenario typed on the command line is the one the Python API builds
from the same numbers.

Example:
    >>> s = inline_scenario("4x5", 2, ["1,1", "2,3"], hard=False)
    >>> (s.grid.rows, s.grid.cols), s.num_robots, s.obstacles
    ((4, 5), 2, ((1, 1), (2, 3)))
    >>> inline_scenario("3x4", None, None, hard=False, endpoints=["0,0:2,3", "2,0:0,3"]).robots[1].goal
    (0, 3)
    >>> parse_obstacle("2;1")
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: --obstacle: expected ROW,COL such as 2,1, got '2;1'
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated

import typer

from qcpp.errors import OptionError
from qcpp.problem.cost_range import check_cost_range, check_phase_range
from qcpp.problem.errors import ScenarioError
from qcpp.problem.presets import grid_scenario
from qcpp.problem.scenario import Scenario
from qcpp.problem.scenario_io import STDIN, STDIN_LABEL, load_scenario

RANGES_NOTE = "ranges (A..B) and comma lists are for qcpp estimate"
"""Said when a single-circuit command is given a range or a list where it takes one value."""


def is_range_or_list(text: str) -> bool:
    """Whether ``text`` reads as ``qcpp estimate``'s range ``A..B`` or comma list rather than one value."""
    return ".." in text or "," in text


def one_whole_number(flag: str) -> Callable[[str], int]:
    """A typer ``parser`` for an option of a single-circuit command that takes one whole number (``-p``,
    ``--robots``): a range or a comma list is refused naming ``flag`` and :data:`RANGES_NOTE`.

    >>> one_whole_number("-p/--layers")(" 3 ")
    3
    >>> try:
    ...     one_whole_number("-p/--layers")("1..3")
    ... except typer.BadParameter as exc:
    ...     print(exc.message)
    one value only, got '1..3': this command builds one circuit; ranges (A..B) and comma lists are for qcpp estimate
    """

    def parse(text: str) -> int:
        if isinstance(text, int):  # a default value
            return text
        if is_range_or_list(text):
            raise typer.BadParameter(f"one value only, got {text!r}: this command builds one circuit; {RANGES_NOTE}")
        try:
            return int(text.strip())
        except ValueError:
            raise typer.BadParameter(f"{text!r} is not a whole number") from None

    parse.__name__ = f"one_whole_number({flag})"
    return parse


__all__ = [
    "GivenScenario",
    "GridFlag",
    "HardObstaclesFlag",
    "ObstacleFlag",
    "RobotCountFlag",
    "RobotFlag",
    "ScenarioFileArg",
    "check_inline_only",
    "flag_error",
    "given_scenario",
    "inline_scenario",
    "parse_grid",
    "parse_obstacle",
    "parse_obstacles",
    "parse_robot",
]

ScenarioFileArg = Annotated[
    Path | None,
    typer.Argument(
        help="Scenario file (.toml or .json; - reads standard input); or give it inline with --grid.",
        show_default=False,
    ),
]
GridFlag = Annotated[
    str | None,
    typer.Option(
        "--grid",
        help="ROWSxCOLS: give the scenario inline instead of a file (see 'qcpp scenario').",
        metavar="RxC",
        show_default=False,
    ),
]
RobotCountFlag = Annotated[
    int | None,
    typer.Option(
        "--robots",
        help="With --grid: robots in the default placement (corners, then the other boundary nodes); default 1.",
        metavar="N",
        show_default=False,
        parser=one_whole_number("--robots"),
    ),
]
RobotFlag = Annotated[
    list[str] | None,
    typer.Option(
        "--robot",
        help="With --grid: START:GOAL as ROW,COL:ROW,COL, one robot's own endpoints (repeat per robot; instead of "
        "--robots).",
        metavar="R,C:R,C",
        show_default=False,
    ),
]
ObstacleFlag = Annotated[
    list[str] | None,
    typer.Option(
        "--obstacle", help="ROW,COL: an obstacle node (repeat for more).", metavar="ROW,COL", show_default=False
    ),
]
HardObstaclesFlag = Annotated[
    bool,
    typer.Option(
        "--hard-obstacles",
        help="Obstacles remove their edges (default: soft, the paper's: they cost).",
    ),
]

_FLAG_OF_FIELD = {"grid": "--grid", "rows": "--grid", "cols": "--grid", "robots": "--robots"}
"""Scenario fields an inline scenario's flags give whole: their errors name the flag."""

_GRID = re.compile(r"^\s*(\d+)\s*[xX]\s*(\d+)\s*$")
_NODE = re.compile(r"^\s*(\d+)\s*,\s*(\d+)\s*$")
_ENDPOINTS = re.compile(r"^\s*(\d+)\s*,\s*(\d+)\s*:\s*(\d+)\s*,\s*(\d+)\s*$")


def parse_grid(text: str) -> tuple[int, int]:
    """``"4x5"`` -> ``(4, 5)``.

    Raises:
        qcpp.errors.OptionError: naming ``--grid``, for anything but one ``ROWSxCOLS``.
    """
    m = _GRID.match(text)
    if m is None:
        note = f"; one grid only: {RANGES_NOTE}" if is_range_or_list(text) else ""
        raise OptionError("--grid", f"expected ROWSxCOLS such as 3x4, got {text!r}{note}")
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


def parse_robot(text: str) -> tuple[tuple[int, int], tuple[int, int]]:
    """``"0,0:2,3"`` -> ``((0, 0), (2, 3))``: one robot's start and goal.

    Raises:
        qcpp.errors.OptionError: naming ``--robot``, for anything but ``ROW,COL:ROW,COL``.

    Example:
        >>> parse_robot("0,0:2,3")
        ((0, 0), (2, 3))
    """
    m = _ENDPOINTS.match(text)
    if m is None:
        raise OptionError("--robot", f"expected START:GOAL as ROW,COL:ROW,COL such as 0,0:2,3, got {text!r}")
    r0, c0, r1, c1 = (int(g) for g in m.groups())
    return (r0, c0), (r1, c1)


def parse_obstacles(texts: Sequence[str] | None) -> list[tuple[int, int]]:
    """Every ``--obstacle`` value, parsed (:func:`parse_obstacle`)."""
    return [parse_obstacle(t) for t in texts or ()]


def inline_scenario(
    grid: str, robots: int | None, obstacles: Sequence[str] | None, hard: bool,
    endpoints: Sequence[str] | None = None,
) -> Scenario:  # fmt: skip
    """The scenario of ``--grid``, ``--robots`` (or ``--robot``, ``endpoints``), ``--obstacle`` and
    ``--hard-obstacles`` (:func:`qcpp.problem.presets.grid_scenario`).

    Raises:
        qcpp.errors.OptionError: a malformed ``--grid``, ``--robot`` or ``--obstacle``; ``--robot`` with
            ``--robots``.
        qcpp.problem.errors.ScenarioError: a scenario that cannot be (an obstacle off the grid or on a robot's
            start or goal, more robots than the default placement holds), naming the field; a refusal of the grid's
            size or of the robot count names the option instead (``--grid: the grid must be at least 2x2, got
            0x3``), as ``qcpp estimate`` words it.
    """
    rows, cols = parse_grid(grid)
    if endpoints and robots is not None:
        raise OptionError("--robot", "gives the robots one by one: do not give --robots too")
    placed = [parse_robot(t) for t in endpoints] if endpoints else (1 if robots is None else robots)
    try:
        return grid_scenario(
            rows, cols, robots=placed, obstacles=parse_obstacles(obstacles), hard_obstacles=hard
        )
    except ScenarioError as exc:
        raise flag_error(exc, placed, obstacles, endpoints) from None


_ROBOT_FIELD = re.compile(r"^robots\[(\d+)\]\.(start|goal)$")
_OBSTACLE_FIELD = re.compile(r"^obstacles\[(\d+)\]$")


def flag_error(
    exc: ScenarioError, robots: object, obstacles: Sequence[str] | None, endpoints: Sequence[str] | None
) -> ScenarioError:
    """``exc``, a refusal of an inline scenario's :func:`~qcpp.problem.presets.grid_scenario`, worded by the
    flags the user typed.

    A field a flag gives names the flag, with its value where the flag repeats (``--obstacle 7,1: (7, 1) is
    outside the 3x3 grid``, ``--robot 0,0:5,5: goal (5, 5) is outside the 3x3 grid``); the robot count names
    the flag that gave the robots (``--robot`` when they came one by one, else ``--robots``); an obstacle on a
    robot's endpoint in the default placement names the obstacle and the way out. Any other field: ``exc``.

    Args:
        exc: The builder's error.
        robots: ``--robots`` as given (a count, a range text, or ``None``), for the message.
        obstacles: ``--obstacle`` values as typed, in order.
        endpoints: ``--robot`` values as typed, in order (empty: the default placement).

    Returns:
        The error to raise (same type as ``exc``).

    Example:
        >>> err = ScenarioError("obstacles[0]", "(7, 1) is outside the 3x3 grid")
        >>> str(flag_error(err, 1, ["7,1"], None))
        '--obstacle 7,1: (7, 1) is outside the 3x3 grid'
    """
    field, reason = exc.field, exc.reason
    if field == "robots" and endpoints:
        return type(exc)("--robot", reason)
    if field in _FLAG_OF_FIELD:
        return type(exc)(_FLAG_OF_FIELD[field], reason)
    if (m := _OBSTACLE_FIELD.match(field)) and obstacles:
        return type(exc)(f"--obstacle {obstacles[int(m[1])].strip()}", reason)
    if not (m := _ROBOT_FIELD.match(field)):
        return exc
    robot, end = int(m[1]), m[2]
    if endpoints:
        return type(exc)(f"--robot {endpoints[robot].strip()}", f"{end} {reason}")
    for text, node in zip(obstacles or (), parse_obstacles(obstacles), strict=True):
        if reason == f"{node} is an obstacle":
            count = 1 if robots is None else robots
            return type(exc)(
                f"--obstacle {text.strip()}",
                f"{node} is robot {robot}'s {end} in the default placement of --robots {count} (place the robots "
                "with --robot START:GOAL)",
            )
    return exc


def check_inline_only(
    grid: str | None, robots: object, obstacles: Sequence[str] | None, hard: bool,
    endpoints: Sequence[str] | None = None,
) -> None:  # fmt: skip
    """Refuse ``--robots``, ``--robot``, ``--obstacle`` or ``--hard-obstacles`` without ``--grid`` (they would be
    ignored).

    Raises:
        qcpp.errors.OptionError: naming the flag.
    """
    if grid is not None:
        return
    for flag, given in (("--robots", robots is not None), ("--robot", bool(endpoints)),
                        ("--obstacle", bool(obstacles)), ("--hard-obstacles", hard)):  # fmt: skip
        if given:
            raise OptionError(flag, "applies with --grid only (no --grid given)")


@dataclass(frozen=True)
class GivenScenario:
    """A command's scenario and how to name it.

    Attributes:
        scenario: The scenario.
        label: For titles and progress lines: the file's name, or the inline scenario's name.
        source: For JSON output (its ``scenario`` field): the file's path as given, or the inline flags that give
            the scenario again (``--grid 4x4 --robots 2 --obstacle 1,1``).
    """

    scenario: Scenario
    label: str
    source: str


def given_scenario(
    path: Path | None, grid: str | None, robots: int | None, obstacles: Sequence[str] | None, hard: bool, *,
    check_range: bool = True, phases: bool = False, endpoints: Sequence[str] | None = None,
) -> GivenScenario:  # fmt: skip
    """The scenario of a command's file argument or of its inline flags (exactly one of the two).

    Args:
        path: The scenario file argument (``None``: not given).
        grid, robots, obstacles, hard: ``--grid``, ``--robots``, ``--obstacle`` and ``--hard-obstacles``.
        check_range: Refuse weights the solvers cannot represent exactly
            (:func:`qcpp.problem.cost_range.check_cost_range`), for an inline scenario as for a file.
        phases: With ``check_range``: the QAOA phases' narrower range
            (:func:`qcpp.problem.cost_range.check_phase_range`).
        endpoints: ``--robot`` values (each robot's ``START:GOAL``), instead of ``robots``.

    Raises:
        qcpp.errors.OptionError: inline flags without ``--grid``, a malformed ``--grid`` or ``--obstacle``.
        ValueError: both a file and ``--grid``, or neither.
        qcpp.problem.errors.ScenarioError: a file or inline scenario that cannot be (naming the field).

    Example:
        >>> g = given_scenario(None, "3x3", 2, ["1,1"], False)
        >>> g.label, g.source
        ('3x3, 2 robot(s), 1 obstacle(s)', '--grid 3x3 --robots 2 --obstacle 1,1')
    """
    check_inline_only(grid, robots, obstacles, hard, endpoints)
    if grid is not None and path is not None:
        raise ValueError(f"--grid gives the scenario: do not give the scenario file {str(path)!r} too")
    if grid is None:
        if path is None:
            raise ValueError(
                "give a scenario file, or the scenario inline with --grid RxC [--robots N] [--obstacle R,C]"
            )
        label = STDIN_LABEL if str(path) == STDIN else path.name  # ``-``: standard input (sniffed TOML or JSON)
        return GivenScenario(load_scenario(path, check_range=check_range, phases=phases), label, str(path))
    s = inline_scenario(grid, robots, obstacles, hard, endpoints)
    if check_range:
        check_phase_range(s) if phases else check_cost_range(s)
    g = s.grid
    placement = ([f"--robot {r.start[0]},{r.start[1]}:{r.goal[0]},{r.goal[1]}" for r in s.robots] if endpoints
                 else [f"--robots {s.num_robots}"])  # fmt: skip
    flags = [f"--grid {g.rows}x{g.cols}", *placement, *(f"--obstacle {r},{c}" for r, c in s.obstacles)]
    flags += ["--hard-obstacles"] if hard else []
    return GivenScenario(s, s.name or f"{g.rows}x{g.cols}", " ".join(flags))
