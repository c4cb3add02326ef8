"""Shared fixtures of the qcpp.problem tests: a scenario factory and a hypothesis strategy of valid scenarios.

Helpers are handed out as session-scoped fixtures (not imported from this file), so they work with
``@given`` tests (hypothesis only objects to function-scoped fixtures) and never clash with other packages'
``conftest.py`` modules.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Sequence
from typing import Any

import pytest
from hypothesis import strategies as st

from qcpp.problem.grid import Grid, Node
from qcpp.problem.scenario import Scenario, scenario_from_dict


def make_scenario(
    rows: int,
    cols: int,
    robots: Sequence[tuple[Node, Node]],
    obstacles: Sequence[Node] = (),
    mode: str = "soft",
    **objective: Any,
) -> Scenario:
    """A validated scenario from plain values: ``mode`` is the obstacle mode, ``objective`` the other
    objective keys of the file format."""
    return scenario_from_dict(
        {
            "grid": {"rows": rows, "cols": cols, "obstacles": [list(o) for o in obstacles]},
            "robots": [{"start": list(s), "goal": list(g)} for s, g in robots],
            "objective": {"obstacles": mode, **objective},
        }
    )


def _free_components(rows: int, cols: int, blocked: set[Node]) -> list[list[Node]]:
    """Connected components of the obstacle-free nodes (4-neighbour BFS written here, not qcpp.problem's)."""
    seen: set[Node] = set()
    comps = []
    for r in range(rows):
        for c in range(cols):
            if (r, c) in blocked or (r, c) in seen:
                continue
            comp, queue = [], deque([(r, c)])
            seen.add((r, c))
            while queue:
                n = queue.popleft()
                comp.append(n)
                for m in ((n[0] - 1, n[1]), (n[0] + 1, n[1]), (n[0], n[1] - 1), (n[0], n[1] + 1)):
                    if 0 <= m[0] < rows and 0 <= m[1] < cols and m not in blocked and m not in seen:
                        seen.add(m)
                        queue.append(m)
            comps.append(comp)
    return comps


@st.composite
def scenario_dicts(
    draw: st.DrawFn,
    min_size: int = 2,
    max_size: int = 6,
    max_robots: int = 3,
    tame_numbers: bool = True,
    names: bool = False,
) -> dict[str, Any]:
    """Random valid scenarios in the file format's dict form.

    Args:
        min_size, max_size: Range of ``rows`` and ``cols``.
        max_robots: Most robots drawn.
        tame_numbers: Weights, alphas and lengths in small ranges (for cost comparisons at 1e-9); otherwise
            any finite float (for the lossless round trip).
        names: Draw an arbitrary text ``name``.
    """
    rows = draw(st.integers(min_size, max_size), label="rows")
    cols = draw(st.integers(min_size, max_size), label="cols")
    nodes = [(r, c) for r in range(rows) for c in range(cols)]
    hard = draw(st.booleans(), label="hard")
    obstacles = draw(st.lists(st.sampled_from(nodes), unique=True, max_size=len(nodes) // 3), label="obstacles")
    blocked = set(obstacles)
    # robots can only be placed in components with at least two nodes (start != goal); in soft mode the
    # whole free node set is one "component" since paths may cross obstacles
    comps = _free_components(rows, cols, blocked) if hard else [[n for n in nodes if n not in blocked]]
    comps = [c for c in comps if len(c) >= 2]
    if not comps:  # all obstacles drawn away: drop them
        obstacles, blocked = [], set()
        comps = [nodes]
    comp_of = {n: i for i, c in enumerate(comps) for n in c}
    candidates = sorted(comp_of)
    n_robots = draw(st.integers(1, min(max_robots, len(candidates))), label="robots")
    starts = draw(st.lists(st.sampled_from(candidates), unique=True, min_size=n_robots, max_size=n_robots))
    robots = []
    for s in starts:
        goal = draw(st.sampled_from([n for n in comps[comp_of[s]] if n != s]))
        robots.append({"start": list(s), "goal": list(goal)})
    if tame_numbers:
        num = st.floats(-3, 3, allow_nan=False).map(lambda x: round(x, 3))
        pos = st.floats(0.25, 3, allow_nan=False).map(lambda x: round(x, 3))
    else:
        num = st.floats(allow_nan=False, allow_infinity=False)
        pos = st.floats(min_value=0, exclude_min=True, allow_infinity=False)
    edges = Grid(rows, cols).edges
    chosen = draw(st.lists(st.sampled_from(edges), unique=True, max_size=4), label="edge_lengths")
    objective = {
        "alpha": [draw(num) for _ in range(3)],
        "obstacle_weight": draw(num),
        "free_weight": draw(num),
        "edge_length": draw(pos),
        "edge_lengths": [[list(u), list(v), draw(pos)] for u, v in chosen],
        "obstacles": "hard" if hard else "soft",
        "balance": draw(st.sampled_from(["chain", "all-pairs"])),
        "degree_target": draw(st.sampled_from(["exact", "paper"])),
    }
    out: dict[str, Any] = {
        "grid": {"rows": rows, "cols": cols, "obstacles": [list(o) for o in obstacles]},
        "robots": robots,
        "objective": objective,
    }
    if names:
        out["name"] = draw(st.text(max_size=12))
    return out


@pytest.fixture(scope="session")
def build() -> Callable[..., Scenario]:
    """``build(rows, cols, [(start, goal), ...], obstacles=(), mode="soft", **objective)`` -> Scenario."""
    return make_scenario


@pytest.fixture(scope="session")
def scenario_dict_strategy() -> Callable[..., st.SearchStrategy[dict[str, Any]]]:
    """The :func:`scenario_dicts` strategy factory (keyword arguments as documented there)."""
    return scenario_dicts


@pytest.fixture(scope="session")
def random_scenarios() -> Callable[..., st.SearchStrategy[Scenario]]:
    """Strategy factory of validated :class:`Scenario` values (same keywords as :func:`scenario_dicts`)."""

    def factory(**kw: Any) -> st.SearchStrategy[Scenario]:
        return scenario_dicts(**kw).map(scenario_from_dict)

    return factory
