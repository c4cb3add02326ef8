"""``qcpp.simulate_noisy``: the routed circuit ``qcpp.compile`` wrote for a named device, simulated by qiskit-aer
without noise, holds the optimum with the probability the independent subspace simulator gives at the same angles;
with the device's noise it loses some of it, more with idle relaxation than without; bad calls raise one line."""

from __future__ import annotations

import importlib.util

import pytest

import qcpp
from tests.api.bad_input_test import error_of

needs_aer = pytest.mark.skipif(importlib.util.find_spec("qiskit_aer") is None, reason="qiskit-aer (extra 'noise')")

S = qcpp.grid_scenario(2, 3, robots=1)
ANGLES = {"gamma_0": 0.37, "beta_0": 0.81}


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
