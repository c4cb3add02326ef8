"""Option combinations a new user tries that do not make sense together: one ``error:`` line naming the flag.

Found by an adversarial pass over the CLI (docs/cli.md, "Probed combinations"); each used to be ignored without a
word or to be refused without naming the flag.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from .clirun import assert_one_line_error, run

PAPER = str(Path(__file__).resolve().parents[2] / "examples" / "paper_3x3.toml")

REFUSED = [
    (("compile", PAPER, "--layout", "medial"), ("--layout medial", "--device")),
    (("compile", PAPER, "--layout", "greedy", "--json"), ("--layout greedy", "--device")),
    (("compile", PAPER, "--local-ancillas"), ("--local-ancillas", "--device")),
    (("solve", PAPER, "-m", "qaoa", "--objective", "cvar:2"), ("--objective", "cvar:2", "gibbs")),
    (("solve", PAPER, "-m", "qaoa", "--optimizer", "multi-angle", "--objective", "bogus"), ("--objective", "bogus")),
    (("simulate", PAPER, "--angles", "0.1,0.2,0.3"), ("--angles", "needs 2 angles", "got 3")),
    (("validate", PAPER, "--dask", "bogus"), ("--dask", "missing port number", "tcp://host:8786")),
    (("validate", PAPER, "--dask", "tcp://h"), ("--dask", "missing port number")),
]


@pytest.mark.parametrize(("args", "fragments"), REFUSED, ids=[" ".join((a[0], *a[2:])) for a, _ in REFUSED])
def test_combination_is_one_line_naming_the_flag(args: tuple[str, ...], fragments: tuple[str, ...]) -> None:
    assert_one_line_error(run(*args), *fragments)


def test_layout_auto_without_device_is_the_default_and_accepted() -> None:
    res = run("compile", PAPER, "--layout", "auto", "--json")
    assert res.exit_code == 0, res.output
