"""Closed-form formulas equal the exact counts of the built and lowered circuits, for every published quantity.

Every grid from 2x2 to 8x8 (rectangles included) with 1 to 4 robots at p = 1, and p = 2, 3 on a subset. The exact
numbers are computed once per module by :func:`estimators.sweep.sweep` on all cores, without the cache; each is
read from the lowered circuit's counts, the high-level circuit, the Hamiltonian or the registers, never from the
formulas.
"""

from __future__ import annotations

import pytest
import sympy as sp

from circuitgen.lowering import lower_mcx
from circuitgen.qaoa import qaoa_circuit
from estimators import formulas
from estimators.formulas import GATE_NAMES, QUANTITIES, evaluate, formula_table, partial_mixer_types
from estimators.sweep import PointResult, grid_points, sweep
from gridcover.hamiltonian import ising_hamiltonian
from gridcover.presets import default_scenario

GRIDS = [(r, c) for r in range(2, 9) for c in range(2, 9)]
SUBSET = [(2, 2), (2, 5), (3, 3), (4, 6), (5, 4), (6, 2)]
POINTS = grid_points(GRIDS, [1, 2, 3, 4], [1]) + grid_points(SUBSET, [1, 2, 3, 4], [2, 3])


SMALL = [pt for pt in POINTS if pt.rows * pt.cols <= 16]
"""Grids of at most 16 nodes: the default run; every point is checked in CI's ``heavy`` step."""


@pytest.fixture(
    scope="module", params=[pytest.param("small"), pytest.param("all", marks=pytest.mark.heavy)]
)
def results(request: pytest.FixtureRequest) -> list[PointResult]:
    if request.param == "small":
        return sweep(SMALL, jobs=1, use_cache=False, progress=False)  # in-process: pytest -n 2 has the cores
    return sweep(POINTS, use_cache=False, progress=False)


def exact_quantities(res: PointResult) -> dict[str, int]:
    pt, c = res.point, res.counts
    regs = dict(c.registers)
    hamiltonian = ising_hamiltonian(default_scenario(pt.rows, pt.cols, pt.robots))
    out = {
        "data_qubits": c.data_qubits,
        "logic_qubits": regs.get("logic", 0),
        "work_qubits": regs.get("work", 0),
        "ancillas": c.ancillas,
        "qubits": c.qubits,
        "gates": c.size,
        "cx": c.cx,
        "two_qubit": c.two_qubit,
        "single_qubit": c.single_qubit,
        "t_count": c.t,
        "toffoli": res.fault_tolerant.toffoli,
        "rotations": res.fault_tolerant.rotations,
        "nonzero_zz": hamiltonian.num_quadratic_terms(1e-12),
        "partial_mixers": res.high_level.ops.get("csbf", 0),
    }
    out.update({f"gate_{g}": c.ops.get(g, 0) for g in GATE_NAMES})
    return out


def test_every_published_quantity_has_a_formula() -> None:
    assert set(formula_table()) == set(QUANTITIES)


def test_formulas_equal_exact_counts(results: list[PointResult]) -> None:
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
    subs = {formulas.V: formulas.V_EXPR, formulas.P: formulas.P_EXPR}
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
            degrees = [0] * g.num_nodes
            for u, v in g.edge_nodes:
                degrees[u] += 1
                degrees[v] += 1
            pairs = sum(d * (d - 1) // 2 for d in degrees)
            vals = {formulas.rows: r, formulas.cols: c}
            assert formulas.V_EXPR.subs(vals) == g.num_edges
            assert formulas.P_EXPR.subs(vals) == pairs


def test_toffoli_count_is_the_ccx_count_after_mcx_lowering() -> None:
    for r, c, k in [(2, 2, 1), (3, 4, 2), (5, 5, 4)]:
        ccx = sum(1 for g in lower_mcx(qaoa_circuit(default_scenario(r, c, k), 1)).gates if g[0] == "ccx")
        assert evaluate(r, c, k, 1)["toffoli"] == ccx


def test_partial_mixer_types_by_corner_class() -> None:
    # Toffolis of one partial mixer from its corner classes, derived from the logic network: an endpoint
    # corner's step has 2 controls (1 Toffoli), an interior corner's 3 (2*3-3 = 3), each excluded pattern 4 (5);
    # the final step has one control per corner step plus the pattern bit; everything is computed and uncomputed.
    def tof(k: int) -> int:
        return 0 if k <= 1 else (1 if k == 2 else 2 * k - 3)

    for m in partial_mixer_types():
        e, b, diagonal = m.key.count("E"), m.key.count("B"), m.key.endswith("D")
        patterns = (0 if e else 1) + (0 if diagonal else 2)
        final = e + b + (1 if patterns else 0)
        assert m.toffoli == 2 * (e * 1 + b * 3 + patterns * 5 + tof(final)), m
        assert m.ops["cx"] == 6 * m.toffoli + 8 + (2 if final == 1 else 0), m  # csbf: 6 ladder + 2 crz cx
        assert m.ops["rz"] == 2
        assert m.ops["t"] + m.ops["tdg"] == 7 * m.toffoli


def test_evaluate_rejects_points_outside_the_domain() -> None:
    for bad in [(1, 3, 1, 1), (3, 3, 5, 1), (3, 3, 1, 0)]:
        with pytest.raises(ValueError):
            evaluate(*bad)
