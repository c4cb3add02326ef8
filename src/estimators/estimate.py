"""Resource estimates of one QAOA circuit from its gadgets' costs, without building a gate list.

:func:`estimate_point` asks the circuit's plan (:func:`circuitgen.qaoa.qaoa_plan`) what it costs: every gadget
reports its lowered cost and its logical cost (ANDs and Toffolis kept whole) without emitting a gate, and the
plan sums them over its call graph. Layers are alike up to their angles, so the cost of ``p`` layers is
``initial state + p * (phase separator + mixer)``: one plan with ``p = 1`` serves every ``p``
(:meth:`circuitgen.qaoa.QaoaPlan.cost_by_section`), and :class:`LayerCosts` is cached per scenario and options.
:mod:`estimators.crosscheck` (run by the tests and ``benchmarks/estimate_speed.py``) checks that these numbers
equal the counts of the compiled, lowered circuit (:func:`estimators.counts.count`).

Depth cannot be summed (ASAP layering overlaps consecutive pieces), so it is either

* ``exact``: composed gadget by gadget from max-plus transfer profiles (:mod:`estimators.depth_compose`, cached
  per gadget kind; equal to the depths of the compiled, lowered circuit, :func:`compiled_depth`, which the tests
  compare), with the frontier carried from ``p`` to ``p + 1`` (:func:`layered_depth`, cached per scenario);
  ``depth="auto"`` (the default) does this when the state preparation plus one layer has at most
  ``depth_budget`` lowered gates (the cost is building the profiles of one layer; each further layer costs a
  small fraction of that), ``depth="exact"`` at any size;
* ``bound``: an upper bound (:func:`depth_bound`): the state preparation's depth plus ``p`` times one layer's
  bound, the partial mixers' own depths (per signature) plus the phase separator's parts' own depths (per class;
  the balance arithmetic by its gate counts), in ``O(robots)`` per scenario;
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

from circuitgen.angles import Angle
from circuitgen.circuit import Circuit, Register, Section
from circuitgen.cost import Cost
from circuitgen.gadgets.partial_mixer import partial_mixer
from circuitgen.gadgets.phase_sums import SumsShape
from circuitgen.lowering import lower
from circuitgen.options import DEFAULT_PLAN, PlanOptions
from circuitgen.qaoa import qaoa_plan
from gridcover.presets import default_scenario
from gridcover.scenario import Scenario, scenario_from_dict, scenario_to_dict

from .depth import Depth, depths
from .depth_compose import LayeredDepth, gadget_depth, known_depth
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
    "DEPTH_MODES",
    "DepthMode",
    "Estimate",
    "EstimateOptions",
    "LayerCosts",
    "Point",
    "estimate_depth",
    "estimate_point",
    "layer_costs",
    "registers_for",
]

DepthMode = Literal["auto", "exact", "bound", "none"]
DEPTH_MODES: tuple[DepthMode, ...] = ("auto", "exact", "bound", "none")
DEFAULT_DEPTH_BUDGET = 20_000
"""``depth="auto"`` computes exact depths when the state preparation and one layer have at most this many lowered
gates (see the module docstring: the size of one layer, not of ``p`` layers, sets the cost)."""


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
        depth_budget: ``auto`` computes exact depths when the state preparation and one layer have at most this
            many lowered gates (``bound`` otherwise).
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
    return qaoa_plan(scenario, 1, options)


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
        return _layout(qaoa_plan(scenario, 0, options))
    mixer = mixer_layer(scenario, options.rule, options.target)
    # p = 0: no phase separator (its ancillas are not needed), the partial mixers still size the logic register
    return _registers(scenario, options, mixer.logic_width, _prep_work(qaoa_plan(scenario, 0, options).state_prep))


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
    plan = qaoa_plan(scenario, p, options)
    registers = tuple(plan.registers)
    return Circuit(registers, list(plan_sections(plan, registers, lowered=True)))


def compiled_depth(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Depth:
    """Depths of the compiled, lowered circuit (builds it: mind its size; the tests' reference)."""
    circ = _compiled(scenario, p, options)
    return depths(circ.gates, circ.num_qubits)


@lru_cache(maxsize=8)
def layered_depth(scenario: Scenario, options: PlanOptions = DEFAULT_PLAN) -> LayeredDepth:
    """The scenario's :class:`~estimators.depth_compose.LayeredDepth` (cached: consecutive points of a sweep,
    ``p = 1, 2, ...`` of one scenario, carry one frontier)."""
    plan = _plan1(scenario, options)
    return LayeredDepth.from_sections(plan.sections(), tuple(plan.registers))


def exact_depth(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Depth:
    """Exact depths of the lowered circuit with ``p`` layers, composed from per-gadget transfer profiles
    (:mod:`estimators.depth_compose`; equal to :func:`compiled_depth`, without building the circuit).

    >>> from gridcover.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> exact_depth(s, 2) == compiled_depth(s, 2)
    True
    """
    return layered_depth(scenario, options).depth(p)


_MIXER_DEPTH: dict[tuple[Hashable, str, str], Depth] = {}
"""Own depth of a partial mixer per signature (:mod:`estimators.mixer_count`), rule and target."""


def _mixer_depth_sum(scenario: Scenario, options: PlanOptions, registers: tuple[Register, ...]) -> Depth:
    """Sum over one layer's partial mixers of their own depths, by signature counts (a grid without obstacles)."""
    mixer = mixer_layer(scenario, options.rule, options.target)
    total = Depth()
    for sig, (robot, (i, j), n) in zip(mixer.signatures, mixer.kinds, strict=True):
        key = (sig, options.rule, options.target)
        d = _MIXER_DEPTH.get(key)
        if d is None:
            plaq = scenario.grid.plaquettes[i * (scenario.grid.cols - 1) + j]
            g = partial_mixer(scenario, robot, plaq, Angle.symbol("beta_0"), scenario.num_variables,
                              options.rule, options.target)  # type: ignore[arg-type]  # fmt: skip
            d = _MIXER_DEPTH[key] = gadget_depth(g, registers) if g is not None else Depth()
        total = total + n * d
    return total


@lru_cache(maxsize=256)
def _layer_depth_bounds(scenario: Scenario, options: PlanOptions) -> tuple[Depth, Depth]:
    """The state preparation's depths (exact) and a bound on one layer's (see :func:`depth_bound`)."""
    lc = layer_costs(scenario, options)
    regs = tuple(Register(name, size) for name, size in lc.registers)
    if scenario.obstacles:
        plan = _plan1(scenario, options)
        init, layer = Depth(), Depth()
        for name, gadget in plan.sections():
            d = gadget_depth(gadget, regs)
            if name == "initial_state":
                init = d
            else:
                layer = layer + d
        return init, layer
    if options.initial == "initial_path":
        # one X per edge of each robot's L-shaped initial path: distinct qubits, one layer (tested against the
        # plan's state preparation)
        init = Depth(1, 0, 0) if lc.sections["initial_state"].total else Depth()
    else:
        init = gadget_depth(_plan1(scenario, options).state_prep, regs)
    layer = _phase_depth_sum(scenario, options, lc, regs) + _mixer_depth_sum(scenario, options, regs)
    return init, layer


_OWN_DEPTH_GATES = 5_000
"""A phase part of more lowered gates than this (the balance arithmetic, over every variable) enters the bound by
its gate counts: its own depth would need its gates emitted and lowered, ``O(variables)`` per scenario."""


def _by_counts(c: Cost) -> Depth:
    return Depth(c.total, c.two_qubit, c.rotations, "bound")


def _phase_depth_sum(scenario: Scenario, options: PlanOptions, lc: LayerCosts, regs: tuple[Register, ...]) -> Depth:
    """A bound on one phase separator's depths: the sum of its parts' own depths, one per class
    (:func:`estimators.phase_count.phase_layer`), a large part by its gate counts; where the phase separator is
    not counted by classes, its gate counts."""
    phase = phase_layer(scenario, options.target, options.phase, options.optimize, options.ancilla_budget)
    if phase is None:
        return _by_counts(lc.sections.get("phase", Cost()))
    total = Depth(1, 0, 1) if phase.rotations else Depth()  # one rz on each of distinct data qubits
    rest = _minus(phase.cost(), Cost.of(rz=phase.rotations))
    ready: list[Any] | None = None
    for i, (g, n) in enumerate(phase.parts):
        rest = _minus(rest, n * g.cost())
        d = known_depth(g)
        if d is None and g.cost().total <= _OWN_DEPTH_GATES:
            if ready is None:  # the parts placed on the layer's qubits, ready to emit (builds the balance too)
                ready = [x for x, _ in phase.gadgets()][(1 if phase.rotations else 0) :]
            d = gadget_depth(ready[i], regs)
        total = total + n * (d if d is not None else _by_counts(g.cost()))
    if phase.balance is not None:
        shape = phase.balance.shape
        if rest == shape.cost():
            return total + _arithmetic_depth_bound(shape)
    return total + _by_counts(rest)


def _arithmetic_depth_bound(shape: SumsShape) -> Depth:
    """A bound on a balance arithmetic gadget's depths from its shape, nothing emitted: its forms' trees run side by
    side (disjoint qubits), so the largest compute half, the register phase and the largest uncompute half, each
    by its gate counts (:meth:`~circuitgen.gadgets.phase_sums.SumsShape.halves`)."""
    halves = shape.halves()

    def widest(costs: list[Cost]) -> Depth:
        return Depth(max((c.total for c in costs), default=0), max((c.two_qubit for c in costs), default=0),
                     max((c.rotations for c in costs), default=0), "bound")  # fmt: skip

    return widest([h[0] for h in halves]) + _by_counts(shape.phase_cost()) + widest([h[1] for h in halves])


def depth_bound(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Depth:
    """An upper bound on the depths of ``p`` layers, in ``O(robots)`` per scenario once the counts are known.

    ``depth(A then B) <= depth(A) + depth(B)`` (ASAP layering can only shorten a concatenation), so the bound is
    the state preparation's depth (exact) plus ``p`` times one layer's bound: the sum of the partial mixers' own
    depths (one per signature, :mod:`estimators.mixer_count`, times its multiplicity; fusing neighbours only
    removes gates, which cannot deepen a circuit) plus the phase separator's parts' own depths (one per class,
    :mod:`estimators.phase_count`; the balance arithmetic, and a phase separator not counted by classes, by gate
    counts: a depth is at most the number of gates, likewise two-qubit gates and rotations). With obstacles the
    layer's bound is the sum of every gadget's own depth (the plan's gadgets are listed).

    >>> from gridcover.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> depth_bound(s, 2).depth >= exact_depth(s, 2).depth
    True
    """
    init, layer = _layer_depth_bounds(scenario, options)
    d = init + p * layer
    return Depth(d.depth, d.two_qubit_depth, d.rotation_depth, "bound")


def estimate_depth(
    scenario: Scenario, p: int, options: EstimateOptions = DEFAULT_OPTIONS, costs: LayerCosts | None = None
) -> Depth | None:
    """The depths :func:`estimate_point` reports: ``exact``, a ``bound`` or ``None`` as ``options.depth`` says
    (``auto``: exact when the state preparation and one layer have at most ``options.depth_budget`` lowered
    gates, a bound otherwise; see the module docstring).

    Args:
        scenario: the scenario.
        p: layers.
        options: the options.
        costs: the scenario's :func:`layer_costs` (looked up if not given).

    Returns:
        The depths, or ``None`` for ``depth="none"``.

    >>> from gridcover.presets import default_scenario
    >>> estimate_depth(default_scenario(3, 3, 1), 2).kind
    'exact'
    """
    mode = options.depth
    if mode == "auto":
        lc = costs if costs is not None else layer_costs(scenario, options.plan)
        mode = "exact" if lc.cost(1).total <= options.depth_budget else "bound"
    if mode == "exact":
        return exact_depth(scenario, p, options.plan)
    if mode == "bound":
        return depth_bound(scenario, p, options.plan)
    return None


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
    depth = estimate_depth(scenario, p, options, lc)
    ft = fault_tolerant_from_cost(logical, options.epsilon, options.synthesis, options.toffoli_t)
    registers = registers_for(scenario, p, options.plan)
    est = Estimate(point, options, registers, cost, logical, lc.sections, depth, ft, None, 0.0)
    phys = None
    if options.physical:
        phys = physical_estimate(est.logical_counts, options.qubit_model, options.qec_scheme, options.error_budget)
    return Estimate(
        point, options, est.registers, cost, logical, lc.sections, depth, ft, phys, time.perf_counter() - start
    )
