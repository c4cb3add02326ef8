"""Where qcpp and the libraries it drives keep files between runs, chosen so that no folder stops a command.

Three things are cached on disk: qcpp's contraction paths (:mod:`qcpp.simulate.tensor`), numba's compiled kernels
(ours in :mod:`qcpp.simulate.subspace_kernels` and quimb's) and matplotlib's font list. Each library picks its own
folder, and fails or warns when it cannot write there: numba raises ``RuntimeError: cannot cache function ...: no
locator available`` when the installed package's ``__pycache__`` and the home folder are both read-only, and
matplotlib prints a two-line warning about a temporary folder. The functions here look before the library is
imported and, only when its own choice would fail, point it elsewhere through its environment variable
(``NUMBA_CACHE_DIR``, ``MPLCONFIGDIR``), in this order:

1. ``$QCPP_CACHE_DIR/<name>``, else ``$XDG_CACHE_HOME/qcpp/<name>``, else ``~/.cache/qcpp/<name>``
   (:func:`cache_root`);
2. ``<temp>/qcpp-<uid>/<name>``: a folder of the current user only (mode 0700, checked before it is trusted,
   since numba loads pickled code from it); a fresh ``mkdtemp`` folder when that name is taken by someone else.

A variable the user set is never changed. A home folder that does not exist is never created (``HOME=/nonexistent``
means no cache under it, not a new tree). The environment is the one process-wide place these libraries read,
so the choice is made once per process: a second call finds the variable set and does nothing.

Example:
    >>> root, source = cache_root({"QCPP_CACHE_DIR": "/data/cache"})
    >>> str(root), source
    ('/data/cache', 'QCPP_CACHE_DIR')
    >>> str(cache_root({"XDG_CACHE_HOME": "/xdg"})[0])
    '/xdg/qcpp'
"""

from __future__ import annotations

import atexit
import errno
import importlib.util
import os
import shutil
import stat
import sys
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path

__all__ = [
    "CACHE_DIR_ENV",
    "cache_root",
    "prepare_folder",
    "private_temp_folder",
    "use_writable_matplotlib_config",
    "use_writable_numba_cache",
]

CACHE_DIR_ENV = "QCPP_CACHE_DIR"
"""Environment variable naming qcpp's cache folder (contraction paths, and numba's kernels when it needs one)."""

NUMBA_PACKAGES = ("qcpp.simulate", "quimb")
"""Packages whose numba functions are compiled with ``cache=True`` when qcpp runs them (their folders decide
whether numba's default, a ``__pycache__`` beside the source, can be written)."""


def _home() -> Path | None:
    try:
        return Path.home()
    except RuntimeError:  # no HOME and no password entry
        return None


def cache_root(environ: Mapping[str, str] | None = None) -> tuple[Path, str]:
    """qcpp's cache folder and where it came from: ``QCPP_CACHE_DIR``, ``XDG_CACHE_HOME`` or ``the home folder``.

    Args:
        environ: The environment (default ``os.environ``).

    Returns:
        ``($QCPP_CACHE_DIR, 'QCPP_CACHE_DIR')`` if set, else ``($XDG_CACHE_HOME/qcpp, 'XDG_CACHE_HOME')``, else
        ``(~/.cache/qcpp, 'the home folder')``. The folder may not exist (:func:`prepare_folder` makes it).
    """
    env = os.environ if environ is None else environ
    if env.get(CACHE_DIR_ENV):
        return Path(env[CACHE_DIR_ENV]), CACHE_DIR_ENV
    if env.get("XDG_CACHE_HOME"):
        return Path(env["XDG_CACHE_HOME"]) / "qcpp", "XDG_CACHE_HOME"
    home = Path(env["HOME"]) if env.get("HOME") else _home()
    return (home or Path("/nonexistent")) / ".cache" / "qcpp", "the home folder"


def prepare_folder(path: Path) -> Path:
    """``path`` created if need be (with its parents) and shown writable by a file created in it and removed.

    A folder inside a home folder that does not exist is refused rather than created with it.

    Raises:
        OSError: the folder cannot be created or written (``strerror`` says why).

    Example:
        >>> d = Path(tempfile.mkdtemp())
        >>> prepare_folder(d / "a" / "b") == d / "a" / "b"
        True
    """
    home = _home()
    if home is not None and not home.is_dir() and path.is_relative_to(home):
        raise FileNotFoundError(errno.ENOENT, f"the home folder {home} does not exist", str(path))
    path.mkdir(parents=True, exist_ok=True)
    tempfile.TemporaryFile(dir=path).close()  # an unnamed file where the system allows (O_TMPFILE)
    return path


def _ready(path: Path) -> bool:
    try:
        prepare_folder(path)
    except OSError:
        return False
    return True


def private_temp_folder(name: str) -> Path:
    """``<temp>/qcpp-<uid>/<name>``, a folder only this user can write (created mode 0700).

    The ``qcpp-<uid>`` folder is trusted only if it is a real folder (not a link) owned by this user and closed to
    others; otherwise a fresh ``mkdtemp`` folder is used, never someone else's, and removed when the process exits
    (nothing can reuse it, so nothing is left behind run after run).

    Raises:
        OSError: the temporary folder cannot be written at all.
    """
    uid = os.getuid() if hasattr(os, "getuid") else None
    base = Path(tempfile.gettempdir()) / (f"qcpp-{uid}" if uid is not None else "qcpp")
    try:
        base.mkdir(mode=0o700, exist_ok=True)
        st = os.lstat(base)
        if (not stat.S_ISDIR(st.st_mode) or (uid is not None and st.st_uid != uid)
                or stat.S_IMODE(st.st_mode) & 0o077):  # fmt: skip
            raise PermissionError(errno.EPERM, "not a private folder", str(base))
    except OSError:
        base = Path(tempfile.mkdtemp(prefix="qcpp-"))
        atexit.register(shutil.rmtree, base, ignore_errors=True)
    return prepare_folder(base / name)


def _fallback(name: str, environ: Mapping[str, str]) -> Path | None:
    """The first usable of ``cache_root()/name`` and ``private_temp_folder(name)``; ``None`` if neither is."""
    candidate = cache_root(environ)[0] / name
    if _ready(candidate):
        return candidate
    try:
        return private_temp_folder(name)
    except OSError:
        return None


def _package_folders(names: Iterable[str]) -> list[Path]:
    folders = []
    for name in names:
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            continue
        if spec is not None and spec.submodule_search_locations:
            folders.extend(Path(p) for p in spec.submodule_search_locations)
    return folders


def use_writable_numba_cache(
    source_folders: Iterable[Path] | None = None, environ: dict[str, str] | None = None
) -> Path | None:
    """Point numba's kernel cache (``NUMBA_CACHE_DIR``) at a writable folder when its default cannot be written.

    Call before numba compiles (or decorates) a ``cache=True`` function: :mod:`qcpp.simulate.subspace_kernels` and
    :mod:`qcpp.simulate.tensor` (quimb's kernels) call it before their imports. numba caches a function in a
    ``__pycache__`` beside its source, else in its own folder under the home folder, and raises when neither can
    be written (a read-only install with a read-only or missing home). Nothing changes when ``NUMBA_CACHE_DIR``
    is set or every source folder's ``__pycache__`` can be written, so an existing cache keeps being used.

    Args:
        source_folders: Folders of the ``cache=True`` functions (default: those of :data:`NUMBA_PACKAGES`).
        environ: The environment to read and set (default ``os.environ``; numba's configuration is reloaded
            when numba is already imported).

    Returns:
        The folder now in ``NUMBA_CACHE_DIR``, or ``None`` when numba's own choice stands.
    """
    env = os.environ if environ is None else environ
    if env.get("NUMBA_CACHE_DIR"):
        return None
    folders = _package_folders(NUMBA_PACKAGES) if source_folders is None else list(source_folders)
    if all(_ready(folder / "__pycache__") for folder in folders):
        return None
    chosen = _fallback("numba", env)
    if chosen is None:
        return None
    env["NUMBA_CACHE_DIR"] = str(chosen)
    config = sys.modules.get("numba.core.config")
    if environ is None and config is not None:
        config.reload_config()  # numba read its environment at import: make it read NUMBA_CACHE_DIR now
    return chosen


def _matplotlib_default_ready(environ: Mapping[str, str]) -> bool:
    """Whether matplotlib's own config and cache folders (``$XDG_CONFIG_HOME/matplotlib`` or
    ``~/.config/matplotlib``; ``$XDG_CACHE_HOME/matplotlib`` or ``~/.cache/matplotlib``) can be written."""
    home = Path(environ["HOME"]) if environ.get("HOME") else _home()
    if home is None:
        return False
    config = Path(environ["XDG_CONFIG_HOME"]) if environ.get("XDG_CONFIG_HOME") else home / ".config"
    cache = Path(environ["XDG_CACHE_HOME"]) if environ.get("XDG_CACHE_HOME") else home / ".cache"
    return _ready(config / "matplotlib") and _ready(cache / "matplotlib")


def use_writable_matplotlib_config(environ: dict[str, str] | None = None) -> Path | None:
    """Point matplotlib's config and cache folder (``MPLCONFIGDIR``) at a writable folder when its default cannot
    be written; call before matplotlib is imported.

    Matplotlib would otherwise make a new temporary folder on every run (building its font list again there) and
    print a two-line warning saying so. Nothing changes when ``MPLCONFIGDIR`` is set or the default folders can be
    written.

    Args:
        environ: The environment to read and set (default ``os.environ``).

    Returns:
        The folder now in ``MPLCONFIGDIR``, or ``None`` when matplotlib's own choice stands.
    """
    env = os.environ if environ is None else environ
    if env.get("MPLCONFIGDIR") or _matplotlib_default_ready(env):
        return None
    chosen = _fallback("matplotlib", env)
    if chosen is not None:
        env["MPLCONFIGDIR"] = str(chosen)
    return chosen
