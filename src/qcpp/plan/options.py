"""How the QAOA circuit of a scenario is built: one frozen value, taken by every entry point.

:class:`PlanOptions` is the one description of the construction choices. :func:`qcpp.plan.qaoa.qaoa_plan`,
:func:`qcpp.plan.qaoa.qaoa_circuit`, :func:`qcpp.plan.compile.compile_scenario`, the estimators, the cross-check
and both CLIs (``qcpp compile`` and ``qcpp estimate``, which build it once from the same flags) take it, so an
option cannot be passed to one path and forgotten by another.

Example:
    >>> opts = PlanOptions(phase="whole-space", ancilla_budget=4)
    >>> opts.target, opts.phase, opts == PlanOptions(ancilla_budget=4, phase="whole-space")
    ('nisq', 'whole-space', True)
    >>> PlanOptions(rule="fast")
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: rule: expected exact or paper, got 'fast'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from qcpp.errors import OptionError, choice_reason
from qcpp.gadgets.initial_state import INITIAL_STATES, Initial
from qcpp.ir.cost import TARGETS, Target
from qcpp.problem.sbf import RULES, Rule

__all__ = [
    "ANGLES", "DEFAULT_PLAN", "INITIAL_STATES", "LAYOUT_METHODS", "OPTIMIZE", "PHASES", "PHASE_LAYOUTS", "Angles",
    "Initial", "PhaseLayout", "PlanOptions",
]

Angles = Literal["layer", "multi"]
ANGLES: tuple[Angles, ...] = ("layer", "multi")
Phase = Literal["feasible", "whole-space"]
PHASES: tuple[Phase, ...] = ("feasible", "whole-space")
Optimize = Literal["cx", "depth"]
OPTIMIZE: tuple[Optimize, ...] = ("cx", "depth")
PhaseLayout = Literal["auto", "pooled", "spatial", "medial"]
PHASE_LAYOUTS: tuple[PhaseLayout, ...] = ("auto", "pooled", "spatial", "medial")
LAYOUT_METHODS = ("auto", "medial", "greedy")
"""How :func:`qcpp.pipeline.device_compile.compile_for_device` lays a circuit onto a device (here, not in hardware,
so that the CLI can check ``--layout`` without importing the router). ``medial``: the geometric layout of
:mod:`qcpp.layout.medial` with windows routed home (:func:`qcpp.routing.windows.route_windows`); ``greedy``:
:func:`qcpp.pipeline.device_compile.best_layout` and one SABRE routing of the whole circuit; ``auto``: medial where the
device is a square grid that holds it, else greedy; on such a grid a circuit of at most
:attr:`qcpp.routing.options.RoutingOptions.auto_compare_max_twoq` two-qubit gates is routed both ways and the fewer
two-qubit gates win."""


@dataclass(frozen=True, kw_only=True)
class PlanOptions:
    """The construction choices of one QAOA circuit (every field is checked on construction: a bad value raises
    :class:`~qcpp.errors.OptionError` naming the field). Keyword arguments only: a field added later cannot shift
    the others' values.

    Attributes:
        rule: SBF logic rule: ``exact`` (default) or ``paper``.
        initial: initial state: ``initial_path`` (default), ``representatives`` or ``local_search`` (the
            paths of a steepest descent over SBF moves, :mod:`qcpp.problem.solvers.descent`; a classical warm
            start) or ``local_search_mix`` (per robot the initial and the descent path in equal superposition)
            (:mod:`qcpp.gadgets.initial_state`).
        target: ``nisq`` (fewest CNOTs; default) or ``ft`` (fewest T and rotations): which constructions are
            cheapest (:mod:`qcpp.gadgets.partial_mixer`, :mod:`qcpp.plan.phase`).
        phase: phase separator: ``feasible`` (exact on feasible assignments; default) or ``whole-space`` (the
            Ising Hamiltonian).
        optimize: phase separator: ``cx`` (cheapest; default) or ``depth`` (shallow coupling layers).
        ancilla_budget: most ancillas the phase separator may use (``None``: as many as the cheapest needs).
        fuse: cut the parity-basis partial mixers at their rotations and fuse each uncompute with the next
            compute (:mod:`qcpp.gadgets.junction`; default). ``False`` keeps one section per partial mixer,
            clean at both ends (same high-level gates, a few more lowered ones); not a CLI flag.
        phase_layout: how the phase separator's gadgets sit on the grid: ``pooled`` (adders in variable order,
            node gadgets take the ancilla pool round robin; fewest CX all-to-all), ``spatial`` (star-shaped adders
            over neighbouring edges, node gadgets with nearby ancillas, 2 CX more per adder:
            :mod:`qcpp.plan.phase_layout`; fewer routed CX on grids and heavy-hex), ``medial`` (``spatial``
            with each robot's balance sums drifting to where the medial layout's robot patches meet:
            :func:`qcpp.plan.phase_layout.balance_sinks`; same gates and counts) or ``auto`` (default: the plan
            builds it as ``pooled``; a compile routed onto a device settles it for the device with
            :func:`qcpp.pipeline.device_plan.device_plan_options`).
        angles: the mixer's parameters: ``layer`` (default; one ``beta_k`` per layer) or ``multi`` (multi-angle
            QAOA: one beta per partial mixer and layer, :func:`qcpp.ir.angles.mixer_symbol`). Same gates and
            counts, only the symbols differ (``--mixer-angles`` of compile and estimate).
        first_phase: build the first layer's phase separator (default). ``False`` omits it (``--skip-first-phase``):
            the circuit is the state preparation, ``mixer_0``, then ``phase_k`` and ``mixer_k`` for ``k = 1..p-1``.
            Exact only from a basis state, where ``exp(-i gamma_0 C)`` is a global phase
            (``docs/paper-notes.md``); :func:`qcpp.plan.qaoa.qaoa_plan` refuses a start that is a superposition.
            ``gamma_0`` stays a parameter name with no gate. Not the default: the paper's circuit has ``p``
            phase separators, and the tables compare like for like with it.
    """

    rule: Rule = "exact"
    initial: Initial = "initial_path"
    target: Target = "nisq"
    phase: Phase = "feasible"
    optimize: Optimize = "cx"
    ancilla_budget: int | None = None
    fuse: bool = True
    phase_layout: PhaseLayout = "auto"
    angles: Angles = "layer"
    first_phase: bool = True

    def __post_init__(self) -> None:
        for name, allowed in (
            ("rule", RULES), ("initial", INITIAL_STATES), ("target", TARGETS), ("phase", PHASES),
            ("optimize", OPTIMIZE), ("phase_layout", PHASE_LAYOUTS), ("angles", ANGLES),
        ):  # fmt: skip
            value = getattr(self, name)
            if value not in allowed:
                raise OptionError(name, choice_reason(value, allowed))
        budget = self.ancilla_budget
        if budget is not None and (not isinstance(budget, int) or isinstance(budget, bool) or budget < 0):
            raise OptionError("ancilla_budget", f"expected an integer >= 0, got {budget!r}")
        if not isinstance(self.fuse, bool):
            raise OptionError("fuse", f"expected True or False, got {self.fuse!r}")
        if not isinstance(self.first_phase, bool):
            raise OptionError("first_phase", f"expected True or False, got {self.first_phase!r}")

    def phase_layers(self, p: int) -> int:
        """How many phase separators a circuit of ``p`` layers has: ``p``, or ``p - 1`` without the first.

        Example:
            >>> PlanOptions().phase_layers(3), PlanOptions(first_phase=False).phase_layers(3)
            (3, 2)
            >>> PlanOptions(first_phase=False).phase_layers(0)
            0
        """
        return p if self.first_phase else max(p - 1, 0)


DEFAULT_PLAN = PlanOptions()
