"""``python -m qcpp`` and the ``qcpp`` console script: signal handling first, then the CLI.

The first statement of :func:`main` makes SIGINT and SIGTERM raise ``KeyboardInterrupt`` (standard library only,
nothing imported yet), and everything after it, the full handling of :mod:`qcpp.cli.interrupt` and the heavy
imports (typer, rich, numpy, ...) included, runs inside one ``try`` that turns an interruption into the one line
``interrupted`` and exit code 130, as during a command's work. ``import qcpp`` before it loads nothing but this
package's ``__init__`` (no :mod:`importlib.metadata`), so the code that runs before :func:`main` is Python's own
start-up (the interpreter, ``site`` and the ``.pth`` files of the installed packages) and the console script's
two lines: a signal in that window is Python's (docs/cli.md, "Interrupting").

With the environment variable :data:`HOLD_ENV` set (not empty or ``0``), :func:`main` writes ``ready: start-up``
on stderr once the first handlers are in place and waits there (at most :data:`HOLD_SECONDS`) for a signal, so a
test can interrupt the start-up at a known point instead of by timing luck.
"""

from __future__ import annotations

import contextlib
import os
import signal

HOLD_ENV = "QCPP_HOLD_START"
"""Environment variable (a test hook): say ``ready: start-up`` before the heavy imports and wait for a signal."""

HOLD_SECONDS = 60.0
"""Longest wait of :data:`HOLD_ENV` (a test that never sends its signal still ends)."""

_EXIT_INTERRUPTED = 130  # qcpp.cli.interrupt.EXIT_CODE, not imported: nothing may load before the handlers
_stops: list[int] = []


def _early_stop(signum: int, frame: object) -> None:
    """SIGINT/SIGTERM before :func:`qcpp.cli.interrupt.install`: ``KeyboardInterrupt`` once (a second signal while
    the first is being reported is ignored, so the report is never cut short by a traceback)."""
    if not _stops:
        _stops.append(signum)
        raise KeyboardInterrupt


def _interrupted() -> None:
    """Say ``interrupted`` (once, as the CLI does) and end the process with exit code 130."""
    import sys

    for sig in (signal.SIGINT, signal.SIGTERM):
        with contextlib.suppress(ValueError, OSError):
            signal.signal(sig, signal.SIG_IGN)
    module = sys.modules.get("qcpp.cli.interrupt")  # loaded: it may have said it already (it says it once)
    try:
        if module is None:
            raise ImportError
        module.report_interrupted()
    except BaseException:
        with contextlib.suppress(OSError):
            os.write(2, b"interrupted\n")
    os._exit(_EXIT_INTERRUPTED)


def _hold() -> None:
    if os.environ.get(HOLD_ENV, "") in ("", "0"):
        return
    import time

    with contextlib.suppress(OSError):
        os.write(2, b"ready: start-up\n")
    time.sleep(HOLD_SECONDS)


def main() -> None:
    """Install the signal handling, import the CLI and run it."""
    signal.signal(signal.SIGINT, _early_stop)
    signal.signal(signal.SIGTERM, _early_stop)
    try:
        _hold()
        from qcpp.cli.interrupt import install
        from qcpp.cli.streams import guard_closed_streams

        guard_closed_streams()  # before any file is opened: none may land on a closed descriptor 0-2
        install()
        from qcpp.cli.app import main as cli_main
    except KeyboardInterrupt:
        _interrupted()
    except BaseException:
        if _stops or _requested():  # what the signal broke (an ImportError out of an interrupted import)
            _interrupted()
        raise
    try:
        cli_main()
    except KeyboardInterrupt:  # one that landed outside the CLI's own handling (while it set up or wound down)
        _interrupted()


def _requested() -> bool:
    """Whether :mod:`qcpp.cli.interrupt` (if it loaded) saw a stop signal."""
    import sys

    module = sys.modules.get("qcpp.cli.interrupt")
    return bool(module is not None and module.stop_requested())


if __name__ == "__main__":
    main()
