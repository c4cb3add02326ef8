"""``qcpp decode``: measured counts of the data register read back as robot paths, feasibility, cost and P(optimum).

A thin layer over :func:`qcpp.decode_counts` for a user who ran ``qcpp compile --qasm F --measure`` on hardware
and saved the counts as JSON. The file is read by :func:`read_counts`, which accepts what a Qiskit user plausibly
saves: a counts object (``{"0101": 12, ...}``, ``get_counts()``; hexadecimal keys ``"0x5"`` too), a list of
bitstrings (one per shot: ``get_bitstrings()``, ``get_memory()``), or ``Result.to_dict()`` of one experiment (its
``counts``, else its ``memory``). Every key must be a bitstring of the scenario's data bits (clbit 0 rightmost) or a
register value; anything else is one line naming the file and what is wrong (exit code 2).

The optimum for P(optimum) is ``--optimum`` when given; else CP-SAT's, when it proves it within ``--time-limit``
seconds (10 by default; the fields a device runs are small); else P(optimum) is left out with a note.

Examples: see :data:`HELP` (``qcpp decode --help``; ``tests/cli/help_and_noise_test.py`` runs them).
"""

from __future__ import annotations

import json
import math
from collections import Counter
from collections.abc import Mapping
from pathlib import Path
from typing import Annotated, Any

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
from qcpp.cli.render import json_text

__all__ = ["HELP", "MAX_COUNTS_BYTES", "OPTIMUM_SECONDS", "decode_command", "read_counts", "register"]

MAX_COUNTS_BYTES = 256 << 20
"""Largest counts file :func:`read_counts` reads (256 MiB: a million shots of a 100-qubit register is about 100 MiB
as a list of bitstrings)."""

OPTIMUM_SECONDS = 10.0
"""CP-SAT's default time for the optimum (``--time-limit``): without a proof by then, no P(optimum)."""

HELP = """Read measured counts (of 'qcpp compile --qasm F --measure') as paths.

Examples:
  qcpp decode examples/paper_3x3.toml --counts examples/counts/3x3.json
  qcpp decode examples/paper_3x3.toml --counts examples/counts/3x3.json --json
  qcpp decode --grid 3x3 --robot 0,0:0,2 --counts examples/counts/3x3.json

--counts FILE is JSON: an object bitstring -> shots (Qiskit's get_counts(),
clbit 0 rightmost; hexadecimal keys '0x5' too), a list of bitstrings, one
per shot (get_bitstrings(), get_memory()), or Result.to_dict() of one
experiment; one bit per data qubit (the 'meas' register). P(optimum) uses
--optimum COST, else CP-SAT's optimum if proven within --time-limit seconds
(default 10), else it is left out. Exit 0; 2: bad input (one line).
"""


def _key_problem(key: str, n: int) -> str | None:
    """What is wrong with one bitstring key for a data register of ``n`` bits, or ``None``."""
    if key.startswith("0x"):
        return None  # a register value: decode_counts checks its range
    if " " in key:
        return (f"key {key!r} has spaces: counts of several classical registers; count the 'meas' register alone "
                "(result[0].data.meas.get_counts())")  # fmt: skip
    if not set(key) <= {"0", "1"}:
        return f"key {key!r} has characters other than 0 and 1"
    if len(key) != n:
        return (f"key {key!r} has {len(key)} bits; the scenario's data register has {n} (one per variable edge, "
                "clbit 0 rightmost)")  # fmt: skip
    return None


def read_counts(path: Path, num_bits: int) -> dict[str, int]:
    """The counts in a JSON file (see the module docstring), checked against a data register of ``num_bits``.

    The file is read as a scenario file is (:func:`qcpp.io.inputs.read_bounded`): at most
    :data:`MAX_COUNTS_BYTES`, and a FIFO, pipe or device that sends nothing for a few seconds is refused.

    Raises:
        ValueError: one line starting with the file's name: unreadable, too large, not JSON, not counts, a key
            that is not a bitstring of ``num_bits`` bits (or a hexadecimal register value), a count that is not a
            non-negative integer, or no shots.

    Example:
        >>> import tempfile
        >>> f = Path(tempfile.mkdtemp()) / "memory.json"
        >>> _ = f.write_text('["01", "10", "01"]')
        >>> read_counts(f, 2)
        {'01': 2, '10': 1}
    """
    from qcpp.io.inputs import InputError, read_bounded

    try:
        raw = read_bounded(path, MAX_COUNTS_BYTES)  # bounded: /dev/zero or a silent FIFO must not hang or fill memory
    except InputError as e:
        raise ValueError(f"{path}: cannot read the file: {e.reason}") from None
    except OSError as e:
        raise ValueError(f"{path}: cannot read the file ({e.strerror or e})") from None
    if len(raw) > MAX_COUNTS_BYTES:
        raise ValueError(f"{path}: the file is larger than {MAX_COUNTS_BYTES >> 20} MiB; not counts")
    try:
        text = raw.decode("utf-8-sig")  # a leading byte order mark is not content
    except UnicodeDecodeError:
        raise ValueError(f"{path}: not a text file (expected JSON counts)") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}: not JSON ({e.msg} at line {e.lineno} column {e.colno})") from None
    if isinstance(data, Mapping) and "results" in data:  # Qiskit's Result.to_dict()
        results = data["results"]
        if not isinstance(results, list) or len(results) != 1:
            n = len(results) if isinstance(results, list) else 0
            raise ValueError(f"{path}: a Qiskit result of {n} experiments; save the counts of one")
        inner = results[0].get("data", {}) if isinstance(results[0], Mapping) else {}
        data = inner.get("counts", inner.get("memory")) if isinstance(inner, Mapping) else None
        if data is None:
            raise ValueError(f"{path}: the Qiskit result has no counts or memory")
    if isinstance(data, list):
        if not all(isinstance(b, str) for b in data):
            bad = next(b for b in data if not isinstance(b, str))
            raise ValueError(f"{path}: a list of shots must hold bitstrings, got {bad!r}")
        data = dict(Counter(data))
    if not isinstance(data, Mapping):
        raise ValueError(f"{path}: expected a JSON object of bitstring -> shots or a list of bitstrings, got "
                         f"{type(data).__name__}")  # fmt: skip
    counts: dict[str, int] = {}
    for key, shots in data.items():
        problem = _key_problem(key, num_bits)
        if problem is not None:
            raise ValueError(f"{path}: {problem}")
        if isinstance(shots, bool) or not isinstance(shots, int) or shots < 0:
            raise ValueError(f"{path}: shots of {key!r} must be a non-negative integer, got {shots!r}")
        counts[key] = shots
    if sum(counts.values()) == 0:
        raise ValueError(f"{path}: no shots")
    return counts


def _optimum(s: Any, given: float | None, seconds: float) -> tuple[float | None, str]:
    """The optimum for P(optimum) and where it came from (a note for the text, ``given``/``cpsat``/why not)."""
    if given is not None:
        return given, "given"
    from qcpp.problem.solvers.cpsat import cpsat

    res = cpsat(s, time_limit=seconds)
    if res.proven_optimal:
        return res.solution.cost.total, "cpsat"
    return None, f"CP-SAT proved no optimum within {seconds:g} s (best {res.solution.cost.total:g}): give --optimum"


def _robot_text(nodes: tuple[Any, ...] | None, edges: tuple[Any, ...]) -> str:
    if nodes is None:
        return f"not a path ({len(edges)} edge{'s' if len(edges) != 1 else ''})"
    return " ".join(f"({r},{c})" for r, c in nodes)


def _number(x: float) -> str:
    return f"{x:g}"


def decode_command(
    scenario: ScenarioFileArg = None,
    counts: Annotated[
        Path | None,
        typer.Option("--counts", help="JSON counts: bitstring -> shots, or a list of bitstrings (see above).",
                     metavar="FILE", show_default=False),
    ] = None,
    optimum: Annotated[
        float | None,
        typer.Option("--optimum", help="The optimal cost, for P(optimum) (default: CP-SAT's, if proven in time).",
                     show_default=False),
    ] = None,
    time_limit: Annotated[
        float, typer.Option("--time-limit", help="Seconds CP-SAT may take for the optimum (without --optimum).")
    ] = OPTIMUM_SECONDS,
    top: Annotated[int, typer.Option("--top", help="Outcomes shown in the text table (most shots first).")] = 10,
    as_json: Annotated[bool, typer.Option("--json", help="Print a JSON object (every outcome) instead.")] = False,
    grid: GridFlag = None,
    robots: RobotCountFlag = None,
    robot: RobotFlag = None,
    obstacle: ObstacleFlag = None,
    hard_obstacles: HardObstaclesFlag = False,
) -> None:
    """Decode measured counts (see ``qcpp decode --help``)."""
    import qcpp
    from qcpp.errors import OptionError

    if counts is None:
        raise ValueError("--counts: give the JSON file of measured counts (bitstring -> shots)")
    if not 0 < time_limit < math.inf:
        raise ValueError(f"--time-limit: expected a positive number of seconds, got {time_limit:g}")
    if top < 1:
        raise ValueError(f"--top: must be at least 1, got {top}")
    if optimum is not None and not math.isfinite(optimum):
        raise ValueError(f"--optimum: expected a finite cost, got {optimum:g}")
    given = given_scenario(scenario, grid, robots, obstacle, hard_obstacles, endpoints=robot)
    s = given.scenario
    table = read_counts(counts, s.num_variables)
    value, source = _optimum(s, optimum, time_limit)
    try:
        decoded = qcpp.decode_counts(s, table, optimum=value)
    except OptionError as e:
        raise ValueError(f"{counts}: {e.reason}") from None
    if as_json:
        out = {"scenario": given.label, "counts_file": str(counts), "distinct": len(decoded.outcomes),
               **decoded.to_dict(), "optimum_source": source if source in ("given", "cpsat") else None}  # fmt: skip
        typer.echo(json_text(out))
        return
    typer.echo(_text(decoded, given.label, str(counts), source, top))


def _text(decoded: Any, label: str, file: str, source: str, top: int) -> str:
    from rich.table import Table

    from qcpp.api.decoding import OPTIMUM_TOL
    from qcpp.cli.render import table_text
    from qcpp.estimators.tables import terminal_width

    width = terminal_width()
    d = decoded
    head = [f"{d.shots:,} shots of {file} on {label}: {len(d.outcomes):,} distinct outcome(s)"]
    summary = f"feasible {d.feasible_share:.1%} of shots"
    summary += f"; best feasible cost {_number(d.best_cost)}" if d.best is not None else "; no feasible shot"
    if d.optimum is not None:
        where = "given" if source == "given" else "CP-SAT, proven"
        summary += f"; optimum {_number(d.optimum)} ({where}); P(optimum) {d.p_optimum:.4g}"
        if d.best is not None and d.best.cost < d.optimum - OPTIMUM_TOL * max(1.0, abs(d.optimum)):
            summary += f" (a measured feasible outcome costs {_number(d.best.cost)}, below the optimum given)"
    else:
        summary += f"; no P(optimum): {source}"
    multi = len(d.outcomes[0].nodes) > 1
    t = Table(title=f"the {min(top, len(d.outcomes))} most frequent outcome(s); paths as nodes from start to goal",
              title_justify="left")  # fmt: skip
    for name, justify in (("#", "right"), ("shots", "right"), ("share", "right"), ("feasible", "left"),
                          ("cost", "right"), ("paths", "left")):  # fmt: skip
        t.add_column(name, justify=justify)  # type: ignore[arg-type]
    for i, o in enumerate(d.outcomes[:top], 1):
        robots = [_robot_text(n, e) for n, e in zip(o.nodes, o.edges, strict=True)]
        paths = "\n".join(f"r{r}: {p}" for r, p in enumerate(robots)) if multi else robots[0]
        mark = ("optimal" if o.optimal else "yes") if o.feasible else "no"
        t.add_row(str(i), f"{o.shots:,}", f"{o.shots / d.shots:.1%}", mark, _number(o.cost), paths)
    import textwrap

    lines = [line for text in (*head, summary) for line in textwrap.wrap(text, width, subsequent_indent="  ",
                                                                          break_long_words=False)]  # fmt: skip
    return "\n".join(lines) + "\n" + table_text(t, width).rstrip("\n")


def register(app: typer.Typer) -> None:
    """Add ``decode`` to ``app``."""
    app.command("decode", help=HELP)(decode_command)
