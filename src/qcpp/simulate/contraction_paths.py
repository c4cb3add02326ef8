"""cotengra's contraction-path optimizers, shared per cache folder, and the paths they keep on disk.

Finding a good contraction path for a circuit's tensor network can take longer than contracting it, and the same
circuit structure comes back at new angles and new bit strings, in this process and in later ones. So
:func:`path_optimizer` hands every contraction of the process one cotengra optimizer per cache folder and settings
(:data:`PATH_OPTIMIZERS`), keyed by the contraction's structure (:class:`StructureKeyedOptimizer`), whose paths also
live in files in qcpp's cache folder (:func:`default_cache_dir`). The files are safe to share between concurrent
runs and to lose; a folder that cannot be used leaves the paths in memory, after a :class:`CacheFolderWarning`.

Example:
    >>> import tempfile
    >>> folder = tempfile.mkdtemp()
    >>> path_optimizer(folder) is path_optimizer(folder), type(path_optimizer(folder)).__name__
    (True, 'StructureKeyedOptimizer')
"""

from __future__ import annotations

import hashlib
import pickle
import threading
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

from qcpp.io.atomic import atomic_open
from qcpp.io.caches import cache_root, prepare_folder

with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # cotengra warns at import time when the optional kahypar is missing
    import cotengra as ctg
    from cotengra.reusable import hash_contraction
    from cotengra.utils import DiskDict

__all__ = [
    "PATH_OPTIMIZERS",
    "CacheFolderWarning",
    "OptimizerCache",
    "StructureKeyedOptimizer",
    "default_cache_dir",
    "path_optimizer",
]


class CacheFolderWarning(UserWarning):
    """The contraction-path cache folder cannot be used; paths are then cached in memory only (this process)."""


def _usable_cache(path: Path) -> Path | None:
    """``path`` created if need be and writable, else ``None`` after one :class:`CacheFolderWarning`."""
    try:
        return prepare_folder(path)
    except OSError as exc:
        source = cache_root()[1]
        warnings.warn(
            f"the contraction-path cache folder {path} (from {source}) cannot be used "
            f"({exc.strerror or exc}); running without the on-disk cache (set QCPP_CACHE_DIR to a writable folder)",
            CacheFolderWarning,
            stacklevel=3,
        )
        return None


def default_cache_dir() -> Path:
    """Where contraction paths are cached across processes.

    ``$QCPP_CACHE_DIR/cotengra`` if set, else ``$XDG_CACHE_HOME/qcpp/cotengra``, else ``~/.cache/qcpp/cotengra``.

    Example:
        >>> default_cache_dir().name
        'cotengra'
    """
    return cache_root()[0] / "cotengra"


class OptimizerCache:
    """The process's cotengra path optimizers, one per cache directory and settings (:func:`path_optimizer`).

    A ``ReusableHyperOptimizer`` keeps the paths it found in memory and on disk; sharing one per directory lets
    every contraction of the process reuse them (the only process-wide state of this module). Thread-safe;
    :meth:`clear` forgets the instances (their on-disk paths stay), for tests.

    Example:
        >>> cache = OptimizerCache()
        >>> made = cache.get(("key",), lambda: object())
        >>> cache.get(("key",), lambda: object()) is made, len(cache)
        (True, 1)
        >>> cache.clear(); len(cache)
        0
    """

    def __init__(self) -> None:
        self._optimizers: dict[tuple[Any, ...], Any] = {}
        self._lock = threading.Lock()

    def get(self, key: tuple[Any, ...], make: Callable[[], Any]) -> Any:
        """The optimizer of ``key``, made by ``make()`` the first time."""
        with self._lock:
            opt = self._optimizers.get(key)
            if opt is None:
                opt = self._optimizers[key] = make()
            return opt

    def clear(self) -> None:
        """Forget every optimizer."""
        with self._lock:
            self._optimizers.clear()

    def __len__(self) -> int:
        return len(self._optimizers)


PATH_OPTIMIZERS = OptimizerCache()
"""The process-wide :class:`OptimizerCache` of :func:`path_optimizer`."""


class _PathFiles(DiskDict):  # type: ignore[misc]
    """cotengra's store of paths (in memory, and one file per path on disk), safe to share and to lose.

    * A file is written whole or not at all (:func:`qcpp.io.atomic.atomic_open`), so another process reading it
      meanwhile, Ctrl-C or a full disk never leaves half a path on disk.
    * A file that cannot be read (cut short before writes were whole, or from another version) counts as absent:
      the path is searched again and the file replaced, instead of every later contraction of that shape failing.
    * A file that cannot be written (a full disk, a folder made read-only meanwhile) leaves the path in memory for
      this process, with a :class:`CacheFolderWarning` that names the file and the reason.
    """

    __slots__ = ()

    def __contains__(self, k: Any) -> bool:
        if not super().__contains__(k):
            return False
        try:
            self[k]  # read now (and kept in memory), so that an unreadable file counts as absent
        except KeyError:
            return False
        return True

    def __getitem__(self, k: Any) -> Any:
        try:
            return super().__getitem__(k)
        except KeyError:
            raise
        except Exception as exc:  # cotengra's retries end in an error of its own on a file cut short
            raise KeyError(k) from exc

    def __setitem__(self, k: Any, v: Any) -> None:
        self._mem_cache[k] = v
        if self._directory is None:
            return
        fname = self._path.joinpath(*(k if isinstance(k, tuple) else (k,)))
        try:
            fname.parent.mkdir(parents=True, exist_ok=True)
            with atomic_open(fname, "wb") as f:
                pickle.dump(v, f)
        except OSError as exc:
            warnings.warn(f"new contraction paths stay in memory: {exc}", CacheFolderWarning, stacklevel=2)


class StructureKeyedOptimizer(ctg.ReusableHyperOptimizer):  # type: ignore[misc]
    """cotengra's ``ReusableHyperOptimizer`` keyed by the whole structure of a contraction, tensors without indices
    included, with an on-disk store that a cut-short or unwritable file does not break (``_PathFiles``).

    cotengra's ``hash_method='b'`` names each index by the tensors it joins, so a tensor with no index (a scalar,
    which quimb's simplification leaves behind, more or fewer at other angles) is absent from the key: every network
    of scalars alone has one key, and a path found for thirteen of them, read back for six, fails on an index out of
    range. The key here is cotengra's with the number of tensors and the positions of the scalars added, so only
    networks of one shape share a path. The keys differ from cotengra's, so paths cotengra cached under its own key
    are never read back.

    Example:
        >>> import numpy as np
        >>> import quimb.tensor as qtn
        >>> opt = StructureKeyedOptimizer(methods=["greedy"], max_repeats=1, hash_method="b", progbar=False)
        >>> scalars = lambda n: qtn.TensorNetwork([qtn.Tensor(np.array(2.0)) for _ in range(n)])
        >>> [float(scalars(n).contract(optimize=opt)) for n in (13, 6)]
        [8192.0, 64.0]
    """

    def __init__(self, *, directory: str | None = None, **kwargs: Any) -> None:
        super().__init__(directory=directory, **kwargs)
        self._cache = _PathFiles(directory)

    def hash_query(self, inputs: Any, output: Any, size_dict: Any) -> tuple[Any, bool]:
        """The contraction's key and whether no path is cached under it (cotengra's contract)."""
        inputs = tuple(inputs)
        base = hash_contraction(inputs, output, size_dict, self._hash_method)
        scalars = tuple(i for i, term in enumerate(inputs) if not len(term))
        key = hashlib.sha1(repr((base, len(inputs), scalars)).encode()).hexdigest()
        h = (key[:2], key[2:]) if self.directory_split else key
        return h, h not in self._cache


def path_optimizer(
    directory: str | Path | None = None,
    *,
    max_repeats: int = 32,
    max_time: float | str = "rate:1e8",
    parallel: bool | int = False,
) -> StructureKeyedOptimizer:
    """The shared cotengra path optimizer for a cache directory (one instance per process and settings).

    Paths are keyed by the structure of the contraction (:class:`StructureKeyedOptimizer`: which tensors share
    which index, the index sizes and the tensors without indices), in memory and on disk, so the same circuit
    structure at new angles or new bit strings reuses its path, also in a later process.

    Args:
        directory: On-disk cache; default :func:`default_cache_dir`.
        max_repeats: Trial paths per search.
        max_time: Search time limit; the default ``'rate:1e8'`` stops once the search has taken longer than the
            best path's estimated run time at 1e8 flop/s (quick for easy contractions).
        parallel: cotengra's ``parallel`` (default off: no worker processes left behind).

    Returns:
        A :class:`StructureKeyedOptimizer` (caching in memory only, after one :class:`CacheFolderWarning`,
        when the folder cannot be created or written).

    Example:
        >>> import tempfile
        >>> d = tempfile.mkdtemp()
        >>> path_optimizer(d) is path_optimizer(d)
        True
    """
    path = Path(directory) if directory is not None else default_cache_dir()
    key = (str(path.absolute()), max_repeats, max_time, parallel)

    def make() -> StructureKeyedOptimizer:
        usable = _usable_cache(path)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "Couldn't import kahypar": the labels method is used instead
            return StructureKeyedOptimizer(
                max_repeats=max_repeats,
                max_time=max_time,
                parallel=parallel,
                directory=str(usable) if usable is not None else None,  # None: in memory only
                hash_method="b",
                progbar=False,
            )

    return PATH_OPTIMIZERS.get(key, make)  # type: ignore[no-any-return]
