"""``qcpp estimate``: resource counts from the gadgets' costs, fault-tolerant and physical estimates, formulas.

A thin layer over :mod:`qcpp.estimators.report`: it parses options and prints, row by row as rows are computed (for
every format but ``table``). Bad input gives exit code 2 and one line ``error: <message>`` on stderr, the format
of the CLI's shared handler (:mod:`qcpp.cli.app`), which also catches anything the command itself does not (e.g. an
unwritable ``--plot`` path). ``register(app)`` adds the command.

Examples: see :data:`HELP` (``qcpp estimate --help``; ``tests/cli/help_and_noise_test.py`` runs them).
"""

from __future__ import annotations

import signal
import sys
import threading
from collections.abc import Sequence
from pathlib import Path
from typing import Annotated, Any

import typer

from qcpp.cli.commands.inline_scenario import (
    HardObstaclesFlag,
    ObstacleFlag,
    RobotFlag,
    flag_error,
    parse_obstacles,
    parse_robot,
)
from qcpp.cli.commands.plan_flags import check_start, with_plan_flags
from qcpp.cli.progress import Progress
from qcpp.cli.render import check_figure_output, echo_note, print_table
from qcpp.errors import OptionError
from qcpp.estimators.tables import terminal_width
from qcpp.plan.options import PlanOptions
from qcpp.problem.errors import ScenarioError

__all__ = ["LONG_SWEEP_ROWS", "estimate", "register"]

LONG_SWEEP_ROWS = 200
"""Sweeps of at least this many rows print their first progress line at once (on a pipe), not after a second."""

HELP = """Resource counts of the lowered QAOA circuit, from its gadgets' costs, without building it.

Examples:
  qcpp estimate --grid 6x8 --robots 1..3 -p 1..3 --format latex
  qcpp estimate --grid 2x2..6x6 --robots 1..3 --compare paper --plot cx.png
  qcpp estimate examples/two_robots_4x4.toml --physical --json
  qcpp estimate --grid 7x6 --robot 0,0:6,5 --robot 0,5:6,0 --obstacle 2,2

Ranges: --grid AxB..CxD (rows A..C, cols B..D), --robots A..B, -p A..B.
Columns defined: docs/resource-estimates.md ("Columns"); the routed ones
(routed_twoq, esp, routed_kind exact/bound): docs/guide/hardware.md.
In a cell, <=N is an upper bound and >=N a lower bound.
"""


@with_plan_flags
def estimate(
    options: PlanOptions,
    scenario_file: Annotated[
        Path | None,
        typer.Argument(
            help="Scenario file (.toml or .json), as --scenario; or give the grid with --grid.", metavar="SCENARIO",
            show_default=False,
        ),
    ] = None,
    grid: Annotated[
        str | None,
        typer.Option(
            "--grid",
            help="ROWSxCOLS, a range AxB..CxD or a comma list (default 3x3).",
        ),
    ] = None,
    robots: Annotated[
        str | None,
        typer.Option(
            "--robots",
            help="N, A..B or a comma list of them: robots in the default placement (default 1).",
        ),
    ] = None,
    p: Annotated[str, typer.Option("-p", "--layers", help="QAOA layers: N, A..B or a comma list of them.")] = "1",
    scenario: Annotated[
        Path | None, typer.Option("--scenario", help="A scenario file instead of --grid/--robots.")
    ] = None,
    explain: Annotated[
        bool,
        typer.Option(
            "--explain", help="Also show the phase construction of each term group, and why (stderr)."
        ),
    ] = False,
    compare: Annotated[
        str | None, typer.Option("--compare", help="Add the paper's estimates (columns, and curves in --plot).")
    ] = None,
    fmt: Annotated[
        str | None,
        typer.Option("--format", help="table, md, csv, json, jsonl or latex (booktabs).", show_default="table"),
    ] = None,  # None: not given (table), so that --json can refuse any --format given with it
    as_json: Annotated[bool, typer.Option("--json", help="Same as --format json (not both).")] = False,
    plot: Annotated[
        str | None, typer.Option("--plot", help="Also plot --metric against the grid (or p) to this PNG/PDF/SVG.")
    ] = None,
    metric: Annotated[
        str | None,
        typer.Option(
            "--metric",
            help="The plotted column: cx (default), qubits, t, depth, ft_total_t, physical_qubits, routed_twoq, ...",
            show_default=False,
        ),
    ] = None,
    columns: Annotated[
        str | None,
        typer.Option("--columns", help="Columns of table, md, csv and latex output, comma-separated (default: what "
                     "fits; json keeps every field). Names such as rows, cols, robots, qubits, cx, t, ft_total_t, "
                     "routed_twoq, routed_kind, esp, log10_esp; every name: the header of --format csv."),
    ] = None,
    wide: Annotated[bool, typer.Option("--wide", help="Table: every default column, however wide.")] = False,
    formula: Annotated[bool, typer.Option("--formula", help="Print the closed-form formulas and stop.")] = False,
    depth: Annotated[
        str,
        typer.Option(
            "--depth",
            help="auto: exact up to --depth-budget gates per layer, else an upper bound (column depth_kind).",
        ),
    ] = "auto",
    depth_budget: Annotated[
        int,
        typer.Option(
            "--depth-budget",
            help="Lowered gates per layer up to which auto depths are exact.",
        ),
    ] = 20_000,
    epsilon: Annotated[
        float, typer.Option("--epsilon", help="Rotation synthesis precision (fault-tolerant columns).")
    ] = 1e-3,
    toffoli_t: Annotated[
        int, typer.Option("--toffoli-t", help="T per Toffoli: 7 (ancilla-free) or 4 (Jones 2013).")
    ] = 7,
    physical: Annotated[
        bool, typer.Option("--physical", help="Add physical estimates (QDK resource estimator).")
    ] = False,
    qubit_model: Annotated[
        str | None,
        typer.Option(
            "--qubit-model",
            help="With --physical: QDK qubit preset (default qubit_gate_ns_e3).",
            show_default=False,
        ),
    ] = None,
    qec_scheme: Annotated[
        str | None,
        typer.Option(
            "--qec-scheme",
            help="With --physical: QDK QEC scheme, surface_code (default) or floquet_code (Majorana).",
            show_default=False,
        ),
    ] = None,
    error_budget: Annotated[
        float | None,
        typer.Option(
            "--error-budget", help="With --physical: error budget of the estimate (default 0.001).", show_default=False
        ),
    ] = None,
    paper_doubling: Annotated[
        str,
        typer.Option(
            "--paper-doubling",
            help="What the paper's 'twice of the controlled partial mixer' doubles.",
        ),
    ] = "partial-mixer",
    device: Annotated[
        str | None,
        typer.Option(
            "--device",
            help="Add routed figures (routed_twoq, esp, ...) on grid[:RxC], heavy-hex[:D], all-to-all[:N], a "
            "named device or a device file (PATH.json).",
        ),
    ] = None,
    effort: Annotated[
        str,
        typer.Option(
            "--effort",
            help="With --device: full (every search) or quick (no choice of partial-mixer plans for the routing: a "
            "few times faster on a named device, for more two-qubit gates); as qcpp compile --effort.",
        ),
    ] = "full",
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
    robot: RobotFlag = None,
) -> None:
    """Resource estimates (see ``qcpp estimate --help``)."""
    # imported here: qcpp.estimators.report pulls in sympy, which would slow every other command's start-up
    from qcpp.estimators.estimate import checked_estimate_options
    from qcpp.estimators.physical import DEFAULT_ERROR_BUDGET, DEFAULT_QEC_SCHEME, DEFAULT_QUBIT_MODEL
    from qcpp.estimators.report import estimate_report, formula_report, points_from_options
    from qcpp.routing.options import effort_routing

    scenario_named = "--scenario" if scenario_file is None else f"the scenario file {str(scenario_file)!r}"
    if scenario_file is not None:
        if scenario is not None:
            raise OptionError("--scenario", f"the scenario file {str(scenario_file)!r} is given already")
        scenario = scenario_file
    if as_json and fmt is not None:  # two formats asked for, even the same one: refused, not one chosen
        raise OptionError("--json", f"is --format json; do not combine it with --format {fmt}")
    fmt = "json" if as_json else fmt or "table"
    physical_only = {"--qubit-model": qubit_model, "--qec-scheme": qec_scheme, "--error-budget": error_budget}
    for name, value in physical_only.items():
        if value is not None and not physical:
            raise OptionError(name, "applies with --physical only (no --physical given)")
    qubit_model = qubit_model if qubit_model is not None else DEFAULT_QUBIT_MODEL
    qec_scheme = qec_scheme if qec_scheme is not None else DEFAULT_QEC_SCHEME
    error_budget = error_budget if error_budget is not None else DEFAULT_ERROR_BUDGET
    if formula:
        if not options.first_phase:
            raise OptionError("--skip-first-phase", "the closed forms (--formula) are of the paper's p phase "
                              "separators; estimate the points instead")  # fmt: skip
        typer.echo(formula_report(fmt, width=terminal_width()), nl=False)  # type: ignore[arg-type]
        return
    settings = checked_estimate_options(
        options, epsilon=epsilon, toffoli_t=toffoli_t, depth=depth, depth_budget=depth_budget, physical=physical,
        qubit_model=qubit_model, qec_scheme=qec_scheme, error_budget=error_budget, flag=_flag,
    )  # fmt: skip
    if plot is not None:
        check_figure_output(plot)  # a bad destination or image type fails before the sweep, not after
    _check_metric(metric, plot=plot, physical=physical, device=device, depth=depth)
    if device is None and effort != "full":
        raise ValueError(f"--effort {effort}: applies with --device only (no device given)")  # as compile says
    obstacles = parse_obstacles(obstacle)
    # a bad range, file or obstacle: one line, exit 2 (qcpp.cli.app)
    endpoints = [parse_robot(t) for t in robot or ()]
    try:
        points = points_from_options(
            grid, robots, p, scenario, obstacles, hard_obstacles, endpoints, scenario_named=scenario_named
        )
    except ScenarioError as exc:
        raise flag_error(exc, robots, obstacle, robot) from None
    for s in dict.fromkeys(point.build_scenario() for point in points.points):
        check_start(s, options)
    if points.skipped:
        echo_note(
            f"skipped {points.skipped} of {points.skipped + len(points.points)} points: the grid is too small for "
            "the robot count (the default placement hosts 2(rows+cols)-4 robots)"
        )
    # progress unless the rows themselves stream to a terminal (a table waits for every row; a pipe shows nothing)
    show = fmt == "table" or plot is not None or not _is_terminal(sys.stdout)
    # a sweep of many rows is known to be long: its first line comes at once, not after a second
    first = 0.0 if len(points.points) >= LONG_SWEEP_ROWS else None
    bar = Progress("estimate", total=len(points.points), unit="rows", mode=None if show else "off", first_after=first)
    held: list[str] = []  # the table: printed once the progress display is gone, also when the plot then fails
    try:
        with bar:
            pieces = estimate_report(
                bar.iterate(points.points, then=_after_rows(fmt, plot)),
                fmt=fmt,  # type: ignore[arg-type]
                options=settings,
                compare_paper=compare == "paper",
                plot=plot,  # written after the last piece
                doubling=paper_doubling,  # type: ignore[arg-type]
                columns=[c.strip() for c in columns.split(",") if c.strip()] if columns is not None else None,
                wide=wide,
                device=device,
                stage=bar.stage,
                metric=metric or "cx",
                routing=effort_routing(effort),
            )
            for piece in pieces:
                if fmt == "table":
                    held.append(piece)
                else:
                    _write_whole(piece)
    finally:
        for piece in held:
            _write_whole(piece)
    if physical:
        echo_note(
            f"physical figures: estimates of the QDK resource estimator ({qubit_model}, {qec_scheme}, error budget "
            f"{error_budget:g}), from the logical counts"
        )
    if plot is not None:
        typer.echo(f"wrote {plot}", err=True)
    if explain:
        _explain(points.points, options)


def _after_rows(fmt: str, plot: str | None) -> str | None:
    """The progress stage once every row is estimated: the table is rendered, then the plot drawn (the report
    says ``drawing the plot`` when it starts)."""
    if fmt == "table":
        return "rendering the table"
    return "rendering the rows" if plot is not None else None


def _check_metric(metric: str | None, *, plot: str | None, physical: bool, device: str | None, depth: str) -> None:
    """Refuse a ``--metric`` without ``--plot``, unknown (listing the metrics), or whose column this run lacks."""
    if metric is None:
        return
    if plot is None:
        raise OptionError("--metric", "applies with --plot only (no --plot given)")
    from qcpp.estimators.plots import plot_metric

    needs = plot_metric(metric, "--metric").needs
    if needs == "physical" and not physical:
        raise OptionError("--metric", f"{metric} needs --physical")
    if needs == "device" and device is None:
        raise OptionError("--metric", f"{metric} needs --device")
    if needs == "depth" and depth == "none":
        raise OptionError("--metric", f"{metric} needs a depth (--depth is none)")


def _flag(name: str) -> str:
    """An option's flag as messages name it: ``depth_budget`` -> ``--depth-budget``."""
    return "--" + name.replace("_", "-")


def _explain(points: Sequence[Any], plan: Any) -> None:
    """The phase plan's choices per distinct scenario, as tables on standard error."""
    from rich.console import Console

    from qcpp.cli.commands.compile import explain_table
    from qcpp.plan.qaoa import qaoa_plan

    console = Console(stderr=True)
    seen: set[object] = set()
    for point in points:
        s = point.build_scenario()
        if s in seen:
            continue
        seen.add(s)
        table = explain_table(qaoa_plan(s, 1, plan).phase_plan.explain())  # the phase plan compile would build
        table.title = f"{s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s): {table.title}"
        print_table(console, table)


def _is_terminal(stream: Any) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


def _write_whole(text: str) -> None:
    """Write ``text`` to standard output now, whole even if Ctrl-C or SIGTERM arrives meanwhile: the signals are
    only recorded during the write and raised as ``KeyboardInterrupt`` once the piece is out, so that an
    interrupted stream ends with a complete row. (The CLI's watchdog still ends a write stuck for too long.)"""
    out = sys.stdout
    if threading.current_thread() is not threading.main_thread():  # signal handlers belong to the main thread
        out.write(text)
        out.flush()
        return
    caught: list[int] = []
    stops = (signal.SIGINT, signal.SIGTERM)
    previous = {sig: signal.signal(sig, lambda signum, frame: caught.append(signum)) for sig in stops}
    try:
        out.write(text)
        out.flush()
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    if caught:
        raise KeyboardInterrupt


def register(app: typer.Typer) -> None:
    """Add ``estimate`` to ``app``."""
    app.command("estimate", help=HELP)(estimate)
