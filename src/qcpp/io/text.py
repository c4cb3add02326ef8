"""Text for a person at a terminal: how wide a line may be, and a duration as people read it.

Here, in the lowest layer, because the progress lines (:mod:`qcpp.io.progress`), the size guards' refusals
(:mod:`qcpp.problem.limits`) and the tables (:mod:`qcpp.estimators.tables`) all word and fit their text alike.

Example:
    >>> format_duration(12.4), format_duration(250)
    ('12 s', '4 min')
    >>> terminal_width() > 0
    True
"""

from __future__ import annotations

import shutil

__all__ = ["format_duration", "terminal_width"]


def terminal_width() -> int:
    """``$COLUMNS`` if set, else the width of the terminal on stdout, else 80."""
    return shutil.get_terminal_size((80, 24)).columns


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
