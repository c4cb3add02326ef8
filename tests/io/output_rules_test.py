"""qcpp.io.atomic's rules for every output path: symlinks, devices, FIFOs, stdout, missing folders, interrupts;
and qcpp.problem.limits' size guards."""

from __future__ import annotations

import os
import stat
import threading
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

import qcpp.io.atomic
from qcpp.io.atomic import OutputError, atomic_open, check_output, discard_pending, write_text_atomic
from qcpp.problem.limits import MAX_GRID_NODES, MAX_LAYERS, SizeError, allow_large, check_grid_size, check_layers
from qcpp.problem.scenario import scenario_from_dict


def test_symlink_target_is_replaced_and_the_link_kept(tmp_path: Path) -> None:
    (tmp_path / "real.txt").write_text("old")
    (tmp_path / "link.txt").symlink_to("real.txt")
    write_text_atomic(tmp_path / "link.txt", "new")
    assert os.readlink(tmp_path / "link.txt") == "real.txt"
    assert (tmp_path / "real.txt").read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.txt", "real.txt"]


def test_devices_are_written_straight_to() -> None:
    write_text_atomic("/dev/null", "anything")
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
    with pytest.raises(OutputError, match=r"^cannot write /dev/full: No space left on device$"):
        write_text_atomic("/dev/full", "x" * 100_000)
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode)


def test_fifo_with_a_reader_gets_the_text_and_stays_a_fifo(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(qcpp.io.atomic, "FIFO_WAIT", 600.0)  # however slowly the reader thread starts
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got: list[str] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_text()))
    reader.start()
    write_text_atomic(fifo, "through the pipe\n")
    reader.join(timeout=600)  # an upper bound for a failed writer (the reader then never gets EOF)
    assert got == ["through the pipe\n"] and stat.S_ISFIFO(fifo.lstat().st_mode)


def test_fifo_without_a_reader_is_an_error_not_a_hang(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(qcpp.io.atomic, "FIFO_WAIT", 0.1)
    os.mkfifo(tmp_path / "pipe")
    with pytest.raises(OutputError, match="no process opened the FIFO"):
        write_text_atomic(tmp_path / "pipe", "x")
    assert stat.S_ISFIFO((tmp_path / "pipe").lstat().st_mode)


def test_missing_folder_is_refused_and_named_as_given(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    for target in ("out/x.qasm", "a/b/c.png"):
        with pytest.raises(OutputError) as err:
            write_text_atomic(target, "x")
        assert str(err.value) == f"cannot write {target}: the folder {os.path.dirname(target)} does not exist"
    with pytest.raises(OutputError, match=r"dangling: it links into the folder .*/missing, which does not exist"):
        (tmp_path / "dangling").symlink_to("missing/x")
        check_output("dangling")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dangling"]


def test_folder_and_empty_name_are_refused(tmp_path: Path) -> None:
    with pytest.raises(OutputError, match="it is a folder"):
        write_text_atomic(tmp_path, "x")
    with pytest.raises(OutputError, match="empty file name"):
        check_output("")


def test_dash_is_standard_output(capsys: pytest.CaptureFixture[str]) -> None:
    with atomic_open("-") as f:
        f.write("to stdout\n")
    assert capsys.readouterr().out == "to stdout\n"


def test_interrupt_mid_write_keeps_the_old_content(tmp_path: Path) -> None:
    p = tmp_path / "out.txt"
    p.write_text("old")
    with pytest.raises(KeyboardInterrupt), atomic_open(p) as f:
        f.write("half")
        raise KeyboardInterrupt
    assert p.read_text() == "old" and sorted(x.name for x in tmp_path.iterdir()) == ["out.txt"]


def test_discard_pending_removes_temporary_files_of_writes_in_progress(tmp_path: Path) -> None:
    with pytest.raises(OSError), atomic_open(tmp_path / "x.txt") as f:
        f.write("half")
        assert len(list(tmp_path.iterdir())) == 1  # the temporary file
        discard_pending()  # what the interrupt watchdog does before os._exit
        assert list(tmp_path.iterdir()) == []
        raise OSError("then the write fails")  # the clean-up copes with the file already gone
    assert list(tmp_path.iterdir()) == []


@given(rows=st.integers(2, 200), cols=st.integers(2, 200))
def test_grid_guard_is_exactly_the_node_limit(rows: int, cols: int) -> None:
    if rows * cols <= MAX_GRID_NODES:
        check_grid_size(rows, cols)
    else:
        with pytest.raises(SizeError, match=r"qcpp\.allow_large\(\) block"):  # the caller's wording: the API's
            check_grid_size(rows, cols)
    with allow_large():
        check_grid_size(rows, cols)


def test_guards_apply_to_scenarios_and_layers() -> None:
    huge = {"grid": {"rows": 10_000, "cols": 10_000}, "robots": [{"start": [0, 0], "goal": [1, 1]}]}
    with pytest.raises(SizeError, match=r"10000x10000 grid has 100,000,000 nodes"):
        scenario_from_dict(huge)
    check_layers(MAX_LAYERS)
    with pytest.raises(SizeError, match="layers"):
        check_layers(MAX_LAYERS + 1)
    with allow_large():
        check_layers(MAX_LAYERS + 1)
    with pytest.raises(SizeError):
        check_layers(MAX_LAYERS + 1)  # the override ends with its block
