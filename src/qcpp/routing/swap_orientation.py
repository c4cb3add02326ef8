"""SWAPs of a routed circuit written the way round that lets their CX cancel with the circuit's.

A SWAP is written as three ``cx`` (:func:`qcpp.routing.sabre.assemble`): ``cx a b; cx b a; cx a b`` or, the same
operator, ``cx b a; cx a b; cx b a``. Which of the two decides whether its outer ``cx`` can cancel with a ``cx`` of
the circuit on the same pair and in the same direction that it commutes to: a ``cx`` commutes with a gate on its
control that is diagonal (``rz``, ``t``, ``s``, ... or a ``cx`` with the same control) and with a gate on its target
that is an X rotation (``x``, ``rx``, or a ``cx`` with the same target). Qiskit's ``CommutativeCancellation`` (part of
the O3 passes, :func:`qcpp.routing.qiskit_o3.qiskit_optimized`) removes such pairs, but only in the direction the
SWAP was written. :func:`orient_swaps` picks, SWAP by SWAP in circuit order, the way round whose outer ``cx`` meet
such a partner before and after it (the way it was written on ties). The operator is unchanged (both ways are the
SWAP), so are the layouts.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Register, Section
    >>> from qcpp.ir.gates import cx, t
    >>> from qcpp.routing.routed_circuit import RoutedCircuit
    >>> c = Circuit([Register("q", 3)], [Section("s", [cx(1, 0), t(1), cx(0, 1), cx(1, 0), cx(0, 1)])])
    >>> r = RoutedCircuit(c, get_device("grid:1x3"), (0, 1), (1, 0), 1, (0, 1))
    >>> [g[1] for g in orient_swaps(r).circuit.gates if g[0] == "cx"]  # cx 1 0 then meets the SWAP's first
    [(1, 0), (1, 0), (0, 1), (1, 0)]
"""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Sequence

from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate, cx
from qcpp.routing.routed_circuit import RoutedCircuit

__all__ = ["orient_swaps"]

DIAGONAL = frozenset({"rz", "t", "tdg", "s", "sdg", "z"})
"""One-qubit gates that commute with a ``cx`` on its control."""

X_AXIS = frozenset({"x", "rx", "sx"})
"""One-qubit gates that commute with a ``cx`` on its target."""


def _meets(gates: Sequence[Gate], on: list[list[int]], k: int, c: int, t: int, step: int) -> bool:
    """Whether ``cx c t`` at index ``k`` commutes, going ``step`` (-1: back, +1: ahead), up to a ``cx c t``
    (``on[q]``: the indices of the gates on qubit ``q``, in order)."""
    lc, lt = on[c], on[t]
    i = bisect_left(lc, k) + step
    j = bisect_left(lt, k) + step
    while True:
        cand = []
        if 0 <= i < len(lc):
            cand.append(lc[i])
        if 0 <= j < len(lt):
            cand.append(lt[j])
        if not cand:
            return False
        g_at = max(cand) if step < 0 else min(cand)  # the next gate on c or t that way
        g = gates[g_at]
        name, qs = g[0], g[1]
        if name == "cx" and qs == (c, t):
            return True
        if len(qs) == 2:
            if name != "cx":
                return False
            gc, gt = qs
            if (gc == c) == (gt == t):  # commutes only sharing just the control or just the target
                return False
        elif qs[0] == c:
            if name not in DIAGONAL:
                return False
        elif name not in X_AXIS:
            return False
        if 0 <= i < len(lc) and lc[i] == g_at:
            i += step
        if 0 <= j < len(lt) and lt[j] == g_at:
            j += step


def orient_swaps(routed: RoutedCircuit) -> RoutedCircuit:
    """``routed`` with every SWAP (three ``cx`` in a row on one pair, alternating direction) written the way round
    whose outer ``cx`` cancel with more of the circuit's by commutation (module docs); the same operator and layouts.
    """
    gates = list(routed.circuit.gates)
    sections = routed.circuit.sections
    section_of = [s for s, sec in enumerate(sections) for _ in sec.gates]
    on: list[list[int]] = [[] for _ in range(routed.circuit.num_qubits)]
    for k, g in enumerate(gates):
        for q in g[1]:
            on[q].append(k)
    changed = False
    k = 0
    while k + 2 < len(gates):
        g0, g1, g2 = gates[k], gates[k + 1], gates[k + 2]
        if not (g0[0] == g1[0] == g2[0] == "cx" and g0[1] == g2[1] and g1[1] == g0[1][::-1]):
            k += 1
            continue
        a, b = g0[1]

        def score(c: int, t: int, k: int = k) -> int:
            return int(_meets(gates, on, k, c, t, -1)) + int(_meets(gates, on, k + 2, c, t, +1))

        if score(b, a) > score(a, b):
            gates[k], gates[k + 1], gates[k + 2] = cx(b, a), cx(a, b), cx(b, a)
            changed = True
        k += 3
    if not changed:
        return routed
    out: list[list[Gate]] = [[] for _ in sections]
    for s, g in zip(section_of, gates, strict=True):
        out[s].append(g)
    written = [Section(sec.name, tuple(gs)) for sec, gs in zip(sections, out, strict=True)]
    circuit = Circuit(routed.circuit.registers, written)
    return RoutedCircuit(circuit, routed.device, routed.initial_layout, routed.final_layout, routed.swaps,
                         routed.measured, routed.fused)  # fmt: skip
