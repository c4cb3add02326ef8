"""Windows routed ahead in a forked process give the answers routed here (:mod:`qcpp.routing.prefetch`).

Evidence: random windows of a heavy-hex lattice (with and without a commuting middle) routed ahead give the ops,
patches seen, whole-component parts and memo entries (translated ones included, which record the qubits the
patches were grown around) of the same windows routed in this process, and the answer came from the other process
(this process routed no patch); a compile whose balance window is routed ahead is the compile without (3x4/2 on
heavy-hex, 4x4/2 on the medial grid), took that window from the other process and leaves no process behind, also
when interrupted; a process that ends early leaves its window to be routed here; a daemonic worker does not fork.
"""

from __future__ import annotations

import multiprocessing
from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.hardware.device import distances, get_device
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.problem.presets import default_scenario
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING
from qcpp.routing.prefetch import can_prefetch, prefetch_windows
from qcpp.routing.windows import Positions, route_window

pytestmark = pytest.mark.skipif(not can_prefetch(), reason="routing ahead needs fork and two cores")

DEVICE = get_device("heavy-hex:9")
DIST = distances(DEVICE)


def _routed(pairs: list[tuple[int, int]], context: RoutingContext, commuting: bool) -> tuple[list, set[int], int]:
    with context.watching() as watch:
        ops = route_window(pairs, Positions.identity(DEVICE.num_qubits), DEVICE, DIST, 0, DEFAULT_ROUTING, context,
                           commuting)  # fmt: skip
    return ops, watch.qubits, watch.whole_component


def _window_entries(context: RoutingContext) -> dict:
    """The routed-window memo, keys without the context's device token."""
    return {key[2:]: value for key, value in context.windows.items() if key[0] == "window"}


@st.composite
def windows(draw: st.DrawFn) -> tuple[list[tuple[int, int]], bool]:
    """A compute and its mirror on qubits near one another, with or without a commuting middle."""
    centre = draw(st.integers(0, DEVICE.num_qubits - 1))
    near = [q for q in range(DEVICE.num_qubits) if DIST[centre, q] <= draw(st.integers(1, 6))]
    qubits = draw(st.permutations(near))[: min(len(near), draw(st.integers(2, 10)))]
    pairs = [tuple(draw(st.permutations(qubits))[:2]) for _ in range(draw(st.integers(1, 30)))]
    commuting = draw(st.booleans())
    blocks = [tuple(draw(st.permutations(qubits))[:2]) for _ in range(draw(st.integers(1, 8)) if commuting else 0)]
    return pairs + [pr for pr in blocks for _ in range(2)] + pairs[::-1], commuting  # type: ignore[return-value]


@settings(max_examples=15, deadline=None)
@given(windows())
def test_a_window_routed_ahead_is_the_window_routed_here(window: tuple[list[tuple[int, int]], bool]) -> None:
    pairs, commuting = window
    here = RoutingContext()
    expected = _routed(pairs, here, commuting)
    ahead = RoutingContext()
    prefetch_windows(ahead, [(tuple(pairs), commuting)], DEVICE, DIST, 0, DEFAULT_ROUTING)
    try:
        assert _routed(pairs, ahead, commuting) == expected
    finally:
        ahead.stop_prefetch()
    assert ahead.taken_ahead == 1 and not ahead.prefetched
    assert all(key[0] == "window" for key in ahead.windows)  # no patch was routed in this process
    assert _window_entries(ahead) == _window_entries(here)


def test_a_memoised_window_is_not_routed_ahead() -> None:
    pairs = [(0, 5), (5, 9), (0, 5)]
    context = RoutingContext()
    _routed(pairs, context, False)  # type: ignore[arg-type]
    prefetch_windows(context, [(tuple(pairs), False)], DEVICE, DIST, 0, DEFAULT_ROUTING)  # type: ignore[arg-type]
    assert not context.prefetched and not context.prefetch_jobs


def _compiled(shape: tuple[int, int, int], device: str, route_ahead: bool) -> tuple[tuple, int]:
    context = RoutingContext()
    routing = replace(DEFAULT_ROUTING, route_ahead=route_ahead)
    result = compile_for_device(default_scenario(*shape), 1, device, routing=routing, context=context)
    assert result.layout_method == "medial"
    routed = result.routed
    return (tuple(routed.circuit.gates), routed.initial_layout, routed.final_layout), context.taken_ahead


@pytest.mark.parametrize(("shape", "device"), [((3, 4, 2), "heavy-hex"), ((4, 4, 2), "grid")])
def test_a_compile_routing_its_balance_window_ahead_is_the_compile_without(
    shape: tuple[int, int, int], device: str
) -> None:
    with_ahead, taken = _compiled(shape, device, True)
    assert taken == 1
    assert not multiprocessing.active_children()  # the process was stopped and reaped
    without, none_taken = _compiled(shape, device, False)
    assert none_taken == 0
    assert with_ahead == without


def test_a_process_that_ends_early_leaves_its_window_to_be_routed_here() -> None:
    """Whether or not the answer arrived before the process was killed, the window is the one routed here."""
    pairs = [(q, (q * 7 + 3) % DEVICE.num_qubits) for q in range(60) if q != (q * 7 + 3) % DEVICE.num_qubits]
    pairs += pairs[::-1]
    expected = _routed(pairs, RoutingContext(), False)
    context = RoutingContext()
    prefetch_windows(context, [(tuple(pairs), False)], DEVICE, DIST, 0, DEFAULT_ROUTING)
    job = context.prefetch_jobs[0]
    job._process.kill()
    try:
        assert _routed(pairs, context, False) == expected
    finally:
        context.stop_prefetch()


def _daemon_can_prefetch(out: multiprocessing.queues.Queue) -> None:  # type: ignore[name-defined]
    out.put(can_prefetch())


def test_a_daemonic_worker_does_not_fork() -> None:
    fork = multiprocessing.get_context("fork")
    out = fork.Queue()
    worker = fork.Process(target=_daemon_can_prefetch, args=(out,), daemon=True)
    worker.start()
    assert out.get(timeout=60) is False
    worker.join()


def test_an_interrupted_compile_stops_the_process_routing_ahead() -> None:
    """Ctrl-C (a KeyboardInterrupt) during the cells' plan choice, with the balance window being routed ahead:
    the compile stops, and so does the process, which is reaped (no process is left behind)."""
    context = RoutingContext()
    jobs: list[int] = []

    def stage(text: str) -> None:
        if text.startswith("choosing partial-mixer plans on the cells (1 /"):
            jobs.append(len(context.prefetch_jobs))
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        compile_for_device(default_scenario(3, 4, 2), 1, "heavy-hex", stage=stage, context=context)
    assert jobs == [1]  # the window was being routed ahead when the interruption came
    assert not context.prefetch_jobs and not context.prefetched
    assert not multiprocessing.active_children()
