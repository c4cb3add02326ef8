"""``qcpp scenario``: the scenario of ``--grid RxC --robots N --obstacle R,C ...`` as a file (TOML, or JSON), so that
the default placement the inline flags of ``compile`` and ``estimate`` use is visible and can be edited.

Examples::

    qcpp scenario --grid 5x5 --robots 2
    qcpp scenario --grid 10x10 --robots 3 --obstacle 4,4 --obstacle 5,6 -o field.toml
    qcpp scenario --grid 4x4 --robots 1 --obstacle 1,1 --hard-obstacles --json

The scenario is built by :func:`qcpp.problem.presets.grid_scenario` (``qcpp.grid_scenario`` in Python), and the
text is :func:`qcpp.problem.scenario.scenario_to_toml` (every objective setting written out): loading it back gives
the same scenario. ``-o FILE`` writes it whole or not at all (:mod:`qcpp.io.atomic`), as TOML or JSON by the suffix.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

from qcpp.cli.commands.inline_scenario import (
    GridFlag,
    HardObstaclesFlag,
    ObstacleFlag,
    RobotCountFlag,
    RobotFlag,
    inline_scenario,
)
from qcpp.cli.render import render_ascii
from qcpp.io.atomic import check_output
from qcpp.problem.scenario import scenario_to_dict
from qcpp.problem.scenario_io import save_scenario, scenario_to_toml

__all__ = ["register", "scenario_command"]

HELP = """Print (or write with -o) the scenario file of --grid, --robots (or
--robot) and --obstacle.

Examples:
  qcpp scenario --grid 5x5 --robots 2
  qcpp scenario --grid 7x6 --robot 0,0:6,5 --robot 0,5:6,0 --obstacle 2,2
  qcpp scenario --grid 10x10 --robots 3 --obstacle 4,4 -o field.toml
  qcpp scenario --grid 4x4 --obstacle 1,1 --hard-obstacles --json --draw

The file spells out the default robot placement; compile, estimate, solve
and the other commands read it. --draw shows the field (qcpp solve draws
the paths on it).
"""


def scenario_command(
    grid: GridFlag = None,
    robots: RobotCountFlag = None,
    robot: RobotFlag = None,
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
    output: Annotated[
        Path | None,
        typer.Option("-o", "--output", help="Write the scenario to this file (.toml or .json) instead of printing it."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of TOML.")] = False,
    draw: Annotated[
        bool, typer.Option("--draw", help="Also draw the grid (obstacles, starts, goals) on stderr.")
    ] = False,
) -> None:
    """Print or write a scenario (see ``qcpp scenario --help``)."""
    if grid is None:
        raise ValueError("--grid: give the grid as ROWSxCOLS (e.g. qcpp scenario --grid 5x5 --robots 2)")
    if output is not None and as_json:
        raise ValueError("--json prints the scenario; with -o the file's suffix (.toml or .json) chooses the format")
    if output is not None:
        check_output(output)  # a bad destination fails before anything is built
    s = inline_scenario(grid, robots, obstacle, hard_obstacles, robot)
    if draw:  # on stderr, so the scenario text on stdout stays a file
        typer.echo(render_ascii(s), err=True)
    if output is not None:
        save_scenario(s, output)
        typer.echo(f"wrote {output}", err=True)
        return
    typer.echo(json.dumps(scenario_to_dict(s), indent=2) if as_json else scenario_to_toml(s), nl=as_json)


def register(app: typer.Typer) -> None:
    """Add ``scenario`` to ``app``."""
    app.command("scenario", help=HELP)(scenario_command)
