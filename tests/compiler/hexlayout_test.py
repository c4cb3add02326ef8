"""The heavy-hex cell layout: coordinates, placement geometry, and routed circuits equal to the compiled ones.

Evidence: the coordinates rebuild Qiskit's heavy-hex coupling map exactly; every plaquette's four edges lie on
one 12-qubit heavy-hex cell, data only on its vertices, at least six qubits free (random scenarios); the lattice
picked is the smallest that holds the layout; compiles with the layout put every two-qubit gate on a coupling,
return every qubit home and equal the unrouted circuit, the logical one and the compiled one whose partial mixers
use the default plans (statevector on the used qubits: 2x3/1, and 2x2/2 in the heavy run;
QCEC on 2x3/2, and on 3x3/1 and a 3x4 obstacle scenario in the heavy run); ``auto`` keeps the cheaper of this layout
and the greedy routing; ``estimate --device heavy-hex`` reports what compile writes.
"""

from __future__ import annotations

import doctest
import importlib

import pytest
from hypothesis import given, settings

from qcpp.hardware.device import get_device, heavy_hex_coordinates, heavy_hex_coupling, heavy_hex_distance
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate
from qcpp.layout.heavy_hex import hex_distance, hex_placement
from qcpp.pipeline.device_compile import compile_for_device, hex_device, layout_device
from qcpp.plan.compile import compile_scenario
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.routing.routed_circuit import RoutedCircuit

from .conftest import scenarios
from .medial_test import BIND, OBSTACLE_INTERIOR
from .routing_test import _assert_equal_up_to_layouts, _on_coupling


def test_doctests() -> None:
    for name in ("qcpp.layout.heavy_hex", "qcpp.hardware.device"):
        result = doctest.testmod(importlib.import_module(name))
        assert result.failed == 0 and result.attempted > 0


@pytest.mark.parametrize("d", [3, 5, 7, 9, 11])
def test_coordinates_rebuild_qiskits_heavy_hex_coupling(d: int) -> None:
    xy = heavy_hex_coordinates(d)
    n, coupling = heavy_hex_coupling(d)
    assert len(xy) == n == len(set(xy))
    at = {p: q for q, p in enumerate(xy)}
    edges = set()
    for (y, x), q in at.items():
        if y % 2 == 0 and (y, x + 1) in at:  # along a row line
            edges.add((q, at[(y, x + 1)]))
        if y % 2 == 1:  # a bridge joins the row lines above and below
            edges |= {(at[(y - 1, x)], q), (q, at[(y + 1, x)])}
    assert {tuple(sorted(e)) for e in edges} == set(coupling)
    assert heavy_hex_distance(get_device(f"heavy-hex:{d}")) == d


def test_named_heavy_hex_devices_and_other_families_get_no_placement() -> None:
    s = default_scenario(2, 2, 1)
    assert heavy_hex_distance(get_device("ibm_torino")) is None  # heavy-hex, but IBM's own qubit numbering
    assert hex_placement(s, get_device("ibm_torino")) is None
    assert hex_placement(s, get_device("grid:9x9")) is None
    assert hex_device(s, "ibm_fez") is None and hex_device(s, "grid") is None


def _cell_of(sites: list[tuple[int, int]], at: dict[tuple[int, int], int]) -> list[tuple[int, int]] | None:
    """The 12-qubit heavy-hex cell (two row-line segments of five and their two bridges) holding ``sites``."""
    top = min(y for y, _ in sites)
    top -= top % 2
    for y0 in (top, top - 2):
        for x0 in range(min(x for _, x in sites) - 4, min(x for _, x in sites) + 1):
            box = [(y, x) for y in (y0, y0 + 1, y0 + 2) for x in range(x0, x0 + 5) if (y, x) in at]
            bridges = [(y, x) for y, x in box if y == y0 + 1]
            if len(box) == 12 and bridges == [(y0 + 1, x0), (y0 + 1, x0 + 4)] and set(sites) <= set(box):
                return box
    return None


@settings(max_examples=30, deadline=None)
@given(scenarios(max_side=5, max_robots=3))
def test_every_plaquette_lies_on_one_cell_with_room_for_its_ancillas(s: Scenario) -> None:
    d = hex_distance(s)
    dev = get_device(f"heavy-hex:{d}")
    homes = hex_placement(s, dev)
    assert homes is not None and len(set(homes)) == len(homes)
    assert d == 3 or hex_placement(s, get_device(f"heavy-hex:{d - 2}")) is None  # the smallest that holds it
    xy = heavy_hex_coordinates(d)
    at = {p: q for q, p in enumerate(xy)}
    taken = {xy[q] for q in homes}
    for robot in range(s.num_robots):
        for plaquette in s.grid.plaquettes:
            sites = [xy[homes[s.variable_index(robot, e)]] for e in plaquette.edges if e in s.variable_edges]
            if len(sites) < 2:
                continue
            cell = _cell_of(sites, at)
            assert cell is not None, (robot, plaquette.corners)
            # data only on the cell's six vertices (row-line qubits in its bridges' columns and midway): both
            # bridges and the four row-line midpoints stay free for the partial mixer's ancillas
            x0 = min(x for _, x in cell)
            assert all(y % 2 == 0 and (x - x0) % 2 == 0 for y, x in set(cell) & taken)
            if len(sites) == 4:
                assert len(set(cell) - taken) >= 6


# --- routed circuits ---------------------------------------------------------------------------------------
def _compact(routed: RoutedCircuit) -> RoutedCircuit:
    """The routed circuit on just the physical qubits it touches (the rest stay |0> and idle)."""
    used = sorted({q for g in routed.circuit.gates for q in g[1]} | set(routed.initial_layout))
    index = {p: i for i, p in enumerate(used)}
    sections = [Section(sec.name, [Gate(g[0], tuple(index[q] for q in g[1]), g[2], g[3]) for g in sec.gates])
                for sec in routed.circuit.sections]  # fmt: skip
    return RoutedCircuit(Circuit([("q", len(used))], sections), get_device(f"all-to-all:{len(used)}"),
                         tuple(index[p] for p in routed.initial_layout), tuple(index[p] for p in routed.final_layout),
                         routed.swaps, routed.measured)  # fmt: skip


@pytest.mark.parametrize(
    "s",
    [default_scenario(2, 3, 1), pytest.param(default_scenario(2, 2, 2), marks=pytest.mark.heavy)],  # 22 qubits: 6 s
    ids=["2x3/1", "2x2/2"],
)
def test_cell_layout_routes_home_and_equals_the_unrouted_circuit(s: Scenario) -> None:
    r = compile_for_device(s, 1, "heavy-hex", bindings=BIND, lowered=True, layout_method="medial")
    assert r.layout_method == "medial" and r.routed.device == hex_device(s, "heavy-hex")
    routed = r.routed
    assert routed.initial_layout == routed.final_layout
    assert _on_coupling(routed)
    assert routed.circuit.count_ops()["cx"] == r.logical.count_ops()["cx"] + 3 * routed.swaps - 2 * routed.num_fused
    _assert_equal_up_to_layouts(r.logical, _compact(routed), seed=5, global_phase=False)
    # the compiled circuit too, whose partial mixers use the default plans (the cells' differ, qcpp.pipeline.cellmixer):
    # its ancillas are other qubits than the logical circuit's, but |0> at both ends, like every unused qubit
    assert r.compiled.circuit.num_qubits <= r.logical.num_qubits and r.compiled.circuit != r.logical
    _assert_equal_up_to_layouts(r.compiled.circuit, _compact(routed), seed=6, global_phase=False)


@pytest.mark.parametrize(
    "s",
    [
        pytest.param(default_scenario(3, 3, 1), marks=pytest.mark.heavy),
        default_scenario(2, 3, 2),  # two robots: visit terms relayed between the stacked patches, balance adders
        pytest.param(scenario_from_dict(OBSTACLE_INTERIOR), marks=pytest.mark.heavy),
    ],
    ids=["3x3/1", "2x3/2", "3x4 obstacle interior"],
)
def test_qcec_proves_cell_layout_routing_equal_to_the_compiled_circuit(s: Scenario) -> None:
    from qcpp.simulate.equivalence import check_equivalence

    from .routing_qcec_test import aligned

    r = compile_for_device(s, 1, "heavy-hex", lowered=True, bindings=BIND, layout_method="medial")
    assert r.layout_method == "medial" and _on_coupling(r.routed)
    n = r.logical.num_qubits
    b = aligned(r.routed, n)
    a = Circuit([("data", n), ("free", b.num_qubits - n)], [Section("logical", list(r.logical.gates))])
    assert check_equivalence(a, b, num_plain=s.num_variables).criterion == "equivalent"


def _twoq(r: RoutedCircuit) -> int:
    return sum(1 for g in r.circuit.gates if len(g[1]) == 2)


@pytest.mark.parametrize("shape", [(2, 2, 1), (2, 2, 2)])
def test_auto_keeps_the_cheaper_of_cells_and_greedy(shape: tuple[int, int, int]) -> None:
    s = default_scenario(*shape)
    cells = compile_for_device(s, 1, "heavy-hex", lowered=True, bindings=BIND, layout_method="medial")
    n = cells.logical.num_qubits
    smallest = get_device("heavy-hex", min_qubits=compile_scenario(s, 1, lowered=True).circuit.num_qubits)
    greedy = compile_for_device(s, 1, smallest, lowered=True, bindings=BIND, layout_method="greedy")
    auto = compile_for_device(s, 1, "heavy-hex", lowered=True, bindings=BIND)
    assert _twoq(auto.routed) == min(_twoq(cells.routed), _twoq(greedy.routed))
    assert auto.layout_method == ("medial" if _twoq(cells.routed) <= _twoq(greedy.routed) else "greedy")
    assert n >= s.num_variables


@pytest.mark.heavy  # the default run has tests/cli/device_cli_test.py's estimate == compile on heavy-hex (3x3/1)
@pytest.mark.parametrize("shape", [(3, 3, 1), (3, 3, 2), (4, 4, 2)])
def test_estimate_device_heavy_hex_equals_compile(shape: tuple[int, int, int]) -> None:
    from qcpp.estimators.estimate import DEFAULT_PLAN
    from qcpp.estimators.routed import routed_fields

    s = default_scenario(*shape)
    fused = compile_scenario(s, 1, lowered=True).circuit
    f = routed_fields(s, 1, DEFAULT_PLAN, "heavy-hex", fused.num_qubits, fused.count_ops()["cx"], 0)
    r = compile_for_device(s, 1, "heavy-hex")
    assert f["routed_kind"] == "exact" and f["device"] == r.routed.device.name
    assert f["routed_twoq"] == r.summary()["routed"]["two_qubit"]
    if r.layout_method == "medial":  # the cell layout (routed home) on the lattice sized for it
        assert f["device"] == layout_device(s, "heavy-hex").name
    else:  # smaller circuits, where the greedy routing on the smallest lattice is cheaper (auto compares)
        assert r.layout_method == "greedy" and f["device"] == get_device("heavy-hex", min_qubits=r.logical_qubits).name
    assert shape != (4, 4, 2) or r.layout_method == "medial"
