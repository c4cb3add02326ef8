"""Tests for qcpp.lowering.passes: mcx v-chains, basis rules, peephole, and lower()."""

from __future__ import annotations

import itertools
import random

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.ir import gates as G
from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, CircuitBuilder, Register, Section
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import (
    DEFAULT_BASIS,
    decompose_gate,
    lower,
    lower_mcx,
    lower_to_basis,
    mcx_work_need,
    peephole,
)
from qcpp.simulate.sparse import simulate_sparse
from qcpp.simulate.statevector import circuit_unitary
from qcpp.testing import circuits

VALUES = {"gamma_0": 0.37, "beta_0": -1.3, "gamma_1": 2.1}


def one(*gates: Gate, n: int | None = None, name: str = "s") -> Circuit:
    n = n if n is not None else 1 + max(q for g in gates for q in g.qubits)
    return Circuit([("data", n)], [Section(name, gates)])


def clean_block(lowered: Circuit, n_orig: int) -> np.ndarray:
    """Columns of the lowered unitary with work ancillas |0> (work qubits are the high ones)."""
    u = circuit_unitary(lowered, VALUES)
    d = 2**n_orig
    # everything must stay in the work=0 block
    np.testing.assert_allclose(u[d:, :d], 0, atol=1e-9)
    return u[:d, :d]


# --- mcx -------------------------------------------------------------------------------------
def polarity_patterns(k: int) -> list[str]:
    if k <= 4:
        return ["".join(p) for p in itertools.product("01", repeat=k)]
    rng = random.Random(k)
    return ["1" * k, "0" * k] + ["".join(rng.choice("01") for _ in range(k)) for _ in range(4)]


@pytest.mark.parametrize("k", range(9))
def test_mcx_lowering_exhaustive_on_basis_states(k: int) -> None:
    for state in polarity_patterns(k):
        gate = G.mcx(list(range(k)), k, state)
        low = lower_mcx(one(gate, n=k + 1))
        work = list(low.qubits_of("work")) if low.has_register("work") else []
        assert len(work) == max(0, k - 2)
        names = low.count_ops()
        if k >= 3:
            assert names.get("ccx", 0) == 1
            assert names.get("and", 0) == names.get("and_dg", 0) == k - 2
            assert names.get("x", 0) == 2 * state.count("0")
            assert set(names) <= {"ccx", "x", "and", "and_dg"}
            assert lower_to_basis(low).count_ops()["cx"] == 6 * k - 6
        for inp in range(2 ** (k + 1)):
            out = simulate_sparse(low, inp)
            assert len(out) == 1
            ((key, amp),) = out.items()
            assert amp == 1
            fire = all(((inp >> i) & 1) == int(b) for i, b in enumerate(state))
            assert key == (inp ^ (1 << k) if fire else inp)  # work bits (above k) are 0 again


def test_mcx_work_register_is_shared_and_sized_by_peak() -> None:
    b = CircuitBuilder([("data", 9)])
    b.append([G.mcx([0, 1, 2], 8), G.mcx([0, 1, 2, 3, 4, 5], 8, "010101"), G.mcx([4, 5, 6, 7], 0)], section="m")
    c = b.build()
    assert mcx_work_need(c) == 4
    low = lower_mcx(c)
    assert low.registers[-1] == Register("work", 4)
    assert low.count_ops() == {"ccx": 3, "and": 1 + 4 + 2, "and_dg": 1 + 4 + 2, "x": 6}
    work = set(low.qubits_of("work"))
    used = {q for g in low.gates for q in g.qubits if q in work}
    assert used == work
    for inp in [0, 0b1111_1111, 0b0010_1010, 0b1_0101_0111]:
        ((key, _),) = simulate_sparse(low, inp).items()
        ((ref, _),) = simulate_sparse(c, inp).items()
        assert key == ref


def test_mcx_existing_work_register() -> None:
    gate = G.mcx([0, 1, 2, 3], 4)
    grown = lower_mcx(Circuit([("data", 5), ("work", 1)], [Section("s", [gate])]))
    assert grown.registers == (Register("data", 5), Register("work", 2))
    big_enough = lower_mcx(Circuit([("data", 5), ("work", 3), ("anc", 1)], [Section("s", [gate])]))
    assert big_enough.registers == (Register("data", 5), Register("work", 3), Register("anc", 1))
    with pytest.raises(ValueError, match="cannot grow"):
        lower_mcx(Circuit([("data", 5), ("work", 1), ("anc", 1)], [Section("s", [gate])]))
    with pytest.raises(ValueError, match="work ancilla"):
        lower_mcx(Circuit([("data", 4), ("work", 2)], [Section("s", [G.mcx([0, 1, 2], 4)])]))


def test_lower_mcx_without_mcx_returns_same_circuit() -> None:
    c = one(G.h(0), G.ccx(0, 1, 2))
    assert lower_mcx(c) is c


# --- basis rules -----------------------------------------------------------------------------
def test_ccx_gives_6_cx_and_9_single_qubit_gates() -> None:
    low = lower_to_basis(one(G.ccx(0, 1, 2)))
    ops = low.count_ops()
    assert ops["cx"] == 6
    assert sum(v for k, v in ops.items() if k != "cx") == 9
    assert set(ops) == {"cx", "h", "t", "tdg"}


@pytest.mark.parametrize(
    ("gate", "expected"),
    [
        (G.crz(0.3, 0, 1), {"cx": 2, "rz": 2}),
        (G.rzz(0.3, 0, 1), {"cx": 2, "rz": 1}),
        (G.rx(0.3, 0), {"h": 2, "rz": 1}),
        (G.ry(0.3, 0), {"h": 2, "rz": 1, "s": 1, "sdg": 1}),
        (G.cz(0, 1), {"h": 2, "cx": 1}),
        (G.cry(0.3, 0, 1), {"cx": 2, "h": 4, "rz": 2, "s": 2, "sdg": 2}),
        (G.sbf(0.3, 0, 1, 2, 3), {"h": 8, "cx": 6, "rz": 1}),
        (G.csbf(0.3, 0, 1, 2, 3, 4), {"h": 8, "cx": 8, "rz": 2}),
        (G.crx(0.3, 0, 1), {"h": 2, "cx": 2, "rz": 2}),
        (G.and_(0, 1, 2), {"h": 2, "cx": 3, "t": 2, "tdg": 2, "sdg": 1}),
        (G.and_dg(0, 1, 2, "01"), {"h": 2, "cx": 3, "t": 2, "tdg": 2, "s": 1, "x": 2}),
    ],
)
def test_rule_counts(gate: Gate, expected: dict[str, int]) -> None:
    assert lower_to_basis(one(gate)).count_ops() == expected


def test_rule_orders() -> None:
    assert [g.name for g in decompose_gate(G.ry(0.3, 0))] == ["sdg", "h", "rz", "h", "s"]
    assert [g.name for g in decompose_gate(G.cry(0.3, 0, 1))] == ["ry", "cx", "ry", "cx"]
    assert [g.name for g in decompose_gate(G.csbf(0.3, 0, 1, 2, 3, 4))].count("crz") == 1
    assert [str(g) for g in decompose_gate(G.crz(0.5, 0, 1))] == ["rz(0.25) 1", "cx 0 1", "rz(-0.25) 1", "cx 0 1"]
    with pytest.raises(ValueError):
        decompose_gate(G.h(0))
    with pytest.raises(ValueError, match="lower_mcx"):
        decompose_gate(G.mcx([0, 1, 2], 3))


DECOMPOSABLE = [
    G.ccx(0, 1, 2), G.crz(0.7, 1, 0), G.cry(-0.9, 0, 1), G.rzz(1.7, 1, 0), G.rx(0.4, 0), G.ry(-2.2, 0),
    G.cz(1, 0), G.crx(0.3, 1, 0), G.sbf(0.8, 3, 1, 0, 2), G.csbf(-0.6, 4, 0, 2, 1, 3),
    G.mcx([1], 0, "0"), G.mcx([2, 0], 1, "10"),
]  # fmt: skip


@pytest.mark.parametrize("gate", DECOMPOSABLE, ids=str)
def test_each_rule_is_exact_including_global_phase(gate: Gate) -> None:
    c = one(gate)
    low = lower_to_basis(c)
    assert set(low.count_ops()) <= DEFAULT_BASIS
    np.testing.assert_allclose(circuit_unitary(low), circuit_unitary(c), atol=1e-12)


def test_symbolic_angles_survive_lowering() -> None:
    g0 = Angle.symbol("gamma_0", 2.0)
    low = lower_to_basis(one(G.crz(g0, 0, 1)))
    assert [g.params[0] for g in low.gates if g.name == "rz"] == [g0 / 2, -(g0 / 2)]


def test_custom_basis() -> None:
    c = one(G.rzz(0.3, 0, 1), G.cry(0.2, 1, 2), G.mcx([0, 1, 2], 3))
    keep = lower_to_basis(c, DEFAULT_BASIS | {"rzz", "ry", "ccx", "and", "and_dg"})
    assert keep.count_ops() == {"ccx": 1, "and": 1, "and_dg": 1, "rzz": 1, "ry": 2, "cx": 2}
    keep_mcx = lower_to_basis(c, DEFAULT_BASIS | {"mcx"})
    assert keep_mcx.count_ops()["mcx"] == 1 and not keep_mcx.has_register("work")
    with pytest.raises(ValueError):
        lower_to_basis(c, {"h", "rz"})
    with pytest.raises(ValueError):
        lower_to_basis(c, {"h", "nonsense"})


# --- peephole --------------------------------------------------------------------------------
def names(c: Circuit) -> list[str]:
    return [str(g) for g in c.gates]


def test_peephole_cascades() -> None:
    c = one(G.h(0), G.x(0), G.cx(0, 1), G.cx(0, 1), G.x(0), G.h(0), G.t(1), G.tdg(1), G.s(2), G.sdg(2))
    assert names(peephole(c)) == []


def test_peephole_respects_blockers_and_orientation() -> None:
    assert len(peephole(one(G.cx(0, 1), G.h(1), G.cx(0, 1)))) == 3
    assert len(peephole(one(G.cx(0, 1), G.cx(1, 0)))) == 2
    assert len(peephole(one(G.cx(0, 1), G.h(2), G.cx(0, 1)))) == 1  # qubit 2 is not in the way
    assert len(peephole(one(G.t(0), G.t(0)))) == 2
    assert len(peephole(one(G.rx(0.3, 0), G.rx(-0.3, 0)))) == 0
    assert len(peephole(one(G.rx(0.3, 0), G.rx(0.3, 0)))) == 2
    assert len(peephole(one(G.mcx([0, 1, 2], 3, "101"), G.mcx([0, 1, 2], 3, "101")))) == 0
    assert len(peephole(one(G.mcx([0, 1, 2], 3, "101"), G.mcx([0, 1, 2], 3, "100")))) == 2
    assert len(peephole(one(G.ccx(0, 1, 2), G.cx(0, 1), G.ccx(0, 1, 2)))) == 3


def test_peephole_merges_rz() -> None:
    assert names(peephole(one(G.rz(0.25, 0), G.rz(0.5, 0)))) == ["rz(0.75) 0"]
    assert names(peephole(one(G.rz(0.25, 0), G.rz(-0.25, 0), G.h(0)))) == ["h 0"]
    assert names(peephole(one(G.rz(0.0, 0), G.h(0)))) == ["h 0"]
    g0 = Angle.symbol("gamma_0")
    merged = list(peephole(one(G.rz(g0, 0), G.rz(0.5, 0), G.rz(-g0, 0))).gates)
    assert merged == [G.rz(0.5, 0)]
    assert list(peephole(one(G.rz(g0, 0), G.rz(-g0, 0), G.x(0))).gates) == [G.x(0)]


def test_peephole_never_crosses_sections() -> None:
    c = Circuit([("data", 1)], [Section("a", [G.h(0), G.rz(0.1, 0)]), Section("b", [G.rz(0.2, 0), G.h(0)])])
    assert peephole(c) == c


# --- lower() and the property tests ----------------------------------------------------------
def test_lower_guarantees() -> None:
    c = one(G.mcx([0, 1, 2, 3, 4], 5, "10101"), G.csbf(0.2, 0, 1, 2, 3, 4), G.ry(0.1, 5))
    low = lower(c)
    assert set(low.count_ops()) <= DEFAULT_BASIS
    assert low.registers == (Register("data", 6), Register("work", 3))
    assert [s.name for s in low.sections] == ["s"]
    assert lower(low) == low  # idempotent on lowered circuits
    assert len(lower(c, peephole=False)) >= len(low)


@pytest.mark.parametrize("state", ["11", "10", "01", "00"])
def test_and_is_exact_on_a_clean_target_and_and_dg_undoes_it(state: str) -> None:
    """On every input with the target |0>, ``and`` lowers to exactly the AND (no phase); ``and_dg`` inverts it."""
    gate = G.and_(0, 1, 2, state)
    # columns 0..3: inputs with the target (qubit 2, the high bit) in |0>; the AND must be exact there
    full = circuit_unitary(lower_to_basis(one(gate)))
    ideal = circuit_unitary(one(gate))
    np.testing.assert_allclose(full[:, :4], ideal[:, :4], atol=1e-12)
    assert not np.allclose(full, ideal)  # a relative-phase construction: not a Toffoli on a dirty target
    pair = lower_to_basis(one(gate, G.and_dg(0, 1, 2, state)))
    np.testing.assert_allclose(circuit_unitary(pair), np.eye(8), atol=1e-12)
    assert peephole(one(gate, G.and_dg(0, 1, 2, state))).count_ops() == {}


@settings(max_examples=60, deadline=None)
@given(circuits(max_qubits=5, max_gates=8, max_controls=4, symbolic=True))
def test_lower_equals_original_on_clean_work_subspace(c: Circuit) -> None:
    low = lower(c)
    assert set(low.count_ops()) <= DEFAULT_BASIS
    assert [s.name for s in low.sections] == [s.name for s in c.sections]
    assert low.registers[: len(c.registers)] == c.registers
    np.testing.assert_allclose(clean_block(low, c.num_qubits), circuit_unitary(c, VALUES), atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(circuits(max_qubits=5, max_gates=12, symbolic=True))
def test_peephole_keeps_unitary_and_never_increases_counts(c: Circuit) -> None:
    for circuit in (c, lower(c, peephole=False)):
        opt = peephole(circuit)
        before, after = circuit.count_ops(), opt.count_ops()
        assert all(after[k] <= before.get(k, 0) for k in after)
        assert all(len(a) <= len(b) for a, b in zip(opt.sections, circuit.sections, strict=True))
        np.testing.assert_allclose(circuit_unitary(opt, VALUES), circuit_unitary(circuit, VALUES), atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.sampled_from(["h", "x", "t", "tdg", "s", "sdg", "cx01", "cx10"]), max_size=40))
def test_peephole_on_self_inverse_words(word: list[str]) -> None:
    make = {
        "h": G.h(0), "x": G.x(0), "t": G.t(1), "tdg": G.tdg(1), "s": G.s(0), "sdg": G.sdg(0),
        "cx01": G.cx(0, 1), "cx10": G.cx(1, 0),
    }  # fmt: skip
    c = one(*[make[w] for w in word], n=2)
    doubled = c.compose(c.inverse())
    assert len(peephole(Circuit(doubled.registers, [Section("s", list(doubled.gates))]))) == 0
