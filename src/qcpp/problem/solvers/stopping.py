"""When a solver stops early: at a wall-clock limit, or when its caller asks it to (Ctrl-C on the command line).

A local search (anneal, genetic) asks :func:`stop_check`'s function before every step; once it answers a reason
the search ends and returns the best assignment found so far, marked with that reason in
:attr:`qcpp.problem.solvers.result.Solution.stopped`. Asking consumes no random numbers, so a run whose check never
fires is the run without one, step for step (same trace, same answer for the same seed).

The reasons are :data:`TIME_LIMIT` and :data:`INTERRUPTED`; the caller's request wins over the clock when both
hold, since it is what the caller will report.

Example:
    >>> ticks = iter([0.0, 1.0, 2.0, 3.0])
    >>> check = stop_check(2.5, clock=lambda: next(ticks))  # started at 0.0: the limit falls at 2.5
    >>> [check(), check(), check()]
    [None, None, 'time limit']
    >>> stop_check(None, stop=lambda: True)()
    'interrupted'
    >>> stop_check(None) is None  # nothing to check: the loops skip the call
    True
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

__all__ = [
    "INTERRUPTED", "TIME_LIMIT", "TIME_LIMITED", "Clock", "StopCheck", "StopFn", "check_time_limit", "stop_check",
    "stopped_note",
]

TIME_LIMITED = ("cpsat", "anneal", "genetic")
"""The methods that take a ``time_limit`` and a ``stop`` request and answer with the best found so far (the API's
and the command line's checks read it)."""

TIME_LIMIT = "time limit"
"""Reason of a search that reached its ``time_limit``."""

INTERRUPTED = "interrupted"
"""Reason of a search its caller's ``stop`` function stopped (the command line's Ctrl-C or SIGTERM)."""

StopFn = Callable[[], bool]
"""A caller's stop request: called between steps, ``True`` once the search should end with what it has."""

Clock = Callable[[], float]
"""Seconds from an arbitrary origin (``time.perf_counter``; tests pass a fake one)."""

StopCheck = Callable[[], "str | None"]
"""What a search calls before each step: ``None`` to go on, else the reason it stops."""


def check_time_limit(time_limit: float | None) -> None:
    """Raise ``ValueError`` unless ``time_limit`` is ``None`` or a positive finite number of seconds.

    Example:
        >>> check_time_limit(0.5)
        >>> check_time_limit(0)
        Traceback (most recent call last):
        ...
        ValueError: time_limit must be a positive number of seconds, got 0
    """
    if time_limit is None:
        return
    if isinstance(time_limit, bool) or not isinstance(time_limit, (int, float)) or not 0 < time_limit < math.inf:
        raise ValueError(f"time_limit must be a positive number of seconds, got {time_limit!r}")


def stop_check(
    time_limit: float | None, stop: StopFn | None = None, clock: Clock = time.perf_counter
) -> StopCheck | None:
    """The check a search asks before each step, its clock started now; ``None`` when there is nothing to check.

    Args:
        time_limit: Seconds from now after which the search stops (``None``: no limit).
        stop: The caller's stop request (``None``: none).
        clock: The clock the limit is measured on.

    Returns:
        A function answering ``None`` (go on), :data:`INTERRUPTED` or :data:`TIME_LIMIT`; once it has answered
        a reason it keeps answering one. ``None`` if neither a limit nor a request is given.
    """
    check_time_limit(time_limit)
    if time_limit is None and stop is None:
        return None
    deadline = clock() + time_limit if time_limit is not None else None

    def check() -> str | None:
        if stop is not None and stop():
            return INTERRUPTED
        if deadline is not None and clock() >= deadline:
            return TIME_LIMIT
        return None

    return check


def stopped_note(reason: str, done: int, total: int, unit: str, time_limit: float | None) -> str:
    """The note of a search that stopped early: why, and how far it got.

    Example:
        >>> stopped_note(TIME_LIMIT, 1200, 20000, "iterations", 2.0)
        'stopped at the time limit (2 s) after 1,200 of 20,000 iterations: the best assignment found so far'
        >>> stopped_note(INTERRUPTED, 3, 40, "generations", None)
        'interrupted after 3 of 40 generations: the best assignment found so far'
    """
    why = f"stopped at the time limit ({time_limit:g} s)" if reason == TIME_LIMIT else "interrupted"
    return f"{why} after {done:,} of {total:,} {unit}: the best assignment found so far"
