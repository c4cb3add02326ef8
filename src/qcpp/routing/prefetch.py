"""Windows routed ahead in a forked process while the caller goes on with other work.

A compile on the geometric layouts routes one large window, the balance arithmetic's (dozens of SABRE seeds of many
trials each), after a long stage in Python on one core: the heavy-hex cells' choice of partial-mixer plans, the
medial grid's ancilla allocation search (times: ``benchmarks/hex_compile_speed.py``). The window does not depend
on that choice or search (a window's routing depends only on its physical pairs and the device around
them), so :func:`prefetch_windows` routes it on another core meanwhile, and the final routing takes the answer
when it reaches the window (:func:`qcpp.routing.windows.route_window`). A thread would not do: Qiskit's routing
call holds the GIL, so it would stall the plan choice for as long as it runs.

The answer is the one the final routing would compute: the forked process is a copy of the caller, routes with a
:class:`~qcpp.routing.context.RoutingContext` of its own, with the same function, pairs, seed and settings, and
every answer is a pure function of its key. What the routing saw (its patches' qubits, whole-component parts, the
qubits patches were grown around) is replayed into the caller's open watches when the window is taken, as a memo
hit replays it. A window the final routing never asks for is not taken;
:meth:`~qcpp.routing.context.RoutingContext.stop_prefetch` ends the process. If the process fails or dies, the
window is routed where it is asked for, as without prefetching.

Prefetching needs ``fork`` (Linux), two usable cores and a process allowed children (:func:`can_prefetch`);
elsewhere :func:`prefetch_windows` does nothing. The process runs SABRE's trials one after another (a forked copy
must not use the thread pool it inherits, whose threads it does not have), ignores Ctrl-C (the caller stops it on
its way out), dies with the caller (:func:`qcpp.io.children.die_with_parent`) and leaves with ``os._exit``, so no
handler, buffer or temporary file of the caller's runs twice.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx
    >>> from qcpp.routing.context import RoutingContext
    >>> from qcpp.routing.windows import route_windows
    >>> device = get_device("grid:1x3")
    >>> c = Circuit([("data", 3)], [Section("g", [cx(0, 2), cx(0, 2)])])
    >>> context = RoutingContext()
    >>> prefetch_windows(context, [(((0, 2), (0, 2)), False)], device, None, 0)
    >>> route_windows(c, device, (0, 1, 2), context=context).swaps, context.prefetched
    (2, {})
    >>> context.stop_prefetch()
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import sys
import warnings
from collections.abc import Sequence
from typing import Any

from qcpp.hardware.device import Device
from qcpp.io.children import die_with_parent
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.windows import SeenRouting, prefetch_key, route_physical_window, window_memoised

__all__ = ["can_prefetch", "prefetch_windows", "usable_cores"]

Window = tuple[tuple[tuple[int, int], ...], bool]
"""A window to route ahead: its two-qubit gates on physical qubits, and whether its middle is a run of commuting
blocks (:func:`qcpp.routing.windows.commuting_middle`)."""


def usable_cores() -> int:
    """The CPU cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - a platform without affinity (macOS, Windows)
        return os.cpu_count() or 1


def can_prefetch() -> bool:
    """Whether :func:`prefetch_windows` routes ahead here: Linux (``fork``) with at least two usable cores, in a
    process that may have children (a daemonic worker, as of ``multiprocessing`` pools and Dask, may not)."""
    return sys.platform.startswith("linux") and usable_cores() >= 2 and not multiprocessing.current_process().daemon


def prefetch_windows(
    context: RoutingContext, windows: Sequence[Window], device: Device, dist: Any, seed: int,
    options: RoutingOptions = DEFAULT_ROUTING,
) -> None:  # fmt: skip
    """Start routing ``windows`` (in order, each once) in a forked process, as
    :func:`~qcpp.routing.windows.route_window` would route them with ``seed`` and ``options``; their answers
    wait in ``context.prefetched`` for the final routing (nothing happens where :func:`can_prefetch` is false).

    Args:
        context: The caller's run; it takes the answers (the process routes in a context of its own).
        windows: The windows (:data:`Window`), physical pairs as the final routing will see them.
        device: The device.
        dist: Its all-pairs distances (:func:`qcpp.hardware.device.distances`; ``None``: computed here).
        seed: SABRE's first seed.
        options: The settings the final routing routes these windows with.
    """
    if not can_prefetch():
        return
    if dist is None:
        from qcpp.hardware.device import distances

        dist = distances(device)
    todo: list[tuple[Window, Any]] = []
    for pairs, commuting in windows:
        physical = tuple(pairs)
        key = prefetch_key(device, physical, (seed, options.window_key, commuting and options.commuting_phases))
        if (physical and key not in context.prefetched and key not in (k for _, k in todo)
                and not window_memoised(context, physical, device, dist, seed, options, commuting)):  # fmt: skip
            todo.append(((physical, commuting), key))
    if not todo:
        return
    try:
        job = _Job([w for w, _ in todo], device, dist, seed, options, context)
    except OSError:  # no process to be had (memory, limits): the windows are routed where they are asked for
        return
    context.prefetch_jobs.append(job)
    for i, (_, key) in enumerate(todo):
        context.prefetched[key] = _Answer(job, i)


class _Job:
    """A forked process routing windows in order and sending each answer down a pipe as it has it."""

    def __init__(self, windows: list[Window], device: Device, dist: Any, seed: int, options: RoutingOptions,
                 context: RoutingContext) -> None:  # fmt: skip
        fork = multiprocessing.get_context("fork")
        self._reader, writer = fork.Pipe(duplex=False)
        args = (writer, os.getpid(), windows, device, dist, seed, options, context.reuse, context.window_limit)
        self._process = fork.Process(target=_route_ahead, args=args, name="qcpp-prefetch", daemon=True)
        with warnings.catch_warnings():
            # Python 3.12+ warns of fork in a process with threads (Qiskit's thread pool, once used): the copy
            # runs only this module's routing, on its one thread, off that pool, and leaves with os._exit
            warnings.filterwarnings("ignore", message=".*fork.*", category=DeprecationWarning)
            self._process.start()
        writer.close()
        self._answers: dict[int, Any] = {}
        self._done = False

    def answer(self, index: int) -> Any:
        """The answer for window ``index`` (waiting for it), or ``None`` if the process ended without it."""
        while index not in self._answers and not self._done:
            try:
                i, answer = self._reader.recv()
            except (EOFError, OSError):  # the process ended (finished, failed or was stopped)
                self._done = True
                break
            self._answers[i] = answer
        return self._answers.pop(index, None)

    def stop(self) -> None:
        """End the process (at once) and close the pipe."""
        if self._process.is_alive():
            self._process.kill()
        self._process.join()
        self._reader.close()
        self._done = True


class _Answer:
    """One window's place in a :class:`_Job`: ``result()`` waits for its answer."""

    def __init__(self, job: _Job, index: int) -> None:
        self._job, self._index = job, index

    def result(self) -> SeenRouting | None:
        """The window's routing and what it saw, or ``None`` (the process ended without it)."""
        return self._job.answer(self._index)  # type: ignore[no-any-return]


def _route_ahead(
    writer: Any, parent: int, windows: list[Window], device: Device, dist: Any, seed: int, options: RoutingOptions,
    reuse: bool, window_limit: int,
) -> None:  # fmt: skip
    """The forked process of :func:`prefetch_windows`: each window's :class:`~qcpp.routing.windows.SeenRouting`, sent
    as ``(index, answer)`` as soon as it has it."""
    die_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the caller stops this process when it is interrupted
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        context = RoutingContext(reuse=reuse, window_limit=window_limit, parallel_trials=False)
        for i, (pairs, commuting) in enumerate(windows):
            writer.send((i, route_physical_window(context, pairs, device, dist, seed, options, commuting)))
        writer.close()
    finally:  # also on an error: the caller, finding no answer, routes the window itself and raises there
        os._exit(0)
