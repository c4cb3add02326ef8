"""Size guards: refuse absurd requests before building anything, naming the size and the override.

Without a guard a huge grid grows to many GB before anything useful happens. Every place that builds a
scenario (file, dict, preset) calls :func:`check_grid_size` first; commands with a layer count call
:func:`check_layers`. Both raise :class:`SizeError` (a :class:`~qcpp.problem.errors.ScenarioError`, so the CLI
prints it as one line with exit code 2) unless large requests are allowed: the CLI's ``--allow-large`` flag
(available on every command) runs the command inside :func:`allow_large`.

The limits are far above anything the repository's methods finish on (the exhaustive solver and the simulators
stop being practical long before), so they only catch typos and runaway scripts.

Example:
    >>> check_grid_size(6, 6)
    >>> try:
    ...     check_grid_size(10000, 10000)
    ... except SizeError as exc:
    ...     print(exc.reason)
    a 10000x10000 grid has 100,000,000 nodes, over the limit of 2,500 (50x50); pass --allow-large to build it anyway
    >>> with allow_large():
    ...     check_grid_size(10000, 10000)
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from contextvars import ContextVar

from qcpp.problem.errors import ScenarioError

__all__ = [
    "MAX_GRID_NODES",
    "MAX_LAYERS",
    "OVERRIDE_FLAG",
    "SizeError",
    "allow_large",
    "check_grid_size",
    "check_layers",
    "format_duration",
    "large_allowed",
    "memory_budget",
]

MAX_GRID_NODES = 2500
"""Largest grid (nodes) built without ``--allow-large``: 50x50."""

MAX_LAYERS = 1000
"""Largest QAOA layer count accepted without ``--allow-large``."""

OVERRIDE_FLAG = "--allow-large"
"""The CLI flag that lifts every limit of this module."""

_ALLOWED: ContextVar[bool] = ContextVar("qcpp_allow_large", default=False)


class SizeError(ScenarioError):
    """A request is larger than a limit of this module (the message names the size and the override)."""


def memory_budget(share: float = 0.5) -> int | None:
    """``share`` of the memory available now (``MemAvailable`` of ``/proc/meminfo``), in bytes; ``None`` where
    that is unknown (not Linux). What size guards compare a predicted peak with.

    Example:
        >>> budget = memory_budget()
        >>> budget is None or budget > 0
        True
    """
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(int(line.split()[1]) * 1024 * share)
    except (OSError, ValueError, IndexError):
        return None
    return None


def large_allowed() -> bool:
    """Whether the limits are lifted in the current context."""
    return _ALLOWED.get()


@contextlib.contextmanager
def allow_large(enabled: bool = True) -> Iterator[None]:
    """Lift (``enabled=True``) or keep the limits inside the ``with`` block."""
    token = _ALLOWED.set(enabled)
    try:
        yield
    finally:
        _ALLOWED.reset(token)


def check_grid_size(rows: int, cols: int, field: str = "grid") -> None:
    """Refuse a grid of more than :data:`MAX_GRID_NODES` nodes (unless :func:`large_allowed`).

    Args:
        rows, cols: the grid size.
        field: the field named in the error.

    Raises:
        SizeError: the grid is too large.
    """
    nodes = rows * cols
    if nodes > MAX_GRID_NODES and not large_allowed():
        raise SizeError(
            field,
            f"a {rows}x{cols} grid has {nodes:,} nodes, over the limit of {MAX_GRID_NODES:,} (50x50); "
            f"pass {OVERRIDE_FLAG} to build it anyway",
        )


def check_layers(p: int, flag: str = "-p") -> None:
    """Refuse more than :data:`MAX_LAYERS` QAOA layers (unless :func:`large_allowed`).

    Raises:
        SizeError: too many layers.

    Example:
        >>> check_layers(3)
    """
    if p > MAX_LAYERS and not large_allowed():
        raise SizeError(
            flag, f"{p:,} layers is over the limit of {MAX_LAYERS:,}; pass {OVERRIDE_FLAG} to run it anyway"
        )


def format_duration(seconds: float) -> str:
    """A duration as people read it (in refusals and progress lines): ``12 s``, ``4 min``, ``2.5 h``, ``9 days``.

    Example:
        >>> format_duration(12.4), format_duration(250), format_duration(9000), format_duration(8e5)
        ('12 s', '4 min', '2.5 h', '9 days')
    """
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.1f} h"
    return f"{seconds / 86400:,.0f} days"
