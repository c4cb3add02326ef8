"""Noisy simulation of routed circuits (qiskit-aer): zero noise is the ideal circuit, a known depolarising and
read-out error give the analytic P(optimum), the shots run in batches that count what one run of every shot
counts, and the size guard's prediction grows with the qubits and shots."""

from __future__ import annotations

import importlib.util
import math
import sys

import pytest

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate
from qcpp.routing.routed_circuit import RoutedCircuit
from qcpp.simulate.noisy import (
    SHOT_BATCH,
    NoisyBackendMissing,
    active_qubits,
    device_noise_model,
    noisy_circuit,
    noisy_need,
    require_aer,
    simulate_noisy,
)

needs_aer = pytest.mark.skipif(importlib.util.find_spec("qiskit_aer") is None, reason="qiskit-aer (extra 'noise')")

E_X = (0.01, 0.03, 0.02)
E_CZ = (0.05, 0.04)
READOUT = (0.02, 0.07, 0.05)


def _device(with_noise: bool = True) -> Device:
    k = 1.0 if with_noise else 0.0
    return Device(
        name="test3", num_qubits=4, coupling=((0, 1), (1, 2), (2, 3)), native_gates=("cz", "rz", "sx", "x"),
        two_qubit_gate="cz",
        error_1q=(("rz", (0.0,) * 4), ("sx", (k * 0.001,) * 4), ("x", tuple(k * e for e in (*E_X, 0.5)))),
        error_2q=tuple(k * e for e in (*E_CZ, 0.5)), readout_error=tuple(k * e for e in (*READOUT, 0.5)),
        duration_1q_s=None, duration_2q_s=None, readout_duration_s=None, source="test", date="-", family="grid",
    )  # fmt: skip


def _routed(device: Device) -> RoutedCircuit:
    """x on qubits 0, 1, 2, then cz(0, 1), cz(1, 2): the data register reads 111 (qubit 3 is never touched)."""
    gates = [Gate("x", (q,), (), None) for q in range(3)]
    gates += [Gate("cz", (0, 1), (), None), Gate("cz", (1, 2), (), None)]
    circuit = Circuit([("q", 4)], [Section("s", gates)])
    return RoutedCircuit(circuit, device, (0, 1, 2, 3), (0, 1, 2, 3), 0, (0, 1, 2))


def _analytic_p111() -> float:
    """Each x leaves its qubit in 1 with probability 1 - e (depolarising of average infidelity e: lambda = 2e);
    each cz is a two-qubit depolarising of lambda = 4e/3 (the pair uniform with probability lambda); then
    independent read-out flips."""
    import itertools

    probs = {}
    for bits in itertools.product((0, 1), repeat=3):
        probs[bits] = math.prod(1 - e if b else e for b, e in zip(bits, E_X))
    for (a, b), e in zip(((0, 1), (1, 2)), E_CZ):
        lam = 4 * e / 3
        new = dict.fromkeys(probs, 0.0)
        for bits, p in probs.items():
            new[bits] += (1 - lam) * p
            for x, y in itertools.product((0, 1), repeat=2):
                moved = list(bits)
                moved[a], moved[b] = x, y
                new[tuple(moved)] += lam * p / 4
        probs = new
    return sum(p * math.prod(1 - r if b else r for b, r in zip(bits, READOUT)) for bits, p in probs.items())


@needs_aer
def test_zero_noise_equals_the_ideal_circuit() -> None:
    routed = _routed(_device(with_noise=False))
    assert active_qubits(routed) == (0, 1, 2)
    for noise in (False, True):
        r = simulate_noisy(routed, [0b111], noise=noise)
        assert r.method == "density_matrix" and r.qubits == 3
        assert r.p_optimum == pytest.approx(1.0, abs=1e-9)
    assert simulate_noisy(routed, [0b011], noise=True).p_optimum == pytest.approx(0.0, abs=1e-9)


@needs_aer
def test_depolarising_and_readout_errors_give_the_analytic_value() -> None:
    routed = _routed(_device())
    expected = _analytic_p111()
    esp = math.prod(1 - e for e in (*E_X, *E_CZ, *READOUT))
    assert abs(expected - esp) > 1e-3  # the check separates the simulation from the ESP product
    exact = simulate_noisy(routed, [0b111])
    assert exact.p_optimum == pytest.approx(expected, abs=1e-9)
    sampled = simulate_noisy(routed, [0b111], method="matrix_product_state", shots=2000, seed=3)
    assert abs(sampled.p_optimum - expected) < 4 * sampled.stderr + 1e-3


@needs_aer
def test_noise_model_covers_only_the_active_qubits() -> None:
    model = device_noise_model(_device(), (0, 1, 2))
    assert sorted(model.noise_qubits) == [0, 1, 2]
    assert {"x", "cz", "measure"} <= set(model.noise_instructions)


def test_missing_aer_is_one_line_naming_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "qiskit_aer", None)  # import fails as if not installed
    with pytest.raises(NoisyBackendMissing, match=r"qcpp\[noise\]") as info:
        require_aer()
    assert "\n" not in str(info.value)
    with pytest.raises(NoisyBackendMissing):
        simulate_noisy(_routed(_device()), [0b111])


@needs_aer
def test_shots_in_batches_count_what_one_run_of_every_shot_counts() -> None:
    from qiskit_aer import AerSimulator

    routed = _routed(_device())
    qubits = active_qubits(routed)
    shots = 2 * SHOT_BATCH + 37
    one = AerSimulator(method="statevector", noise_model=device_noise_model(routed.device, qubits), seed_simulator=5)
    counts = one.run(noisy_circuit(routed, qubits), shots=shots).result().get_counts()
    calls: list[tuple[int, int]] = []
    r = simulate_noisy(routed, [0b111], method="statevector", shots=shots, seed=5, progress=lambda *a: calls.append(a))
    assert r.p_optimum * shots == counts.get("111", 0)
    assert calls == [(SHOT_BATCH, shots), (2 * SHOT_BATCH, shots), (shots, shots)]


def test_the_prediction_grows_with_qubits_and_shots_and_exact_runs_need_no_shots() -> None:
    small = noisy_need(_routed(_device()), shots=1000)
    assert "density matrix" in small.what and small.seconds is not None and small.seconds < 60
    wide = _wide(22)
    few, many = noisy_need(wide, shots=10), noisy_need(wide, shots=10_000)
    assert few.seconds is not None and many.seconds is not None and many.seconds > 100 * few.seconds
    assert noisy_need(wide, shots=10_000, noise=False) == noisy_need(wide, shots=1, noise=False)
    assert noisy_need(_wide(26), shots=10, method="statevector").bytes > noisy_need(wide, shots=10).bytes
    assert "matrix product state" in noisy_need(_wide(26), shots=10).what


def _wide(n: int) -> RoutedCircuit:
    """An x on each of ``n`` qubits of a line device (abstract: no errors needed for a prediction)."""
    from qcpp.hardware.device import get_device

    circuit = Circuit([("q", n)], [Section("s", [Gate("x", (q,), (), None) for q in range(n)])])
    return RoutedCircuit(circuit, get_device(f"grid:{n}x1"), tuple(range(n)), tuple(range(n)), 0, tuple(range(n)))
