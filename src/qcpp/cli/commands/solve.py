"""``qcpp solve``: solve a scenario with one of the registered methods and show the paths.

Examples::

    qcpp solve --grid 3x3 --robots 2 --obstacle 1,1 --method dfs
    qcpp solve examples/two_robots_4x4.toml --method anneal --seed 3 --plot paths.png --plot-trace trace.png
    qcpp solve examples/two_robots_4x4.toml --method qaoa -p 6 --plot-trace trace.png
    qcpp solve examples/two_robots_5x5.toml --method cpsat --json

Methods come from :data:`SOLVE_METHODS` (name -> :class:`qcpp.problem.solvers.SolveMethod`); ``--method``
accepts exactly its keys. Adding a method is one entry: a function
``f(scenario, *, seed, rule, progress) -> qcpp.problem.solvers.Solution`` stored under its name.

``qaoa`` (:mod:`qcpp.training.qaoa_solver`, imported on first use) lives in a higher layer than the classical
solvers, so it is registered here rather than in :data:`qcpp.problem.solvers.SOLVERS`. It alone takes the options of
:data:`QAOA_DEFAULTS` (their help says what they do) and adds the fields of
:func:`qcpp.training.qaoa_solver.qaoa_details` to the JSON and a trace sparkline to the text.

The JSON is ``scenario`` (the file or flags given) followed by
:func:`qcpp.problem.solvers.solution_to_dict` of the answer, which is what ``qcpp.solve(...).to_dict(scenario)``
returns for the same method and options: one builder for both.

``qubo`` (:func:`qcpp.qubo.solve.solve_qubo`) alone takes ``--sampler`` (``tabu``, the default, or ``sa``:
dwave-samplers' tabu search or simulated annealing on the per-robot QUBO).

``cpsat`` (:func:`qcpp.problem.solvers.cpsat`) takes ``--time-limit`` (seconds; default: until the optimum is
proven) and alone ``--workers`` (CP-SAT's threads; default 1, deterministic), and adds ``proven_optimal``, ``bound``,
``gap``, ``relative_gap`` (:func:`qcpp.problem.solvers.cpsat.relative_gap`) and ``status`` to the JSON and a proof
line to the text. ``anneal`` and ``genetic`` take ``--time-limit`` too, and ``--iterations`` / ``--generations``.

A search that stops early (``--time-limit`` on anneal or genetic, or Ctrl-C / SIGTERM on anneal, genetic or cpsat)
answers with the best found so far, marked: ``stopped`` in the JSON (``time limit`` or ``interrupted``) and a line in
the text. Ctrl-C reaches these three solvers as a stop request (:func:`qcpp.cli.interrupt.deferred_stop`): the
answer is printed whole, then ``interrupted`` on stderr and exit 130, as every command ends on a signal; a second
Ctrl-C stops at once. The other methods stop at the first signal with no answer.

``dfs`` predicts its size first (:func:`qcpp.problem.solvers.exhaustive.dfs_paths`: paths per robot, assignments,
memory, time) and refuses a search that would not fit in the available memory or would run for more than
:data:`qcpp.problem.limits.MAX_SECONDS`, in one line naming that size and ``--allow-large``; ``qaoa`` refuses a
subspace simulator that would not fit (:func:`qcpp.simulate.footprint.training_need`). Every method shows progress
on stderr (:mod:`qcpp.cli.progress`).
"""

from __future__ import annotations

import contextlib
import math
import sys
import threading
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from qcpp.cli.commands.inline_scenario import (
    GivenScenario,
    GridFlag,
    HardObstaclesFlag,
    ObstacleFlag,
    RobotCountFlag,
    RobotFlag,
    ScenarioFileArg,
    given_scenario,
)
from qcpp.cli.commands.plan_flags import RuleFlag
from qcpp.cli.interrupt import deferred_stop
from qcpp.cli.progress import Progress
from qcpp.cli.render import check_figure_output, json_text, plot_paths, plot_trace, print_table, render_ascii
from qcpp.estimators.tables import terminal_width
from qcpp.plan.options import INITIAL_STATES
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers import SOLVERS, ProgressFn, Solution, SolveMethod, solution_to_dict
from qcpp.problem.solvers.stopping import TIME_LIMITED
from qcpp.training.objectives import GIBBS_SCALE

if TYPE_CHECKING:
    from qcpp.problem.solvers.cpsat import CpSatResult
    from qcpp.training.qaoa_solver import QaoaSolution

__all__ = [
    "METHOD_HELP",
    "QAOA_DEFAULTS",
    "SOLVE_METHODS",
    "register",
    "solve_command",
    "solve_help",
    "sparkline",
]

QAOA_DEFAULTS = {"p": 1, "optimizer": "layerwise", "objective": "gibbs", "maxiter": 200, "initial": "initial_path",
                 "mixer_warm": False, "restart_every_level": None, "gibbs_scale": GIBBS_SCALE}
"""Defaults of the QAOA-only options (any other value with another method is an error)."""

BASIS_STARTS = ("initial_path", "local_search")
"""Initial states that are one basis state (X gates only), whatever the scenario."""
BASIS_START_NOTE = ("note: g0 has no effect: from a basis-state start the first phase separator is a global "
                    "phase (p counts it as a layer; at p = 1 the state does not depend on the cost)")
"""The line the text output adds after the angles when the initial state is in :data:`BASIS_STARTS`."""


def _qaoa(scenario: Scenario, *, seed: int, rule: str, progress: ProgressFn | None) -> Solution:
    """The ``qaoa`` entry with default settings (``solve_command`` passes its QAOA options itself)."""
    from qcpp.training.qaoa_solver import solve_qaoa

    return solve_qaoa(scenario, seed=seed, rule=rule, progress=progress).solution  # type: ignore[arg-type]


def _qubo(scenario: Scenario, *, seed: int, rule: str, progress: ProgressFn | None) -> Solution:
    """The ``qubo`` entry: tabu search on the per-robot QUBO, decoded, cycles dropped, SBF-polished."""
    from qcpp.qubo.solve import solve_qubo

    return solve_qubo(scenario, seed=seed, rule=rule, progress=progress).solution


SOLVE_METHODS: dict[str, SolveMethod] = {**SOLVERS, "qaoa": _qaoa, "qubo": _qubo}
"""``--method`` name -> solver. Register new methods here (the CLI reads the keys at call time)."""

STOPPED_LINE = {"time limit": "stopped at the time limit", "interrupted": "interrupted"}
"""The text output's words for :attr:`qcpp.problem.solvers.Solution.stopped`."""

_SPARK = "▁▂▃▄▅▆▇█"


SPARK_WIDTH = 60
"""Most bars of the objective's sparkline (a wide terminal gets this many, a narrow one fewer)."""

MIN_SPARK = 5
"""Fewest bars worth drawing: with less room the objective line shows the first and last values only."""


def sparkline(values: Sequence[float], width: int = SPARK_WIDTH) -> str:
    """A one-line bar chart of ``values`` (resampled to at most ``width`` bars; low = short; none for ``width`` < 1).

    Example:
        >>> sparkline([3.0, 2.0, 1.0, 0.0])
        '█▆▃▁'
    """
    if not values or width < 1:
        return ""
    bars = min(width, len(values))
    idx = [round(i * (len(values) - 1) / max(1, bars - 1)) for i in range(bars)]
    pts = [values[i] for i in idx]
    lo, hi = min(pts), max(pts)
    span = hi - lo or 1.0
    return "".join(_SPARK[round((v - lo) / span * (len(_SPARK) - 1))] for v in pts)


def objective_line(objective: str, trace: Sequence[float], width: int) -> str:
    """``<objective> objective per iteration: <first> <sparkline> <last>`` in at most ``width`` characters.

    The two values are kept whole; the sparkline takes the room they leave, up to :data:`SPARK_WIDTH` bars, and is
    left out with less than :data:`MIN_SPARK` (the line is then longer than ``width`` only if the words and the
    two values alone are).

    Args:
        objective: The training objective's name (``gibbs``).
        trace: The objective per iteration, at least one value.
        width: Characters the line may take (the terminal's width).

    Example:
        >>> trace = [3.0 / (1 + i) for i in range(100)]
        >>> objective_line("gibbs", trace, 50)
        'gibbs objective per iteration: 3 █▂▁▁▁▁▁▁▁▁▁▁ 0.03'
        >>> objective_line("gibbs", trace, 40)
        'gibbs objective per iteration: 3 0.03'
    """
    first, last = f"{objective} objective per iteration: {trace[0]:.6g}", f"{trace[-1]:.6g}"
    room = min(SPARK_WIDTH, width - len(first) - len(last) - 2)
    return " ".join([first, *([sparkline(trace, room)] if room >= MIN_SPARK else []), last])


METHOD_HELP = {
    "dfs": "exhaustive search, the exact optimum",
    "cpsat": "OR-Tools CP-SAT: the optimum with a proof (a bound at --time-limit)",
    "anneal": "simulated annealing with SBF moves (the paper's baseline)",
    "genetic": "the paper's genetic algorithm with SBF mutations",
    "qaoa": "QAOA trained on the subspace simulator: its most probable answer",
    "qubo": "tabu search (--sampler sa: annealing) on the QUBO, repaired by SBF moves (extra: annealing)",
}
"""One line per method for ``qcpp solve --help`` (a method registered without one is still listed)."""


def solve_help() -> str:
    """The help text of ``solve``: every method of :data:`SOLVE_METHODS`, described.

    Example:
        >>> all(name in solve_help() for name in SOLVE_METHODS)
        True
    """
    methods = "\n".join(f"  {name} = {METHOD_HELP.get(name, 'see its documentation')}" for name in SOLVE_METHODS)
    return f"""Solve a scenario ({', '.join(SOLVE_METHODS)}) and show the paths, the cost and its parts.

Examples:
  qcpp solve --grid 3x3 --robots 2 --obstacle 1,1 --method dfs
  qcpp solve examples/two_robots_4x4.toml -m anneal --seed 3 --plot paths.png
  qcpp solve examples/two_robots_5x5.toml --method cpsat --json
  qcpp solve examples/paper_3x3.toml --method qaoa -p 2 --plot-trace trace.png

Methods (--method):
{methods}
"""


def _dfs_paths(scenario: Scenario, description: str) -> list[list[int]]:
    """The robots' paths for ``dfs``, after the size prediction (refused over the limits, one line)."""
    from qcpp.problem.limits import OVERRIDE_FLAG
    from qcpp.problem.solvers.exhaustive import DfsTooLargeError, budgeted_dfs_paths

    with Progress(description) as bar:
        bar.stage("counting and enumerating paths")
        try:
            return budgeted_dfs_paths(scenario)
        except DfsTooLargeError as exc:
            raise ValueError(
                f"{exc}; pass {OVERRIDE_FLAG} to run it anyway, or use --method cpsat (exact, with a time limit) "
                "or anneal"
            ) from None


def _qaoa_guard(scenario: Scenario, source: str, description: str, p: int) -> None:
    """Refuse (one line, exit 2) a QAOA training whose subspace simulator would not fit in the available memory
    (:func:`qcpp.simulate.guards.check_training_size`); ``--allow-large`` lifts it."""
    from qcpp.simulate.guards import check_training_size

    with Progress(description) as bar:
        check_training_size(scenario, source, stage=bar.stage, p=p)


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
    scenario: ScenarioFileArg = None,
    method: Annotated[
        str, typer.Option("--method", "-m", help="Solver (see above).")
    ] = "anneal",
    seed: Annotated[int, typer.Option("--seed", help="Random seed (anneal, genetic, qaoa's initial angles).")] = 0,
    rule: RuleFlag = "exact",
    as_json: Annotated[bool, typer.Option("--json", help="Print one JSON object instead of the drawing.")] = False,
    plot: Annotated[
        Path | None, typer.Option("--plot", help="Also draw the paths to this image (PNG, SVG, ...).")
    ] = None,
    plot_trace_file: Annotated[
        Path | None,
        typer.Option("--plot-trace", help="Also plot the cost trace (anneal, genetic: best so far; qaoa: objective)."),
    ] = None,
    p: Annotated[int, typer.Option("-p", "--layers", help="QAOA layers (qaoa).")] = QAOA_DEFAULTS["p"],
    optimizer: Annotated[
        str, typer.Option("--optimizer", help="QAOA training (qaoa): layerwise (L-BFGS-B for p = 1, 2, ... in "
                          "turn, warm-started), multi-angle (one beta per partial mixer and layer, every gamma 0, "
                          "layer by layer from seeded random starts; the JSON adds the circuit's bindings), or one "
                          "nesterov, cobyla or lbfgsb run at depth p.")
    ] = QAOA_DEFAULTS["optimizer"],
    objective: Annotated[
        str, typer.Option("--objective", help="QAOA training objective (qaoa): gibbs, cvar or expectation.")
    ] = QAOA_DEFAULTS["objective"],
    maxiter: Annotated[
        int, typer.Option("--maxiter", help="QAOA optimiser steps / evaluations / iterations per run (qaoa).")
    ] = QAOA_DEFAULTS["maxiter"],
    initial: Annotated[
        str, typer.Option("--initial", help=f"QAOA initial state (qaoa): {', '.join(INITIAL_STATES)} (local_search: "
                          "the paths of a steepest descent over SBF moves; local_search_mix: per robot the initial "
                          "and the descent path in equal superposition).")
    ] = QAOA_DEFAULTS["initial"],
    mixer_warm: Annotated[
        bool, typer.Option("--mixer-warm", help="QAOA layerwise training (qaoa): also start every level from the "
                           "mixer-only warm start (betas trained with every gamma 0, where the state is a product "
                           "over robots).")
    ] = QAOA_DEFAULTS["mixer_warm"],
    restart_every_level: Annotated[
        bool | None, typer.Option("--restart-every-level/--no-restart-every-level", help="QAOA layerwise training "
                                  "(qaoa): also start every level p > 1 from the linear ramp and two random angle "
                                  "sets, not only from the level below.", show_default="on for layerwise")
    ] = QAOA_DEFAULTS["restart_every_level"],
    gibbs_scale: Annotated[
        float, typer.Option("--gibbs-scale", help="QAOA gibbs objective (qaoa): inverse temperature in units of "
                            "1/sigma (sigma: the cost's standard deviation); larger weighs the optimum more.")
    ] = QAOA_DEFAULTS["gibbs_scale"],
    time_limit: Annotated[
        float | None,
        typer.Option("--time-limit", help="Seconds before the search stops with its best so far (cpsat: and a bound "
                     "and gap; anneal, genetic: marked as stopped at the limit).",
                     show_default="cpsat: until proven; anneal, genetic: all their iterations"),
    ] = None,
    workers: Annotated[
        int | None,
        typer.Option("--workers", help="CP-SAT search threads (cpsat). More search in parallel, but the answer and "
                     "the time to it may then differ from run to run; 1 is deterministic.", show_default="1"),
    ] = None,
    iterations: Annotated[
        int | None,
        typer.Option("--iterations", help="Annealing iterations per restart (anneal).", show_default="20000"),
    ] = None,
    generations: Annotated[
        int | None,
        typer.Option("--generations", help="Generations of the genetic algorithm (genetic).", show_default="40"),
    ] = None,
    sampler: Annotated[
        str, typer.Option("--sampler", help="Sampler on the QUBO (qubo): tabu (tabu search, one run per read) or sa "
                          "(simulated annealing, 1,000 sweeps per read); 100 reads either way.")
    ] = "tabu",
    grid: GridFlag = None,
    robots: RobotCountFlag = None,
    robot: RobotFlag = None,
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
) -> None:
    """Solve a scenario (see ``qcpp solve --help``)."""
    qaoa_options = {"p": p, "optimizer": optimizer, "objective": objective, "maxiter": maxiter, "initial": initial,
                    "mixer_warm": mixer_warm, "restart_every_level": restart_every_level, "gibbs_scale": gibbs_scale}
    if method != "qaoa":
        for name, value in qaoa_options.items():
            if value != QAOA_DEFAULTS[name]:
                flag = "-p" if name == "p" else f"--{name.replace('_', '-')}"
                raise ValueError(f"{flag}: applies to --method qaoa only (got --method {method})")
    if method == "qaoa":
        from qcpp.training.objectives import OBJECTIVES

        if objective not in OBJECTIVES:  # before the scenario is loaded, and naming the flag
            raise ValueError(f"--objective: unknown objective {objective!r} (expected one of {', '.join(OBJECTIVES)})")
    if mixer_warm and optimizer != "layerwise":
        raise ValueError(f"--mixer-warm: applies to --optimizer layerwise only (got --optimizer {optimizer})")
    if restart_every_level and optimizer != "layerwise":
        raise ValueError(f"--restart-every-level: applies to --optimizer layerwise only (got --optimizer {optimizer})")
    if not 0 < gibbs_scale < math.inf:
        raise ValueError(f"--gibbs-scale: expected a positive finite number, got {gibbs_scale:g}")
    if gibbs_scale != GIBBS_SCALE and objective != "gibbs":
        raise ValueError(f"--gibbs-scale: applies to --objective gibbs only (got --objective {objective})")
    if time_limit is not None and method not in TIME_LIMITED:
        methods = ", ".join(TIME_LIMITED[:-1]) + f" or {TIME_LIMITED[-1]}"
        raise ValueError(f"--time-limit: applies to --method {methods} only (got --method {method})")
    if time_limit is not None and not 0 < time_limit < math.inf:
        raise ValueError(f"--time-limit: expected a positive number of seconds, got {time_limit:g}")
    for flag, value, owner in (("--workers", workers, "cpsat"), ("--iterations", iterations, "anneal"),
                               ("--generations", generations, "genetic")):  # fmt: skip
        if value is not None and method != owner:
            raise ValueError(f"{flag}: applies to --method {owner} only (got --method {method})")
        if value is not None and value < 1:
            raise ValueError(f"{flag}: expected a positive integer, got {value}")
    if sampler != "tabu" and method != "qubo":
        raise ValueError(f"--sampler: applies to --method qubo only (got --method {method})")
    if method == "qubo":
        from qcpp.qubo.solve import SAMPLERS

        if sampler not in SAMPLERS:  # before the scenario is loaded, and naming the flag
            raise ValueError(f"--sampler: unknown sampler {sampler!r} (expected one of tabu, sa)")
    for out in (plot, plot_trace_file):
        if out is not None:
            check_figure_output(out)  # a bad destination or image type fails before solving, not after
    given = given_scenario(scenario, grid, robots, obstacle, hard_obstacles, phases=method == "qaoa", endpoints=robot)
    s = given.scenario
    qaoa = None
    exact = None
    description = f"{method} on {given.label}"
    if method == "qaoa":
        _qaoa_guard(s, given.source, description, p)
    dfs_lists = _dfs_paths(s, description) if method == "dfs" and SOLVE_METHODS["dfs"] is SOLVERS["dfs"] else None
    unit = {"dfs": "assignments", "cpsat": "improving solutions"}.get(method, "steps")
    stoppable = method in TIME_LIMITED and SOLVE_METHODS[method] is SOLVERS[method]
    # the stoppable solvers take the first Ctrl-C as a request and answer with their best so far: the block
    # covers the answer's output too, so that it is printed whole before the command ends as interrupted
    with deferred_stop() if stoppable else contextlib.nullcontext(threading.Event()) as stopped:
        with Progress(description, unit=unit, deadline=time_limit) as bar:  # the time left ends at the limit
            progress = bar.update  # a qcpp.problem.solvers.ProgressFn; stdout stays clean for --json
            if stoppable:
                sol, exact = _stoppable(s, method, seed, rule, progress, stopped.is_set, time_limit,
                                        {"workers": workers, "iterations": iterations, "generations": generations})
            else:
                sol, qaoa = _unstoppable(s, method, seed, rule, progress, dfs_lists, sampler, qaoa_options)
        _finish(s, sol, method, qaoa, exact, objective, as_json, given, plot, plot_trace_file, p, optimizer)
    if stopped.is_set():
        raise KeyboardInterrupt  # the answer is out: end as every interrupted command (``interrupted``, 130)


def _stoppable(s: Scenario, method: str, seed: int, rule: str, progress: ProgressFn, stop: Callable[[], bool],
               time_limit: float | None,
               options: dict[str, int | None]) -> tuple[Solution, CpSatResult | None]:  # fmt: skip
    """Run cpsat, anneal or genetic with the stop request and the options given (``None``: the solver's default)."""
    given = {name: value for name, value in options.items() if value is not None}
    if method == "cpsat":
        from qcpp.problem.solvers import cpsat

        exact = cpsat(s, seed=seed, time_limit=time_limit, progress=progress, stop=stop, **given)
        return exact.solution, exact
    solver = SOLVERS[method]
    return solver(s, seed=seed, rule=rule, progress=progress, time_limit=time_limit, stop=stop,  # type: ignore[call-arg]
                  **given), None  # fmt: skip


def _unstoppable(s: Scenario, method: str, seed: int, rule: str, progress: ProgressFn,
                 dfs_lists: list[list[int]] | None, sampler: str,
                 qaoa_options: dict[str, object]) -> tuple[Solution, QaoaSolution | None]:  # fmt: skip
    """Run dfs, qaoa, qubo or a registered method (a signal stops them with no answer)."""
    if dfs_lists is not None:
        from qcpp.problem.solvers.exhaustive import dfs

        return dfs(s, progress=progress, paths=dfs_lists), None
    if method == "qaoa":
        from qcpp.training.qaoa_solver import solve_qaoa

        qaoa = solve_qaoa(s, seed=seed, rule=rule, progress=progress, **qaoa_options)  # type: ignore[arg-type]
        return qaoa.solution, qaoa
    if method == "qubo" and SOLVE_METHODS["qubo"] is _qubo:
        from qcpp.qubo.solve import solve_qubo

        return solve_qubo(s, sampler=sampler, seed=seed, rule=rule, progress=progress).solution, None  # type: ignore[arg-type]
    return SOLVE_METHODS[method](s, seed=seed, rule=rule, progress=progress), None  # type: ignore[arg-type]


def _finish(s: Scenario, sol: Solution, method: str, qaoa: QaoaSolution | None, exact: CpSatResult | None,
            objective: str, as_json: bool, given: GivenScenario, plot: Path | None, plot_trace_file: Path | None,
            p: int, optimizer: str) -> None:  # fmt: skip
    """Print the answer, then write the plots asked for."""
    if plot_trace_file is not None and not sol.trace:
        raise ValueError(f"--plot-trace: method {method!r} has no cost trace")
    _print_result(s, sol, method, qaoa, exact, objective, as_json, given.source)
    # the plots last: a plot that cannot be written (a full disk) leaves the printed result standing
    if plot is not None:
        plot_paths(s, sol.paths, plot, title=f"{s.name or given.label}: {method}, cost {sol.cost.total:g}")
        typer.echo(f"wrote {plot}", err=True)
    if plot_trace_file is not None:
        if qaoa is not None:
            # the training objective per iteration (in units of cost), drawn as a line
            plot_trace(qaoa.trace, plot_trace_file, optimum=qaoa.optimum, label=f"{objective} objective",
                       title=f"qaoa p={p} ({optimizer}, {objective}) on {s.name or given.label}",
                       xlabel="training iteration", steps=False)
        else:
            unit = "generation" if method == "genetic" else "iteration"
            plot_trace(sol.trace, plot_trace_file, title=f"{method}: best cost so far", xlabel=unit)
        typer.echo(f"wrote {plot_trace_file}", err=True)


def _print_result(s: Scenario, sol: Solution, method: str, qaoa: QaoaSolution | None, exact: CpSatResult | None,
                  objective: str, as_json: bool, source: str) -> None:  # fmt: skip
    """The solution on standard output: one JSON object, or the drawing, the cost table and the details."""
    if as_json:
        # the method's own fields (cpsat's proof, qaoa's training) ride in sol.details: qcpp.solve's to_dict is this
        typer.echo(json_text({"scenario": source, **solution_to_dict(s, sol)}))
        sys.stdout.flush()
        return
    console = Console()
    console.print(render_ascii(s, sol.paths), markup=False, highlight=False)
    console.print()
    print_table(console, _cost_table(s, sol))
    details = [f"method {method}", f"{sol.seconds:.3f} s", f"{sol.evaluated:,} assignments scored"]
    if sol.paths_per_robot:
        details.append("paths per robot " + " x ".join(f"{n:,}" for n in sol.paths_per_robot))
    if sol.seed is not None:
        details.append(f"seed {sol.seed}")
    if sol.rule is not None:
        details.append(f"rule {sol.rule}")
    console.print(", ".join(details), highlight=False)
    if qaoa is not None:
        # two short lines, each wrapped at spaces to the terminal's width like the notes
        console.print(f"most probable assignment (drawn above): probability {qaoa.probability:.4g}", highlight=False)
        console.print(f"probability of an optimal assignment: {qaoa.p_optimum:.4g}", highlight=False)
        console.print(objective_line(objective, qaoa.trace, terminal_width()), highlight=False, soft_wrap=True)
        console.print("angles [g0, b0, ...]: " + ", ".join(f"{a:.4f}" for a in qaoa.angles), markup=False,
                      highlight=False, soft_wrap=True)
        if qaoa.initial in BASIS_STARTS:
            console.print(BASIS_START_NOTE, markup=False, highlight=False)
    if exact is not None:
        verdict = "proven optimal" if exact.proven_optimal else f"not proven: bound {exact.bound:g}, gap {exact.gap:g}"
        if not exact.proven_optimal and math.isfinite(exact.bound):
            # OR-Tools' relative gap: (cost - bound) / max(1, |cost|)
            verdict += f" = {100 * exact.relative_gap:.3g}% of |cost|"
        console.print(f"cpsat: {verdict} ({exact.status})", highlight=False)
    if sol.stopped is not None:
        console.print(f"{method}: {STOPPED_LINE.get(sol.stopped, sol.stopped)}: the best found so far, not proven "
                      "optimal", highlight=False)
    for note in sol.notes:
        console.print(f"[dim]note: {escape(note)}[/dim]", highlight=False)  # wrapped at spaces to the width
    sys.stdout.flush()


def register(app: typer.Typer) -> None:
    """Add ``solve`` to ``app``."""
    app.command("solve", help=solve_help())(solve_command)
