"""Fault-tolerant (Clifford+T) estimates, labelled as estimates, beside the exact counts.

Three non-Clifford costs are estimated for a circuit *before* the Clifford+T step (high level, with ``mcx``, or
after :func:`circuitgen.lowering.lower_mcx`):

1. **Toffoli = 7 T.** Every Toffoli left after multi-controlled-X lowering costs 7 T (the Nielsen-Chuang
   decomposition that :func:`circuitgen.lowering.lower_to_basis` uses has 4 ``t`` + 3 ``tdg``), so this equals the
   exact T count of the lowered circuit.
2. **Logical AND** (Gidney 2018, "Halving the cost of quantum addition", Quantum 2, 74): a Toffoli whose target
   is a clean ancilla (|0>) computes a temporary logical AND for 4 T; the mirror-image Toffoli that later
   returns that ancilla to |0> is replaced by an X-basis measurement and a classically controlled CZ, 0 T.
   In our circuits the pairs are (a) the compute and uncompute ladders of every clean-ancilla v-chain (the
   ``k - 2`` Toffolis into the ``work`` register, always mirrored inside one multi-controlled X), and (b) the
   Toffoli onto a ``logic`` temporary that holds 0 (the corner ``blocked`` bits and the output bit of an SBF
   logic network) together with its mirror in the network's uncompute half. Toffolis XOR-ing into a bit that
   already holds a value (the pattern bit, which starts at 1 and collects three terms) stay 7 T.
3. **Rotation synthesis**: each arbitrary-angle RZ (symbolic, or not a multiple of pi/4) is approximated to
   precision epsilon with about ``3 log2(1/epsilon) + O(log log(1/epsilon))`` T gates (Ross & Selinger,
   "Optimal ancilla-free Clifford+T approximation of z-rotations", Quantum Inf. Comput. 16, 901 (2016),
   arXiv:1403.2975: "In the typical case, this yields circuit approximations of T-count
   3 log_2(1/epsilon) + O(log(log(1/epsilon)))"). We use the leading term ``ceil(3 log2(1/epsilon))`` and
   omit the O(log log) term (model ``ross-selinger``); model ``selinger`` uses the earlier bound
   ``4 log2(1/epsilon) + 10`` ("T-count K + 4 log2(1/epsilon), where K is approximately equal to 10",
   Selinger, "Efficient Clifford+T approximation of single-qubit operators", Quantum Inf. Comput. 15, 159
   (2015), arXiv:1212.6253). An RZ whose angle is an odd multiple of pi/4 is one T gate (up to Cliffords);
   a multiple of pi/2 is Clifford.

How compute/uncompute pairs are found: each ancilla (every qubit outside the ``data`` register) carries the
XOR of the AND terms written into it so far (a term = its controls' qubits, required values, X parity and, for
ancilla controls, their own contents). A Toffoli (or the target step of a multi-controlled X) into an ancilla
that holds nothing is an AND computation; one whose term is exactly what the ancilla holds is its
uncomputation. This is valid when the controls still have the same Boolean value at the uncompute, which our
mixers guarantee: the SBF flip that runs between compute and uncompute never changes the logic network's
values (that is why the network's uncompute returns the ancillas to |0>, which circuitgen's tests check).

Example:
    >>> from circuitgen.circuit import CircuitBuilder
    >>> from circuitgen.gates import mcx
    >>> b = CircuitBuilder([("data", 4), ("logic", 1)])
    >>> step = mcx([0, 1, 2, 3], 4, "0101")
    >>> b.append([step, step], section="m")   # compute into a clean bit, then uncompute it
    >>> ft = fault_tolerant_estimate(b.build(), epsilon=1e-3)
    >>> ft.toffoli, ft.and_compute, ft.and_uncompute, ft.toffoli_full
    (10, 5, 5, 0)
    >>> ft.t_toffoli7, ft.t_logical_and
    (70, 20)
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import asdict, dataclass
from operator import attrgetter
from typing import Any, Literal

from circuitgen.angles import Angle
from circuitgen.circuit import Circuit
from circuitgen.gates import GATE_SPECS
from circuitgen.lowering import lower

__all__ = [
    "SYNTHESIS_MODELS",
    "FaultTolerantEstimate",
    "RotationCount",
    "count_rotations",
    "fault_tolerant_estimate",
    "rotation_t_cost",
    "toffoli_roles",
]

SynthesisModel = Literal["ross-selinger", "selinger"]
SYNTHESIS_MODELS: tuple[SynthesisModel, ...] = ("ross-selinger", "selinger")
DEFAULT_EPSILON = 1e-3
T_PER_TOFFOLI = 7
T_PER_AND = 4

_ONE = ("one",)
# diagonal gates that are not permutations (rz, rzz, t, ...) never change a computational basis value
_PASSIVE = frozenset(n for n, spec in GATE_SPECS.items() if spec.diagonal and not spec.permutation)


def rotation_t_cost(epsilon: float, model: SynthesisModel = "ross-selinger") -> int:
    """T gates to approximate one arbitrary-angle RZ to precision ``epsilon`` (see the module docstring).

    Args:
        epsilon: target precision, ``0 < epsilon < 1``.
        model: ``ross-selinger`` (``ceil(3 log2(1/epsilon))``) or ``selinger`` (``ceil(4 log2(1/epsilon)) + 10``).

    Returns:
        The T count per rotation.

    >>> rotation_t_cost(1e-3), rotation_t_cost(1e-10), rotation_t_cost(1e-3, "selinger")
    (30, 100, 50)
    """
    if not 0.0 < epsilon < 1.0:
        raise ValueError(f"epsilon must be in (0, 1), got {epsilon!r}")
    bits = math.log2(1.0 / epsilon)
    if model == "ross-selinger":
        return math.ceil(3.0 * bits - 1e-9)
    if model == "selinger":
        return math.ceil(4.0 * bits - 1e-9) + 10
    raise ValueError(f"unknown synthesis model {model!r} (expected one of {SYNTHESIS_MODELS})")


@dataclass(frozen=True)
class ToffoliRoles:
    """Toffolis (after multi-controlled-X lowering) by their role for the logical-AND construction.

    Attributes:
        and_compute: Toffolis computing an AND into a clean ancilla (4 T each).
        and_uncompute: their mirror images (0 T each, measurement-based).
        full: every other Toffoli (7 T each).
    """

    and_compute: int
    and_uncompute: int
    full: int

    @property
    def total(self) -> int:
        """All Toffolis."""
        return self.and_compute + self.and_uncompute + self.full


def toffoli_roles(circuit: Circuit) -> ToffoliRoles:
    """Classify the Toffolis that :func:`circuitgen.lowering.lower_mcx` would produce (see the module docstring).

    Args:
        circuit: a circuit before the Clifford+T step (``mcx``/``ccx``/``cx``/``x`` and any other gates).

    Returns:
        The :class:`ToffoliRoles`; ``total`` equals the ``ccx`` count of ``lower_mcx(circuit)``.

    >>> from circuitgen.circuit import CircuitBuilder
    >>> from circuitgen.gates import ccx, x
    >>> b = CircuitBuilder([("data", 2), ("logic", 1)])
    >>> b.append([x(2), ccx(0, 1, 2), ccx(0, 1, 2), x(2)], section="s")
    >>> toffoli_roles(b.build())   # the target is not clean: both are full Toffolis
    ToffoliRoles(and_compute=0, and_uncompute=0, full=2)
    """
    data = set(circuit.qubits_of("data")) if circuit.has_register("data") else set()
    state: dict[int, frozenset[Any]] = {}
    parity: dict[int, int] = {}
    dirty = 0
    compute = uncompute = full = 0
    empty: frozenset[Any] = frozenset()
    for g in circuit.gates:
        name = g[0]
        if name in _PASSIVE:
            continue
        qubits = g[1]
        spec = GATE_SPECS[name]
        if name == "x":
            q = qubits[0]
            parity[q] = parity.get(q, 0) ^ 1
            if q not in data:
                state[q] = state.get(q, empty) ^ {_ONE}
            continue
        if spec.permutation:  # cx, ccx, mcx
            controls, target = qubits[:-1], qubits[-1]
            ctrl_state = g[3] if g[3] is not None else "1" * len(controls)
            k = len(controls)
            if k >= 3:  # clean-ancilla v-chain: k - 2 ANDs into work qubits and their mirrors
                compute += k - 2
                uncompute += k - 2
            term = tuple(
                sorted(
                    (c, (bit == "1") ^ parity.get(c, 0), None if c in data else state.get(c, empty))
                    for c, bit in zip(controls, ctrl_state, strict=True)
                )
            )
            if target in data:
                if k >= 2:
                    full += 1
                continue
            held = state.get(target, empty)
            if k >= 2:
                if not held:
                    compute += 1
                elif held == {term}:
                    uncompute += 1
                else:
                    full += 1
            state[target] = held ^ {term}
            continue
        # Other gates: controls (first qubit of controlled gates) and diagonal gates keep basis values.
        touched = qubits[1:] if name in ("crz", "cry", "csbf") else qubits
        if spec.diagonal:
            continue
        for q in touched:
            if q not in data:
                dirty += 1
                state[q] = frozenset({("dirty", dirty)})
    return ToffoliRoles(compute, uncompute, full)


@dataclass(frozen=True)
class RotationCount:
    """Single-qubit Z rotations of a lowered circuit by synthesis cost.

    Attributes:
        arbitrary: RZ with a symbolic angle or one that is not a multiple of pi/4.
        t_like: RZ by an odd multiple of pi/4 (one T up to Cliffords).
        clifford: RZ by a multiple of pi/2.
    """

    arbitrary: int
    t_like: int
    clifford: int


_is_bound = attrgetter("is_bound")


def _angle_class(theta: object) -> str:
    if isinstance(theta, Angle):
        if not theta.is_bound:
            return "arbitrary"
        theta = theta.constant
    quarters = float(theta) / (math.pi / 4)  # type: ignore[arg-type]
    nearest = round(quarters)
    if abs(quarters - nearest) > 1e-9:
        return "arbitrary"
    return "clifford" if nearest % 2 == 0 else "t_like"


def count_rotations(gates: Iterable[tuple[Any, ...]]) -> RotationCount:
    """Classify the ``rz`` gates of a lowered gate sequence.

    Args:
        gates: gate tuples; only ``rz`` gates are looked at.

    Returns:
        The :class:`RotationCount`.

    >>> count_rotations([("rz", (0,), (math.pi / 2,)), ("rz", (0,), (math.pi / 4,)), ("rz", (1,), (0.1,))])
    RotationCount(arbitrary=1, t_like=1, clifford=1)
    """
    angles = [g[2][0] for g in gates if g[0] == "rz"]
    symbolic = [a for a in angles if type(a) is Angle]
    unbound = len(symbolic) - sum(map(_is_bound, symbolic))
    counts = {"arbitrary": unbound, "t_like": 0, "clifford": 0}
    if unbound < len(angles):
        for a in angles:
            if not (type(a) is Angle and not a.is_bound):
                counts[_angle_class(a)] += 1
    return RotationCount(**counts)


@dataclass(frozen=True)
class FaultTolerantEstimate:
    """Clifford+T estimates (labelled as estimates; the exact counts are in :class:`~estimators.counts.ResourceCount`).

    Attributes:
        toffoli: Toffolis after multi-controlled-X lowering.
        and_compute, and_uncompute, toffoli_full: their roles (see :func:`toffoli_roles`).
        explicit_t: ``t``/``tdg`` gates already present before the Clifford+T step.
        rotations: arbitrary-angle RZ of the lowered circuit.
        t_like_rotations: RZ by odd multiples of pi/4.
        epsilon: synthesis precision per rotation.
        synthesis: the rotation synthesis model.
        t_per_rotation: T gates per arbitrary rotation.
        t_toffoli7: T count of the logic with Toffoli = 7 T (plus explicit and pi/4 T gates).
        t_logical_and: the same with logical-AND compute = 4 T and uncompute = 0 T.
        t_rotations: ``rotations * t_per_rotation``.
        total_t_toffoli7: ``t_toffoli7 + t_rotations``.
        total_t_logical_and: ``t_logical_and + t_rotations``.
    """

    toffoli: int
    and_compute: int
    and_uncompute: int
    toffoli_full: int
    explicit_t: int
    rotations: int
    t_like_rotations: int
    epsilon: float
    synthesis: str
    t_per_rotation: int
    t_toffoli7: int
    t_logical_and: int
    t_rotations: int
    total_t_toffoli7: int
    total_t_logical_and: int

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return asdict(self)


def fault_tolerant_estimate(
    circuit: Circuit,
    lowered: Circuit | None = None,
    epsilon: float = DEFAULT_EPSILON,
    synthesis: SynthesisModel = "ross-selinger",
) -> FaultTolerantEstimate:
    """Clifford+T estimates of ``circuit`` (see the module docstring).

    Args:
        circuit: the circuit before the Clifford+T step (e.g. ``qaoa_circuit(...)``).
        lowered: ``lower(circuit)`` if already at hand (its ``rz`` gates are the rotations); computed if None.
        epsilon: synthesis precision per rotation.
        synthesis: rotation synthesis model (:func:`rotation_t_cost`).

    Returns:
        The :class:`FaultTolerantEstimate`.
    """
    roles = toffoli_roles(circuit)
    explicit_t = sum(1 for g in circuit.gates if g[0] in ("t", "tdg"))
    if lowered is None:
        lowered = lower(circuit)
    rot = count_rotations(lowered.gates)
    per_rot = rotation_t_cost(epsilon, synthesis)
    extra = explicit_t + rot.t_like
    t7 = T_PER_TOFFOLI * roles.total + extra
    t_and = T_PER_AND * roles.and_compute + T_PER_TOFFOLI * roles.full + extra
    t_rot = rot.arbitrary * per_rot
    return FaultTolerantEstimate(
        toffoli=roles.total,
        and_compute=roles.and_compute,
        and_uncompute=roles.and_uncompute,
        toffoli_full=roles.full,
        explicit_t=explicit_t,
        rotations=rot.arbitrary,
        t_like_rotations=rot.t_like,
        epsilon=epsilon,
        synthesis=synthesis,
        t_per_rotation=per_rot,
        t_toffoli7=t7,
        t_logical_and=t_and,
        t_rotations=t_rot,
        total_t_toffoli7=t7 + t_rot,
        total_t_logical_and=t_and + t_rot,
    )
