"""The memos of one compile or estimate run, and the patch watches open in it: the routing's only mutable state.

A device compile routes the same windows many times (the ancilla allocation's candidates, the heavy-hex cells'
plan variants, the far-phase relays' with-and-without comparison, the final routing), so every answer that is a
pure function of its key is memoised: routed windows (on their physical pairs and the options, on a heavy-hex
lattice up to the lattice's translations), SABRE's routing of a patch, each device's patches and SABRE passes, the
allocation and placement searches' winners, the cells' plan choices, what the routed bound needs of each gadget
kind, and whole device compiles (so an estimate of what was just compiled routes nothing again).
:class:`RoutingContext` owns all of them; a compile creates one (or takes the caller's, so an estimate sweep
can share it) and passes it down, so no answer depends on what ran before in the process, and dropping the context
frees the memory.

Watches (:meth:`RoutingContext.watching`) collect the device qubits of every patch routed inside a block and how
many window parts were routed on their whole connected component (a window spanning far-apart qubits: that routing
depends on the whole device): a routing on a crop of the device answers for the device only if no patch reached a
side the crop cut (:mod:`qcpp.estimators.window_classes`, :func:`qcpp.pipeline.device_compile.medial_compile`).

Example:
    >>> context = RoutingContext()
    >>> with context.watching() as watch:
    ...     context.saw_patch((3, 4), whole=True)
    >>> watch.qubits, watch.whole_component
    ({3, 4}, 1)
    >>> context.saw_patch((5,), whole=False)  # no watch open: nothing collects it
    >>> watch.qubits
    {3, 4}
"""

from __future__ import annotations

import contextlib
import gc
from collections.abc import Hashable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

__all__ = ["PatchWatch", "RoutingContext", "collector_paused"]


@dataclass
class PatchWatch:
    """What the routings inside one :meth:`RoutingContext.watching` block did.

    Attributes:
        qubits: The device qubits of every patch routed (memoised windows included).
        whole_component: Window parts routed on their whole connected component.
    """

    qubits: set[int] = field(default_factory=set)
    whole_component: int = 0


class RoutingContext:
    """The memos and open watches of routing runs (module docs); not shared between threads.

    In the public API (``qcpp.RoutingContext``) one is passed as ``context=`` to ``qcpp.compile`` and
    ``qcpp.estimate`` calls with a device that route the same circuits: the estimate of a circuit just compiled, or
    a table that compiles it again, is answered from it. Every memo is a pure function of its key, so the results
    are the same with or without one; it only saves the searches' time, and holds their memory until it is dropped
    or cleared (:meth:`clear`).

    >>> import qcpp
    >>> context = qcpp.RoutingContext()
    >>> s = qcpp.grid_scenario(2, 2, robots=1)
    >>> routed = qcpp.compile(s, device="heavy-hex", context=context)
    >>> qcpp.estimate(s, device="heavy-hex", context=context).routed_twoq == routed.counts()["cz"]
    True

    Args:
        reuse: Whether a window may be answered by another window's routing: on a heavy-hex lattice, by the
            routing of its translation (:class:`qcpp.routing.patches.Lattice`), and a heavy-hex cell's relabelled
            parity program by the A* of an equal program (:func:`qcpp.pipeline.cellmixer.cell_mixers`). ``False``
            memoises windows on their physical pairs only and plans every program afresh: the same answers,
            slower (``tests/compiler/window_memo_test.py`` compares both).
        window_limit: Entries :attr:`windows` holds before a routed window's entry starts it over (a bound on
            memory: every entry is a pure function of its key, so starting over changes no answer).
        parallel_trials: Whether SABRE may run a routing's trials on several threads
            (:func:`qcpp.routing.patches.run_sabre`; the same answer either way).
        compiles_kept: Whole device compiles :attr:`compiles` keeps, the latest (a routed circuit may hold tens of
            thousands of gates; ``0``: none, for a sweep whose rows never repeat).

    Attributes:
        windows: Routed windows and SABRE's routings of patches (:mod:`qcpp.routing.windows`,
            :func:`qcpp.routing.patches.sabre_local`).
        patch_indexes: The last few devices' patch indexes (:func:`qcpp.routing.patches.patch_index`).
        sabre_passes: A ``SabreSwap`` pass per patch shape, with what routing on it needs
            (:func:`qcpp.routing.patches.patch_sabre`).
        within_two: The last distance matrix and, per qubit, the qubits within two steps
            (:func:`qcpp.routing.bridge.copy_chain`).
        allocations: The allocation search's ranks per section class (:func:`qcpp.layout.medial.allocate_ancillas`).
        free_sites: The last ``(device, distances, homes)``'s free sites (:func:`qcpp.layout.medial.allocate_ancillas`).
        placements: The placement search's routings, cheapest first, per circuit and device
            (:func:`qcpp.layout.placement_search.search_route`).
        cell_choices: The cells' plan choice per cell class (:func:`qcpp.pipeline.cellmixer.cell_mixers`).
        plans: The A*'s plan per parity program and target (:func:`qcpp.pipeline.cellmixer.cell_mixers`).
        relabelled: The relabelled plans per parity program and target (:func:`qcpp.pipeline.cellmixer.cell_mixers`).
        window_classes: The routed cost of a window class per signature and device
            (:func:`qcpp.estimators.window_classes.routed_sum`).
        kind_routes: What the routed bound needs of each gadget kind, per kind key
            (:func:`qcpp.estimators.layout_bound.kind_route`).
        compiles: Whole device compiles per scenario, depth, device and every setting
            (:func:`qcpp.pipeline.device_compile.compile_for_device`).
        watches: The open watches (:meth:`watching`).
        centres: Open sets collecting the qubits every patch routed was grown around
            (:func:`qcpp.routing.windows.route_window` keys a translated window on the lattice around them).
        prefetched: Windows being routed ahead in another process, per window key, each a handle whose
            ``result()`` waits for what the routing gave and saw, or ``None`` if it gave nothing
            (:func:`qcpp.routing.prefetch.prefetch_windows`); a window takes its entry on its first miss.
        prefetch_jobs: The processes routing ahead (each with a ``stop()``; :meth:`stop_prefetch`).
        taken_ahead: Windows answered by a process routing ahead so far.
    """

    def __init__(
        self, *, reuse: bool = True, window_limit: int = 1 << 18, parallel_trials: bool = True, compiles_kept: int = 4
    ) -> None:
        self.reuse = reuse
        self.window_limit = window_limit
        self.parallel_trials = parallel_trials
        self.compiles_kept = compiles_kept
        self.windows: dict[Hashable, Any] = {}
        self.patch_indexes: list[Any] = []
        self.sabre_passes: dict[Hashable, Any] = {}
        self.within_two: list[tuple[Any, dict[int, list[tuple[int, int]]]]] = []
        self.allocations: dict[Hashable, tuple[int, ...]] = {}
        self.free_sites: list[tuple[Any, ...]] = []
        self.placements: dict[Hashable, list[tuple[int, tuple[int, ...], int]]] = {}
        self.cell_choices: dict[Hashable, Any] = {}
        self.plans: dict[Hashable, Any] = {}
        self.relabelled: dict[Hashable, Any] = {}
        self.window_classes: dict[Hashable, Any] = {}
        self.kind_routes: dict[Hashable, Any] = {}
        self.compiles: dict[Hashable, Any] = {}
        self.watches: list[PatchWatch] = []
        self.centres: list[set[int]] = []
        self.prefetched: dict[Hashable, Any] = {}
        self.prefetch_jobs: list[Any] = []
        self.taken_ahead = 0

    def clear(self) -> None:
        """Forget every memo (open watches stay open)."""
        for memo in (self.windows, self.sabre_passes, self.allocations, self.placements, self.cell_choices,
                     self.plans, self.relabelled, self.window_classes, self.kind_routes, self.compiles):  # fmt: skip
            memo.clear()
        for kept in (self.patch_indexes, self.within_two, self.free_sites):
            kept.clear()
        self.stop_prefetch()

    @contextlib.contextmanager
    def watching(self) -> Iterator[PatchWatch]:
        """Collect the patches routed inside the block; blocks nest (each collects everything inside it).

        Returns:
            A context manager giving the :class:`PatchWatch` it fills.
        """
        watch = PatchWatch()
        self.watches.append(watch)
        try:
            yield watch
        finally:  # by identity: equal watches may be open at once
            del self.watches[next(i for i, w in enumerate(self.watches) if w is watch)]

    def keep_compile(self, key: Hashable, result: Any) -> None:
        """Memoise a whole device compile under ``key`` in :attr:`compiles`, forgetting the oldest beyond
        :attr:`compiles_kept`."""
        if self.compiles_kept < 1:
            return
        self.compiles.pop(key, None)
        self.compiles[key] = result
        while len(self.compiles) > self.compiles_kept:
            del self.compiles[next(iter(self.compiles))]

    def stop_prefetch(self) -> None:
        """Stop the processes routing windows ahead and forget the windows not taken."""
        self.prefetched.clear()
        while self.prefetch_jobs:
            self.prefetch_jobs.pop().stop()

    def saw_patch(self, qubits: Iterable[int], whole: int) -> None:
        """Tell every open watch that a routing used the device ``qubits`` with ``whole`` parts routed on their whole
        connected component."""
        for watch in self.watches:
            watch.qubits.update(qubits)
            watch.whole_component += int(whole)


@contextlib.contextmanager
def collector_paused() -> Iterator[None]:
    """Pause Python's cyclic garbage collector inside the block (reference counting still frees every object no
    cycle holds), and restore it as it was.

    A device compile's searches allocate millions of short-lived tuples and keep hundreds of thousands in the
    context's memos; the collector's passes traverse them again and again and find next to nothing. Whatever
    cycles the block leaves are collected by the first pass after it.

    >>> import gc
    >>> with collector_paused():
    ...     gc.isenabled()
    False
    >>> gc.isenabled()
    True

    Returns:
        A context manager.
    """
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()
