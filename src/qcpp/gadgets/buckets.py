"""Square buckets of the doubled lattice, visited ring by ring: the nearest-point searches of the place-aware
layouts (:mod:`qcpp.gadgets.phase_sums`' local-first adders, :mod:`qcpp.plan.phase_layout`'s ancilla
choice) look at the buckets around a point instead of every point.

A point ``p`` lies in bucket ``(floor(p_y / size), floor(p_x / size))``. Every point of a bucket at Chebyshev
distance ``rho >= 1`` from ``p``'s bucket is more than ``(rho - 1) * size`` away from ``p`` (Manhattan): once the
buckets of rings ``0 .. rho`` are searched, a point not yet seen is more than ``rho * size`` away.

Example:
    >>> sorted(ring(0, 0, 1))
    [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)]
    >>> list(ring(3, 4, 0)), len(list(ring(0, 0, 3)))
    ([(3, 4)], 24)
"""

from __future__ import annotations

from collections.abc import Iterator

__all__ = ["bucket", "ring"]


def bucket(y: float, x: float, size: int) -> tuple[int, int]:
    """The bucket holding point ``(y, x)``.

    >>> bucket(5, 2, 2), bucket(-0.5, 3.9, 4)
    ((2, 1), (-1, 0))
    """
    return int(y // size), int(x // size)


def ring(cy: int, cx: int, rho: int) -> Iterator[tuple[int, int]]:
    """The ``8 rho`` buckets (one for ``rho = 0``) at Chebyshev distance ``rho`` from bucket ``(cy, cx)``.

    Args:
        cy: The centre bucket's row.
        cx: Its column.
        rho: The ring's distance from it, in buckets.

    Returns:
        The ring's buckets, each once.
    """
    if rho == 0:
        yield cy, cx
        return
    for dx in range(-rho, rho + 1):
        yield cy - rho, cx + dx
        yield cy + rho, cx + dx
    for dy in range(1 - rho, rho):
        yield cy + dy, cx - rho
        yield cy + dy, cx + rho
