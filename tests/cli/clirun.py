"""What the CLI tests share: run ``qcpp`` in-process, and the one-line-error contract for bad input."""

from __future__ import annotations

from click.testing import Result
from typer.testing import CliRunner

from qcpp.cli.app import app


def run(*args: str) -> Result:
    """``qcpp ARGS`` in-process (stdout and stderr kept apart)."""
    return CliRunner().invoke(app, list(args))


def assert_one_line_error(res: Result, *fragments: str) -> None:
    """Exit 2, nothing on stdout, one ``error: ...`` line on stderr naming every fragment, no traceback."""
    assert res.exit_code == 2, res.output
    assert res.stdout == ""
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    assert "Traceback" not in res.output
    for f in fragments:
        assert f in lines[0]
