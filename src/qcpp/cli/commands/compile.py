"""``qcpp compile``: build the QAOA circuit of a scenario and write it as OpenQASM 2 or 3.

Examples::

    qcpp compile examples/paper_3x3.toml -p 1 --qasm out.qasm3 --qasm-version 3
    qcpp compile --grid 10x10 --robots 2 --obstacle 4,4 --obstacle 5,6 --lowered --json
    qcpp compile examples/paper_3x3.toml -p 1 --lowered --bind gamma_0=0.3 beta_0=0.7 --qasm out.qasm
    qcpp compile examples/paper_3x3.toml --qasm - > out.qasm3      # OpenQASM on stdout, the summary on stderr
    qcpp compile examples/paper_3x3.toml --qasm out.qasm3 --qasm-profile portable   # for Braket, PennyLane
    qcpp compile --grid 2x3 --robots 1 --device ibm_fez --bind gamma_0=0.3 beta_0=0.7 --qasm fez.qasm --measure

Output files follow :mod:`qcpp.io.atomic`: written whole or not at all, symlinks followed, devices and FIFOs
written straight to, a missing folder is an error (checked before compiling).

Library errors (bad scenario, unbound symbols for OpenQASM 2, unwritable file) surface through the CLI's shared
handler as one line on stderr and exit code 2.

Writing ``--qasm`` streams: the circuit is built, lowered, bound and written one section of its plan at a time
(:func:`qcpp.lowering.qasm_stream.write_qasm_sections`), so peak memory does not grow with ``p``; the file is the
same, byte for byte, as writing the whole circuit.

Size guard: before building anything, the lowered circuit's gate count is predicted from the plan's gadget
costs (:func:`qcpp.estimators.guard.predict_size`, exact, without building a gate) and with it the peak memory
and time (:func:`qcpp.estimators.guard.compile_need`); a compile that would not fit in the available memory or
would run for more than an hour is refused with one line naming the prediction, the limit and the override
(``--force``), exit 2. ``--max-gates N`` refuses circuits over ``N`` lowered gates instead. ``--allow-large``
lifts the grid and layer limits only (grids over 50x50, ``p`` over 1000): a large grid is still refused when its
compile would not fit or would run for hours, so asking for a big field never starts an unbounded run by
accident. In text mode a compile predicted to run for more than :data:`NOTE_ABOVE_SECONDS` says so first, on
stderr (the predicted time and peak memory).

Progress: a circuit predicted at :data:`STREAM_ABOVE_GATES` lowered gates or more, and every ``--qasm`` write, is
built section by section with progress on stderr (:mod:`qcpp.cli.progress`: gates handed out of the predicted total;
writing OpenQASM takes two passes over the sections, each counting the circuit's gates from 0; the time left only
when no OpenQASM is written, as writing costs per gate vary too much to extrapolate).
"""

from __future__ import annotations

import contextlib
import math
import time
from collections import Counter
from collections.abc import Iterable, Iterator
from typing import Annotated, Any

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
    check_inline_only,
    given_scenario,
)
from qcpp.cli.commands.plan_flags import LayersFlag, check_start, with_plan_flags
from qcpp.cli.progress import Progress
from qcpp.cli.render import echo_note, json_text, print_table
from qcpp.estimators.guard import SizePrediction, check_size, compile_need, predict_size
from qcpp.estimators.tables import from_log
from qcpp.hardware.device import device_arg, device_names
from qcpp.io.atomic import check_output, is_stdout
from qcpp.ir.angles import UnboundParameterError, symbol_sort_key
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.lowering.qasm_profiles import ZERO_START_NOTE, Profile, check_profile, write_qasm_profile
from qcpp.lowering.qasm_stream import write_qasm_sections
from qcpp.plan.compile import check_binding_values, compile_scenario, compile_summary, parse_bindings
from qcpp.plan.options import PlanOptions
from qcpp.problem.limits import allow_large as lifted_limits
from qcpp.problem.limits import format_duration
from qcpp.problem.scenario import Scenario
from qcpp.routing.native import RUNNABLE_ESP
from qcpp.routing.options import effort_routing

__all__ = ["STREAM_ABOVE_GATES", "compile_command", "register"]

NOTE_ABOVE_SECONDS = 60.0
"""A compile predicted to run longer than this prints its prediction (time, peak memory) before the work."""

LAYOUT_SHOWN = 32
"""Layouts of at most this many logical qubits are printed in the text output (all of them are in ``--json``)."""

STREAM_ABOVE_GATES = 100_000
"""Circuits predicted to have at least this many lowered gates are built section by section with progress on
stderr (a compile long enough to want it), even without ``--qasm``; smaller ones are built whole."""

HELP = """Compile a scenario's QAOA circuit; lower it, bind angles, route it, write OpenQASM.

Examples:
  qcpp compile examples/paper_3x3.toml -p 2 --lowered --qasm out.qasm
  qcpp compile --grid 5x5 --robots 2 --obstacle 2,1 --json
  qcpp compile examples/paper_3x3.toml --bind gamma_0=0.3 beta_0=0.7 --qasm -
  qcpp compile examples/paper_3x3.toml --device heavy-hex --qasm routed.qasm

Files are written whole or not at all.
"""


@with_plan_flags
def compile_command(
    options: PlanOptions,
    scenario: ScenarioFileArg = None,
    assignments: Annotated[
        list[str] | None, typer.Argument(help="More NAME=VALUE bindings following --bind.", show_default=False)
    ] = None,
    p: LayersFlag = 1,
    lowered: Annotated[bool, typer.Option("--lowered", help="Lower to {cx, x, h, rz, t, tdg, s, sdg}.")] = False,
    bind: Annotated[
        list[str] | None, typer.Option("--bind", help="NAME=VALUE (repeat, or list several after one --bind).")
    ] = None,
    qasm: Annotated[
        str | None, typer.Option("--qasm", help="Write OpenQASM to this file (- for standard output).")
    ] = None,
    qasm_version: Annotated[
        int | None, typer.Option("--qasm-version", help="OpenQASM version: 2 or 3 (default 3).", show_default=False)
    ] = None,
    qasm_profile: Annotated[
        str,
        typer.Option(
            "--qasm-profile",
            help="OpenQASM 3 export profile: default (include stdgates.inc and qcpp's gate definitions; Qiskit, "
            "Cirq, the QDK), portable (no include, no gate definitions: Amazon Braket's local simulator, PennyLane's "
            "from_qasm3) or braket (Braket's native gate names). Same unitary in each.",
        ),
    ] = "default",
    measure: Annotated[
        bool,
        typer.Option(
            "--measure",
            help="With --qasm: also measure every data qubit at the end into a classical register meas (data qubit "
            "i into meas[i]; with --device from its physical qubit at the end, final_layout[i]).",
        ),
    ] = False,
    explain: Annotated[
        bool, typer.Option("--explain", help="Show which phase construction was chosen per term group, and why.")
    ] = False,
    as_json: Annotated[bool, typer.Option("--json", help="Print a JSON object instead of a table.")] = False,
    max_gates: Annotated[
        int | None,
        typer.Option(
            "--max-gates",
            help="Refuse circuits predicted to exceed this many lowered gates (default: refuse only what would not "
            "fit in the available memory or would run for more than an hour).",
            min=0,
            show_default=False,
        ),
    ] = None,
    force: Annotated[
        bool,
        typer.Option(
            "--force",
            help="Build even past --max-gates or the size guard (predicted over the available memory or an hour).",
        ),
    ] = False,
    allow_large: Annotated[
        bool,
        typer.Option(
            "--allow-large",
            help="Lift the grid and layer limits (grids over 50x50, p over 1000); the size guard (memory, an hour) "
            "still holds: --force lifts it.",
        ),
    ] = False,
    device: Annotated[
        str | None,
        typer.Option(
            "--device",
            help="Route onto grid[:RxC], heavy-hex[:D], all-to-all[:N] (no size: the smallest that fits), a "
            f"named device ({', '.join(device_names())}) or a device file (PATH.json; the format: the hardware "
            "guide); the circuit's qubits are then the device's, its gates native.",
        ),
    ] = None,
    local_ancillas: Annotated[
        bool, typer.Option("--local-ancillas", help="With --device: give gadgets region-local ancillas (greedy).")
    ] = False,
    layout: Annotated[
        str,
        typer.Option(
            "--layout",
            help="With --device: medial (the geometric layout, every gadget routed home; on ibm_fez and "
            "ibm_torino the heavy-hex cells routed on heavy-hex:D and placed where they embed), greedy (one SABRE "
            "routing of the whole circuit) or auto (medial where it fits and routes cheaper).",
        ),
    ] = "auto",
    optimize_for: Annotated[
        str | None,
        typer.Option(
            "--optimize-for",
            help="With --device: the figure the routing is chosen by on a named device, esp (success probability "
            "with idle decoherence; the default there) or twoq (fewest two-qubit gates); the candidates are qcpp's "
            "own routings (as written and after Qiskit's O3 optimisation at their layout), Qiskit O3 on the "
            "calibrated target, and all of these moved onto the best-calibrated qubits; on IBM devices also the "
            "heavy-hex cells routed on heavy-hex:D, placed where they embed. The families (grid, "
            "heavy-hex, all-to-all) keep their single routing.",
            show_default=False,
        ),
    ] = None,
    zero_start: Annotated[
        bool,
        typer.Option(
            "--zero-start",
            help="On a named device, also offer routings simplified for the all-|0> start the device runs from; the "
            "circuit then equals the logical one only on that input: put no gates before it.",
        ),
    ] = False,
    effort: Annotated[
        str,
        typer.Option(
            "--effort",
            help="With --device: full (every search) or quick (no choice of partial-mixer plans for the routing: a "
            "few times faster on a named device, for more two-qubit gates).",
        ),
    ] = "full",
    grid: GridFlag = None,
    robots: RobotCountFlag = None,
    robot: RobotFlag = None,
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
) -> None:
    """Compile a scenario (see ``qcpp compile --help``)."""
    check_inline_only(grid, robots, obstacle, hard_obstacles, robot)
    extra = list(assignments or [])
    if grid is not None and scenario is not None and bind and "=" in str(scenario):
        extra.insert(0, str(scenario))  # NAME=VALUE after --bind, taken for the (absent) file argument
        scenario = None
    del allow_large  # read by the CLI's handler (qcpp.cli.app.handle_errors): the grid and layer limits only
    if (grid is None) == (scenario is None):
        # raises: names what is missing or extra
        given_scenario(scenario, grid, robots, obstacle, hard_obstacles, endpoints=robot)
    if device is None:  # routing flags without a device are refused, not silently ignored
        if layout != "auto":
            raise ValueError(f"--layout {layout}: applies with --device only (no device given)")
        if local_ancillas:
            raise ValueError("--local-ancillas: applies with --device only (no device given)")
        if optimize_for is not None:
            raise ValueError(f"--optimize-for {optimize_for}: applies with --device only (no device given)")
    if device is None and effort != "full":
        raise ValueError(f"--effort {effort}: applies with --device only (no device given)")
    if zero_start:
        from qcpp.pipeline.candidates import zero_start_refusal

        refusal = zero_start_refusal(device, lowered, "--lowered")
        if refusal is not None:
            raise ValueError(f"--zero-start: {refusal.replace('named device only', 'named --device only')}")
    if extra and not bind:
        raise ValueError(f"unexpected argument {extra[0]!r} (bindings go after --bind)")
    bindings = check_binding_values(parse_bindings([*(bind or []), *extra]))
    if qasm is None:  # the OpenQASM flags without --qasm are refused, not silently ignored
        qasm_only = {"--qasm-version": qasm_version is not None, "--qasm-profile": qasm_profile != "default",
                     "--measure": measure}  # fmt: skip
        for flag, given_flag in qasm_only.items():
            if given_flag:
                raise ValueError(f"{flag}: applies with --qasm only (no --qasm given)")
    qasm_version = 3 if qasm_version is None else qasm_version
    check_profile(qasm_profile, qasm_version, "--qasm-profile", "--qasm-version")
    to_stdout = qasm is not None and is_stdout(qasm)  # -, /dev/stdout, ...: stdout holds the text only
    if to_stdout and as_json:
        raise ValueError(f"--qasm {qasm} and --json both write to standard output; choose one")
    if qasm is not None:
        check_output(qasm)  # a bad destination fails before the compile, not after
    given = given_scenario(scenario, grid, robots, obstacle, hard_obstacles, endpoints=robot)
    s, label = given.scenario, given.label
    check_start(s, options)
    streamed = device is None and (qasm is not None or predict_size(s, p, options).gates >= STREAM_ABOVE_GATES)
    size = _guard(s, p, options, max_gates, force, streamed=streamed)
    need = compile_need(s, p, options, streamed=streamed, size=size)
    if not as_json and need.seconds is not None and need.seconds > NOTE_ABOVE_SECONDS:
        echo_note(f"note: {need.what}: predicted to run for about {format_duration(need.seconds)}, peak "
                  f"{need.bytes / 1e9:.1f} GB of memory")  # fmt: skip
    if device is not None:
        summary, phase_explain = _routed(
            s, p, options, device, lowered, bindings, local_ancillas, qasm, qasm_version, layout, qasm_profile,
            optimize_for, measure, zero_start, effort,
        )
    elif qasm is not None or size.gates >= STREAM_ABOVE_GATES:
        task = f"compile {s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s), p={p}"
        # the prediction counts lowered gates: the high-level circuit's count is not known before it is built (a
        # written circuit's second pass takes the first pass's count as its total)
        total = size.gates if lowered else None
        big = size.gates >= STREAM_ABOVE_GATES  # known to be long: the first line comes at once
        # building a section costs more per gate in some sections than in others (a 30x30 grid's mixer sections
        # build two to three times slower than its phase sections, in either walk): the share of gates done does
        # not extrapolate to the time left, so that is shown only when the sections are counted
        with Progress(task, total=total, unit="gates", first_after=0.0 if big else None,
                      time_left=qasm is None) as bar:  # fmt: skip
            summary, phase_explain = _stream(s, p, options, lowered, bindings, qasm, qasm_version, bar, qasm_profile,
                                             measure)  # fmt: skip
    else:
        result = compile_scenario(s, p, options, lowered=lowered, bindings=bindings, bind_field="--bind")
        summary, phase_explain = result.summary(), result.phase_explain
    if qasm is not None:  # written by _routed or _stream
        summary["qasm"] = {"path": str(qasm), "version": qasm_version}
        if qasm_profile != "default":
            summary["qasm"]["profile"] = qasm_profile
        if measure:
            summary["qasm"]["measured"] = "meas"  # the classical register: data qubit i into meas[i]
    if explain:
        summary["phase_explain"] = phase_explain
    if not options.first_phase:  # as estimate's rows say it; the default's summary keeps its keys
        summary["first_phase"] = False
    if as_json:
        typer.echo(json_text(summary))
        return
    console = Console(stderr=to_stdout)  # with --qasm -, stdout is the OpenQASM text only
    form = "lowered" if lowered else "high level"
    if device is not None:
        form = f"routed on {summary['device']['name']}, {'lowered' if lowered else 'native gates'}"
    skipped = "" if options.first_phase else ", no first phase separator"
    table = Table(title=f"{label}: p={p}, rule={options.rule}, target={options.target}{skipped}, {form}")
    table.add_column("gate")
    table.add_column("count", justify="right")
    for name, n in summary["gates"].items():
        table.add_row(name, str(n))
    table.add_row("[bold]total", f"[bold]{summary['total_gates']}")
    print_table(console, table)
    regs = ", ".join(f"{k} {v}" for k, v in summary["registers"].items())
    console.print(f"qubits: {summary['qubits']}" + (f" ({regs})" if len(summary["registers"]) > 1 else ""))
    if device is not None:
        routed = summary["routed"]
        duration = "unknown" if routed["duration_s"] is None else f"{routed['duration_s']:.6g} s"
        idle = "" if routed.get("esp_idle") is None else f" ({_esp(routed, 'esp_idle')} with idle decoherence)"
        console.print(
            f"routed: {routed['two_qubit']} two-qubit gates ({routed['swaps']} SWAPs), "
            f"ESP {_esp(routed, 'esp')}{idle}, duration {duration}; {summary['device_note']}"
        )
        console.print(_layouts_line(summary["initial_layout"], summary["final_layout"]))
        console.print(esp_verdict(routed["esp"] if routed.get("esp_idle") is None else routed["esp_idle"],
                                  idle=routed.get("esp_idle") is not None))  # fmt: skip
        if routed.get("candidates"):
            effort = "" if routed.get("effort", "full") == "full" else f", effort {routed['effort']}"
            console.print(f"chosen by {routed['optimize_for']}: {routed['chosen']} "
                          f"(of {len(routed['candidates'])} candidates, Qiskit O3 among them{effort})")  # fmt: skip
            peer = qiskit_o3_line(routed)
            if peer:
                console.print(peer)
        if not routed.get("equal_on_every_input", True):
            console.print("note: simplified for the all-|0> start (--zero-start): equals the logical circuit only "
                          "from that start; put no gates before it")  # fmt: skip
    if summary["symbols"]:
        console.print(f"unbound symbols: {', '.join(summary['symbols'])}")
    console.print(f"time: {summary['seconds']:.3f} s")
    if qasm is not None:
        where = "standard output" if to_stdout else qasm
        form = f"OpenQASM {qasm_version}" + (f", {qasm_profile} profile" if qasm_profile != "default" else "")
        form += ", data qubits measured into meas" if measure else ""
        console.print(f"wrote {where} ({form})", markup=False, soft_wrap=True)  # a path stays whole
    if explain:
        print_table(console, explain_table(phase_explain, in_circuit=options.phase_layers(p) > 0))


def _layouts_line(initial: list[int], final: list[int]) -> str:
    """The layouts the device note announces (logical qubit ``i`` -> physical qubit), in full up to
    :data:`LAYOUT_SHOWN` qubits; longer ones are in ``--json``."""
    if len(initial) > LAYOUT_SHOWN:
        return f"layouts: {len(initial)} logical qubits each (initial_layout, final_layout in --json)"
    return f"initial layout {' '.join(map(str, initial))}; final layout {' '.join(map(str, final))}"


def qiskit_o3_line(routed: dict[str, Any]) -> str | None:
    """Qiskit O3's best seed against the chosen circuit, by the figure compile chose for (``--json``'s
    ``routed``; ``None`` when no ``qiskit O3 seed`` candidate ran).

    Example:
        >>> routed = {"optimize_for": "esp", "chosen": "qcpp", "two_qubit": 269, "esp": 0.33, "esp_idle": 0.16,
        ...           "candidates": [{"name": "qcpp", "two_qubit": 269, "esp": 0.33, "esp_idle": 0.16},
        ...                          {"name": "qiskit O3 seed 0", "two_qubit": 303, "esp": 0.28, "esp_idle": 0.06},
        ...                          {"name": "qiskit O3 seed 1", "two_qubit": 310, "esp": 0.27, "esp_idle": 0.05}]}
        >>> for part in qiskit_o3_line(routed).split("; "):
        ...     print(part)
        Qiskit O3 (best of 2 seeds by esp): 303 two-qubit gates, ESP 0.28 (0.06 idle)
        chosen: 0.89x its two-qubit gates, 2.67x its ESP (idle)
    """
    seeds = [c for c in routed["candidates"] if c["name"].startswith("qiskit O3 seed ") and "+" not in c["name"]]
    if not seeds:
        return None
    from qcpp.pipeline.candidates import figure_key

    idle = routed.get("esp_idle") is not None

    def figure(c: dict[str, Any]) -> float:
        return c["esp_idle"] if idle else c["esp"]

    best = max(seeds, key=lambda c: figure_key(c["two_qubit"], c["esp"], c.get("esp_idle"), routed["optimize_for"]))
    esp_text = f"ESP {best['esp']:.3g}" + (f" ({best['esp_idle']:.3g} idle)" if idle else "")
    ratio_esp = figure(routed) / figure(best) if figure(best) > 0 else math.inf
    return (
        f"Qiskit O3 (best of {len(seeds)} seeds by {routed['optimize_for']}): {best['two_qubit']:,} two-qubit gates, "
        f"{esp_text}; chosen: {routed['two_qubit'] / best['two_qubit']:.2f}x its two-qubit gates, "
        f"{ratio_esp:.3g}x its ESP{' (idle)' if idle else ''}"
    )


def _esp(routed: dict[str, Any], key: str) -> str:
    """``routed[key]`` (an ESP) to 3 significant digits, or from its base-10 log where it underflowed to 0.

    >>> _esp({"esp": 0.0, "log10_esp": -1234.55}, "esp"), _esp({"esp": 0.1234, "log10_esp": -0.9}, "esp")
    ('2.818e-1235', '0.123')
    """
    return from_log(routed, key) or f"{routed[key]:.3g}"


def esp_verdict(esp: float, *, idle: bool) -> str:
    """What an ESP means for running the circuit: the share of shots without an error, against the verdict's bar
    :data:`qcpp.routing.native.RUNNABLE_ESP` (docs/guide/hardware.md).

    Args:
        esp: The routed circuit's ESP (with idle decoherence where ``idle``).
        idle: Whether ``esp`` includes idle decoherence.

    Example:
        >>> esp_verdict(0.163, idle=True)
        'verdict: about 16% of shots run without an error (ESP with idle decoherence 0.163 >= 0.1: worth running)'
        >>> esp_verdict(9.2e-06, idle=False)[:58]
        'verdict: about 1 shot in 108,696 runs without an error (ES'
        >>> esp_verdict(2.1e-17, idle=True)[:46]
        'verdict: about 1 shot in 4.8e16 runs without a'
    """
    which = "ESP with idle decoherence" if idle else "ESP"
    if esp >= 0.01:
        one_in = f"about {esp:.0%} of shots run"
    else:
        one_in = "no shot runs" if esp <= 0 else f"about 1 shot in {_count(1 / esp)} runs"
    judged = "worth running" if esp >= RUNNABLE_ESP else "noise dominates; see docs/guide/hardware.md"
    relation = ">=" if esp >= RUNNABLE_ESP else "<"
    return f"verdict: {one_in} without an error ({which} {esp:.3g} {relation} {RUNNABLE_ESP:g}: {judged})"


def _count(n: float) -> str:
    """``n`` rounded, with thousands separators up to a million, else as ``4.8e16``."""
    if n < 1e6:
        return f"{round(n):,}"
    mantissa, exponent = f"{n:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def explain_table(rows: list[dict], in_circuit: bool = True) -> Table:
    """The phase plan's choices: per term group, the construction, its cost and the alternatives' costs;
    ``in_circuit=False`` says the compiled circuit has no phase separator (``--skip-first-phase`` at ``p = 1``), so
    the plan is shown for what a later layer would use."""
    none = "; this circuit has none: --skip-first-phase at p = 1" if not in_circuit else ""
    table = Table(title=f"phase separator: construction per term group (cost of one layer{none})")
    for col in ("group", "count", "chosen", "cx", "rotations", "T (ft)", "alternatives (cx / rotations / T)"):
        table.add_column(col, justify="right" if col in ("count", "cx", "rotations", "T (ft)") else "left")
    for row in rows:
        c = row["cost"]
        alts = "\n".join(
            f"{name}: {a['cx']:,} / {a['rotations']:,} / {a['t_ft']:,}" for name, a in row["alternatives"].items()
        )
        table.add_row(
            str(row["group"]), str(row.get("count", 1)), str(row["construction"]),
            f"{c['cx']:,}", f"{c['rotations']:,}", f"{c['t_ft']:,}", alts or "-",
        )  # fmt: skip
    return table


def _routed(
    s: Scenario,
    p: int,
    options: PlanOptions,
    device: str,
    lowered: bool,
    bindings: dict[str, float],
    local_ancillas: bool,
    qasm: str | None,
    version: int,
    layout: str = "auto",
    profile: Profile = "default",
    optimize_for: str | None = None,
    measure: bool = False,
    zero_start: bool = False,
    effort: str = "full",
) -> tuple[dict[str, Any], list[dict]]:
    """Compile, route onto ``device`` (:func:`qcpp.pipeline.device_compile.compile_for_device`) and write OpenQASM
    (``measure``: with every data qubit measured at its physical qubit at the end); the summary adds ``device``,
    ``initial_layout``, ``final_layout`` and ``routed`` (``zero_start``: also the candidates simplified for the
    all-|0> start; ``effort``: :func:`qcpp.routing.options.effort_routing`)."""
    from qcpp.pipeline.device_compile import compile_for_device

    task = f"compile {s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s), p={p}, --device {device}"
    with Progress(task) as bar:  # silent unless it takes a few seconds (the heavy-hex cells' plan choice)
        result = compile_for_device(s, p, device_arg(device), options, lowered=lowered, bindings=bindings,
                                    local_ancillas=local_ancillas, layout_method=layout, stage=bar.stage,
                                    optimize_for=optimize_for, bind_field="--bind", zero_start=zero_start,
                                    routing=effort_routing(effort))  # fmt: skip
    if qasm is not None:
        with _bind_hint():
            measured = result.routed.final_layout[: s.num_variables] if measure else None
            note = None if result.equal_on_every_input else ZERO_START_NOTE
            write_qasm_profile(result.routed.circuit, qasm, version, profile, measured, note)  # type: ignore[arg-type]
    return result.compile_summary(), result.compiled.phase_explain


def _guard(
    s: Scenario, p: int, options: PlanOptions, max_gates: int | None, force: bool, *, streamed: bool
) -> SizePrediction:
    """The predicted size; unless ``force``, refuse (one line, exit 2) a circuit predicted to exceed ``max_gates``
    lowered gates or, without ``max_gates``, one that would not fit in memory or would run for hours
    (:func:`qcpp.estimators.guard.check_size`). Only ``--force`` lifts it: ``--allow-large`` (the grid and layer
    limits) does not, so a grid past 50x50 is still refused when its compile would not fit or would run for hours."""
    override = "raise it with --max-gates N, or pass --force"
    with lifted_limits(False):
        return check_size(s, p, options, max_gates, override, force, streamed=streamed, allow_large_hint="pass --force")


def _stream(
    s: Scenario,
    p: int,
    options: PlanOptions,
    lowered: bool,
    bindings: dict[str, float],
    qasm: str | None,
    version: int,
    progress: Progress,
    profile: Profile = "default",
    measure: bool = False,
) -> tuple[dict[str, Any], list[dict]]:
    """Build, lower, bind and (if ``qasm`` is a path) write the circuit one plan section at a time (peak memory
    independent of ``p``; ``measure``: the data qubits measured at the end); return the summary
    :meth:`qcpp.plan.compile.CompileResult.summary` would give and the
    phase plan's choices. ``progress`` counts the gates of every section handed out."""
    from qcpp.plan.qaoa import qaoa_plan

    start = time.perf_counter()
    progress.stage("planning the circuit")
    plan = qaoa_plan(s, p, options)
    plan.check_bindings(bindings, "--bind")
    progress.stage("building the sections")
    # the lowered circuit has the plan's registers (work included); the high-level one has no work register
    registers = tuple(plan.registers) if lowered else tuple(r for r in plan.registers if r.name != "work")

    walks = 0

    def sections() -> Iterator[Section]:
        # writing OpenQASM walks the sections twice (the header's symbols and gate definitions, then the text):
        # each pass counts the circuit's gates once, from 0, so the count ends at the circuit's gate count
        nonlocal walks
        walks += 1
        if walks > 1:
            progress.update(0, progress.done)  # the first pass counted every gate: the total, known now
        if qasm is not None:
            progress.stage(f"pass {walks} / 2: " + ("collecting symbols" if walks == 1 else "writing OpenQASM"))
        for sec in plan.emit_sections(lowered):
            out = Circuit(registers, [sec]).bind(bindings).sections[0] if bindings else sec
            yield out
            progress.advance(len(out.gates))

    if qasm is not None:
        with _bind_hint():
            measured = range(s.num_variables) if measure else None
            ops, symbols = write_qasm_sections(registers, sections, qasm, version, profile,  # type: ignore[arg-type]
                                               measured)  # fmt: skip
    else:
        ops, symbols = _count_sections(registers, sections())
    summary = compile_summary(s, registers, ops, symbols, lowered, time.perf_counter() - start)
    return summary, (plan.phase_plan.explain() if plan.phase_plan is not None else [])


BIND_HINT = "give them with --bind NAME=VALUE"
"""How the command line's message on unbound angles (OpenQASM 2 needs numbers) ends."""


@contextlib.contextmanager
def _bind_hint() -> Iterator[None]:
    """Re-raise an :class:`~qcpp.ir.angles.UnboundParameterError` with :data:`BIND_HINT` as its ending."""
    try:
        yield
    except UnboundParameterError as exc:
        raise UnboundParameterError(exc.symbols, exc.context, BIND_HINT) from None


def _count_sections(
    registers: tuple[Register, ...], sections: Iterable[Section]
) -> tuple[Counter[str], tuple[str, ...]]:
    """Gates per name and the unbound symbols (in :attr:`Circuit.symbols` order) of a stream of sections."""
    ops: Counter[str] = Counter()
    found: set[str] = set()
    for sec in sections:
        ops.update(g[0] for g in sec.gates)
        found.update(Circuit(registers, [sec]).symbols)
    return ops, tuple(sorted(found, key=symbol_sort_key))


def register(app: typer.Typer) -> None:
    """Add ``compile`` to ``app``."""
    app.command("compile", help=HELP)(compile_command)
