"""Text drawing (every edge and node character checked against the paths) and atomic plots."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from qcpp.cli.render import LEGEND, plot_paths, plot_trace, render_ascii
from qcpp.problem.grid import Node
from qcpp.problem.paths import edges_of, enumerate_paths, path_from_nodes
from qcpp.problem.scenario import Scenario, scenario_from_dict

PNG = b"\x89PNG\r\n\x1a\n"


def build(
    rows: int, cols: int, robots: list[tuple[Node, Node]], obstacles: list[Node] = (), mode: str = "soft"  # type: ignore[assignment]
) -> Scenario:
    return scenario_from_dict({
        "grid": {"rows": rows, "cols": cols, "obstacles": [list(o) for o in obstacles]},
        "robots": [{"start": list(s), "goal": list(g)} for s, g in robots],
        "objective": {"obstacles": mode},
    })


def _char(lines: list[str], row: int, col: int) -> str:
    line = lines[row]
    return line[col] if col < len(line) else " "


def test_every_edge_and_node_character() -> None:
    s = build(3, 4, [((0, 0), (2, 3)), ((2, 0), (0, 3))], [(1, 1), (1, 2)], "soft")
    p0 = path_from_nodes(s.grid, [(0, 0), (0, 1), (0, 2), (0, 3), (1, 3), (2, 3)])
    p1 = path_from_nodes(s.grid, [(2, 0), (1, 0), (1, 1), (0, 1), (0, 2), (0, 3)])
    lines = render_ascii(s, [p0, p1], legend=False).split("\n")
    assert len(lines) == 2 * 3 - 1
    assert all(line == line.rstrip() for line in lines)
    users = {e: {r for r, p in enumerate((p0, p1)) if (p >> e) & 1} for e in range(s.grid.num_edges)}
    for e, ((r0, c0), (r1, _)) in enumerate(s.grid.edges):
        expected = " " if not users[e] else str(min(users[e])) if len(users[e]) == 1 else "*"
        if r0 == r1:
            seg = "".join(_char(lines, 2 * r0, 4 * c0 + k) for k in (1, 2, 3))
            assert seg == ("   " if expected == " " else f"-{expected}-"), (e, seg)
        else:
            assert _char(lines, 2 * r0 + 1, 4 * c0) == expected, e
    on_path = [{n for e in edges_of(p) for n in s.grid.edges[e]} for p in (p0, p1)]
    expected_nodes = {
        (0, 0): "S", (2, 3): "G", (2, 0): "S", (0, 3): "G",  # (0, 3): robot 1's goal, also on robot 0's path
        (1, 1): "X", (1, 2): "#",  # obstacle crossed by robot 1 / untouched obstacle
        (0, 1): "*", (0, 2): "*", (1, 0): "o", (1, 3): "o", (2, 1): ".", (2, 2): ".",
    }  # fmt: skip
    assert (0, 3) in on_path[0] and (0, 3) in on_path[1]
    for node, ch in expected_nodes.items():
        assert _char(lines, 2 * node[0], 4 * node[1]) == ch, node


def test_endpoint_shared_by_two_robots_is_E() -> None:
    s = build(2, 3, [((0, 0), (1, 2)), ((1, 2), (0, 1))])
    lines = render_ascii(s, legend=False).split("\n")
    assert _char(lines, 2, 8) == "E" and _char(lines, 0, 0) == "S" and _char(lines, 0, 4) == "G"


def test_legend_and_robot_lines() -> None:
    s = build(3, 3, [((0, 0), (2, 2))])
    p = enumerate_paths(s, 0)[0]
    text = render_ascii(s, [p])
    assert LEGEND in text
    assert f"robot 0: (0, 0) -> (2, 2), {p.bit_count()} edges" in text
    assert max(len(line) for line in text.split("\n")) <= 80


def test_wrong_number_of_paths() -> None:
    s = build(2, 2, [((0, 0), (1, 1))])
    with pytest.raises(ValueError, match="1 paths"):
        render_ascii(s, [])
    with pytest.raises(ValueError, match="1 paths"):
        plot_paths(s, [1, 2], "unused.png")


def test_plot_paths_writes_png_atomically(tmp_path: Path) -> None:
    s = build(4, 4, [((0, 0), (3, 3)), ((3, 0), (0, 3))], [(1, 2)])
    paths = [enumerate_paths(s, r)[5] for r in range(2)]
    target = tmp_path / "paths.png"
    target.write_bytes(b"old")
    assert plot_paths(s, paths, target) == target
    assert target.read_bytes()[:8] == PNG
    assert [p.name for p in tmp_path.iterdir()] == ["paths.png"]
    mask = os.umask(0o022)
    os.umask(mask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~mask  # not mkstemp's 0600
    svg = plot_paths(s, None, tmp_path / "grid.svg", title="grid only")
    assert b"<svg" in svg.read_bytes()[:500]


def test_plot_failure_leaves_target_and_no_temp_file(tmp_path: Path) -> None:
    s = build(2, 2, [((0, 0), (1, 1))])
    target = tmp_path / "paths.nosuchformat"
    target.write_bytes(b"old")
    with pytest.raises(ValueError):
        plot_paths(s, None, target)
    assert target.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == [target.name]
    with pytest.raises(OSError):
        plot_paths(s, None, tmp_path / "missing-dir" / "p.png")


def test_plot_trace(tmp_path: Path) -> None:
    out = plot_trace([5.0, 3.0, 3.0, -1.0] * 100, tmp_path / "t.png", optimum=-1.0)
    assert out.read_bytes()[:8] == PNG
    assert [p.name for p in tmp_path.iterdir()] == ["t.png"]
    with pytest.raises(ValueError, match="empty"):
        plot_trace([], tmp_path / "e.png")
