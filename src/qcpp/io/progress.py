"""Progress of long work on stderr: a bar on a terminal, a line every few seconds on a pipe or file.

One mechanism for the command line (:mod:`qcpp.cli.progress`) and the API's ``progress=True``
(:mod:`qcpp.api.progress`), so a log and a notebook read the same lines; it lives in the lowest layer because both
use it. :class:`Progress` is a context manager that knows the task, its size (when known), how far the work got and
which stage it is in. Stdout is never touched, so ``--json``, CSV and OpenQASM on stdout stay clean.

* **Terminal** (stderr is a TTY): a transient rich bar, erased when the work ends.
* **Pipe or file**: nothing for the first :data:`FIRST_LINE_AFTER` seconds, then one line every
  :data:`DEFAULT_INTERVAL` seconds from a heartbeat thread (so one long native call still shows it is alive),
  e.g. ``estimate: 1,234 / 60,807 rows (2.0%), 6 s elapsed, about 4 min left``, and a last line when it ends. A
  new stage is written at once where no line came for as long (a native call that holds the GIL starves the
  heartbeat, so a stage that starts one announces itself) and the heartbeat's next line waits an interval from
  it (not a copy of it a moment later), so a log gets about one line per interval however fast the stages change.
  Every line fits the terminal's width (:func:`qcpp.io.text.terminal_width`: ``$COLUMNS``, else 80 on a pipe): the
  counts, the share and the times are never cut; the task is cut at its end (down to its first word) and then the
  stage in its middle, where a stage's own counts (``(3 / 6)``) sit at its end and stay, with ``…`` for what went.
  Cuts fall between words where a boundary is within :data:`WORD_REACH` characters; only a longer word (a path) is
  cut inside.
* ``QCPP_PROGRESS`` picks the form (``auto``, ``bar``, ``lines``, ``off``); ``QCPP_PROGRESS_INTERVAL`` sets the
  seconds between lines (``0``: a line at every step, synchronously, so tests never depend on timing).
* While numba compiles (the first run after installing compiles the simulators' kernels, up to a minute), the
  stage shown is :data:`COMPILING`: once numba is imported the progress listens to its ``numba:compile`` events
  (numba's event API), which fire only when a kernel is not in numba's on-disk cache.

The work itself never imports this module: it takes plain callbacks (``progress(done, total)``,
:data:`qcpp.problem.solvers.ProgressFn`; ``stage(text)``), and the command or the API call passes
:meth:`Progress.update` and :meth:`Progress.stage`.

Example:
    >>> import io
    >>> out = io.StringIO()
    >>> with Progress("demo", total=2, unit="steps", stream=out, mode="lines", interval=0) as bar:
    ...     for _ in bar.iterate(["a", "b"]):
    ...         pass
    >>> [line.split(", ")[0] for line in out.getvalue().splitlines()]  # then elapsed time (and time left)
    ['demo: 0 / 2 steps (0.0%)', 'demo: 1 / 2 steps (50.0%)', 'demo: 2 / 2 steps (100.0%)', 'demo: 2 steps done in 0 s']
"""

from __future__ import annotations

import contextlib
import math
import os
import re
import sys
import threading
import time
from collections.abc import Iterable, Iterator
from types import TracebackType
from typing import Any, Literal, TextIO, TypeVar

from qcpp.io.text import format_duration, terminal_width

__all__ = [
    "COMPILING",
    "DEFAULT_INTERVAL",
    "FIRST_LINE_AFTER",
    "INTERVAL_ENV",
    "MODE_ENV",
    "Mode",
    "Progress",
    "progress_mode",
]

Mode = Literal["auto", "bar", "lines", "off"]
MODES: tuple[Mode, ...] = ("auto", "bar", "lines", "off")

MODE_ENV = "QCPP_PROGRESS"
"""Environment variable choosing the form of progress: ``auto`` (default), ``bar``, ``lines`` or ``off``."""

INTERVAL_ENV = "QCPP_PROGRESS_INTERVAL"
"""Environment variable: seconds between progress lines on a pipe (``0``: a line at every step)."""

DEFAULT_INTERVAL = 5.0
"""Seconds between two progress lines on a pipe or file."""

FIRST_LINE_AFTER = 1.0
"""Seconds of work before the first progress line on a pipe (quicker commands print none)."""

HEARTBEAT_JOIN_SECONDS = 1.0
"""How long leaving a :class:`Progress` waits for its heartbeat thread."""

MIN_STAGE = 12
"""Fewest characters a cut stage keeps in a line; with less room the line leaves the stage out."""

WORD_REACH = 20
"""A line cut short ends at a word boundary found within this many characters before the cut, so no word is split;
where none is (a long path or name), the word is cut, and the ``…`` shows it."""

BAR_WIDTH = 20
"""Characters of the bar on a terminal (rich's default, 40, leaves an 80-column terminal little room for the task)."""

COMPILING = "compiling numba kernels (first run only)"
"""Shown as the stage while numba compiles: the first run after installing can spend a minute there."""

T = TypeVar("T")


def progress_mode(stream: TextIO | None = None) -> Mode:
    """The form progress takes on ``stream`` (default stderr): ``bar``, ``lines`` or ``off``.

    ``QCPP_PROGRESS`` decides when set to ``bar``, ``lines`` or ``off``; else a terminal gets ``bar`` and
    anything else ``lines``.

    Raises:
        ValueError: ``QCPP_PROGRESS`` holds something else.
    """
    chosen = os.environ.get(MODE_ENV, "auto").strip().lower() or "auto"
    if chosen not in MODES:
        raise ValueError(f"{MODE_ENV}={chosen!r}: expected one of {', '.join(MODES)}")
    if chosen != "auto":
        return chosen  # type: ignore[return-value]
    out = stream if stream is not None else sys.stderr
    try:
        return "bar" if out.isatty() else "lines"
    except (AttributeError, ValueError):  # a closed or odd stream
        return "lines"


def _interval_from_env() -> float:
    text = os.environ.get(INTERVAL_ENV, "").strip()
    if not text:
        return DEFAULT_INTERVAL
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{INTERVAL_ENV}={text!r}: expected a number of seconds") from None
    if not value >= 0 or value == float("inf"):
        raise ValueError(f"{INTERVAL_ENV}={text!r}: expected a finite number of seconds, at least 0")
    return value


class Progress:
    """Progress of one task on stderr (see the module docstring for the forms it takes).

    Args:
        task: What runs, a few words (``estimate``, ``compile 40x40, 8 robots``); starts every line.
        total: Steps in all, if known (a bar then shows the fraction and the time left).
        unit: What a step is, plural (``rows``, ``sections``, ``assignments``).
        stream: Where to write (default ``sys.stderr``).
        mode: ``auto``/``bar``/``lines``/``off``; default from ``QCPP_PROGRESS`` (see :func:`progress_mode`).
        interval: Seconds between lines (default ``QCPP_PROGRESS_INTERVAL`` or :data:`DEFAULT_INTERVAL`).
        first_after: Seconds before the first line (default :data:`FIRST_LINE_AFTER`; 0 with ``interval`` 0).
        time_left: Show the time left (extrapolated from the share of steps done); ``False`` where steps differ
            too much in cost for that to be an estimate (the counts and the elapsed time are still shown).
        deadline: Seconds after entering at which the work stops whatever is left (a solver's time limit): the
            time left shown is at most what remains until then.
        width: Characters a line may take (default :func:`qcpp.io.text.terminal_width`); a pipe or log
            gets lines this wide at most, so a long task or stage does not wrap in a terminal showing the log.
    """

    def __init__(
        self,
        task: str,
        total: int | None = None,
        unit: str = "steps",
        *,
        stream: TextIO | None = None,
        mode: Mode | None = None,
        interval: float | None = None,
        first_after: float | None = None,
        time_left: bool = True,
        deadline: float | None = None,
        width: int | None = None,
    ) -> None:
        self.task = task
        self.width = terminal_width() if width is None else width
        self.time_left = time_left
        self.deadline = deadline
        self.total = total
        self.unit = unit
        self.done = 0
        self.stage_text = ""
        self._stream = stream
        self._mode: Mode = progress_mode(stream) if mode in (None, "auto") else mode  # type: ignore[assignment]
        self._interval = _interval_from_env() if interval is None else interval
        self._first_after = (0.0 if self._interval == 0 else FIRST_LINE_AFTER) if first_after is None else first_after
        self._start = 0.0
        self._lines = 0
        self._last_line = -math.inf  # when the last line was written (seconds since the start)
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._bar: Any = None
        self._bar_task: Any = None
        self._compiles = 0  # numba compilations running now (nested: a kernel compiles the ones it calls)
        self._listener: Any = None  # our numba:compile listener, once numba is imported

    # ------------------------------------------------------------------ context

    def __enter__(self) -> Progress:
        self._start = time.monotonic()
        if self._mode == "bar":
            self._start_bar()
        elif self._mode == "lines":
            if self._interval == 0:
                self._line()
            else:
                self._thread = threading.Thread(target=self._heartbeat, name="qcpp-progress", daemon=True)
                self._thread.start()
        return self

    def __exit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        self._stop.set()
        if self._listener is not None:
            from numba.core import event

            with contextlib.suppress(Exception):
                event.unregister("numba:compile", self._listener)
            self._listener = None
        if self._thread is not None:
            self._thread.join(timeout=HEARTBEAT_JOIN_SECONDS)
        with self._lock:  # a heartbeat line being written now ends before the caller's last line (``interrupted``)
            pass
        if self._bar is not None:
            with contextlib.suppress(Exception):
                self._bar.stop()
        if exc_type is None and self._mode == "lines" and self._lines:
            size = f"{_counted(self.done, self.unit)} " if self.total is not None or self.done else ""
            self._write(_fit_line(self.task, "", [f"{size}done in {format_duration(self._elapsed())}"], self.width))

    # ------------------------------------------------------------------ reporting

    def update(self, done: int, total: int | None = None) -> None:
        """Set how many steps are done (and the total, if it changed): a :data:`~qcpp.problem.solvers.ProgressFn`."""
        self.done = done
        if total is not None:
            self.total = total
        self._after_change()

    def advance(self, steps: int = 1) -> None:
        """``steps`` more steps are done."""
        self.done += steps
        self._after_change()

    def stage(self, text: str) -> None:
        """Name the stage the work is in now (``compiling the circuit``); shown next to the counts."""
        changed = text != self.stage_text
        self.stage_text = text
        self._after_change()
        if changed:
            self._announce()

    def iterate(self, items: Iterable[T], then: str | None = None) -> Iterator[T]:
        """Yield ``items``, counting one step as each is handed out (done = items handed out before it).

        Args:
            items: The steps.
            then: Stage to show once every item is done (what the consumer does next, e.g. ``rendering the table``).
        """
        for item in items:
            yield item
            self.advance()
        if then is not None:
            self.stage(then)

    def status(self) -> str:
        """The current line (without a newline), at most :attr:`width` characters where the numbers leave room.

        The line is ``task: counts, stage, elapsed time[, time left]``; when it is too long the task and then the
        stage are shortened (see :func:`_fit_line`), never the counts or the times.
        """
        counts = []
        if self.total is not None:
            share = f" ({100.0 * self.done / self.total:.1f}%)" if self.total else ""
            counts.append(f"{self.done:,} / {self.total:,} {self.unit}{share}")
        elif self.done:
            counts.append(_counted(self.done, self.unit))
        elapsed = self._elapsed()
        times = f"{format_duration(elapsed)} elapsed"
        if self.time_left and self.total and 0 < self.done < self.total and elapsed >= 1.0:
            left = capped_left(elapsed * (self.total - self.done) / self.done, elapsed, self.deadline)
            times += f", about {format_duration(left)} left"
        return _fit_line(self.task, self._stage(), [*counts, times], self.width)

    # ------------------------------------------------------------------ internals

    def _elapsed(self) -> float:
        return time.monotonic() - self._start if self._start else 0.0

    def _stage(self) -> str:
        """The stage as shown: :attr:`stage_text`, or :data:`COMPILING` while numba compiles (in its place: an
        80-column line has no room for both)."""
        self._listen_to_numba()
        return COMPILING if self._compiles else self.stage_text

    def _listen_to_numba(self) -> None:
        """Register for numba's compile events once numba is imported (never imported here: most commands do
        without it, and importing it takes a good part of a second)."""
        if (self._listener is not None or self._mode == "off" or not self._start or self._stop.is_set()
                or "numba.core.event" not in sys.modules):  # fmt: skip
            return  # listening only between entering and leaving: __exit__ unregisters
        from numba.core import event

        progress = self

        class _Compiles(event.Listener):  # type: ignore[misc]
            def on_start(self, ev: Any) -> None:
                progress._compiling(+1)

            def on_end(self, ev: Any) -> None:
                progress._compiling(-1)

        self._listener = _Compiles()
        event.register("numba:compile", self._listener)

    def _compiling(self, delta: int) -> None:
        """A numba compilation started (+1) or ended (-1); the shown stage changes when the first starts and the
        last ends. Never raises: it runs inside numba's compiler."""
        with contextlib.suppress(Exception):
            before = self._compiles
            self._compiles = max(0, before + delta)  # one that started before we listened ends unseen
            if (before == 0) != (self._compiles == 0) and not self._stop.is_set():
                self._after_change()
                self._announce()

    def _announce(self) -> None:
        """Write the line now when the stage changed and no line came for an interval."""
        elapsed = self._elapsed()
        if (self._mode == "lines" and self._interval > 0 and elapsed >= self._first_after
                and elapsed - self._last_line >= self._interval):  # fmt: skip
            # say so now: the next stage may be one native call that holds the GIL (QCEC, a contraction), and
            # then the heartbeat thread cannot write until it returns; but not again within an interval, so stages
            # that change many times a second do not flood a log
            self._line()

    def _after_change(self) -> None:
        if self._mode == "bar" and self._bar is not None:
            with contextlib.suppress(Exception):
                self._bar.update(self._bar_task, completed=self.done, total=self.total, description=self._label())
        elif self._mode == "lines" and self._interval == 0:
            self._line()

    def _label(self) -> str:
        stage = self._stage()
        return f"{self.task}: {stage}" if stage else self.task

    def _line(self, unless_stopped: bool = False) -> None:
        self._write(self.status(), unless_stopped)

    def _write(self, text: str, unless_stopped: bool = False) -> None:
        out = self._stream if self._stream is not None else sys.stderr
        with self._lock:
            if unless_stopped and self._stop.is_set():  # the heartbeat woke after the work ended: no stale line
                return
            try:
                out.write(text + "\n")
                out.flush()
            except (OSError, ValueError):  # stderr gone: progress is not worth failing the work for
                self._mode = "off"
                return
            self._lines += 1
            self._last_line = self._elapsed()

    def _heartbeat(self) -> None:
        """A line every interval after the first-line delay, counted from the last line written: a stage announced
        meanwhile (:meth:`_announce`) restarts the wait, so its line is not followed at once by the same one."""
        if self._stop.wait(self._first_after):
            return
        while not self._stop.is_set():
            wait = self._interval - (self._elapsed() - self._last_line)
            if wait > 0:
                if self._stop.wait(wait):
                    return
                continue
            self._line(unless_stopped=True)

    def _start_bar(self) -> None:
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            SpinnerColumn,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )
        from rich.progress import (
            Progress as RichProgress,
        )
        from rich.table import Column

        console = Console(file=self._stream if self._stream is not None else sys.stderr)
        # the description takes the width the other columns leave (cut with an ellipsis), so the bar and the
        # elapsed time stay on screen at any terminal width
        self._bar = RichProgress(
            SpinnerColumn(),
            TextColumn("{task.description}", table_column=Column(ratio=1, no_wrap=True, overflow="ellipsis")),
            BarColumn(bar_width=BAR_WIDTH),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            *([_capped_remaining(TimeRemainingColumn, self.deadline)] if self.time_left else []),
            console=console,
            transient=True,
            expand=True,
        )
        self._bar_task = self._bar.add_task(self._label(), total=self.total)
        self._bar.start()


def capped_left(left: float, elapsed: float, deadline: float | None) -> float:
    """``left`` seconds of work, at most what remains until ``deadline`` (seconds after the start; ``None``: none).

    >>> capped_left(90.0, 50.0, 60.0), capped_left(5.0, 50.0, 60.0), capped_left(9.0, 70.0, 60.0)
    (10.0, 5.0, 0.0)
    """
    return left if deadline is None else min(left, max(0.0, deadline - elapsed))


def _capped_remaining(column: Any, deadline: float | None) -> Any:
    """Rich's ``TimeRemainingColumn`` (the class ``column``), its time left at most what remains until ``deadline``
    (:func:`capped_left`)."""
    if deadline is None:
        return column()

    class Capped(column):  # type: ignore[misc, valid-type]
        def render(self, task: Any) -> Any:
            left = task.time_remaining
            if task.elapsed is not None:
                left = max(0.0, deadline - task.elapsed) if left is None else capped_left(left, task.elapsed, deadline)
            return super().render(_WithTimeLeft(task, left))  # rich's own formatting of the capped figure

    return Capped()


class _WithTimeLeft:
    """A rich task seen with another ``time_remaining`` (every other attribute is the task's)."""

    def __init__(self, task: Any, time_remaining: float | None) -> None:
        self._task = task
        self.time_remaining = time_remaining

    def __getattr__(self, name: str) -> Any:
        return getattr(self._task, name)


def _counted(n: int, unit: str) -> str:
    """``n`` of ``unit`` (a plural): ``1 row``, ``3 rows``, ``1 improving solution``.

    Example:
        >>> _counted(1, "rows"), _counted(1_234, "rows"), _counted(1, "improving solutions"), _counted(0, "steps")
        ('1 row', '1,234 rows', '1 improving solution', '0 steps')
    """
    return f"{n:,} {unit[:-1] if n == 1 and unit.endswith('s') else unit}"


def _word_prefix(text: str, room: int, may_be_empty: bool = False) -> str:
    """The start of ``text`` in at most ``room`` characters, ending between two words where the cut would fall
    inside one and a space is within :data:`WORD_REACH` characters before it (else the word is cut); trailing
    spaces, commas and colons go.

    Args:
        text: The text.
        room: Characters the start may take.
        may_be_empty: The start of ``text`` counts as a word boundary too (where something else shows the text).

    Example:
        >>> _word_prefix("routing the whole circuit", 15), _word_prefix("examples/a_very_long_file_name.toml", 15)
        ('routing the', 'examples/a_very')
        >>> _word_prefix("simulating the subspace", 8), _word_prefix("simulating the subspace", 8, may_be_empty=True)
        ('simulati', '')
    """
    if len(text) <= room:
        return text
    kept = text[: max(room, 0)]
    space = kept.rfind(" ")
    if space < 0 and may_be_empty:
        space = 0
    if text[len(kept)] != " " and space >= 0 and len(kept) - space <= WORD_REACH:  # no half words
        kept = kept[:space]
    return kept.rstrip(" ,:")


def _cut_end(text: str, room: int) -> str:
    """``text`` in at most ``room`` characters: if it is longer, its end goes for ``…``, at a word boundary where
    one is near (:func:`_word_prefix`).

    Example:
        >>> _cut_end("compile 3x4, 1 robot(s), p=1", 16)
        'compile 3x4, 1…'
    """
    if len(text) <= room:
        return text
    return _word_prefix(text, room - 1) + "…"


def _cut_middle(text: str, room: int) -> str:
    """``text`` in at most ``room`` characters: if it is longer, whole words from its middle go for `` … ``.

    The end keeps up to half the room, so a stage's own counts (``... on heavy-hex:9 (3 / 6)``) survive next to
    its start (the row or the pass it belongs to). The end starts at a word; where the room for it falls inside
    the last word, the end goes instead (:func:`_cut_end`), so no piece of a word is left after the ``…``.

    Example:
        >>> _cut_middle("3x3 r1 p1 on heavy-hex:7: choosing partial-mixer plans on the cells (13 / 18)", 30)
        '3x3 r1 p1 on … (13 / 18)'
        >>> _cut_middle("routing the whole circuit", 12)
        'routing the…'
    """
    if len(text) <= room:
        return text
    counts = re.search(r"\([0-9,]+ / [0-9,]+\)$", text)  # ``(3 / 6)``: whole or not at all
    group = len(counts[0]) if counts else 0
    if room < max(7, group + 4):
        return _cut_end(text, room)
    start = len(text) - max((room - 3) // 2, group)
    if start > 0 and text[start - 1] != " ":  # the end would start inside a word: at the next one, if any
        space = text.find(" ", start, len(text) - 1)
        if space < 0:
            return _cut_end(text, room)
        start = space + 1
    tail = text[start:]
    head = _word_prefix(text, room - 3 - len(tail), may_be_empty=True)
    if head and text[len(head)] not in " ,:":
        return f"{head}… {tail}"  # a long word cut: the ``…`` right after it marks the cut
    return f"{head} … {tail}" if head else f"… {tail}"


def _fit_line(task: str, stage: str, numbers: list[str], width: int) -> str:
    """The progress line ``task: numbers[0], stage, numbers[1:]`` in at most ``width`` characters if it can be.

    The numbers (counts, share, elapsed time, time left) are never cut: they are what the line is for. The task is
    cut first, at its end and down to its first word (the command, which the reader typed); then the stage, in its
    middle, down to :data:`MIN_STAGE` characters; with less room the stage is left out. A line longer than
    ``width`` remains only where the first word and the numbers alone are longer.

    Args:
        task: The task (``compile 3x4, 1 robot(s), p=1``).
        stage: The stage, or ``""``.
        numbers: The counts (if any) and then the times, each kept whole.
        width: Characters the line may take.

    Returns:
        The line, without a newline.

    Example:
        >>> _fit_line("compile 3x4, 1 robot(s)", "routing the whole circuit", ["3 s elapsed"], 40)
        'compile…: routing … circuit, 3 s elapsed'
    """
    head, rest = (numbers[:1], numbers[1:]) if len(numbers) > 1 else ([], numbers)

    def line(t: str, s: str) -> str:
        return f"{t}: {', '.join([*head, *([s] if s else []), *rest])}"

    if len(line(task, stage)) <= width:
        return line(task, stage)
    floor = min(len(task), len(task.split(" ", 1)[0]) + 1)  # the first word and the ``…`` after it
    if stage:
        spare = width - len(line("", stage))  # what the task may take with the stage whole
        short = _cut_end(task, max(spare, floor)) if spare < len(task) else task
        stage_room = width - len(line(short, "")) - 2
        if stage_room >= min(len(stage), MIN_STAGE):
            return line(short, _cut_middle(stage, stage_room))
    spare = width - len(line("", ""))
    return line(_cut_end(task, max(spare, floor)), "")
