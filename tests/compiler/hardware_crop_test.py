"""Long strips on their square medial grid: routed on the part around the layout, and the same result as on the
whole device (:func:`qcpp.pipeline.device_compile._cropped`, :func:`qcpp.pipeline.device_compile._greedy_compare`)."""

from __future__ import annotations

from dataclasses import replace

import pytest

from qcpp.pipeline.device_compile import compile_for_device
from qcpp.problem.presets import default_scenario
from qcpp.routing.options import DEFAULT_ROUTING


@pytest.mark.parametrize(
    "shape", [(2, 12, 1), pytest.param((2, 20, 1), marks=pytest.mark.heavy)], ids=["2x12/1", "2x20/1"]
)
def test_the_crop_routes_a_strip_as_the_whole_device_does(shape: tuple[int, int, int]) -> None:
    s = default_scenario(*shape)
    side = 2 * shape[1] - 1
    crop = replace(DEFAULT_ROUTING, crop_min_qubits=0)  # 2x12/1's grid:23x23 is small enough to route whole
    seen: list[str] = []
    cropped = compile_for_device(s, 1, "grid", layout_method="medial", lowered=True, stage=seen.append, routing=crop)
    assert any(f"grid:9x{side}" in text for text in seen)  # the crop: 3 rows of homes and 6 to spare
    seen.clear()
    whole = compile_for_device(s, 1, "grid", layout_method="medial", lowered=True, stage=seen.append,
                               routing=replace(DEFAULT_ROUTING, crop_min_qubits=side * side))  # fmt: skip
    assert not any(f"grid:9x{side}" in text for text in seen)  # no crop
    assert cropped.routed.device.name == whole.routed.device.name == f"grid:{side}x{side}"
    assert list(cropped.routed.circuit.gates) == list(whole.routed.circuit.gates)
    assert cropped.routed.initial_layout == whole.routed.initial_layout
    assert cropped.routed.final_layout == whole.routed.final_layout
    assert cropped.routed.swaps == whole.routed.swaps and cropped.routed.fused == whole.routed.fused


def test_the_greedy_comparison_on_a_sub_grid_is_a_routing_of_the_device() -> None:
    sub_grid = replace(DEFAULT_ROUTING, greedy_compare_max_qubits=0)
    r = compile_for_device(default_scenario(2, 2, 1), 1, "grid", lowered=True, routing=sub_grid)  # greedy wins
    assert r.layout_method == "greedy" and r.routed.device.name == "grid:3x3"
    couplings = set(r.routed.device.coupling)
    assert all(tuple(sorted(g[1])) in couplings for g in r.routed.circuit.gates if len(g[1]) == 2)
    assert len(set(r.routed.initial_layout)) == len(r.routed.initial_layout) == r.compiled.circuit.num_qubits
    assert max(r.routed.initial_layout) < r.routed.device.num_qubits
