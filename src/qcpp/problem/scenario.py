"""Scenarios: a grid, robots with start and goal, obstacles, and the objective's settings.

A scenario is an immutable value. It is built from plain dicts (the file format's dict form), validates
everything on the way in (raising :class:`~qcpp.problem.errors.ScenarioError` naming the field), and converts
back losslessly (``scenario_from_dict(scenario_to_dict(s)) == s``). Files are read and written by
:mod:`qcpp.problem.scenario_io`.

Variable indexing (the data-qubit order of every circuit): the decision variable ``x[r, e]`` for robot
``r`` and grid edge ``e`` has index ``r * V + k``, where ``k`` is the position of ``e`` in
:attr:`Scenario.variable_edges` (grid edge indices in ascending order) and ``V`` their number. In ``soft``
obstacle mode every grid edge is a variable; in ``hard`` mode edges touching an obstacle are not.

Example:
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3, "obstacles": [[1, 1]]},
    ...                         "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> s.num_variables, s.objective.obstacles
    (12, 'soft')
    >>> scenario_from_dict(scenario_to_dict(s)) == s
    True
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Literal

import numpy as np

from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import Grid, Node
from qcpp.problem.limits import check_grid_size

ObstacleMode = Literal["soft", "hard"]
BalanceMode = Literal["chain", "all-pairs"]
DegreeTargetMode = Literal["exact", "paper"]


@dataclass(frozen=True)
class Robot:
    """One robot: it must travel a simple path from ``start`` to ``goal``."""

    start: Node
    goal: Node


@dataclass(frozen=True)
class Objective:
    """Settings of the cost ``c = alpha0*c1 + alpha1*c2 + alpha2*c3`` (see :mod:`qcpp.problem.cost`).

    Attributes:
        alpha: Weights ``(alpha0, alpha1, alpha2)`` of the coverage/obstacle, balance and degree terms.
        obstacle_weight: ``w_e`` on edges touching an obstacle (the paper: positive).
        free_weight: ``w_e`` on every other edge (the paper: negative).
        edge_length: Default length ``d_e`` of every edge.
        edge_lengths: Overrides ``((u, v), d)`` of single edges' lengths, sorted by edge.
        obstacles: ``soft`` (the paper: obstacle edges are variables that only cost) or ``hard`` (edges
            touching obstacles are removed from the variable set).
        balance: ``chain`` (the paper's equation: consecutive robots r, r+1) or ``all-pairs`` (the paper's
            text: every pair of robots).
        degree_target: ``exact`` (free node 2, endpoint nodes one per robot endpoint, obstacle nodes 0) or
            ``paper`` (every node 2 except start and goal nodes, which are left out of c3).
    """

    alpha: tuple[float, float, float] = (1.0, 1.0, 1.0)
    obstacle_weight: float = 1.0
    free_weight: float = -1.0
    edge_length: float = 1.0
    edge_lengths: tuple[tuple[tuple[Node, Node], float], ...] = ()
    obstacles: ObstacleMode = "soft"
    balance: BalanceMode = "chain"
    degree_target: DegreeTargetMode = "exact"


@dataclass(frozen=True)
class Scenario:
    """A complete coverage-path-planning instance: a grid, robots with their endpoints, obstacles and the
    objective. Build one with ``qcpp.grid_scenario`` (or ``qcpp.default_scenario``), read one with
    ``qcpp.load_scenario``; every way of building one validates it (so does the constructor), and it is immutable.

    Attributes:
        grid: The grid graph (:class:`~qcpp.problem.grid.Grid`): ``rows``, ``cols``, ``edges`` (node pairs, in the
            order of the variables: bit ``e`` of a path mask is ``grid.edges[e]``) and ``plaquettes`` (the unit
            squares a mixer move flips).
        robots: The robots, in order (robot ``r`` is the ``r``-th).
        obstacles: Obstacle nodes, sorted row-major.
        objective: The objective's settings.
        name: Optional free-text label.
    """

    grid: Grid
    robots: tuple[Robot, ...]
    obstacles: tuple[Node, ...] = ()
    objective: Objective = field(default_factory=Objective)
    name: str = ""

    def __post_init__(self) -> None:
        _validate(self)

    def _repr_svg_(self) -> str:
        """The grid drawn for notebooks (:func:`qcpp.problem.drawing.scenario_svg`)."""
        from qcpp.problem.drawing import scenario_svg

        return scenario_svg(self)

    # ----- derived data (cached; the dataclass is frozen so this never goes stale) -----

    @cached_property
    def obstacle_set(self) -> frozenset[Node]:
        return frozenset(self.obstacles)

    @cached_property
    def obstacle_edges(self) -> frozenset[int]:
        """Grid edge indices that touch an obstacle node."""
        return frozenset(
            i for i, (u, v) in enumerate(self.grid.edges) if u in self.obstacle_set or v in self.obstacle_set
        )

    @cached_property
    def variable_edges(self) -> tuple[int, ...]:
        """Grid edge indices that are decision variables (ascending)."""
        if self.objective.obstacles == "hard":
            return tuple(i for i in range(self.grid.num_edges) if i not in self.obstacle_edges)
        return tuple(range(self.grid.num_edges))

    @cached_property
    def variable_mask(self) -> int:
        """Bit mask over grid edges of :attr:`variable_edges`."""
        m = 0
        for e in self.variable_edges:
            m |= 1 << e
        return m

    @cached_property
    def _variable_position(self) -> dict[int, int]:
        return {e: k for k, e in enumerate(self.variable_edges)}

    @property
    def num_robots(self) -> int:
        """Robots (each one path to find)."""
        return len(self.robots)

    @property
    def edges_per_robot(self) -> int:
        return len(self.variable_edges)

    @property
    def num_variables(self) -> int:
        """Binary variables ``x[robot, edge]`` (the circuit's data qubits): robots times the edges each may use
        (every grid edge, less those touching a hard obstacle)."""
        return self.num_robots * self.edges_per_robot

    def variable_index(self, robot: int, edge: int) -> int:
        """Index of variable ``x[robot, edge]`` (``edge`` a grid edge index).

        Raises:
            KeyError: if ``edge`` is not a variable (touches an obstacle in hard mode).
        """
        try:
            return robot * self.edges_per_robot + self._variable_position[edge]
        except KeyError:
            raise KeyError(f"grid edge {edge} is not a decision variable in this scenario") from None

    def variable_of(self, index: int) -> tuple[int, int]:
        """Inverse of :meth:`variable_index`: ``(robot, grid edge)``."""
        r, k = divmod(index, self.edges_per_robot)
        return r, self.variable_edges[k]

    @cached_property
    def edge_weights(self) -> np.ndarray:
        """``w_e`` for every grid edge."""
        w = np.full(self.grid.num_edges, self.objective.free_weight, dtype=float)
        for e in self.obstacle_edges:
            w[e] = self.objective.obstacle_weight
        return w

    @cached_property
    def edge_lengths(self) -> np.ndarray:
        """``d_e`` for every grid edge."""
        d = np.full(self.grid.num_edges, self.objective.edge_length, dtype=float)
        for (u, v), length in self.objective.edge_lengths:
            d[self.grid.edge_index(u, v)] = length
        return d

    @cached_property
    def degree_targets(self) -> np.ndarray:
        """Target degree ``t_i`` of each node (row-major), NaN where the node is left out of ``c3``.

        ``exact``: obstacle nodes 0; a node that is the start or goal of ``k >= 1`` robots ``k``; every
        other node 2. ``paper``: every node 2, except start and goal nodes, which are left out (NaN).
        """
        g = self.grid
        t = np.full(g.num_nodes, 2.0)
        endpoint_count = np.zeros(g.num_nodes)
        for rb in self.robots:
            endpoint_count[g.node_index(rb.start)] += 1
            endpoint_count[g.node_index(rb.goal)] += 1
        if self.objective.degree_target == "paper":
            t[endpoint_count > 0] = np.nan
            return t
        for o in self.obstacles:
            t[g.node_index(o)] = 0.0
        mask = endpoint_count > 0
        t[mask] = endpoint_count[mask]
        return t


# ---------------------------------------------------------------- validation

def _validate(s: Scenario) -> None:
    g = s.grid
    for name, value in (("grid.rows", g.rows), ("grid.cols", g.cols)):
        if not isinstance(value, int) or isinstance(value, bool):
            raise ScenarioError(name, f"expected an integer, got {value!r}")
        if value < 2:
            raise ScenarioError(name, f"the grid must be at least 2x2, got {value}")
    check_grid_size(g.rows, g.cols)
    seen: set[Node] = set()
    for i, o in enumerate(s.obstacles):
        _check_node(g, o, f"grid.obstacles[{i}]")
        if o in seen:
            raise ScenarioError(f"grid.obstacles[{i}]", f"{o} is listed twice")
        seen.add(o)
    if list(s.obstacles) != sorted(s.obstacles):
        raise ScenarioError("grid.obstacles", "must be sorted row-major (use scenario_from_dict)")
    if not s.robots:
        raise ScenarioError("robots", "at least one robot is needed")
    free_nodes = g.num_nodes - len(s.obstacles)
    if len(s.robots) > free_nodes:
        raise ScenarioError(
            "robots", f"{len(s.robots)} robots do not fit on the {free_nodes} free nodes of the grid"
        )
    starts: dict[Node, int] = {}
    for r, rb in enumerate(s.robots):
        _check_node(g, rb.start, f"robots[{r}].start")
        _check_node(g, rb.goal, f"robots[{r}].goal")
        for key, node in (("start", rb.start), ("goal", rb.goal)):
            if node in s.obstacle_set:
                raise ScenarioError(f"robots[{r}].{key}", f"{node} is an obstacle")
        if rb.start == rb.goal:
            raise ScenarioError(f"robots[{r}].goal", f"equals the start {rb.start}; a path needs two ends")
        if rb.start in starts:
            raise ScenarioError(
                f"robots[{r}].start", f"{rb.start} is already robot {starts[rb.start]}'s start"
            )
        starts[rb.start] = r
    ob = s.objective
    if len(ob.alpha) != 3:
        raise ScenarioError("objective.alpha", f"expected 3 numbers, got {len(ob.alpha)}")
    for i, a in enumerate(ob.alpha):
        _check_number(a, f"objective.alpha[{i}]")
    _check_number(ob.obstacle_weight, "objective.obstacle_weight")
    _check_number(ob.free_weight, "objective.free_weight")
    _check_number(ob.edge_length, "objective.edge_length", positive=True)
    seen_edges: set[tuple[Node, Node]] = set()
    for i, ((u, v), d) in enumerate(ob.edge_lengths):
        _check_node(g, u, f"objective.edge_lengths[{i}]")
        _check_node(g, v, f"objective.edge_lengths[{i}]")
        if abs(u[0] - v[0]) + abs(u[1] - v[1]) != 1:
            raise ScenarioError(f"objective.edge_lengths[{i}]", f"{u} and {v} are not grid neighbours")
        _check_number(d, f"objective.edge_lengths[{i}]", positive=True)
        if u > v:
            raise ScenarioError(f"objective.edge_lengths[{i}]", f"write the edge as ({v}, {u}), row-major first")
        if (u, v) in seen_edges:
            raise ScenarioError(f"objective.edge_lengths[{i}]", f"the edge {u}-{v} is listed twice")
        seen_edges.add((u, v))
    if list(ob.edge_lengths) != sorted(ob.edge_lengths):
        raise ScenarioError("objective.edge_lengths", "must be sorted by edge (use scenario_from_dict)")
    for name, value, allowed in (
        ("objective.obstacles", ob.obstacles, ("soft", "hard")),
        ("objective.balance", ob.balance, ("chain", "all-pairs")),
        ("objective.degree_target", ob.degree_target, ("exact", "paper")),
    ):
        if value not in allowed:
            raise ScenarioError(name, f"expected one of {', '.join(map(repr, allowed))}, got {value!r}")
    if ob.obstacles == "hard":
        for r, rb in enumerate(s.robots):
            if not _reachable(g, s.obstacle_set, rb.start, rb.goal):
                raise ScenarioError(
                    f"robots[{r}].goal",
                    f"{rb.goal} cannot be reached from {rb.start} without crossing an obstacle (hard mode)",
                )


def _check_node(g: Grid, node: Any, name: str) -> None:
    if (
        not isinstance(node, tuple)
        or len(node) != 2
        or not all(isinstance(x, int) and not isinstance(x, bool) for x in node)
    ):
        raise ScenarioError(name, f"expected a node [row, col] of two integers, got {node!r}")
    if not g.contains(node):
        raise ScenarioError(name, f"{node} is outside the {g.rows}x{g.cols} grid")


def _check_number(x: Any, name: str, positive: bool = False) -> None:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
        raise ScenarioError(name, f"expected a finite number, got {x!r}")
    if positive and x <= 0:
        raise ScenarioError(name, f"must be positive, got {x!r}")


def _reachable(g: Grid, blocked: frozenset[Node], a: Node, b: Node) -> bool:
    seen = {a}
    queue = deque([a])
    while queue:
        n = queue.popleft()
        if n == b:
            return True
        for m in g.neighbours(n):
            if m not in seen and m not in blocked:
                seen.add(m)
                queue.append(m)
    return False


# ---------------------------------------------------------------- dict conversion

_TOP_KEYS = {"name", "grid", "robots", "objective"}
_GRID_KEYS = {"rows", "cols", "obstacles"}
_ROBOT_KEYS = {"start", "goal"}
_OBJECTIVE_KEYS = {
    "alpha",
    "obstacle_weight",
    "free_weight",
    "edge_length",
    "edge_lengths",
    "obstacles",
    "balance",
    "degree_target",
}


def _reject_unknown(d: Mapping[str, Any], allowed: set[str], where: str) -> None:
    for k in d:
        if k not in allowed:
            prefix = f"{where}." if where else ""
            hint = ", ".join(sorted(allowed))
            raise ScenarioError(f"{prefix}{k}", f"unknown key (allowed: {hint})")


def _mapping(x: Any, name: str) -> Mapping[str, Any]:
    if not isinstance(x, Mapping):
        raise ScenarioError(name, f"expected a table/object, got {type(x).__name__}")
    return x


def _node(x: Any, name: str) -> Node:
    if (
        not isinstance(x, Sequence)
        or isinstance(x, str)
        or len(x) != 2
        or not all(isinstance(v, int) and not isinstance(v, bool) for v in x)
    ):
        raise ScenarioError(name, f"expected a node [row, col] of two integers, got {x!r}")
    return (int(x[0]), int(x[1]))


def _int(x: Any, name: str) -> int:
    if isinstance(x, bool) or not isinstance(x, int):
        raise ScenarioError(name, f"expected an integer, got {x!r}")
    return x


def _float(x: Any, name: str) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        raise ScenarioError(name, f"expected a number, got {x!r}")
    try:
        return float(x)
    except OverflowError:  # an integer too large for a float (JSON allows any length)
        raise ScenarioError(name, f"expected a finite number, got an integer of {len(str(x))} digits") from None


def _str(x: Any, name: str) -> str:
    if not isinstance(x, str):
        raise ScenarioError(name, f"expected a string, got {x!r}")
    return x


def _list(x: Any, name: str) -> Sequence[Any]:
    if isinstance(x, str) or not isinstance(x, Sequence):
        raise ScenarioError(name, f"expected a list, got {x!r}")
    return x


def scenario_from_dict(data: Mapping[str, Any]) -> Scenario:
    """Build and validate a scenario from the file format's dict form.

    Args:
        data: ``{"grid": {"rows", "cols", "obstacles"?}, "robots": [{"start", "goal"}, ...],
            "objective"?: {...}, "name"?: str}`` (see ``examples/*.toml``).

    Returns:
        The validated :class:`Scenario`.

    Raises:
        ScenarioError: naming the first offending field.
    """
    data = _mapping(data, "scenario")
    _reject_unknown(data, _TOP_KEYS, "")
    if "grid" not in data:
        raise ScenarioError("grid", "missing (needs rows and cols)")
    grid_d = _mapping(data["grid"], "grid")
    _reject_unknown(grid_d, _GRID_KEYS, "grid")
    for k in ("rows", "cols"):
        if k not in grid_d:
            raise ScenarioError(f"grid.{k}", "missing")
    rows, cols = _int(grid_d["rows"], "grid.rows"), _int(grid_d["cols"], "grid.cols")
    if rows < 2 or cols < 2:
        field_name = "grid.rows" if rows < 2 else "grid.cols"
        raise ScenarioError(field_name, f"the grid must be at least 2x2, got {rows}x{cols}")
    check_grid_size(rows, cols)  # before anything of the grid's size is built
    obstacles = [
        _node(o, f"grid.obstacles[{i}]") for i, o in enumerate(_list(grid_d.get("obstacles", []), "grid.obstacles"))
    ]
    # per-entry checks here, before sorting, so that errors name the entry as written
    grid = Grid(rows, cols)
    for i, o in enumerate(obstacles):
        _check_node(grid, o, f"grid.obstacles[{i}]")
        if o in obstacles[:i]:
            raise ScenarioError(f"grid.obstacles[{i}]", f"{o} is listed twice")
    if "robots" not in data:
        raise ScenarioError("robots", "missing (at least one robot with start and goal)")
    robots = []
    for r, rd in enumerate(_list(data["robots"], "robots")):
        rd = _mapping(rd, f"robots[{r}]")
        _reject_unknown(rd, _ROBOT_KEYS, f"robots[{r}]")
        for k in ("start", "goal"):
            if k not in rd:
                raise ScenarioError(f"robots[{r}].{k}", "missing")
        robots.append(Robot(_node(rd["start"], f"robots[{r}].start"), _node(rd["goal"], f"robots[{r}].goal")))
    od = _mapping(data.get("objective", {}), "objective")
    _reject_unknown(od, _OBJECTIVE_KEYS, "objective")
    defaults = Objective()
    alpha = defaults.alpha
    if "alpha" in od:
        al = _list(od["alpha"], "objective.alpha")
        if len(al) != 3:
            raise ScenarioError("objective.alpha", f"expected 3 numbers (alpha0, alpha1, alpha2), got {len(al)}")
        alpha = tuple(_float(a, f"objective.alpha[{i}]") for i, a in enumerate(al))  # type: ignore[assignment]
    lengths = []
    for i, item in enumerate(_list(od.get("edge_lengths", []), "objective.edge_lengths")):
        name = f"objective.edge_lengths[{i}]"
        item = _list(item, name)
        if len(item) != 3:
            raise ScenarioError(name, f"expected [[row, col], [row, col], length], got {item!r}")
        u, v = _node(item[0], name), _node(item[1], name)
        _check_node(grid, u, name)
        _check_node(grid, v, name)
        if abs(u[0] - v[0]) + abs(u[1] - v[1]) != 1:
            raise ScenarioError(name, f"{u} and {v} are not grid neighbours")
        edge, length = (min(u, v), max(u, v)), _float(item[2], name)
        _check_number(length, name, positive=True)
        if any(e == edge for e, _ in lengths):
            raise ScenarioError(name, f"the edge {edge[0]}-{edge[1]} is listed twice")
        lengths.append((edge, length))
    objective = Objective(
        alpha=alpha,
        obstacle_weight=_float(od.get("obstacle_weight", defaults.obstacle_weight), "objective.obstacle_weight"),
        free_weight=_float(od.get("free_weight", defaults.free_weight), "objective.free_weight"),
        edge_length=_float(od.get("edge_length", defaults.edge_length), "objective.edge_length"),
        edge_lengths=tuple(sorted(lengths)),
        obstacles=_str(od.get("obstacles", defaults.obstacles), "objective.obstacles"),  # type: ignore[arg-type]
        balance=_str(od.get("balance", defaults.balance), "objective.balance"),  # type: ignore[arg-type]
        degree_target=_str(od.get("degree_target", defaults.degree_target), "objective.degree_target"),  # type: ignore[arg-type]
    )
    name = _str(data.get("name", ""), "name")
    return Scenario(grid, tuple(robots), tuple(sorted(obstacles)), objective, name)


def scenario_to_dict(s: Scenario) -> dict[str, Any]:
    """The file format's dict form of ``s`` (every objective setting written out).

    ``scenario_from_dict(scenario_to_dict(s)) == s`` for every scenario.
    """
    ob = s.objective
    out: dict[str, Any] = {}
    if s.name:
        out["name"] = s.name
    out["grid"] = {"rows": s.grid.rows, "cols": s.grid.cols, "obstacles": [list(o) for o in s.obstacles]}
    out["robots"] = [{"start": list(rb.start), "goal": list(rb.goal)} for rb in s.robots]
    out["objective"] = {
        "alpha": [float(a) for a in ob.alpha],
        "obstacle_weight": float(ob.obstacle_weight),
        "free_weight": float(ob.free_weight),
        "edge_length": float(ob.edge_length),
        "edge_lengths": [[list(u), list(v), float(d)] for (u, v), d in ob.edge_lengths],
        "obstacles": ob.obstacles,
        "balance": ob.balance,
        "degree_target": ob.degree_target,
    }
    return out
