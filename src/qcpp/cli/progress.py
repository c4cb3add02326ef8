"""Progress of long commands on stderr: the lines and the bar of :mod:`qcpp.io.progress`, which the API's
``progress=True`` writes too, plus what only the command line does.

What only the command line does: entering a :class:`Progress` calls :func:`qcpp.cli.interrupt.announce_ready`
(``ready: <task>`` on stderr with ``QCPP_READY`` set), the moment from which a signal lands in the command's work.
Everything else (the forms, ``QCPP_PROGRESS``, ``QCPP_PROGRESS_INTERVAL``, lines that fit the terminal's width,
the numba stage) is :class:`qcpp.io.progress.Progress`'s.

Example:
    >>> import io
    >>> out = io.StringIO()
    >>> with Progress("demo", total=1, unit="steps", stream=out, mode="lines", interval=0) as bar:
    ...     bar.advance()
    >>> out.getvalue().splitlines()[-1]
    'demo: 1 step done in 0 s'
"""

from __future__ import annotations

from qcpp.cli.interrupt import announce_ready
from qcpp.io import progress as _lines

__all__ = ["Progress"]


class Progress(_lines.Progress):
    """:class:`qcpp.io.progress.Progress` (same arguments, same output) that says ``ready: <task>`` on entering
    where ``QCPP_READY`` asks for it."""

    def __enter__(self) -> Progress:
        announce_ready(self.task)
        super().__enter__()
        return self
