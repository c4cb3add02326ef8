"""``qcpp solve``: solve a scenario with one of the registered methods and show the paths.

Examples::

    qcpp solve examples/paper_3x3.toml --method dfs
    qcpp solve examples/two_robots_4x4.toml --method anneal --seed 3 --plot paths.png --plot-trace trace.png
    qcpp solve examples/two_robots_5x5.toml --method genetic --rule paper --json

Methods come from :data:`SOLVE_METHODS` (name -> :class:`gridcover.solvers.SolveMethod`); ``--method``
accepts exactly its keys. Adding a method (e.g. QAOA) is one entry: a function
``f(scenario, *, seed, rule, progress) -> gridcover.solvers.Solution`` stored under its name.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn
from rich.table import Table

from gridcover.render import plot_paths, plot_trace, render_ascii
from gridcover.sbf import RULES
from gridcover.scenario import Scenario, load_scenario
from gridcover.solvers import SOLVERS, ProgressFn, Solution, SolveMethod, solution_to_dict

__all__ = ["SOLVE_METHODS", "progress_reporter", "register", "solve_command"]

SOLVE_METHODS: dict[str, SolveMethod] = dict(SOLVERS)
"""``--method`` name -> solver. Register new methods here (the CLI reads the keys at call time)."""

HELP = (
    "Solve a scenario (dfs = exhaustive optimum, anneal = simulated annealing, genetic = the paper's GA with "
    "SBF mutations) and print the paths on the grid, the cost and its parts."
)


@contextmanager
def progress_reporter(description: str) -> Iterator[ProgressFn]:
    """A :data:`~gridcover.solvers.ProgressFn` drawing a rich progress bar on stderr (only on a terminal).

    The bar is transient (erased when done) and never touches stdout, so ``--json`` output stays clean.
    """
    console = Console(stderr=True)
    with Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=not console.is_terminal,
    ) as bar:
        task = bar.add_task(description, total=None)

        def update(done: int, total: int) -> None:
            bar.update(task, completed=done, total=total)

        yield update


def _cost_table(scenario: Scenario, sol: Solution) -> Table:
    a0, a1, a2 = scenario.objective.alpha
    table = Table(title="cost", title_justify="left")
    for col in ("term", "value", "weight", "weighted"):
        table.add_column(col, justify="left" if col == "term" else "right")
    for term, value, weight in (
        ("c1 obstacles/coverage", sol.cost.c1, a0),
        ("c2 length balance", sol.cost.c2, a1),
        ("c3 node degrees", sol.cost.c3, a2),
    ):
        table.add_row(term, f"{value:g}", f"{weight:g}", f"{weight * value:g}")
    table.add_row("[bold]total", "", "", f"[bold]{sol.cost.total:g}")
    return table


def solve_command(
    scenario: Annotated[Path, typer.Argument(help="Scenario file (.toml or .json).", show_default=False)],
    method: Annotated[str, typer.Option("--method", "-m", help="Solver: dfs, anneal or genetic.")] = "anneal",
    seed: Annotated[int, typer.Option("--seed", help="Random seed (anneal, genetic).")] = 0,
    rule: Annotated[str, typer.Option("--rule", help="SBF move rule: exact or paper.")] = "exact",
    as_json: Annotated[bool, typer.Option("--json", help="Print one JSON object instead of the drawing.")] = False,
    plot: Annotated[
        Path | None, typer.Option("--plot", help="Also draw the paths to this image (PNG, SVG, ...).")
    ] = None,
    plot_trace_file: Annotated[
        Path | None, typer.Option("--plot-trace", help="Also plot the best-so-far cost trace (anneal, genetic).")
    ] = None,
) -> None:
    """Solve a scenario (see ``qcpp solve --help``)."""
    if method not in SOLVE_METHODS:
        raise ValueError(f"--method: unknown method {method!r} (expected one of {', '.join(SOLVE_METHODS)})")
    if rule not in RULES:
        raise ValueError(f"--rule: expected one of {', '.join(RULES)}, got {rule!r}")
    s = load_scenario(scenario)
    with progress_reporter(f"{method} on {scenario.name}") as progress:
        sol = SOLVE_METHODS[method](s, seed=seed, rule=rule, progress=progress)  # type: ignore[arg-type]
    if plot is not None:
        plot_paths(s, sol.paths, plot, title=f"{s.name or scenario.name}: {method}, cost {sol.cost.total:g}")
    if plot_trace_file is not None:
        if not sol.trace:
            raise ValueError(f"--plot-trace: method {method!r} has no cost trace")
        unit = "generation" if method == "genetic" else "iteration"
        plot_trace(sol.trace, plot_trace_file, title=f"{method}: best cost so far", xlabel=unit)

    if as_json:
        out = {"scenario": str(scenario), **solution_to_dict(s, sol, include_trace=False)}
        if sol.trace:
            out["trace_length"] = len(sol.trace)
        typer.echo(json.dumps(out))
        return
    console = Console()
    console.print(render_ascii(s, sol.paths), markup=False, highlight=False)
    console.print()
    console.print(_cost_table(s, sol))
    details = [f"method {method}", f"{sol.seconds:.3f} s", f"{sol.evaluated:,} assignments scored"]
    if sol.paths_per_robot:
        details.append("paths per robot " + " x ".join(f"{n:,}" for n in sol.paths_per_robot))
    if sol.seed is not None:
        details.append(f"seed {sol.seed}")
    if sol.rule is not None:
        details.append(f"rule {sol.rule}")
    console.print(", ".join(details), highlight=False)
    for note in sol.notes:
        console.print(f"[dim]note: {note}[/dim]", highlight=False)
    for path in (plot, plot_trace_file):
        if path is not None:
            typer.echo(f"wrote {path}", err=True)
    sys.stdout.flush()


def register(app: typer.Typer) -> None:
    """Add ``solve`` to ``app``."""
    app.command("solve", help=HELP)(solve_command)
