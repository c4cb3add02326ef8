"""Ctrl-C and SIGTERM: every command stops within about two seconds, says ``interrupted`` once, exits 130.

How (installed by :func:`qcpp.cli.main`, i.e. only for the real command line, never on import):

1. SIGTERM gets the same treatment as SIGINT: Python raises ``KeyboardInterrupt`` in the main thread. The CLI
   (:class:`qcpp.cli.QcppGroup`) turns it into the line ``interrupted`` on stderr and exit code 130. On the way
   out, ``with`` blocks clean up: :func:`fileio.atomic.atomic_open` removes its temporary file (the
   destination keeps its old content); ``qcpp estimate`` ends after the row it is writing (it has no worker
   processes and no cache: rows are cheap to recompute).
2. A watchdog thread wakes on the signal itself (:func:`signal.set_wakeup_fd`, written by the C-level handler
   even while the main thread is inside a long native call). If the process is still alive
   :data:`GRACE_SECONDS` later -- the main thread stuck in native code, or a cleanup step hanging -- it removes
   pending temporary files, terminates child processes, prints ``interrupted`` (if nobody did) and ends the
   process with :func:`os._exit` (130).
3. Forked children (worker processes) ignore SIGINT and get the default SIGTERM: a terminal's Ctrl-C reaches the
   whole process group, and workers must neither print tracebacks nor keep running after the parent is gone;
   the parent stops them.

Example:
    >>> report_interrupted.__name__
    'report_interrupted'
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import sys
import threading
import time
from types import FrameType

from fileio.atomic import discard_pending

__all__ = ["EXIT_CODE", "GRACE_SECONDS", "install", "report_interrupted"]

GRACE_SECONDS = 1.5
"""How long the main thread gets to unwind after a signal before the watchdog ends the process."""

EXIT_CODE = 130
"""Exit code after an interruption (128 + SIGINT, the shell convention)."""

_reported = threading.Event()
_installed = False
_STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)


def report_interrupted() -> None:
    """Print ``interrupted`` on stderr (once per process)."""
    if _reported.is_set():
        return
    _reported.set()
    with contextlib.suppress(Exception):
        sys.stderr.write("interrupted\n")
        sys.stderr.flush()


def _raise_interrupt(signum: int, frame: FrameType | None) -> None:
    raise KeyboardInterrupt


def _watchdog(fd: int) -> None:
    while True:
        try:
            data = os.read(fd, 64)
        except OSError:
            return
        if not data:
            return
        if any(b in _STOP_SIGNALS for b in data):
            break
    time.sleep(GRACE_SECONDS)
    discard_pending()
    for child in multiprocessing.active_children():
        with contextlib.suppress(Exception):
            child.kill()
    if not _reported.is_set():
        _reported.set()
        with contextlib.suppress(OSError):
            os.write(2, b"interrupted\n")
    os._exit(EXIT_CODE)


def _in_child_after_fork() -> None:
    with contextlib.suppress(ValueError, OSError):
        signal.set_wakeup_fd(-1)
    with contextlib.suppress(ValueError, OSError):
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)


def install() -> None:
    """Install the SIGTERM handler, the wakeup pipe, the watchdog thread and the fork hook (once; main thread)."""
    global _installed
    if _installed or threading.current_thread() is not threading.main_thread():
        return
    _installed = True
    signal.signal(signal.SIGTERM, _raise_interrupt)
    # also when inherited as ignored (a shell's `cmd &`): an explicit `kill -INT` must stop the command too
    signal.signal(signal.SIGINT, signal.default_int_handler)
    if os.name != "posix":  # pragma: no cover - the wakeup pipe and fork hooks are POSIX
        return
    read_fd, write_fd = os.pipe()
    os.set_blocking(write_fd, False)
    signal.set_wakeup_fd(write_fd, warn_on_full_buffer=False)
    threading.Thread(target=_watchdog, args=(read_fd,), name="qcpp-interrupt-watchdog", daemon=True).start()
    os.register_at_fork(after_in_child=_in_child_after_fork)
