"""Fault-tolerant (Clifford+T) estimates from a circuit's logical cost, labelled as estimates.

The input is a *logical cost* (:meth:`qcpp.gadgets.Gadget.logical_cost`, or
``Cost.count(lower(circuit, basis=LOGICAL_BASIS).gates)``): the lowered gate counts with ``and``, ``and_dg`` and
``ccx`` kept whole. The model (the **logical-AND model**):

1. **AND compute = 4 T.** An ``and`` computes ``a AND b`` into a clean ancilla (Gidney 2018, "Halving the cost of
   quantum addition", Quantum 2, 74: a temporary logical AND for 4 T).
2. **AND uncompute = 0 T.** Its mirror ``and_dg`` is done by an X-basis measurement and a classically
   controlled CZ (Gidney 2018): one measurement, no T. (The gate-level circuit that ``qcpp compile`` emits
   implements it unitarily, 4 T, which the exact ``t`` column counts.)
3. **Full Toffoli** (``ccx``, the target holds data) = **7 T** by default, the T-optimal ancilla-free Clifford+T
   circuit (Amy, Maslov, Mosca, Roetteler 2013, "A meet-in-the-middle algorithm for fast synthesis of
   depth-optimal quantum circuits"; the decomposition :func:`qcpp.lowering.passes.lower_to_basis` uses), or
   **4 T** with ``toffoli_t=4`` (Jones 2013, "Low-overhead constructions for the fault-tolerant Toffoli gate",
   PRA 87, 022328: one ancilla and a measurement).
4. **Explicit ``t``/``tdg``** count 1 T each; ``s``, ``h``, ``cx``, ``x`` are Clifford (0 T).
5. **Rotations**: each ``rz`` (an arbitrary angle: Clifford and T phases are lowered to ``s``/``t``) costs
   ``ceil(3 log2(1/epsilon))`` T (model ``ross-selinger``, the leading term of Ross & Selinger,
   arXiv:1403.2975) or ``4 log2(1/epsilon) + 10`` (model ``selinger``, arXiv:1212.6253).

Example:
    >>> from qcpp.ir.cost import Cost
    >>> ft = fault_tolerant_from_cost(Cost.of({"and": 5, "and_dg": 5, "ccx": 2, "rz": 3, "t": 1}), epsilon=1e-3)
    >>> ft.t_logic, ft.t_rotations, ft.total_t, ft.measurements
    (35, 90, 125, 5)
    >>> fault_tolerant_from_cost(Cost.of(ccx=2), toffoli_t=4).t_logic
    8
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from qcpp.ir.cost import Cost

__all__ = [
    "DEFAULT_EPSILON",
    "SYNTHESIS_MODELS",
    "TOFFOLI_T_CHOICES",
    "FaultTolerantEstimate",
    "SynthesisModel",
    "fault_tolerant_from_cost",
    "rotation_t_cost",
]

SynthesisModel = Literal["ross-selinger", "selinger"]
SYNTHESIS_MODELS: tuple[SynthesisModel, ...] = ("ross-selinger", "selinger")
DEFAULT_EPSILON = 1e-3
T_PER_AND = 4
TOFFOLI_T_CHOICES: tuple[int, ...] = (7, 4)
"""T per full Toffoli: 7 (ancilla-free, the default) or 4 (Jones 2013, with an ancilla and a measurement)."""


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
class FaultTolerantEstimate:
    """Clifford+T estimates in the logical-AND model (labelled as estimates; exact counts live elsewhere).

    Attributes:
        and_compute: ``and`` gates (4 T each).
        and_uncompute: ``and_dg`` gates (measurement-based, 0 T).
        toffoli_full: ``ccx`` gates (``toffoli_t`` T each).
        explicit_t: ``t``/``tdg`` gates.
        rotations: arbitrary-angle ``rz`` gates.
        measurements: measurement-based uncomputes (``and_dg``); the final read-out is not included.
        epsilon: synthesis precision per rotation.
        synthesis: rotation synthesis model.
        toffoli_t: T per full Toffoli (7 or 4).
        t_per_rotation: T per rotation.
        t_logic: ``4 and_compute + toffoli_t toffoli_full + explicit_t``.
        t_rotations: ``rotations * t_per_rotation``.
        total_t: ``t_logic + t_rotations``.
    """

    and_compute: int
    and_uncompute: int
    toffoli_full: int
    explicit_t: int
    rotations: int
    measurements: int
    epsilon: float
    synthesis: str
    toffoli_t: int
    t_per_rotation: int
    t_logic: int
    t_rotations: int
    total_t: int

    @property
    def toffoli(self) -> int:
        """ANDs and full Toffolis (every three-qubit gate of the logical circuit)."""
        return self.and_compute + self.and_uncompute + self.toffoli_full


def fault_tolerant_from_cost(
    logical: Cost,
    epsilon: float = DEFAULT_EPSILON,
    synthesis: SynthesisModel = "ross-selinger",
    toffoli_t: int = 7,
) -> FaultTolerantEstimate:
    """The logical-AND model's T counts of a logical cost (see the module docstring).

    Args:
        logical: gate counts with ``and``/``and_dg``/``ccx`` kept whole (a gadget's or plan's ``logical_cost()``).
        epsilon: synthesis precision per rotation.
        synthesis: rotation synthesis model (:func:`rotation_t_cost`).
        toffoli_t: T per full Toffoli, 7 or 4.

    Raises:
        ValueError: a bad ``epsilon``, ``synthesis`` or ``toffoli_t``.
    """
    if toffoli_t not in TOFFOLI_T_CHOICES:
        raise ValueError(f"toffoli_t must be one of {TOFFOLI_T_CHOICES}, got {toffoli_t!r}")
    per_rot = rotation_t_cost(epsilon, synthesis)
    ands, undo, full = logical["and"], logical["and_dg"], logical["ccx"]
    explicit = logical.t
    t_logic = T_PER_AND * ands + toffoli_t * full + explicit
    t_rot = logical.rotations * per_rot
    return FaultTolerantEstimate(
        and_compute=ands,
        and_uncompute=undo,
        toffoli_full=full,
        explicit_t=explicit,
        rotations=logical.rotations,
        measurements=undo,
        epsilon=epsilon,
        synthesis=synthesis,
        toffoli_t=toffoli_t,
        t_per_rotation=per_rot,
        t_logic=t_logic,
        t_rotations=t_rot,
        total_t=t_logic + t_rot,
    )
