"""Long strips on their square medial grid: routed on the part around the layout, and the same result as on the
whole device (:func:`qcpp.pipeline.device_compile._cropped`, :func:`qcpp.pipeline.device_compile._greedy_compare`)."""

from __future__ import annotations

import pytest

from qcpp.pipeline import device_compile as hardware
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.problem.presets import default_scenario


@pytest.mark.parametrize(
    "shape", [(2, 12, 1), pytest.param((2, 20, 1), marks=pytest.mark.heavy)], ids=["2x12/1", "2x20/1"]
)
def test_the_crop_routes_a_strip_as_the_whole_device_does(
    monkeypatch: pytest.MonkeyPatch, shape: tuple[int, int, int]
) -> None:
    s = default_scenario(*shape)
    monkeypatch.setattr(hardware, "CROP_MIN_QUBITS", 0)  # 2x12/1's grid:23x23 is small enough to route whole
    seen: list[str] = []
    cropped = compile_for_device(s, 1, "grid", layout_method="medial", lowered=True, stage=seen.append)
    side = 2 * shape[1] - 1
    assert any(f"grid:9x{side}" in text for text in seen)  # the crop: 3 rows of homes and 6 to spare
    monkeypatch.setattr(hardware, "_cropped", lambda dev, homes: None)
    whole = compile_for_device(s, 1, "grid", layout_method="medial", lowered=True)
    assert cropped.routed.device.name == whole.routed.device.name == f"grid:{side}x{side}"
    assert list(cropped.routed.circuit.gates) == list(whole.routed.circuit.gates)
    assert cropped.routed.initial_layout == whole.routed.initial_layout
    assert cropped.routed.final_layout == whole.routed.final_layout
    assert cropped.routed.swaps == whole.routed.swaps and cropped.routed.fused == whole.routed.fused


def test_the_greedy_comparison_on_a_sub_grid_is_a_routing_of_the_device(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(hardware, "GREEDY_COMPARE_MAX_QUBITS", 0)
    r = compile_for_device(default_scenario(2, 2, 1), 1, "grid", lowered=True)  # greedy wins on 2x2/1
    assert r.layout_method == "greedy" and r.routed.device.name == "grid:3x3"
    couplings = set(r.routed.device.coupling)
    assert all(tuple(sorted(g[1])) in couplings for g in r.routed.circuit.gates if len(g[1]) == 2)
    assert len(set(r.routed.initial_layout)) == len(r.routed.initial_layout) == r.compiled.circuit.num_qubits
    assert max(r.routed.initial_layout) < r.routed.device.num_qubits
