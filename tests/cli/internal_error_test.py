"""An unexpected exception inside a command (a bug in qcpp) is one line and exit code 1, not a traceback; with
``QCPP_DEBUG=1`` it propagates with its traceback. Bad input keeps its one line and exit code 2.

The bug is planted in-process: a function ``qcpp solve`` calls raises.
"""

from __future__ import annotations

import sys

import pytest

import qcpp.cli.commands.solve as solve_cmd
from qcpp.cli.app import DEBUG_ENV, main
from qcpp.errors import OptionError, missing_extra
from tests.cli.clirun import run

SOLVE = ("solve", "--grid", "2x3", "--robots", "1", "--method", "dfs")
HINT = f"(set {DEBUG_ENV}=1 for the traceback; please report it)"


def plant(monkeypatch: pytest.MonkeyPatch, exc: Exception) -> None:
    def broken(*args: object, **kwargs: object) -> object:
        raise exc

    monkeypatch.setattr(solve_cmd, "_dfs_paths", broken)


def run_main(monkeypatch: pytest.MonkeyPatch, *args: str) -> None:
    """The console script's :func:`qcpp.cli.app.main` in this process, without the process-wide signal handlers
    and stream guards it installs (they would outlive the test in the worker)."""
    monkeypatch.setattr("qcpp.cli.interrupt.install", lambda: None)
    monkeypatch.setattr("qcpp.cli.streams.guard_closed_streams", lambda: None)
    monkeypatch.setattr(sys, "argv", ["qcpp", *args])
    main()


def test_the_command_runs_unplanted() -> None:
    assert run(*SOLVE).exit_code == 0


@pytest.mark.parametrize(
    ("exc", "line"),
    [
        (RuntimeError("a gadget\nwent"), f"error: internal error: RuntimeError: a gadget went {HINT}"),
        (KeyError("mixer_1"), f"error: internal error: KeyError: 'mixer_1' {HINT}"),
        (AssertionError(), f"error: internal error: AssertionError {HINT}"),
    ],
)
def test_a_bug_is_one_line_and_exit_code_1(monkeypatch: pytest.MonkeyPatch, exc: Exception, line: str) -> None:
    monkeypatch.delenv(DEBUG_ENV, raising=False)
    plant(monkeypatch, exc)
    res = run(*SOLVE)
    assert (res.exit_code, res.stdout, res.stderr) == (1, "", line + "\n")
    assert res.exception is None or isinstance(res.exception, SystemExit)


@pytest.mark.parametrize("exc", [OptionError("--x", "bad"), missing_extra("the dfs", "a package", "extra")])
def test_bad_input_stays_exit_code_2_without_the_hint(monkeypatch: pytest.MonkeyPatch, exc: Exception) -> None:
    plant(monkeypatch, exc)
    res = run(*SOLVE)
    assert (res.exit_code, res.stderr) == (2, f"error: {exc}\n")


@pytest.mark.parametrize("value", ["1", "yes"])
def test_qcpp_debug_shows_the_traceback(monkeypatch: pytest.MonkeyPatch, value: str) -> None:
    """In the app the exception propagates (the runner catches it); from ``main``, the console script's entry,
    it leaves the process, which prints the traceback."""
    monkeypatch.setenv(DEBUG_ENV, value)
    plant(monkeypatch, RuntimeError("planted"))
    res = run(*SOLVE)
    assert isinstance(res.exception, RuntimeError) and "internal error" not in res.stderr
    with pytest.raises(RuntimeError, match="planted"):
        run_main(monkeypatch, *SOLVE)


def test_qcpp_debug_0_is_off(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setenv(DEBUG_ENV, "0")
    plant(monkeypatch, RuntimeError("planted"))
    with pytest.raises(SystemExit) as exit_info:
        run_main(monkeypatch, *SOLVE)
    assert exit_info.value.code == 1
    assert capsys.readouterr().err == f"error: internal error: RuntimeError: planted {HINT}\n"
