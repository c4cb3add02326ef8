"""Ctrl-C and SIGTERM: every command stops within about two seconds, says ``interrupted`` once, exits 130.

How (installed by :func:`qcpp.cli.app.main`, i.e. only for the real command line, never on import):

1. SIGTERM is treated as SIGINT: ``KeyboardInterrupt`` in the main thread, which the CLI
   (:class:`qcpp.cli.app.QcppGroup`) turns into the line ``interrupted`` and exit code 130; ``with`` blocks clean up
   on the way out (:func:`qcpp.io.atomic.atomic_open` removes its temporary file).
2. A watchdog thread wakes on the signal itself (:func:`signal.set_wakeup_fd`, written even while the main thread is
   inside a long native call). If the process is still alive :data:`GRACE_SECONDS` later it removes pending
   temporary files, terminates child processes, prints ``interrupted`` (if nobody did) and ends the process with
   :func:`os._exit` (130).
3. Forked children ignore SIGINT and get the default SIGTERM (a terminal's Ctrl-C reaches the whole process group;
   the parent stops them).
4. ``interrupted`` is written once, under a lock, so the watchdog never ends the process between "reported" and
   "written". :func:`stop_requested` lets the CLI report an exception the signal caused (e.g. an ``ImportError``
   from a ``KeyboardInterrupt`` inside a C extension's import) as ``interrupted``.
5. :func:`deferred_stop`: a command that can answer with what it has (``qcpp solve``: the best paths found so far)
   asks for the first signal as a flag rather than an exception: inside the block the first SIGINT or SIGTERM sets
   the block's event (from the handler, and from the watchdog, which also reaches a main thread inside a native
   call), and the command finishes its output and then raises ``KeyboardInterrupt`` itself (``interrupted``, exit
   130, as everywhere). A second signal raises at once, as outside the block, and the watchdog's grace starts; the
   watchdog also ends a block that has not finished :data:`DEFERRED_SECONDS` after the first signal.
6. :func:`announce_ready`: with ``QCPP_READY`` set (not empty or ``0``) the CLI prints ``ready: <what>`` on stderr
   once its signal handling is installed and the command's work has started, so tests that interrupt a real
   process wait for that line instead of sleeping.

Example:
    >>> report_interrupted.__name__
    'report_interrupted'
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import select
import signal
import sys
import threading
import time
from collections.abc import Iterator
from types import FrameType

from qcpp.io.atomic import discard_pending

__all__ = [
    "EXIT_CODE",
    "GRACE_SECONDS",
    "READY_ENV",
    "announce_ready",
    "deferred_stop",
    "install",
    "report_interrupted",
    "stop_requested",
]

GRACE_SECONDS = 1.5
"""How long the main thread gets to unwind after a signal before the watchdog ends the process."""

EXIT_CODE = 130
"""Exit code after an interruption (128 + SIGINT, the shell convention)."""

READY_ENV = "QCPP_READY"
"""Environment variable that turns on the ``ready: <what>`` line of :func:`announce_ready`."""

DEFERRED_SECONDS = 10.0
"""How long a :func:`deferred_stop` block may take to finish its answer after the first signal before the watchdog
ends the process (a second signal ends it sooner)."""

REPORT_WAIT_SECONDS = 2.0
"""How long the watchdog waits for a main thread that is writing ``interrupted`` right now."""

_reported = threading.Event()  # set once the line is out
_report_lock = threading.Lock()
_requested: list[int] = []  # the stop signals that arrived (a list: a signal handler must not take a lock)
_installed = False
_STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)
_deferring: list[threading.Event] = []  # the events of the open deferred_stop() blocks, innermost last


def report_interrupted() -> None:
    """Print ``interrupted`` on stderr (once per process; the watchdog never cuts the write short)."""
    with _report_lock:
        if _reported.is_set():
            return
        try:
            sys.stderr.write("interrupted\n")
            sys.stderr.flush()
        except Exception:  # a closed or replaced sys.stderr: the file descriptor still works
            with contextlib.suppress(OSError):
                os.write(2, b"interrupted\n")
        _reported.set()


def stop_requested() -> bool:
    """True once SIGINT or SIGTERM arrived in this process (through :func:`install`'s handlers)."""
    return bool(_requested)


def announce_ready(what: str) -> None:
    """Print ``ready: <what>`` on stderr if the environment variable :data:`READY_ENV` is set (else nothing).

    Called when a command's work starts (imports done, signal handling installed): the moment from which an
    interrupt lands in the work itself. A readiness signal for tests and scripts, off by default.

    Args:
        what: A few words naming the work.

    Example:
        >>> announce_ready("nothing")  # QCPP_READY unset: prints nothing
    """
    if os.environ.get(READY_ENV, "") not in ("", "0"):
        with contextlib.suppress(Exception):
            sys.stderr.write(f"ready: {what}\n")
            sys.stderr.flush()


@contextlib.contextmanager
def deferred_stop() -> Iterator[threading.Event]:
    """Within the block the first SIGINT or SIGTERM sets the yielded event instead of raising ``KeyboardInterrupt``.

    The block polls the event (a solver's ``stop`` function: ``event.is_set``), finishes what it prints, and raises
    ``KeyboardInterrupt`` after the block if the event is set, so the command still ends with ``interrupted`` and
    exit 130. A second signal raises at once. Outside the main thread, or before :func:`install` (the API, tests),
    the handlers are left alone and the event is never set.

    Example:
        >>> with deferred_stop() as stopped:
        ...     stopped.is_set()
        False
    """
    flag = threading.Event()
    if not _installed or threading.current_thread() is not threading.main_thread():
        yield flag
        return
    seen: list[int] = []

    def record(signum: int, frame: FrameType | None) -> None:
        _requested.append(signum)
        seen.append(signum)
        if len(seen) > 1:
            raise KeyboardInterrupt
        flag.set()

    previous = {sig: signal.signal(sig, record) for sig in _STOP_SIGNALS}
    _deferring.append(flag)
    try:
        yield flag
    finally:
        _deferring.remove(flag)
        for sig, handler in previous.items():
            signal.signal(sig, handler)


def _raise_interrupt(signum: int, frame: FrameType | None) -> None:
    _requested.append(signum)
    raise KeyboardInterrupt


def _unraisable(info: sys.UnraisableHookArgs) -> None:
    """A stop signal whose ``KeyboardInterrupt`` landed in a finaliser (``__del__``, a weakref callback) is not
    printed as "Exception ignored ... Traceback": the watchdog, woken by the same signal, ends the process."""
    if isinstance(info.exc_value, KeyboardInterrupt) and _requested:
        return
    sys.__unraisablehook__(info)


def _watchdog(fd: int) -> None:
    deadline: float | None = None  # set while a deferred_stop() block finishes its answer after the first signal
    while True:
        if deadline is not None:
            ready, _, _ = select.select([fd], [], [], max(0.0, deadline - time.monotonic()))
            if not ready:
                break  # the block took too long: end the process as after any signal
        try:
            data = os.read(fd, 64)
        except OSError:
            return
        if not data:
            return
        stops = [b for b in data if b in _STOP_SIGNALS]
        if stops:
            _requested.extend(stops)  # also before the main thread ran its Python-level handler
            blocks = list(_deferring)  # a copy: the main thread may leave its block meanwhile
            if deadline is None and len(stops) == 1 and blocks:
                # a command that answers with what it has: let it (the flag also reaches a native call's poller)
                blocks[-1].set()
                deadline = time.monotonic() + DEFERRED_SECONDS
                continue
            break
    time.sleep(GRACE_SECONDS)
    discard_pending()
    for child in multiprocessing.active_children():
        with contextlib.suppress(Exception):
            child.kill()
    # the main thread may be writing the line right now: let it finish rather than end the process mid-report
    if _report_lock.acquire(timeout=REPORT_WAIT_SECONDS) and not _reported.is_set():
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
    signal.signal(signal.SIGINT, _raise_interrupt)
    sys.unraisablehook = _unraisable
    if os.name != "posix":  # pragma: no cover - the wakeup pipe and fork hooks are POSIX
        return
    read_fd, write_fd = os.pipe()
    os.set_blocking(write_fd, False)
    signal.set_wakeup_fd(write_fd, warn_on_full_buffer=False)
    threading.Thread(target=_watchdog, args=(read_fd,), name="qcpp-interrupt-watchdog", daemon=True).start()
    os.register_at_fork(after_in_child=_in_child_after_fork)
