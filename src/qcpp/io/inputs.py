"""Read an input file boundedly: at most ``max_bytes``, and never waiting for ever on a FIFO or a device.

A regular file is read as usual. Anything else that can be opened for reading -- a FIFO (``mkfifo s.toml``), a
pipe (``/dev/stdin`` of ``cmd | qcpp ...``), a character device (``/dev/zero``, a terminal) -- is read without
blocking: every wait for more data is limited to :data:`INPUT_WAIT` seconds (so a FIFO nobody writes to cannot
block the command for ever), and reading stops at ``max_bytes + 1`` bytes (so ``/dev/zero`` cannot fill the
memory). Sockets and directories fail as the system says.

A pipe the process was handed (``/dev/stdin``, ``/dev/fd/N``, ``/proc/self/fd/N``: a shell pipeline's or a
``<(...)``'s) is the exception: its writer was started with it, so its data is waited for as long as it takes, as
``cat`` waits (a slow producer is not a missing one; Ctrl-C still stops the wait). The limit is for a named FIFO,
which no process may ever open.

Example:
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> with open(os.path.join(d, "s.toml"), "w") as f:
    ...     _ = f.write("x = 1")
    >>> read_bounded(os.path.join(d, "s.toml"), 100)
    b'x = 1'
    >>> fifo = os.path.join(d, "fifo.toml")
    >>> os.mkfifo(fifo)
    >>> try:
    ...     read_bounded(fifo, 100, wait=0.05)
    ... except InputError as exc:
    ...     print(exc.reason)
    no process wrote to the FIFO within 0.05 s
"""

from __future__ import annotations

import errno
import os
import select
import stat
import time

__all__ = ["INPUT_WAIT", "InputError", "handed_down", "read_bounded"]

INPUT_WAIT = 3.0
"""Seconds an input FIFO, pipe or device may keep the reader waiting for more data before it gives up."""


class InputError(OSError):
    """An input file that cannot be read; ``reason`` says why (without the path)."""

    def __init__(self, path: str, reason: str, code: int | None = None) -> None:
        super().__init__(code, reason, path)
        self.reason = reason


def _kind(mode: int) -> str:
    if stat.S_ISFIFO(mode):
        return "FIFO"
    if stat.S_ISCHR(mode):
        return "device"
    if stat.S_ISSOCK(mode):
        return "socket"
    return "file"


def handed_down(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` names a descriptor the process was started with: ``/dev/stdin``, ``/dev/fd/N`` or
    ``/proc/self/fd/N`` (a pipe there has its writer from the start: :func:`read_bounded` waits for it).

    Example:
        >>> handed_down("/dev/stdin"), handed_down("/dev/fd/63"), handed_down("/tmp/fifo.toml")
        (True, True, False)
    """
    name = os.fspath(path)
    return name == "/dev/stdin" or name.startswith(("/dev/fd/", "/proc/self/fd/"))


def read_bounded(path: str | os.PathLike[str], max_bytes: int, *, wait: float | None = None) -> bytes:
    """The content of ``path``, at most ``max_bytes + 1`` bytes (the caller refuses more).

    Args:
        path: The file (symbolic links followed).
        max_bytes: The largest content the caller accepts; one byte more is read so that it can tell.
        wait: Longest wait, in seconds, for more data from a FIFO, pipe or device (``None``: :data:`INPUT_WAIT`);
            a pipe the process was handed (:func:`handed_down`) is waited for without a limit.

    Raises:
        InputError: the file cannot be opened, or a FIFO/pipe/device gave no data for ``wait`` seconds.
        OSError: other read errors (directories: ``IsADirectoryError``).
    """
    name = os.fspath(path)
    wait = INPUT_WAIT if wait is None else wait
    st = os.stat(name)
    if stat.S_ISREG(st.st_mode) or stat.S_ISDIR(st.st_mode) or stat.S_ISBLK(st.st_mode):
        with open(name, "rb") as f:
            return f.read(max_bytes + 1)
    kind = _kind(st.st_mode)
    patient = stat.S_ISFIFO(st.st_mode) and handed_down(name)  # its writer exists: no time limit
    try:
        fd = os.open(name, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as exc:
        raise InputError(name, f"cannot open the {kind} ({exc.strerror or exc})", exc.errno) from None
    chunks: list[bytes] = []
    size = 0
    try:
        poller = select.poll()
        poller.register(fd, select.POLLIN | select.POLLHUP)
        while size <= max_bytes:
            deadline = time.monotonic() + wait
            while True:  # poll again after a signal or a spurious wake-up, within the same deadline
                left = deadline - time.monotonic()
                if not patient and (left <= 0 or not poller.poll(left * 1000)):
                    if size:
                        reason = f"the {kind} sent no more data for {wait:g} s and did not end ({size:,} bytes read)"
                    elif kind == "FIFO":
                        reason = f"no process wrote to the FIFO within {wait:g} s"
                    else:
                        reason = f"the {kind} sent no data within {wait:g} s"
                    raise InputError(name, reason, errno.ETIMEDOUT)
                if patient:
                    poller.poll()  # until data or the writer's end
                try:
                    data = os.read(fd, min(1 << 20, max_bytes + 1 - size))
                except BlockingIOError:
                    continue
                break
            if not data:
                break
            chunks.append(data)
            size += len(data)
    finally:
        os.close(fd)
    return b"".join(chunks)
