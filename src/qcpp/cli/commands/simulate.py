"""``qcpp simulate``: evaluate QAOA angles on a scenario with one of the simulators.

A thin layer over :func:`qcpp.training.evaluate.evaluate`: parses the options, prints a short report (or one JSON
object with ``--json``). Bad input raises ``ValueError``/``ScenarioError``, which the CLI's shared handler
turns into one line on stderr and exit code 2.

Examples::

    qcpp simulate examples/paper_3x3.toml -p 1 --angles 0.3,1.2
    qcpp simulate examples/paper_3x3.toml -p 2 --method statevector --seed 4 --json
    qcpp simulate examples/two_robots_4x4.toml -p 3 --method subspace --rule exact
    qcpp simulate examples/obstacles_hard_4x4.toml -p 2 --initial representatives
"""

from __future__ import annotations

import math
from typing import Annotated

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from qcpp.cli.commands.inline_scenario import (
    GridFlag,
    HardObstaclesFlag,
    ObstacleFlag,
    RobotCountFlag,
    RobotFlag,
    ScenarioFileArg,
    given_scenario,
)
from qcpp.cli.commands.plan_flags import InitialFlag, LayersFlag, RuleFlag
from qcpp.cli.progress import Progress
from qcpp.cli.render import json_text, print_table
from qcpp.problem.scenario import Scenario

__all__ = ["parse_angles", "register", "simulate_command"]

HELP = """Evaluate QAOA angles: expectation <C>, probability of the optimum, feasible probability.

Examples:
  qcpp simulate examples/paper_3x3.toml -p 1 --angles 0.3,1.2
  qcpp simulate --grid 3x3 --obstacle 1,1 -p 2 --method statevector --json
  qcpp simulate examples/two_robots_4x4.toml -p 3 --seed 4

Methods: subspace = the feasible-subspace simulator; statevector = the
compiled circuit's dense state; tensor = a tensor network (quimb).
"""


def parse_angles(text: str) -> list[float]:
    """``"g0,b0,g1,b1"`` -> floats.

    Raises:
        ValueError: naming the item that is not a finite number.

    Example:
        >>> parse_angles("0.3, 1.2")
        [0.3, 1.2]
    """
    out = []
    for part in text.split(","):
        item = part.strip()
        try:
            value = float(item)
        except ValueError:
            raise ValueError(f"--angles: {item!r} is not a number (expected g0,b0,g1,b1,...)") from None
        if not math.isfinite(value):
            raise ValueError(f"--angles: {item!r} is not a finite number")
        out.append(value)
    return out


def _guard(s: Scenario, source: str, p: int, method: str) -> None:
    """Refuse (one line, exit 2) a simulation predicted to need more memory than is available or to run for
    hours (:func:`qcpp.simulate.guards.check_simulation_size`); ``--allow-large`` lifts it."""
    from qcpp.simulate.guards import check_simulation_size

    check_simulation_size(s, source, p=p, method=method)


def simulate_command(
    scenario: ScenarioFileArg = None,
    p: LayersFlag = 1,
    method: Annotated[
        str, typer.Option("--method", "-m", help="Simulator: subspace, statevector or tensor.")
    ] = "subspace",
    angles: Annotated[
        str | None, typer.Option("--angles", help="g0,b0,g1,b1,... (2p values); default: random from --seed.")
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the random angles (at least 0).")] = 0,
    rule: RuleFlag = "exact",
    initial: InitialFlag = "initial_path",
    as_json: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
    grid: GridFlag = None,
    robots: RobotCountFlag = None,
    robot: RobotFlag = None,
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
) -> None:
    """Evaluate QAOA angles (see ``qcpp simulate --help``)."""
    from qcpp.training.evaluate import evaluate  # scipy: imported when the command runs, not at start-up

    values = parse_angles(angles) if angles is not None else None
    if values is not None and len(values) != 2 * p:  # before the scenario is loaded, naming the flag
        raise ValueError(f"--angles: p = {p} needs {2 * p} angles (g0,b0,...), got {len(values)}")
    given = given_scenario(scenario, grid, robots, obstacle, hard_obstacles, phases=True, endpoints=robot)
    s = given.scenario
    _guard(s, given.source, p, method)
    with Progress(f"simulate {given.label}") as bar:
        bar.stage(f"simulating ({method})")
        angle_seed = None if values is not None else seed
        res = evaluate(s, p, method, angles=values, seed=angle_seed, rule=rule, initial=initial)  # type: ignore[arg-type]
    if as_json:
        typer.echo(json_text({"scenario": given.source, **res.as_dict(), "rule": rule, "initial": initial}))
        return
    start = "" if initial == "initial_path" else f", from {initial}"
    table = Table(title=f"{s.name or given.label}: p={p}, {method}{start}", title_justify="left")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_row(escape("angles [g0, b0, ...]"), ", ".join(f"{a:.6g}" for a in res.angles))
    table.add_row("expectation <C>", f"{res.expectation:.10g}")
    table.add_row("probability of the optimum", f"{res.p_optimum:.6g}")
    table.add_row("held on feasible, clean ancillas", f"{res.amplitudes_held:.12g}")
    if res.qubits is not None:
        table.add_row("qubits simulated", str(res.qubits))
    table.add_row("amplitudes computed", f"{res.basis_states:,}")
    table.add_row("seconds", f"{res.seconds:.3f}")
    print_table(Console(), table)


def register(app: typer.Typer) -> None:
    """Add ``simulate`` to ``app``."""
    app.command("simulate", help=HELP)(simulate_command)
