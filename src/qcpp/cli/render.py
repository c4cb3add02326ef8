"""Drawing scenarios and robot paths: plain-text grids, PNG plots of paths and of cost traces.

Text drawing (:func:`render_ascii`): node ``(r, c)`` sits at text row ``2 r`` and column ``4 c``; a
horizontal edge fills the three characters between two nodes, a vertical edge the one character between
two rows. Legend:

====================  ==============================================================================
``S`` / ``G``         start / goal of a robot (``E`` if the node is an endpoint of several robots)
``-k-`` / ``k``       horizontal / vertical edge on robot ``k``'s path (``k`` = robot index mod 10)
``-*-`` / ``*``       edge on the paths of several robots
``o``                 node on exactly one robot's path; ``*`` node on several robots' paths
``.``                 free node no path visits
``#`` / ``X``         obstacle / obstacle that a path crosses (possible with soft obstacles)
====================  ==============================================================================

Plots (:func:`plot_paths`, :func:`plot_trace`) use matplotlib's object API with the Agg canvas (no pyplot,
no global backend switch) and are written atomically: to a temporary file in the target's folder, then
renamed over it.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.problem.paths import path_from_nodes
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3, "obstacles": [[1, 1]]},
    ...                         "robots": [{"start": [0, 0], "goal": [1, 2]}]})
    >>> p = path_from_nodes(s.grid, [(0, 0), (0, 1), (0, 2), (1, 2)])
    >>> print(render_ascii(s, [p], legend=False))
    S-0-o-0-o
            0
    .   #   G
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from qcpp.estimators.tables import draw, records, terminal_width, title_lines
from qcpp.io.atomic import OutputError, check_output, is_stdout, save_figure_atomic
from qcpp.io.caches import use_writable_matplotlib_config
from qcpp.problem.paths import edges_of
from qcpp.problem.scenario import Scenario

LEGEND = (
    "S start, G goal, E endpoint of several robots, -k- / k edge of robot k,\n"
    "o path node, * shared by robots, . unvisited, # obstacle, X obstacle on a path"
)

# distinct colours (matplotlib's tab10) for robots 0..9; robot k uses COLOURS[k % 10]
COLOURS = (
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
    "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf",
)  # fmt: skip


def _check_paths(scenario: Scenario, paths: Sequence[int] | None) -> Sequence[int]:
    if paths is None:
        return ()
    if len(paths) != scenario.num_robots:
        raise ValueError(f"expected {scenario.num_robots} paths (one per robot), got {len(paths)}")
    return paths


def check_figure_output(path: str | os.PathLike[str]) -> None:
    """Fail early if ``path`` cannot take a command's figure (:func:`qcpp.io.atomic.check_output` with
    ``figure=True``), and refuse standard output: every command that draws also prints its text or JSON there, and
    image bytes among it serve neither a reader nor a parser.

    Raises:
        OutputError: naming ``path``.

    Example:
        >>> try:
        ...     check_figure_output("-")
        ... except OutputError as exc:
        ...     print(exc)
        cannot write -: standard output holds the command's text; give the image a file name
    """
    if is_stdout(os.fspath(path)):
        raise OutputError(os.fspath(path), "standard output holds the command's text; give the image a file name")
    check_output(path, figure=True)


def render_ascii(scenario: Scenario, paths: Sequence[int] | None = None, *, legend: bool = True) -> str:
    """The grid with obstacles, endpoints and (optionally) one path per robot as text (legend: module docstring).

    Args:
        paths: One edge mask per robot, or ``None`` for just the grid, obstacles and endpoints.
        legend: Append the legend and one line per robot (its start, goal and edge count).

    Returns:
        The drawing, lines joined by newlines, without trailing spaces or a final newline.

    Raises:
        ValueError: if the number of paths is not the number of robots.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> print(render_ascii(s, legend=False))
        S   .
        <BLANKLINE>
        .   G
    """
    paths = _check_paths(scenario, paths)
    g = scenario.grid
    canvas = [[" "] * (4 * (g.cols - 1) + 1) for _ in range(2 * (g.rows - 1) + 1)]
    edge_users: dict[int, set[int]] = {}
    node_users: dict[tuple[int, int], set[int]] = {}
    for r, mask in enumerate(paths):
        for e in edges_of(mask):
            edge_users.setdefault(e, set()).add(r)
            for n in g.edges[e]:
                node_users.setdefault(n, set()).add(r)
    for e, users in edge_users.items():
        (r0, c0), (r1, _) = g.edges[e]
        ch = str(min(users) % 10) if len(users) == 1 else "*"
        if r0 == r1:
            canvas[2 * r0][4 * c0 + 1 : 4 * c0 + 4] = ["-", ch, "-"]
        else:
            canvas[2 * r0 + 1][4 * c0] = ch
    endpoints: dict[tuple[int, int], list[str]] = {}
    for rb in scenario.robots:
        endpoints.setdefault(rb.start, []).append("S")
        endpoints.setdefault(rb.goal, []).append("G")
    for node in g.nodes:
        users = node_users.get(node, set())
        if node in endpoints:
            kinds = endpoints[node]
            ch = kinds[0] if len(kinds) == 1 else "E"
        elif node in scenario.obstacle_set:
            ch = "X" if users else "#"
        elif users:
            ch = "o" if len(users) == 1 else "*"
        else:
            ch = "."
        canvas[2 * node[0]][4 * node[1]] = ch
    lines = ["".join(row).rstrip() for row in canvas]
    if legend:
        lines += ["", LEGEND]
        for r, rb in enumerate(scenario.robots):
            extra = f", {len(edges_of(paths[r]))} edges" if paths else ""
            lines.append(f"robot {r}: {rb.start} -> {rb.goal}{extra}")
    return "\n".join(lines)


def plot_paths(
    scenario: Scenario,
    paths: Sequence[int] | None,
    file: str | os.PathLike[str],
    *,
    title: str | None = None,
) -> Path:
    """Draw the grid, obstacles, each robot's path in its own colour and its start/goal markers to ``file``.

    Robots' paths are offset slightly from each other so shared edges stay visible. Starts are squares,
    goals are stars, in the robot's colour; obstacles are black crosses on grey squares.

    Args:
        paths: One edge mask per robot (or ``None``: grid, obstacles and endpoints only).
        file: Output path; the format follows the suffix (``.png``, ``.svg``, ``.pdf``, ...).
        title: Figure title (default: the scenario's name, else its size).

    Raises:
        ValueError: if the number of paths is wrong or the format is unknown to matplotlib.
        OSError: if the file cannot be written.

    Example:
        >>> import tempfile, pathlib
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> from qcpp.problem.paths import initial_path
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> out = plot_paths(s, [initial_path(s, 0)], pathlib.Path(tempfile.mkdtemp()) / "p.png")
        >>> out.read_bytes()[:8] == b"\\x89PNG\\r\\n\\x1a\\n"
        True
    """
    use_writable_matplotlib_config()  # before matplotlib picks its folders
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    paths = _check_paths(scenario, paths)
    g = scenario.grid
    size = 1.0 + 0.9 * max(g.rows, g.cols)
    fig = Figure(figsize=(size + 1.6, size))
    ax = fig.add_subplot()
    # grid edges and nodes; x = column, y = -row so row 0 is at the top
    for (r0, c0), (r1, c1) in g.edges:
        ax.plot([c0, c1], [-r0, -r1], color="#d0d0d0", lw=1.0, zorder=1)
    ax.scatter([c for _, c in g.nodes], [-r for r, _ in g.nodes], s=18, color="#a0a0a0", zorder=2)
    if scenario.obstacles:
        ox = [c for _, c in scenario.obstacles]
        oy = [-r for r, _ in scenario.obstacles]
        ax.scatter(ox, oy, s=420, marker="s", color="#bbbbbb", edgecolors="black", zorder=3)
        ax.scatter(ox, oy, s=160, marker="x", color="black", linewidths=2.5, zorder=4)
    n = scenario.num_robots
    handles = []
    for r, rb in enumerate(scenario.robots):
        colour = COLOURS[r % len(COLOURS)]
        off = 0.0 if n == 1 else 0.09 * (r - (n - 1) / 2)
        if paths:
            for e in edges_of(paths[r]):
                (r0, c0), (r1, c1) = g.edges[e]
                ax.plot([c0 + off, c1 + off], [-r0 - off, -r1 - off], color=colour, lw=3.5, alpha=0.9,
                        solid_capstyle="round", zorder=5)
        ax.scatter([rb.start[1] + off], [-rb.start[0] - off], s=170, marker="s", color=colour,
                   edgecolors="black", zorder=6)
        ax.scatter([rb.goal[1] + off], [-rb.goal[0] - off], s=300, marker="*", color=colour,
                   edgecolors="black", zorder=6)
        handles.append(Line2D([], [], color=colour, lw=3.5, label=f"robot {r}"))
    handles += [
        Line2D([], [], ls="", marker="s", color="white", markeredgecolor="black", markersize=9, label="start"),
        Line2D([], [], ls="", marker="*", color="white", markeredgecolor="black", markersize=13, label="goal"),
    ]
    if scenario.obstacles:
        handles.append(Line2D([], [], ls="", marker="x", color="black", markersize=9, mew=2.5, label="obstacle"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False)
    ax.set_xticks(range(g.cols))
    ax.set_yticks([-r for r in range(g.rows)], [str(r) for r in range(g.rows)])
    ax.set_xlabel("column")
    ax.set_ylabel("row")
    ax.set_xlim(-0.5, g.cols - 0.5)
    ax.set_ylim(-(g.rows - 0.5), 0.5)
    ax.set_aspect("equal")
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    ax.set_title(title if title is not None else (scenario.name or f"{g.rows}x{g.cols} grid"), fontsize=10)
    fig.tight_layout()
    return save_figure_atomic(fig, file, bbox_inches="tight", dpi=110)


def plot_trace(
    trace: Sequence[float],
    file: str | os.PathLike[str],
    *,
    title: str = "best cost so far",
    optimum: float | None = None,
    xlabel: str = "iteration",
    label: str = "best so far",
    steps: bool = True,
) -> Path:
    """Plot a best-so-far cost trace (e.g. :attr:`qcpp.problem.solvers.Solution.trace`) to ``file``.

    Args:
        trace: Cost after each iteration / generation.
        file: Output path (format from the suffix).
        optimum: If given, drawn as a dashed horizontal line (e.g. the exhaustive optimum).
        label: Legend label of the trace.
        steps: Draw the trace as steps (a best-so-far value holds until the next improvement) or as a line
            (an objective that moves every iteration, such as QAOA's training).

    Raises:
        ValueError: if ``trace`` is empty or the format is unknown.
        OSError: if the file cannot be written.

    Example:
        >>> import tempfile, pathlib
        >>> out = plot_trace([3.0, 1.0, 1.0, -2.0], pathlib.Path(tempfile.mkdtemp()) / "t.png", optimum=-2.0)
        >>> out.stat().st_size > 0
        True
    """
    use_writable_matplotlib_config()  # before matplotlib picks its folders
    from matplotlib.figure import Figure

    if len(trace) == 0:
        raise ValueError("the trace is empty (dfs has no trace)")
    fig = Figure(figsize=(6.0, 3.6))
    ax = fig.add_subplot()
    xs = range(1, len(trace) + 1)
    if steps:
        ax.step(xs, list(trace), where="post", color=COLOURS[0], lw=1.8, label=label)
    else:
        ax.plot(xs, list(trace), color=COLOURS[0], lw=1.8, label=label)
    if optimum is not None:
        ax.axhline(optimum, color=COLOURS[3], ls="--", lw=1.2, label=f"optimum {optimum:g}")
    if len(trace) > 200:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("cost")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(frameon=False)
    fig.tight_layout()
    return save_figure_atomic(fig, file)


def _plain(cell: Any) -> str:
    from rich.text import Text

    if isinstance(cell, Text):
        return cell.plain
    return Text.from_markup(str(cell)).plain


def _title(table: Any) -> str:
    return _plain(table.title) if table.title else ""


def _drawn(table: Any, width: int = 100_000) -> str:
    """The table (without its title) drawn by rich within ``width``, plain text."""
    title, table.title = table.title, None
    try:
        return "\n".join(line.rstrip() for line in draw(table, width).splitlines())
    finally:
        table.title = title


_BOX = str.maketrans(dict.fromkeys("│┃║|", " "))


def table_fits(table: Any, width: int) -> bool:
    """Whether rich draws ``table`` within ``width`` without cutting anything: every word of every header and
    cell must appear whole (rich may still wrap a cell's words onto several lines, which cuts nothing)."""
    drawn = _drawn(table, width)
    if "…" in drawn:
        return False
    shown = set(drawn.translate(_BOX).split())
    words = {w for c in table.columns for x in [c.header, *c.cells] for w in _plain(x).split()}
    return words <= shown


def table_text(table: Any, width: int) -> str:
    """A rich ``Table`` as text of at most ``width`` characters per line, never cutting a number or a name.

    The title is wrapped at spaces only (a file name longer than the line stands whole on its own line). The
    table is drawn as is when it fits; otherwise each row becomes a record (:func:`qcpp.estimators.tables.records`),
    one ``header  value`` line per column (a two-column table gives one ``label  value`` line per row), or,
    where that is too wide, the value on the line below its header, indented. Only a single header or value
    longer than ``width`` can make a line longer.

    Args:
        table: The ``rich.table.Table``.
        width: Characters per line (the console's width).

    Returns:
        The text, ending with a newline.

    Example:
        >>> from rich.table import Table
        >>> t = Table(title="cost of examples/two_robots_5x5.toml")
        >>> t.add_column("term"); t.add_column("value", justify="right")
        >>> t.add_row("c1 obstacles/coverage", "-23456")
        >>> print(table_text(t, 29), end="")
        cost of
        examples/two_robots_5x5.toml
        c1 obstacles/coverage  -23456
    """
    if table_fits(table, width):
        return "\n".join([*title_lines(_title(table), width), _drawn(table, width)]) + "\n"
    headers = [_plain(c.header) for c in table.columns]
    rows = list(zip(*([_plain(x) for x in c.cells] for c in table.columns), strict=True))
    blocks = [rows] if len(headers) == 2 else [list(zip(headers, row, strict=True)) for row in rows]
    return records(_title(table), blocks, width, sep="  ", per_field=True)


def print_table(console: Any, table: Any) -> None:
    """Print ``table`` on the rich ``console`` within its width (:func:`table_text`); a table that fits is
    printed by rich itself, so it keeps its colours."""
    if not table_fits(table, console.width):
        console.print(table_text(table, console.width), markup=False, highlight=False, soft_wrap=True, end="")
        return
    for line in title_lines(_title(table), console.width):
        console.print(line, markup=False, highlight=False, soft_wrap=True)
    title, table.title = table.title, None
    try:
        console.print(table)
    finally:
        table.title = title


def json_text(value: Any) -> str:
    """``value`` as one line of strict JSON, file names decoded: a name Python read in a non-UTF-8 locale
    (``LC_ALL=C``) holds its undecodable bytes as lone surrogates (``caf\\udcc3\\udca9.toml``), which JSON
    escapes into text no strict reader accepts; such a string is read as UTF-8 again (``café.toml``), with
    U+FFFD for bytes that are not UTF-8.

    Example:
        >>> json_text({"scenario": "caf\\udcc3\\udca9.toml", "n": [1, "x"]})
        '{"scenario": "caf\\\\u00e9.toml", "n": [1, "x"]}'
    """
    import json

    return json.dumps(_decoded(value))


def _decoded(value: Any) -> Any:
    if isinstance(value, str):
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:  # lone surrogates: bytes the locale could not decode
            try:
                raw = value.encode("utf-8", "surrogateescape")
            except UnicodeEncodeError:  # a surrogate that stands for no byte
                raw = value.encode("utf-8", "replace")
            return raw.decode("utf-8", "replace")
        return value
    if isinstance(value, dict):
        return {_decoded(k): _decoded(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_decoded(v) for v in value]
    return value


def echo_note(text: str) -> None:
    """``text`` on standard error, wrapped at spaces to the terminal's width
    (:func:`qcpp.io.text.terminal_width`); no word is cut."""
    import textwrap

    import typer

    lines = textwrap.wrap(text, terminal_width(), break_long_words=False, break_on_hyphens=False)
    typer.echo("\n".join(lines), err=True)
