"""Success measures: the chance that repeated independent tries hit, the tries needed, binomial intervals.

The question every method is asked (:mod:`examples/experiments/time_to_solution.py`) is "how many independent
tries reach the optimum with probability ``target`` (99%)?". For a try that hits with probability ``p`` that is
:func:`tries_for` (``shots_for`` is the same count read as QAOA shots); ``S`` tries succeed with
:func:`success_probability`; an empirical rate gets its :func:`wilson_interval`.

Example:
    >>> round(float(success_probability(0.5, 3)), 6), shots_for(0.5, 0.99)
    (0.875, 7)
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["EXACT_COUNTS", "shots_for", "success_probability", "tries_for", "wilson_interval"]


def success_probability(p_hit: float | np.ndarray, shots: int | np.ndarray) -> np.ndarray:
    """Probability that ``shots`` independent draws, each a hit with probability ``p_hit``, hit at least once.

    ``1 - (1 - p_hit)^shots``, computed as ``-expm1(shots * log1p(-p_hit))`` so that tiny ``p_hit`` keep
    their precision. Broadcasts over both arguments.

    Args:
        p_hit: Per-draw hit probability in ``[0, 1]``.
        shots: Number of draws (>= 0).

    Returns:
        The probability (float array; 0-d for scalar input).

    Raises:
        ValueError: if ``p_hit`` is outside ``[0, 1]`` or ``shots`` is negative.

    Example:
        >>> success_probability([0.0, 0.1, 1.0], 2).round(4).tolist()
        [0.0, 0.19, 1.0]
    """
    p = np.asarray(p_hit, dtype=float)
    s = np.asarray(shots, dtype=float)
    if np.any((p < 0) | (p > 1)) or np.any(~np.isfinite(p)):
        raise ValueError(f"p_hit must be in [0, 1], got {p_hit}")
    if np.any(s < 0):
        raise ValueError(f"shots must be >= 0, got {shots}")
    with np.errstate(divide="ignore", invalid="ignore"):
        out = -np.expm1(s * np.log1p(-p))
    return np.where(p >= 1, np.where(s > 0, 1.0, 0.0), out)


EXACT_COUNTS = 2**53
"""Counts from here on are not exact in floating point: :func:`shots_for` returns them as floats, unrefined."""


def shots_for(p_hit: float, target: float = 0.99) -> float:
    """Fewest draws that reach success probability ``target`` (``inf`` if ``p_hit == 0``).

    An ``int`` below :data:`EXACT_COUNTS`; beyond it (``p_hit`` below about ``5e-16`` at 99%) the float
    ``ceil(log(1 - target) / log(1 - p_hit))``, since one draw more or less is below float resolution there.

    Example:
        >>> shots_for(0.1, 0.5), shots_for(1.0), shots_for(0.0)
        (7, 1, inf)
        >>> f"{shots_for(1e-100):.4g}"
        '4.605e+100'
    """
    if not 0 <= p_hit <= 1:
        raise ValueError(f"p_hit must be in [0, 1], got {p_hit}")
    if not 0 < target < 1:
        raise ValueError(f"target must be in (0, 1), got {target}")
    if p_hit == 0:
        return math.inf
    if p_hit == 1:
        return 1
    ratio = math.log1p(-target) / math.log1p(-p_hit)
    if not math.isfinite(ratio):  # beyond the largest float (p_hit near 1e-308)
        return math.inf
    n = math.ceil(ratio)
    if n >= EXACT_COUNTS:  # n and n - 1 are the same float: the rounding guard below could never move n
        return float(n)
    # guard against rounding in the logarithms: the smallest n with 1 - (1-p)^n >= target
    while n > 1 and float(success_probability(p_hit, n - 1)) >= target:
        n -= 1
    while float(success_probability(p_hit, n)) < target:
        n += 1
    return n


def wilson_interval(successes: int, trials: int, z: float = 1.96) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion (default 95%).

    Example:
        >>> lo, hi = wilson_interval(50, 50)
        >>> round(lo, 3), hi
        (0.929, 1.0)
    """
    if trials < 1 or not 0 <= successes <= trials:
        raise ValueError(f"need 0 <= successes <= trials and trials >= 1, got {successes}/{trials}")
    phat = successes / trials
    den = 1 + z * z / trials
    centre = (phat + z * z / (2 * trials)) / den
    half = z * math.sqrt(phat * (1 - phat) / trials + z * z / (4 * trials * trials)) / den
    lo = 0.0 if successes == 0 else max(0.0, centre - half)  # the exact ends, free of rounding
    hi = 1.0 if successes == trials else min(1.0, centre + half)
    return lo, hi


def tries_for(p_hit: float, target: float = 0.99) -> float:
    """Independent tries (runs of a stochastic solver, shots of a QAOA state) that reach ``target``: an alias
    of :func:`shots_for`, named for the runs of SA and GA.

    Example:
        >>> tries_for(0.3), tries_for(1.0)
        (13, 1)
    """
    return shots_for(p_hit, target)
