"""The paper's estimates, recomputed by hand from the text of its section "Resource estimates"."""

from __future__ import annotations

import pytest

from qcpp.estimators.paper import paper_estimate, paper_partial_mixer, toffoli_decomposition


def test_toffoli_decomposition_follows_barenco_4_l_minus_2() -> None:
    # "An (l+1)-qubit Toffoli gate can be decomposed into 4(l-2) 3-qubit Toffoli gates ... when l >= 3"
    for l_controls in range(3, 9):
        assert toffoli_decomposition(l_controls + 1) == 4 * (l_controls - 2)
    assert toffoli_decomposition(3) == 1
    with pytest.raises(ValueError):
        toffoli_decomposition(2)


def test_partial_mixer_by_hand() -> None:
    five_qubit = 4 * (4 - 2)  # l = 4 controls
    seven_qubit = 4 * (6 - 2)  # l = 6 controls
    toffolis = 1 * five_qubit + 2 * five_qubit + 4 * 1 + 1 * seven_qubit  # f1, f2, f3, f
    assert toffolis == 44
    sbf_cx = 6 + 2  # the figure's 6 CNOT, plus the controlled RZ's 2 CNOT
    sbf_1q = 8 + 2  # the figure's 8 H; its RZ becomes the controlled RZ's 2 RZ
    pm = paper_partial_mixer()
    assert (pm.toffolis, pm.logic_cx, pm.logic_single_qubit) == (toffolis, 6 * toffolis, 9 * toffolis)
    assert (pm.sbf_cx, pm.sbf_single_qubit) == (sbf_cx, sbf_1q)
    # "the total gate requirement is twice of the controlled partial mixer" (literal: all of it)
    assert (pm.cx, pm.single_qubit) == (2 * (6 * toffolis + sbf_cx), 2 * (9 * toffolis + sbf_1q))
    logic_only = paper_partial_mixer("logic")
    assert (logic_only.cx, logic_only.single_qubit) == (2 * 6 * toffolis + sbf_cx, 2 * 9 * toffolis + sbf_1q)
    with pytest.raises(ValueError):
        paper_partial_mixer("everything")  # type: ignore[arg-type]


def test_three_by_three_one_robot_by_hand() -> None:
    m = n = 3
    r = 1
    e = m * (n - 1) + n * (m - 1)
    assert e == 12
    re = r * e
    est = paper_estimate(3, 3, 1, p=1)
    assert est.edges == e
    # the paper's own experiment: "Twenty qubits (12 decision variable qubits + 8 ancillary qubits)"
    assert (est.data_qubits, est.ancillas, est.qubits) == (12, 8, 20)
    assert est.phase_cx == re * (re + 1) == 156
    assert est.phase_single_qubit == re + re * (re + 1) // 2 == 90
    assert est.partial_mixers == r * (m - 1) * (n - 1) == 4
    assert (est.partial_mixer_cx, est.partial_mixer_single_qubit) == (544, 812)
    assert est.initial_single_qubit == r * (m + n - 2) == 4
    assert est.cx == 156 + 4 * 544 == 2332
    assert est.single_qubit == 4 + 90 + 4 * 812 == 3342
    assert est.toffolis == 4 * 2 * 44


def test_two_robots_three_by_three_is_about_forty_qubits() -> None:
    # "The number of qubits needed to run QAOA algorithm for two robots on a 3x3 grid (~40)"
    assert paper_estimate(3, 3, 2).qubits == 40


def test_layers_multiply_and_initial_state_is_added_once() -> None:
    one, three = paper_estimate(4, 5, 3, p=1), paper_estimate(4, 5, 3, p=3)
    assert three.cx == 3 * one.cx
    assert three.single_qubit - three.initial_single_qubit == 3 * (one.single_qubit - one.initial_single_qubit)
    assert paper_estimate(4, 5, 3, p=0).cx == 0


def test_symmetric_in_rows_and_cols() -> None:
    assert paper_estimate(3, 7, 2) == paper_estimate(7, 3, 2).__class__(
        **{**paper_estimate(7, 3, 2).to_dict(), "rows": 3, "cols": 7}
    )


@pytest.mark.parametrize("bad", [(1, 3, 1, 1), (3, 3, 0, 1), (3, 3, 1, -1), (3.0, 3, 1, 1)])
def test_bad_input(bad: tuple[int, int, int, int]) -> None:
    with pytest.raises(ValueError):
        paper_estimate(*bad)
