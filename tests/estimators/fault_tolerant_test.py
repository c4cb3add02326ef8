"""Clifford+T estimates: hand examples for the Toffoli roles and rotation costs, and consistency with exact counts."""

from __future__ import annotations

import math

import pytest

from circuitgen.angles import Angle
from circuitgen.circuit import CircuitBuilder
from circuitgen.gates import ccx, cx, h, mcx, rz, x
from circuitgen.lowering import lower, lower_mcx
from circuitgen.qaoa import qaoa_circuit
from estimators.counts import count
from estimators.fault_tolerant import (
    count_rotations,
    fault_tolerant_estimate,
    rotation_t_cost,
    toffoli_roles,
)
from gridcover.presets import default_scenario
from gridcover.sbf import sbf_logic


def build(gates: list, logic: int = 2, data: int = 4):  # type: ignore[no-untyped-def]
    b = CircuitBuilder([("data", data), ("logic", logic)])
    b.append(gates, section="s")
    return b.build()


def test_and_into_clean_bit_then_its_mirror() -> None:
    step = mcx([0, 1, 2, 3], 4, "1001")  # 4 controls: ladder of 2 into work, 1 onto the target, 2 back
    roles = toffoli_roles(build([step, step]))
    # per mcx: 2 ladder ANDs (4 T) + 2 ladder un-ANDs (0 T); the target Toffoli: AND first, un-AND second
    assert (roles.and_compute, roles.and_uncompute, roles.full) == (2 + 1 + 2, 2 + 1 + 2, 0)
    ft = fault_tolerant_estimate(build([step, step]))
    assert ft.toffoli == 10 == sum(1 for g in lower_mcx(build([step, step])).gates if g[0] == "ccx")
    assert ft.t_toffoli7 == 7 * 10
    assert ft.t_logical_and == 4 * 5 + 0 * 5


def test_target_holding_a_value_needs_full_toffolis() -> None:
    # x then two XORs of the same AND: the bit holds 1 at both, so neither is a clean AND
    roles = toffoli_roles(build([x(4), ccx(0, 1, 4), ccx(0, 1, 4), x(4)]))
    assert (roles.and_compute, roles.and_uncompute, roles.full) == (0, 0, 2)


def test_flipped_control_makes_a_different_term() -> None:
    # between the two Toffolis the control q0 is flipped: the second is not the mirror of the first
    roles = toffoli_roles(build([ccx(0, 1, 4), x(0), ccx(0, 1, 4)]))
    assert (roles.and_compute, roles.and_uncompute, roles.full) == (1, 0, 1)


def test_non_diagonal_gate_on_an_ancilla_spoils_it() -> None:
    roles = toffoli_roles(build([h(4), ccx(0, 1, 4)]))
    assert (roles.and_compute, roles.full) == (0, 1)
    roles = toffoli_roles(build([rz(0.3, 4), ccx(0, 1, 4)]))  # diagonal: still |0>
    assert roles.and_compute == 1


def test_copy_into_ancilla_is_tracked() -> None:
    # cx copies q0 into the ancilla; a later Toffoli into it is not an AND into |0>
    roles = toffoli_roles(build([cx(0, 4), ccx(1, 2, 4)]))
    assert roles.full == 1


def test_toffoli_into_data_qubit_is_full() -> None:
    assert toffoli_roles(build([ccx(0, 1, 2)])).full == 1


def test_rotation_t_cost_formulas() -> None:
    for eps in [1e-2, 1e-3, 1e-6, 1e-10]:
        assert rotation_t_cost(eps) == math.ceil(3 * math.log2(1 / eps))
        assert rotation_t_cost(eps, "selinger") == math.ceil(4 * math.log2(1 / eps)) + 10
    assert rotation_t_cost(2**-10) == 30  # exactly 3 * 10, no rounding up
    for bad in [0.0, 1.0, -1e-3]:
        with pytest.raises(ValueError):
            rotation_t_cost(bad)
    with pytest.raises(ValueError):
        rotation_t_cost(1e-3, "solovay-kitaev")  # type: ignore[arg-type]


def test_count_rotations_by_angle() -> None:
    gates = [
        rz(math.pi / 2, 0),  # S: Clifford
        rz(math.pi, 0),  # Z: Clifford
        rz(-math.pi / 4, 0),  # T-like
        rz(3 * math.pi / 4, 1),  # T-like
        rz(0.1, 1),  # arbitrary
        rz(Angle.symbol("gamma_0", 2.0), 1),  # symbolic: arbitrary
        rz(Angle(math.pi / 4), 1),  # a bound Angle: T-like
    ]
    r = count_rotations(gates)
    assert (r.arbitrary, r.t_like, r.clifford) == (2, 3, 2)


def test_qaoa_circuits_toffoli_count_and_t_count_match_exact_counts() -> None:
    for rows, cols, robots, rule in [(3, 3, 1, "exact"), (2, 3, 2, "exact"), (3, 4, 2, "paper")]:
        circ = qaoa_circuit(default_scenario(rows, cols, robots), 1, rule=rule)  # type: ignore[arg-type]
        low = lower(circ)
        ft = fault_tolerant_estimate(circ, low, epsilon=1e-4)
        rc = count(low)
        assert ft.toffoli == sum(1 for g in lower_mcx(circ).gates if g[0] == "ccx")
        assert ft.t_toffoli7 == rc.t  # Nielsen-Chuang Toffoli: 7 T, nothing else has T
        assert ft.rotations == rc.ops["rz"]  # every RZ angle is symbolic
        assert ft.and_compute == ft.and_uncompute  # every temporary AND is uncomputed
        assert ft.t_rotations == ft.rotations * math.ceil(3 * math.log2(1e4))
        assert ft.total_t_logical_and == ft.t_logical_and + ft.t_rotations


def test_three_by_three_full_toffolis_are_the_pattern_steps() -> None:
    # The pattern bit starts at 1 (an X) and collects one 4-control term per excluded pattern; those target
    # Toffolis (one per pattern step, in the compute and the uncompute half) are the only full ones.
    s = default_scenario(3, 3, 1)
    patterns = sum(
        sum(1 for st in sbf_logic(s, 0, q).steps if len(st.literals) == 4) for q in s.grid.plaquettes
    )
    ft = fault_tolerant_estimate(qaoa_circuit(s, 1))
    assert ft.toffoli_full == 2 * patterns
    assert ft.t_logical_and == 4 * ft.and_compute + 7 * ft.toffoli_full
