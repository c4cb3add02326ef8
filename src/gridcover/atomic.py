"""Write files whole or not at all: the one implementation every package uses.

The content goes to a temporary file in the destination's folder, is flushed to disk, gets the permissions a
plain ``open(path, "w")`` would give (an existing file's mode, else ``0o666`` less the umask; ``mkstemp`` alone
would leave ``0o600``), and is renamed over the destination with :func:`os.replace`. On any error the temporary
file is removed and the destination is left as it was.

Example:
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> with atomic_open(os.path.join(d, "out.txt")) as f:
    ...     _ = f.write("hello")
    >>> open(os.path.join(d, "out.txt")).read()
    'hello'
"""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any, Literal


def _target_mode(path: str) -> int:
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except FileNotFoundError:
        mask = os.umask(0o022)
        os.umask(mask)
        return 0o666 & ~mask


@contextlib.contextmanager
def atomic_open(path: str | os.PathLike[str], mode: Literal["w", "wb"] = "w") -> Iterator[IO[Any]]:
    """Open a temporary file that replaces ``path`` when the ``with`` block ends without an error.

    Args:
        path: Destination file (its folder must exist).
        mode: ``"w"`` (UTF-8 text, ``\\n`` newlines) or ``"wb"``.

    Yields:
        The open temporary file.
    """
    target = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(target))
    file_mode = _target_mode(target)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{os.path.basename(target)}.", suffix=".tmp")
    try:
        if mode == "wb":
            f: IO[Any] = os.fdopen(fd, "wb")
        else:
            f = os.fdopen(fd, "w", encoding="utf-8", newline="\n")
        with f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, file_mode)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_text_atomic(path: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` to ``path`` whole or not at all."""
    with atomic_open(path) as f:
        f.write(text)


def save_figure_atomic(fig: Any, path: str | os.PathLike[str], **savefig: Any) -> Path:
    """``fig.savefig`` (format from the suffix, default PNG) into ``path``, whole or not at all."""
    target = Path(path)
    fmt = target.suffix[1:].lower() or "png"
    with atomic_open(target, "wb") as f:
        fig.savefig(f, format=fmt, **savefig)
    return target
