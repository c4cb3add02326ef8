"""Size guards: refuse absurd requests before building anything, naming the size and the override.

Without a guard a huge grid grows to many GB before anything useful happens. Every place that builds a
scenario (file, dict, preset) calls :func:`check_grid_size` first; commands with a layer count call
:func:`check_layers`. Both raise :class:`SizeError` (a :class:`~qcpp.problem.errors.ScenarioError`, so the CLI
prints it as one line with exit code 2) unless large requests are allowed: the CLI's ``--allow-large`` flag
(available on every command) runs the command inside :func:`allow_large`.

The grid and layer limits are far above anything the repository's methods finish on (the exhaustive solver and the
simulators stop being practical long before), so they only catch typos and runaway scripts.

The work-size guards (``qcpp simulate``, ``validate``, ``solve``, ``compile``) are predictions, not fixed counts:
each command predicts the peak memory of its process (a :class:`Need`, from a model of measured peaks) and,
where it can, its run time, and :func:`check_need` refuses only what would not fit in the memory the machine
has available (:func:`available_memory`: ``MemAvailable``, less under an address-space limit; the environment
variable :data:`MEMORY_ENV` overrides it, e.g. for tests) or would run for more than :data:`MAX_SECONDS`. The
refusal is one line naming the prediction, the limit and the override.

Example:
    >>> check_grid_size(6, 6)
    >>> try:
    ...     check_grid_size(10000, 10000)
    ... except SizeError as exc:
    ...     print(exc.reason)
    a 10000x10000 grid has 100,000,000 nodes, over the limit of 2,500 (50x50); call it in a qcpp.allow_large() block \
to build it anyway
    >>> with allow_large():
    ...     check_grid_size(10000, 10000)
    >>> need = Need("simulating 5 amplitudes", bytes=3 * 10**9, seconds=7200.0)
    >>> try:
    ...     check_need(need, available=24 * 10**9)
    ... except SizeError as exc:
    ...     print(exc.reason.split("; ")[0])
    simulating 5 amplitudes: predicted to run for about 2.0 h (peak 3.0 GB of memory), over the limit of 1 h
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Iterator
from contextvars import ContextVar
from dataclasses import dataclass

from qcpp.io.text import format_duration
from qcpp.problem.errors import ScenarioError

__all__ = [
    "API_OVERRIDE",
    "MAX_GRID_NODES",
    "MAX_LAYERS",
    "MAX_SECONDS",
    "MEMORY_ENV",
    "OVERRIDE_FLAG",
    "Need",
    "SizeError",
    "allow_large",
    "available_memory",
    "check_grid_size",
    "check_layers",
    "check_need",
    "default_lift",
    "format_duration",
    "large_allowed",
    "lift_wording",
    "memory_budget",
    "parse_bytes",
]

MAX_GRID_NODES = 2500
"""Largest grid (nodes) built without ``--allow-large``: 50x50."""

MAX_LAYERS = 1000
"""Largest QAOA layer count accepted without ``--allow-large``."""

OVERRIDE_FLAG = "--allow-large"
"""The CLI flag that lifts every limit of this module."""

API_OVERRIDE = "call it in a qcpp.allow_large() block"
"""How a caller of the Python API lifts the limits (:func:`allow_large`), for the messages the API's guards give."""

MAX_SECONDS = 3600.0
"""Work predicted to run longer than this (an hour) is refused: it would run for hours, not minutes."""

MEMORY_ENV = "QCPP_MEMORY_AVAILABLE"
"""Environment variable that sets the available memory the guards compare with (bytes, or ``512M``, ``24G``)."""

_ALLOWED: ContextVar[bool] = ContextVar("qcpp_allow_large", default=False)
_LIFT: ContextVar[str] = ContextVar("qcpp_size_lift", default=API_OVERRIDE)


class SizeError(ScenarioError):
    """A request is larger than a limit of this module (the message names the size and the override)."""


def parse_bytes(text: str) -> int:
    """``"3000000"``, ``"512M"``, ``"24G"``, ``"1.5T"`` (powers of 1000; a trailing ``B`` is allowed) -> bytes.

    Raises:
        ValueError: naming the text, if it is not such a size.

    Example:
        >>> parse_bytes("24G"), parse_bytes("512mb"), parse_bytes("1000")
        (24000000000, 512000000, 1000)
    """
    m = re.fullmatch(r"\s*(\d+(?:\.\d*)?)\s*([kmgt]?)b?\s*", text, re.IGNORECASE)
    if m is None:
        raise ValueError(f"{MEMORY_ENV}: expected a size such as 512M or 24G, got {text!r}")
    scale = {"": 1, "k": 10**3, "m": 10**6, "g": 10**9, "t": 10**12}[m.group(2).lower()]
    return int(float(m.group(1)) * scale)


def _mem_available() -> int | None:
    """``MemAvailable`` of ``/proc/meminfo`` (Linux), else psutil's figure, else ``None``."""
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        import psutil

        return int(psutil.virtual_memory().available)
    except Exception:  # psutil missing or unsupported here
        return None


def _address_space_left() -> int | None:
    """How far this process's resident memory can still grow under its address-space limit (``RLIMIT_AS``):
    the limit less the address space in use now, plus the resident memory now (so it compares with a predicted
    peak of resident memory). ``None`` without a limit or where it cannot be read."""
    try:
        import resource

        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
        if soft == resource.RLIM_INFINITY:
            return None
        with open("/proc/self/statm", encoding="ascii") as f:
            size, resident = (int(x) for x in f.read().split()[:2])
    except (ImportError, OSError, ValueError, AttributeError):
        return None
    page = os.sysconf("SC_PAGE_SIZE")
    return max(0, soft - size * page) + resident * page


def available_memory() -> int | None:
    """The memory a command's process may grow to, in bytes: :data:`MEMORY_ENV` when set, else the machine's
    available memory (``MemAvailable``), lowered to what an address-space limit (``ulimit -v``) leaves; ``None``
    where neither is known.

    Raises:
        ValueError: :data:`MEMORY_ENV` holds something that is not a size.

    Example:
        >>> memory = available_memory()
        >>> memory is None or memory > 0
        True
    """
    text = os.environ.get(MEMORY_ENV, "").strip()
    if text:
        return parse_bytes(text)
    figures = [m for m in (_mem_available(), _address_space_left()) if m is not None]
    return min(figures) if figures else None


def memory_budget(share: float = 0.5) -> int | None:
    """``share`` of :func:`available_memory`, in bytes; ``None`` where that is unknown.

    Example:
        >>> budget = memory_budget()
        >>> budget is None or budget > 0
        True
    """
    memory = available_memory()
    return None if memory is None else int(memory * share)


@dataclass(frozen=True)
class Need:
    """What a piece of work is predicted to take, for :func:`check_need`.

    Attributes:
        what: The work, in a few words with its size (``simulating 73,788,100 amplitudes``).
        bytes: Predicted peak resident memory of the whole process, in bytes.
        seconds: Predicted wall time (``None``: no time model).
        at_least: Whether the figures are lower bounds (counting stopped early).
    """

    what: str
    bytes: int
    seconds: float | None = None
    at_least: bool = False

    def describe(self) -> str:
        """``"peak 3.1 GB of memory, about 17 s"`` (``at least`` where the figures are lower bounds)."""
        lead = "at least " if self.at_least else ""
        text = f"peak {lead}{self.bytes / 1e9:.1f} GB of memory"
        if self.seconds is not None:
            text += f", {lead or 'about '}{format_duration(self.seconds)}"
        return text


def check_need(need: Need, *, available: int | None = None, field: str = "", override: str = "") -> None:
    """Refuse (:class:`SizeError`, one line naming the prediction, the limit and :data:`OVERRIDE_FLAG`) work
    predicted to need more memory than is available or to run longer than :data:`MAX_SECONDS`; nothing when
    :func:`large_allowed`.

    Args:
        need: The prediction.
        available: The memory to compare with (default :func:`available_memory`; unknown: memory not checked).
        field: What the error is about (a file or a flag), printed first.
        override: How to lift the limit, for the message (default: :func:`default_lift`).

    Raises:
        SizeError: the work would not fit, or would run for hours.

    Example:
        >>> check_need(Need("a small job", bytes=10**8, seconds=3.0), available=10**9)
    """
    if large_allowed():
        return
    memory = available_memory() if available is None else available
    lead = "at least " if need.at_least else ""
    lift = override or default_lift()
    if memory is not None and need.bytes > memory:
        raise SizeError(
            field,
            f"{need.what}: predicted peak {lead}{need.bytes / 1e9:.1f} GB of memory, over the {memory / 1e9:.1f} GB "
            f"available; {lift} to try anyway",
        )
    if need.seconds is not None and need.seconds > MAX_SECONDS:
        raise SizeError(
            field,
            f"{need.what}: predicted to run for {lead or 'about '}{format_duration(need.seconds)} (peak "
            f"{need.bytes / 1e9:.1f} GB of memory), over the limit of {MAX_SECONDS / 3600:g} h; "
            f"{lift} to run it anyway",
        )


def large_allowed() -> bool:
    """Whether the limits are lifted in the current context."""
    return _ALLOWED.get()


def default_lift() -> str:
    """How a refusal without an explicit ``override`` says to lift the limit: for the caller in charge, the Python
    API's :data:`API_OVERRIDE` unless a :func:`lift_wording` block (the command line's ``pass --allow-large``) is
    in effect, so one check words its message for whoever called it."""
    return _LIFT.get()


@contextlib.contextmanager
def lift_wording(text: str) -> Iterator[None]:
    """Inside the ``with`` block, refusals without an explicit ``override`` say ``text`` (the command line runs
    every command in ``lift_wording("pass --allow-large")``).

    Example:
        >>> with lift_wording(f"pass {OVERRIDE_FLAG}"):
        ...     default_lift()
        'pass --allow-large'
        >>> default_lift()
        'call it in a qcpp.allow_large() block'
    """
    token = _LIFT.set(text)
    try:
        yield
    finally:
        _LIFT.reset(token)


@contextlib.contextmanager
def allow_large(enabled: bool = True) -> Iterator[None]:
    """Lift (``enabled=True``) or keep (``enabled=False``) qcpp's size limits inside the ``with`` block: the API's
    counterpart of the command line's ``--allow-large``.

    The limits, each raising :class:`SizeError` before any work where lifted they would not:

    * grids of more than :data:`MAX_GRID_NODES` nodes (50x50) and more than :data:`MAX_LAYERS` QAOA layers;
    * work predicted to need more memory than the machine has available (``QCPP_MEMORY_AVAILABLE`` overrides
      the reading), or to run for more than :data:`MAX_SECONDS` (an hour): state simulations and training,
      exhaustive search (``solve(method="dfs")``), validation's reference states.

    The setting is a context variable: it holds in the ``with`` block (and threads or tasks started inside it),
    and the limits are back when the block ends.

    Example:
        >>> import qcpp
        >>> s = qcpp.grid_scenario(3, 3, robots=1)
        >>> qcpp.estimate(s, p=1001)
        Traceback (most recent call last):
        ...
        qcpp.problem.limits.SizeError: p: 1,001 layers is over the limit of 1,000; call it in a qcpp.allow_large() \
block to run it anyway
        >>> with qcpp.allow_large():
        ...     qcpp.estimate(s, p=1001, depth="none").p
        1001
    """
    token = _ALLOWED.set(enabled)
    try:
        yield
    finally:
        _ALLOWED.reset(token)


def check_grid_size(rows: int, cols: int, field: str = "grid", override: str = "") -> None:
    """Refuse a grid of more than :data:`MAX_GRID_NODES` nodes (unless :func:`large_allowed`).

    Args:
        rows, cols: the grid size.
        field: the field named in the error.
        override: How to lift the limit, for the message (default: :func:`default_lift`, the caller's wording).

    Raises:
        SizeError: the grid is too large.
    """
    nodes = rows * cols
    if nodes > MAX_GRID_NODES and not large_allowed():
        lift = override or default_lift()
        raise SizeError(
            field,
            f"a {rows}x{cols} grid has {nodes:,} nodes, over the limit of {MAX_GRID_NODES:,} (50x50); "
            f"{lift} to build it anyway",
        )


def check_layers(p: int, flag: str = "-p", override: str = "") -> None:
    """Refuse more than :data:`MAX_LAYERS` QAOA layers (unless :func:`large_allowed`).

    Args:
        p: The layer count.
        flag: The option named in the error (``-p``, or ``p`` for the Python API).
        override: How to lift the limit, for the message (default: :func:`default_lift`, the caller's wording).

    Raises:
        SizeError: too many layers.

    Example:
        >>> check_layers(3)
        >>> check_layers(5000, "p", API_OVERRIDE)
        Traceback (most recent call last):
        ...
        qcpp.problem.limits.SizeError: p: 5,000 layers is over the limit of 1,000; call it in a qcpp.allow_large() \
block to run it anyway
    """
    if p > MAX_LAYERS and not large_allowed():
        lift = override or default_lift()
        raise SizeError(flag, f"{p:,} layers is over the limit of {MAX_LAYERS:,}; {lift} to run it anyway")
