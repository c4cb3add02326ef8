"""The search space of the local-search solvers: SBF moves, move-graph components and a cost cache.

:class:`MoveSpace` gives, for one robot and one path, the paths one *allowed* SBF flip away (the rule's
compiled :class:`~qcpp.problem.sbf.SbfLogic` decides, exactly as the QAOA mixer's controls would). A flip
whose result is not a feasible path is skipped and counted: that never happens with the ``exact`` rule
from a feasible path, but it does with the ``paper`` rule. Neighbour lists are cached per path.

Hard obstacles (and the ``paper`` rule) can split a robot's feasible paths into several components of the
move graph that no sequence of moves connects (:func:`qcpp.problem.sbf.move_components`). With
``components="all"`` the space enumerates them so solvers can start in every one; this enumerates every
feasible path, so ``"auto"`` does it only on grids of at most :data:`AUTO_COMPONENT_NODES` nodes and
otherwise starts from the initial paths alone (``"initial"``), which is then noted in the result.

:class:`CostCache` scores assignments (tuples of masks) with the quadratic form of the cost
(:func:`qcpp.problem.cost.quadratic_cost`), memoised.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.problem.paths import initial_path
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> space = MoveSpace(s, "exact", "all")
    >>> len(space.neighbours(0, initial_path(s, 0))), space.num_components
    (3, (1,))
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Sequence
from typing import Literal

import numpy as np

from qcpp.problem.cost import cost_parts, quadratic_cost
from qcpp.problem.cost_range import check_cost_range
from qcpp.problem.paths import initial_path, is_feasible, path_bits
from qcpp.problem.sbf import RULES, Rule, move_components, sbf_logic
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers.result import Solution

ComponentMode = Literal["auto", "all", "initial"]
COMPONENT_MODES: tuple[ComponentMode, ...] = ("auto", "all", "initial")
AUTO_COMPONENT_NODES = 25
"""``components="auto"`` analyses components on grids with at most this many nodes (5x5)."""


class MoveSpace:
    """Allowed SBF neighbours of every robot's paths, and (optionally) the move-graph components.

    Args:
        rule: SBF rule (``exact`` or ``paper``).
        components: ``all``, ``initial`` or ``auto`` (see the module docstring).

    Raises:
        ValueError: on an unknown rule or component mode.
    """

    def __init__(self, scenario: Scenario, rule: Rule, components: ComponentMode = "auto") -> None:
        if rule not in RULES:
            raise ValueError(f"unknown SBF rule {rule!r} (expected one of {', '.join(RULES)})")
        if components not in COMPONENT_MODES:
            raise ValueError(f"unknown component mode {components!r} (expected one of {', '.join(COMPONENT_MODES)})")
        self.scenario = scenario
        self.rule = rule
        plaqs = scenario.grid.plaquettes
        self._flips = [
            [(q.edge_mask, sbf_logic(scenario, r, q, rule)) for q in plaqs] for r in range(scenario.num_robots)
        ]
        self._cache: list[dict[int, tuple[int, ...]]] = [{} for _ in range(scenario.num_robots)]
        self.infeasible_skipped = 0
        """Allowed flips (counted once per path and plaquette) whose result was not a feasible path."""
        self.visited: list[set[int]] = [set() for _ in range(scenario.num_robots)]
        """Per robot, the components its paths were in (:meth:`visit`)."""
        if components == "auto":
            components = "all" if scenario.grid.num_nodes <= AUTO_COMPONENT_NODES else "initial"
        self.analysed = components == "all"
        self._component_of: list[dict[int, int]] = []
        self.representatives: tuple[tuple[int, ...], ...]
        if self.analysed:
            reps = []
            for r in range(scenario.num_robots):
                comps = move_components(scenario, r, rule)
                self._component_of.append({m: i for i, c in enumerate(comps) for m in c})
                reps.append(tuple(c[0] for c in comps))
            self.representatives = tuple(reps)
        else:
            self.representatives = tuple((initial_path(scenario, r),) for r in range(scenario.num_robots))

    @property
    def num_components(self) -> tuple[int, ...]:
        """Components per robot (empty if they were not analysed)."""
        return tuple(len(r) for r in self.representatives) if self.analysed else ()

    def starts(self) -> list[tuple[int, ...]]:
        """Every combination of one representative per robot; the initial paths come first."""
        return list(itertools.product(*self.representatives))

    def component(self, robot: int, mask: int) -> int:
        """Index of the component holding ``mask`` (``0`` when components were not analysed)."""
        return self._component_of[robot][mask] if self.analysed else 0

    def visit(self, masks: Sequence[int]) -> None:
        """Record the components of an assignment (one path per robot) in :attr:`visited`."""
        for r, m in enumerate(masks):
            self.visited[r].add(self.component(r, m))

    def neighbours(self, robot: int, mask: int) -> tuple[int, ...]:
        """Feasible paths one allowed SBF flip away from ``mask`` (plaquette order)."""
        cache = self._cache[robot]
        out = cache.get(mask)
        if out is None:
            found = []
            for qmask, logic in self._flips[robot]:
                if logic.evaluate(mask):
                    new = mask ^ qmask
                    if is_feasible(self.scenario, robot, new):
                        found.append(new)
                    else:
                        self.infeasible_skipped += 1
            out = cache[mask] = tuple(found)
        return out

    def random_flip(self, masks: tuple[int, ...], rng: np.random.Generator) -> tuple[int, ...] | None:
        """One random allowed flip: a uniformly random robot among those with a move, then a uniformly random
        move of it. ``None`` if no robot can move."""
        movable = [r for r in range(len(masks)) if self.neighbours(r, masks[r])]
        if not movable:
            return None
        r = movable[int(rng.integers(len(movable)))]
        nb = self.neighbours(r, masks[r])
        new = nb[int(rng.integers(len(nb)))]
        return (*masks[:r], new, *masks[r + 1:])

    def notes(self) -> list[str]:
        """Remarks for :attr:`~qcpp.problem.solvers.result.Solution.notes`."""
        out = []
        if not self.analysed:
            out.append("move-graph components not analysed: searched only from the initial paths' components")
        if self.infeasible_skipped:
            out.append(
                f"{self.infeasible_skipped} allowed flip(s) ({self.rule} rule) gave infeasible paths and were skipped"
            )
        return out


class CostCache:
    """Memoised total cost of assignments (one mask per robot), from the quadratic form of the cost.

    ``calls`` counts every lookup (the solvers' ``evaluated``); ``len(cache)`` the distinct assignments.
    """

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario
        q = quadratic_cost(scenario)
        self._const = q.const
        self._linear = q.linear
        self._quad = q.quad + q.quad.T  # symmetric, so x.Q.x / 2 is the pair sum
        self._bits: dict[tuple[int, int], np.ndarray] = {}
        self._values: dict[tuple[int, ...], float] = {}
        self.calls = 0

    def __len__(self) -> int:
        return len(self._values)

    def __call__(self, masks: tuple[int, ...]) -> float:
        self.calls += 1
        val = self._values.get(masks)
        if val is None:
            parts = []
            for r, m in enumerate(masks):
                b = self._bits.get((r, m))
                if b is None:
                    b = self._bits[(r, m)] = path_bits(self.scenario, m).astype(float)
                parts.append(b)
            x = np.concatenate(parts)
            val = self._values[masks] = float(self._const + x @ self._linear + 0.5 * (x @ self._quad @ x))
        return val


def search_start(
    scenario: Scenario, seed: int, rule: Rule, components: ComponentMode
) -> tuple[float, np.random.Generator, MoveSpace, CostCache]:
    """What a local search over SBF moves starts with (anneal, genetic): the scenario's weights checked
    (:func:`~qcpp.problem.cost_range.check_cost_range`: float64 costs), the start time, the seeded generator, the
    move space and an empty cost cache."""
    check_cost_range(scenario)
    return time.perf_counter(), np.random.default_rng(seed), MoveSpace(scenario, rule, components), CostCache(scenario)


def search_solution(
    method: str,
    best: tuple[int, ...],
    started: float,
    cost: CostCache,
    trace: Sequence[float],
    space: MoveSpace,
    seed: int,
    notes: Sequence[str],
) -> Solution:
    """The :class:`~qcpp.problem.solvers.result.Solution` of a local search over SBF moves (anneal, genetic).

    Args:
        method: Solver name.
        best: Best assignment found.
        started: ``time.perf_counter()`` at the start of the search.
        cost: The cost cache (its ``calls`` is the number of evaluations).
        trace: Best-so-far cost per iteration.
        space: The move space searched (scenario, rule, components, those visited).
        seed: The seed used.
        notes: Free-text notes.
    """
    return Solution(
        method=method,
        paths=best,
        cost=cost_parts(space.scenario, best),
        seconds=time.perf_counter() - started,
        evaluated=cost.calls,
        trace=tuple(trace),
        num_components=space.num_components,
        components_visited=tuple(tuple(sorted(v)) for v in space.visited),
        seed=seed,
        rule=space.rule,
        notes=tuple(notes),
    )
