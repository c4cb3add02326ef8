"""Output destinations are checked before the work, and a plot is written after the printed result.

A read-only folder is made by making ``tempfile`` fail with EROFS there (tests cannot mount, and root writes into
chmod-ed folders): both the check's probe (``TemporaryFile``) and the write's temporary file (``mkstemp``). The
progress is on as a line per step (``QCPP_PROGRESS_INTERVAL=0``), so any work done before the error shows as a
progress line on standard error.
"""

from __future__ import annotations

import errno
import tempfile
from pathlib import Path

import pytest

from qcpp.io.atomic import OutputError, check_output

from .clirun import assert_one_line_error, run

REPO = Path(__file__).resolve().parents[2]
EX = str(REPO / "examples" / "paper_3x3.toml")


@pytest.fixture
def progress_lines(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("QCPP_PROGRESS", "lines")
    monkeypatch.setenv("QCPP_PROGRESS_INTERVAL", "0")


def _read_only(monkeypatch: pytest.MonkeyPatch, folder: Path) -> None:
    for name in ("TemporaryFile", "mkstemp"):
        real = getattr(tempfile, name)

        def refuse(*args, dir=None, _real=real, **kwargs):  # type: ignore[no-untyped-def]
            if dir is not None and Path(dir).resolve() == folder.resolve():
                raise OSError(errno.EROFS, "Read-only file system", str(dir))
            return _real(*args, dir=dir, **kwargs)

        monkeypatch.setattr(tempfile, name, refuse)


def test_check_output_finds_a_read_only_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    _read_only(monkeypatch, tmp_path)
    for target in (tmp_path / "new.qasm", tmp_path / "old.qasm"):
        if target.name == "old.qasm":
            target.write_text("old")  # replaced by a rename: the folder must be writable too
        with pytest.raises(OutputError, match=r"is not writable \(Read-only file system\)") as caught:
            check_output(target)
        assert caught.value.errno == errno.EROFS and str(target) in str(caught.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old.qasm"]


def test_check_output_leaves_nothing_behind(tmp_path: Path) -> None:
    check_output(tmp_path / "x.qasm")
    check_output(tmp_path / "p.svg", figure=True)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("suffix", ["txt", "qasm", "PNGG"])
def test_check_output_refuses_an_image_type_matplotlib_cannot_write(tmp_path: Path, suffix: str) -> None:
    with pytest.raises(OutputError, match=rf"unsupported image type \.{suffix.lower()} \(expected png, svg, pdf,"):
        check_output(tmp_path / f"out.{suffix}", figure=True)
    for fine in ("out.png", "out.PDF", "out.svg", "noext"):
        check_output(tmp_path / fine, figure=True)


@pytest.mark.parametrize(
    "args",
    [
        ("compile", EX, "--qasm", "ro/x.qasm"),
        ("solve", EX, "-m", "dfs", "--plot", "ro/p.png"),
        ("solve", EX, "-m", "anneal", "--plot-trace", "ro/t.png"),
        ("estimate", "--grid", "2x2..3x3", "--plot", "ro/e.png"),
    ],
    ids=["compile --qasm", "solve --plot", "solve --plot-trace", "estimate --plot"],
)
def test_a_read_only_folder_is_one_line_before_any_work(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                        progress_lines: None, args: tuple[str, ...]) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "ro").mkdir()
    _read_only(monkeypatch, tmp_path / "ro")
    res = run(*args)
    assert_one_line_error(res, args[-1], "Read-only file system")  # no progress line: nothing ran


@pytest.mark.parametrize(
    "args",
    [
        ("solve", EX, "-m", "dfs", "--plot", "out.txt"),
        ("solve", EX, "-m", "anneal", "--plot-trace", "trace.qasm"),
        ("estimate", "--grid", "2x2..3x3", "--plot", "e.csv"),
    ],
    ids=["solve --plot", "solve --plot-trace", "estimate --plot"],
)
def test_an_unknown_image_type_is_one_line_before_any_work(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                           progress_lines: None, args: tuple[str, ...]) -> None:
    monkeypatch.chdir(tmp_path)
    res = run(*args)
    assert_one_line_error(res, args[-1], "unsupported image type", "png, svg, pdf")
    assert list(tmp_path.iterdir()) == []


def _programs(folder: Path, *names: str) -> str:
    """A ``PATH`` of one folder holding executables ``names`` (scripts that do nothing)."""
    folder.mkdir(exist_ok=True)
    for name in names:
        (folder / name).write_text("#!/bin/sh\n")
        (folder / name).chmod(0o755)
    return str(folder)


def test_check_output_refuses_a_figure_whose_tex_programs_are_missing(tmp_path: Path,
                                                                      monkeypatch: pytest.MonkeyPatch) -> None:
    """matplotlib runs TeX only when it saves the figure, after the work: the check finds it missing first."""
    import matplotlib

    out = tmp_path / "out"
    out.mkdir()
    monkeypatch.setenv("PATH", "")
    with matplotlib.rc_context({"text.usetex": False, "pgf.texsystem": "xelatex"}):
        with pytest.raises(OutputError, match=r"out\.pgf: a \.pgf figure needs xelatex \(matplotlib's pgf\.tex"):
            check_output(out / "out.pgf", figure=True)
        for fine in ("out.png", "out.pdf", "out.svg", "noext"):
            check_output(out / fine, figure=True)  # matplotlib alone
        monkeypatch.setenv("PATH", _programs(tmp_path / "bin", "xelatex"))
        check_output(out / "out.pgf", figure=True)
    lualatex = matplotlib.rc_context({"text.usetex": False, "pgf.texsystem": "lualatex"})
    with lualatex, pytest.raises(OutputError, match=r"needs lualatex"):
        check_output(out / "out.pgf", figure=True)
    monkeypatch.setenv("PATH", "")
    with matplotlib.rc_context({"text.usetex": True}):
        with pytest.raises(OutputError, match=r"needs latex \(matplotlib's text\.usetex\) and dvipng"):
            check_output(out / "out.png", figure=True)
        with pytest.raises(OutputError, match=r"\.pdf figure needs latex \(matplotlib's text\.usetex\), not found"):
            check_output(out / "out.pdf", figure=True)
        monkeypatch.setenv("PATH", _programs(tmp_path / "bin", "latex", "dvipng"))
        check_output(out / "out.png", figure=True)
    assert list(out.iterdir()) == []


@pytest.mark.parametrize(
    "args",
    [
        ("solve", EX, "-m", "dfs", "--plot", "p.pgf"),
        ("estimate", "--grid", "2x2..3x3", "--plot", "e.pgf"),
    ],
    ids=["solve --plot", "estimate --plot"],
)
def test_a_pgf_plot_without_tex_is_one_line_before_any_work(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                            progress_lines: None, args: tuple[str, ...]) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("PATH", "")
    res = run(*args)
    assert_one_line_error(res, args[-1], "needs xelatex", "not found on PATH")  # no progress line: nothing ran
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("args", "printed"),
    [
        (("solve", EX, "-m", "dfs", "--plot", "/dev/full"), "assignments scored"),
        (("solve", EX, "-m", "dfs", "--json", "--plot", "/dev/full"), '"scenario"'),
        (("estimate", "--grid", "2x2..3x3", "--plot", "/dev/full"), "rows"),
        (("estimate", "--grid", "2x2..3x3", "--format", "csv", "--plot", "/dev/full"), "rows,cols"),
    ],
    ids=["solve", "solve --json", "estimate", "estimate csv"],
)
def test_a_plot_that_cannot_be_written_leaves_the_printed_result(args: tuple[str, ...], printed: str) -> None:
    """The plot is written last: a full disk under it is one error line, and the result is on standard output."""
    res = run(*args)
    assert res.exit_code == 2, res.output
    assert printed in res.stdout
    errors = [line for line in res.stderr.splitlines() if line.startswith("error: ")]
    assert errors == ["error: cannot write /dev/full: No space left on device"], res.stderr


def test_a_fifo_without_a_reader_under_plot_leaves_the_printed_table(tmp_path: Path,
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    import os

    import qcpp.io.atomic

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(qcpp.io.atomic, "FIFO_WAIT", 0.2)
    os.mkfifo(tmp_path / "fifo")
    res = run("estimate", "--grid", "2x2", "--plot", "fifo")
    assert res.exit_code == 2 and "| rows |" in res.stdout.replace("┃", "|"), res.output
    assert "cannot write fifo: no process opened the FIFO" in res.stderr


@pytest.mark.parametrize(
    "args",
    [
        ("estimate", "--grid", "3x3", "--plot", "-"),
        ("estimate", "--grid", "3x3", "--plot", "/dev/stdout"),
        ("solve", "--grid", "3x3", "--plot", "-"),
        ("solve", "--grid", "3x3", "-m", "anneal", "--plot-trace", "/dev/stdout"),
    ],
)
def test_a_plot_to_standard_output_is_one_line_before_any_work(args: tuple[str, ...]) -> None:
    """The command prints its table or JSON on standard output: image bytes there would corrupt both."""
    res = run(*args)
    assert_one_line_error(res, args[-1], "standard output holds the command's text")
