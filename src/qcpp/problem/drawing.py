"""A scenario drawn as SVG text: the grid's edges, obstacles as dark squares, each robot's start (filled circle) and
goal (ring) in the robot's colour, numbered. What a notebook shows for a :class:`~qcpp.problem.scenario.Scenario`
(its ``_repr_svg_``); plain text, no plotting library.

Example:
    >>> from qcpp.problem.presets import grid_scenario
    >>> svg = scenario_svg(grid_scenario(3, 3, robots=1, obstacles=[(1, 1)]))
    >>> svg.startswith("<svg") and svg.count("<rect") == 2  # the background and one obstacle
    True
"""

from __future__ import annotations

from collections.abc import Sequence
from html import escape
from typing import Protocol

from qcpp.problem.grid import Grid, Node


class _Robot(Protocol):
    start: Node
    goal: Node


class Drawable(Protocol):
    """What the drawing reads of a :class:`~qcpp.problem.scenario.Scenario` (so this module, which the scenario's
    ``_repr_svg_`` imports, need not import the scenario)."""

    grid: Grid
    name: str
    obstacles: Sequence[Node]
    robots: Sequence[_Robot]

    @property
    def num_robots(self) -> int: ...

__all__ = ["ROBOT_COLOURS", "scenario_svg"]

ROBOT_COLOURS: tuple[str, ...] = (
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f",
)  # fmt: skip
"""Robot ``r`` is drawn in colour ``r`` (modulo their number): matplotlib's ``tab10``."""


def scenario_svg(scenario: Drawable, cell: int = 40) -> str:
    """The SVG of ``scenario`` (see the module docstring).

    Args:
        cell: Pixels between neighbouring nodes.

    Returns:
        A standalone ``<svg>`` element with a ``<title>`` naming the grid and robots.
    """
    g = scenario.grid
    pad = cell // 2 + 4
    width, height = (g.cols - 1) * cell + 2 * pad, (g.rows - 1) * cell + 2 * pad

    def xy(node: tuple[int, int]) -> tuple[int, int]:
        return pad + node[1] * cell, pad + node[0] * cell

    title = f"{g.rows}x{g.cols} grid, {scenario.num_robots} robot(s), {len(scenario.obstacles)} obstacle(s)"
    if scenario.name:
        title = f"{scenario.name}: {title}"
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" '
        'font-family="sans-serif" font-size="11">',
        f"<title>{escape(title)}</title>",
        f'<rect width="{width}" height="{height}" fill="white"/>',
    ]
    for u, v in g.edges:
        (x1, y1), (x2, y2) = xy(u), xy(v)
        out.append(f'<line x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}" stroke="#bbb" stroke-width="2"/>')
    half = cell // 3
    for o in scenario.obstacles:
        x, y = xy(o)
        out.append(f'<rect x="{x - half}" y="{y - half}" width="{2 * half}" height="{2 * half}" fill="#333"/>')
    r = max(cell // 5, 3)
    for i, rb in enumerate(scenario.robots):
        colour = ROBOT_COLOURS[i % len(ROBOT_COLOURS)]
        (sx, sy), (gx, gy) = xy(rb.start), xy(rb.goal)
        out.append(f'<circle cx="{sx}" cy="{sy}" r="{r}" fill="{colour}"><title>robot {i} start</title></circle>')
        out.append(
            f'<circle cx="{gx}" cy="{gy}" r="{r}" fill="white" stroke="{colour}" stroke-width="3">'
            f"<title>robot {i} goal</title></circle>"
        )
        out.append(f'<text x="{sx}" y="{sy + 4}" text-anchor="middle" fill="white">{i}</text>')
        out.append(f'<text x="{gx}" y="{gy + 4}" text-anchor="middle" fill="{colour}">{i}</text>')
    out.append("</svg>")
    return "\n".join(out)
