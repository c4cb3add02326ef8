"""Exact ASAP depths of a circuit built from gadgets, without building the circuit: max-plus transfer profiles.

ASAP layering (:func:`qcpp.estimators.depth.depths`) is a longest-path computation: every gate sets the level of its
qubits to ``max(levels of its qubits) + c`` (``c`` per depth kind: every gate for ``depth``, two-qubit gates for
``two_qubit_depth``, ``rz`` for ``rotation_depth``). That is a max-plus linear map, so a whole gadget is one: with
``f`` the levels of its ``k`` qubits before it, the levels after it are ``f'[j] = max_i (f[i] + D[i][j])``,
``D[i][j]`` the most levels on a path from its input on qubit ``i`` to its output on qubit ``j`` (``-inf`` if none).
Composing the maps section by section from zeros gives exactly the levels of the concatenated lowered gates
(lowering never crosses a section boundary, so each gadget is lowered alone, as the compiler does).

A gadget's ``D`` (:func:`transfer_profile`, the three depths in one block-diagonal matrix) is computed once and
cached: per kind for *anchored* gadgets (:data:`ANCHORS`: their kind fixes their gates up to their qubit slots,
so a gadget costs one look-up across every scenario), per lowered structure for the others; a gadget on more than
:data:`MATRIX_QUBITS` qubits is cut into runs of gates on at most that many qubits, one matrix per run.
:class:`LayeredDepth` holds one scenario's state preparation and one layer and carries the frontier from ``p`` to
``p + 1``, so a sweep over ``p = 1..P`` propagates ``P`` layers in all.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.plan.options import DEFAULT_PLAN
    >>> from qcpp.estimators.estimate import compiled_depth, layered_depth
    >>> s = default_scenario(3, 3, 2)
    >>> layered_depth(s, DEFAULT_PLAN).depth(2) == compiled_depth(s, 2)
    True
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from qcpp.estimators.depth import Depth
from qcpp.gadgets.junction import MixerJunction, MixerRotation
from qcpp.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer, plan_slots
from qcpp.gadgets.phase_visits import VisitPhase, visit_ancillas
from qcpp.gadgets.pricing import COSTS
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.lowering.passes import WORK_REGISTER, lower

__all__ = [
    "ANCHORS",
    "ANCHOR_SLOTS",
    "MATRIX_QUBITS",
    "NEG",
    "LayeredDepth",
    "MatrixStep",
    "anchored_profile",
    "gadget_depth",
    "gadget_steps",
    "known_depth",
    "lowered_gates",
    "transfer_profile",
]

NEG = -(1 << 40)
"""``-inf`` of the integer profiles: no path (far below any sum of real levels, far above int64 overflow)."""
MATRIX_QUBITS = 24
"""Widest transfer matrix of a non-anchored gadget; a wider gadget is cut into consecutive runs of gates on at
most this many qubits (one matrix each; wider matrices cost more per application than they save)."""

ANCHOR_SLOTS = 64
"""Most slots an anchored gadget may have (its matrix is ``3 x slots`` square); a wider one goes by runs."""

_ROT = "rz"  # the only gate that adds a rotation level (lowered circuits: an arbitrary rotation is an rz)


def lowered_gates(gadget: Any, registers: Sequence[Register], name: str = "g") -> list[tuple[Any, ...]]:
    """A gadget's lowered gates: each block (``emit_blocks()`` if it has them, else ``emit()``) its own section,
    lowered with the circuit's ``registers`` (``work`` included), as the compiler lowers it."""
    blocks = getattr(gadget, "emit_blocks", None)
    secs = [Section(name, tuple(b)) for b in (blocks() if blocks is not None else [gadget.emit()])]
    return list(lower(Circuit(registers, secs)).gates)


def transfer_profile(gates: Iterable[tuple[Any, ...]], qubits: Sequence[int]) -> np.ndarray:
    """The ``(3k, 3k)`` max-plus transfer matrix of ``gates`` on ``qubits`` (in that order).

    Block ``t`` (rows and columns ``t*k .. t*k + k - 1``) is depth ``t`` of :class:`~qcpp.estimators.depth.Depth`
    (all gates, two-qubit gates, rotations); ``M[t*k + i][t*k + j]`` is the most levels on a path from qubit
    ``i``'s input to qubit ``j``'s output, :data:`NEG` if none (and off the diagonal blocks).

    Args:
        gates: lowered gate tuples ``(name, qubits, ...)``, every qubit in ``qubits``.
        qubits: the gadget's qubits; position ``i`` is row/column ``i`` of each block.

    Returns:
        The matrix (``int64``).

    >>> m = transfer_profile([("h", (5,)), ("cx", (5, 7)), ("rz", (7,), (0.1,))], [5, 7])
    >>> m[:2, :2].tolist()  # all gates: h, cx on qubit 5; h, cx, rz from 5 to 7; cx, rz from 7 to 7
    [[2, 3], [1, 2]]
    """
    pos = {q: i for i, q in enumerate(qubits)}
    k = len(qubits)
    # lv[t, j, i]: depth t's levels from each input i to qubit j's current output
    lv = np.full((3, k, k), NEG, dtype=np.int64)
    for t in range(3):
        np.fill_diagonal(lv[t], 0)
    one = np.array([1, 0, 0], dtype=np.int64)[:, None]
    one_rz = np.array([1, 0, 1], dtype=np.int64)[:, None]
    two = np.array([1, 1, 0], dtype=np.int64)[:, None]
    for g in gates:
        qs = [pos[q] for q in g[1]]
        if len(qs) == 1:
            lv[:, qs[0]] += one_rz if g[0] == _ROT else one
            continue
        lv[:, qs] = (lv[:, qs].max(axis=1) + (two if len(qs) == 2 else one))[:, None, :]
    out = np.full((3 * k, 3 * k), NEG, dtype=np.int64)
    for t in range(3):
        out[t * k : (t + 1) * k, t * k : (t + 1) * k] = lv[t].T  # D[i][j] = lv[j][i]
    out[out < NEG // 2] = NEG  # unreachable stays NEG however many gates added to it
    return out


# --- anchors: gadgets whose kind fixes their gates up to a slot order of their qubits -------------------------
def _mixer_anchors(g: ParityPartialMixer | McxPartialMixer) -> tuple[Hashable, tuple[int, ...]]:
    temps = range(g.logic_offset, g.logic_offset + g.num_temps)
    return (type(g).__name__, g.kind), (*g.plaquette_qubits, *g.outer_qubits, *temps)


def _junction_anchors(g: MixerJunction) -> tuple[Hashable, tuple[int, ...]]:
    # the kind holds both partial mixers' kinds and which slots they share: the left one's slots, then the right
    # one's own
    left = g.left.slot_qubits if g.left is not None else ()
    right = g.right.slot_qubits if g.right is not None else ()
    if g.left is not None and g.right is not None:
        right = tuple(q for q, o in zip(right, g.overlap, strict=True) if o < 0)
    return ("MixerJunction", g.kind), (*left, *right)


def _rotation_anchors(g: MixerRotation) -> tuple[Hashable, tuple[int, ...]]:
    m = g.mixer
    qubit = dict(zip(plan_slots(m.plan, len(m.outer_qubits)), m.slot_qubits, strict=True))
    return ("MixerRotation", g.kind), tuple(qubit[s] for s in m.plan.rotation[1])


def _visit_anchors(g: VisitPhase) -> tuple[Hashable, tuple[int, ...]]:
    # a zero coefficient emits no phase (its cost differs), so it is part of the key; the gadget uses the first
    # ancillas it needs, whatever the pool it is given
    need = visit_ancillas(tuple(len(v) for v in g.visitors), g.products)
    return ("VisitPhase", g.kind), (*(q for v in g.visitors for q in v), *g.ancillas[:need])


ANCHORS: dict[type, Callable[[Any], tuple[Hashable, tuple[int, ...]]]] = {
    ParityPartialMixer: _mixer_anchors,
    McxPartialMixer: _mixer_anchors,
    MixerJunction: _junction_anchors,
    MixerRotation: _rotation_anchors,
    VisitPhase: _visit_anchors,
}
"""Per gadget class: ``gadget -> (key, slot qubits)``. Gadgets with equal keys have equal lowered gates once
their slot qubits are renamed by slot (plus ``work`` ancillas, at the same offsets of the ``work`` register)."""


@dataclass(frozen=True, eq=False)
class MatrixStep:
    """A gadget as a transfer matrix on its qubits.

    Attributes:
        index: positions in the flat frontier (``3n``: the three depths of ``n`` qubits) of the matrix's rows.
        matrix: the :func:`transfer_profile`.
    """

    index: np.ndarray
    matrix: np.ndarray


_CACHE_LIMIT = 4096
"""Entries per cache (a matrix is at most ``3 * 24`` squared int64, 41 kB, for runs; a sweep of 2x2..40x40 meets
a few hundred structures), then the cache starts again: a bound on memory."""
_ANCHORED = COSTS.table("anchored profile", _CACHE_LIMIT)
"""Per kind, in the kinds' one cache: ``(anchor key, slots) -> (profile on slots + work qubits, work offsets)``,
or ``None`` when the kind cannot be anchored."""
_OWN_DEPTH = COSTS.table("own depth", _CACHE_LIMIT)
"""Per kind, in the kinds' one cache: anchor key -> the gadget's own :class:`~qcpp.estimators.depth.Depth`."""
_STRUCTURE_TABLE = "transfer by structure"
"""The name of :data:`~qcpp.gadgets.pricing.COSTS`' table of lowered gate structure (qubits renamed by first
appearance) -> transfer matrix: keyed by gates, not by kind (a run of an arithmetic gadget, or a state
preparation), in a table of its own."""


def _work_start(registers: Sequence[Register]) -> int:
    start = 0
    for r in registers:
        if r.name == WORK_REGISTER:
            return start
        start += r.size
    return start


def _index(qubits: Sequence[int], n: int) -> np.ndarray:
    q = np.asarray(qubits, dtype=np.intp)
    return np.concatenate([q, q + n, q + 2 * n])


def anchored_profile(gadget: Any, registers: Sequence[Register]) -> tuple[tuple[int, ...], np.ndarray] | None:
    """``(qubits, profile)`` of an anchored gadget from the per-kind cache (``None`` if it is not anchored).

    Args:
        gadget: any gadget.
        registers: the circuit's registers (for the ``work`` register's position).

    Returns:
        The gadget's qubits in slot order (then its ``work`` ancillas) and the cached :func:`transfer_profile`.
    """
    anchors = ANCHORS.get(type(gadget))
    if anchors is None:
        return None
    key, slots = anchors(gadget)
    if len(slots) > ANCHOR_SLOTS or len(set(slots)) != len(slots):
        return None
    key = (key, len(slots))
    work0 = _work_start(registers)
    hit = _ANCHORED.get(key, False)
    if hit is False:
        gates = lowered_gates(gadget, registers)
        seen = set(slots)
        extra = sorted({q for g in gates for q in g[1] if q not in seen})
        if any(q < work0 for q in extra):
            hit = None  # touches a qubit outside its slots and the work register: not anchorable
        else:
            hit = (transfer_profile(gates, (*slots, *extra)), tuple(q - work0 for q in extra))
        COSTS.remember("anchored profile", key, hit)
    if hit is None:
        return None
    matrix, work = hit
    return (*slots, *(work0 + o for o in work)), matrix


def _runs(gates: Sequence[tuple[Any, ...]], limit: int) -> Iterator[tuple[Hashable, list[int], list[tuple]]]:
    """Consecutive runs of ``gates`` on at most ``limit`` qubits each (a gate on more is a run of its own), as
    ``(structure key, qubits in first-appearance order, gates)``; the key is the run with qubits renamed by first
    appearance (and whether each one-qubit gate is an ``rz``), all a transfer matrix depends on."""
    pos: dict[int, int] = {}
    flat: list[int] = []
    run: list[tuple] = []
    for g in gates:
        qs = g[1]
        if len(qs) == 1:
            i = pos.get(qs[0])
            if i is None:
                if len(pos) >= limit:
                    yield tuple(flat), list(pos), run
                    pos, flat, run = {}, [], []
                i = pos[qs[0]] = len(pos)
            flat += (-1 if g[0] == _ROT else -2, i)  # arity markers (rz apart) are negative, positions not
            run.append(g)
            continue
        if run and len(pos) + sum(q not in pos for q in qs) > limit:
            yield tuple(flat), list(pos), run
            pos, flat, run = {}, [], []
        flat.append(-len(qs) - 1)
        for q in qs:
            i = pos.get(q)
            if i is None:
                i = pos[q] = len(pos)
            flat.append(i)
        run.append(g)
    if run:
        yield tuple(flat), list(pos), run


def gadget_steps(gadget: Any, registers: Sequence[Register]) -> list[MatrixStep]:
    """One gadget as transfer matrices: one (cached per kind) if it is anchored, else its lowered gates cut into
    consecutive runs of at most :data:`MATRIX_QUBITS` qubits, one matrix per run (cached per run structure: the
    gates with qubits renamed by first appearance). Composing the runs is exact like composing gadgets.

    Args:
        gadget: any gadget (``emit()``, optionally ``emit_blocks()``).
        registers: the circuit's registers, ``work`` included.

    Returns:
        The steps, in order.
    """
    n = sum(r.size for r in registers)
    hit = anchored_profile(gadget, registers)
    if hit is not None:
        return [MatrixStep(_index(hit[0], n), hit[1])] if hit[0] else []
    out = []
    by_structure = COSTS.table(_STRUCTURE_TABLE, _CACHE_LIMIT)
    for key, qubits, run in _runs(lowered_gates(gadget, registers), MATRIX_QUBITS):
        matrix = by_structure.get(key)
        if matrix is None:
            matrix = transfer_profile(run, qubits)
            COSTS.remember(_STRUCTURE_TABLE, key, matrix)
        out.append(MatrixStep(_index(qubits, n), matrix))
    return out


def _propagate(levels: np.ndarray, steps: Sequence[MatrixStep]) -> None:
    """Apply ``steps`` to the flat frontier ``levels`` (``3n``: the three depths of ``n`` qubits) in place."""
    for st in steps:
        idx = st.index
        levels[idx] = (levels[idx][:, None] + st.matrix).max(axis=0)


def gadget_depth(gadget: Any, registers: Sequence[Register]) -> Depth:
    """A gadget's own depths (lowered alone, from an idle start): exact, and cached per kind when anchored.

    Args:
        gadget: any gadget.
        registers: the circuit's registers, ``work`` included.

    Returns:
        An ``exact`` :class:`~qcpp.estimators.depth.Depth` of the gadget alone.
    """
    anchors = ANCHORS.get(type(gadget))
    key = anchors(gadget)[0] if anchors is not None else None
    hit = _OWN_DEPTH.get(key) if key is not None else None
    if hit is None:
        steps = gadget_steps(gadget, registers)
        if len(steps) == 1:
            m = steps[0].matrix
            k = len(m) // 3
            hit = Depth(*(max(int(m[t * k : (t + 1) * k].max()), 0) if k else 0 for t in range(3)), "exact")  # type: ignore[arg-type]
        else:
            n = sum(r.size for r in registers)
            levels = np.zeros(3 * n, dtype=np.int64)
            _propagate(levels, steps)
            hit = _depth(levels, n)
        if key is not None:  # equal kinds, equal gates up to qubit names: equal own depths
            COSTS.remember("own depth", key, hit)
    return hit


def known_depth(gadget: Any) -> Depth | None:
    """The gadget's own depths if :func:`gadget_depth` has met its kind (an anchored one) before, else ``None``
    (looks at the kind only: nothing is emitted)."""
    anchors = ANCHORS.get(type(gadget))
    return _OWN_DEPTH.get(anchors(gadget)[0]) if anchors is not None else None


def _depth(levels: np.ndarray, n: int) -> Depth:
    if n == 0:
        return Depth()
    return Depth(int(levels[:n].max()), int(levels[n : 2 * n].max()), int(levels[2 * n :].max()), "exact")


class LayeredDepth:
    """Exact depths of ``initial steps + p x layer steps`` for any ``p``, carried from ``p`` to ``p + 1`` (the
    first layer's steps may differ: ``first``, the layer without its phase separator).

    Build it with :meth:`from_sections`. :meth:`depth` answers any ``p``: the depths of every ``p`` it has passed
    are kept (three integers each), the frontier only for the largest, so asking ``p = 1, 2, ..., P`` in turn
    propagates ``P`` layers in all, and asking a smaller ``p`` afterwards costs nothing.
    """

    def __init__(
        self,
        num_qubits: int,
        initial: Sequence[MatrixStep],
        layer: Sequence[MatrixStep],
        first: Sequence[MatrixStep] | None = None,
    ) -> None:
        self.num_qubits = num_qubits
        self.initial = tuple(initial)
        self.layer = tuple(layer)
        self.first = self.layer if first is None else tuple(first)
        self._levels: np.ndarray | None = None
        self._depths: list[Depth] = []

    @classmethod
    def from_sections(
        cls, sections: Iterable[tuple[str, Any]], registers: Sequence[Register], initial: str = "initial_state"
    ) -> LayeredDepth:
        """From ``(section name, gadget)`` of a plan with ONE layer (:meth:`qcpp.plan.qaoa.QaoaPlan.sections`), or
        with TWO whose first differs from every later one (no phase separator): the gadgets of section ``initial``
        form the state preparation, those of layer 0 (names ending ``_0``) the first layer, those of layer 1 the
        layer repeated after it (the first one, if there is no layer 1).

        Args:
            sections: the plan's sections, in circuit order.
            registers: the lowered circuit's registers (``work`` included).
            initial: name of the state preparation's section.
        """
        init: list[MatrixStep] = []
        first: list[MatrixStep] = []
        later: list[MatrixStep] = []
        for name, gadget in sections:
            (init if name == initial else first if name.endswith("_0") else later).extend(
                gadget_steps(gadget, registers)
            )
        return cls(sum(r.size for r in registers), init, later or first, first)

    def depth(self, p: int) -> Depth:
        """Exact depths of the state preparation and ``p`` layers."""
        if p < 0:
            raise ValueError(f"p must be >= 0, got {p}")
        n = self.num_qubits
        if self._levels is None:
            self._levels = np.zeros(3 * n, dtype=np.int64)
            _propagate(self._levels, self.initial)
            self._depths.append(_depth(self._levels, n))
        while len(self._depths) <= p:
            _propagate(self._levels, self.first if len(self._depths) == 1 else self.layer)
            self._depths.append(_depth(self._levels, n))
        return self._depths[p]
