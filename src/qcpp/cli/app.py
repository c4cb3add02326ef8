"""The ``qcpp`` command line: one typer app, the commands of :mod:`qcpp.cli.commands`, shared error handling.

Every command is a thin layer: it parses options, calls library functions and prints (human-readable by
default, one JSON object on stdout with ``--json``; progress and messages go to stderr).

One error style everywhere (exit codes: 0 done, 1 a check failed or an internal error, 2 bad input, 130
interrupted):

* A :class:`~qcpp.problem.errors.ScenarioError`, ``ValueError``, ``OSError`` or ``MemoryError`` escaping a command
  becomes **one line** on stderr, ``error: <message>``, and exit code 2 -- never a traceback
  (:func:`handle_errors`).
* Anything else is a bug in qcpp: one line ``error: internal error: <type>: <message> (set QCPP_DEBUG=1 for the
  traceback; please report it)`` and exit code 1 (:func:`internal_error_line`); with ``QCPP_DEBUG=1``
  (:data:`DEBUG_ENV`) the exception propagates with its traceback (:class:`QcppGroup`).
* Usage errors found while parsing are the same one line plus a hint,
  ``error: -p/--layers: 'x' is not a valid integer (see 'qcpp compile --help')`` (:class:`QcppGroup`).
* ``--device`` is checked the same way in every command that takes it, before any work.
* An option of one value given twice (``--grid 3x3 --grid 4x4``) is refused, not read as its last value.
* Numeric options are checked by name in every command (:data:`NUMERIC_OPTIONS`: e.g. ``-p`` at least 1 and at
  most :data:`qcpp.problem.limits.MAX_LAYERS`, ``--seed`` at least 0), choice options by :data:`CHOICES`.
* Ctrl-C (SIGINT) or SIGTERM: one line ``interrupted`` on stderr and exit code 130 (see :mod:`qcpp.cli.interrupt`).
* ``--allow-large`` (every command) lifts the size guards of :mod:`qcpp.problem.limits`.

Adding a command: write ``qcpp/cli/commands/<name>.py`` with the command function and
``register(app)`` (``app.command("<name>", help=...)(function)``), give it a ``--json`` option, and add the
module to :data:`COMMAND_MODULES`. Registering on :data:`app` (a :class:`QcppTyper`) gives it all of the above.

Example:
    >>> from typer.testing import CliRunner
    >>> res = CliRunner().invoke(app, ["solve", "no/such/file.toml"])
    >>> res.exit_code, res.stderr.startswith("error: no/such/file.toml: cannot read the file")
    (2, True)
    >>> res = CliRunner().invoke(app, ["solve", "x.toml", "--bogus-flag"])
    >>> res.exit_code, res.stderr
    (2, "error: No such option: --bogus-flag (see 'qcpp solve --help')\\n")
"""

from __future__ import annotations

import contextlib
import errno
import functools
import importlib
import inspect
import os
import re
import sys
import warnings
from collections.abc import Callable, Iterator, Sequence
from typing import Annotated, Any, TypeVar, get_type_hints

import typer
from typer.core import TyperCommand, TyperGroup

from qcpp import __version__
from qcpp.cli.interrupt import report_interrupted, stop_requested
from qcpp.errors import OptionError, check_count, choice_reason
from qcpp.problem.errors import ScenarioError
from qcpp.problem.limits import OVERRIDE_FLAG, allow_large, check_layers, lift_wording

try:  # typer >= 0.25 ships its own copy of click
    from typer._click import exceptions as _click_exc
    from typer._click.core import Context, Parameter
    from typer._click.globals import get_current_context
except ImportError:  # pragma: no cover - older typer on the real click
    from click import exceptions as _click_exc  # type: ignore[no-redef]
    from click.core import Context, Parameter  # type: ignore[no-redef,assignment]
    from click.globals import get_current_context  # type: ignore[no-redef]

__all__ = [
    "CHOICES",
    "CHOICES_IN_METAVAR",
    "COMMAND_MODULES",
    "DEBUG_ENV",
    "EXIT_INTERNAL",
    "EXIT_INTERRUPTED",
    "EXIT_USAGE",
    "HELP",
    "LIBRARY_CHECKED",
    "LIBRARY_ERRORS",
    "NUMERIC_OPTIONS",
    "PANELS",
    "QcppCommand",
    "QcppGroup",
    "QcppTyper",
    "app",
    "choices_of",
    "error_line",
    "handle_errors",
    "internal_error_line",
    "main",
    "one_line_warnings",
    "usage_error_line",
]

EXIT_USAGE = 2
"""Exit code of every bad-input error."""

EXIT_INTERRUPTED = 130
"""Exit code after Ctrl-C or SIGTERM (128 + SIGINT, the shell convention)."""

EXIT_INTERNAL = 1
"""Exit code of an internal error (a bug in qcpp, not bad input: that is :data:`EXIT_USAGE`)."""

DEBUG_ENV = "QCPP_DEBUG"
"""Environment variable: set (not empty or ``0``), an internal error shows its Python traceback instead of one line."""

LIBRARY_ERRORS: tuple[type[BaseException], ...] = (ScenarioError, ValueError, OSError)
"""Exceptions that mean bad input or environment (exit code 2 with one line), not a bug (traceback)."""

COMMAND_MODULES: tuple[str, ...] = (
    "qcpp.cli.commands.solve",
    "qcpp.cli.commands.simulate",
    "qcpp.cli.commands.compile",
    "qcpp.cli.commands.estimate",
    "qcpp.cli.commands.validate",
    "qcpp.cli.commands.verify",
    "qcpp.cli.commands.export",
    "qcpp.cli.commands.decode",
    "qcpp.cli.commands.scenario",
)
"""Modules whose ``register(app)`` adds a command, in ``--help`` order."""

NUMERIC_OPTIONS: dict[str, int] = {"p": 1, "maxiter": 1, "max_amplitudes": 1, "seed": 0, "samples": 1}
"""Integer parameters checked in every command, by parameter name: the smallest value allowed."""

F = TypeVar("F", bound=Callable[..., Any])

_WRITE_ERRNOS = frozenset({errno.ENOSPC, errno.EIO, errno.EFBIG, errno.EDQUOT})


def error_line(exc: BaseException | str) -> str:
    """``exc`` as one line of text (newlines folded; the exception type if it has no message)."""
    text = " ".join(part.strip() for part in str(exc).splitlines() if part.strip())
    return text or (type(exc).__name__ if isinstance(exc, BaseException) else "error")


def internal_error_line(exc: BaseException) -> str:
    """The one line of an unexpected exception (a bug): its type and message, and how to see the traceback.

    Example:
        >>> internal_error_line(RuntimeError("no\\nway"))
        'error: internal error: RuntimeError: no way (set QCPP_DEBUG=1 for the traceback; please report it)'
        >>> internal_error_line(KeyError())
        'error: internal error: KeyError (set QCPP_DEBUG=1 for the traceback; please report it)'
    """
    text = error_line(exc) if str(exc).strip() else ""
    what = f"{type(exc).__name__}: {text}" if text else type(exc).__name__
    return f"error: internal error: {what} (set {DEBUG_ENV}=1 for the traceback; please report it)"


def _debugging() -> bool:
    return os.environ.get(DEBUG_ENV, "").strip() not in ("", "0")


def _is_option(param: Parameter) -> bool:
    return param.param_type_name == "option"


def _param_name(param: Parameter) -> str:
    if _is_option(param):
        return "/".join(param.opts)
    return (param.name or "argument").upper()


def usage_error_line(exc: Exception) -> str:
    """A click usage error as ``error: <what>: <why> (see '<command> --help')``.

    Example:
        >>> usage_error_line(_click_exc.UsageError("No such option: --x"))
        'error: No such option: --x'
    """
    param = getattr(exc, "param", None)
    if isinstance(exc, _click_exc.BadParameter) and param is not None and not isinstance(
        exc, _click_exc.MissingParameter
    ):
        text = f"{_param_name(param)}: {error_line(exc.message)}"
    else:
        text = error_line(exc.format_message() if isinstance(exc, _click_exc.ClickException) else str(exc))
    ctx = getattr(exc, "ctx", None)
    if ctx is not None:
        text += f" (see '{ctx.command_path} --help')"
    return f"error: {text}"


def _check_options(kwargs: dict[str, Any]) -> None:
    ctx = get_current_context(silent=True)
    for name, low in NUMERIC_OPTIONS.items():
        value = kwargs.get(name)
        if not isinstance(value, int) or isinstance(value, bool):
            continue
        param = next((q for q in ctx.command.params if q.name == name), None) if ctx else None
        flag = _param_name(param) if param is not None else name
        try:
            check_count(value, flag, low)  # the Python API's check too: the same reason after the name
        except OptionError as exc:
            raise _click_exc.BadParameter(exc.reason, ctx=ctx, param=param) from None
        if name == "p":
            check_layers(value, flag)
    _check_device(kwargs, ctx)
    for param in ctx.command.params if ctx else ():  # choice options: one check, one message, every command
        value, key = kwargs.get(param.name or ""), f"{ctx.command.name}.{param.name}"  # type: ignore[union-attr]
        values = None if value in (None, param.default) or key in LIBRARY_CHECKED else choices_of(*key.split("."))
        if values is not None and str(value) not in values:
            raise _click_exc.BadParameter(choice_reason(value, values), ctx=ctx, param=param)


def _check_device(kwargs: dict[str, Any], ctx: Context | None) -> None:
    """``--device`` names a device (:func:`qcpp.hardware.device.get_device`), checked before any work in every
    command that takes it, one message everywhere: ``--device: unknown device 'x' (known: ...)``."""
    param = next((q for q in ctx.command.params if "--device" in getattr(q, "opts", ())), None) if ctx else None
    spec = kwargs.get(param.name or "") if param is not None else None
    if not isinstance(spec, str):
        return
    from qcpp.hardware.device import DeviceError, get_device  # here: most commands never load the device data

    try:
        get_device(spec)
    except DeviceError as exc:
        raise _click_exc.BadParameter(str(exc), ctx=ctx, param=param) from None


@contextlib.contextmanager
def one_line_warnings() -> Iterator[None]:
    """Show each distinct Python warning raised inside as one line ``note: <message>`` on stderr, once.

    Python's own format is two lines (``file:line: Category: message`` and the source line) that name our
    internals; a warning that matters to the user (an unusable cache folder, a numerical overflow) reads as one
    line instead, like every other message of the CLI.

    Example:
        >>> import warnings
        >>> with one_line_warnings():
        ...     warnings.warn("the cache folder /proc/x cannot be used")  # doctest: +SKIP
        note: the cache folder /proc/x cannot be used
    """
    seen: set[str] = set()

    def show(message: Warning | str, category: type[Warning], *args: Any, **kwargs: Any) -> None:
        text = error_line(message)
        if text not in seen:
            seen.add(text)
            with contextlib.suppress(OSError, ValueError, AttributeError):
                typer.echo(f"note: {text}", err=True)

    with warnings.catch_warnings():
        warnings.showwarning = show
        yield


def handle_errors(fn: F) -> F:
    """Wrap a command callback: the exit-code rules of the module docstring, plus ``--allow-large``.

    The wrapper's signature is ``fn``'s plus a keyword ``allow_large`` flag (unless ``fn`` has its own), so every
    command accepts ``--allow-large``.
    """
    sig = inspect.signature(fn, eval_str=True)
    own_flag = "allow_large" in sig.parameters

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        large = kwargs["allow_large"] if own_flag else kwargs.pop("allow_large", False)
        try:
            with allow_large(bool(large)), lift_wording(f"pass {OVERRIDE_FLAG}"), one_line_warnings():
                _check_options(kwargs)
                return fn(*args, **kwargs)
        except BrokenPipeError:  # the reader of stdout left: typer exits quietly (code 1)
            raise
        except Exception as exc:
            if stop_requested():  # what the signal broke (e.g. an import: ImportError) is an interruption
                raise KeyboardInterrupt from None
            if isinstance(exc, MemoryError):
                typer.echo("error: out of memory (ask for less: a smaller grid, fewer robots or layers)", err=True)
                raise typer.Exit(code=EXIT_USAGE) from None
            if not isinstance(exc, LIBRARY_ERRORS):
                raise
            message = error_line(exc)
            if isinstance(exc, OSError) and exc.filename is None and exc.errno in _WRITE_ERRNOS:
                # named files fail as qcpp.io.atomic.OutputError (with the name): this was stdout
                _stdout_failure()
                message = f"cannot write standard output: {exc.strerror}"
            typer.echo(f"error: {message}", err=True)
            raise typer.Exit(code=EXIT_USAGE) from None

    if not own_flag:
        flag = inspect.Parameter(
            "allow_large",
            inspect.Parameter.KEYWORD_ONLY,
            default=False,
            annotation=Annotated[
                bool, typer.Option(OVERRIDE_FLAG, help="Lift the size guards (grids over 50x50, p over 1000).")
            ],
        )
        wrapper.__signature__ = sig.replace(parameters=[*sig.parameters.values(), flag])  # type: ignore[attr-defined]
        hints = get_type_hints(fn, include_extras=True)
        wrapper.__annotations__ = {**hints, "allow_large": flag.annotation}
    return wrapper  # type: ignore[return-value]


def _tidy_help(params: Sequence[Parameter]) -> None:
    """Show flags as flags (no ``<bool>``) and arguments by an upper-case name (``SCENARIO``)."""
    for param in params:
        if _is_option(param):
            if getattr(param, "is_flag", False) and param.metavar is None:
                param.metavar = ""
        elif param.metavar is None and param.name:
            param.metavar = param.name.upper()


class _TidyHelp:
    """Mixin for click commands and groups: help shows flags as flags (see :func:`_tidy_help`)."""

    params: list[Any]

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        _tidy_help(self.params)

    def format_help(self, ctx: Context, formatter: Any) -> None:
        _tidy_help(self.params)  # also the options added after construction (--install-completion, ...)
        super().format_help(ctx, formatter)  # type: ignore[misc]

    def get_help_option(self, ctx: Context) -> Any:
        option = super().get_help_option(ctx)  # type: ignore[misc]
        if option is not None:
            _tidy_help([option])
        return option


def _lazy(module: str, name: str) -> Callable[[], Sequence[Any]]:
    return lambda: tuple(getattr(importlib.import_module(module), name))


CHOICES: dict[str, Callable[[], Sequence[Any]]] = {
    "rule": _lazy("qcpp.problem.sbf", "RULES"),
    "target": _lazy("qcpp.ir.cost", "TARGETS"),
    "phase": _lazy("qcpp.plan.options", "PHASES"),
    "optimize": _lazy("qcpp.plan.options", "OPTIMIZE"),
    "initial": _lazy("qcpp.plan.options", "INITIAL_STATES"),
    "qasm_version": lambda: (3, 2),
    "qasm_profile": _lazy("qcpp.lowering.qasm_profiles", "PROFILES"),
    "solve.method": _lazy("qcpp.cli.commands.solve", "SOLVE_METHODS"),
    "solve.optimizer": _lazy("qcpp.training.qaoa_solver", "QAOA_OPTIMIZERS"),
    "phase_layout": _lazy("qcpp.plan.options", "PHASE_LAYOUTS"),
    "compile.layout": _lazy("qcpp.plan.options", "LAYOUT_METHODS"),
    "compile.optimize_for": _lazy("qcpp.pipeline.candidates", "OPTIMIZE_FOR"),
    "compile.effort": _lazy("qcpp.routing.options", "EFFORTS"),
    "estimate.effort": _lazy("qcpp.routing.options", "EFFORTS"),
    "compile.angles": _lazy("qcpp.plan.options", "ANGLES"),  # --mixer-angles (simulate's --angles are values)
    "estimate.angles": _lazy("qcpp.plan.options", "ANGLES"),
    "simulate.method": _lazy("qcpp.training.evaluate", "METHODS"),
    "validate.backend": _lazy("qcpp.simulate.validate", "BACKENDS"),
    "verify.method": _lazy("qcpp.verification.report", "METHODS"),
    "estimate.fmt": _lazy("qcpp.estimators.tables", "FORMATS"),
    "estimate.compare": lambda: ("paper",),
    "estimate.depth": _lazy("qcpp.estimators.estimate", "DEPTH_MODES"),
    "estimate.qubit_model": _lazy("qcpp.estimators.physical", "QUBIT_MODELS"),
    "estimate.qec_scheme": _lazy("qcpp.estimators.physical", "QEC_SCHEMES"),
    "estimate.paper_doubling": _lazy("qcpp.estimators.paper", "DOUBLINGS"),
    "estimate.toffoli_t": _lazy("qcpp.estimators.fault_tolerant", "TOFFOLI_T_CHOICES"),
    "export.fmt": _lazy("qcpp.qubo.export", "EXPORT_FORMATS"),
    "export.form": _lazy("qcpp.qubo.model", "FORMS"),
}
"""Options that take one of a fixed set of values: ``command.param`` (or ``param`` in every command) -> the
values, read from the constant the command validates against when help is shown (not at start-up: some live
behind heavy imports). ``--help`` shows them as ``[a|b|c]`` instead of ``<str>``, and shell completion offers
them. A value outside them is refused before the command runs (``--rule: expected exact or paper, got 'fast'``),
except for the options of :data:`LIBRARY_CHECKED`."""

LIBRARY_CHECKED = frozenset({"solve.optimizer", "solve.initial"})
"""Choice options whose values the library checks itself, with its own message (``unknown optimizer 'adam'``)."""


def choices_of(command: str, param: str) -> tuple[str, ...] | None:
    """The values of a choice option (:data:`CHOICES`), as text; ``None`` for any other option.

    Example:
        >>> choices_of("solve", "rule")
        ('exact', 'paper')
    """
    source = CHOICES.get(f"{command}.{param}") or CHOICES.get(param)
    return tuple(str(v) for v in source()) if source is not None else None


CHOICES_IN_METAVAR = 16
"""Choice lists up to this many characters show as the metavar ``[a|b|c]``; longer ones go into the option's help
text (``One of: a, b, c.``, unless it names each already), where they wrap across the wide column instead of
widening the narrow one."""


def _show_choices(command: Any) -> None:
    """Show each choice option's values (at help time: the values may need heavy imports): as the metavar
    ``[a|b|c]``, or, if that is longer than :data:`CHOICES_IN_METAVAR`, at the end of its help text."""
    for param in command.params:
        values = choices_of(command.name or "", param.name or "") if _is_option(param) else None
        if not values:
            continue
        shown = "[" + "|".join(values) + "]"
        if len(shown) <= CHOICES_IN_METAVAR:
            param.metavar = shown
            continue
        own = param.__dict__.setdefault("_own_help", param.help or "")
        param.metavar = "<str>"
        named = all(re.search(rf"(?<![\w-]){re.escape(v)}(?![\w-])", own) for v in values)
        param.help = own if named else f"{own} One of: {', '.join(values)}.".strip()


def _complete_choices(command: Any) -> None:
    """Make shell completion offer each choice option's values (looked up when completing)."""
    for param in command.params:
        key = f"{command.name}.{param.name}"
        if _is_option(param) and (key in CHOICES or param.name in CHOICES):

            def complete(ctx: Any, p: Any, incomplete: str, name: str = param.name or "") -> list[str]:
                return [v for v in choices_of(command.name or "", name) or () if v.startswith(incomplete)]

            param._custom_shell_complete = complete


PANELS: dict[str, str] = {
    # what the command works on
    "scenario": "Scenario", "grid": "Scenario", "robots": "Scenario", "robot": "Scenario", "obstacle": "Scenario",
    "hard_obstacles": "Scenario", "p": "Scenario", "counts": "Scenario",
    # how the circuit is built (compile, estimate, validate: qcpp.cli.commands.plan_flags)
    "rule": "Plan", "initial": "Plan", "target": "Plan", "phase": "Plan", "optimize": "Plan",
    "ancilla_budget": "Plan", "phase_layout": "Plan", "angles": "Plan", "skip_first_phase": "Plan", "lowered": "Plan",
    "bind": "Plan",
    # the run of the other commands
    "method": "Method", "seed": "Method", "optimizer": "Method", "objective": "Method", "maxiter": "Method",
    "mixer_warm": "Method", "restart_every_level": "Method", "gibbs_scale": "Method", "time_limit": "Method",
    "backend": "Method", "max_amplitudes": "Method",
    "dask": "Method", "samples": "Method", "form": "Method", "penalty": "Method",
    "solve.rule": "Method", "solve.initial": "Method", "solve.p": "Method", "solve.sampler": "Method",
    "solve.workers": "Method", "solve.iterations": "Method", "solve.generations": "Method",
    "simulate.rule": "Method",
    "simulate.angles": "Method", "validate.angle_values": "Method", "verify.rule": "Method",
    "optimum": "Method",
    # estimate's models
    "depth": "Estimates", "depth_budget": "Estimates", "epsilon": "Estimates", "toffoli_t": "Estimates",
    "paper_doubling": "Estimates", "physical": "Estimates", "qubit_model": "Estimates",
    "qec_scheme": "Estimates", "error_budget": "Estimates",
    "device": "Device/routing", "local_ancillas": "Device/routing", "layout": "Device/routing",
    "optimize_for": "Device/routing", "zero_start": "Device/routing", "effort": "Device/routing",
    # what is written where
    "as_json": "Output", "fmt": "Output", "columns": "Output", "wide": "Output", "compare": "Output",
    "plot": "Output", "metric": "Output", "plot_trace_file": "Output", "qasm": "Output", "qasm_version": "Output",
    "qasm_profile": "Output", "out": "Output", "output": "Output", "explain": "Output", "formula": "Output",
    "draw": "Output", "measure": "Output", "top": "Output",
    "max_gates": "Advanced", "force": "Advanced", "allow_large": "Advanced", "help": "Advanced",
}  # fmt: skip
"""The help panel of each option, by parameter name (``command.param`` first): every command groups its options
alike, in the panels' order here (``tests/cli/help_and_noise_test.py`` checks that no option is left out)."""

_PANEL_ORDER = tuple(dict.fromkeys(PANELS.values()))


def _panel(command: str, param: Parameter) -> str | None:
    return PANELS.get(f"{command}.{param.name}") or PANELS.get(param.name or "")


def _set_panels(command: Any, params: Sequence[Parameter]) -> None:
    """Put each option into its panel (:data:`PANELS`); arguments stay in typer's ``Arguments`` panel."""
    for param in params:
        panel = _panel(command.name or "", param) if _is_option(param) else None
        if panel is not None:
            param.rich_help_panel = panel  # type: ignore[attr-defined]


def _one_row_per_flag(params: Sequence[Parameter]) -> list[Parameter]:
    """``params`` for the help text, an ``--x/--no-x`` flag shown as two rows: ``--x`` with its help, then ``--no-x``
    ("The opposite of --x."), each name in the option column.

    typer gives the ``--no-x`` form a column of its own in the option's panel, which then leaves so little room at 80
    columns that rich cuts the names (``--restart-every-…``). The copies only display; parsing keeps ``params``.
    """
    import copy

    shown: list[Parameter] = []
    for param in params:
        if not (_is_option(param) and param.secondary_opts):
            shown.append(param)
            continue
        negative = copy.copy(param)
        positive = copy.copy(param)
        positive.secondary_opts = []
        negative.opts, negative.secondary_opts = list(param.secondary_opts), []
        negative.help = f"The opposite of {max(param.opts, key=len)}."  # type: ignore[attr-defined]
        negative.show_default = False  # type: ignore[attr-defined]
        shown += [positive, negative]
    return shown


def _refuse_repeated(command: Any, ctx: Context, args: Sequence[str]) -> None:
    """Refuse an option that takes one value given more than once (``--grid 12x20 --grid 20x30``): click would
    keep the last and drop the others unsaid, so a sweep meant over both would silently be of one. Options that
    collect their values (``--robot``, ``--obstacle``) and flags are not refused.

    Raises:
        click's BadParameter: the first such option, naming it and how often it was given (exit 2, one line).
    """
    if ctx.resilient_parsing:  # shell completion parses partial lines: nothing to refuse there
        return
    _, _, order = command.make_parser(ctx).parse_args(args=list(args))  # its errors are super().parse_args's too
    seen: dict[str, int] = {}
    for param in order:
        if not _is_option(param) or param.multiple or param.count or param.is_flag:  # type: ignore[attr-defined]
            continue
        name = param.name or ""
        seen[name] = seen.get(name, 0) + 1
        if seen[name] == 2:
            times = sum(q is param for q in order)
            hint = " (it takes a comma list)" if "comma" in (getattr(param, "help", None) or "") else ""
            reason = f"given {'twice' if times == 2 else f'{times} times'}; give it once{hint}"
            raise _click_exc.BadParameter(reason, ctx=ctx, param=param)


class QcppCommand(_TidyHelp, TyperCommand):
    """A typer command whose help shows flags as flags, choice options' values (:data:`CHOICES`), the options
    in panels (:data:`PANELS`), and each name of an ``--x/--no-x`` flag on a row of its own
    (:func:`_one_row_per_flag`), so that no option name is cut at 80 columns; an option of one value given twice
    is refused (:func:`_refuse_repeated`).
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        _complete_choices(self)

    def get_help_option(self, ctx: Context) -> Any:
        option = super().get_help_option(ctx)
        if option is not None:
            _set_panels(self, [option])
        return option

    def parse_args(self, ctx: Context, args: list[str]) -> list[str]:
        _refuse_repeated(self, ctx, args)
        return super().parse_args(ctx, args)

    def format_help(self, ctx: Context, formatter: Any) -> None:
        _show_choices(self)
        _set_panels(self, self.params)
        kept = self.params
        rank = {name: i for i, name in enumerate(_PANEL_ORDER)}
        # typer prints the panels in the order of their first option: list the options panel by panel
        shown = _one_row_per_flag(kept)
        self.params = sorted(shown, key=lambda q: rank.get(getattr(q, "rich_help_panel", None) or "", -1))
        try:
            super().format_help(ctx, formatter)
        finally:
            self.params = kept


class QcppGroup(_TidyHelp, TyperGroup):
    """The top-level group: one-line usage errors (exit 2), ``interrupted`` (exit 130), and one line for any other
    exception, a bug (exit 1; its traceback with ``QCPP_DEBUG=1``)."""

    def invoke(self, ctx: Context) -> Any:
        try:
            return super().invoke(ctx)
        except KeyboardInterrupt:
            report_interrupted()
            raise typer.Exit(code=EXIT_INTERRUPTED) from None
        except Exception:
            if not stop_requested():
                raise
            report_interrupted()  # an exception the signal caused, not a bug
            raise typer.Exit(code=EXIT_INTERRUPTED) from None

    def main(  # type: ignore[override]
        self,
        args: Sequence[str] | None = None,
        prog_name: str | None = None,
        complete_var: str | None = None,
        standalone_mode: bool = True,
        **extra: Any,
    ) -> Any:
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        try:
            rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except _click_exc.NoArgsIsHelpError as exc:
            typer.echo(exc.format_message(), err=True)
            sys.exit(EXIT_USAGE)
        except _click_exc.ClickException as exc:
            typer.echo(usage_error_line(exc), err=True)
            sys.exit(EXIT_USAGE)
        except typer.Abort:
            report_interrupted()
            sys.exit(EXIT_INTERRUPTED)
        except KeyboardInterrupt:
            report_interrupted()
            sys.exit(EXIT_INTERRUPTED)
        except Exception as exc:  # not bad input (handle_errors took that) nor a click exit: a bug
            if stop_requested():  # outside invoke (typer building the context): what the signal broke
                report_interrupted()
                sys.exit(EXIT_INTERRUPTED)
            if _debugging():
                raise
            typer.echo(internal_error_line(exc), err=True)
            sys.exit(EXIT_INTERNAL)
        if rv == EXIT_INTERRUPTED and stop_requested():
            # typer >= 0.2x turns a KeyboardInterrupt outside invoke (its lazy imports while it builds the
            # context) into Exit(130), which standalone_mode=False returns silently: say it, as everywhere else
            report_interrupted()
        sys.exit(rv if isinstance(rv, int) and not isinstance(rv, bool) else 0)


class QcppTyper(typer.Typer):
    """A :class:`typer.Typer` built on :class:`QcppGroup` whose commands are wrapped in :func:`handle_errors`."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("cls", QcppGroup)
        super().__init__(*args, **kwargs)

    def command(self, name: str | None = None, **kwargs: Any) -> Callable[[F], F]:  # type: ignore[override]
        kwargs.setdefault("cls", QcppCommand)
        register = super().command(name, **kwargs)

        def decorator(fn: F) -> F:
            register(handle_errors(fn))
            return fn

        return decorator


HELP = """QAOA multi-robot coverage path planning: solve scenarios, compile circuits, estimate resources.

Examples:
  qcpp scenario --grid 5x5 --robots 2 --obstacle 2,1 -o field.toml
  qcpp estimate --grid 6x8 --robots 1..3 -p 1..3 --format md
  qcpp compile field.toml -p 2 --lowered --qasm field.qasm
  qcpp solve field.toml --method cpsat

'qcpp COMMAND --help' shows a command's options and more examples.
"""

app = QcppTyper(
    name="qcpp",
    help=HELP,
    no_args_is_help=True,
    add_completion=True,
    pretty_exceptions_show_locals=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"qcpp {__version__}")
        raise typer.Exit()


@app.callback(help=HELP)
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Print the version and exit.")
    ] = False,
) -> None:
    """QAOA multi-robot coverage path planning: solve scenarios, compile circuits, estimate resources."""


for _name in COMMAND_MODULES:
    importlib.import_module(_name).register(app)


def _stdout_failure() -> str | None:
    """Flush stdout; if that fails (``> /dev/full``), point it at ``/dev/null`` and return the reason."""
    try:
        sys.stdout.flush()
        return None
    except OSError as exc:
        reason = exc.strerror or str(exc) or type(exc).__name__
    with contextlib.suppress(OSError, ValueError, AttributeError):  # keep later flushes from failing again
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    return reason


def _finish_stdout(code: Any) -> Any:
    """Flush stdout; a failed flush (``> /dev/full``) is one error line and exit code 2, not a traceback."""
    try:
        sys.stdout.flush()
    except BrokenPipeError:  # the reader left (``| head``): nothing to report
        _stdout_failure()
        return code or 1
    except OSError:
        reason = _stdout_failure()
        typer.echo(f"error: cannot write standard output: {reason}", err=True)
        return EXIT_USAGE
    if not code and _reader_gone():
        return 1  # the reader (``| head -1``) left: the rest was written into the pipe but never read
    return code


def _reader_gone() -> bool:
    """Whether standard output is a pipe whose reading end is closed (``poll`` says ``POLLERR``)."""
    import select
    import stat

    try:
        if not stat.S_ISFIFO(os.fstat(1).st_mode):
            return False
        poller = select.poll()
        poller.register(1, select.POLLOUT)
        return any(events & select.POLLERR for _, events in poller.poll(0))
    except (OSError, ValueError, AttributeError):
        return False


def main() -> None:
    """Run the app with Ctrl-C/SIGTERM handling (the console script enters through :func:`qcpp.__main__.main`)."""
    from qcpp.cli.interrupt import install
    from qcpp.cli.streams import guard_closed_streams

    guard_closed_streams()
    install()
    try:
        app(prog_name="qcpp")
    except SystemExit as exc:
        code = exc.code
    else:  # pragma: no cover - the group always exits
        code = 0
    code = _finish_stdout(code)
    if code == EXIT_INTERRUPTED:  # skip freeing what the interrupted work built (seconds for millions of gates)
        with contextlib.suppress(OSError, ValueError):
            sys.stderr.flush()
        os._exit(EXIT_INTERRUPTED)
    sys.exit(code)
