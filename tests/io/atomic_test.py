"""Atomic writes: whole or not at all, with the permissions a plain open() would give."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from qcpp.io.atomic import atomic_open, write_text_atomic


def test_new_file_gets_umask_permissions_not_0600(tmp_path: Path) -> None:
    old = os.umask(0o022)
    try:
        write_text_atomic(tmp_path / "a.txt", "x")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "a.txt").stat().st_mode) == 0o644


def test_existing_file_keeps_its_mode(tmp_path: Path) -> None:
    p = tmp_path / "b.txt"
    p.write_text("old")
    p.chmod(0o640)
    write_text_atomic(p, "new")
    assert p.read_text() == "new"
    assert stat.S_IMODE(p.stat().st_mode) == 0o640


def test_existing_file_keeps_its_group_where_the_writer_may_set_it(tmp_path: Path) -> None:
    p = tmp_path / "g.txt"
    p.write_text("old")
    mine = p.stat().st_gid
    others = [g for g in ([*os.getgroups(), 65534] if os.geteuid() == 0 else os.getgroups()) if g != mine]
    if not others:
        pytest.skip("the user belongs to one group only (and is not root): no other group to keep")
    os.chown(p, -1, others[0])
    p.chmod(0o640)
    write_text_atomic(p, "new")
    assert p.read_text() == "new" and p.stat().st_gid == others[0]  # a new file, given the old one's group
    assert stat.S_IMODE(p.stat().st_mode) == 0o640


def test_failure_leaves_destination_and_no_temp_file(tmp_path: Path) -> None:
    p = tmp_path / "c.txt"
    p.write_text("old")
    with pytest.raises(RuntimeError), atomic_open(p) as f:
        f.write("half")
        raise RuntimeError("boom")
    assert p.read_text() == "old"
    assert sorted(x.name for x in tmp_path.iterdir()) == ["c.txt"]
