"""Solve a scenario on its QUBO with a local annealer: sample, decode, drop cycles, check, polish with SBF moves.

The pipeline (``qcpp solve --method qubo``):

1. Build the ``per-robot`` model (:func:`qcpp.qubo.model.per_robot_bqm`, penalty from
   :func:`qcpp.qubo.model.penalty_rule` unless given) and sample it with dwave-samplers' simulated annealing
   (``sa``) or tabu search (``tabu``): optional dependencies, ``pip install 'qcpp[annealing]'``.
2. Decode every read into one edge set per robot (:func:`qcpp.qubo.model.decode_edges`).
3. A read is **feasible** if every robot's edges are a simple start-goal path
   (:func:`qcpp.problem.paths.is_feasible`), **repairable** if every robot's degrees are right (1 at its ends, 0 or 2
   elsewhere: a path plus separate cycles, which degree penalties cannot tell from a path) -- dropping the
   cycles (:func:`drop_cycles`) then leaves a feasible path. Feasible reads are repairable too.
4. The distinct repaired assignments, best first (at most ``polish`` of them), are polished by steepest descent
   with SBF moves (:func:`qcpp.problem.solvers.descent.steepest_descent`); the best result is the answer.

Reported (:class:`QuboRun`): reads, feasible, repairable, how many reads were at the answer's cost before any
polishing (``at_best``), the lowest sampled energy, and the time spent sampling.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> run = solve_qubo(default_scenario(3, 3, 1), reads=20)           # doctest: +SKIP
    >>> run.solution.cost.total                                         # doctest: +SKIP
    -8.0
"""

from __future__ import annotations

import time
from collections import Counter
from dataclasses import dataclass
from typing import Literal

import numpy as np

from qcpp.errors import MissingExtraError, missing_extra
from qcpp.problem.cost import cost_parts
from qcpp.problem.paths import edges_of, is_feasible
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers.descent import steepest_descent
from qcpp.problem.solvers.moves import CostCache, MoveSpace
from qcpp.problem.solvers.result import ProgressFn, Solution
from qcpp.qubo.model import Bqm, decode_edges, per_robot_bqm, to_dimod

__all__ = [
    "INSTALL_HINT",
    "SAMPLERS",
    "MissingAnnealer",
    "QuboRun",
    "drop_cycles",
    "require_annealer",
    "sample_bqm",
    "solve_qubo",
]

Sampler = Literal["sa", "tabu"]
SAMPLERS: tuple[Sampler, ...] = ("sa", "tabu")

INSTALL_HINT = "pip install 'qcpp[annealing]'"
"""What to install for the annealers (dimod and dwave-samplers)."""

DEFAULT_READS = 100
DEFAULT_SWEEPS = 1000
DEFAULT_TABU_RESTARTS = 0
DEFAULT_TABU_MS = 10_000
DEFAULT_POLISH = 100


class MissingAnnealer(MissingExtraError):
    """dimod or dwave-samplers is not installed (a ``ValueError``: the CLI prints it as one line, exit 2; and an
    ``ImportError``)."""


def require_annealer() -> None:
    """Raise :class:`MissingAnnealer` naming what to install unless dimod and dwave-samplers import."""
    try:
        import dimod  # noqa: F401
        import dwave.samplers  # noqa: F401
    except ImportError as exc:
        raise MissingAnnealer(str(missing_extra("the qubo method", "dimod and dwave-samplers", "annealing",
                                                exc.name))) from None  # fmt: skip


def drop_cycles(scenario: Scenario, robot: int, mask: int) -> int | None:
    """The robot's start-goal path inside ``mask`` when ``mask`` is that path plus separate cycles, else ``None``.

    Right degrees (1 at the robot's ends, 0 or 2 elsewhere) mean exactly that: the walk from the start ends at
    the goal and every other edge lies on a cycle touching no path node.

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> from qcpp.problem.paths import path_from_nodes
        >>> s = default_scenario(3, 4, 1)   # (0, 0) -> (2, 3)
        >>> g = s.grid
        >>> path = path_from_nodes(g, [(0, 0), (1, 0), (2, 0), (2, 1), (2, 2), (2, 3)])
        >>> ring = path_from_nodes(g, [(0, 1), (0, 2), (1, 2), (1, 1), (0, 1)])
        >>> drop_cycles(s, 0, path | ring) == path
        True
    """
    g = scenario.grid
    rb = scenario.robots[robot]
    inc = g.incident_edges
    ends = (g.node_index(rb.start), g.node_index(rb.goal))
    deg = Counter(n for e in edges_of(mask) for n in g.edge_nodes[e])
    for n in ends:
        if deg.get(n, 0) != 1:
            return None
    if any(d != 2 for n, d in deg.items() if n not in ends):
        return None
    cur, prev, path = ends[0], -1, 0
    while cur != ends[1]:
        nxt = next(f for f in inc[cur] if (mask >> f) & 1 and f != prev)
        a, b = g.edge_nodes[nxt]
        path |= 1 << nxt
        cur, prev = (b if a == cur else a), nxt
    return path if is_feasible(scenario, robot, path) else None


def sample_bqm(
    model: Bqm,
    *,
    sampler: Sampler = "tabu",
    reads: int = DEFAULT_READS,
    sweeps: int = DEFAULT_SWEEPS,
    tabu_restarts: int = DEFAULT_TABU_RESTARTS,
    tabu_ms: int = DEFAULT_TABU_MS,
    seed: int = 0,
) -> tuple[np.ndarray, np.ndarray]:
    """Sample ``model`` with dwave-samplers: ``(bits (reads, n) in the model's variable order, energies)``.

    Tabu search is bounded by ``tabu_restarts`` restarts per read, not by time, so a seed gives the same samples
    on any machine; ``tabu_ms`` is only a safety cap per read.

    Raises:
        MissingAnnealer: without dimod / dwave-samplers.
        ValueError: on an unknown sampler or a non-positive count.
    """
    require_annealer()
    from dwave.samplers import SimulatedAnnealingSampler, TabuSampler

    if sampler not in SAMPLERS:
        raise ValueError(f"unknown sampler {sampler!r} (expected one of {', '.join(SAMPLERS)})")
    for name, value, low in (("reads", reads, 1), ("sweeps", sweeps, 1), ("tabu_ms", tabu_ms, 1),
                             ("tabu_restarts", tabu_restarts, 0)):
        if value < low:
            raise ValueError(f"{name} must be at least {low}, got {value}")
    bqm = to_dimod(model)
    seed32 = int(seed) % (2**32)
    if sampler == "sa":
        ss = SimulatedAnnealingSampler().sample(bqm, num_reads=reads, num_sweeps=sweeps, seed=seed32)
    else:
        ss = TabuSampler().sample(bqm, num_reads=reads, timeout=tabu_ms, num_restarts=tabu_restarts, seed=seed32)
    bits = ss.record.sample
    order = [ss.variables.index(lab) for lab in model.labels]
    out = np.repeat(bits[:, order], ss.record.num_occurrences, axis=0).astype(np.uint8)
    energies = np.repeat(ss.record.energy, ss.record.num_occurrences)
    return out, energies


@dataclass(frozen=True)
class QuboRun:
    """One :func:`solve_qubo` run.

    Attributes:
        solution: The answer (polished; ``method="qubo"``).
        reads: Reads sampled.
        feasible: Reads whose decoded edges were feasible paths as sampled.
        repairable: Reads feasible after dropping cycles (feasible ones included).
        at_best: Reads whose repaired cost already equalled the answer's cost (before polishing).
        best_read_cost: Best repaired read's cost before polishing (``None`` if no read was repairable).
        lowest_energy: Lowest sampled energy.
        penalty: The degree penalty ``P`` of the model.
        sampler: ``sa`` or ``tabu``.
        sample_seconds: Time spent in the sampler.
    """

    solution: Solution
    reads: int
    feasible: int
    repairable: int
    at_best: int
    best_read_cost: float | None
    lowest_energy: float
    penalty: float
    sampler: str
    sample_seconds: float


def solve_qubo(
    scenario: Scenario,
    *,
    penalty: float | None = None,
    sampler: Sampler = "tabu",
    reads: int = DEFAULT_READS,
    sweeps: int = DEFAULT_SWEEPS,
    tabu_restarts: int = DEFAULT_TABU_RESTARTS,
    tabu_ms: int = DEFAULT_TABU_MS,
    polish: int = DEFAULT_POLISH,
    seed: int = 0,
    rule: str = "exact",
    progress: ProgressFn | None = None,
) -> QuboRun:
    """Sample the ``per-robot`` QUBO, decode, drop cycles, polish (see the module docstring).

    Args:
        penalty: Degree penalty ``P`` (``None``: :func:`qcpp.qubo.model.penalty_rule`).
        sampler: ``sa`` (simulated annealing, ``sweeps`` per read) or ``tabu`` (``tabu_restarts`` per read).
        reads: Number of reads.
        sweeps: Simulated-annealing sweeps per read.
        tabu_restarts: Tabu search restarts per read (0: one tabu run per read).
        tabu_ms: Safety cap on one tabu read's time (milliseconds; see :func:`sample_bqm`).
        polish: How many distinct repaired assignments (best first) to polish with SBF moves (0: none).
        seed: Sampler seed.
        rule: SBF rule of the polishing moves.
        progress: Called as ``progress(done, 3)`` after building, sampling and polishing.

    Returns:
        A :class:`QuboRun`. When no read is repairable the answer starts from the initial paths (noted).

    Raises:
        MissingAnnealer: without dimod / dwave-samplers.
    """
    require_annealer()
    t0 = time.perf_counter()
    model = per_robot_bqm(scenario, penalty)
    if progress is not None:
        progress(1, 3)
    t1 = time.perf_counter()
    bits, energies = sample_bqm(model, sampler=sampler, reads=reads, sweeps=sweeps, tabu_restarts=tabu_restarts,
                                tabu_ms=tabu_ms, seed=seed)
    sample_seconds = time.perf_counter() - t1
    if progress is not None:
        progress(2, 3)
    feasible = repairable = 0
    repaired: list[tuple[int, ...]] = []
    for row in bits:
        masks = decode_edges(scenario, model, row)
        if all(is_feasible(scenario, r, m) for r, m in enumerate(masks)):
            feasible += 1
        fixed = tuple(drop_cycles(scenario, r, m) for r, m in enumerate(masks))
        if all(m is not None for m in fixed):
            repairable += 1
            repaired.append(fixed)  # type: ignore[arg-type]
    space = MoveSpace(scenario, rule, "initial")  # type: ignore[arg-type]
    cost = CostCache(scenario)
    read_costs = [cost(a) for a in repaired]
    notes = [f"per-robot QUBO, penalty P = {model.penalty:g}, {model.num_variables} variables, {sampler}"]
    candidates = sorted(set(zip(read_costs, repaired)))[: max(polish, 1)]
    if not candidates:
        notes.append("no read was repairable: started from the initial paths instead")
        start = space.starts()[0]
        candidates = [(cost(start), start)]
    best_cost, best = candidates[0]
    scored = 0  # by the polish, besides the cost cache's lookups
    if polish:
        for _, start in candidates:
            cand, _, n = steepest_descent(scenario, start, space)
            scored += n
            c = cost(cand)
            if c < best_cost - 1e-12:
                best, best_cost = cand, c
    at_best = sum(1 for c in read_costs if abs(c - best_cost) <= 1e-9)
    if progress is not None:
        progress(3, 3)
    sol = Solution(
        method="qubo",
        paths=best,
        cost=cost_parts(scenario, best),
        seconds=time.perf_counter() - t0,
        evaluated=cost.calls + scored,
        seed=seed,
        rule=rule if polish else None,
        notes=(
            *notes,
            f"{reads} reads: {feasible} feasible, {repairable} repairable (cycles dropped), "
            f"{at_best} at the answer's cost before polishing",
        ),
    )
    return QuboRun(
        solution=sol,
        reads=len(bits),
        feasible=feasible,
        repairable=repairable,
        at_best=at_best,
        best_read_cost=min(read_costs) if read_costs else None,
        lowest_energy=float(energies.min()),
        penalty=float(model.penalty or 0.0),
        sampler=sampler,
        sample_seconds=sample_seconds,
    )
