"""Tensor-network validation of compiled, lowered QAOA circuits at 18-40 qubits (quimb + cotengra).

Everything that uses quimb lives in this one module: numba compiles quimb's kernels once per process.
Each case compiles the lowered circuit, runs it from |0...0> at seeded random angles and checks, with two
independent tensor methods (an MPS of the whole circuit, and exact contraction with a reused cotengra path),
that the ancillas end in |0> (probability 1 to 1e-8) and that feasible assignments' amplitudes equal the exact
feasible-subspace simulator's (1e-8).

The 18-40 qubit checks are ``heavy`` (CI runs them in a second step); the CLI check stays in the default run.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from gridcover.presets import default_scenario
from gridcover.scenario import load_scenario
from qcpp.cli import app
from simulate.validate import validate

EXAMPLE = Path(__file__).parents[2] / "examples" / "paper_3x3.toml"


@pytest.mark.heavy  # 30 s to 2 min each on 2 cores: CI's second step
@pytest.mark.parametrize(
    ("rows", "cols", "robots", "p", "max_amplitudes"),
    [
        (3, 3, 1, 1, None),  # 18 qubits: every feasible amplitude
        (3, 3, 2, 1, 16),  # 30 qubits
        (3, 4, 2, 1, 6),  # 40 qubits: the MPS checks all 1,444 amplitudes, contraction a seeded sample
    ],
)
def test_compiled_circuit_matches_subspace_simulator(
    rows: int, cols: int, robots: int, p: int, max_amplitudes: int | None
) -> None:
    report = validate(default_scenario(rows, cols, robots), p, backend="tensor", seed=7, max_amplitudes=max_amplitudes)
    assert report.passed, report.to_dict()
    assert abs(report.ancilla_probability - 1) < 1e-8
    assert report.max_amplitude_error < 1e-8
    mps = [c for c in report.checks if c.method == "tensor MPS"]
    assert mps and all(c.status == "pass" for c in mps)
    assert report.amplitudes_checked == report.feasible_assignments


@pytest.mark.heavy
def test_tensor_agrees_with_dense_statevector_on_the_paper_example() -> None:
    s = load_scenario(EXAMPLE)
    dense = validate(s, 2, backend="statevector", seed=3)
    tensor = validate(s, 2, backend="tensor", seed=3)
    assert dense.passed and tensor.passed
    assert dense.angles == tensor.angles


def test_validate_cli_json_and_exit_codes() -> None:
    res = CliRunner().invoke(app, ["validate", str(EXAMPLE), "-p", "1", "--backend", "tensor", "--json"])
    assert res.exit_code == 0, res.stderr
    d = json.loads(res.stdout)
    assert d["passed"] is True and d["backend"] == "tensor" and d["amplitudes_checked"] == d["feasible_assignments"]
    bad = CliRunner().invoke(app, ["validate", str(EXAMPLE), "-p", "1", "--angles", "0.1"])
    assert bad.exit_code == 2 and "--angles" in bad.stderr and len(bad.stderr.strip().splitlines()) == 1
