"""Closed-form formulas equal the exact counts, for every published quantity.

The formulas describe the circuit with the whole-space (Ising) phase separator (``--phase whole-space``); the
default feasible-subspace phase separator has no closed form here. They are the call graph's counting run with
symbolic sides; the phase separator's symbolic term counts are also checked against the Hamiltonian directly.
Every grid from 2x2 to 8x8 (rectangles included) with 1 to 4 robots at p = 1, and p = 2, 3 on a subset. The
exact numbers are the gadget-summed counts of :func:`qcpp.estimators.estimate.estimate_point` (themselves equal to
the counts of the compiled, lowered circuit: ``tests/estimators/estimate_test.py``), the Hamiltonian and the
registers, never the formulas.
"""

from __future__ import annotations

import pytest
import sympy as sp

from qcpp.estimators import formulas
from qcpp.estimators.estimate import Estimate, EstimateOptions, estimate_point
from qcpp.estimators.formulas import GATE_NAMES, QUANTITIES, evaluate, formula_table
from qcpp.estimators.sweep import grid_points
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.hamiltonian import ising_hamiltonian
from qcpp.problem.paths import initial_path
from qcpp.problem.presets import default_scenario, max_default_robots

GRIDS = [(r, c) for r in range(2, 9) for c in range(2, 9)]
SUBSET = [(2, 2), (2, 5), (3, 3), (4, 6), (5, 4), (6, 2)]
POINTS = grid_points(GRIDS, [1, 2, 3, 4], [1]) + grid_points(SUBSET, [1, 2, 3, 4], [2, 3])


WHOLE_SPACE = EstimateOptions(plan=PlanOptions(phase="whole-space"), depth="none")
"""The formulas' domain: the whole-space (Ising) phase separator."""

SMALL = [pt for pt in POINTS if pt.rows * pt.cols <= 16]
"""Grids of at most 16 nodes: the default run; every point is checked in CI's ``heavy`` step."""


@pytest.fixture(scope="module", params=[pytest.param("small"), pytest.param("all", marks=pytest.mark.heavy)])
def results(request: pytest.FixtureRequest) -> list[Estimate]:
    points = SMALL if request.param == "small" else POINTS
    return [estimate_point(pt, WHOLE_SPACE) for pt in points]


def exact_quantities(est: Estimate) -> dict[str, int]:
    pt, c = est.point, est.cost
    regs = dict(est.registers)
    hamiltonian = ising_hamiltonian(default_scenario(pt.rows, pt.cols, pt.robots))
    out = {
        "data_qubits": est.data_qubits,
        "logic_qubits": regs.get("logic", 0),
        "work_qubits": regs.get("work", 0),
        "ancillas": est.qubits - est.data_qubits,
        "qubits": est.qubits,
        "gates": c.total,
        "cx": c.cx,
        "two_qubit": c.two_qubit,
        "single_qubit": c.single_qubit,
        "t_count": c.t,
        "toffoli": est.fault_tolerant.toffoli,
        "rotations": est.fault_tolerant.rotations,
        "nonzero_zz": hamiltonian.num_quadratic_terms(1e-12),
        "partial_mixers": pt.p * pt.robots * (pt.rows - 1) * (pt.cols - 1),
    }
    out.update({f"gate_{g}": c[g] for g in GATE_NAMES})
    return out


def test_every_published_quantity_has_a_formula() -> None:
    assert set(formula_table()) == set(QUANTITIES)


def test_formulas_equal_exact_counts(results: list[Estimate]) -> None:
    mismatches = []
    for res in results:
        pt = res.point
        want = exact_quantities(res)
        got = evaluate(pt.rows, pt.cols, pt.robots, pt.p)
        assert set(want) == set(QUANTITIES)
        mismatches += [(pt.label, k, got[k], v) for k, v in want.items() if got[k] != v]
    assert mismatches == []
    assert [r.point for r in results] in (SMALL, POINTS)
    assert len(POINTS) == 7 * 7 * 4 + len(SUBSET) * 4 * 2


def test_structured_and_explicit_forms_agree() -> None:
    explicit, structured = formula_table(), formula_table(structured=True)
    subs = {formulas.V: formulas.V_EXPR}
    for name in QUANTITIES:
        for point in [(2, 2, 1, 1), (3, 5, 2, 2), (6, 4, 4, 3), (9, 11, 3, 1)]:
            vals = dict(zip((formulas.rows, formulas.cols, formulas.robots, formulas.p), point))
            a = sp.sympify(explicit[name]).subs(vals)
            b = sp.sympify(structured[name]).subs(subs).subs(vals)
            assert a == b, (name, point)


def test_abbreviations_count_what_they_say() -> None:
    for r in range(2, 7):
        for c in range(2, 7):
            g = default_scenario(r, c, 1).grid
            assert formulas.V_EXPR.subs({formulas.rows: r, formulas.cols: c}) == g.num_edges


@pytest.mark.parametrize("rows_case, cols_case", [(2, 2), (2, 5), (3, 4), (5, 3), (4, 4), (5, 5)])
def test_phase_terms_are_the_call_graphs_counting_run_symbolically(rows_case: int, cols_case: int) -> None:
    """The symbolic counts of the phase separator's terms, evaluated, are the Hamiltonian's nonzero terms on
    every grid of the case (sides of >= 5 nodes up to 9)."""
    sides = {2: [2], 3: [3], 4: [4], 5: [5, 6, 7, 9]}
    for k in (1, 2, 3, 4):
        (lin, _), (zz, _) = formulas.part_terms("phase", rows_case, cols_case, k)
        for r in sides[rows_case]:
            for c in sides[cols_case]:
                if k > max_default_robots(r, c):
                    continue
                h = ising_hamiltonian(default_scenario(r, c, k))
                vals = {formulas.rows: r, formulas.cols: c}
                assert lin.subs(vals) == len(list(h.linear_terms(1e-12))), (r, c, k)
                assert zz.subs(vals) == h.num_quadratic_terms(1e-12), (r, c, k)


@pytest.mark.parametrize("rows_case, cols_case", [(2, 2), (2, 5), (3, 4), (5, 3), (4, 4), (5, 5)])
def test_initial_state_terms_are_the_call_graphs_counting_run_symbolically(rows_case: int, cols_case: int) -> None:
    """The symbolic X count of the state preparation, evaluated, is the number of X gates of the compiled initial
    state on every grid of the case (sides of >= 5 nodes up to 11), and the initial paths' edges."""
    sides = {2: [2], 3: [3], 4: [4], 5: [5, 6, 7, 8, 11]}
    for k in (1, 2, 3, 4):
        ((n, term),) = formulas.part_terms("initial_state", rows_case, cols_case, k)
        assert term.ops["x"] == 1 and sum(term.ops.values()) == 1
        for r in sides[rows_case]:
            for c in sides[cols_case]:
                if k > max_default_robots(r, c):
                    continue
                s = default_scenario(r, c, k)
                prep = [g for sec in qaoa_circuit(s, 0).sections if sec.name == "initial_state" for g in sec.gates]
                assert {g.name for g in prep} == {"x"}
                want = sum(initial_path(s, robot).bit_count() for robot in range(k))
                assert n.subs({formulas.rows: r, formulas.cols: c}) == len(prep) == want, (r, c, k)


def test_evaluate_rejects_points_outside_the_domain() -> None:
    for bad in [(1, 3, 1, 1), (3, 3, 5, 1), (3, 3, 1, 0)]:
        with pytest.raises(ValueError):
            evaluate(*bad)
