"""Logical-AND model: hand examples, rotation costs, and consistency with the logical-basis counts of circuits."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from qcpp.estimators.fault_tolerant import fault_tolerant_from_cost, rotation_t_cost
from qcpp.ir.circuit import CircuitBuilder
from qcpp.ir.cost import Cost
from qcpp.ir.gates import mcx
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.presets import default_scenario


def test_mcx_into_a_clean_bit_costs_ands_and_one_toffoli() -> None:
    # a 5-control X: 3 clean ANDs on the work ladder (4 T each), one full Toffoli (7 T), 3 measured uncomputes
    b = CircuitBuilder([("data", 5), ("logic", 1)])
    b.append([mcx([0, 1, 2, 3, 4], 5)], section="m")
    logical = Cost.count(lower(b.build(), LOGICAL_BASIS).gates)
    ft = fault_tolerant_from_cost(logical)
    assert (ft.and_compute, ft.and_uncompute, ft.toffoli_full, ft.measurements) == (3, 3, 1, 3)
    assert ft.t_logic == 3 * 4 + 7 and ft.toffoli == 7
    assert fault_tolerant_from_cost(logical, toffoli_t=4).t_logic == 3 * 4 + 4
    assert ft.rotations == 0 and ft.total_t == ft.t_logic


@given(
    st.integers(0, 50), st.integers(0, 50), st.integers(0, 50), st.integers(0, 50), st.integers(0, 50),
    st.sampled_from([1e-2, 1e-3, 1e-6]), st.sampled_from([7, 4]),
)  # fmt: skip
def test_totals_add_up(ands: int, undo: int, ccx: int, t: int, rz: int, eps: float, tt: int) -> None:
    c = Cost.of({"and": ands, "and_dg": undo, "ccx": ccx, "t": t, "tdg": t, "rz": rz, "cx": 9, "h": 4})
    ft = fault_tolerant_from_cost(c, eps, toffoli_t=tt)
    assert ft.t_logic == 4 * ands + tt * ccx + 2 * t
    assert ft.t_rotations == rz * rotation_t_cost(eps) and ft.total_t == ft.t_logic + ft.t_rotations
    # scaling the circuit scales every estimate
    ft3 = fault_tolerant_from_cost(3 * c, eps, toffoli_t=tt)
    assert ft3.total_t == 3 * ft.total_t and ft3.measurements == 3 * ft.measurements


def test_rotation_t_cost_formulas() -> None:
    for eps in (1e-1, 1e-3, 1e-6, 1e-10):
        assert rotation_t_cost(eps) == math.ceil(3 * math.log2(1 / eps) - 1e-9)
        assert rotation_t_cost(eps, "selinger") == math.ceil(4 * math.log2(1 / eps) - 1e-9) + 10
    for bad in (0.0, 1.0, -1e-3, 2.0):
        with pytest.raises(ValueError):
            rotation_t_cost(bad)
    with pytest.raises(ValueError):
        rotation_t_cost(1e-3, "solovay")  # type: ignore[arg-type]
    with pytest.raises(ValueError):
        fault_tolerant_from_cost(Cost(), toffoli_t=5)


def test_qaoa_circuit_every_and_is_uncomputed_and_rotations_are_the_rz_gates() -> None:
    for rows, cols, robots in [(3, 3, 1), (2, 3, 2), (3, 4, 5)]:
        circ = qaoa_circuit(default_scenario(rows, cols, robots), 1)
        logical = Cost.count(lower(circ, LOGICAL_BASIS).gates)
        ft = fault_tolerant_from_cost(logical, epsilon=1e-4)
        assert ft.and_compute == ft.and_uncompute > 0  # every temporary AND is uncomputed
        assert ft.rotations == Cost.count(lower(circ).gates).rotations
        assert ft.t_rotations == ft.rotations * math.ceil(3 * math.log2(1e4))
