"""The ``qcpp`` command line: one typer app, the commands of :mod:`qcpp.commands`, shared error handling.

Every command is a thin layer: it parses options, calls library functions and prints (human-readable by
default, one JSON object on stdout with ``--json``; progress and messages go to stderr).

Errors: the app is a :class:`QcppTyper`, whose ``command()`` wraps every registered callback in
:func:`handle_errors`: a :class:`~gridcover.errors.ScenarioError`, ``ValueError`` or ``OSError`` escaping a
command becomes **one line** on stderr, ``error: <message>``, and exit code 2 -- never a traceback. Commands
get this for free by being registered on :data:`app` (``register(app)`` in their module).

Adding a command: write ``qcpp/commands/<name>.py`` with the command function and
``register(app)`` (``app.command("<name>", help=...)(function)``), give it a ``--json`` option, and add the
module to :data:`COMMAND_MODULES`.

Example:
    >>> from typer.testing import CliRunner
    >>> res = CliRunner().invoke(app, ["solve", "no/such/file.toml"])
    >>> res.exit_code, res.stderr.startswith("error: no/such/file.toml: cannot read the file")
    (2, True)
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable
from typing import Annotated, Any, TypeVar

import typer

from gridcover.errors import ScenarioError
from qcpp import __version__

__all__ = ["COMMAND_MODULES", "LIBRARY_ERRORS", "QcppTyper", "app", "error_line", "handle_errors", "main"]

LIBRARY_ERRORS: tuple[type[BaseException], ...] = (ScenarioError, ValueError, OSError)
"""Exceptions that mean bad input or environment (exit code 2 with one line), not a bug (traceback)."""

COMMAND_MODULES: tuple[str, ...] = (
    "qcpp.commands.solve",
    "qcpp.commands.simulate",
    "qcpp.commands.compile",
    "qcpp.commands.estimate",
    "qcpp.commands.validate",
)
"""Modules whose ``register(app)`` adds a command, in ``--help`` order."""

F = TypeVar("F", bound=Callable[..., Any])


def error_line(exc: BaseException) -> str:
    """``exc`` as one line of text (newlines folded; the exception type if it has no message)."""
    text = " ".join(part.strip() for part in str(exc).splitlines() if part.strip())
    return text or type(exc).__name__


def handle_errors(fn: F) -> F:
    """Wrap a command callback: :data:`LIBRARY_ERRORS` become ``error: <message>`` on stderr and exit code 2."""

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except LIBRARY_ERRORS as exc:
            typer.echo(f"error: {error_line(exc)}", err=True)
            raise typer.Exit(code=2) from None

    return wrapper  # type: ignore[return-value]


class QcppTyper(typer.Typer):
    """A :class:`typer.Typer` whose ``command()`` registers callbacks wrapped in :func:`handle_errors`."""

    def command(self, name: str | None = None, **kwargs: Any) -> Callable[[F], F]:  # type: ignore[override]
        register = super().command(name, **kwargs)

        def decorator(fn: F) -> F:
            register(handle_errors(fn))
            return fn

        return decorator


app = QcppTyper(
    name="qcpp",
    help="QAOA multi-robot coverage path planning: solve scenarios, compile circuits, estimate resources.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_show_locals=False,
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"qcpp {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Print the version and exit.")
    ] = False,
) -> None:
    """QAOA multi-robot coverage path planning: solve scenarios, compile circuits, estimate resources."""


for _name in COMMAND_MODULES:
    importlib.import_module(_name).register(app)


def main() -> None:
    """Entry point of the ``qcpp`` console script."""
    app(prog_name="qcpp")
