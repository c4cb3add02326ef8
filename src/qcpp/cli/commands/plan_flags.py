"""The plan flags shared by ``qcpp compile``, ``qcpp estimate`` and ``qcpp validate``: one definition, one
:class:`PlanOptions`; and the flags every scenario command declares alike (:data:`LayersFlag`, ``--rule``; the
scenario argument and its inline flags: :mod:`qcpp.cli.commands.inline_scenario`).

Each command takes an ``options: PlanOptions`` parameter and is decorated with :func:`with_plan_flags`, which
puts the plan flags in its place and builds the options with :func:`plan_options`, so they accept exactly the
same flags with the same help, defaults and checks (``tests/cli/plan_flags_test.py`` compares them).

Example:
    >>> plan_options("exact", "representatives", "ft", "feasible", "cx", None).initial
    'representatives'
    >>> plan_options("exact", "path", "nisq", "feasible", "cx", None)
    Traceback (most recent call last):
    ...
    ValueError: --initial: expected initial_path or representatives or local_search or local_search_mix, got 'path'
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from typing import TYPE_CHECKING, Annotated, Any, TypeVar, get_type_hints

import typer

from qcpp.cli.commands.inline_scenario import one_whole_number
from qcpp.errors import OptionError
from qcpp.plan.options import PlanOptions

if TYPE_CHECKING:
    from qcpp.problem.scenario import Scenario

__all__ = [
    "PLAN_FLAGS",
    "AncillaBudgetFlag",
    "AnglesFlag",
    "InitialFlag",
    "LayersFlag",
    "OptimizeFlag",
    "PhaseFlag",
    "PhaseLayoutFlag",
    "RuleFlag",
    "SkipFirstPhaseFlag",
    "TargetFlag",
    "check_start",
    "plan_flag_message",
    "plan_options",
    "with_plan_flags",
]

LayersFlag = Annotated[
    int, typer.Option("-p", "--layers", help="QAOA layers (at least 1).", parser=one_whole_number("-p/--layers"))
]
RuleFlag = Annotated[str, typer.Option("--rule", help="SBF logic rule.")]
InitialFlag = Annotated[
    str,
    typer.Option(
        "--initial",
        help="Initial state: initial_path, representatives, local_search (a classical warm start) or "
        "local_search_mix (both paths in superposition).",
    ),
]
TargetFlag = Annotated[
    str,
    typer.Option(
        "--target",
        help="Choose constructions for nisq (fewest CNOTs) or ft (fewest T and rotations).",
    ),
]
PhaseFlag = Annotated[
    str,
    typer.Option(
        "--phase",
        help="Phase separator: feasible (exact on feasible paths) or whole-space (the Ising one).",
    ),
]
OptimizeFlag = Annotated[
    str, typer.Option("--optimize", help="Phase separator: fewest CX, or shallow coupling layers.")
]
AncillaBudgetFlag = Annotated[
    int | None,
    typer.Option("--ancilla-budget", help="Most ancillas of the phase separator (fewer cost more CX)."),
]

PhaseLayoutFlag = Annotated[
    str,
    typer.Option(
        "--phase-layout",
        help="Phase separator layout: pooled (fewest CX), spatial or medial (fewer routed CX), or auto (medial "
        "or spatial with a --device).",
    ),
]

AnglesFlag = Annotated[
    str,
    typer.Option(
        "--mixer-angles",
        help="Mixer angles: one per layer, or one per partial mixer (multi-angle QAOA; same gates).",
    ),
]

SkipFirstPhaseFlag = Annotated[
    bool,
    typer.Option(
        "--skip-first-phase",
        help="Omit the first phase separator: on a basis-state start (initial_path, local_search) it is a global "
        "phase, so the state is the same (gamma_0 stays a name with no gate).",
    ),
]

PLAN_FLAGS: tuple[str, ...] = (
    "--rule", "--initial", "--target", "--phase", "--optimize", "--ancilla-budget", "--phase-layout", "--mixer-angles",
    "--skip-first-phase",
)
"""The flags above, in :class:`~qcpp.plan.options.PlanOptions` field order."""

_PARAMETERS: tuple[tuple[str, Any], ...] = (
    ("rule", RuleFlag), ("initial", InitialFlag), ("target", TargetFlag), ("phase", PhaseFlag),
    ("optimize", OptimizeFlag), ("ancilla_budget", AncillaBudgetFlag), ("phase_layout", PhaseLayoutFlag),
    ("angles", AnglesFlag), ("skip_first_phase", SkipFirstPhaseFlag),
)  # fmt: skip
_DEFAULTS: dict[str, Any] = {"skip_first_phase": False}
"""The flags that are no field of :class:`~qcpp.plan.options.PlanOptions` (``--skip-first-phase`` is
``first_phase=False``), with their defaults."""

FLAG_OF_FIELD: dict[str, str] = {"angles": "--mixer-angles", "first_phase": "--skip-first-phase"}
"""The plan flags whose name is not their field's (``ancilla_budget`` is ``--ancilla-budget``)."""

F = TypeVar("F", bound=Callable[..., Any])


def with_plan_flags(command: F) -> F:
    """``command`` with the plan flags in place of its ``options`` parameter (after its own parameters; defaults
    those of :class:`~qcpp.plan.options.PlanOptions`), called with the options they build (:func:`plan_options`).
    """
    defaults, keyword = PlanOptions(), inspect.Parameter.KEYWORD_ONLY
    flags = [
        inspect.Parameter(name, keyword, default=_DEFAULTS[name] if name in _DEFAULTS else getattr(defaults, name),
                          annotation=a)
        for name, a in _PARAMETERS
    ]  # fmt: skip
    sig = inspect.signature(command, eval_str=True)
    hints = get_type_hints(command, include_extras=True)

    @functools.wraps(command)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        options = plan_options(*(kwargs.pop(name) for name, _ in _PARAMETERS))
        return command(*args, options=options, **kwargs)

    own = [q for q in sig.parameters.values() if q.name != "options"]
    wrapper.__signature__ = sig.replace(parameters=[*own, *flags])  # type: ignore[attr-defined]
    wrapper.__annotations__ = {**{q.name: hints[q.name] for q in own}, **{q.name: q.annotation for q in flags}}
    return wrapper  # type: ignore[return-value]


def plan_options(
    rule: str, initial: str, target: str, phase: str, optimize: str, ancilla_budget: int | None,
    phase_layout: str = "auto", angles: str = "layer", skip_first_phase: bool = False,
) -> PlanOptions:
    """The :class:`~qcpp.plan.options.PlanOptions` of the plan flags.

    Args:
        rule, initial, target, phase, optimize, ancilla_budget, phase_layout, angles: the flags' values
            (``angles`` is ``--mixer-angles``).
        skip_first_phase: ``--skip-first-phase`` (``first_phase=False``).

    Raises:
        ValueError: one line naming the flag (``--initial: expected ..., got ...``).
    """
    try:
        return PlanOptions(
            rule=rule, initial=initial, target=target, phase=phase, optimize=optimize,  # type: ignore[arg-type]
            ancilla_budget=ancilla_budget, phase_layout=phase_layout, angles=angles,  # type: ignore[arg-type]
            first_phase=not skip_first_phase,
        )
    except ValueError as exc:
        raise ValueError(plan_flag_message(exc)) from None


def plan_flag_message(exc: ValueError) -> str:
    """A plan option's message (``field: problem``, :class:`~qcpp.errors.OptionError`) with the field named by its
    flag, as the command line says it: ``first_phase: ...`` is ``--skip-first-phase: ...``.

    Example:
        >>> from qcpp.errors import OptionError
        >>> plan_flag_message(OptionError("ancilla_budget", "expected an integer >= 0, got -1"))
        '--ancilla-budget: expected an integer >= 0, got -1'
    """
    field, _, problem = str(exc).partition(": ")  # PlanOptions names the field first
    return f"{FLAG_OF_FIELD.get(field, '--' + field.replace('_', '-'))}: {problem}"


def check_start(scenario: Scenario, options: PlanOptions) -> None:
    """Refuse ``--skip-first-phase`` where the scenario's start is not a basis state, before any work: the check of
    :func:`qcpp.plan.qaoa.qaoa_plan`, its message naming the flag.

    Raises:
        qcpp.errors.OptionError: ``--skip-first-phase: ...`` naming the initial state.
    """
    if options.first_phase:
        return
    from qcpp.plan.qaoa import qaoa_plan  # here: the plan is not loaded by every command's start-up

    try:
        qaoa_plan(scenario, 0, options)  # builds the state preparation only
    except OptionError as exc:
        raise OptionError("--skip-first-phase", exc.reason) from None
