"""Closed standard streams: ``qcpp ... >&-`` exits quietly with code 1 instead of an ``AttributeError`` traceback.

When the shell starts a program with file descriptor 1 (or 0, 2) closed, Python sets ``sys.stdout`` to ``None``
and the next file the program opens *gets that descriptor*, so a later ``print`` would land in that file.
:func:`guard_closed_streams` (called first thing by :func:`qcpp.__main__.main` and :func:`qcpp.cli.app.main`) puts
``/dev/null`` on every closed descriptor 0-2, so no file ever takes one, and makes a closed standard output
behave like a pipe whose reader left: the first write raises ``BrokenPipeError``, which the CLI already turns into
a quiet exit with code 1 (as for ``qcpp ... | head -1``). The work before the first write still happens (a
``--qasm out.qasm`` file is written whole), as with any Unix tool whose output fails.

Example:
    >>> guard_closed_streams()  # all three streams open here: nothing changes
    False
"""

from __future__ import annotations

import errno
import io
import os
import sys

__all__ = ["ClosedStdout", "guard_closed_streams"]


class ClosedStdout(io.TextIOWrapper):
    """A text stream on ``/dev/null`` whose writes fail like a pipe without a reader (``BrokenPipeError``)."""

    def write(self, text: str) -> int:  # type: ignore[override]
        raise BrokenPipeError(errno.EPIPE, "standard output is closed")

    def writelines(self, lines: object) -> None:  # type: ignore[override]
        raise BrokenPipeError(errno.EPIPE, "standard output is closed")

    def flush(self) -> None:
        """Nothing is ever buffered (every write fails), so flushing (also at exit) is quiet."""


def _is_open(fd: int) -> bool:
    try:
        os.fstat(fd)
    except OSError:
        return False
    return True


def guard_closed_streams() -> bool:
    """Occupy closed descriptors 0-2 with ``/dev/null``; a closed stdout fails on its first write.

    Returns:
        Whether standard output was closed.
    """
    closed = {fd: not _is_open(fd) for fd in (0, 1, 2)}
    for fd, is_closed in closed.items():
        if is_closed:
            null = os.open(os.devnull, os.O_RDWR)
            if null != fd:
                os.dup2(null, fd)
                os.close(null)
    if closed[2]:
        sys.stderr = open(2, "w", closefd=False)  # noqa: SIM115 - lives as long as the process
    if closed[0]:
        sys.stdin = open(0, closefd=False)  # noqa: SIM115
    if closed[1]:
        sys.stdout = ClosedStdout(open(1, "wb", closefd=False), encoding="utf-8")  # noqa: SIM115
    return closed[1]
