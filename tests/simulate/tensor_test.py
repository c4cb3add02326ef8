"""Tests of simulate.tensor (quimb) and simulate.validate: the one test module that uses quimb.

numba compiles quimb's kernels once per process (about 20 s), so everything quimb-related lives here behind the
module-scoped ``tn`` fixture, which also holds one shared cotengra path optimizer (cache under the repo's
gitignored ``.cache/``). References are independent: the dense statevector simulator (Qiskit's bit order), the
sparse simulator and the feasible-subspace simulator.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from circuitgen.angles import Angle, UnboundParameterError
from circuitgen.circuit import Circuit, Section
from circuitgen.compile import compile_scenario
from circuitgen.gates import (
    Gate,
    ccx,
    cry,
    crz,
    csbf,
    cx,
    cz,
    h,
    mcx,
    rx,
    ry,
    rz,
    rzz,
    s,
    sbf,
    sdg,
    t,
    tdg,
    x,
)
from gridcover.paths import assignment_bits, enumerate_paths
from gridcover.presets import default_scenario
from simulate.statevector import simulate_statevector
from simulate.subspace import SubspaceQAOA
from simulate.validate import ValidationReport, random_angles, validate

pytestmark = pytest.mark.filterwarnings("ignore:Couldn't import `kahypar`")

CACHE = Path(__file__).resolve().parents[2] / ".cache" / "cotengra-tests"


@pytest.fixture(scope="module")
def tn() -> SimpleNamespace:
    """The tensor module with numba's kernels compiled and one shared path optimizer."""
    from simulate import tensor

    opt = tensor.path_optimizer(CACHE)
    warm = Circuit([("q", 2)], [Section("s", [h(0), cx(0, 1)])])
    tensor.TensorCircuit(warm, optimizer=opt).amplitude(0)
    return SimpleNamespace(mod=tensor, opt=opt)


def _prep(n: int, rng: np.random.Generator) -> list[Gate]:
    """A random product state, so that every gate acts on a generic input."""
    gates: list[Gate] = []
    for q in range(n):
        gates += [ry(float(rng.uniform(0.3, 2.8)), q), rz(float(rng.uniform(-3, 3)), q)]
    return gates


GATE_CASES = {
    "x": [x(2)],
    "h": [h(1)],
    "t": [t(0)],
    "tdg": [tdg(3)],
    "s": [s(4)],
    "sdg": [sdg(2)],
    "rz": [rz(0.7, 1)],
    "rx": [rx(-1.1, 3)],
    "ry": [ry(0.4, 0)],
    "cx": [cx(3, 1)],
    "cz": [cz(4, 0)],
    "crz": [crz(0.9, 4, 1)],
    "cry": [cry(-0.6, 1, 3)],
    "rzz": [rzz(1.3, 3, 0)],
    "ccx": [ccx(4, 1, 2)],
    "mcx3_positive": [mcx([4, 0, 2], 1)],
    "mcx3_mixed": [mcx([4, 0, 2], 1, "101")],
    "mcx9_mixed": [mcx([9, 0, 7, 2, 5, 1, 8, 3], 4, "10110101")],  # 9 qubits > RAW_MCX_MAX_QUBITS: X-conjugated
    "sbf": [sbf(0.8, 3, 0, 4, 1)],
    "csbf": [csbf(-1.2, 2, 4, 0, 3, 1)],
}


@pytest.mark.parametrize("name", sorted(GATE_CASES))
def test_every_gate_matches_the_dense_simulator(tn: SimpleNamespace, name: str) -> None:
    """Each gate (qubits in non-ascending order) on a random product state: quimb's dense state == ours."""
    gates = GATE_CASES[name]
    n = 1 + max(q for g in gates for q in g.qubits)
    n = max(n, 5)
    rng = np.random.default_rng(len(name))
    c = Circuit([("q", n)], [Section("prep", _prep(n, rng)), Section("gate", gates)])
    want = simulate_statevector(c)
    got = np.asarray(tn.mod.to_quimb(c).to_dense(reverse=True)).reshape(-1)
    assert np.abs(got - want).max() < 1e-10
    # the exact-contraction amplitudes and the MPS (ancilla-like qubit order shuffled) agree too
    idx = list(rng.choice(1 << n, size=6, replace=False))
    amps = tn.mod.TensorCircuit(c, optimizer=tn.opt).amplitudes(idx)
    assert np.abs(amps - want[idx]).max() < 1e-10
    layout = list(rng.permutation(n))
    mps = tn.mod.MPSCircuit(c, layout=layout)
    assert np.abs(mps.amplitudes(idx) - want[idx]).max() < 1e-10


def test_initial_basis_state_and_bit_orders(tn: SimpleNamespace) -> None:
    rng = np.random.default_rng(7)
    gates = [*_prep(4, rng), cx(0, 3), ccx(3, 1, 2), mcx([2, 0, 1], 3, "011"), rzz(0.4, 1, 2)]
    gates = gates[8:]  # no product-state prep: start from a basis state instead
    c = Circuit([("q", 4)], [Section("s", [h(1), *gates])])
    start = 0b1001  # q0 = 1, q3 = 1
    want = simulate_statevector(c, initial=start)
    tc = tn.mod.TensorCircuit(c, psi0_bits=start, optimizer=tn.opt)
    for k in range(16):
        as_str = "".join(str((k >> i) & 1) for i in range(4))  # character i = qubit i
        assert abs(tc.amplitude(k) - want[k]) < 1e-12
        assert abs(tc.amplitude(as_str) - want[k]) < 1e-12
    assert tn.mod.TensorCircuit(c, psi0_bits="1001", optimizer=tn.opt).amplitude(0b1011) == pytest.approx(
        want[0b1011], abs=1e-12
    )
    m = tn.mod.MPSCircuit(c, psi0_bits=[1, 0, 0, 1], layout=[3, 1, 0, 2])
    assert np.abs(m.amplitudes(range(16)) - want).max() < 1e-12


def test_state_bits_rejects_bad_input(tn: SimpleNamespace) -> None:
    assert tn.mod.state_bits(5, 3) == (1, 0, 1)
    with pytest.raises(ValueError, match="out of range"):
        tn.mod.state_bits(8, 3)
    with pytest.raises(ValueError, match="3 bits, expected 4"):
        tn.mod.state_bits("010", 4)
    with pytest.raises(ValueError, match="0 or 1"):
        tn.mod.state_bits([0, 2, 1], 3)


def test_unbound_symbols_raise(tn: SimpleNamespace) -> None:
    c = Circuit([("q", 2)], [Section("s", [rzz(Angle.symbol("gamma_0"), 0, 1)])])
    with pytest.raises(UnboundParameterError):
        tn.mod.to_quimb(c)
    assert abs(tn.mod.amplitudes(c, [0], bindings={"gamma_0": 0.5}, optimizer=tn.opt)[0] - np.exp(-0.25j)) < 1e-12


def test_probabilities_and_marginal_match_dense(tn: SimpleNamespace) -> None:
    rng = np.random.default_rng(11)
    n = 6
    gates = [*_prep(n, rng), cx(0, 4), ccx(4, 2, 5), crz(0.7, 5, 1), sbf(0.9, 0, 1, 2, 3), cry(1.1, 3, 0)]
    c = Circuit([("q", n)], [Section("s", gates)])
    p = np.abs(simulate_statevector(c)) ** 2
    bits = (np.arange(1 << n)[:, None] >> np.arange(n)) & 1
    tc = tn.mod.TensorCircuit(c, optimizer=tn.opt)
    mps = tn.mod.MPSCircuit(c, layout=[5, 0, 3, 1, 4, 2])
    fixed = {4: 0, 1: 1, 2: 0}
    want = p[(bits[:, 4] == 0) & (bits[:, 1] == 1) & (bits[:, 2] == 0)].sum()
    assert tc.probability(fixed) == pytest.approx(want, abs=1e-12)
    assert mps.probability(fixed) == pytest.approx(want, abs=1e-12)
    assert tc.zero_probability([3, 5]) == pytest.approx(p[(bits[:, 3] == 0) & (bits[:, 5] == 0)].sum(), abs=1e-12)
    marg = tc.marginal([5, 2])
    for b5 in (0, 1):
        for b2 in (0, 1):
            assert marg[b5, b2] == pytest.approx(p[(bits[:, 5] == b5) & (bits[:, 2] == b2)].sum(), abs=1e-12)
    info = tc.rehearse_probability(fixed)
    assert info.width >= 0 and info.num_tensors >= 1


def test_too_wide_contractions_are_refused(tn: SimpleNamespace) -> None:
    rng = np.random.default_rng(3)
    n = 6
    gates = [h(q) for q in range(n)] + [cx(q, (q + 1) % n) for q in range(n)] + _prep(n, rng)
    c = Circuit([("q", n)], [Section("s", gates + [cx(q, (q + 3) % n) for q in range(n)] + _prep(n, rng))])
    tc = tn.mod.TensorCircuit(c, optimizer=tn.opt, max_width=-1)  # every real contraction is too wide
    assert tc.rehearse_amplitude(0).num_tensors > 1
    with pytest.raises(tn.mod.ContractionTooWideError, match="exceeds max_width -1"):
        tc.amplitude(0)


def test_samples_lie_in_the_support_and_repeat_with_the_seed(tn: SimpleNamespace) -> None:
    c = Circuit([("q", 4)], [Section("s", [h(0), cx(0, 2), ry(1.0, 3), mcx([0, 3], 1, "10")])])
    p = np.abs(simulate_statevector(c)) ** 2
    tc = tn.mod.TensorCircuit(c, optimizer=tn.opt)
    a = tc.sample(40, seed=5)
    assert a.shape == (40, 4)
    index = a @ (1 << np.arange(4))
    assert np.all(p[index] > 1e-9)
    assert np.array_equal(a, tc.sample(40, seed=5))
    assert len(set(index.tolist())) > 1


# ------------------------------------------------------------------------------------------------ compiled QAOA


def _bindings(angles: np.ndarray) -> dict[str, float]:
    p = len(angles) // 2
    return {f"gamma_{k}": float(angles[2 * k]) for k in range(p)} | {
        f"beta_{k}": float(angles[2 * k + 1]) for k in range(p)
    }


@pytest.mark.slow
def test_quimb_amplitudes_equal_the_dense_state_on_the_compiled_3x3_circuit(tn: SimpleNamespace) -> None:
    """All 2^18 dense amplitudes of the lowered one-robot 3x3 circuit (p=1) vs a sample of quimb's amplitudes."""
    sc = default_scenario(3, 3, 1)
    angles = random_angles(1, seed=21)
    circuit = compile_scenario(sc, 1, lowered=True, bindings=_bindings(angles)).circuit
    assert circuit.num_qubits == 18
    dense = simulate_statevector(circuit)
    rng = np.random.default_rng(21)
    support = np.flatnonzero(np.abs(dense) > 1e-9)
    idx = [*support.tolist(), *rng.choice(1 << 18, size=12, replace=False).tolist()]  # non-zero and random ones
    tc = tn.mod.TensorCircuit(circuit, optimizer=tn.opt)
    got = tc.amplitudes(idx)
    assert np.abs(got - dense[idx]).max() < 1e-10
    assert np.abs(tn.mod.MPSCircuit(circuit).amplitudes(idx) - dense[idx]).max() < 1e-10
    # the dense state lives on feasible paths with clean ancillas, as the subspace simulator says
    ref = SubspaceQAOA(sc).state(angles)
    for k, mask in enumerate(enumerate_paths(sc, 0)):
        i = int(sum(int(b) << q for q, b in enumerate(assignment_bits(sc, [mask]))))
        assert abs(dense[i] - ref[SubspaceQAOA(sc).index_of([mask])]) < 1e-10, k
    assert np.sum(np.abs(dense[: 1 << sc.num_variables]) ** 2) == pytest.approx(1.0, abs=1e-10)


def _check(report: ValidationReport, name: str, method: str):  # type: ignore[no-untyped-def]
    (found,) = [c for c in report.checks if c.name == name and c.method == method]
    return found


VALIDATIONS = [
    # (rows, cols, robots, p, max_amplitudes, exact-contraction count expected, MPS)
    pytest.param(3, 3, 1, 1, None, 12, id="1robot-3x3-p1"),
    pytest.param(3, 3, 1, 2, None, 12, id="1robot-3x3-p2"),
    pytest.param(3, 3, 2, 1, None, 144, id="2robots-3x3-p1"),
    pytest.param(3, 4, 2, 1, 24, 24, id="2robots-3x4-p1-sample"),
]


@pytest.mark.slow
@pytest.mark.parametrize(("rows", "cols", "robots", "p", "max_amps", "n_exact"), VALIDATIONS)
def test_validate_tensor_backend(
    tn: SimpleNamespace, rows: int, cols: int, robots: int, p: int, max_amps: int | None, n_exact: int
) -> None:
    """Lowered QAOA circuit from |0...0>, seeded random angles:

    * MPS: P(every logic/work ancilla is 0) = 1 to 1e-8, and every feasible assignment's amplitude (all of them,
      12 / 144 / 1444) equals the subspace simulator's to 1e-8;
    * exact contraction: the amplitudes of every feasible assignment (3x3), or of a seeded sample of 24 of the
      1444 (3x4), equal the subspace simulator's to 1e-8.
    """
    sc = default_scenario(rows, cols, robots)
    report = validate(sc, p, backend="tensor", seed=5, max_amplitudes=max_amps, cache_dir=CACHE)
    total = math.prod(len(enumerate_paths(sc, r)) for r in range(robots))
    assert report.feasible_assignments == total
    assert report.qubits == compile_scenario(sc, p, lowered=True).circuit.num_qubits
    anc = _check(report, "ancilla_probability", "tensor MPS")
    assert anc.status == "pass" and anc.error <= 1e-8
    mps = _check(report, "amplitudes", "tensor MPS")
    assert mps.status == "pass" and mps.count == total and mps.value <= 1e-8
    exact = _check(report, "amplitudes", "tensor contraction")
    assert exact.status == "pass" and exact.count == n_exact and exact.value <= 1e-8
    assert report.passed
    assert report.angles == tuple(random_angles(p, 5))


@pytest.mark.slow
def test_validate_two_robots_3x3_p2_with_the_mps(tn: SimpleNamespace) -> None:
    """p=2 on 30 qubits: the MPS checks every amplitude and the ancillas; the exact contraction is too wide here
    (width 21-27 without kahypar) and is not asked for."""
    sc = default_scenario(3, 3, 2)
    report = validate(sc, 2, backend="tensor", seed=2, max_amplitudes=0, cache_dir=CACHE)
    assert _check(report, "ancilla_probability", "tensor MPS").error <= 1e-8
    assert _check(report, "amplitudes", "tensor MPS").count == 144
    assert _check(report, "amplitudes", "tensor contraction").status == "skipped"
    assert report.passed and report.max_amplitude_error <= 1e-8


@pytest.mark.slow
def test_a_broken_circuit_fails_the_checks(tn: SimpleNamespace) -> None:
    """Dropping one T gate of the lowered mixer leaves a dirty ancilla or wrong amplitudes: the comparison bites."""
    sc = default_scenario(3, 3, 1)
    angles = random_angles(1, seed=8)
    circuit = compile_scenario(sc, 1, lowered=True, bindings=_bindings(angles)).circuit
    sections = list(circuit.sections)
    k = next(i for i, sec in enumerate(sections) if sec.name == "mixer_0")
    gates = list(sections[k].gates)
    gates.pop(next(i for i, g in enumerate(gates) if g.name == "t"))
    sections[k] = Section("mixer_0", gates)
    broken = Circuit(circuit.registers, sections)
    m = tn.mod.MPSCircuit(broken)
    ancillas = range(sc.num_variables, broken.num_qubits)
    q = SubspaceQAOA(sc)
    ref = q.state(angles)
    idx = [q.data_index((mask,)) for mask in q.bases[0]]
    amp_err = float(np.max(np.abs(tn.mod.TensorCircuit(broken, optimizer=tn.opt).amplitudes(idx) - ref.reshape(-1))))
    assert abs(1 - m.zero_probability(ancillas)) > 1e-6 or amp_err > 1e-6


# ------------------------------------------------------------------------------------------------ other backends


def test_validate_statevector_and_sparse_agree_with_the_subspace() -> None:
    sc = default_scenario(3, 3, 1)
    for backend in ("statevector", "sparse"):
        r = validate(sc, 1, backend=backend, seed=4)  # type: ignore[arg-type]
        assert r.passed, r
        assert r.amplitudes_checked == 12 and r.max_amplitude_error <= 1e-8
        assert abs(1 - r.ancilla_probability) <= 1e-8
        d = json.loads(json.dumps(r.to_dict()))
        assert d["passed"] is True and d["backend"] == backend and len(d["checks"]) == 2


def test_validate_sparse_two_robots_p2() -> None:
    r = validate(default_scenario(3, 3, 2), 2, backend="sparse", seed=9)
    assert r.passed and r.amplitudes_checked == 144


def test_validate_reports_wrong_angles_as_failure() -> None:
    """Angles are bound into the circuit; a reference at other angles must disagree (the check can fail)."""
    sc = default_scenario(3, 3, 1)
    good = validate(sc, 1, backend="sparse", angles=[0.4, 1.3])
    assert good.passed and good.seed is None
    q = SubspaceQAOA(sc)
    assert np.abs(q.state([0.4, 1.3]) - q.state([0.4, 1.31])).max() > 1e-4


def test_validate_rejects_bad_input() -> None:
    sc = default_scenario(3, 3, 1)
    with pytest.raises(ValueError, match="unknown backend"):
        validate(sc, 1, backend="gpu")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="positive integer"):
        validate(sc, 0)
    with pytest.raises(ValueError, match="expected 2 finite angles"):
        validate(sc, 1, backend="sparse", angles=[0.1])
    with pytest.raises(ValueError, match="unknown SBF rule"):
        validate(sc, 1, rule="fuzzy")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="exceed 26"):
        validate(default_scenario(3, 4, 2), 1, backend="statevector")


# ------------------------------------------------------------------------------------------------ qcpp validate


@pytest.fixture
def scenario_file(tmp_path: Path) -> Path:
    from gridcover.scenario import save_scenario

    path = tmp_path / "one_robot_3x3.toml"
    save_scenario(default_scenario(3, 3, 1), path)
    return path


def test_cli_validate_prints_the_checks_and_exits_0(scenario_file: Path) -> None:
    from typer.testing import CliRunner

    from qcpp.cli import app

    res = CliRunner().invoke(app, ["validate", str(scenario_file), "-p", "1", "--backend", "sparse", "--seed", "3"])
    assert res.exit_code == 0, res.output
    assert "ancilla_probability" in res.stdout and "amplitudes" in res.stdout and "PASSED" in res.stdout
    res = CliRunner().invoke(app, ["validate", str(scenario_file), "-p", "1", "--backend", "statevector", "--json"])
    assert res.exit_code == 0
    d = json.loads(res.stdout)
    assert d["passed"] is True and d["amplitudes_checked"] == 12 and d["max_amplitude_error"] <= 1e-8
    assert abs(1 - d["ancilla_probability"]) <= 1e-8 and d["seconds"] >= 0


def test_cli_validate_exit_codes_for_failures_and_bad_input(
    scenario_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from typer.testing import CliRunner

    import simulate.validate as sv
    from qcpp.cli import app

    res = CliRunner().invoke(app, ["validate", str(scenario_file), "--backend", "gpu"])
    assert res.exit_code == 2 and res.stderr.startswith("error: --backend")
    real = sv.validate

    def failing(*args, **kwargs):  # type: ignore[no-untyped-def]
        r = real(*args, **kwargs)
        bad = sv.Check("amplitudes", "injected", 0.5, 0.5, 12, "fail", 0.0, "a wrong amplitude")
        return sv.ValidationReport(**{**r.__dict__, "checks": (*r.checks, bad)})

    monkeypatch.setattr(sv, "validate", failing)
    res = CliRunner().invoke(app, ["validate", str(scenario_file), "--backend", "sparse"])
    assert res.exit_code == 1 and "FAILED" in res.stdout
    res = CliRunner().invoke(app, ["validate", str(scenario_file), "--backend", "sparse", "--json"])
    assert res.exit_code == 1 and json.loads(res.stdout)["passed"] is False
