"""Capture what native libraries print straight to file descriptors 1 and 2 (QCEC's ``[QCEC] Warning`` lines,
OR-Tools' logs), so that the caller can turn what matters into its own one line instead of letting it leak.

Python-level ``sys.stdout``/``sys.stderr`` redirection cannot catch these: C++ code writes to the descriptors
themselves. :func:`capture_native_output` points descriptors 1 and 2 at a temporary file for the duration of the
``with`` block and hands back the captured lines. Use it around one library call only: anything the process
prints meanwhile (a progress bar in another thread) is captured too.

Example:
    >>> import os
    >>> with capture_native_output() as captured:
    ...     _ = os.write(2, b"[lib] Warning: something\\n")
    >>> captured.lines
    ['[lib] Warning: something']
"""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field

__all__ = ["Captured", "capture_native_output"]


@dataclass
class Captured:
    """The lines captured by :func:`capture_native_output` (filled in when the block ends)."""

    lines: list[str] = field(default_factory=list)


def _flush() -> None:
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()


@contextlib.contextmanager
def capture_native_output() -> Iterator[Captured]:
    """Redirect standard output and error (file descriptors 1 and 2) to a temporary file inside the block; the
    lines written there end up in ``.lines``.

    Yields:
        A :class:`Captured` whose ``lines`` (without trailing whitespace, empty lines dropped) are set on exit.
    """
    captured = Captured()
    _flush()
    saved: dict[int, int] = {}
    with tempfile.TemporaryFile() as sink:
        try:
            for fd in (1, 2):
                try:
                    saved[fd] = os.dup(fd)
                except OSError:  # a closed descriptor: nothing to capture there
                    continue
                os.dup2(sink.fileno(), fd)
            yield captured
        finally:
            _flush()
            for fd, copy in saved.items():
                os.dup2(copy, fd)
                os.close(copy)
            sink.seek(0)
            text = sink.read().decode("utf-8", "replace")
            captured.lines = [line.rstrip() for line in text.splitlines() if line.strip()]
