"""The routed sum over window classes equals what ``compile --device grid`` writes (medial layout).

Each case computes :func:`qcpp.estimators.window_classes.routed_sum` (in its own routing context, so none of its
memoised routings or allocation searches reaches the compile), then compiles the circuit routed on the same device and
compares the two-qubit count, the one-qubit count, the native gate counts by name and the ESP; the sum's depth and
duration must bound the circuit's.
"""

from __future__ import annotations

import doctest
import importlib
import math

import pytest
from hypothesis import HealthCheck, given, settings

from qcpp.estimators import window_classes
from qcpp.estimators.counts import count_gates
from qcpp.estimators.crosscheck import interior_endpoints
from qcpp.estimators.window_classes import routed_sum
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario
from qcpp.routing.context import RoutingContext
from qcpp.routing.native import duration_s, esp

from .conftest import scenarios


def test_doctests() -> None:
    result = doctest.testmod(importlib.import_module("qcpp.estimators.window_classes"))
    assert result.attempted and not result.failed


DEFAULT = PlanOptions()


def _assert_sum_equals_compile(s: Scenario, p: int, options: PlanOptions = DEFAULT, device: str = "grid") -> None:
    summed = routed_sum(s, p, options, device)
    assert summed is not None
    # a fresh context: compile routes every window and searches every allocation afresh (determinism, not a memo)
    r = compile_for_device(s, p, device, options, bindings=None, layout_method="medial", context=RoutingContext())
    routed = r.routed
    assert routed.device.name == summed.device.name
    ops = routed.circuit.count_ops()
    two = routed.device.two_qubit_gate
    assert summed.native_ops == {k: v for k, v in ops.items() if v}
    assert summed.two_qubit == ops.get(two, 0)
    assert summed.one_qubit == sum(v for k, v in ops.items() if k != two)
    assert summed.swaps == routed.swaps
    assert summed.log_esp is not None
    assert math.isclose(summed.log_esp, math.log(esp(routed)), rel_tol=1e-9, abs_tol=1e-9)
    gc = count_gates(routed.circuit.gates, routed.circuit.num_qubits)
    assert gc.depth <= summed.depth_bound
    assert gc.two_qubit_depth <= summed.two_qubit_depth_bound
    actual = duration_s(routed)
    if actual is not None:
        assert summed.duration_bound_s is not None and actual <= summed.duration_bound_s * (1 + 1e-12)
    lowered = r.logical.count_ops()
    assert {k: v * 1 for k, v in summed.lowered_ops.items()} == {k: v for k, v in lowered.items() if v}
    compiled = r.compiled.circuit.count_ops()  # before allocation and relays
    assert summed.compiled_ops == {k: v for k, v in compiled.items() if v}


CASES = {
    "3x3/1 p1": (lambda: default_scenario(3, 3, 1), 1, PlanOptions()),
    "3x3/1 p2 ft": (lambda: default_scenario(3, 3, 1), 2, PlanOptions(target="ft")),
    "3x3/2 p1": (lambda: default_scenario(3, 3, 2), 1, PlanOptions()),
    "4x4/2 p2": (lambda: default_scenario(4, 4, 2), 2, PlanOptions()),
    "3x4 interior p1": (lambda: interior_endpoints(3, 4), 1, PlanOptions()),
    "4x4 hard interior p1": (lambda: interior_endpoints(4, 4, "hard"), 1, PlanOptions()),
    "4x4 soft interior p2 depth": (lambda: interior_endpoints(4, 4, "soft"), 2, PlanOptions(optimize="depth")),
    "3x3/3 p1": (lambda: default_scenario(3, 3, 3), 1, PlanOptions()),
    "3x3/1 paper rule": (lambda: default_scenario(3, 3, 1), 1, PlanOptions(rule="paper")),
    "3x3/1 representatives": (lambda: default_scenario(3, 3, 1), 1, PlanOptions(initial="representatives")),
    "4x4/2 budget 0": (lambda: default_scenario(4, 4, 2), 1, PlanOptions(ancilla_budget=0)),
    "3x4/2 pooled": (lambda: default_scenario(3, 4, 2), 1, PlanOptions(phase_layout="pooled")),
    "3x3/1 p0": (lambda: default_scenario(3, 3, 1), 0, PlanOptions()),
    # without the first phase separator: layer 1's phase separator stands for p - 1 (none at p = 1)
    "3x3/2 p1 no first phase": (lambda: default_scenario(3, 3, 2), 1, PlanOptions(first_phase=False)),
    "3x3/2 p3 no first phase": (lambda: default_scenario(3, 3, 2), 3, PlanOptions(first_phase=False)),
}


@pytest.mark.parametrize("case", list(CASES))
def test_routed_sum_equals_compile(case: str) -> None:
    build, p, options = CASES[case]
    _assert_sum_equals_compile(build(), p, options)


@settings(max_examples=3, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(s=scenarios(max_side=4, max_robots=3))
def test_routed_sum_equals_compile_on_random_scenarios(s: Scenario) -> None:
    _assert_sum_equals_compile(s, 1)


@pytest.mark.heavy
@settings(max_examples=24, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(s=scenarios(max_side=4, max_robots=3))
def test_routed_sum_equals_compile_on_more_random_scenarios(s: Scenario) -> None:
    """The default run's property on eight times as many scenarios."""
    _assert_sum_equals_compile(s, 1)


@pytest.mark.parametrize(
    "shape", [(3, 10, 1), pytest.param((10, 10, 1), marks=pytest.mark.heavy)], ids=["3x10/1", "10x10/1"]
)
def test_windows_sharing_a_class_route_as_compile_routes_each(shape: tuple[int, int, int]) -> None:
    s = default_scenario(*shape)
    summed = routed_sum(s, 1, context=RoutingContext())  # each class routed here, from this scenario's representative
    assert summed is not None and len(summed.classes) < summed.windows  # translated windows share a class
    _assert_sum_equals_compile(s, 1)


def test_a_larger_device_than_needed_gives_the_same_sum_as_compile() -> None:
    _assert_sum_equals_compile(default_scenario(3, 3, 1), 1, device="grid:9x11")


def test_windows_of_one_class_share_one_routing() -> None:
    s = routed_sum(default_scenario(16, 16, 1), 1)
    assert s is not None
    assert len(s.classes) < s.windows / 2  # interior partial mixers and visit gadgets repeat
    assert sum(c.multiplicity for c in s.classes) == s.windows


def test_not_a_square_grid_gives_none() -> None:
    assert routed_sum(default_scenario(3, 3, 1), 1, device="heavy-hex") is None
    assert routed_sum(default_scenario(3, 3, 1), 1, device="grid:4x4") is None  # too small for the layout


@pytest.mark.heavy
@pytest.mark.parametrize(
    ("rows", "cols", "robots", "p"),
    [(6, 6, 3, 1), (5, 5, 2, 2), (8, 8, 2, 1), (14, 14, 1, 2), (30, 30, 1, 1)],
)
def test_routed_sum_equals_compile_where_compile_takes_seconds(rows: int, cols: int, robots: int, p: int) -> None:
    """Three robots, two robots over one and two layers, and one robot on grids up to 30x30 (900 qubits).

    A larger grid with the same robots and layers adds more translated windows of the classes the smaller one has
    (every device here is below :data:`~qcpp.estimators.window_classes.WHOLE_DEVICE_MAX_QUBITS`), so two robots
    run on 8x8 and the large sizes with one robot, whose compile is the cheapest."""
    _assert_sum_equals_compile(default_scenario(rows, cols, robots), p)


def test_windows_over_the_whole_device_budget_give_none(monkeypatch: pytest.MonkeyPatch) -> None:
    s = default_scenario(3, 3, 2)  # its balance, coupling and visit windows need the whole device
    assert routed_sum(s, 1, whole_device_work=0) is None  # a fresh context: those windows cost work
    context = RoutingContext()
    exact = routed_sum(s, 1, context=context)
    assert exact is not None
    assert routed_sum(s, 1, whole_device_work=0, context=context) == exact  # known already: no work
    monkeypatch.setattr(window_classes, "WHOLE_DEVICE_MAX_QUBITS", exact.device.num_qubits - 1)
    assert routed_sum(s, 1) is None


@pytest.mark.parametrize(
    "with_5x5", [False, pytest.param(True, marks=pytest.mark.heavy)], ids=["4x4 interior, 3x4/2", "and 5x5/1"]
)
def test_the_allocation_search_answers_by_its_cache_key(with_5x5: bool) -> None:
    """The allocation search's memo (per section up to translation) may serve compile and the sum in one context:
    both are exact only if every section with one key searches to the same answer, on the device and on any crop
    of it."""

    answers: dict = {}  # type: ignore[type-arg]
    conflicts = []

    class Fresh(dict):  # type: ignore[type-arg]
        """Never answers from memory; remembers every answer and notes keys answered two ways."""

        def get(self, key, default=None):  # type: ignore[no-untyped-def]
            return None

        def __setitem__(self, key, value) -> None:  # type: ignore[no-untyped-def]
            if answers.setdefault(key, value) != value:
                conflicts.append((key, answers[key], value))

    context = RoutingContext()
    context.allocations = Fresh()
    small = [interior_endpoints(4, 4, "soft"), default_scenario(3, 4, 2)]
    for s in [default_scenario(5, 5, 1), *small] if with_5x5 else small:
        routed_sum(s, 1, context=context)
        compile_for_device(s, 1, "grid", layout_method="medial", context=context)
    assert len(answers) > 10 and not conflicts
