"""Far phases relayed through clean device qubits (:mod:`qcpp.routing.bridge`).

Evidence: a copy chain's CX network, as a map on basis states, writes the source's value into its holder and
changes nothing else (every holder was |0>); relayed circuits equal the original ones on every input whose
non-data qubits are |0> (statevector, hypothesis-drawn circuits of far ``rzz`` runs between non-diagonal
gates, every rewrite kept); a medial compile that relays equals the compiled circuit (QCEC, two robots).
"""

from __future__ import annotations

import doctest
import importlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.hardware.device import distances, get_device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cx, h, rz
from qcpp.routing.bridge import bridge_far_phases, copy_chain

from .routing_test import _permuted, _statevector


def test_doctests() -> None:
    result = doctest.testmod(importlib.import_module("qcpp.routing.bridge"))
    assert result.failed == 0 and result.attempted > 0


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_a_copy_chain_copies_the_source_and_changes_nothing_else(data: st.DataObject) -> None:
    dev = get_device(data.draw(st.sampled_from(["grid:3x5", "grid:4x4", "grid:2x7", "heavy-hex:3"])))
    dist = distances(dev)
    n = dev.num_qubits
    source, target = data.draw(st.lists(st.integers(0, n - 1), min_size=2, max_size=2, unique=True))
    others = [q for q in range(n) if q not in (source, target)]
    clean = set(data.draw(st.lists(st.sampled_from(others), unique=True)))
    found = copy_chain(source, target, clean, dist)
    if dist[source, target] <= 2:
        assert found is None
    if found is None:
        return
    pairs, holder = found
    assert holder in clean and dist[holder, target] <= 2
    assert all(dist[a, b] == 1 for a, b in pairs)
    state = np.array(data.draw(st.lists(st.integers(0, 1), min_size=n, max_size=n)))
    state[list(clean)] = 0
    before = state.copy()
    for a, b in pairs:
        state[b] ^= state[a]
    assert state[holder] == before[source]
    # qubits the chain passes through are restored; clean qubits it writes hold copies of the source
    assert all(state[q] == before[q] or (q in clean and state[q] == before[source]) for q in range(n))
    # the chain reversed undoes it
    for a, b in reversed(pairs):
        state[b] ^= state[a]
    assert (state == before).all()


@st.composite
def far_phase_circuits(draw: st.DrawFn) -> tuple[Circuit, tuple[int, ...], str]:
    """A few data qubits spread over a small grid, sections of H layers around runs of rzz and rz."""
    device = draw(st.sampled_from(["grid:2x6", "grid:3x4", "grid:1x9"]))
    n_dev = get_device(device).num_qubits
    n = draw(st.integers(2, 4))
    layout = tuple(draw(st.permutations(range(n_dev)))[:n])
    pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(lambda p: p[0] != p[1])
    sections = []
    for k in range(draw(st.integers(1, 2))):
        gates: list[Gate] = [h(q) for q in range(n)]
        for a, b in draw(st.lists(pair, min_size=1, max_size=4)):
            gates += [cx(a, b), rz(0.3 + 0.2 * a + 0.1 * b, b), cx(a, b)]
            if draw(st.booleans()):
                gates.append(rz(0.7, a))
        gates += [h(q) for q in range(n)]
        sections.append(Section(f"phase_{k}", gates))
    return Circuit([("data", n)], sections), layout, device


@settings(max_examples=40, deadline=None)
@given(far_phase_circuits(), st.integers(0, 5))
def test_relayed_circuits_equal_the_original(case: tuple[Circuit, tuple[int, ...], str], seed: int) -> None:
    circuit, layout, device = case
    dev = get_device(device)
    out, new_layout = bridge_far_phases(circuit, layout, dev, only_if_cheaper=False)
    n, big = circuit.num_qubits, dev.num_qubits
    assert new_layout[:n] == layout and len(set(new_layout)) == len(new_layout)
    assert [sec.name for sec in out.sections] == [sec.name for sec in circuit.sections]
    rng = np.random.default_rng(seed)
    prefix = [Gate("ry", (q,), (float(rng.uniform(0, 3)),), None) for q in range(n)]
    want = _permuted(_statevector(circuit, prefix, n), n, big, layout)
    got = _permuted(_statevector(out, prefix, out.num_qubits), out.num_qubits, big, new_layout)
    assert np.allclose(got, want, atol=1e-9)


def test_a_far_phase_on_a_line_is_relayed_and_cheaper() -> None:
    circuit = Circuit([("data", 2)], [Section("phase", [cx(0, 1), rz(0.4, 1), cx(0, 1)])])
    dev = get_device("grid:1x9")
    out, layout = bridge_far_phases(circuit, (0, 8), dev)
    assert out.num_qubits > 2  # relayed: SWAPs 7 steps there and back would cost 2 + 42 CX
    assert all(abs(layout[g[1][0]] - layout[g[1][1]]) == 1 for g in out.gates if len(g[1]) == 2)
    assert out.count_ops()["cx"] == 16
    near, same = bridge_far_phases(circuit, (0, 1), dev)
    assert list(near.gates) == list(circuit.gates) and same == (0, 1)


@pytest.mark.slow
def test_qcec_proves_a_relayed_two_robot_compile_equal_to_the_compiled_circuit() -> None:
    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.problem.presets import default_scenario
    from qcpp.simulate.equivalence import check_equivalence

    from .routing_qcec_test import aligned

    s = default_scenario(2, 3, 2)
    r = compile_for_device(s, 1, "grid", lowered=True, bindings={"gamma_0": 0.37, "beta_0": 0.81},
                           layout_method="medial")
    assert r.layout_method == "medial"
    compiled = r.compiled.circuit
    assert r.logical.count_ops()["cx"] > compiled.count_ops()["cx"]  # some phase was relayed
    b = aligned(r.routed, r.logical.num_qubits)
    a = Circuit([("data", compiled.num_qubits), ("free", b.num_qubits - compiled.num_qubits)],
                [Section("compiled", list(compiled.gates))])  # fmt: skip
    assert check_equivalence(a, b, num_plain=s.num_variables).criterion == "equivalent"
