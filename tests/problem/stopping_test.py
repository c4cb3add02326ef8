"""Solvers that stop early (a time limit, a caller's stop request) answer with the best found so far, say why, and
run unchanged without either. No test reads the real clock: the limits run on a fake clock that ticks per call."""

from __future__ import annotations

from collections.abc import Callable

import pytest

from qcpp.problem.cost import cost_parts
from qcpp.problem.paths import is_feasible
from qcpp.problem.presets import grid_scenario
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers import Solution, anneal, genetic
from qcpp.problem.solvers.stopping import INTERRUPTED, TIME_LIMIT, stop_check

S = grid_scenario(4, 4, robots=2)


def ticking(step: float = 1.0) -> Callable[[], float]:
    """A clock that advances ``step`` seconds every time it is read."""
    now = [0.0]

    def clock() -> float:
        now[0] += step
        return now[0]

    return clock


def after(n: int) -> Callable[[], bool]:
    """A stop request that answers ``True`` from its ``n + 1``-th call on."""
    calls = [0]

    def stop() -> bool:
        calls[0] += 1
        return calls[0] > n

    return stop


def assert_valid(s: Scenario, sol: Solution) -> None:
    assert all(is_feasible(s, r, m) for r, m in enumerate(sol.paths))
    assert sol.cost == cost_parts(s, sol.paths)


def test_anneal_stops_at_the_time_limit_with_the_best_so_far() -> None:
    # the clock is read once at the start and once per iteration: 5 s at 1 s per read stops before iteration 5
    sol = anneal(S, seed=4, iterations=2000, time_limit=5.0, clock=ticking())
    assert sol.stopped == TIME_LIMIT and len(sol.trace) == 4
    assert_valid(S, sol)
    assert sol.cost.total == sol.trace[-1]
    assert any(n.startswith("stopped at the time limit (5 s) after 4 of 2,000 iterations") for n in sol.notes)


def test_anneal_cut_short_follows_the_same_trace() -> None:
    full = anneal(S, seed=4, iterations=300)
    cut = anneal(S, seed=4, iterations=300, stop=after(120))
    assert full.stopped is None and cut.stopped == INTERRUPTED
    assert cut.trace == full.trace[:120]
    assert_valid(S, cut)


def test_anneal_without_a_limit_is_the_run_with_a_limit_it_never_reaches() -> None:
    free = anneal(S, seed=2, iterations=400)
    limited = anneal(S, seed=2, iterations=400, time_limit=1e9, clock=ticking())
    assert limited.stopped is None and limited.trace == free.trace and limited.paths == free.paths
    assert limited.notes == free.notes


def test_genetic_stops_inside_a_generation_with_its_best_child() -> None:
    full = genetic(S, seed=1, generations=6)
    done: list[int] = []
    calls = [0]

    def stop() -> bool:  # the second generation's start and 40 of its children, then stop
        calls[0] += bool(done)
        return calls[0] > 41

    cut = genetic(S, seed=1, generations=6, stop=stop, progress=lambda k, n: done.append(k))
    assert cut.stopped == INTERRUPTED and done == [1] and len(cut.trace) == 2
    assert cut.trace[0] == full.trace[0] and full.trace[1] <= cut.trace[1] <= cut.trace[0]
    assert_valid(S, cut)
    assert cut.cost.total == cut.trace[-1]
    assert any(n.startswith("interrupted after 2 of 6 generations") for n in cut.notes)


def test_genetic_time_limit_before_the_first_generation_answers_the_initial_population() -> None:
    sol = genetic(S, seed=1, generations=6, time_limit=0.5, clock=ticking())
    assert sol.stopped == TIME_LIMIT and sol.trace == ()
    assert_valid(S, sol)
    assert sol.to_dict(S)["stopped"] == "time limit"


def test_a_run_that_ends_on_its_own_has_no_stopped_field() -> None:
    sol = genetic(S, seed=1, generations=2)
    assert sol.stopped is None and "stopped" not in sol.to_dict(S)


@pytest.mark.parametrize("bad", [0, -1.0, float("inf"), float("nan"), True])
def test_bad_time_limits_are_value_errors(bad: float) -> None:
    with pytest.raises(ValueError, match="time_limit must be a positive number of seconds"):
        anneal(S, iterations=10, time_limit=bad)
    with pytest.raises(ValueError, match="time_limit"):
        stop_check(bad)


def test_cpsat_asked_to_stop_before_it_starts_answers_the_initial_paths() -> None:
    from qcpp.problem.solvers.cpsat import cpsat

    s = grid_scenario(3, 3, robots=1)
    res = cpsat(s, stop=lambda: True)
    assert res.solution.stopped == INTERRUPTED and not res.proven_optimal and res.status == "UNKNOWN"
    assert_valid(s, res.solution)
    assert any("before the search was interrupted" in n for n in res.solution.notes)
    proven = cpsat(s, stop=lambda: False)
    assert proven.proven_optimal and proven.solution.stopped is None


def test_cpsat_relative_gap_is_ortools_definition() -> None:
    from qcpp.problem.solvers.cpsat import relative_gap

    assert relative_gap(1336.0, -199.0) == pytest.approx(1535 / 1336)
    assert relative_gap(0.5, -1.5) == 2.0  # |cost| < 1: divided by 1
    assert relative_gap(-20.0, -20.0) == 0.0


@pytest.mark.parametrize("method", ["anneal", "genetic", "cpsat"])
def test_the_api_s_stop_request_ends_a_search_with_its_best_so_far(method: str) -> None:
    """``qcpp.solve(stop=...)``: what ``qcpp solve`` does on Ctrl-C, for a script (a stop that never answers
    ``True`` changes nothing)."""
    import qcpp

    stopped = qcpp.solve(S, method, stop=after(5))
    assert stopped.stopped == INTERRUPTED
    assert_valid(S, stopped)
    never, plain = qcpp.solve(S, method, stop=lambda: False), qcpp.solve(S, method)
    assert (never.paths, never.cost, never.stopped) == (plain.paths, plain.cost, None)
