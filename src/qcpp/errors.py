"""The one error hierarchy of qcpp: every bad input a public function refuses is a :class:`QcppError`.

:class:`QcppError` derives from ``ValueError``, so ``except ValueError`` keeps working; its subclasses say what
was wrong (:class:`~qcpp.problem.errors.ScenarioError` for a scenario, :class:`OptionError` for an option such as
``p`` or a plan option, :class:`~qcpp.hardware.device.DeviceError` for a device,
:class:`~qcpp.ir.angles.UnboundParameterError` for symbols without a value). Every message is one line, the same
line the command line prints after ``error:`` for the same mistake.

This module imports nothing from qcpp, so that every layer can raise these errors.

The checks here are shared by the command line and the Python API (:mod:`qcpp.api`), which name the option in
their own way (``-p/--layers`` or ``p``) and give the same reason after it.

Example:
    >>> check_count(0, "p")
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: p: must be at least 1, got 0
    >>> check_choice("fast", ("exact", "paper"), "rule")
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: rule: expected exact or paper, got 'fast'
    >>> issubclass(OptionError, ValueError)
    True
"""

from __future__ import annotations

from collections.abc import Iterable

__all__ = [
    "MissingExtraError",
    "OptionError",
    "QcppError",
    "check_choice",
    "check_count",
    "choice_reason",
    "missing_extra",
]


class QcppError(ValueError):
    """Bad input to qcpp (a scenario, an option, a device name, ...): the message is one line saying what and why."""


class MissingExtraError(QcppError, ImportError):
    """An optional dependency is not installed (Cirq, pytket, qiskit-aer, dimod, ...): the message names what
    needs it, what is missing and the extra that installs it (:func:`missing_extra`).

    A :class:`QcppError` (so the command line prints it as one line, exit 2, and ``except qcpp.QcppError`` catches
    every refusal) and an ``ImportError`` (so ``except ImportError`` around an optional feature keeps working).
    """


def missing_extra(what: str, needs: str, extra: str, missing: str | None = None) -> MissingExtraError:
    """The error of an optional dependency that is not installed, worded alike for the API and the command line.

    Args:
        what: What needs it, as any caller reads it (``to_cirq``, ``the QUBO samplers``).
        needs: The packages (``cirq-core``, ``dimod and dwave-samplers``).
        extra: The qcpp extra that installs them (``cirq``).
        missing: The module that failed to import (``ImportError.name``), if known.

    Example:
        >>> print(missing_extra("to_cirq", "cirq-core", "cirq", "cirq"))
        to_cirq needs cirq-core (cirq is missing): pip install 'qcpp[cirq]'
        >>> isinstance(missing_extra("x", "y", "z"), ImportError)
        True
    """
    gone = f" ({missing} is missing)" if missing else ""
    return MissingExtraError(f"{what} needs {needs}{gone}: pip install 'qcpp[{extra}]'")


class OptionError(QcppError):
    """An option value that is out of range, of the wrong type, or unknown (``p``, a plan option, a binding).

    The message starts with the option it is about (``p: must be at least 1, got 0``), unless ``field`` is empty.

    Args:
        field: The option's name as the caller spells it (``p``, ``-p/--layers``, ``rule``); may be empty.
        reason: What is wrong with it.
    """

    def __init__(self, field: str, reason: str) -> None:
        self.field = field
        self.reason = reason
        super().__init__(f"{field}: {reason}" if field else reason)

    def __reduce__(self) -> tuple[type[OptionError], tuple[str, str]]:
        # picklable with both arguments, so that errors cross process-pool boundaries intact
        return (type(self), (self.field, self.reason))


def check_count(value: object, name: str, low: int = 1) -> int:
    """``value`` if it is an integer of at least ``low`` (a count such as ``p``), else :class:`OptionError`.

    Args:
        value: The value given.
        name: The option's name in the message.
        low: The smallest value allowed.

    Returns:
        ``value``.

    Raises:
        OptionError: not an integer (``bool`` is refused too) or below ``low``.
    """
    if isinstance(value, bool) or not isinstance(value, int):
        raise OptionError(name, f"expected an integer, got {value!r}")
    if value < low:
        raise OptionError(name, f"must be at least {low}, got {value}")
    return value


def choice_reason(value: object, values: Iterable[object]) -> str:
    """The reason a value outside ``values`` is refused: ``expected a or b, got 'c'``."""
    return f"expected {' or '.join(str(v) for v in values)}, got {value!r}"


def check_choice(value: object, values: Iterable[object], name: str) -> None:
    """Refuse ``value`` unless it is one of ``values`` (compared as given and as text).

    Raises:
        OptionError: naming ``name`` and listing ``values`` (:func:`choice_reason`).
    """
    allowed = tuple(values)
    if value not in allowed and str(value) not in {str(v) for v in allowed}:
        raise OptionError(name, choice_reason(value, allowed))
