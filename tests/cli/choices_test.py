"""Every choice option of every command (``qcpp.cli.app.CHOICES``) refuses a value outside its choices before the
command runs, in one line naming the flag, the choices and the value (exit 2)."""

from __future__ import annotations

from pathlib import Path

import pytest
import typer

from qcpp.cli.app import CHOICES, LIBRARY_CHECKED, app, choices_of

from .clirun import assert_one_line_error, run

PAPER = str(Path(__file__).resolve().parents[2] / "examples" / "paper_3x3.toml")
NEEDS = {"estimate": [], "export": [PAPER, "--format", "qubo", "--out", "-"]}
"""Arguments a command needs besides the option under test (default: the scenario file)."""


def _integer(param: object) -> bool:
    """An integer option, whatever its default (``--qasm-version``'s is ``None``: not given)."""
    annotation = getattr(getattr(param, "type_descriptor", None), "annotation", None)
    return isinstance(getattr(param, "default", None), int) or annotation is int


def _cases() -> list[tuple[str, str, str, bool]]:
    commands = typer.main.get_command(app).commands  # type: ignore[attr-defined]
    return [
        (name, param.opts[0], param.name, _integer(param))
        for name, command in commands.items()
        for param in command.params
        if param.param_type_name == "option"
        and (f"{name}.{param.name}" in CHOICES or param.name in CHOICES)
        and f"{name}.{param.name}" not in LIBRARY_CHECKED
    ]


CASES = _cases()


def test_every_command_has_choice_options() -> None:
    assert {name for name, *_ in CASES} == {"solve", "simulate", "compile", "estimate", "validate", "verify", "export"}


@pytest.mark.parametrize(("command", "flag", "param", "integer"), CASES, ids=[f"{c} {f}" for c, f, *_ in CASES])
def test_a_value_outside_the_choices_is_one_line(command: str, flag: str, param: str, integer: bool) -> None:
    value = "999" if integer else "bogus"
    needs = list(NEEDS.get(command, [PAPER]))
    if flag.split("/")[0] in needs:  # the option under test in place of the one needed: an option is given once
        at = needs.index(flag.split("/")[0])
        del needs[at : at + 2]
    res = run(command, *needs, flag, value)
    choices = choices_of(command, param)
    assert choices is not None
    assert_one_line_error(res, flag, f"expected {' or '.join(choices)}", value)
