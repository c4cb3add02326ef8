"""The QDK resource estimator's own reading of qcpp's circuits against qcpp's logical counts, term by term."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.estimators.physical import physical_estimate
from qcpp.estimators.qdk_reading import asap_rotation_depth, logical_and_qasm, qdk_read
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.lowering.qasm import to_qasm3
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario

ANGLES = {"gamma_0": 0.3, "beta_0": 0.7}


def _g(name: str, qubits: tuple[int, ...], *params: float) -> Gate:
    return Gate(name, qubits, tuple(params), None)


def test_asap_rule_layers_t_gates_and_counts_rotation_layers() -> None:
    # rz q0 | cx aligns q1 to q0's layer | t q1 takes a layer | rz q1 lands one layer later: two rotation layers
    gates = [_g("rz", (0,), 0.3), _g("cx", (0, 1)), _g("t", (1,)), _g("rz", (1,), 0.2), _g("rz", (2,), 0.1)]
    assert asap_rotation_depth(gates, 3) == 2
    # rz of a multiple of pi/4: a T (takes a layer, no rotation) or a Clifford (nothing)
    assert asap_rotation_depth([_g("rz", (0,), math.pi / 4), _g("rz", (0,), 0.3)], 1) == 1
    assert asap_rotation_depth([_g("rz", (0,), math.pi / 2), _g("rz", (1,), 0.3), _g("rz", (0,), 0.3)], 2) == 1
    with pytest.raises(ValueError, match="not read"):
        asap_rotation_depth([Gate("and", (0, 1, 2), (), None)], 3)


def test_logical_and_text_refuses_unlowered_or_unbound_gates() -> None:
    with pytest.raises(ValueError, match="logical basis"):
        logical_and_qasm(Circuit([("data", 2)], [Section("s", [_g("rzz", (0, 1), 0.1)])]))
    from qcpp.ir.angles import Angle

    unbound = Gate("rz", (0,), (Angle.symbol("gamma_0", 1.0),), None)
    with pytest.raises(ValueError, match="unbound"):
        logical_and_qasm(Circuit([("data", 1)], [Section("s", [unbound])]))


@pytest.mark.heavy
@pytest.mark.parametrize("target", ["nisq", "ft"])
def test_qdk_reading_agrees_with_qcpp_counts(target: str) -> None:
    """On a small circuit the QDK, reading the logical-AND text, counts what qcpp counts (within 5%, exact in
    practice) in every term but the rotation depth, which is never below qcpp's; with its rotation depth handed to
    the estimator, qcpp's counts give the QDK's physical qubits and runtime; the Python rule reproduces the QDK's
    rotation depth on the file as written."""
    plan = PlanOptions(target=target)  # type: ignore[arg-type]
    est = estimate_point(Point(2, 3, 1, 1), EstimateOptions(plan=plan, depth="exact", physical=True))
    ours = est.logical_counts
    circuit = compile_scenario(default_scenario(2, 3, 1), 1, plan, bindings=ANGLES).circuit
    qdk = qdk_read(logical_and_qasm(lower(circuit, basis=LOGICAL_BASIS)))
    theirs = qdk.counts
    assert ours.ccix_count > 0 and ours.rotation_count > 0  # the terms under test are present

    def close(a: float, b: float) -> bool:
        return abs(a - b) <= 0.05 * max(abs(a), abs(b))

    assert close(ours.num_qubits, theirs.num_qubits)
    assert close(ours.rotation_count, theirs.rotation_count)
    assert close(ours.measurement_count, theirs.measurement_count)
    assert close(ours.t_count, theirs.t_count)
    assert close(ours.ccz_count + ours.ccix_count, theirs.ccz_count + theirs.ccix_count)
    assert est.physical is not None
    assert close(est.physical.t_states, qdk.physical.t_states)
    n = ours.num_qubits
    assert qdk.logical_qubits == 2 * n + math.ceil(math.sqrt(8 * n)) + 1
    assert ours.rotation_depth <= theirs.rotation_depth

    swapped = physical_estimate(replace(ours, rotation_depth=theirs.rotation_depth))
    assert close(swapped.physical_qubits, qdk.physical.physical_qubits)
    assert close(swapped.runtime_s, qdk.physical.runtime_s)
    assert swapped.code_distance == qdk.physical.code_distance

    as_file = qdk_read(to_qasm3(circuit))
    assert as_file.counts.rotation_depth == asap_rotation_depth(lower(circuit, peephole=False).gates, n)
    # the file writes each AND and each uncompute as 4 T gates: 4 more T states per uncompute than qcpp's model
    assert as_file.physical.t_states - est.physical.t_states == 4 * ours.ccix_count


def test_qdk_read_silences_the_legacy_estimators_deprecation_and_nothing_else(monkeypatch: pytest.MonkeyPatch) -> None:
    import warnings

    from qdk import openqasm

    text = 'OPENQASM 3.0;\ninclude "stdgates.inc";\nqubit[1] q;\nt q[0];\nrz(0.3) q[0];\n'
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        reading = qdk_read(text)
    assert reading.counts.t_count == 1 and reading.counts.rotation_count == 1
    assert not [w for w in seen if "deprecated" in str(w.message)], [str(w.message) for w in seen]

    class Called(Exception):
        pass

    def legacy(source: str, params: object) -> None:
        warnings.warn("This version of QRE is deprecated and will be removed", DeprecationWarning, stacklevel=2)
        warnings.warn("another deprecation", DeprecationWarning, stacklevel=2)
        raise Called

    monkeypatch.setattr(openqasm, "estimate", legacy)
    with warnings.catch_warnings(record=True) as seen, pytest.raises(Called):
        warnings.simplefilter("always")
        qdk_read(text)
    assert [str(w.message) for w in seen] == ["another deprecation"]


def test_qdk_read_names_the_missing_legacy_estimator(monkeypatch: pytest.MonkeyPatch) -> None:
    from qdk import openqasm

    monkeypatch.delattr(openqasm, "estimate")
    with pytest.raises(ImportError, match=r"qdk\.openqasm\.estimate"):
        qdk_read('OPENQASM 3.0;\nqubit[1] q;\n')
