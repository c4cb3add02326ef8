"""``qcpp.decode_counts``: measured bitstrings of the data register read back as robot paths, feasibility and cost.

A circuit exported with measurements (``Compiled.to_qiskit(measure=True)``, ``to_qasm(..., measure=True)``,
``qcpp compile --measure``) reads data qubit ``i`` (variable ``i``: robot ``r = i // V``, its ``k``-th variable
edge, :meth:`qcpp.Scenario.variable_of`) into classical bit ``i``, so a sampler's counts
(``result[0].data.meas.get_counts()``, Qiskit's convention: clbit 0 rightmost) are keyed by the data register as
it is. Each outcome is turned into one edge set per robot (:func:`qcpp.problem.paths.assignment_from_bits`),
checked for feasibility per robot (:func:`qcpp.problem.paths.is_feasible`: a simple path from its start to its
goal) and costed by the scenario's objective (:func:`qcpp.problem.cost.cost_parts_bits`, defined on every bit
string; read it as a path cost only where the outcome is feasible).

Example:
    >>> import qcpp
    >>> s = qcpp.grid_scenario(2, 2, robots=1)
    >>> d = qcpp.decode_counts(s, {"0101": 60, "1010": 30, "1111": 10}, optimum=qcpp.solve(s))
    >>> d.shots, d.feasible_share, d.best.nodes, d.p_optimum
    (100, 0.9, (((0, 0), (0, 1), (1, 1)),), 0.9)
    >>> d.outcomes[2].feasible, d.outcomes[2].nodes
    (False, (None,))
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from qcpp.api.checks import check_scenario_arg
from qcpp.api.scenarios import Scenario
from qcpp.errors import OptionError
from qcpp.problem.grid import Node

__all__ = ["DecodedCounts", "Outcome", "decode_counts"]

OPTIMUM_TOL = 1e-9
"""An outcome is optimal where it is feasible and its cost is at most ``optimum + OPTIMUM_TOL * max(1, |optimum|)``
(the tolerance :func:`qcpp.training.evaluate.feasible_assignments` marks the optimal assignments with)."""


@dataclass(frozen=True)
class Outcome:
    """One measured bitstring of the data register, read as robot paths.

    Attributes:
        bits: The data register as counted, clbit (variable) 0 rightmost.
        shots: How many shots gave it.
        paths: Per robot, its edges as an edge mask over the grid's edge numbers (bit ``e``: grid edge ``e``;
            qcpp's path value, :mod:`qcpp.problem.paths`).
        edges: Per robot, its edges as node pairs ``((row, col), (row, col))``, by edge number.
        nodes: Per robot, the walk from its start to its goal where its edges are a feasible path, else ``None``.
        feasible: Every robot's edges are a feasible path (a simple path from its start to its goal).
        cost: The objective's total on these bits (``c = alpha0 c1 + alpha1 c2 + alpha2 c3``).
        optimal: Feasible with the optimum's cost (``None``: no optimum given).
    """

    bits: str
    shots: int
    paths: tuple[int, ...]
    edges: tuple[tuple[tuple[Node, Node], ...], ...]
    nodes: tuple[tuple[Node, ...] | None, ...]
    feasible: bool
    cost: float
    optimal: bool | None

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict (nodes and edges as lists)."""
        return {
            "bits": self.bits, "shots": self.shots, "feasible": self.feasible, "cost": self.cost,
            "optimal": self.optimal, "edges": [[[list(u), list(v)] for u, v in es] for es in self.edges],
            "nodes": [None if ns is None else [list(n) for n in ns] for ns in self.nodes],
        }  # fmt: skip


@dataclass(frozen=True)
class DecodedCounts:
    """Measured counts decoded (:func:`decode_counts`).

    Attributes:
        outcomes: Every distinct outcome measured (one shot or more), most shots first (ties: by bits).
        shots: The shots counted.
        feasible_share: The share of shots whose outcome is feasible.
        best: The feasible outcome of lowest cost (ties: most shots), or ``None`` where no shot was feasible.
        optimum: The optimal cost given, or ``None``.
        p_optimum: The share of shots whose outcome is optimal (``None``: no optimum given).
    """

    outcomes: tuple[Outcome, ...]
    shots: int
    feasible_share: float
    best: Outcome | None
    optimum: float | None
    p_optimum: float | None

    @property
    def best_cost(self) -> float | None:
        """The cost of :attr:`best` (``None``: no feasible shot)."""
        return None if self.best is None else self.best.cost

    def __repr__(self) -> str:
        """The summary, not the outcomes (thousands of them after a hardware run; :meth:`to_dict` has them all).

        Example:
            >>> import qcpp
            >>> s = qcpp.grid_scenario(2, 2, robots=1)
            >>> qcpp.decode_counts(s, {"0101": 60, "1010": 30, "1111": 10}, optimum=qcpp.solve(s))
            DecodedCounts(shots=100, outcomes=3, feasible_share=0.9, best_cost=2, p_optimum=0.9)
        """
        return (
            f"DecodedCounts(shots={self.shots}, outcomes={len(self.outcomes)}, "
            f"feasible_share={self.feasible_share:.4g}, "
            f"best_cost={self.best_cost if self.best_cost is None else format(self.best_cost, '.6g')}, "
            f"p_optimum={self.p_optimum if self.p_optimum is None else format(self.p_optimum, '.4g')})"
        )

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict: the summary and every outcome."""
        return {
            "shots": self.shots, "feasible_share": self.feasible_share, "best_cost": self.best_cost,
            "optimum": self.optimum, "p_optimum": self.p_optimum, "outcomes": [o.to_dict() for o in self.outcomes],
        }  # fmt: skip


def _optimum_value(optimum: object) -> float | None:
    if optimum is None:
        return None
    total = getattr(getattr(optimum, "cost", None), "total", None)  # a qcpp Solution (qcpp.solve)
    value = total if total is not None else optimum
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise OptionError("optimum", f"expected the optimal cost (a number, or qcpp.solve's answer), got {optimum!r}")
    return float(value)


def _register(key: object, n: int) -> int:
    """The data-register integer of one counts key (``'0101'``, ``'0x5'`` or an int)."""
    if isinstance(key, (int,)) and not isinstance(key, bool):
        value = key
    elif isinstance(key, str) and key.startswith("0x"):
        try:
            value = int(key, 16)
        except ValueError:
            raise OptionError("counts", f"key {key!r} is not a hexadecimal register value") from None
    elif isinstance(key, str) and len(key) == n and set(key) <= {"0", "1"}:
        return int(key, 2)
    else:
        raise OptionError(
            "counts",
            f"key {key!r} is not a bitstring of the {n} data bits (clbit 0 rightmost, one register: measure the "
            "circuit with measure=True and count its 'meas' register)",
        )
    if not 0 <= value < 1 << n:
        raise OptionError("counts", f"key {key!r} is outside the {n}-bit data register")
    return value


def decode_counts(scenario: Scenario, counts: Any, *, optimum: Any = None) -> DecodedCounts:
    """Decode measured counts of the data register into robot paths, feasibility and cost (module docs).

    Args:
        scenario: The scenario compiled.
        counts: Outcome -> shots: a dict or Qiskit ``Counts`` keyed by bitstrings of ``scenario.num_variables``
            bits (clbit 0 rightmost), hexadecimal strings (``'0x1f'``) or register integers; or anything with
            ``get_counts()`` (a ``SamplerV2`` result's ``BitArray``, ``result[0].data.meas``).
        optimum: The optimal cost (a number, or the answer of :func:`qcpp.solve`, whose ``cost.total`` is taken), for
            :attr:`DecodedCounts.p_optimum`; ``None``: not computed.

    Returns:
        The :class:`DecodedCounts`.

    Raises:
        qcpp.errors.OptionError: a key that is not a register value of the data bits, a negative or non-integer
            count, no shots, or a bad ``optimum``.
    """
    import numpy as np

    from qcpp.problem.cost import cost_parts_bits
    from qcpp.problem.paths import assignment_from_bits, edges_of, is_feasible, path_to_nodes

    s = check_scenario_arg(scenario)
    if hasattr(counts, "get_counts") and not isinstance(counts, Mapping):
        counts = counts.get_counts()
    if not isinstance(counts, Mapping):
        raise OptionError("counts", f"expected a mapping of outcomes to shots, got {type(counts).__name__}")
    best_value = _optimum_value(optimum)
    n = s.num_variables
    merged: dict[int, int] = {}
    for key, shots in counts.items():
        if isinstance(shots, bool) or not isinstance(shots, (int, np.integer)) or shots < 0:
            raise OptionError("counts", f"shots of {key!r} must be a non-negative integer, got {shots!r}")
        value = _register(key, n)
        merged[value] = merged.get(value, 0) + int(shots)
    merged = {v: k for v, k in merged.items() if k}  # an outcome listed at 0 shots was never measured
    total = sum(merged.values())
    if total == 0:
        raise OptionError("counts", "no shots")
    values = sorted(merged, key=lambda v: (-merged[v], v))
    bits = np.array([[(v >> i) & 1 for i in range(n)] for v in values], dtype=np.uint8).reshape(len(values), n)
    costs = cost_parts_bits(s, bits)[:, 3] if values else np.zeros(0)
    grid = s.grid
    limit = None if best_value is None else best_value + OPTIMUM_TOL * max(1.0, abs(best_value))
    outcomes = []
    for row, v, c in zip(bits, values, costs):
        paths = assignment_from_bits(s, row)
        ok = [is_feasible(s, r, m) for r, m in enumerate(paths)]
        nodes = tuple(tuple(path_to_nodes(grid, m, s.robots[r].start)) if good else None
                      for r, (m, good) in enumerate(zip(paths, ok)))  # fmt: skip
        edges = tuple(tuple(grid.edges[e] for e in edges_of(m)) for m in paths)
        feasible = all(ok)
        optimal = None if limit is None else feasible and float(c) <= limit
        outcomes.append(Outcome(format(v, f"0{n}b"), merged[v], paths, edges, nodes, feasible, float(c), optimal))
    feasible_shots = sum(o.shots for o in outcomes if o.feasible)
    feasibles = [o for o in outcomes if o.feasible]
    best = min(feasibles, key=lambda o: (o.cost, -o.shots, o.bits)) if feasibles else None
    p_opt = None if limit is None else sum(o.shots for o in outcomes if o.optimal) / total
    return DecodedCounts(tuple(outcomes), total, feasible_shots / total, best, best_value, p_opt)
