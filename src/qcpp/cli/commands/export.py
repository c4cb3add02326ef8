"""``qcpp export``: write a scenario's cost as a QUBO / Ising model / MIP for annealers and other solvers.

Examples::

    qcpp export examples/two_robots_4x4.toml --format bqm --out model.json        # dimod JSON (needs dimod)
    qcpp export examples/two_robots_4x4.toml --format ising --form paper --out ising.json
    qcpp export examples/two_robots_5x5.toml --format qubo --penalty 8 --out qubo.json
    qcpp export examples/two_robots_5x5.toml --format mps --out model.mps          # loads in OR-Tools, SCIP, ...

The model (:mod:`qcpp.qubo.model`) and the formats (:mod:`qcpp.qubo.export`) are documented there and in
docs/qubo.md. The file is written whole or not at all; ``--out -`` writes to standard output.
"""

from __future__ import annotations

import math
from typing import Annotated

import typer

from qcpp.cli.commands.inline_scenario import (
    GridFlag,
    HardObstaclesFlag,
    ObstacleFlag,
    RobotCountFlag,
    RobotFlag,
    ScenarioFileArg,
    given_scenario,
)
from qcpp.cli.progress import Progress
from qcpp.cli.render import echo_note, json_text
from qcpp.io.atomic import check_output, is_stdout, write_text_atomic
from qcpp.qubo.export import EXPORT_FORMATS, export_text
from qcpp.qubo.model import FORMS, bqm_for
from qcpp.qubo.solve import INSTALL_HINT

__all__ = ["HELP", "export_command", "register"]

HELP = """Write the scenario's cost as a QUBO, Ising model, dimod BQM or LP/MPS program.

Examples:
  qcpp export examples/two_robots_4x4.toml --format ising --out ising.json
  qcpp export --grid 4x4 --robots 2 -f qubo --form paper -o qubo.json
  qcpp export examples/two_robots_5x5.toml --format mps --out model.mps

--form per-robot adds degree penalties with visit bits (zero on feasible
paths); --form paper is exactly the paper's cost. Ising: x = (1 - Z)/2.
"""


def export_command(
    fmt: Annotated[
        str, typer.Option("--format", "-f", help=f"Output format: {', '.join(EXPORT_FORMATS)}.", show_default=False)
    ],
    out: Annotated[str, typer.Option("--out", "-o", help="Output file ('-': standard output).", show_default=False)],
    scenario: ScenarioFileArg = None,
    form: Annotated[str, typer.Option("--form", help=f"Model form: {' or '.join(FORMS)}.")] = "per-robot",
    penalty: Annotated[
        float | None,
        typer.Option("--penalty", help="Degree penalty P of the per-robot form.", show_default="the documented rule"),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print a JSON summary on stdout.")] = False,
    grid: GridFlag = None,
    robots: RobotCountFlag = None,
    robot: RobotFlag = None,
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
) -> None:
    """Export a scenario's QUBO (see ``qcpp export --help``)."""
    if penalty is not None:
        if form != "per-robot":
            raise ValueError(f"--penalty: applies to --form per-robot only (got --form {form})")
        if not (math.isfinite(penalty) and penalty > 0):
            raise ValueError(f"--penalty: expected a positive finite number, got {penalty:g}")
    if as_json and is_stdout(out):
        raise ValueError("--json: the summary goes to standard output, so --out must name a file")
    if fmt == "bqm":
        try:
            import dimod  # noqa: F401
        except ImportError:
            raise ValueError(f"--format bqm needs dimod: {INSTALL_HINT} (ising, qubo, lp, mps need nothing)") from None
    check_output(out)  # a bad destination fails before any work
    given = given_scenario(scenario, grid, robots, obstacle, hard_obstacles, check_range=False, endpoints=robot)
    s = given.scenario
    with Progress(f"export {fmt} of {given.label}", total=2) as bar:
        # the penalty rule's upper bound (a short SBF annealing run) and the MIP exports take seconds on big grids
        model = bqm_for(s, form, penalty)
        bar.advance()
        text = export_text(model, fmt)
        bar.advance()
    write_text_atomic(out, text)
    summary = {
        "scenario": given.source,
        "out": out,
        "format": fmt,
        "form": model.form,
        "penalty": model.penalty,
        "variables": model.num_variables,
        "edge_variables": model.num_edge_variables,
        "interactions": model.num_interactions,
    }
    if as_json:
        typer.echo(json_text(summary))
        return
    extra = f", penalty P = {model.penalty:g}" if model.penalty is not None else ""
    if not is_stdout(out):
        line = (f"wrote {out}: {fmt}, {model.form} form, {model.num_variables} variables, "
                f"{model.num_interactions} interactions{extra}")
        echo_note(line)


def register(app: typer.Typer) -> None:
    """Add ``export`` to ``app``."""
    app.command("export", help=HELP)(export_command)
