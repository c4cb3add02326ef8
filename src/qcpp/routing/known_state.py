"""A routed circuit simplified for the state a device starts in: every qubit |0>.

A device runs a circuit from reset, so the input of a routed circuit is known: every physical qubit is |0>. The
QAOA circuit starts with ``x`` gates on some data qubits (the robots' start) and runs its first partial mixers'
parity networks and SWAPs on qubits still in a computational-basis state, where a ``cx`` does nothing (control
|0>) or is an ``x`` on its target (control |1>). :func:`from_zero` propagates that knowledge through the circuit
and removes those ``cx``:

* per qubit a known basis value (0 or 1) while every branch of the state agrees on it, and
* per qubit ``q`` a relation ``x_q = x_p xor v`` to one other qubit ``p`` (after a ``cx p q`` onto a known ``q``:
  the first two ``cx`` of a SWAP into a qubit in |0>), so the next ``cx q p`` is known to leave ``p`` in the basis
  state ``v`` (the SWAP's third ``cx`` then has a control in |0> and goes).

Diagonal one-qubit gates (``rz``, ``t``, ``s``, ...) and two-qubit diagonal gates (``cz``, ``rzz``) keep what is
known (they change phases, not which basis states the state is supported on); ``x`` flips it; any other one-qubit
gate forgets it for its qubit. Every rewrite is exact on the states that can occur, so the result prepares the same
state from |0...0> as the input (a ``cx`` with its control in |0> on every branch is the identity there, with its
control in |1> it is ``x`` on the target): it equals the input on the all-|0> input, not as a unitary on every
input. The layouts, SWAP count and measured qubits are the input's.

Why: Qiskit's O3 passes keep the unitary (they cannot know the input), so these ``cx`` stay in every routing,
Qiskit's own included; on one robot on 3x3 about a quarter of the routed ``cx`` act on basis-state controls.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Register, Section
    >>> from qcpp.ir.gates import cx, h, x
    >>> gates = [x(0), h(2), cx(0, 1), cx(1, 2), cx(2, 1), cx(1, 2)]  # cx 0 1 on |1>; a SWAP of 1 with 2
    >>> r = RoutedCircuit(Circuit([Register("q", 3)], [Section("s", gates)]), get_device("grid:1x3"),
    ...                   (0, 1, 2), (0, 2, 1), 1, (0, 1, 2))
    >>> [(g[0], g[1]) for g in from_zero(r).circuit.gates]  # cx 0 1 and the SWAP's first cx have a control in |1>
    [('x', (0,)), ('h', (2,)), ('x', (1,)), ('x', (2,)), ('cx', (2, 1)), ('cx', (1, 2))]
    >>> gates = [h(0), cx(0, 1), cx(1, 0), cx(0, 1)]  # a SWAP of a superposition into |0>
    >>> r = RoutedCircuit(Circuit([Register("q", 2)], [Section("s", gates)]), get_device("grid:1x2"),
    ...                   (0,), (1,), 1, (0,))
    >>> [(g[0], g[1]) for g in from_zero(r).circuit.gates]  # two cx move it, the third has its control in |0>
    [('h', (0,)), ('cx', (0, 1)), ('cx', (1, 0))]
"""

from __future__ import annotations

from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, x
from qcpp.routing.routed_circuit import RoutedCircuit

__all__ = ["from_zero"]

DIAGONAL_1Q = frozenset({"rz", "t", "tdg", "s", "sdg", "z"})
"""One-qubit gates diagonal in the computational basis: they keep a known basis value and relation."""

DIAGONAL_2Q = frozenset({"cz", "rzz"})
"""Two-qubit gates diagonal in the computational basis."""


class _Known:
    """What is known of the computational-basis support of the state, per qubit (module docs).

    ``value[q]``: 0 or 1 where every branch has that value on ``q`` (``None``: not known). ``rel[q] = (p, v)``:
    every branch has ``x_q = x_p xor v`` (neither ``q`` nor ``p`` has a known value then).
    """

    def __init__(self, num_qubits: int) -> None:
        self.value: list[int | None] = [0] * num_qubits
        self.rel: dict[int, tuple[int, int]] = {}

    def forget_relations(self, q: int) -> None:
        """Drop every relation that names ``q``."""
        self.rel.pop(q, None)
        for k in [k for k, (p, _) in self.rel.items() if p == q]:
            del self.rel[k]

    def forget(self, q: int) -> None:
        """Nothing is known of ``q`` any more."""
        self.value[q] = None
        self.forget_relations(q)

    def flip(self, q: int) -> None:
        """An ``x`` on ``q``: its value and every relation that names it flip."""
        v = self.value[q]
        if v is not None:
            self.value[q] = 1 - v
        if q in self.rel:
            p, w = self.rel[q]
            self.rel[q] = (p, 1 - w)
        for k, (p, w) in list(self.rel.items()):
            if p == q:
                self.rel[k] = (p, 1 - w)

    def cx(self, c: int, t: int) -> None:
        """A ``cx c t`` whose control has no known value: ``x_t`` becomes ``x_t xor x_c``."""
        v = self.value[t]
        if v is not None:  # t = c xor v
            self.value[t] = None
            self.forget_relations(t)
            self.rel[t] = (c, v)
            return
        for q, p in ((c, t), (t, c)):
            r = self.rel.get(q)
            if r is not None and r[0] == p:  # x_t xor x_c is the constant r[1]
                self.forget_relations(t)
                self.value[t] = r[1]
                return
        self.forget_relations(t)  # x_c is unchanged, so relations of c to others stay


def from_zero(routed: RoutedCircuit) -> RoutedCircuit:
    """``routed`` (CX and one-qubit gates, or any one- and two-qubit gates) with every ``cx`` whose control is in a
    known basis state on every branch, starting from all qubits in |0>, removed (control |0>) or written as ``x`` on
    its target (control |1>) (module docs). Equal to ``routed`` on the all-|0> input; the same layouts, SWAPs,
    measured qubits and sections (a section may lose gates).

    Args:
        routed: A routed circuit (physical qubits; every one of them |0> at the start).

    Returns:
        The simplified routed circuit (``routed`` itself where nothing changes).
    """
    known = _Known(routed.circuit.num_qubits)
    changed = False
    sections = []
    for sec in routed.circuit.sections:
        out: list[Gate] = []
        for g in sec.gates:
            name, qs = g[0], g[1]
            if len(qs) == 1:
                q = qs[0]
                if name == "x":
                    known.flip(q)
                elif name not in DIAGONAL_1Q:
                    known.forget(q)
                out.append(g)
                continue
            if name == "cx" and len(qs) == 2:
                c, t = qs
                v = known.value[c]
                if v is None:
                    known.cx(c, t)
                    out.append(g)
                    continue
                changed = True
                if v == 1:
                    known.flip(t)
                    out.append(x(t))
                continue
            if name not in DIAGONAL_2Q:
                for q in qs:
                    known.forget(q)
            out.append(g)
        sections.append(Section(sec.name, out))
    if not changed:
        return routed
    circuit = Circuit(routed.circuit.registers, sections)
    return RoutedCircuit(circuit, routed.device, routed.initial_layout, routed.final_layout, routed.swaps,
                         routed.measured, routed.fused)  # fmt: skip
