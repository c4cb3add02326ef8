"""The routed-window memo up to the heavy-hex lattice's translations, and the cells' plan-choice memos, change no
answer (:class:`qcpp.routing.patches.Lattice`, :func:`qcpp.routing.windows.route_window`,
:func:`qcpp.pipeline.cellmixer.cell_mixers`).

Evidence: a window routed after its translation was memoised gives the ops, patches and whole-component count of
the same window routed from a cold memo, on random windows and translations of a heavy-hex lattice (interior and
boundary), and the translated entry is used where the lattice around both is the same; a heavy-hex compile with
every memo of this speed-up gives the circuit, routing and plan choices of the compile without them (a
``RoutingContext(reuse=False)``; 2x3/1 on the cells in the default run; 4x4/2 and 5x5/3 on heavy-hex and on a grid
in the heavy run).
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.hardware.device import distances, get_device, heavy_hex_coordinates
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.problem.presets import default_scenario
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING
from qcpp.routing.patches import PARALLEL_MIN_TRIALS
from qcpp.routing.windows import Positions, route_window

DEVICE = get_device("heavy-hex:13")
DIST = distances(DEVICE)
COORDS = heavy_hex_coordinates(13)
AT = {c: i for i, c in enumerate(COORDS)}


def _routed(
    pairs: list[tuple[int, int]], context: RoutingContext, commuting: bool = False
) -> tuple[list, set[int], int]:
    """The window of physical ``pairs`` routed from home: its ops, the patches it saw, its whole-component parts."""
    with context.watching() as watch:
        pos = Positions.identity(DEVICE.num_qubits)
        ops = route_window(pairs, pos, DEVICE, DIST, 0, DEFAULT_ROUTING, context, commuting)
    return ops, watch.qubits, watch.whole_component


@st.composite
def translated_windows(draw: st.DrawFn) -> tuple[list[tuple[int, int]], list[tuple[int, int]], bool]:
    """A window (a compute and its mirror, qubits near one another, with or without a commuting middle between
    them: pairs of equal pairs, :func:`qcpp.routing.commuting.commuting_blocks`), the same window moved by a
    multiple of four in both coordinates, and whether it has the middle."""
    centre = draw(st.integers(0, DEVICE.num_qubits - 1))
    near = [q for q in range(DEVICE.num_qubits) if DIST[centre, q] <= draw(st.integers(1, 4))]
    n = min(len(near), draw(st.integers(2, 6)))
    qubits = draw(st.permutations(near))[:n]
    k = draw(st.integers(1, 10))
    pairs = [tuple(draw(st.permutations(qubits))[:2]) for _ in range(k)]
    commuting = draw(st.booleans())
    blocks = [tuple(draw(st.permutations(qubits))[:2]) for _ in range(draw(st.integers(1, 12)) if commuting else 0)]
    pairs += [pr for pr in blocks for _ in range(2)] + pairs[::-1]
    dy, dx = draw(st.sampled_from([(dy, dx) for dy in (-8, -4, 0, 4, 8) for dx in (-8, -4, 0, 4, 8) if dy or dx]))
    moved = {q: AT.get((COORDS[q][0] + dy, COORDS[q][1] + dx)) for q in qubits}
    if any(m is None for m in moved.values()):
        dy = dx = 0  # off the lattice: the window itself
        moved = {q: q for q in qubits}
    return pairs, [(moved[a], moved[b]) for a, b in pairs], commuting  # type: ignore[misc]


@settings(max_examples=40, deadline=None)
@given(translated_windows())
def test_a_window_routed_after_its_translation_routes_as_from_a_cold_memo(
    windows: tuple[list[tuple[int, int]], list[tuple[int, int]], bool],
) -> None:
    pairs, moved, commuting = windows
    cold = _routed(moved, RoutingContext(), commuting)
    warm = RoutingContext()
    _routed(pairs, warm, commuting)
    assert _routed(moved, warm, commuting) == cold


def test_an_interior_window_is_answered_by_its_translation() -> None:
    """The translated entry is used: the second window costs no routing (the memo does not grow)."""
    base = AT[(10, 8)]
    pairs = [(base, AT[(10, 12)]), (AT[(10, 12)], AT[(12, 10)]), (AT[(10, 12)], base)]
    moved = [tuple(AT[(COORDS[q][0] + 4, COORDS[q][1] + 4)] for q in pr) for pr in pairs]
    context = RoutingContext()
    first = _routed(pairs, context)  # type: ignore[arg-type]
    size = len(context.windows)
    second = _routed(moved, context)  # type: ignore[arg-type]
    assert len(context.windows) == size
    shift = {q: AT[(COORDS[q][0] + 4, COORDS[q][1] + 4)] for q in first[1]}
    assert second[0] == [(name, (shift[a], shift[b])) for name, (a, b) in first[0]]
    assert second[1] == set(shift.values()) and second[2] == first[2] == 0


def test_options_that_differ_only_in_their_searches_share_routed_windows() -> None:
    """A window's routing depends on :attr:`~qcpp.routing.options.RoutingOptions.window_key` only, so a search with
    other allocation settings finds the windows routed before (the memo does not grow), and settings a routing
    reads do not share them."""
    from dataclasses import replace

    from qcpp.routing.windows import route_window_cx

    pairs = [(AT[(10, 8)], AT[(10, 12)]), (AT[(10, 12)], AT[(12, 10)]), (AT[(10, 12)], AT[(10, 8)])]
    context = RoutingContext()
    first = route_window_cx(pairs, None, DEVICE, DIST, 0, DEFAULT_ROUTING, context)  # type: ignore[arg-type]
    size = len(context.windows)
    other = replace(DEFAULT_ROUTING, search_ranks=1, allocation_search=False, cell_screen=0)
    assert route_window_cx(pairs, None, DEVICE, DIST, 0, other, context) == first  # type: ignore[arg-type]
    assert len(context.windows) == size
    route_window_cx(pairs, None, DEVICE, DIST, 0, replace(DEFAULT_ROUTING, trials=4), context)  # type: ignore[arg-type]
    assert len(context.windows) > size


@settings(max_examples=10, deadline=None)
@given(st.data())
def test_sabre_keeps_the_same_trial_on_threads(data: st.DataObject) -> None:
    """Qiskit's SABRE routes alike with its trials on threads or one after another (what
    :data:`~qcpp.routing.patches.PARALLEL_MIN_TRIALS` relies on)."""
    from qiskit._accelerate.sabre import sabre_routing

    from qcpp.routing.patches import patch_sabre

    dev = get_device("heavy-hex:3")
    size = dev.num_qubits
    shape = patch_sabre(RoutingContext(), tuple(dev.coupling), size)  # type: ignore[arg-type]
    assert shape.call is not None
    target, heuristic, layout = shape.call
    pairs = [tuple(data.draw(st.permutations(range(size)))[:2]) for _ in range(data.draw(st.integers(1, 60)))]
    dag = shape.empty.copy_empty_like()
    for a, b in pairs:
        dag.apply_operation_back(shape.gate, (shape.bits[a], shape.bits[b]), (), check=False)
    seed = data.draw(st.integers(0, 99))

    def ops(parallel: bool) -> list:
        out, _ = sabre_routing(dag, target, heuristic, layout, PARALLEL_MIN_TRIALS, seed, parallel)
        return [(n.name, [q._index for q in n.qargs]) for n in out.topological_op_nodes()]

    assert ops(True) == ops(False)


def _compiled(shape: tuple[int, int, int], device: str, memos: bool) -> tuple:
    """The routed circuit, layouts and partial-mixer sections of a compile, with or without the memos that answer
    one query from another's (windows up to the lattice's translations, the A* of equal relabelled programs)."""
    context = RoutingContext(reuse=memos)
    result = compile_for_device(default_scenario(*shape), 1, device, lowered=True, layout_method="medial",
                                context=context)  # fmt: skip
    if memos and device == "heavy-hex":  # windows kept up to translation, one A* shared by equal programs
        assert any(key[2] == "translated" for key in context.windows if key[0] == "window")
        assert len(context.plans) < sum(24 for _ in context.relabelled)
    if not memos:
        assert not context.plans and all(index.lattice is None for index in context.patch_indexes)
    routed = result.routed
    return ([(g[0], g[1]) for g in routed.circuit.gates], routed.initial_layout, routed.swaps, routed.fused,
            [(s.name, [(g[0], g[1]) for g in s.gates]) for s in result.logical.sections])  # fmt: skip


@pytest.mark.parametrize(
    ("shape", "device"),
    [
        ((2, 3, 1), "heavy-hex"),
        pytest.param((4, 4, 2), "heavy-hex", marks=pytest.mark.heavy),
        pytest.param((4, 4, 3), "heavy-hex", marks=pytest.mark.heavy),
        pytest.param((4, 4, 2), "grid", marks=pytest.mark.heavy),
        pytest.param((5, 5, 3), "grid", marks=pytest.mark.heavy),
    ],
    ids=["2x3/1-heavy-hex", "4x4/2-heavy-hex", "4x4/3-heavy-hex", "4x4/2-grid", "5x5/3-grid"],
)
def test_the_memos_change_no_choice(shape: tuple[int, int, int], device: str) -> None:
    """The allocation search, the cells' plan choice and the routing pick what they pick without the memos.

    Three robots on heavy-hex run on 4x4, not 5x5: the memos answer translated windows and share one A* there too
    (:func:`_compiled` asserts both) in under half the CPU time; 5x5 with three robots is kept on the grid."""
    assert _compiled(shape, device, True) == _compiled(shape, device, False)


@settings(max_examples=20, deadline=None)
@given(st.data())
def test_a_patch_routing_reads_sabre_as_the_pass_writes_it(data: st.DataObject) -> None:
    """sabre_local's events (read off SABRE's routed DAG) are the SWAPs and gates of the SabreSwap pass's circuit,
    in its order."""
    from qiskit import QuantumCircuit
    from qiskit.transpiler import PassManager
    from qiskit.transpiler.passes import SabreSwap

    from qcpp.routing.patches import sabre_local
    from qcpp.routing.routed_circuit import coupling_map

    dev = get_device(data.draw(st.sampled_from(["grid:3x3", "heavy-hex:3"])))
    size = dev.num_qubits
    pairs = tuple(tuple(data.draw(st.permutations(range(size)))[:2]) for _ in range(data.draw(st.integers(1, 25))))
    seed, trials = data.draw(st.integers(0, 9)), data.draw(st.sampled_from([1, 4, 16, PARALLEL_MIN_TRIALS]))
    qc = QuantumCircuit(size)
    for a, b in pairs:
        qc.cx(a, b)
    reference = PassManager([SabreSwap(coupling_map(dev), heuristic="decay", seed=seed, trials=trials)]).run(qc)
    events = sabre_local(RoutingContext(), tuple(dev.coupling), size, pairs, seed, trials)  # type: ignore[arg-type]
    where = list(range(size))  # position -> the qubit that started there
    replayed = []
    for kind, what in events:
        if kind == "swap":
            x, y = what
            where[x], where[y] = where[y], where[x]
            replayed.append(("swap", [x, y]))
        else:
            a, b = pairs[what]
            replayed.append(("cx", [where.index(a), where.index(b)]))
    assert replayed == [(i.operation.name, [reference.find_bit(q).index for q in i.qubits]) for i in reference.data]
