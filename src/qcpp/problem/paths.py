"""Robot paths as edge bit-sets.

A path is an ``int`` bit mask over *grid* edge indices (bit ``e`` set = the robot uses edge ``e``): the
decision variables ``x[r, e]`` of one robot. Masks are hashable, cheap to flip (``mask ^ plaquette``) and
convert to variable bit vectors with :func:`path_bits`.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
    >>> p = initial_path(s, 0)
    >>> path_to_nodes(s.grid, p, (0, 0))
    [(0, 0), (0, 1), (1, 1)]
    >>> is_feasible(s, 0, p), len(enumerate_paths(s, 0))
    (True, 2)
"""

from __future__ import annotations

import itertools
from collections import deque
from collections.abc import Iterable, Iterator, Sequence

import numpy as np

from qcpp.problem.grid import Grid, Node
from qcpp.problem.scenario import Scenario


def path_from_nodes(grid: Grid, nodes: Sequence[Node]) -> int:
    """Edge mask of the walk through ``nodes`` (consecutive nodes must be 4-neighbours).

    Raises:
        ValueError: if two consecutive nodes are not neighbours.
    """
    mask = 0
    for u, v in zip(nodes, nodes[1:]):
        try:
            mask |= 1 << grid.edge_index(u, v)
        except KeyError as exc:
            raise ValueError(str(exc.args[0])) from None
    return mask


def edges_of(mask: int) -> list[int]:
    """Grid edge indices set in ``mask`` (ascending)."""
    out = []
    while mask:
        low = mask & -mask
        out.append(low.bit_length() - 1)
        mask ^= low
    return out


def path_to_nodes(grid: Grid, mask: int, start: Node) -> list[Node]:
    """Walk the edges of ``mask`` from ``start`` and return the node sequence.

    Raises:
        ValueError: if the edges are not exactly one simple path beginning at ``start``.
    """
    adj: dict[Node, list[Node]] = {}
    for e in edges_of(mask):
        u, v = grid.edges[e]
        adj.setdefault(u, []).append(v)
        adj.setdefault(v, []).append(u)
    if not adj:
        raise ValueError("the path has no edges")
    if len(adj.get(start, [])) != 1:
        raise ValueError(f"the start {start} does not have exactly one path edge")
    nodes = [start]
    prev, cur = None, start
    while True:
        nxt = [n for n in adj[cur] if n != prev]
        if len(adj[cur]) > 2:
            raise ValueError(f"node {cur} has {len(adj[cur])} path edges")
        if not nxt:
            break
        prev, cur = cur, nxt[0]
        if cur in nodes:
            raise ValueError(f"the path revisits {cur}")
        nodes.append(cur)
    if len(nodes) - 1 != mask.bit_count():
        raise ValueError("the edges do not form one connected path")
    return nodes


def is_feasible(scenario: Scenario, robot: int, mask: int) -> bool:
    """Whether ``mask`` is a simple path from the robot's start to its goal.

    Feasible means: connected, no loop, no backtracking, no node or edge visited twice, and (hard obstacle
    mode) no edge touching an obstacle.
    """
    if mask & ~scenario.variable_mask:
        return False
    rb = scenario.robots[robot]
    grid = scenario.grid
    inc = grid.incident_edges
    start, goal = grid.node_index(rb.start), grid.node_index(rb.goal)
    for e in edges_of(mask):
        for n in grid.edge_nodes[e]:
            deg = sum((mask >> f) & 1 for f in inc[n])
            if deg != (1 if n in (start, goal) else 2):
                return False
    for n in (start, goal):
        if sum((mask >> f) & 1 for f in inc[n]) != 1:
            return False
    # Degrees are now 1 at the ends and 2 elsewhere, so the walk from the start ends at the goal;
    # it covers every edge only if there is no separate cycle.
    cur, prev_edge, steps = start, -1, 0
    while cur != goal:
        e = next(f for f in inc[cur] if (mask >> f) & 1 and f != prev_edge)
        a, b = grid.edge_nodes[e]
        cur, prev_edge, steps = (b if a == cur else a), e, steps + 1
    return steps == mask.bit_count()


def initial_path(scenario: Scenario, robot: int) -> int:
    """The paper's trivial initial path: horizontally to the goal's column, then vertically to the goal.

    Where that path crosses an obstacle in ``hard`` mode, the fallback is the shortest obstacle-free path
    found by breadth-first search with the fixed neighbour order up, left, right, down (so the result is
    deterministic).
    """
    rb = scenario.robots[robot]
    (r0, c0), (r1, c1) = rb.start, rb.goal
    step_c = 1 if c1 >= c0 else -1
    step_r = 1 if r1 >= r0 else -1
    nodes = [(r0, c) for c in range(c0, c1 + step_c, step_c)]
    nodes += [(r, c1) for r in range(r0 + step_r, r1 + step_r, step_r)]
    mask = path_from_nodes(scenario.grid, nodes)
    # the L-shaped walk is a simple path by construction: feasible unless an edge is not a variable (hard mode)
    if rb.start != rb.goal and not mask & ~scenario.variable_mask:
        return mask
    return shortest_path(scenario, robot)


def shortest_path(scenario: Scenario, robot: int) -> int:
    """A shortest feasible path by BFS (neighbour order up, left, right, down)."""
    rb = scenario.robots[robot]
    grid = scenario.grid
    blocked = scenario.obstacle_set if scenario.objective.obstacles == "hard" else frozenset()
    parent: dict[Node, Node | None] = {rb.start: None}
    queue = deque([rb.start])
    while queue:
        n = queue.popleft()
        if n == rb.goal:
            break
        for m in grid.neighbours(n):
            if m not in parent and m not in blocked:
                parent[m] = n
                queue.append(m)
    nodes: list[Node] = [rb.goal]
    while (p := parent[nodes[-1]]) is not None:
        nodes.append(p)
    return path_from_nodes(grid, nodes[::-1])


def enumerate_paths(scenario: Scenario, robot: int) -> list[int]:
    """All feasible (simple start-goal) paths of one robot, by depth-first search.

    The order is the DFS order with neighbours tried up, left, right, down; it is deterministic.
    """
    return list(iter_paths(scenario, robot))


def iter_paths(scenario: Scenario, robot: int) -> Iterator[int]:
    """The paths of :func:`enumerate_paths`, in the same order, one at a time (nothing is kept)."""
    rb = scenario.robots[robot]
    grid = scenario.grid
    n_nodes = grid.num_nodes
    blocked = [False] * n_nodes
    if scenario.objective.obstacles == "hard":
        for o in scenario.obstacles:
            blocked[grid.node_index(o)] = True
    # adjacency as (neighbour node index, edge index) pairs in the documented order
    adj: list[list[tuple[int, int]]] = []
    for node in grid.nodes:
        adj.append([(grid.node_index(m), grid.edge_index(node, m)) for m in grid.neighbours(node)])
    start, goal = grid.node_index(rb.start), grid.node_index(rb.goal)
    visited = [False] * n_nodes
    visited[start] = True
    # iterative DFS: stack of (node, mask, iterator position)
    stack: list[tuple[int, int, int]] = [(start, 0, 0)]
    while stack:
        node, mask, pos = stack.pop()
        if pos < len(adj[node]):
            stack.append((node, mask, pos + 1))
            m, e = adj[node][pos]
            if visited[m] or blocked[m]:
                continue
            if m == goal:
                yield mask | (1 << e)
                continue
            visited[m] = True
            stack.append((m, mask | (1 << e), 0))
        else:
            visited[node] = False


def count_paths(scenario: Scenario, robot: int, cap: int | None = None) -> int:
    """How many paths :func:`enumerate_paths` gives, counting no further than ``cap``.

    Args:
        cap: Stop counting here (``None``: count them all). The work is proportional to the count returned.

    Returns:
        ``min(number of paths, cap)``.

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> count_paths(default_scenario(4, 4, 1), 0), count_paths(default_scenario(4, 4, 1), 0, cap=100)
        (184, 100)
    """
    return sum(1 for _ in itertools.islice(iter_paths(scenario, robot), cap))


def path_bits(scenario: Scenario, mask: int) -> np.ndarray:
    """The robot's variable bit vector (length ``edges_per_robot``, dtype uint8) of an edge mask."""
    return np.array([(mask >> e) & 1 for e in scenario.variable_edges], dtype=np.uint8)


def paths_matrix(scenario: Scenario, masks: Iterable[int]) -> np.ndarray:
    """Stack :func:`path_bits` of many masks: shape ``(len(masks), edges_per_robot)``, uint8."""
    ve = np.array(scenario.variable_edges, dtype=np.int64)
    masks = list(masks)
    if not masks:
        return np.zeros((0, len(ve)), dtype=np.uint8)
    # split big ints into 62-bit chunks so numpy can do the shifting
    n_chunks = (scenario.grid.num_edges + 61) // 62
    chunks = np.array([[(m >> (62 * k)) & ((1 << 62) - 1) for k in range(n_chunks)] for m in masks], dtype=np.int64)
    return ((chunks[:, ve // 62] >> (ve % 62)) & 1).astype(np.uint8)


def mask_from_bits(scenario: Scenario, bits: Sequence[int]) -> int:
    """Inverse of :func:`path_bits`."""
    mask = 0
    for b, e in zip(bits, scenario.variable_edges):
        if b:
            mask |= 1 << e
    return mask


def assignment_bits(scenario: Scenario, masks: Sequence[int]) -> np.ndarray:
    """All robots' variables as one bit vector in variable-index order (see :mod:`qcpp.problem.scenario`)."""
    if len(masks) != scenario.num_robots:
        raise ValueError(f"expected {scenario.num_robots} paths, got {len(masks)}")
    return np.concatenate([path_bits(scenario, m) for m in masks])


def assignment_from_bits(scenario: Scenario, bits: Sequence[int]) -> tuple[int, ...]:
    """Inverse of :func:`assignment_bits`: one edge mask per robot."""
    v = scenario.edges_per_robot
    return tuple(mask_from_bits(scenario, bits[r * v : (r + 1) * v]) for r in range(scenario.num_robots))
