"""The ESP with idle decoherence, the calibrated Qiskit target and the choice among routed candidates."""

from __future__ import annotations

import math

import pytest

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import cz, rx, rz
from qcpp.routing.native import esp, esp_idle, idle_fidelity, idle_times_s
from qcpp.routing.routed_circuit import RoutedCircuit

US = 1e-6


def toy_device(t1: tuple[float | None, ...] | None = (100 * US, 200 * US, None),
               t2: tuple[float | None, ...] | None = (50 * US, 500 * US, 100 * US)) -> Device:  # fmt: skip
    """Three qubits on a line, every figure chosen by hand."""
    return Device(
        name="toy", num_qubits=3, coupling=((0, 1), (1, 2)), native_gates=("cz", "rz", "sx", "x"),
        two_qubit_gate="cz",
        error_1q=(("rz", (0.0,) * 3), ("sx", (0.001, 0.002, 0.003)), ("x", (0.001, 0.002, 0.003))),
        error_2q=(0.01, 0.02), readout_error=(0.05, 0.0, 0.1),
        duration_1q_s=(("rz", (0.0,) * 3), ("sx", (1 * US,) * 3), ("x", (1 * US,) * 3)),
        duration_2q_s=(2 * US, 3 * US), readout_duration_s=(1 * US,) * 3,
        source="by hand", date="-", family="grid", t1_s=t1, t2_s=t2,
    )  # fmt: skip


def toy_routed(device: Device) -> RoutedCircuit:
    # q0: sx [0, 1], cz01 [1, 3], then waits for the readout at 6: idle 3 us
    # q1: cz01 [1, 3], cz12 [3, 6]: never idle;  q2: sx [0, 1], rz (virtual), cz12 [3, 6]: idle 2 us (T1 unknown)
    gates = [rx(math.pi / 2, 0), rx(math.pi / 2, 2), rz(0.3, 2), cz(0, 1), cz(1, 2)]
    circuit = Circuit([Register("q", 3)], [Section("s", gates)])
    return RoutedCircuit(circuit, device, (0, 1, 2), (0, 1, 2), 0, (0, 2))


def test_idle_times_follow_the_asap_schedule_by_hand() -> None:
    t = idle_times_s(toy_routed(toy_device()))
    assert t is not None
    assert [round(x / US, 9) for x in t] == [3.0, 0.0, 2.0]


def test_esp_with_idle_decoherence_is_the_hand_computed_product() -> None:
    routed = toy_routed(toy_device())
    gates = (1 - 0.001) * (1 - 0.003) * (1 - 0.01) * (1 - 0.02) * (1 - 0.05) * (1 - 0.1)
    assert esp(routed) == pytest.approx(gates, rel=1e-12)
    idle_q0 = (3 + math.exp(-3 / 100) + 2 * math.exp(-3 / 50)) / 6  # q2 idles too, but its T1 is unknown
    assert esp_idle(routed) == pytest.approx(gates * idle_q0, rel=1e-12)


def test_t2_is_capped_at_twice_t1_and_no_coherence_data_means_no_idle_figure() -> None:
    assert idle_fidelity(5 * US, 100 * US, 1000 * US) == idle_fidelity(5 * US, 100 * US, 200 * US)
    assert idle_fidelity(5 * US, 100 * US, 150 * US) < idle_fidelity(5 * US, 100 * US, 200 * US) < 1
    assert esp_idle(toy_routed(toy_device(t1=None, t2=None))) is None
