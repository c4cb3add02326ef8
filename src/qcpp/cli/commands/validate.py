"""``qcpp validate``: check a compiled, lowered QAOA circuit against the exact feasible-subspace simulator.

Examples::

    qcpp validate examples/paper_3x3.toml -p 2 --backend tensor
    qcpp validate examples/two_robots_4x4.toml -p 1 --backend sparse --json
    qcpp validate examples/paper_3x3.toml -p 2 --backend qcec
    qcpp validate examples/two_robots_4x4.toml -p 2 --dask tcp://scheduler:8786

The default backend is ``auto``: the one that fits (:func:`qcpp.simulate.validate.choose_backend`: the dense statevector
up to 20 qubits, else the sparse state). The size (feasible assignments, the reference state's size) is predicted
first (:func:`qcpp.simulate.footprint.validate_need`: peak memory and time) and a validation that would not fit in
the available memory or would run for hours is refused in one line naming the prediction, the limit and
``--allow-large`` (:func:`qcpp.problem.limits.check_need`). The stages show as progress on stderr
(:mod:`qcpp.cli.progress`).

Exit code 0 (``PASSED``) only when every check ran and passed; 1 when a check failed (``FAILED``) or could not
run (``INCOMPLETE``, e.g. a tensor contraction too wide: a check that did not run never reports PASSED); bad
input is one line on stderr and exit code 2 (the CLI's shared handler). ``--json`` prints
:meth:`~qcpp.simulate.validate.ValidationReport.to_dict`, the object :func:`qcpp.validate` returns: its ``verdict``
(``passed``, ``failed`` or ``incomplete``) decides the exit code, and ``passed`` is true only for ``passed``.
"""

from __future__ import annotations

from typing import Annotated

import typer
from rich.console import Console
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
from qcpp.cli.commands.plan_flags import LayersFlag, check_start, plan_flag_message, with_plan_flags
from qcpp.cli.commands.simulate import parse_angles
from qcpp.cli.progress import Progress
from qcpp.cli.render import json_text, print_table
from qcpp.errors import OptionError
from qcpp.plan.options import PlanOptions

__all__ = ["register", "validate_command"]

HELP = """Run the compiled, lowered circuit and compare it with the exact subspace simulator.

Examples:
  qcpp validate examples/paper_3x3.toml -p 2 --backend tensor
  qcpp validate --grid 2x3 --robots 2 --json
  qcpp validate examples/paper_3x3.toml --backend qcec

Checks that the ancillas end in |0> and every feasible amplitude matches;
the plan flags are those of compile and estimate (not --mixer-angles multi);
qcec proves the lowered circuit equal to the high-level one (MQT QCEC).
Exit 0: every check ran and passed; 1: one failed or was skipped.
"""


@with_plan_flags
def validate_command(
    options: PlanOptions,
    scenario: ScenarioFileArg = None,
    p: LayersFlag = 1,
    backend: Annotated[
        str,
        typer.Option("--backend", help="auto (what fits: statevector or sparse), tensor, statevector, sparse or qcec."),
    ] = "auto",
    angle_values: Annotated[
        str | None, typer.Option("--angles", help="g0,b0,g1,b1,... (default: seeded random angles).")
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the random angles and the amplitude sample.")] = 0,
    max_amplitudes: Annotated[
        int,
        typer.Option("--max-amplitudes", help="tensor: contract at most this many amplitudes exactly (at least 1)."),
    ] = 256,
    as_json: Annotated[bool, typer.Option("--json", help="Print a JSON object instead of a table.")] = False,
    dask: Annotated[
        str | None,
        typer.Option(
            "--dask",
            help="tensor: run sliced wide contractions on a dask cluster: a scheduler address "
            "(tcp://host:8786) or 'local' for a LocalCluster on this machine. Default: in-process.",
        ),
    ] = None,
    grid: GridFlag = None,
    robots: RobotCountFlag = None,
    robot: RobotFlag = None,
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
) -> None:
    """Validate a compiled circuit (see ``qcpp validate --help``)."""
    from qcpp.problem.limits import check_need, large_allowed
    from qcpp.simulate.cluster import check_dask_address
    from qcpp.simulate.footprint import validate_need
    from qcpp.simulate.validate import check_validatable, validate

    try:
        check_validatable(options)
    except OptionError as exc:
        raise ValueError(plan_flag_message(exc)) from None
    if dask is not None and backend == "auto":
        backend = "tensor"  # only the tensor backend contracts on a cluster: asking for one picks it
    if dask is not None and backend != "tensor":
        raise ValueError(f"--dask: only the tensor backend uses a dask cluster, got --backend {backend}")
    if dask is not None:
        check_dask_address(dask, "--dask")
    values = None
    if angle_values is not None:
        values = parse_angles(angle_values)
        if len(values) != 2 * p:
            raise ValueError(f"--angles: p = {p} needs {2 * p} angles (g0,b0,...), got {len(values)}")
    if backend == "qcec":
        try:
            import mqt.qcec  # noqa: F401
            import qiskit  # noqa: F401
        except ImportError as exc:
            raise ValueError(f"--backend qcec needs mqt.qcec and qiskit (pip install 'qcpp[test]'): {exc}") from None
    given = given_scenario(scenario, grid, robots, obstacle, hard_obstacles, phases=True, endpoints=robot)
    s = given.scenario
    check_start(s, options)
    with Progress(f"validate {given.label}") as bar:
        if not large_allowed():
            bar.stage("predicting the size")
            check_need(validate_need(s), field=given.source)
        report = validate(
            s,
            p,
            backend=backend,  # type: ignore[arg-type]
            angles=values,
            seed=seed,
            options=options,
            max_amplitudes=max_amplitudes,
            dask=dask,
            max_assignments=None,  # checked above, from the memory and time it would take
            max_bytes=None,
            stage=bar.stage,
        )
    chosen = f"{report.backend} (auto)" if backend == "auto" else report.backend  # said in the table's title
    backend = report.backend
    skipped = [c.name for c in report.checks if c.status == "skipped"]
    verdict = report.verdict
    if as_json:
        typer.echo(json_text(report.to_dict()))
    else:
        plan = "".join(f", {k}={v}" for k, v in report.plan.items())  # the plan options that are not the default
        table = Table(
            title=f"{given.label}: p={p}{plan}, backend={chosen}, {report.qubits} qubits, {report.gates} gates"
        )
        for col in ("check", "method", "value", "error", "count", "status", "seconds"):
            table.add_column(col, justify="left" if col in ("check", "method", "status") else "right")
        for c in report.checks:
            colour = {"pass": "green", "fail": "red"}.get(c.status, "yellow")
            table.add_row(
                c.name, c.method, f"{c.value:.3g}", f"{c.error:.2g}", str(c.count),
                f"[{colour}]{c.status}", f"{c.seconds:.2f}",
            )
        console = Console()
        print_table(console, table)
        for c in report.checks:
            if c.note:
                console.print(f"{c.name} ({c.method}): {c.note}", markup=False, soft_wrap=True)
        detail = f" ({len(skipped)} check(s) skipped: {', '.join(skipped)})" if skipped else ""
        if backend == "qcec":  # a decision procedure: no amplitudes compared, so no tolerance to claim
            scope = "lowered == high level on every input with clean ancillas, decided exactly by QCEC"
        else:
            scope = f"{report.feasible_assignments} feasible assignments, tolerance {report.tolerance:g}"
        console.print(f"{verdict.upper()}{detail}: {scope}, {report.seconds:.1f} s", markup=False)
    if verdict != "passed":
        raise typer.Exit(code=1)


def register(app: typer.Typer) -> None:
    """Add ``validate`` to ``app``."""
    app.command("validate", help=HELP)(validate_command)
