"""Errors raised by the problem model."""

from __future__ import annotations

from qcpp.errors import QcppError


class ScenarioError(QcppError):
    """A scenario is malformed or infeasible.

    The message always starts with the field it is about, e.g.
    ``robots[1].goal: (5, 0) is outside the 3x3 grid``.

    Args:
        field: Dotted path of the offending field (``grid.rows``, ``robots[0].start``, ...).
        reason: What is wrong with it.
    """

    def __init__(self, field: str, reason: str) -> None:
        self.field = field
        self.reason = reason
        super().__init__(f"{field}: {reason}" if field else reason)

    def __reduce__(self) -> tuple[type[ScenarioError], tuple[str, str]]:
        # picklable with both arguments, so that errors cross process-pool boundaries intact
        return (type(self), (self.field, self.reason))
