"""Cache folders (qcpp.io.caches): a read-only install or home never stops a command, a missing home is not created.

A read-only file system cannot be mounted here (tests need no privileges, and root writes into chmod-ed folders),
so "cannot write" is made by making ``tempfile.TemporaryFile`` fail with EROFS in the chosen folders: the probe
numba runs for each of its cache locations, and the one :func:`qcpp.io.caches.prepare_folder` runs.
"""

from __future__ import annotations

import errno
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from qcpp.io import caches
from qcpp.io.caches import cache_root, prepare_folder, use_writable_matplotlib_config, use_writable_numba_cache

REPO = Path(__file__).resolve().parents[2]


def _read_only(monkeypatch: pytest.MonkeyPatch, *folders: Path) -> None:
    """``tempfile.TemporaryFile`` in (or below) ``folders`` fails as on a read-only file system."""
    real = tempfile.TemporaryFile
    roots = [str(f) for f in folders]

    def temporary_file(*args, dir=None, **kwargs):  # type: ignore[no-untyped-def]
        if dir is not None and any(str(dir).startswith(r) for r in roots):
            raise OSError(errno.EROFS, "Read-only file system", str(dir))
        return real(*args, dir=dir, **kwargs)

    monkeypatch.setattr(tempfile, "TemporaryFile", temporary_file)


def test_cache_root_order() -> None:
    assert cache_root({"QCPP_CACHE_DIR": "/q", "XDG_CACHE_HOME": "/x", "HOME": "/h"}) == (Path("/q"), "QCPP_CACHE_DIR")
    assert cache_root({"XDG_CACHE_HOME": "/x", "HOME": "/h"}) == (Path("/x/qcpp"), "XDG_CACHE_HOME")
    assert cache_root({"HOME": "/h"}) == (Path("/h/.cache/qcpp"), "the home folder")


def test_a_missing_home_is_not_created(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    home = tmp_path / "nonexistent"
    monkeypatch.setenv("HOME", str(home))
    with pytest.raises(FileNotFoundError, match=r"the home folder .* does not exist"):
        prepare_folder(home / ".cache" / "qcpp" / "cotengra")
    assert not home.exists()


def test_numba_keeps_its_own_cache_when_the_install_is_writable(tmp_path: Path) -> None:
    env = {"HOME": str(tmp_path)}
    assert use_writable_numba_cache([tmp_path / "pkg"], env) is None
    assert "NUMBA_CACHE_DIR" not in env
    assert use_writable_numba_cache([tmp_path], {"NUMBA_CACHE_DIR": "/set/by/user"}) is None


def test_numba_cache_in_qcpp_cache_dir_when_the_install_is_read_only(tmp_path: Path,
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    install = tmp_path / "site-packages"
    install.mkdir()
    _read_only(monkeypatch, install)
    env = {"QCPP_CACHE_DIR": str(tmp_path / "cache"), "HOME": str(tmp_path / "home")}
    assert use_writable_numba_cache([install], env) == tmp_path / "cache" / "numba"
    assert env["NUMBA_CACHE_DIR"] == str(tmp_path / "cache" / "numba")


def test_numba_cache_in_a_private_temp_folder_with_a_missing_home(tmp_path: Path,
                                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    install, temp, home = tmp_path / "site-packages", tmp_path / "tmp", tmp_path / "nonexistent"
    install.mkdir()
    temp.mkdir()
    _read_only(monkeypatch, install)
    monkeypatch.setattr(tempfile, "tempdir", str(temp))
    monkeypatch.setenv("HOME", str(home))
    env = {"HOME": str(home)}
    chosen = use_writable_numba_cache([install], env)
    assert chosen is not None and chosen.parent.parent == temp and chosen.name == "numba"
    assert (chosen.parent.stat().st_mode & 0o777) == 0o700
    assert not home.exists()


def test_a_shared_temp_folder_is_not_trusted(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """numba loads pickled code from its cache: a ``qcpp-<uid>`` folder others can write is never used."""
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    planted = tmp_path / f"qcpp-{os.getuid()}"
    planted.mkdir()
    planted.chmod(0o777)
    chosen = caches.private_temp_folder("numba")
    assert chosen.parent != planted and chosen.is_dir()


def test_matplotlib_gets_a_writable_folder_with_a_read_only_home(tmp_path: Path,
                                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    home = tmp_path / "home"
    home.mkdir()
    _read_only(monkeypatch, home)
    env = {"HOME": str(home), "QCPP_CACHE_DIR": str(tmp_path / "cache")}
    assert use_writable_matplotlib_config(env) == tmp_path / "cache" / "matplotlib"
    assert env["MPLCONFIGDIR"] == str(tmp_path / "cache" / "matplotlib")
    writable = {"HOME": str(tmp_path / "other")}
    assert use_writable_matplotlib_config(writable) is None and "MPLCONFIGDIR" not in writable


_READ_ONLY_INSTALL = """
import errno, importlib.util, os, sys, tempfile
read_only = [os.path.dirname(importlib.util.find_spec(name).origin) for name in ("qcpp", "quimb")]
read_only.append(os.environ["HOME"])
real = tempfile.TemporaryFile
def temporary_file(*args, dir=None, **kwargs):
    if dir is not None and any(str(dir).startswith(r) for r in read_only):
        raise OSError(errno.EROFS, "Read-only file system", str(dir))
    return real(*args, dir=dir, **kwargs)
tempfile.TemporaryFile = temporary_file
import qcpp.simulate.subspace_kernels
import qcpp.simulate.tensor
import numba.core.config
print(numba.core.config.CACHE_DIR)
"""


def test_a_read_only_install_and_home_still_load_the_kernels(tmp_path: Path) -> None:
    """numba raised ``cannot cache function ...: no locator available`` at import: the package's ``__pycache__``
    and the home folder both read-only. Now its cache goes to ``$QCPP_CACHE_DIR/numba``."""
    home = tmp_path / "home"
    home.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "XDG_CACHE_HOME")}
    env.update(HOME=str(home), QCPP_CACHE_DIR=str(tmp_path / "cache"), PYTHONPATH=str(REPO / "src"))
    res = subprocess.run([sys.executable, "-c", _READ_ONLY_INSTALL], env=env, capture_output=True, text=True,
                         timeout=300, check=False)  # fmt: skip
    assert res.returncode == 0, res.stderr[-2000:]
    assert res.stdout.strip() == str(tmp_path / "cache" / "numba")


def test_the_contraction_path_cache_is_not_made_in_a_missing_home(tmp_path: Path,
                                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    """``HOME=/nonexistent`` (as root) made ``/nonexistent/.cache/qcpp/cotengra``: now paths stay in memory, after
    one note naming the folder."""
    from qcpp.simulate.contraction_paths import (
        PATH_OPTIMIZERS,
        CacheFolderWarning,
        default_cache_dir,
        path_optimizer,
    )

    home = tmp_path / "nonexistent"
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.delenv("QCPP_CACHE_DIR", raising=False)
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    assert default_cache_dir() == home / ".cache" / "qcpp" / "cotengra"
    try:
        with pytest.warns(CacheFolderWarning, match="does not exist"):
            path_optimizer(max_repeats=3)
    finally:
        PATH_OPTIMIZERS.clear()
    assert not home.exists()


def test_an_untrusted_temp_folder_leaves_no_folder_behind(tmp_path: Path) -> None:
    """With ``qcpp-<uid>`` not private, each process takes a fresh folder: it goes when the process exits."""
    planted = tmp_path / f"qcpp-{os.getuid()}"
    planted.mkdir()
    planted.chmod(0o777)
    code = "from qcpp.io.caches import private_temp_folder; print(private_temp_folder('numba'))"
    env = {**os.environ, "TMPDIR": str(tmp_path)}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    used = Path(done.stdout.strip())
    assert used.parent.parent == tmp_path and used.parent != planted  # the fresh folder was used
    assert not used.parent.exists() and sorted(tmp_path.iterdir()) == [planted]
