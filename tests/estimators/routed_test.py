"""``estimate --device``: which way the routed figures are obtained, and that each is what it says."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from qcpp.estimators import layout_bound, routed
from qcpp.estimators.layout_bound import bound_plan, compact_placement, layout_twoq_bound
from qcpp.estimators.routed import routed_fields
from qcpp.hardware.device import get_device
from qcpp.layout.medial import medial_placement
from qcpp.pipeline.device_compile import compile_for_device, layout_device
from qcpp.pipeline.device_plan import device_plan_options
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario
from qcpp.routing.context import RoutingContext
from qcpp.routing.native import esp
from tests.compiler.conftest import scenarios


def _fields(s, p, device, **kw):  # type: ignore[no-untyped-def]
    cost = qaoa_plan(s, p, PlanOptions()).cost()
    return routed_fields(s, p, PlanOptions(), device, qubits=qaoa_plan(s, p).num_qubits, cx=cost.two_qubit,
                         one_qubit=cost.single_qubit, total_gates=cost.total, **kw)  # fmt: skip


@pytest.mark.parametrize(  # the window sum is exact on 4x5/2 (on 3x3/2, 3x4/2 and 4x4/2 it is a bound)
    "shape", [(4, 5, 2), pytest.param((5, 5, 2), marks=pytest.mark.heavy)], ids=["4x5/2", "5x5/2"]
)
def test_the_window_sum_gives_compiles_counts_and_esp(
    monkeypatch: pytest.MonkeyPatch, shape: tuple[int, int, int]
) -> None:
    monkeypatch.setattr(routed, "EXACT_MAX_GATES", 0)  # take the window sum at a size compile answers quickly
    s = default_scenario(*shape)
    f = _fields(s, 1, "grid")
    assert f["routed_kind"] == "exact" and f["routed_depth_kind"] == "bound"
    assert f["routed_model"] == routed.SUM_MODEL
    r = compile_for_device(s, 1, "grid", context=RoutingContext())  # searched and routed afresh, apart from the sum
    assert r.layout_method == "medial" and f["device"] == r.routed.device.name
    summary = r.summary()["routed"]
    assert f["routed_twoq"] == summary["two_qubit"]
    assert math.isclose(f["esp"], esp(r.routed), rel_tol=1e-9)


@pytest.mark.parametrize("shape", [(3, 4, 2), pytest.param((4, 4, 2), marks=pytest.mark.heavy)], ids=["3x4/2", "4x4/2"])
def test_the_bound_counts_the_circuit_the_device_compile_routes(
    monkeypatch: pytest.MonkeyPatch, shape: tuple[int, int, int]
) -> None:
    monkeypatch.setattr(routed, "EXACT_MAX_GATES", 0)
    s = default_scenario(*shape)
    f = _fields(s, 1, "heavy-hex")
    assert f["routed_kind"] == "bound" and f["routed_model"] == routed.LAYOUT_BOUND_MODEL
    dev = get_device(f["device"])
    assert f["routed_twoq"] == layout_twoq_bound(bound_plan(s, 1, PlanOptions(), dev), dev)
    laid = qaoa_plan(s, 1, replace(device_plan_options(PlanOptions(), "heavy-hex"), fuse=False))
    pooled = qaoa_plan(s, 1, PlanOptions(phase_layout="pooled", fuse=False)).cost().two_qubit
    assert laid.cost().two_qubit > pooled  # star adders: the row's own (pooled) count would not bound the device's


@pytest.mark.parametrize(
    ("shape", "device"),
    [((2, 3, 1), "ibm_fez"), pytest.param((3, 4, 2), "ibm_torino", marks=pytest.mark.heavy)],
    ids=["2x3/1-ibm_fez", "3x4/2-ibm_torino"],
)
def test_off_the_geometric_layout_the_bound_is_at_least_what_compile_routes(
    monkeypatch: pytest.MonkeyPatch, shape: tuple[int, int, int], device: str
) -> None:
    """Data in a breadth-first ball of the device: the bound of the routing from there against compile's greedy
    routing, two-qubit count and ESP."""
    monkeypatch.setattr(routed, "EXACT_MAX_GATES", 0)
    s = default_scenario(*shape)
    f = _fields(s, 1, device)
    assert f["routed_kind"] == "bound" and f["routed_model"] == routed.BALL_BOUND_MODEL
    summary = compile_for_device(s, 1, device).summary()["routed"]
    assert summary["two_qubit"] <= f["routed_twoq"] and f["esp"] <= summary["esp"]


def test_on_an_all_to_all_device_the_bound_is_the_circuits_two_qubit_count(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(routed, "EXACT_MAX_GATES", 0)
    s = default_scenario(3, 3, 2)
    f = _fields(s, 1, "quantinuum_helios")
    assert f["routed_kind"] == "bound" and f["routed_model"] == routed.BALL_BOUND_MODEL
    assert f["routed_twoq"] == compile_for_device(s, 1, "quantinuum_helios").summary()["routed"]["two_qubit"]


def test_the_bound_grows_an_unsized_device_as_compile_does(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where a section wants more free qubits than the device has: the unsized family grows, a named device does
    not fit."""
    s = default_scenario(3, 3, 1)
    small, big = get_device("grid:5x5"), get_device("grid:6x6")
    plan = bound_plan(s, 1, PlanOptions(), small)
    real = layout_bound.layout_twoq_bound
    monkeypatch.setattr(layout_bound, "layout_twoq_bound",
                        lambda plan, dev, *args: None if dev.name == "grid:5x5" else real(plan, dev, *args))
    grown = routed._bound_of_compiled(plan, small, grows=True)
    assert grown["device"] == "grid:6x6" and grown["routed_twoq"] == real(plan, big)
    kept = routed._bound_of_compiled(plan, small)
    assert kept["fits"] is False and kept["routed_twoq"] is None


def test_a_bound_row_builds_its_plan_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """The bound's cost, placement and grown devices all read the one plan the row builds."""
    import qcpp.plan.qaoa

    monkeypatch.setattr(routed, "EXACT_MAX_GATES", 0)
    s = default_scenario(3, 4, 2)
    row = qaoa_plan(s, 1, PlanOptions())
    cost = row.cost()
    built: list[int] = []
    real = qcpp.plan.qaoa.qaoa_plan
    monkeypatch.setattr(qcpp.plan.qaoa, "qaoa_plan", lambda *args: built.append(1) or real(*args))
    f = routed_fields(s, 1, PlanOptions(), "heavy-hex", qubits=row.num_qubits, cx=cost.two_qubit,
                      one_qubit=cost.single_qubit, total_gates=cost.total)  # fmt: skip
    assert f["routed_model"] == routed.LAYOUT_BOUND_MODEL and len(built) == 1


def test_off_the_layout_the_data_sit_in_the_largest_piece() -> None:
    # a 2-qubit piece holding qubit 0 and the middle qubit, beside a 7-qubit line
    line = tuple((q, q + 1) for q in range(4, 10))
    whole = get_device("grid:1x11")
    kept = len(line) + 1  # per-coupling data for the couplings kept
    durations = None if whole.duration_2q_s is None else whole.duration_2q_s[:kept]
    dev = replace(whole, coupling=((0, 1), *line), error_2q=whole.error_2q[:kept], duration_2q_s=durations)
    assert sorted(compact_placement(dev, 7) or ()) == list(range(4, 11))
    assert compact_placement(dev, 8) is None


def test_small_rows_are_compiled_and_exact_everywhere() -> None:
    f = _fields(default_scenario(3, 3, 1), 1, "grid")
    assert (f["routed_kind"], f["routed_depth_kind"], f["routed_model"]) == ("exact", "exact", routed.COMPILE_MODEL)


@pytest.mark.parametrize(
    ("shape", "device"),
    [
        ((4, 4, 1), "grid"),
        ((3, 4, 2), "grid"),
        ((2, 3, 1), "heavy-hex"),
        pytest.param((3, 3, 1), "heavy-hex", marks=pytest.mark.heavy),
        pytest.param((4, 5, 3), "grid", marks=pytest.mark.heavy),
        pytest.param((4, 4, 2), "heavy-hex", marks=pytest.mark.heavy),
    ],
    ids=["4x4/1-grid", "3x4/2-grid", "2x3/1-heavy-hex", "3x3/1-heavy-hex", "4x5/3-grid", "4x4/2-heavy-hex"],
)
def test_the_bound_is_at_least_what_compile_routes(shape: tuple[int, int, int], device: str) -> None:
    s = default_scenario(*shape)
    r = compile_for_device(s, 1, device, layout_method="medial", lowered=True)
    dev = r.routed.device
    f = routed._bound_of_compiled(bound_plan(s, 1, PlanOptions(), dev), dev)
    assert f["routed_model"] == routed.LAYOUT_BOUND_MODEL
    assert sum(len(g[1]) == 2 for g in r.routed.circuit.gates) <= f["routed_twoq"]
    assert f["esp"] <= esp(compile_for_device(s, 1, dev, layout_method="medial").routed)


SMALL_ROUTED = [
    ((2, 3, 1), "grid"),
    ((3, 3, 1), "grid"),
    ((2, 3, 1), "heavy-hex"),
    pytest.param((3, 3, 2), "grid", marks=pytest.mark.heavy),
    pytest.param((3, 3, 3), "grid", marks=pytest.mark.heavy),
    pytest.param((4, 4, 2), "grid", marks=pytest.mark.heavy),
    pytest.param((3, 3, 1), "heavy-hex", marks=pytest.mark.heavy),
    pytest.param((3, 3, 2), "heavy-hex", marks=pytest.mark.heavy),
    pytest.param((3, 3, 3), "heavy-hex", marks=pytest.mark.heavy),
]


def _small_id(v: object) -> str:
    return v if isinstance(v, str) else "x".join(map(str, v))  # type: ignore[call-overload]


@pytest.mark.parametrize(("shape", "device"), SMALL_ROUTED, ids=_small_id)
@pytest.mark.parametrize("p", [1, 2])
def test_the_layout_bound_is_at_least_what_compile_device_routes(
    shape: tuple[int, int, int], device: str, p: int
) -> None:
    """The estimate's bound (on the device it sizes for the row, as routed_fields does) against the two-qubit
    count of ``qcpp compile --device`` (its own choice of layout and device size), 1-3 robots."""
    s = default_scenario(*shape)
    r = compile_for_device(s, p, device, lowered=True)
    compiled = sum(len(g[1]) == 2 for sec in r.routed.circuit.sections for g in sec.gates)
    dev = layout_device(s, device)
    assert dev is not None
    f = routed._bound_of_compiled(bound_plan(s, p, PlanOptions(), dev), dev)
    assert f["routed_model"] == routed.LAYOUT_BOUND_MODEL
    assert compiled <= f["routed_twoq"]


@pytest.mark.heavy
@given(scenarios(max_side=3, max_robots=2), st.integers(1, 2), st.sampled_from(["grid", "heavy-hex"]))
@settings(max_examples=6)
def test_the_layout_bound_is_at_least_what_compile_routes_on_random_scenarios(s: Scenario, p: int, device: str) -> None:
    """As above on random small scenarios (obstacles, robots anywhere)."""
    dev = layout_device(s, device)
    assume(dev is not None and medial_placement(s, dev) is not None)
    assert dev is not None
    r = compile_for_device(s, p, device, lowered=True)
    compiled = sum(len(g[1]) == 2 for sec in r.routed.circuit.sections for g in sec.gates)
    assert compiled <= routed._bound_of_compiled(bound_plan(s, p, PlanOptions(), dev), dev, grows=True)["routed_twoq"]


def test_charging_one_step_less_per_gate_falls_below_compile(monkeypatch: pytest.MonkeyPatch) -> None:
    """The check above can fail: gates charged one step shorter than their distance (``d - 1``) bound less
    than compile routes."""
    s = default_scenario(3, 3, 1)
    r = compile_for_device(s, 1, "grid", lowered=True)
    compiled = sum(len(g[1]) == 2 for sec in r.routed.circuit.sections for g in sec.gates)
    dev = layout_device(s, "grid")
    assert dev is not None
    plan = bound_plan(s, 1, PlanOptions(), dev)
    assert compiled <= layout_twoq_bound(plan, dev)
    real = layout_bound.gate_distances
    monkeypatch.setattr(layout_bound, "gate_distances", lambda *args: real(*args) - 1)
    assert layout_twoq_bound(plan, dev) < compiled


def test_a_long_row_names_its_routing_stages() -> None:
    seen: list[str] = []
    f = _fields(default_scenario(2, 3, 1), 1, "grid", stage=seen.append)
    assert f["routed_kind"] == "exact"
    assert seen[0] == "2x3 r1 p1 on grid:5x5: compiling the circuit"
    assert any(text.endswith("windows") for text in seen) and seen[-1] == ""  # cleared when the row is done


def test_the_esp_is_summed_in_log_space_so_a_long_routing_keeps_it() -> None:
    """A routing bound of 12x20 size (1.6 million two-qubit gates) has an ESP far below the smallest double: ``esp``
    is 0.0, ``log10_esp`` the figure, equal to the product written as a sum of log10 terms."""
    device = get_device("heavy-hex:9")
    twoq, one_qubit, data = 1_629_850, 120_000, 400
    f = routed._bound(device, twoq, one_qubit, data, routed.LAYOUT_BOUND_MODEL)
    e2, ro = max(device.error_2q), max(device.readout_error)
    e1 = max(e for _, per_q in device.error_1q for e in per_q)
    expected = twoq * math.log10(1 - e2) + (3 * one_qubit + 6 * twoq) * math.log10(1 - e1) + data * math.log10(1 - ro)
    assert f["esp"] == 0.0 and f["log10_esp"] == pytest.approx(expected, abs=1e-5) and f["log10_esp"] < -308
    assert f["log10_esp_idle"] is None and set(routed._NONE) <= set(f)


def test_an_exact_rows_log10_esp_is_the_log_of_its_esp() -> None:
    f = _fields(default_scenario(2, 3, 1), 1, "ibm_fez")
    assert f["routed_kind"] == "exact" and 0 < f["esp_idle"] < f["esp"] < 1
    assert f["log10_esp"] == pytest.approx(math.log10(f["esp"]), abs=1e-6)
    assert f["log10_esp_idle"] == pytest.approx(math.log10(f["esp_idle"]), abs=1e-6)
