"""The medial layout, local ancilla allocation and home-returning window routing.

Evidence: the placement's geometry is checked on every plaquette (its four edges are device neighbours of one
free site), allocation keeps every section's gates up to renaming its ancillas (statevector), routed windows put
every two-qubit gate on a coupling, return every qubit home, and equal the unrouted circuit (statevector on small
scenarios, QCEC on 3x3/1 and an obstacle scenario with an interior endpoint).
"""

from __future__ import annotations

import doctest
import importlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.hardware.device import get_device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cx, h, rx, ry
from qcpp.layout.medial import allocate_ancillas, allocate_section, grid_shape, medial_placement, medial_shape
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.plan.phase_layout import tiling
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.routing.windows import mirror_length, route_windows

from .conftest import scenarios
from .routing_test import _assert_equal_up_to_layouts, _on_coupling, _permuted, _statevector

BIND = {"gamma_0": 0.37, "beta_0": 0.81}
OBSTACLE_INTERIOR = {
    "grid": {"rows": 3, "cols": 4, "obstacles": [[0, 3]]},
    "robots": [{"start": [1, 1], "goal": [2, 3]}],
    "objective": {"obstacles": "hard"},
}


def test_doctests() -> None:
    result = doctest.testmod(importlib.import_module("qcpp.layout.medial"))
    assert result.failed == 0 and result.attempted > 0


def _unfused(s: Scenario) -> Circuit:
    return compile_scenario(s, 1, PlanOptions(fuse=False), lowered=True, bindings=BIND).circuit


# --- placement ---------------------------------------------------------------------------------------------
def test_grid_shape_recognises_square_lattices_only() -> None:
    assert grid_shape(get_device("grid:3x5")) == (3, 5)
    assert grid_shape(get_device("google_willow")) == (7, 15)
    assert grid_shape(get_device("heavy-hex:3")) is None
    assert grid_shape(get_device("all-to-all:9")) is None


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5, 8])
def test_tiling_holds_every_robot(k: int) -> None:
    down, across = tiling(k, (5, 5))
    assert down * across >= k and (down - 1) * across < k


@settings(max_examples=30, deadline=None)
@given(scenarios(max_side=5, max_robots=3))
def test_every_plaquette_surrounds_a_free_site(s: Scenario) -> None:
    rows, cols = medial_shape(s)
    dev = get_device(f"grid:{rows}x{cols}")
    homes = medial_placement(s, dev)
    assert homes is not None and len(set(homes)) == len(homes)
    nbrs: dict[int, set[int]] = {}
    for a, b in dev.coupling:
        nbrs.setdefault(a, set()).add(b)
        nbrs.setdefault(b, set()).add(a)
    taken = set(homes)
    for robot in range(s.num_robots):
        for plaq in s.grid.plaquettes:
            qs = [homes[s.variable_index(robot, e)] for e in plaq.edges if e in s.variable_edges]
            if not qs:
                continue
            common = set.intersection(*(nbrs[q] for q in qs)) - taken
            assert common, f"robot {robot}, plaquette {plaq.index}: no free site next to all its edges"


def test_too_small_or_irregular_devices_fall_back_to_greedy() -> None:
    s = default_scenario(3, 3, 1)
    assert medial_placement(s, get_device("grid:4x4")) is None
    assert medial_placement(s, get_device("heavy-hex:5")) is None
    r = compile_for_device(s, 1, "grid:4x4", bindings=BIND, lowered=True)
    assert r.layout_method == "greedy" and r.summary()["routed"]["layout"] == "greedy"
    with pytest.raises(ValueError, match="needs a 5x5 grid"):
        compile_for_device(s, 1, "grid:4x4", bindings=BIND, layout_method="medial")


# --- allocation --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("search", [False, True])
def test_allocation_renames_ancillas_only_and_keeps_the_state(search: bool) -> None:
    s = default_scenario(2, 3, 1)
    logical = _unfused(s)
    dev = get_device("grid:3x5")
    homes = medial_placement(s, dev)
    assert homes is not None
    local, layout = allocate_ancillas(logical, homes, dev, search=search)
    assert local.count_ops() == logical.count_ops()
    assert [sec.name for sec in local.sections] == [sec.name for sec in logical.sections]
    assert layout[: s.num_variables] == homes and len(set(layout)) == len(layout)
    n_data = s.num_variables
    for before, after in zip(logical.gates, local.gates, strict=True):
        assert before[0] == after[0] and [q for q in before[1] if q < n_data] == [q for q in after[1] if q < n_data]
    rng = np.random.default_rng(5)
    prefix = [ry(float(rng.uniform(0, 3)), q) for q in range(n_data)]
    big = max(local.num_qubits, logical.num_qubits)
    want = _permuted(_statevector(logical, prefix, logical.num_qubits), logical.num_qubits, big,
                     tuple(range(logical.num_qubits)))  # fmt: skip
    got = _permuted(_statevector(local, prefix, local.num_qubits), local.num_qubits, big,
                    tuple(range(local.num_qubits)))  # fmt: skip
    assert np.allclose(got, want, atol=1e-9)


def test_the_allocation_search_never_routes_a_window_to_more_gates() -> None:
    """The search keeps a section's greedy allocation unless its window routes to fewer two-qubit gates; on
    3x3/1 it finds fewer for some partial mixers."""
    from qcpp.hardware.device import distances
    from qcpp.routing.sabre import window_cx
    from qcpp.routing.windows import Positions, route_window

    s = default_scenario(3, 3, 1)
    dev = get_device("grid:5x5")
    homes = medial_placement(s, dev)
    assert homes is not None
    dist = distances(dev)
    costs = []
    for search in (False, True):
        local, layout = allocate_ancillas(_unfused(s), homes, dev, search=search)
        pos = Positions(layout, dev.num_qubits)
        costs.append([window_cx(route_window([g[1] for g in sec.gates if len(g[1]) == 2], pos, dev, dist))  # type: ignore[misc]
                      for sec in local.sections])  # fmt: skip
    greedy, searched = costs
    assert all(b <= a for a, b in zip(greedy, searched, strict=True))
    assert sum(searched) < sum(greedy)


@pytest.mark.parametrize("device", ["grid:3x5", "heavy-hex:7"])
def test_a_section_alone_gets_the_ancillas_the_whole_allocation_gives_it(device: str) -> None:
    """allocate_section (what the cells' plan choice asks of each candidate) puts every ancilla of a section where
    allocate_ancillas puts it among all the sections, with and without the search."""
    s = default_scenario(2, 3, 1)
    logical = _unfused(s)
    dev = get_device(device)
    homes = medial_placement(s, dev)
    assert homes is not None
    n_data = s.num_variables
    for search in (False, True):
        local, layout = allocate_ancillas(logical, homes, dev, search=search)
        for before, after in zip(logical.sections, local.sections, strict=True):
            alone = allocate_section(before, homes, dev, search=search)
            whole = {q: layout[r] for g, h in zip(before.gates, after.gates, strict=True)
                     for q, r in zip(g[1], h[1], strict=True) if q >= n_data}  # fmt: skip
            assert alone == whole


def test_partial_mixer_ancillas_sit_next_to_their_plaquette() -> None:
    s = default_scenario(4, 4, 1)
    dev = get_device("grid:7x7")
    homes = medial_placement(s, dev)
    assert homes is not None
    local, layout = allocate_ancillas(_unfused(s), homes, dev)
    n_data = s.num_variables
    for sec in local.sections:
        if not sec.name.startswith("mixer"):
            continue
        qs = {q for g in sec.gates for q in g[1]}
        rc = [divmod(layout[q], 7) for q in qs]
        span = max(r for r, _ in rc) - min(r for r, _ in rc), max(c for _, c in rc) - min(c for _, c in rc)
        anc = [q for q in qs if q >= n_data]
        assert anc and max(span) <= 4  # a plaquette, its outer edges and its ancillas: a 5x5 patch at most


# --- routing -----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("pairs", [[], [(0, 1)], [(0, 1), (1, 0)], [(0, 1), (1, 2), (1, 2), (1, 0)]])
def test_mirror_length_examples(pairs: list[tuple[int, int]]) -> None:
    m = mirror_length(pairs)
    assert m <= len(pairs) // 2
    assert all(sorted(pairs[i]) == sorted(pairs[-1 - i]) for i in range(m))
    assert m == len(pairs) // 2 or sorted(pairs[m]) != sorted(pairs[-1 - m])


@pytest.mark.parametrize(
    "s",
    [default_scenario(3, 4, 2),
     scenario_from_dict({"grid": {"rows": 4, "cols": 4, "obstacles": [[1, 2]]}, "objective": {"obstacles": "hard"},
                         "robots": [{"start": [0, 0], "goal": [3, 3]}, {"start": [0, 3], "goal": [3, 0]}]})],
    ids=["3x4/2", "4x4/2-hard-obstacle"],
)  # fmt: skip
def test_the_balance_window_gets_the_large_window_search(s: Scenario) -> None:
    """The balance arithmetic's window (the largest of a two-robot circuit on the medial grid) has a compute of at
    least ``large_window_pairs`` gates also where a hard obstacle or a small grid shrinks it, so it is routed with
    the several seeds and the wider search (``RoutingOptions.large_window_pairs``)."""
    from qcpp.routing.options import DEFAULT_ROUTING

    result = compile_for_device(s, 1, "grid", lowered=True, bindings={"gamma_0": 0.3, "beta_0": 0.7})
    assert result.layout_method == "medial"
    largest = max(result.logical.sections, key=lambda sec: sum(len(g[1]) == 2 for g in sec.gates))
    pairs = [(g[1][0], g[1][1]) for g in largest.gates if len(g[1]) == 2]
    assert mirror_length(pairs) >= DEFAULT_ROUTING.large_window_pairs


@pytest.mark.parametrize(
    ("s", "device"),
    [(default_scenario(2, 3, 1), "grid:3x5"), (default_scenario(2, 2, 2), "grid:3x6")],
    ids=["2x3/1", "2x2/2"],
)
def test_windows_return_home_and_equal_the_unrouted_circuit(s: Scenario, device: str) -> None:
    r = compile_for_device(s, 1, device, bindings=BIND, lowered=True, layout_method="medial")
    assert r.layout_method == "medial"
    routed = r.routed
    assert routed.initial_layout == routed.final_layout
    assert _on_coupling(routed)
    assert routed.circuit.count_ops()["cx"] == r.logical.count_ops()["cx"] + 3 * routed.swaps - 2 * routed.num_fused
    _assert_equal_up_to_layouts(r.logical, routed, seed=4, global_phase=False)


@settings(max_examples=25, deadline=None)
@given(st.data())
def test_random_mirrored_windows_route_home(data: st.DataObject) -> None:
    n = data.draw(st.integers(2, 6))
    pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(lambda p: p[0] != p[1])
    sections = []
    for w in range(data.draw(st.integers(1, 3))):
        compute = data.draw(st.lists(pair, max_size=6))
        middle = data.draw(st.lists(pair, max_size=4))
        gates: list[Gate] = []
        for a, b in compute:
            gates += [h(a), cx(a, b)]
        for a, b in middle:
            gates += [cx(a, b), rx(0.4 + a, b)]
        for a, b in reversed(compute):
            gates += [cx(a, b), h(a)]
        sections.append(Section(f"w{w}", gates))
    logical = Circuit([("data", n)], sections)
    dev = get_device(data.draw(st.sampled_from(["grid:2x4", "grid:3x3", "heavy-hex:3"])))
    layout = data.draw(st.permutations(range(dev.num_qubits)))[:n]
    routed = route_windows(logical, dev, layout, seed=data.draw(st.integers(0, 3)))
    assert _on_coupling(routed) and routed.final_layout == routed.initial_layout
    added = 3 * routed.swaps - 2 * routed.num_fused  # a SWAP fused with a CX on its pair adds 1 CX, not 3
    assert routed.circuit.count_ops().get("cx", 0) == logical.count_ops().get("cx", 0) + added
    _assert_equal_up_to_layouts(logical, routed, seed=0, global_phase=False)


@pytest.mark.slow
@pytest.mark.parametrize(
    "s", [default_scenario(3, 3, 1), scenario_from_dict(OBSTACLE_INTERIOR)], ids=["3x3/1", "3x4 obstacle interior"]
)
def test_qcec_proves_medial_routing_equal_to_the_compiled_circuit(s: Scenario) -> None:
    from qcpp.simulate.equivalence import check_equivalence

    from .routing_qcec_test import aligned

    r = compile_for_device(s, 1, "grid", lowered=True, bindings=BIND, layout_method="medial")
    n = r.logical.num_qubits
    b = aligned(r.routed, n)
    a = Circuit([("data", n), ("free", b.num_qubits - n)], [Section("logical", list(r.logical.gates))])
    assert check_equivalence(a, b, num_plain=s.num_variables).criterion == "equivalent"


# --- the routed cost per kind ------------------------------------------------------------------------------
def test_a_partial_mixer_kinds_routed_cost_is_fixed_in_the_interior() -> None:
    """Windows return home, so a section's routed cost depends only on its gates and its neighbourhood: every
    interior partial mixer of one kind (plaquettes two or more rows and columns from the border) routes to the
    same count, and the routed circuit's count is the sum of its windows' counts."""
    from qcpp.hardware.device import distances
    from qcpp.plan.qaoa import qaoa_plan
    from qcpp.routing.windows import Positions, route_window

    s = default_scenario(8, 8, 1)
    dev = get_device("grid:15x15")
    homes = medial_placement(s, dev)
    assert homes is not None
    local, layout = allocate_ancillas(_unfused(s), homes, dev)
    dist = distances(dev)
    pos = Positions(layout, dev.num_qubits)
    mixers = (g for name, g in qaoa_plan(s, 1, PlanOptions(fuse=False)).sections() if name == "mixer_0")
    by_kind: dict[object, set[int]] = {}
    seen: dict[object, list[tuple[int, int]]] = {}
    total = 0
    for sec in local.sections:
        pairs = [g[1] for g in sec.gates if len(g[1]) == 2]
        ops = route_window(pairs, pos, dev, dist)  # type: ignore[arg-type]
        assert pos.where == list(layout)
        cost = sum(1 if name == "cx" else 3 for name, _ in ops)
        total += cost
        if sec.name.startswith("mixer"):
            m = next(mixers)
            edges = tuple(s.variable_of(q)[1] for q in m.plaquette_qubits)
            (r0, c0) = next(pl.corners[0] for pl in s.grid.plaquettes if pl.edges == edges)
            if 2 <= r0 <= s.grid.rows - 4 and 2 <= c0 <= s.grid.cols - 4:
                by_kind.setdefault(m.kind, set()).add(cost)
                seen.setdefault(m.kind, []).append((r0, c0))
    assert sum(len(v) for v in seen.values()) >= 9 and max(len(v) for v in seen.values()) >= 4
    assert all(len(costs) == 1 for costs in by_kind.values())
    routed = route_windows(local, dev, layout)
    assert routed.circuit.count_ops()["cx"] == total - 2 * routed.num_fused  # SWAPs fused with a CX: 2 CX fewer


def test_estimate_device_grid_equals_compile() -> None:
    from qcpp.estimators.estimate import DEFAULT_PLAN
    from qcpp.estimators.routed import routed_fields

    for s in (default_scenario(3, 3, 1), scenario_from_dict(OBSTACLE_INTERIOR)):
        fused = compile_scenario(s, 1, lowered=True).circuit
        f = routed_fields(s, 1, DEFAULT_PLAN, "grid", fused.num_qubits, fused.count_ops()["cx"], 0)
        r = compile_for_device(s, 1, "grid")
        assert f["routed_kind"] == "exact" and f["device"] == r.routed.device.name
        assert f["routed_twoq"] == r.summary()["routed"]["two_qubit"]


@pytest.mark.parametrize("k", [2, 3, 4])
def test_interleave_puts_an_edges_copies_side_by_side(k: int) -> None:
    s = default_scenario(3, 4, k)
    rows, cols = medial_shape(s, "interleave")
    dev = get_device(f"grid:{rows}x{cols}")
    homes = medial_placement(s, dev, "interleave")
    assert homes is not None and len(set(homes)) == len(homes)
    down, across = tiling(k, (1, 1))
    for e in s.variable_edges:
        rc = [divmod(homes[s.variable_index(r, e)], cols) for r in range(k)]
        assert max(r for r, _ in rc) - min(r for r, _ in rc) < down
        assert max(c for _, c in rc) - min(c for _, c in rc) < across
    s2 = default_scenario(2, 2, 2)
    r = compile_for_device(s2, 1, "grid:6x3", bindings=BIND, lowered=True, arrangement="interleave",
                           layout_method="medial")  # fmt: skip
    assert r.layout_method == "medial" and _on_coupling(r.routed)
    _assert_equal_up_to_layouts(r.logical, r.routed, seed=6, global_phase=False)


@pytest.mark.parametrize("shape", [(2, 2, 1), (2, 3, 1), (3, 3, 1)])
def test_auto_keeps_the_fewer_two_qubit_gates_on_small_circuits(shape: tuple[int, int, int]) -> None:
    s = default_scenario(*shape)
    counts = {}
    for method in ("medial", "greedy", "auto"):
        r = compile_for_device(s, 1, "google_willow", bindings=BIND, lowered=True, layout_method=method)
        counts[method] = r.routed.circuit.count_ops()["cx"]
    assert counts["auto"] == min(counts["medial"], counts["greedy"])
