"""Exports of the QUBO (qcpp.qubo.export): every format read back gives the model's energies."""

from __future__ import annotations

import json

import numpy as np
import pytest

from qcpp.problem.presets import default_scenario
from qcpp.problem.solvers import dfs
from qcpp.qubo.export import EXPORT_FORMATS, export_text, mip_name
from qcpp.qubo.model import best_auxiliaries, paper_bqm, per_robot_bqm


def _random_rows(n: int, seed: int = 0) -> np.ndarray:
    return (np.random.default_rng(seed).random((16, n)) < 0.4).astype(np.uint8)


@pytest.fixture(scope="module")
def model():  # type: ignore[no-untyped-def]
    return per_robot_bqm(default_scenario(3, 3, 2), penalty=7.5)


def test_qubo_list_reads_back(model) -> None:  # type: ignore[no-untyped-def]
    d = json.loads(export_text(model, "qubo"))
    assert d["variables"] == list(model.labels) and d["penalty"] == 7.5 and d["form"] == "per-robot"
    col = {lab: i for i, lab in enumerate(d["variables"])}
    diag = [(a, b) for a, b, _ in d["Q"] if a == b]
    assert len(diag) == model.num_variables
    rows = _random_rows(model.num_variables)
    e = d["offset"] + sum(q * rows[:, col[a]] * rows[:, col[b]] for a, b, q in d["Q"])
    assert np.allclose(e, model.energy(rows))


def test_ising_reads_back_with_x_equals_one_minus_z_over_two(model) -> None:  # type: ignore[no-untyped-def]
    d = json.loads(export_text(model, "ising"))
    col = {lab: i for i, lab in enumerate(d["variables"])}
    rows = _random_rows(model.num_variables, 1)
    z = 1 - 2 * rows.astype(float)
    e = d["offset"] + sum(h * z[:, col[a]] for a, h in d["h"].items())
    e = e + sum(j * z[:, col[a]] * z[:, col[b]] for a, b, j in d["J"])
    assert np.allclose(e, model.energy(rows))


def test_bqm_json_is_dimod_serializable_and_the_spin_sign_trap(model) -> None:  # type: ignore[no-untyped-def]
    dimod = pytest.importorskip("dimod")
    bqm = dimod.BinaryQuadraticModel.from_serializable(json.loads(export_text(model, "bqm")))
    rows = _random_rows(model.num_variables, 2)
    got = bqm.energies((rows, list(model.labels)))
    assert np.allclose(got, model.energy(rows))
    # dimod's spins are s = 2x - 1 = -Z: from_ising needs -h, with h taken as it is the energies differ
    d = json.loads(export_text(model, "ising"))
    J = {(a, b): j for a, b, j in d["J"]}
    spins = 2 * rows.astype(int) - 1
    right = dimod.BinaryQuadraticModel.from_ising({k: -v for k, v in d["h"].items()}, J, d["offset"])
    wrong = dimod.BinaryQuadraticModel.from_ising(d["h"], J, d["offset"])
    assert np.allclose(right.energies((spins, list(model.labels))), model.energy(rows))
    assert not np.allclose(wrong.energies((spins, list(model.labels))), model.energy(rows))


@pytest.mark.parametrize("form", ["paper", "per-robot"])
def test_mps_loads_in_or_tools_and_its_optimum_is_the_qubo_minimum(form: str, build) -> None:  # type: ignore[no-untyped-def]
    from ortools.linear_solver.python import model_builder as mb

    s = build(2, 3, [((0, 0), (1, 2))])
    m = paper_bqm(s) if form == "paper" else per_robot_bqm(s)
    n = m.num_variables
    rows = ((np.arange(1 << n)[:, None] >> np.arange(n)) & 1).astype(np.uint8)
    brute = float(m.energy(rows).min())
    loaded = mb.Model()
    assert loaded.import_from_mps_string(export_text(m, "mps"))
    assert loaded.num_variables == n + m.num_interactions
    solver = mb.Solver("CP_SAT")
    assert solver.solve(loaded) == mb.SolveStatus.OPTIMAL
    assert solver.objective_value == pytest.approx(brute)
    if form == "per-robot":  # on this grid no path-plus-cycle beats the path: the MIP optimum is the optimum
        assert brute == pytest.approx(dfs(s).cost.total)
        x = np.array([round(solver.value(loaded.var_from_index(i))) for i in range(n)])
        assert m.energy(best_auxiliaries(m, x[: m.num_edge_variables])) == pytest.approx(brute)


def test_lp_text_names_and_sections() -> None:
    m = per_robot_bqm(default_scenario(2, 2, 1), penalty=3.0)
    text = export_text(m, "lp")
    for section in ("Minimize", "Subject to", "Binaries", "End"):
        assert section in text
    for lab in m.labels:
        assert mip_name(lab) in text
        assert ":" not in mip_name(lab) and "-" not in mip_name(lab) and "," not in mip_name(lab)


def test_unknown_format_is_refused() -> None:
    with pytest.raises(ValueError, match="unknown export format"):
        export_text(paper_bqm(default_scenario(2, 2, 1)), "csv")
    assert "bqm" in EXPORT_FORMATS and "mps" in EXPORT_FORMATS
