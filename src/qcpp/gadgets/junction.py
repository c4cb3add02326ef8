"""Junctions: the uncompute of one partial mixer fused with the compute of the next, as a gadget of its own.

Consecutive partial mixers share qubits (the same clean ``logic`` temporaries, shared edges), so the end of
one and the start of the next can cancel (``and_dg(a, b, t)`` then ``and(a', b, t)`` loses 2 CX and 4 one-qubit
gates), which a per-gadget lowering would leave to a later optimiser. So a layer of parity-basis partial mixers
``m_0, ..., m_{n-1}`` is cut at its rotations instead:

    Junction(-, m_0)  Rotation(m_0)  Junction(m_0, m_1)  Rotation(m_1)  ...  Rotation(m_{n-1})  Junction(m_{n-1}, -)

where ``Junction(l, r)`` emits the mirrored leaves of ``l`` then the compute leaves of ``r`` (one section, so
the peephole pass cancels across the old boundary) and ``Rotation(m)`` the controlled rotation of ``m``. The
gates are those of the unfused partial mixers in the same order: same unitary, same clean ancillas.

**Cost without emitting.** A junction's lowered gates are fixed by its :attr:`MixerJunction.kind`: the two
partial mixers' kinds (their plans) and which qubits they share (:attr:`MixerJunction.overlap`: for each qubit
slot of the right one, the slot of the left one on the same qubit). The cost of a kind is computed once, by
lowering the kind's own canonical gate list, cached and reused for every junction of that kind (a grid has a
handful). The call graph lists the junctions and rotations themselves.

The ``paper`` rule's controlled-X network (:class:`~qcpp.gadgets.partial_mixer.McxPartialMixer`) is not
fused: it is lowered leaf by leaf on purpose (see its ``emit_blocks``).

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.gadgets.partial_mixer import partial_mixer
    >>> s = default_scenario(3, 3, 1)
    >>> ms = [partial_mixer(s, 0, q, 0.7, s.num_variables) for q in s.grid.plaquettes]
    >>> pieces = mixer_pieces(ms)
    >>> [type(g).__name__ for g in pieces[:3]], len(pieces)
    (['MixerJunction', 'MixerRotation', 'MixerJunction'], 9)
    >>> sum(m.cost().cx for m in ms), sum(g.cost().cx for g in pieces)
    (108, 106)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

from qcpp.gadgets.leaves import leaf_cost, leaf_logical_cost
from qcpp.gadgets.partial_mixer import (
    McxPartialMixer,
    MixerPlan,
    ParityMixerKind,
    ParityPartialMixer,
    emit_plan,
    plan_parity_mixer,
    plan_slots,
)
from qcpp.gadgets.pricing import PricedByKind
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import LOGICAL_BASIS, lower

__all__ = ["JunctionKind", "MixerJunction", "MixerRotation", "RotationKind", "mixer_pieces"]


class JunctionKind(NamedTuple):
    """Kind key of a :class:`MixerJunction`: equal kinds, equal gates up to qubit names.

    Attributes:
        gadget: ``"mixer_junction"``.
        left, right: the kinds of the partial mixers that end and start here (``None`` at an open end).
        overlap: :attr:`MixerJunction.overlap`.
    """

    gadget: str
    left: ParityMixerKind | None
    right: ParityMixerKind | None
    overlap: tuple[int, ...]


class RotationKind(NamedTuple):
    """Kind key of a :class:`MixerRotation`.

    Attributes:
        gadget: ``"mixer_rotation"``.
        rotation: the leaf's name, ``"crx"`` or ``"ccrx"``.
    """

    gadget: str
    rotation: str


@dataclass(frozen=True)
class MixerRotation:
    """The controlled rotation of a parity-basis partial mixer (``crx`` or ``ccrx``), between two junctions.

    Attributes:
        mixer: the partial mixer.
    """

    mixer: ParityPartialMixer

    @property
    def kind(self) -> RotationKind:
        """The rotation leaf's name."""
        return RotationKind("mixer_rotation", self.mixer.plan.rotation[0])

    def cost(self) -> Cost:
        """Lowered cost (the leaf's closed form)."""
        return leaf_cost(self.mixer.plan.rotation[0])

    def logical_cost(self) -> Cost:
        """The same (a rotation has no AND)."""
        return leaf_logical_cost(self.mixer.plan.rotation[0])

    def needs(self) -> tuple[int, int]:
        """Those of its partial mixer (the rotation runs while the mixer's temporaries are computed)."""
        return self.mixer.needs()

    def emit(self) -> list[Gate]:
        """The rotation's gates."""
        return self.mixer.parts()[1]


@dataclass(frozen=True)
class MixerJunction(PricedByKind):
    """The mirrored leaves of ``left`` then the compute leaves of ``right`` (either may be absent: the open ends
    of a layer), lowered as one section (see the module docstring).

    Attributes:
        left: the partial mixer that ends here, or ``None``.
        right: the partial mixer that starts here, or ``None``.
    """

    left: ParityPartialMixer | None
    right: ParityPartialMixer | None

    @cached_property
    def overlap(self) -> tuple[int, ...]:
        """For each qubit slot of ``right`` (:func:`~qcpp.gadgets.partial_mixer.plan_slots` order), the
        index of the slot of ``left`` on the same qubit, or ``-1``."""
        if self.left is None or self.right is None:
            return ()
        where = {qb: i for i, qb in enumerate(self.left.slot_qubits)}
        return tuple(where.get(qb, -1) for qb in self.right.slot_qubits)

    @cached_property
    def kind(self) -> JunctionKind:
        """The two partial mixers' kinds and :attr:`overlap`: equal kinds, equal gates up to qubit names."""
        return JunctionKind(
            "mixer_junction",
            None if self.left is None else self.left.kind,  # type: ignore[arg-type]
            None if self.right is None else self.right.kind,  # type: ignore[arg-type]
            self.overlap,
        )

    def _kind_costs(self) -> tuple[Cost, Cost]:
        return _junction_costs(self.kind)

    def needs(self) -> tuple[int, int]:
        """The larger needs of its two sides (one side at least is present)."""
        sides = [m.needs() for m in (self.left, self.right) if m is not None]
        return max(t for t, _ in sides), max(w for _, w in sides)

    def emit(self) -> list[Gate]:
        """The mirrored leaves of ``left``, then the compute leaves of ``right``."""
        tail = self.left.parts()[2] if self.left is not None else []
        head = self.right.parts()[0] if self.right is not None else []
        return [*tail, *head]


def _plan(kind: ParityMixerKind) -> MixerPlan:
    assert kind.gadget == "parity", kind
    return plan_parity_mixer(kind.program, kind.target)


def _junction_costs(kind: JunctionKind) -> tuple[Cost, Cost]:
    """Lowered and logical cost of a junction kind, from its canonical gate list: the left plan's slots on qubits
    ``0..``, the right plan's on the left's where :attr:`MixerJunction.overlap` says so and on fresh qubits
    otherwise."""
    left_kind, right_kind, overlap = kind.left, kind.right, kind.overlap
    gates: list[Gate] = []
    n = 0
    if left_kind is not None:
        plan = _plan(left_kind)
        slots = plan_slots(plan, left_kind.program.num_outer)
        gates += emit_plan(plan, {s: i for i, s in enumerate(slots)}, 0.0)[2]
        n = len(slots)
    if right_kind is not None:
        plan = _plan(right_kind)
        slots = plan_slots(plan, right_kind.program.num_outer)
        qubit = {}
        for s, shared in zip(slots, overlap or (-1,) * len(slots), strict=True):
            if shared < 0:
                shared, n = n, n + 1
            qubit[s] = shared
        gates += emit_plan(plan, qubit, 0.0)[0]
    n = max((q + 1 for g in gates for q in g.qubits), default=1)
    circ = Circuit([("q", n)], [Section("junction", tuple(gates))])
    return Cost.count(lower(circ).gates), Cost.count(lower(circ, LOGICAL_BASIS).gates)


def mixer_pieces(
    mixers: Sequence[ParityPartialMixer | McxPartialMixer],
) -> list[ParityPartialMixer | McxPartialMixer | MixerJunction | MixerRotation]:
    """One layer's partial mixers as the gadgets the circuit emits (each a section of its own).

    Args:
        mixers: the layer's partial mixers in circuit order (all parity-basis, or all controlled-X network).

    Returns:
        For parity-basis partial mixers: junctions and rotations (see the module docstring); otherwise the
        partial mixers themselves.
    """
    if not mixers or not isinstance(mixers[0], ParityPartialMixer):
        return list(mixers)
    out: list[ParityPartialMixer | McxPartialMixer | MixerJunction | MixerRotation] = []
    prev: ParityPartialMixer | None = None
    for m in mixers:
        assert isinstance(m, ParityPartialMixer)
        out += [MixerJunction(prev, m), MixerRotation(m)]
        prev = m
    out.append(MixerJunction(prev, None))
    return out
