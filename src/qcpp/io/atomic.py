"""Write output files whole or not at all: the one implementation every package and every output option uses.

The rules (one behaviour for ``--qasm``, ``--plot``, ``--plot-trace`` and every other output path):

* **Regular files** (or a new path): the content goes to a temporary file in the destination's folder, is
  flushed, gets the permissions a plain ``open(path, "w")`` would give, and is renamed over the destination
  (:func:`os.replace`). On any error (or Ctrl-C) the temporary file is removed and the destination is unchanged.
* **Symbolic links** are followed: the file the link points to is replaced, the link stays a link.
* What a replaced file keeps: its permission bits and, where the writer may set it (a member of the group, or
  root), its group; its owner becomes the writer, and it is a new file (inode): **hard links** to the old one keep
  the old content, as with any editor that saves by renaming.
* A process killed outright (SIGKILL, a power cut) between creating and renaming the temporary file leaves it in
  the destination's folder as a hidden ``.NAME.XXXXXXXX.tmp`` (Ctrl-C and SIGTERM remove it); it is never read or
  reused, and is safe to delete.
* **Existing non-regular files** (a device such as ``/dev/null`` or ``/dev/full``, a FIFO) are written straight
  to, never replaced. A FIFO must get a reader within :data:`FIFO_WAIT` seconds.
* ``-`` means standard output, and so do its names :data:`STDOUT_NAMES` (``/dev/stdout``, ...): written to the
  process's standard output whatever it is redirected to (a terminal, a pipe or a regular file, which a rename
  through ``/proc`` could not replace).
* **Missing folders are not created**: writing ``out/x.qasm`` when ``out`` does not exist is an error (as for
  ``cp`` or a compiler's ``-o``), so a typo in a folder name never silently makes a new tree.
* :func:`check_output` finds every unwritable place before the work starts: a missing folder, and a folder where
  no file can be created (read-only folder or file system, ``/proc``), by creating the same temporary file the
  write would create and removing it at once (unnamed where the system allows, so nothing shows in the folder);
  with ``figure=True`` also an image type matplotlib cannot write, or one it writes only with TeX programs that are
  not on ``PATH`` (``.pgf``, or ``text.usetex`` set: :func:`figure_programs`).
* Every failure is an :class:`OutputError` (an ``OSError``) whose message names the path **as the caller gave
  it**, e.g. ``cannot write out/x.qasm: the folder out does not exist`` -- never the temporary name.

Example:
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> with atomic_open(os.path.join(d, "out.txt")) as f:
    ...     _ = f.write("hello")
    >>> open(os.path.join(d, "out.txt")).read()
    'hello'
    >>> try:
    ...     write_text_atomic(os.path.join(d, "no", "x.txt"), "hi")
    ... except OutputError as exc:
    ...     print(str(exc).replace(d, "D"))
    cannot write D/no/x.txt: the folder D/no does not exist
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import stat
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any, Literal

__all__ = [
    "FIFO_WAIT",
    "STDOUT_NAMES",
    "OutputError",
    "atomic_open",
    "check_output",
    "discard_pending",
    "figure_formats",
    "figure_programs",
    "is_stdout",
    "save_figure_atomic",
    "write_text_atomic",
]

FIFO_WAIT = 3.0
"""Seconds to wait for a reader to open a FIFO before giving up (a blocking open could wait for ever)."""

_PENDING: set[str] = set()
"""Temporary files being written now (removed by :func:`discard_pending` if the process must die at once)."""


class OutputError(OSError):
    """An output file cannot be written; ``str()`` is ``cannot write <path as given>: <reason>``.

    Args:
        path: the destination as the caller (user) gave it.
        reason: what went wrong.
        code: the ``errno`` value, if any.
    """

    def __init__(self, path: str, reason: str, code: int | None = None) -> None:
        super().__init__(code, reason, path)

    def __str__(self) -> str:
        return f"cannot write {self.filename}: {self.strerror}"


def _reason(exc: OSError) -> str:
    return exc.strerror or str(exc) or type(exc).__name__


def _wrap(target: str, exc: OSError) -> OutputError:
    return exc if isinstance(exc, OutputError) else OutputError(target, _reason(exc), exc.errno)


STDOUT_NAMES = frozenset({"/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"})
"""Paths that name standard output: written as ``-`` is."""


def is_stdout(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` is standard output: ``-`` or one of :data:`STDOUT_NAMES`. A command that writes a file there
    keeps its own text off standard output (its summary on stderr, ``--json`` refused), whichever name was given.

    Example:
        >>> is_stdout("-"), is_stdout("/dev/stdout"), is_stdout("out.qasm")
        (True, True, False)
    """
    target = os.fspath(path)
    return target == "-" or target in STDOUT_NAMES


def _target_mode(path: str) -> int:
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except FileNotFoundError:
        mask = os.umask(0o022)
        os.umask(mask)
        return 0o666 & ~mask


def _existing(real: str) -> os.stat_result | None:
    try:
        return os.stat(real)
    except FileNotFoundError:
        return None


def check_output(path: str | os.PathLike[str], *, figure: bool = False) -> None:
    """Fail early (before any expensive work) if ``path`` cannot be an output file.

    Checks that the destination is not a folder, that its folder exists and that a file can be created in it (the
    write renames a temporary file over the destination): a read-only folder or file system fails here, not after
    the work. The probe is a temporary file removed at once; nothing is left behind. A device or FIFO, written
    straight to, is not probed.

    Args:
        path: the destination as given by the user (``-`` and :data:`STDOUT_NAMES` are standard output and always
            fine).
        figure: ``path`` is an image for :func:`save_figure_atomic`: its suffix must name a format matplotlib
            writes (none: PNG), and the programs matplotlib runs for it (:func:`figure_programs`) must be on
            ``PATH``.

    Raises:
        OutputError: naming ``path``.

    Example:
        >>> check_output("-")
        >>> try:
        ...     check_output("/")
        ... except OutputError as exc:
        ...     print(exc)
        cannot write /: it is a folder
    """
    target = os.fspath(path)
    if is_stdout(target):
        return
    if not target:
        raise OutputError(target, "empty file name")
    if figure:
        _check_figure_format(target)
    real = os.path.realpath(target)
    try:
        st = _existing(real)
    except OSError as exc:
        raise _wrap(target, exc) from None
    if st is not None:
        if stat.S_ISDIR(st.st_mode):
            raise OutputError(target, "it is a folder", errno.EISDIR)
        if not stat.S_ISREG(st.st_mode):
            return  # a device or FIFO: written straight to
    folder = os.path.dirname(real)
    given = os.path.dirname(target) or "."
    if not os.path.isdir(folder):
        if os.path.isdir(given):  # a symlink into a missing folder
            raise OutputError(target, f"it links into the folder {folder}, which does not exist", errno.ENOENT)
        raise OutputError(target, f"the folder {given} does not exist", errno.ENOENT)
    try:
        tempfile.TemporaryFile(dir=folder, prefix=f".{os.path.basename(real)}.", suffix=".tmp").close()
    except OSError as exc:
        shown = given if os.path.realpath(given) == folder else folder
        raise OutputError(target, f"the folder {shown} is not writable ({_reason(exc)})", exc.errno) from None


def figure_formats() -> list[str]:
    """The image suffixes matplotlib writes (``png``, ``svg``, ``pdf``, ...), from matplotlib itself."""
    from qcpp.io.caches import use_writable_matplotlib_config

    use_writable_matplotlib_config()
    from matplotlib.backend_bases import FigureCanvasBase

    return sorted(FigureCanvasBase.get_supported_filetypes())


RASTER_FORMATS = frozenset({"png", "jpg", "jpeg", "tif", "tiff", "webp", "gif", "avif", "raw", "rgba"})
"""Image types matplotlib draws as pixels (Agg): with ``text.usetex`` their text goes through ``dvipng``."""


def figure_programs(fmt: str) -> tuple[tuple[str, str], ...]:
    """The outside programs matplotlib runs to write a figure as ``fmt``, each with the setting that asks for it.

    ``.pgf`` measures its text with ``rcParams["pgf.texsystem"]`` (``xelatex`` by default; ``lualatex``,
    ``pdflatex``); with ``rcParams["text.usetex"]`` every type needs ``latex``, and the pixel types
    (:data:`RASTER_FORMATS`) ``dvipng`` as well. Every other figure is drawn by matplotlib alone.

    Args:
        fmt: The image type, a suffix without the dot (``pgf``, ``png``).

    Returns:
        ``(program, why)`` pairs, in the order matplotlib needs them; empty for most types.

    Example:
        >>> import matplotlib
        >>> with matplotlib.rc_context({"pgf.texsystem": "lualatex", "text.usetex": False}):
        ...     figure_programs("pgf"), figure_programs("svg")
        ((('lualatex', "matplotlib's pgf.texsystem"),), ())
    """
    from qcpp.io.caches import use_writable_matplotlib_config

    use_writable_matplotlib_config()
    import matplotlib

    if fmt == "pgf":  # the pgf backend typesets with its own TeX system whatever text.usetex says
        return ((str(matplotlib.rcParams["pgf.texsystem"]), "matplotlib's pgf.texsystem"),)
    if not matplotlib.rcParams["text.usetex"]:
        return ()
    why = "matplotlib's text.usetex"
    return (("latex", why), ("dvipng", why)) if fmt in RASTER_FORMATS else (("latex", why),)


def _check_figure_format(target: str) -> None:
    suffix = Path(target).suffix[1:].lower()
    formats = figure_formats()
    if suffix and suffix not in formats:
        common = [f for f in ("png", "svg", "pdf") if f in formats]
        rest = [f for f in formats if f not in common]
        raise OutputError(
            target, f"unsupported image type .{suffix} (expected {', '.join(common + rest)})", errno.EINVAL
        )
    fmt = suffix or "png"
    missing = [(program, why) for program, why in figure_programs(fmt) if shutil.which(program) is None]
    if missing:  # found now, not after the work: matplotlib runs them only when it saves the figure
        programs = " and ".join(f"{program} ({why})" for program, why in missing)
        advice = "install TeX, or write .pdf, .svg or .png" if fmt == "pgf" else "install them, or turn text.usetex off"
        raise OutputError(target, f"a .{fmt} figure needs {programs}, not found on PATH: {advice}", errno.ENOENT)


def _open_fifo(real: str, target: str) -> int:
    deadline = time.monotonic() + FIFO_WAIT
    while True:
        try:
            fd = os.open(real, os.O_WRONLY | os.O_NONBLOCK)
        except OSError as exc:
            if exc.errno != errno.ENXIO:
                raise
            if time.monotonic() >= deadline:
                raise OutputError(
                    target, f"no process opened the FIFO for reading within {FIFO_WAIT:g} s", errno.ENXIO
                ) from None
            time.sleep(0.05)
            continue
        os.set_blocking(fd, True)
        return fd


def _fdopen(fd: int, mode: str) -> IO[Any]:
    if mode == "wb":
        return os.fdopen(fd, "wb")
    return os.fdopen(fd, "w", encoding="utf-8", newline="\n")


@contextlib.contextmanager
def _stdout(mode: str) -> Iterator[IO[Any]]:
    stream: IO[Any] = sys.stdout.buffer if mode == "wb" else sys.stdout
    try:
        yield stream
        stream.flush()
    except BrokenPipeError:  # the reader left (``| head``): not an error of ours, the caller decides
        raise
    except OSError as exc:
        if exc.filename is None:
            raise OutputError("standard output", _reason(exc), exc.errno) from None
        raise


@contextlib.contextmanager
def _direct(real: str, target: str, st: os.stat_result, mode: str) -> Iterator[IO[Any]]:
    try:
        fd = _open_fifo(real, target) if stat.S_ISFIFO(st.st_mode) else os.open(real, os.O_WRONLY)
        f = _fdopen(fd, mode)
    except OSError as exc:
        raise _wrap(target, exc) from None
    try:
        with f:
            yield f
            f.flush()
    except OSError as exc:
        if exc.filename is None:  # our write/flush/close, not an error of the caller's own
            raise _wrap(target, exc) from None
        raise


@contextlib.contextmanager
def atomic_open(path: str | os.PathLike[str], mode: Literal["w", "wb"] = "w") -> Iterator[IO[Any]]:
    """Open ``path`` for writing by the rules of the module docstring (atomic for regular files).

    Args:
        path: Destination (``-`` for standard output). Its folder must exist.
        mode: ``"w"`` (UTF-8 text, ``\\n`` newlines) or ``"wb"``.

    Yields:
        The open (temporary, device, FIFO or standard output) file.

    Raises:
        OutputError: the destination cannot be written (the message names ``path``).
    """
    target = os.fspath(path)
    if is_stdout(target):
        with _stdout(mode) as f:
            yield f
        return
    check_output(target)
    real = os.path.realpath(target)
    st = _existing(real)
    if st is not None and not stat.S_ISREG(st.st_mode):
        with _direct(real, target, st, mode) as f:
            yield f
        return
    file_mode = _target_mode(real)
    try:
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(real), prefix=f".{os.path.basename(real)}.", suffix=".tmp")
    except OSError as exc:
        raise _wrap(target, exc) from None
    _PENDING.add(tmp)
    try:
        f = _fdopen(fd, mode)
        with f:
            yield f
            f.flush()
            os.fsync(f.fileno())
            if st is not None and st.st_gid != os.fstat(f.fileno()).st_gid:
                with contextlib.suppress(OSError):  # allowed for a member of the group (and root) only
                    os.fchown(f.fileno(), -1, st.st_gid)
        os.chmod(tmp, file_mode)  # after the chown, which may clear the setgid bit
        os.replace(tmp, real)
    except BaseException as exc:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        if isinstance(exc, OSError) and (exc.filename is None or exc.filename in (tmp, real)):
            raise _wrap(target, exc) from None
        raise
    finally:
        _PENDING.discard(tmp)


def discard_pending() -> None:
    """Remove the temporary files of writes still in progress (for a process about to ``os._exit``)."""
    for tmp in list(_PENDING):
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        _PENDING.discard(tmp)


def write_text_atomic(path: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` to ``path`` whole or not at all."""
    with atomic_open(path) as f:
        f.write(text)


def save_figure_atomic(fig: Any, path: str | os.PathLike[str], **savefig: Any) -> Path:
    """``fig.savefig`` (format from the suffix, default PNG) into ``path``, whole or not at all."""
    target = Path(path)
    fmt = target.suffix[1:].lower() or "png"
    if is_stdout(path):
        fmt = "png"
    with atomic_open(path, "wb") as f:
        fig.savefig(f, format=fmt, **savefig)
    return target
