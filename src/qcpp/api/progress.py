"""The ``progress=`` argument of the long API calls: one mechanism for ``qcpp.compile``, ``train_qaoa``,
``solve``, ``validate``, ``estimate``, ``verify`` and ``simulate_noisy``.

Every one of them takes the same three kinds of value:

* ``None`` or ``False`` (the default): nothing is reported;
* ``True``: a progress line on stderr, as the command line writes on a pipe (:class:`qcpp.io.progress.Progress`
  in its ``lines`` form): nothing for the first second, then a line every few seconds
  (``QCPP_PROGRESS_INTERVAL``) with the counts, the stage and the elapsed time, and a last line when it ends. In a
  notebook the lines appear under the cell;
* a function ``progress(done, total)`` (:data:`qcpp.problem.solvers.ProgressFn`), called from the calling thread
  as the work advances: ``done`` counts the call's steps (each call documents its unit) and ``total`` is their
  number, or ``None`` where it is not known in advance (CP-SAT's improving solutions, the stages of a device
  compile). Whatever it raises ends the call (``KeyboardInterrupt`` included).

:func:`reporting` turns the argument into the :class:`Reporter` the work is given: its ``update`` is the
``ProgressFn`` the library's loops already call (``bar and bar.update``: ``None`` without a reporter), its
``stage`` the ``stage(text)`` hook of the pipelines that name their stages (device compiles, validation). For a
function, where the call counts stages (``stages=True``) each
stage that starts is one step: ``progress(1, None)``, ``progress(2, None)``, ...

Example:
    >>> seen = []
    >>> with reporting(lambda done, total: seen.append((done, total)), "demo", total=2) as bar:
    ...     bar.update(1)
    ...     bar.update(2)
    >>> seen
    [(1, 2), (2, 2)]
    >>> with reporting(None, "demo") as bar:
    ...     print(bar)  # nothing to report: the work runs without hooks
    None
    >>> check_progress_arg("yes")
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: progress: expected True, False, None or a function progress(done, total), got 'yes'
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from typing import Protocol

from qcpp.errors import OptionError

__all__ = ["ProgressArg", "Reporter", "check_progress_arg", "reporting"]

ProgressArg = bool | Callable[[int, int | None], None] | None
"""What ``progress=`` accepts: ``None``/``False``, ``True``, or a function ``progress(done, total)``."""


class Reporter(Protocol):
    """What the work of a call is given: counts (``update``) and stage names (``stage``)."""

    def update(self, done: int, total: int | None = None) -> None:
        """``done`` steps of ``total`` (``None``: the total is unchanged or not known)."""

    def stage(self, text: str) -> None:
        """A stage starts (a few words: ``routing the whole circuit on ibm_fez``)."""


def check_progress_arg(progress: object) -> ProgressArg:
    """``progress`` if it is ``None``, ``True``, ``False`` or callable.

    Raises:
        qcpp.errors.OptionError: anything else (naming ``progress``).
    """
    if progress is None or isinstance(progress, bool) or callable(progress):
        return progress  # type: ignore[return-value]
    raise OptionError("progress", f"expected True, False, None or a function progress(done, total), got {progress!r}")


class _Callback:
    """A user's ``progress(done, total)``: counts passed on; stages counted as steps where ``stages``."""

    def __init__(self, fn: Callable[[int, int | None], None], total: int | None, stages: bool) -> None:
        self._fn = fn
        self._total = total
        self._stages = stages
        self._started = 0

    def update(self, done: int, total: int | None = None) -> None:
        if total is not None:
            self._total = total
        self._fn(done, self._total)

    def stage(self, text: str) -> None:
        if self._stages:
            self._started += 1
            self._fn(self._started, None)


@contextlib.contextmanager
def reporting(
    progress: ProgressArg, task: str, *, unit: str = "steps", total: int | None = None, stages: bool = False,
    time_left: bool = True, deadline: float | None = None,
) -> Iterator[Reporter | None]:  # fmt: skip
    """The :class:`Reporter` of one call's ``progress`` argument, for the duration of the ``with`` block (``None``
    when nothing is to be reported: the work then runs without hooks, as it would without the argument).

    Args:
        progress: The call's ``progress`` argument (checked with :func:`check_progress_arg`).
        task: What runs, a few words starting the lines of ``progress=True`` (``compile 30x30, 8 robot(s), p=3``).
        unit: What a step is, plural (``gates``, ``levels``).
        total: Steps in all, if known.
        stages: For a function: count each stage as a step (calls whose work reports stages only).
        time_left: ``progress=True``: show the time left (``False`` where steps differ too much in cost).
        deadline: ``progress=True``: seconds after the start at which the work stops (a time limit): the time left
            shown is at most what remains until then.

    Raises:
        qcpp.errors.OptionError: ``progress`` is none of the accepted kinds.
    """
    progress = check_progress_arg(progress)
    if progress is None or progress is False:
        yield None
    elif progress is True:
        from qcpp.io.progress import Progress  # the command line's lines: one format for a log and a notebook

        with Progress(task, total=total, unit=unit, mode="lines", time_left=time_left, deadline=deadline) as bar:
            yield bar
    else:
        yield _Callback(progress, total, stages)  # type: ignore[arg-type]
