"""The paper's genetic algorithm: a population of assignments evolved by SBF mutations.

* **Initial population**: the initial paths, one individual per other combination of move-graph component
  representatives (every component seeded), then random mutants of the initial assignment (1 to
  ``2 * (rows + cols)`` allowed flips) until ``population`` distinct individuals exist or no new ones turn up.
* **Mutation** (every generation, on every member): ``mutation="all"`` (default) is the paper's step
  literally, "apply the SBF operation on all four-node sub-grids and add the offspring": every single
  allowed flip of every robot of every member. ``mutation="random"`` instead makes ``children`` mutants per
  member, each with 1 to ``flips`` random allowed flips (random robot, random allowed plaquette).
* **Crossover**: ``round(crossover * population)`` children per generation, each from two parents picked by
  binary tournament, taking every robot's whole path from one parent or the other (uniformly). Robots'
  paths are independent, so children are always feasible.
* **Selection** (``mu + lambda``): members and offspring are merged and duplicates dropped; then
  ``selection="truncation"`` (default) keeps the ``population`` cheapest (a stable sort: on equal cost the
  older individual wins), ``selection="tournament"`` keeps the ``elite`` cheapest and fills up with winners
  of binary tournaments drawn without replacement from the rest.

With the defaults (population 192, 40 generations) this is close to a beam search over the SBF move graph
whose randomness is in the initial population and the crossover.

``time_limit`` (seconds) and ``stop`` (a caller's request, e.g. Ctrl-C) end the search early with the best
individual so far (:mod:`qcpp.problem.solvers.stopping`); without them the run is unchanged.

The trace is the best cost after each generation; ``components_visited`` lists, per robot, the components
of every individual ever scored.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> sol = genetic(s, seed=1, generations=10)
    >>> from qcpp.problem.solvers.exhaustive import dfs
    >>> sol.cost == dfs(s).cost, len(sol.trace)
    (True, 10)
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Literal

import numpy as np

from qcpp.problem.sbf import Rule
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers.moves import ComponentMode, MoveSpace, search_solution, search_start
from qcpp.problem.solvers.result import ProgressFn, Solution
from qcpp.problem.solvers.stopping import Clock, StopFn, stop_check, stopped_note

MutationMode = Literal["all", "random"]
SelectionMode = Literal["truncation", "tournament"]
Assignment = tuple[int, ...]


def genetic(
    scenario: Scenario,
    *,
    seed: int = 0,
    population: int = 192,
    generations: int = 40,
    mutation: MutationMode = "all",
    children: int = 2,
    flips: int = 3,
    crossover: float = 0.25,
    selection: SelectionMode = "truncation",
    elite: int = 2,
    rule: Rule = "exact",
    components: ComponentMode = "auto",
    progress: ProgressFn | None = None,
    time_limit: float | None = None,
    stop: StopFn | None = None,
    clock: Clock = time.perf_counter,
) -> Solution:
    """Evolve assignments with SBF mutations and path-swapping crossover (see the module docstring).

    Args:
        seed: Seed of ``numpy.random.default_rng``; the same seed gives the same trace.
        population: Individuals kept after each selection.
        generations: Number of generations.
        mutation: ``all`` (every single allowed flip of every member) or ``random``.
        children: Mutants per member and generation (``mutation="random"`` only).
        flips: Maximum random flips per mutant (``mutation="random"`` only).
        crossover: Crossover children per generation, as a fraction of ``population`` (0 disables it).
        selection: ``truncation`` or ``tournament`` survivor selection.
        elite: Survivors taken by cost before the tournaments (``selection="tournament"`` only).
        rule: SBF rule deciding the allowed flips (``exact`` or ``paper``).
        components: Move-graph component handling: ``all``, ``initial`` or ``auto``
            (see :mod:`qcpp.problem.solvers.moves`).
        progress: Called as ``progress(done, total)`` in generations.
        time_limit: Seconds after which the search stops with the best individual so far (``None``: none; the
            clock starts before the move space is built). Asked before every child is scored, so a generation
            can be cut short; the same seed gives the same trace up to where it stops.
        stop: Asked where ``time_limit`` is; once it returns ``True`` the search stops the same way (the command
            line's Ctrl-C).
        clock: The clock ``time_limit`` is measured on (tests pass a fake one).

    Returns:
        The best individual ever scored, with ``trace``, ``seed``, ``rule`` and the component fields; a search
        that stopped early says why in ``stopped`` and how far it got in a note (the trace then ends with the
        best after the generation it stopped in, if it had scored any child of it).

    Raises:
        ValueError: on non-positive sizes, a negative ``crossover``, a ``time_limit`` that is not a positive
            number, or an unknown mode / rule.
        ScenarioError: weights outside :mod:`qcpp.problem.cost_range`'s range.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 0], "goal": [1, 2]}]})
        >>> genetic(s, seed=5, generations=5).trace == genetic(s, seed=5, generations=5).trace
        True
    """
    sizes = (("population", population), ("generations", generations), ("children", children), ("flips", flips))
    for name, value in sizes:
        if value < 1:
            raise ValueError(f"{name} must be positive, got {value}")
    if not 0 <= elite <= population:
        raise ValueError(f"elite must be between 0 and population ({population}), got {elite}")
    if crossover < 0:
        raise ValueError(f"crossover must be >= 0, got {crossover}")
    if mutation not in ("all", "random"):
        raise ValueError(f"unknown mutation mode {mutation!r} (expected 'all' or 'random')")
    if selection not in ("truncation", "tournament"):
        raise ValueError(f"unknown selection {selection!r} (expected 'truncation' or 'tournament')")
    check = stop_check(time_limit, stop, clock)
    t_start, rng, space, cost = search_start(scenario, seed, rule, components)

    def score(ind: Assignment) -> float:
        space.visit(ind)
        return cost(ind)

    pop = _initial_population(space, population, rng)
    costs = [score(ind) for ind in pop]
    best_i = int(np.argmin(costs))
    best, best_cost = pop[best_i], costs[best_i]
    n_cross = round(crossover * population)
    trace: list[float] = []
    stopped: str | None = None
    for gen in range(generations):
        if check is not None and (stopped := check()):
            break
        offspring: list[Assignment] = []
        for ind in pop:
            if mutation == "all":
                for r, m in enumerate(ind):
                    offspring += [(*ind[:r], n, *ind[r + 1:]) for n in space.neighbours(r, m)]
            else:
                for _ in range(children):
                    child = ind
                    for _ in range(int(rng.integers(1, flips + 1))):
                        child = space.random_flip(child, rng) or child
                    offspring.append(child)
        for _ in range(n_cross):
            a, b = _tournament(costs, rng), _tournament(costs, rng)
            take = rng.random(scenario.num_robots) < 0.5
            offspring.append(tuple(pa if t else pb for pa, pb, t in zip(pop[a], pop[b], take)))
        merged = dict(zip(pop, costs))
        for child in offspring:
            if check is not None and (stopped := check()):
                break
            if child not in merged:
                merged[child] = score(child)
        if stopped:
            # the generation is cut short: its best child so far counts (the first of the cheapest, as selection's
            # stable sort would take it)
            cheapest = min(merged.items(), key=lambda kv: kv[1])
            if cheapest[1] < best_cost:
                best, best_cost = cheapest
            if len(merged) > len(pop):
                trace.append(best_cost)
            break
        ranked = _select(list(merged.items()), population, elite, selection, rng)
        pop = [ind for ind, _ in ranked]
        costs = [c for _, c in ranked]
        if costs[0] < best_cost:
            best, best_cost = pop[0], costs[0]
        trace.append(best_cost)
        if progress is not None:
            progress(gen + 1, generations)

    notes = [
        f"mutation: {mutation}; selection: (mu + lambda) {selection} to {population}; "
        "crossover parents by binary tournament",
        *space.notes(),
        f"{len(cost)} distinct assignments scored",
    ]
    if stopped:
        notes.append(stopped_note(stopped, len(trace), generations, "generations", time_limit))
    sol = search_solution("genetic", best, t_start, cost, trace, space, seed, notes)
    return replace(sol, stopped=stopped) if stopped else sol


def _initial_population(space: MoveSpace, size: int, rng: np.random.Generator) -> list[Assignment]:
    """Component representatives' combinations (initial paths first), then random mutants of the initial one."""
    pop = list(dict.fromkeys(space.starts()))
    seen = set(pop)
    g = space.scenario.grid
    max_walk = 2 * (g.rows + g.cols)
    misses = 0
    while len(pop) < size and misses < 10 * size:
        ind = pop[0]
        for _ in range(int(rng.integers(1, max_walk + 1))):
            ind = space.random_flip(ind, rng) or ind
        if ind in seen:
            misses += 1
            continue
        seen.add(ind)
        pop.append(ind)
    return pop


def _select(
    pool: list[tuple[Assignment, float]], size: int, elite: int, selection: SelectionMode, rng: np.random.Generator
) -> list[tuple[Assignment, float]]:
    """Survivors, cheapest first: the ``elite`` cheapest, then (``tournament``) winners of binary tournaments
    drawn without replacement from the rest, or (``truncation``) simply the next cheapest."""
    ranked = sorted(pool, key=lambda kv: kv[1])
    if selection == "truncation" or len(ranked) <= size:
        return ranked[:size]
    out, rest = ranked[:elite], ranked[elite:]
    while len(out) < size:
        i, j = (int(k) for k in rng.choice(len(rest), size=2, replace=False)) if len(rest) > 1 else (0, 0)
        win = min(i, j)  # rest is sorted, so the lower index is the cheaper (the older on a tie)
        out.append(rest.pop(win))
    return sorted(out, key=lambda kv: kv[1])


def _tournament(costs: list[float], rng: np.random.Generator) -> int:
    """Index of the cheaper of two uniformly drawn members (the first on a tie)."""
    a, b = (int(i) for i in rng.integers(len(costs), size=2))
    return a if costs[a] <= costs[b] else b
