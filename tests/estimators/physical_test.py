"""Physical estimates: the logical counts handed to the QDK estimator, its figures, and refusals as ValueErrors."""

from __future__ import annotations

import pytest

from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.estimators.physical import (
    QEC_SCHEMES,
    QUBIT_MODELS,
    LogicalCounts,
    PhysicalEstimateError,
    physical_estimate,
)

COUNTS = LogicalCounts(
    num_qubits=40, t_count=200, rotation_count=30, rotation_depth=10, ccz_count=8, ccix_count=60, measurement_count=90
)


def test_logical_counts_of_an_estimate() -> None:
    est = estimate_point(Point(3, 3, 2, 2), EstimateOptions(physical=True))
    lc = est.logical_counts
    assert lc.num_qubits == est.qubits
    assert (lc.ccix_count, lc.ccz_count) == (est.logical["and"], est.logical["ccx"])
    assert lc.measurement_count == est.logical["and_dg"] + est.data_qubits
    assert lc.rotation_count == est.logical.rotations and 0 < lc.rotation_depth <= lc.rotation_count
    assert lc.t_count == est.logical.t
    ph = est.physical
    assert ph is not None and ph.physical_qubits == ph.algorithm_qubits + ph.t_factory_qubits
    assert ph.physical_qubits > 2 * est.qubits and ph.runtime_s > 0 and ph.t_factories >= 1
    # the estimator's T states: T gates + 4 per CCZ/CCiX + its own T per rotation
    assert ph.t_states >= lc.t_count + 4 * (lc.ccz_count + lc.ccix_count) + lc.rotation_count


def test_more_work_never_needs_fewer_resources() -> None:
    small = physical_estimate(COUNTS)
    bigger = physical_estimate(LogicalCounts(**{**COUNTS.__dict__, "t_count": 200_000, "rotation_count": 3000}))
    assert bigger.runtime_s > small.runtime_s
    assert bigger.t_states > small.t_states


def test_models_and_budget_are_passed_through() -> None:
    base = physical_estimate(COUNTS)
    better = physical_estimate(COUNTS, qubit_model="qubit_gate_ns_e4")
    assert (base.qubit_model, better.qubit_model) == ("qubit_gate_ns_e3", "qubit_gate_ns_e4")
    assert better.code_distance < base.code_distance  # lower physical error rates need a smaller code
    maj = physical_estimate(COUNTS, qubit_model="qubit_maj_ns_e6", qec_scheme="floquet_code", error_budget=1e-2)
    assert maj.qec_scheme == "floquet_code" and maj.error_budget == 1e-2
    assert set(QUBIT_MODELS) >= {"qubit_gate_ns_e3", "qubit_maj_ns_e6"} and QEC_SCHEMES[0] == "surface_code"


@pytest.mark.parametrize(
    "kwargs",
    [{"qubit_model": "transmon"}, {"qec_scheme": "color_code"}, {"error_budget": 0.0}, {"error_budget": 1.5}],
)
def test_bad_options(kwargs: dict) -> None:
    with pytest.raises(ValueError):
        physical_estimate(COUNTS, **kwargs)


def test_estimator_refusals_are_value_errors_with_one_line() -> None:
    with pytest.raises(ValueError, match="floquet_code needs a Majorana qubit model") as info:
        physical_estimate(COUNTS, qec_scheme="floquet_code")  # refused before the QDK: it needs Majorana qubits
    assert "\n" not in str(info.value) and "qubit_gate_ns_e3" in str(info.value)
    with pytest.raises(PhysicalEstimateError) as qdk:  # the QDK's own refusal: no code distance reaches the budget
        physical_estimate(COUNTS, error_budget=1e-30)
    message = str(qdk.value)
    assert isinstance(qdk.value, ValueError) and "\n" not in message and "QDK resource estimator" in message
