"""Default placement: unchanged corners for 1-4 robots, distinct boundary starts beyond, reflected goals."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from qcpp.problem.errors import ScenarioError
from qcpp.problem.paths import initial_path, is_feasible
from qcpp.problem.presets import boundary_nodes, default_scenario, max_default_robots


def test_one_to_four_robots_keep_the_corner_placement() -> None:
    s = default_scenario(4, 5, 4)
    assert [(r.start, r.goal) for r in s.robots] == [
        ((0, 0), (3, 4)),
        ((0, 4), (3, 0)),
        ((3, 0), (0, 4)),
        ((3, 4), (0, 0)),
    ]
    assert [r.start for r in default_scenario(4, 5, 2).robots] == [(0, 0), (0, 4)]


def test_boundary_nodes_walk_the_perimeter_once() -> None:
    for rows, cols in [(2, 2), (2, 5), (3, 3), (6, 4)]:
        nodes = boundary_nodes(rows, cols)
        assert len(nodes) == len(set(nodes)) == max_default_robots(rows, cols)
        assert all(r in (0, rows - 1) or c in (0, cols - 1) for r, c in nodes)
        assert all(abs(a[0] - b[0]) + abs(a[1] - b[1]) == 1 for a, b in zip(nodes, nodes[1:] + nodes[:1]))


@given(st.integers(2, 12), st.integers(2, 12), st.data())
def test_any_robot_count_the_grid_hosts(rows: int, cols: int, data: st.DataObject) -> None:
    k = data.draw(st.integers(1, max_default_robots(rows, cols)))
    s = default_scenario(rows, cols, k)
    starts = [r.start for r in s.robots]
    assert len(set(starts)) == k and len({r.goal for r in s.robots}) == k
    for i, rb in enumerate(s.robots):
        assert rb.goal == (rows - 1 - rb.start[0], cols - 1 - rb.start[1])
        assert rb.start in boundary_nodes(rows, cols)
        assert is_feasible(s, i, initial_path(s, i))


def test_extra_robots_are_spread_around_the_boundary() -> None:
    s = default_scenario(10, 10, 8)
    extra = [r.start for r in s.robots[4:]]
    ring = boundary_nodes(10, 10)
    pos = sorted(ring.index(n) for n in extra)
    gaps = [b - a for a, b in zip(pos, [*pos[1:], pos[0] + len(ring)])]
    assert max(gaps) - min(gaps) <= 2  # even spacing up to the corners skipped


@pytest.mark.parametrize("rows, cols, robots", [(2, 2, 5), (2, 3, 7), (3, 3, 0), (1, 3, 1), (3, 3, 9)])
def test_too_many_robots_or_bad_grid_is_refused(rows: int, cols: int, robots: int) -> None:
    with pytest.raises(ScenarioError):
        default_scenario(rows, cols, robots)
