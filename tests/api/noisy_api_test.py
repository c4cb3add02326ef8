"""``qcpp.simulate_noisy``: the routed circuit ``qcpp.compile`` wrote for a named device, simulated by qiskit-aer
without noise, holds the optimum with the probability the independent subspace simulator gives at the same angles,
exactly on every method; with the device's noise it loses some of it, more with idle relaxation than without; a
run predicted to take hours is refused in one line, a small one runs and reports its progress; bad calls raise one
line."""

from __future__ import annotations

import importlib.util

import pytest

import qcpp
from tests.api.bad_input_test import error_of

needs_aer = pytest.mark.skipif(importlib.util.find_spec("qiskit_aer") is None, reason="qiskit-aer (extra 'noise')")

S = qcpp.grid_scenario(2, 3, robots=1)
ANGLES = {"gamma_0": 0.37, "beta_0": 0.81}

pytestmark = pytest.mark.xdist_group("noisy_api")  # one worker compiles the module's circuit (tests/conftest.py)


@pytest.fixture(scope="module")
def compiled() -> qcpp.Compiled:
    return qcpp.compile(S, device="ibm_fez", bind=ANGLES)


@needs_aer
def test_without_noise_the_routed_circuit_holds_the_subspace_simulator_s_p_optimum(compiled: qcpp.Compiled) -> None:
    ideal = qcpp.simulate_qaoa(S, 1, angles=[ANGLES["gamma_0"], ANGLES["beta_0"]], method="subspace").p_optimum
    assert 0.05 < ideal < 0.95  # the angles make a state the check can tell apart from a basis state
    r = qcpp.simulate_noisy(compiled, noise=False)
    assert r.method == "density_matrix" and r.shots == 0 and r.stderr == 0.0 and r.qubits <= 10
    assert r.p_optimum == pytest.approx(ideal, abs=1e-9)


@needs_aer
@pytest.mark.parametrize("method", ["statevector", "matrix_product_state"])
def test_without_noise_every_method_gives_the_exact_p_optimum(compiled: qcpp.Compiled, method: str) -> None:
    ideal = qcpp.simulate_qaoa(S, 1, angles=[ANGLES["gamma_0"], ANGLES["beta_0"]], method="subspace").p_optimum
    r = qcpp.simulate_noisy(compiled, noise=False, method=method, shots=20)
    assert r.method == method and r.shots == 0 and r.stderr == 0.0 and not r.noise
    assert r.p_optimum == pytest.approx(ideal, abs=1e-9)


@needs_aer
def test_a_run_predicted_to_take_hours_is_refused_and_a_small_one_runs_with_progress(
    compiled: qcpp.Compiled,
) -> None:
    huge = error_of(lambda: qcpp.simulate_noisy(compiled, method="statevector", shots=10**9), qcpp.SizeError)
    assert huge.startswith("compiled: 1,000,000,000 noisy trajectories of ")
    assert "predicted to run for" in huge and "qcpp.allow_large()" in huge
    calls: list[tuple[int, int]] = []
    exact = qcpp.simulate_noisy(compiled).p_optimum  # density matrix: exact, no progress
    sampled = qcpp.simulate_noisy(compiled, method="statevector", shots=150, progress=lambda *a: calls.append(a))
    assert calls == [(100, 150), (150, 150)]  # runs of SHOT_BATCH shots
    assert sampled.shots == 150 and sampled.method == "statevector" and sampled.stderr > 0
    assert abs(sampled.p_optimum - exact) < 4 * sampled.stderr
    again = qcpp.simulate_noisy(compiled, method="statevector", shots=150)
    assert again == sampled  # the same seeds with or without progress


@needs_aer
def test_progress_true_writes_the_shot_runs_on_stderr(
    compiled: qcpp.Compiled, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """``progress=True``, as on every long API call (:mod:`qcpp.api.progress`): the command line's lines."""
    monkeypatch.setenv("QCPP_PROGRESS_INTERVAL", "0")
    qcpp.simulate_noisy(compiled, method="statevector", shots=150, progress=True)
    out, err = capsys.readouterr()
    lines = err.splitlines()
    assert out == "" and lines[0].startswith("simulate_noisy on ibm_fez: 0 / 150 shots"), err
    assert any(line.startswith("simulate_noisy on ibm_fez: 100 / 150 shots") for line in lines), err
    assert lines[-1].startswith("simulate_noisy on ibm_fez: 150 shots done in"), err


def test_the_guard_refuses_what_would_not_fit_in_memory(monkeypatch: pytest.MonkeyPatch) -> None:
    from qcpp.problem.limits import MEMORY_ENV

    bound = qcpp.compile(qcpp.grid_scenario(2, 2, robots=1), device="quantinuum_helios",
                         bind={"gamma_0": 0.1, "beta_0": 0.2})  # fmt: skip
    monkeypatch.setenv(MEMORY_ENV, "1M")
    message = error_of(lambda: qcpp.simulate_noisy(bound), qcpp.SizeError)
    assert "density matrix" in message and "GB of memory" in message and "qcpp.allow_large()" in message


@needs_aer
def test_the_device_s_noise_costs_probability_and_idling_costs_more(compiled: qcpp.Compiled) -> None:
    ideal = qcpp.simulate_noisy(compiled, noise=False).p_optimum
    gates_only = qcpp.simulate_noisy(compiled, idle=False).p_optimum
    with_idle = qcpp.simulate_noisy(compiled).p_optimum
    assert 0.0 < with_idle < gates_only < ideal
    # the idle-aware ESP counts every idle decay as a lost shot: below the simulated figure
    assert compiled.esp_idle is not None and compiled.esp is not None and compiled.esp_idle < compiled.esp
    assert compiled.esp_idle * ideal < with_idle


def test_bad_calls_name_what_is_wrong() -> None:
    s = qcpp.grid_scenario(2, 2, robots=1)
    assert error_of(lambda: qcpp.simulate_noisy(qcpp.compile(s)), qcpp.OptionError).startswith("compiled: no device")
    lowered = qcpp.compile(s, device="quantinuum_helios", lowered=True, bind={"gamma_0": 0.1, "beta_0": 0.2})
    assert "lowered" in error_of(lambda: qcpp.simulate_noisy(lowered), qcpp.OptionError)
    unbound = qcpp.compile(s, device="quantinuum_helios", bind={"gamma_0": 0.1})
    assert "beta_0" in error_of(lambda: qcpp.simulate_noisy(unbound), qcpp.UnboundParameterError)
    bound = qcpp.compile(s, device="quantinuum_helios", bind={"gamma_0": 0.1, "beta_0": 0.2})
    assert error_of(lambda: qcpp.simulate_noisy(bound, shots=0), qcpp.OptionError).startswith("shots:")
    assert error_of(lambda: qcpp.simulate_noisy(bound, method="mps"), qcpp.OptionError).startswith("method:")
    assert error_of(lambda: qcpp.simulate_noisy(s), qcpp.OptionError).startswith("compiled:")  # type: ignore[arg-type]
    assert qcpp.compile(s).esp is None and qcpp.compile(s).esp_idle is None
