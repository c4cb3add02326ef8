"""``qcpp estimate``: exact resource counts, the paper's estimates and the closed-form formulas.

A thin layer over :mod:`estimators.report`: it parses options and prints. Bad input gives exit code 2 and one line
``error: <message>`` on stderr, the format of the CLI's shared handler (:mod:`qcpp.cli`), which also catches
anything the command itself does not (e.g. an unwritable ``--plot`` path). ``register(app)`` adds the command.

Examples::

    qcpp estimate --grid 3x3 --robots 1
    qcpp estimate --grid 2x2..8x8 --robots 1..4 -p 1..3 --compare paper --format md
    qcpp estimate --grid 3x3..6x6 --robots 1..3 --compare paper --plot estimates.png
    qcpp estimate --scenario examples/two_robots.toml -p 2 --json
    qcpp estimate --formula
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from estimators.paper import DOUBLINGS
from estimators.tables import FORMATS
from gridcover.atomic import check_output
from gridcover.errors import ScenarioError

__all__ = ["estimate", "register"]

HELP = (
    "Exact resource counts of the lowered QAOA circuit (qubits, gates, CNOT, T, depth), optionally beside the "
    "paper's estimates, plus labelled fault-tolerant estimates. Ranges: --grid AxB..CxD means every rows in A..C "
    "and every cols in B..D; --robots and -p take N or A..B."
)


def _fail(message: str) -> typer.Exit:
    typer.echo(f"error: {message}", err=True)
    return typer.Exit(code=2)


def estimate(
    grid: Annotated[
        str | None,
        typer.Option(
            "--grid",
            help="ROWSxCOLS, AxB..CxD (every rows in A..C, cols in B..D) or a comma list of these; default 3x3.",
        ),
    ] = None,
    robots: Annotated[
        str | None, typer.Option("--robots", help="Robots: N or A..B (1 to 4, corner placement; default 1).")
    ] = None,
    p: Annotated[str, typer.Option("-p", "--layers", help="QAOA layers: N or A..B.")] = "1",
    scenario: Annotated[
        Path | None, typer.Option("--scenario", help="Estimate this scenario file instead of the default ones.")
    ] = None,
    rule: Annotated[str, typer.Option("--rule", help="SBF logic rule: exact or paper.")] = "exact",
    compare: Annotated[str | None, typer.Option("--compare", help="Add the paper's estimates: paper.")] = None,
    fmt: Annotated[str, typer.Option("--format", help="Output: table, md, csv or json.")] = "table",
    as_json: Annotated[bool, typer.Option("--json", help="Same as --format json.")] = False,
    plot: Annotated[
        str | None, typer.Option("--plot", help="Also write the comparison plot (PNG) here (its folder must exist).")
    ] = None,
    columns: Annotated[
        str | None,
        typer.Option("--columns", help="Table columns, comma-separated (any CSV column; default: what fits)."),
    ] = None,
    wide: Annotated[bool, typer.Option("--wide", help="Table: every default column, however wide.")] = False,
    formula: Annotated[bool, typer.Option("--formula", help="Print the closed-form formulas and stop.")] = False,
    no_cache: Annotated[bool, typer.Option("--no-cache", help="Neither read nor write the estimate cache.")] = False,
    jobs: Annotated[int | None, typer.Option("--jobs", "-j", help="Worker processes (default: all cores).")] = None,
    epsilon: Annotated[
        float, typer.Option("--epsilon", help="Rotation synthesis precision of the fault-tolerant columns.")
    ] = 1e-3,
    paper_doubling: Annotated[
        str,
        typer.Option(
            "--paper-doubling",
            help="What the paper's 'twice of the controlled partial mixer' doubles: partial-mixer or logic.",
        ),
    ] = "partial-mixer",
) -> None:
    """Exact resource counts (see ``qcpp estimate --help``)."""
    # imported here: estimators.report pulls in sympy, which would slow every other command's start-up
    from estimators.report import estimate_report, formula_report, points_from_options

    if as_json:
        fmt = "json"
    if fmt not in FORMATS:
        raise _fail(f"bad --format {fmt!r}: expected one of {', '.join(FORMATS)}")
    if formula:
        typer.echo(formula_report(fmt), nl=False)  # type: ignore[arg-type]
        return
    if compare not in (None, "paper"):
        raise _fail(f"bad --compare {compare!r}: the only comparison is 'paper'")
    if paper_doubling not in DOUBLINGS:
        raise _fail(f"bad --paper-doubling {paper_doubling!r}: expected one of {', '.join(DOUBLINGS)}")
    if not 0.0 < epsilon < 1.0:
        raise _fail(f"bad --epsilon {epsilon}: must be in (0, 1)")
    if plot is not None:
        check_output(plot)  # a bad destination fails before the sweep, not after
    try:
        points = points_from_options(grid, robots, p, scenario, rule)
    except ScenarioError as exc:
        raise _fail(str(exc)) from None
    except ValueError as exc:
        raise _fail(str(exc)) from None
    text = estimate_report(
        points,
        fmt=fmt,  # type: ignore[arg-type]
        compare_paper=compare == "paper",
        plot=plot,
        use_cache=not no_cache,
        jobs=jobs,
        epsilon=epsilon,
        doubling=paper_doubling,  # type: ignore[arg-type]
        progress=sys.stderr.isatty(),
        columns=[c.strip() for c in columns.split(",") if c.strip()] if columns is not None else None,
        wide=wide,
    )
    typer.echo(text, nl=False)
    if plot is not None:
        typer.echo(f"wrote {plot}", err=True)


def register(app: typer.Typer) -> None:
    """Add ``estimate`` to ``app``."""
    app.command("estimate", help=HELP)(estimate)
