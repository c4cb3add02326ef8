"""Resource estimates of one QAOA circuit from its gadgets' costs, without building a gate list.

:func:`estimate_point` asks the circuit's plan (:func:`circuitgen.qaoa.qaoa_plan`) what it costs: every gadget
reports its lowered cost and its logical cost (ANDs and Toffolis kept whole) without emitting a gate, and the
plan sums them over its call graph. Layers are alike up to their angles, so the cost of ``p`` layers is
``initial state + p * (phase separator + mixer)``: one plan with ``p = 1`` serves every ``p``
(:meth:`circuitgen.qaoa.QaoaPlan.cost_by_section`), and :class:`LayerCosts` is cached per scenario and options.
:mod:`estimators.crosscheck` (run by the tests and ``benchmarks/estimate_speed.py``) checks that these numbers
equal the counts of the compiled, lowered circuit (:func:`estimators.counts.count`).

Depth cannot be summed exactly (ASAP layering overlaps consecutive pieces), so it is either

* ``exact``: computed on the compiled circuit (built from the plan's gadgets, lowered and layered), when the
  circuit has at most ``depth_budget`` gates (``depth="auto"``, the default) or when asked (``depth="exact"``);
* ``bound``: an upper bound, the sum over the circuit's gadgets of each gadget's own depth (computed once per
  partial-mixer kind on its lowered gates, a kind being the whole program; each phase gadget's own; a gadget of
  more than :data:`GADGET_DEPTH_LIMIT` gates counts its gate numbers instead), which ASAP layering can only
  shorten;
* absent (``depth="none"``).

The row says which (``depth_kind``); nothing is silently estimated.

Example:
    >>> from estimators.estimate import EstimateOptions, Point, estimate_point
    >>> est = estimate_point(Point(2, 2, 1, 1))
    >>> est.qubits, est.depth.kind
    (4, 'exact')
"""

from __future__ import annotations

import json
import time
from collections.abc import Hashable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from typing import Any, Literal

from circuitgen.circuit import Circuit, Register, Section
from circuitgen.cost import Cost
from circuitgen.gadgets.junction import MixerJunction, MixerRotation
from circuitgen.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer
from circuitgen.lowering import lower
from circuitgen.qaoa import qaoa_plan
from gridcover.presets import default_scenario
from gridcover.scenario import Scenario, scenario_from_dict, scenario_to_dict

from .depth import Depth, depths
from .fault_tolerant import DEFAULT_EPSILON, FaultTolerantEstimate, SynthesisModel, fault_tolerant_from_cost
from .mixer_count import mixer_layer
from .phase_count import phase_layer
from .physical import (
    DEFAULT_ERROR_BUDGET,
    DEFAULT_QEC_SCHEME,
    DEFAULT_QUBIT_MODEL,
    LogicalCounts,
    PhysicalEstimate,
    physical_estimate,
)

__all__ = [
    "DEFAULT_DEPTH_BUDGET",
    "DEFAULT_OPTIONS",
    "DEFAULT_PLAN",
    "DEPTH_MODES",
    "GADGET_DEPTH_LIMIT",
    "DepthMode",
    "Estimate",
    "EstimateOptions",
    "LayerCosts",
    "PlanOptions",
    "Point",
    "estimate_point",
    "layer_costs",
    "registers_for",
]

DepthMode = Literal["auto", "exact", "bound", "none"]
DEPTH_MODES: tuple[DepthMode, ...] = ("auto", "exact", "bound", "none")
DEFAULT_DEPTH_BUDGET = 300_000
"""``depth="auto"`` compiles the circuit for its exact depth up to this many lowered gates (about 1 s)."""
GADGET_DEPTH_LIMIT = 50_000
"""A gadget with more lowered gates than this contributes its gate counts to a depth bound (not its layering)."""


@dataclass(frozen=True)
class PlanOptions:
    """How the circuit is built (the keyword options of :func:`circuitgen.qaoa.qaoa_plan`)."""

    rule: str = "exact"
    initial: str = "initial_path"
    target: str = "nisq"
    phase: str = "feasible"
    optimize: str = "cx"
    ancilla_budget: int | None = None

    def plan(self, scenario: Scenario, p: int) -> Any:
        """The plan of ``scenario`` with ``p`` layers."""
        return qaoa_plan(
            scenario,
            p,
            rule=self.rule,  # type: ignore[arg-type]
            initial=self.initial,
            target=self.target,  # type: ignore[arg-type]
            phase=self.phase,  # type: ignore[arg-type]
            optimize=self.optimize,  # type: ignore[arg-type]
            ancilla_budget=self.ancilla_budget,
        )


def gadget_blocks(gadget: Any) -> list[Sequence[Any]]:
    """A gadget's gates as the sections the circuit gives it (``emit_blocks()`` if it has them, else one)."""
    blocks = getattr(gadget, "emit_blocks", None)
    return list(blocks()) if blocks is not None else [gadget.emit()]


def plan_sections(plan: Any, registers: Sequence[Register], lowered: bool) -> Iterator[Section]:
    """The sections of a plan's circuit, one gadget at a time (lowered one by one if asked, which equals lowering
    the whole circuit: passes never cross sections and ``registers`` already hold the ``work`` register)."""
    for name, gadget in plan.sections():
        secs = [Section(name, tuple(b)) for b in gadget_blocks(gadget)]
        if lowered:
            secs = list(lower(Circuit(registers, secs)).sections)
        yield from secs


@dataclass(frozen=True)
class EstimateOptions:
    """What to estimate beyond the exact counts.

    Attributes:
        plan: circuit construction options.
        epsilon, synthesis, toffoli_t: the fault-tolerant model (:mod:`estimators.fault_tolerant`).
        depth: ``auto``, ``exact``, ``bound`` or ``none`` (see the module docstring).
        depth_budget: largest circuit (lowered gates) whose depth ``auto`` computes exactly.
        physical: run the QDK resource estimator (:mod:`estimators.physical`).
        qubit_model, qec_scheme, error_budget: its model.
    """

    plan: PlanOptions = field(default_factory=PlanOptions)
    epsilon: float = DEFAULT_EPSILON
    synthesis: SynthesisModel = "ross-selinger"
    toffoli_t: int = 7
    depth: DepthMode = "auto"
    depth_budget: int = DEFAULT_DEPTH_BUDGET
    physical: bool = False
    qubit_model: str = DEFAULT_QUBIT_MODEL
    qec_scheme: str = DEFAULT_QEC_SCHEME
    error_budget: float = DEFAULT_ERROR_BUDGET


DEFAULT_PLAN = PlanOptions()
DEFAULT_OPTIONS = EstimateOptions()


@dataclass(frozen=True)
class Point:
    """One circuit: the default scenario of a grid and robot count (or a given scenario) with ``p`` layers.

    Attributes:
        rows, cols, robots: the grid and robot count.
        p: QAOA layers.
        scenario: canonical JSON of a given scenario, or ``None`` for :func:`gridcover.presets.default_scenario`.
    """

    rows: int
    cols: int
    robots: int
    p: int
    scenario: str | None = None

    def build_scenario(self) -> Scenario:
        """The scenario of this point."""
        if self.scenario is not None:
            return _scenario_from_json(self.scenario)
        return _default(self.rows, self.cols, self.robots)

    @classmethod
    def from_scenario(cls, scenario: Scenario, p: int) -> Point:
        """A point for a given scenario."""
        text = json.dumps(scenario_to_dict(scenario), sort_keys=True)
        g = scenario.grid
        return cls(g.rows, g.cols, scenario.num_robots, p, text)

    @property
    def label(self) -> str:
        """Short text such as ``3x4 r2 p1``."""
        return f"{self.rows}x{self.cols} r{self.robots} p{self.p}" + ("" if self.scenario is None else " (file)")


@lru_cache(maxsize=64)
def _default(rows: int, cols: int, robots: int) -> Scenario:
    return default_scenario(rows, cols, robots)


@lru_cache(maxsize=64)
def _scenario_from_json(text: str) -> Scenario:
    return scenario_from_dict(json.loads(text))


def _minus(a: Cost, b: Cost) -> Cost:
    """``a - b`` for costs with ``b <= a`` name by name."""
    out = a.to_dict()
    for k, v in b.items:
        out[k] = out.get(k, 0) - v
        if out[k] < 0:
            raise ArithmeticError(f"cost of one layer is negative for {k!r}: the plan is not linear in p")
    return Cost.of(out)


@dataclass(frozen=True)
class LayerCosts:
    """What one scenario costs, independent of ``p`` (from one plan with ``p = 1``).

    Attributes:
        registers: ``(name, size)`` of the registers for ``p >= 1`` (``work`` included; with ``p = 0`` there is
            no mixer and the ``work`` register may be smaller: :func:`estimate_point` asks a ``p = 0`` plan).
        sections: lowered costs of ``initial_state`` and of one layer's ``phase`` and ``mixer``.
        logical: the same with ANDs and Toffolis kept whole.
    """

    registers: tuple[tuple[str, int], ...]
    sections: Mapping[str, Cost]
    logical: Mapping[str, Cost]

    def cost(self, p: int) -> Cost:
        """Lowered cost of ``p`` layers."""
        return _total(self.sections, p, self._layer)

    def logical_cost(self, p: int) -> Cost:
        """Logical cost of ``p`` layers."""
        return _total(self.logical, p, self._logical_layer)

    @cached_property
    def _layer(self) -> Cost:
        return self.sections.get("phase", Cost()) + self.sections.get("mixer", Cost())

    @cached_property
    def _logical_layer(self) -> Cost:
        return self.logical.get("phase", Cost()) + self.logical.get("mixer", Cost())


def _total(parts: Mapping[str, Cost], p: int, layer: Cost) -> Cost:
    return parts.get("initial_state", Cost()) + p * layer


def _layout(plan: Any) -> tuple[tuple[str, int], ...]:
    return tuple((r.name, r.size) for r in plan.registers)


@lru_cache(maxsize=16)
def _plan1(scenario: Scenario, options: PlanOptions) -> Any:
    """One layer's plan, shared by the costs and the depth bound (its phase plan is the expensive part)."""
    return options.plan(scenario, 1)


@lru_cache(maxsize=256)
def layer_costs(scenario: Scenario, options: PlanOptions = DEFAULT_PLAN) -> LayerCosts:
    """The :class:`LayerCosts` of a scenario (cached: a sweep over ``p`` asks once).

    On a grid without obstacles the mixer's cost comes from :func:`estimators.mixer_count.mixer_layer`
    (signature counting, ``O(robots)``), the state preparation's and the phase separator's from the plan's own
    gadgets; otherwise from :meth:`circuitgen.qaoa.QaoaPlan.cost_by_section`. Both agree
    (``tests/estimators/mixer_count_test.py``).

    Args:
        scenario: the scenario.
        options: circuit construction options.

    Returns:
        The layer costs.
    """
    plan1 = _plan1(scenario, options)
    if scenario.obstacles:
        keys = ("initial_state", "phase", "mixer")
        lowered, logical = plan1.cost_by_section(), plan1.cost_by_section(logical=True)
        return LayerCosts(
            registers=_layout(plan1),
            sections={k: lowered[k] for k in keys if k in lowered},
            logical={k: logical[k] for k in keys if k in logical},
        )
    mixer = mixer_layer(scenario, options.rule, options.target)
    # the phase separator by classes where that is exact, else the plan's own (built apart from its partial mixers)
    phase = phase_layer(scenario, options.target, options.phase, options.optimize, options.ancilla_budget)
    if phase is None:
        phase = plan1.phase_plan
    if options.initial == "initial_path":
        # on a grid without obstacles each robot's initial path is the L-shaped path (feasible), prepared by one
        # X per edge: its length is the Manhattan distance (the tests compare with the plan's StatePrep)
        steps = sum(abs(rb.goal[0] - rb.start[0]) + abs(rb.goal[1] - rb.start[1]) for rb in scenario.robots)
        prep_cost = prep_logical = Cost.of(x=steps)
        prep_work = 0
    else:
        prep = plan1.state_prep
        prep_cost, prep_logical, prep_work = prep.cost(), prep.logical_cost(), _prep_work(prep)
    return LayerCosts(
        registers=_registers(
            scenario, options, max(mixer.logic_width, phase.num_ancillas), max(mixer.work_need, prep_work)
        ),
        sections={"initial_state": prep_cost, "phase": phase.cost(), "mixer": mixer.cost},
        logical={"initial_state": prep_logical, "phase": phase.logical_cost(), "mixer": mixer.logical},
    )


def _prep_work(prep: Any) -> int:
    return max((len(g.qubits) - 3 for g in prep.gates if g.name == "mcx"), default=0)


def _registers(scenario: Scenario, options: PlanOptions, logic: int, work: int) -> tuple[tuple[str, int], ...]:
    """The layout :attr:`circuitgen.qaoa.QaoaPlan.registers` gives: ``data``, ``logic``, ``work`` (non-empty)."""
    logic = max(logic, 1 if options.initial == "representatives" else 0)
    regs = [("data", scenario.num_variables), ("logic", logic), ("work", work)]
    return tuple(r for r in regs if r[0] == "data" or r[1])


@lru_cache(maxsize=64)
def _registers0(scenario: Scenario, options: PlanOptions) -> tuple[tuple[str, int], ...]:
    if scenario.obstacles:
        return _layout(options.plan(scenario, 0))
    mixer = mixer_layer(scenario, options.rule, options.target)
    # p = 0: no phase separator (its ancillas are not needed), the partial mixers still size the logic register
    return _registers(scenario, options, mixer.logic_width, _prep_work(options.plan(scenario, 0).state_prep))


def registers_for(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> tuple[tuple[str, int], ...]:
    """``(name, size)`` of the lowered circuit's registers with ``p`` layers (no gate is built)."""
    return layer_costs(scenario, options).registers if p else _registers0(scenario, options)


@dataclass(frozen=True)
class Estimate:
    """Counts and estimates of one point.

    Attributes:
        point: the point.
        options: the options used.
        registers: ``(name, size)`` of every register.
        cost: lowered gate counts (exact).
        logical: logical gate counts (ANDs and Toffolis whole; exact).
        sections: per-layer lowered costs (``initial_state``, ``phase``, ``mixer``).
        depth: the depths, exact or a bound, or ``None``.
        fault_tolerant: logical-AND model T counts.
        physical: QDK estimator figures, or ``None``.
        seconds: wall-clock seconds spent on this point (excluding cached layer costs).
    """

    point: Point
    options: EstimateOptions
    registers: tuple[tuple[str, int], ...]
    cost: Cost
    logical: Cost
    sections: Mapping[str, Cost]
    depth: Depth | None
    fault_tolerant: FaultTolerantEstimate
    physical: PhysicalEstimate | None
    seconds: float

    @property
    def qubits(self) -> int:
        """All qubits."""
        return sum(size for _, size in self.registers)

    @property
    def data_qubits(self) -> int:
        """The ``data`` register."""
        return sum(size for name, size in self.registers if name == "data")

    @property
    def logical_counts(self) -> LogicalCounts:
        """The physical estimator's input (rotation depth: this estimate's, or the rotation count if none)."""
        rot_depth = self.depth.rotation_depth if self.depth is not None else self.logical.rotations
        return LogicalCounts(
            num_qubits=self.qubits,
            t_count=self.logical.t,
            rotation_count=self.logical.rotations,
            rotation_depth=rot_depth,
            ccz_count=self.logical["ccx"],
            ccix_count=self.logical["and"],
            measurement_count=self.logical["and_dg"] + self.data_qubits,
        )


def _compiled(scenario: Scenario, p: int, options: PlanOptions) -> Circuit:
    """The circuit built from the plan's gadgets, lowered."""
    plan = options.plan(scenario, p)
    registers = tuple(plan.registers)
    return Circuit(registers, list(plan_sections(plan, registers, lowered=True)))


def exact_depth(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Depth:
    """Depths of the compiled, lowered circuit (builds it: mind its size)."""
    circ = _compiled(scenario, p, options)
    return depths(circ.gates, circ.num_qubits)


def _gadget_depth(name: str, gadget: Any, registers: tuple[Register, ...], cache: dict[Hashable, Depth]) -> Depth:
    """One gadget's own depths (lowered alone), cached by kind where the kind is the whole construction up to the
    qubits: partial mixers (their program), mixer junctions and rotations, and the arithmetic and visit-bit phase
    gadgets (their weights and products). The Ising phase gadget's kind holds only its term counts (two coupling
    graphs of one size can layer differently), so its depth is computed each time."""
    kind = gadget.kind
    cacheable = isinstance(gadget, ParityPartialMixer | McxPartialMixer | MixerJunction | MixerRotation) or (
        isinstance(kind, tuple) and bool(kind) and kind[0] in _STRUCTURAL_PHASE_KINDS
    )
    hit = cache.get(kind) if cacheable else None
    if hit is None:
        c = gadget.cost()
        if c.total > GADGET_DEPTH_LIMIT:
            hit = Depth(c.total, c.two_qubit, c.rotations, "bound")
        else:
            secs = [Section(name, tuple(b)) for b in gadget_blocks(gadget)]
            circ = lower(Circuit(registers, secs))
            hit = depths(circ.gates, circ.num_qubits)
        if cacheable:
            cache[kind] = hit
    return hit


_STRUCTURAL_PHASE_KINDS = frozenset({"sums", "sums-register", "sums-accumulate", "visits"})
_DEPTH_BY_KIND: dict[Hashable, Depth] = {}
"""Depth of one partial mixer per kind, shared by every scenario (see :func:`_gadget_depth`)."""


@lru_cache(maxsize=256)
def _layer_depth_bounds(scenario: Scenario, options: PlanOptions) -> tuple[Depth, Depth]:
    """Depth bounds of the state preparation and of one layer: sums of per-gadget depths (per signature count
    for the mixer of a grid without obstacles, :mod:`estimators.mixer_count`)."""
    plan = _plan1(scenario, options)
    regs = tuple(Register(name, size) for name, size in layer_costs(scenario, options).registers)
    cache = _DEPTH_BY_KIND
    if not scenario.obstacles:
        init = _gadget_depth("initial_state", plan.state_prep, regs, cache)
        layer = Depth()
        for gadget in plan.phase_plan.gadgets("gamma_0", 0, scenario.num_variables):
            layer = layer + _gadget_depth("phase_0", gadget, regs, cache)
        mixer = mixer_layer(scenario, options.rule, options.target)
        for gadget, n in mixer.gadgets(scenario, options.rule, options.target):
            layer = layer + n * _gadget_depth("mixer_0", gadget, regs, cache)
        return init, layer
    init, layer = Depth(), Depth()
    for name, gadget in plan.sections():
        d = _gadget_depth(name, gadget, regs, cache)
        if name == "initial_state":
            init = init + d
        else:
            layer = layer + d
    return init, layer


def depth_bound(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Depth:
    """An upper bound on the depths of ``p`` layers: the sum over gadgets of their own depths.

    >>> from gridcover.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> depth_bound(s, 2).depth >= exact_depth(s, 2).depth
    True
    """
    init, layer = _layer_depth_bounds(scenario, options)
    d = init + p * layer
    return Depth(d.depth, d.two_qubit_depth, d.rotation_depth, "bound")


def estimate_point(point: Point, options: EstimateOptions = DEFAULT_OPTIONS) -> Estimate:
    """Counts and estimates of one point (see the module docstring).

    Args:
        point: the point.
        options: what to estimate and how.

    Returns:
        The :class:`Estimate`.

    Raises:
        gridcover.errors.ScenarioError: the grid cannot host the robots.
        estimators.physical.PhysicalEstimateError: the physical estimator refused the counts.
    """
    start = time.perf_counter()
    scenario = point.build_scenario()
    lc = layer_costs(scenario, options.plan)
    p = point.p
    cost = lc.cost(p)
    logical = lc.logical_cost(p)
    mode = options.depth
    if mode == "auto":
        mode = "exact" if cost.total <= options.depth_budget else "bound"
    depth: Depth | None = None
    if mode == "exact":
        depth = exact_depth(scenario, p, options.plan)
    elif mode == "bound":
        depth = depth_bound(scenario, p, options.plan)
    ft = fault_tolerant_from_cost(logical, options.epsilon, options.synthesis, options.toffoli_t)
    registers = registers_for(scenario, p, options.plan)
    est = Estimate(point, options, registers, cost, logical, lc.sections, depth, ft, None, 0.0)
    phys = None
    if options.physical:
        phys = physical_estimate(est.logical_counts, options.qubit_model, options.qec_scheme, options.error_budget)
    return Estimate(
        point, options, est.registers, cost, logical, lc.sections, depth, ft, phys, time.perf_counter() - start
    )
