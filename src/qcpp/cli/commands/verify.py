"""``qcpp verify``: does the compiled circuit keep every feasible path feasible? (see :mod:`qcpp.verification`).

Examples::

    qcpp verify examples/paper_3x3.toml -p 2
    qcpp verify examples/paper_3x3.toml -p 1 --rule paper --json
    qcpp verify big.toml -p 3 --method gadgets
    qcpp verify --grid 4x4 --robots 3 --target ft

Exit code 0 when feasibility preservation holds, 1 with a counterexample (printed: the input path(s) and the
output, each robot's edges after ``robot k:``, the gadget, its plaquette and its local picture's corner letters in
words; then the input and the output drawn on the grid as ``qcpp solve`` draws paths), 2 on bad input (one line on
stderr), 3 when the gadget method could neither certify nor refute (``not_certified``: only local inputs no
feasible path was shown to contain; the first is printed, and drawn, with whether ``--method state`` can decide on
this field). 3 is not 0 because nothing was certified, and not 1 because
nothing was refuted: a script can tell "broken" from "undecided". The text report fits the terminal's width
(``$COLUMNS``, else the terminal's, else 80, as for the other commands' tables); ``--json`` prints
:meth:`qcpp.verification.VerifyReport.to_dict` on stdout, every field whole. Progress goes to stderr
(:mod:`qcpp.cli.progress`): checks (gadget method) or inputs run (state method) of the total, without a time
left, since one check or input can cost a hundred times another (the state method's mixer inputs against its
phase inputs).
"""

from __future__ import annotations

import shutil
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
from qcpp.cli.commands.plan_flags import LayersFlag, RuleFlag, TargetFlag
from qcpp.cli.progress import Progress
from qcpp.cli.render import json_text, render_ascii
from qcpp.problem.scenario import Scenario
from qcpp.verification.report import Counterexample

__all__ = ["drawn_counterexample", "register", "verify_command"]

HELP = """Check that the compiled circuit keeps every feasible path feasible (clean ancillas).

Examples:
  qcpp verify examples/paper_3x3.toml -p 2
  qcpp verify --grid 3x4 --robots 2 --obstacle 1,1 --samples 200 --json
  qcpp verify examples/two_robots_5x5.toml -p 3 --method gadgets
  qcpp verify --grid 4x4 --robots 3 --target ft

Methods: state = run the lowered circuit on every feasible input (or a
sample); gadgets = every gadget kind on all its local inputs (any size).
Exit 0: holds; 1: a counterexample; 2: bad input; 3: not certified (the
gadget method found only local inputs it could not place on a feasible
path: no proof and no counterexample; --method state decides on a field it
can enumerate). 3 is nonzero because nothing was certified, and distinct
from 1 so a script can tell a broken circuit from an undecided one.
"""


def verify_command(
    scenario: ScenarioFileArg = None,
    p: LayersFlag = 1,
    rule: RuleFlag = "exact",
    target: TargetFlag = "nisq",
    method: Annotated[str, typer.Option("--method", help="state, gadgets or auto.")] = "auto",
    samples: Annotated[
        int, typer.Option("--samples", help="state: most feasible inputs per part; a seeded sample beyond.")
    ] = 2000,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the angles and of the sample.")] = 0,
    as_json: Annotated[bool, typer.Option("--json", help="Print a JSON object instead of text.")] = False,
    grid: GridFlag = None,
    robots: RobotCountFlag = None,
    robot: RobotFlag = None,
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
) -> None:
    """Verify feasibility preservation (see ``qcpp verify --help``)."""
    from qcpp.plan.options import PlanOptions
    from qcpp.verification import choose_method, resolve_method, verify

    options = PlanOptions(rule=rule, target=target)  # type: ignore[arg-type]
    given = given_scenario(scenario, grid, robots, obstacle, hard_obstacles, endpoints=robot)
    s = given.scenario
    method = resolve_method(s, p, rule, method, samples, options)  # type: ignore[arg-type]
    unit = "inputs" if method == "state" else "checks"  # what progress counts
    with Progress(f"verify {given.label}", unit=unit, time_left=False) as bar:
        report = verify(s, p, rule, method, samples, seed, progress=bar.update, options=options)  # type: ignore[arg-type]
    undecided = report.outcome == "not_certified"
    if as_json:
        typer.echo(json_text(report.to_dict()))
    else:
        width = shutil.get_terminal_size((80, 24)).columns
        typer.echo(report.summary(width))
        shown = report.counterexample or report.unresolved
        drawing = drawn_counterexample(s, shown, width) if shown is not None else None
        if drawing:
            typer.echo(drawing)
        if undecided:
            fits = choose_method(s, p, options, samples) == "state"
            typer.echo(echo_wrap(
                "This field fits --method state: rerun with --method state to decide."
                if fits else
                "This field is too large for --method state (more than 62 qubits or more than --samples feasible "
                "assignments): a smaller field with the same rule and endpoint pictures can be decided instead.",
                width,
            ))  # fmt: skip
    if not report.holds:
        raise typer.Exit(code=3 if undecided else 1)


def drawn_counterexample(scenario: Scenario, cx: Counterexample, width: int) -> str | None:
    """The counterexample's input and output drawn on the grid, as ``qcpp solve`` draws paths
    (:func:`qcpp.cli.render.render_ascii`: ``-k-`` / ``k`` an edge of robot ``k``; its legend after the input, with
    each robot's input edge count).

    Returns:
        The text, or ``None`` where there is nothing to draw (no edges: a phase gadget's input) or the grid is wider
        than ``width`` (the report says every edge in words anyway). The legend is left out where it is wider.

    Example:
        >>> from qcpp.problem.presets import grid_scenario
        >>> s = grid_scenario(2, 2, robots=[((0, 0), (1, 1))])
        >>> cx = Counterexample("state", "mixer_0", None, 0, None, ((((0, 0), (0, 1)), ((0, 1), (1, 1))),),
        ...                     ((((0, 0), (1, 0)),),), (), 1.0, "robot 0's path leaves the feasible set")
        >>> print(drawn_counterexample(s, cx, 80).splitlines()[:4])
        ['input, drawn:', '  S-0-o', '      0', '  .   G']
    """
    grid = scenario.grid
    if 4 * (grid.cols - 1) + 3 > width:
        return None
    drawings = []
    for name, paths in (("input", cx.input_paths), ("output", cx.output_paths)):
        masks = [0] * scenario.num_robots
        for robot, edges in zip(cx.path_robots(paths), paths, strict=True):
            if robot is None or not 0 <= robot < scenario.num_robots:
                continue
            for u, v in edges:
                masks[robot] |= 1 << grid.edge_index(tuple(u), tuple(v))  # type: ignore[arg-type]
        if not any(masks):
            continue
        lines = render_ascii(scenario, masks, legend=name == "input").splitlines()
        if max(map(len, lines)) + 2 > width:  # the legend's long lines: left out on a narrow terminal
            lines = render_ascii(scenario, masks, legend=False).splitlines()
        drawings += [f"{name}, drawn:", *(f"  {line}" if line else "" for line in lines)]
    return "\n".join(drawings) or None


def echo_wrap(text: str, width: int) -> str:
    """``text`` wrapped at spaces to ``width`` (at least 40) columns."""
    import textwrap

    return "\n".join(textwrap.wrap(text, max(width, 40), break_long_words=False, break_on_hyphens=False))


def register(app: typer.Typer) -> None:
    """Add ``verify`` to ``app``."""
    app.command("verify", help=HELP)(verify_command)
