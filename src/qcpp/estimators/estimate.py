"""Resource estimates of one QAOA circuit from its gadgets' costs, without building a gate list.

:func:`estimate_point` sums the circuit's call graph (:meth:`qcpp.plan.qaoa.QaoaPlan.call_graph`): layers are
alike up to their angles, so ``p`` layers cost ``initial state + p * (phase separator + mixer)`` (one phase
separator fewer with ``PlanOptions(first_phase=False)``) and one plan with ``p = 1`` serves every ``p``
(:func:`layer_costs`). :mod:`qcpp.estimators.crosscheck` checks these numbers against
the compiled, lowered circuit. Depth cannot be summed (ASAP layering overlaps consecutive pieces), so it is
``exact`` (composed from per-kind transfer profiles, :mod:`qcpp.estimators.depth_compose`, the frontier carried from
``p`` to ``p + 1``: :func:`layered_depth`; ``depth="auto"`` when the state preparation plus one layer has at most
``depth_budget`` lowered gates), a ``bound`` (:func:`depth_bound`, ``O(robots)`` per scenario) or absent
(``depth="none"``); the row says which (``depth_kind``).

Example:
    >>> from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
    >>> est = estimate_point(Point(2, 2, 1, 1))
    >>> est.qubits, est.depth.kind
    (4, 'exact')
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Literal

from qcpp.errors import OptionError, check_choice, check_count
from qcpp.estimators.depth import Depth, depths
from qcpp.estimators.depth_compose import LayeredDepth, gadget_depth, known_depth
from qcpp.estimators.fault_tolerant import (
    DEFAULT_EPSILON,
    TOFFOLI_T_CHOICES,
    FaultTolerantEstimate,
    SynthesisModel,
    fault_tolerant_from_cost,
)
from qcpp.estimators.physical import (
    DEFAULT_ERROR_BUDGET,
    DEFAULT_QEC_SCHEME,
    DEFAULT_QUBIT_MODEL,
    QEC_SCHEMES,
    QUBIT_MODELS,
    LogicalCounts,
    PhysicalEstimate,
    model_scheme_error,
    physical_estimate,
)
from qcpp.gadgets.blocks import XLayerKind
from qcpp.gadgets.phase_ising import IsingKind
from qcpp.gadgets.phase_sums import SumsShape
from qcpp.gadgets.pricing import COSTS
from qcpp.gadgets.visit_batch import VisitBatch
from qcpp.ir.circuit import Register
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import WORK_REGISTER, lower
from qcpp.plan.call_graph import SCENARIOS_KEPT, CallGraph, Deferred, GadgetKind
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.plan.qaoa import QaoaPlan, qaoa_circuit, qaoa_plan
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict, scenario_to_dict

__all__ = [
    "DEFAULT_DEPTH_BUDGET",
    "DEFAULT_OPTIONS",
    "DEPTH_MODES",
    "DepthMode",
    "Estimate",
    "EstimateOptions",
    "Point",
    "checked_estimate_options",
    "estimate_depth",
    "estimate_point",
    "layer_costs",
    "registers_for",
]

DepthMode = Literal["auto", "exact", "bound", "none"]
DEPTH_MODES: tuple[DepthMode, ...] = ("auto", "exact", "bound", "none")
DEFAULT_DEPTH_BUDGET = 20_000
"""``depth="auto"``'s default ``depth_budget`` (the size of one layer, not of ``p`` layers, sets the cost)."""


@dataclass(frozen=True)
class EstimateOptions:
    """What to estimate beyond the exact counts.

    Attributes:
        plan: circuit construction options.
        epsilon, synthesis, toffoli_t: the fault-tolerant model (:mod:`qcpp.estimators.fault_tolerant`).
        depth, depth_budget: which depths (see the module docstring).
        physical: run the QDK resource estimator (:mod:`qcpp.estimators.physical`).
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


def checked_estimate_options(
    plan: PlanOptions = DEFAULT_PLAN,
    *,
    epsilon: float = DEFAULT_EPSILON,
    toffoli_t: int = 7,
    depth: str = "auto",
    depth_budget: int = DEFAULT_DEPTH_BUDGET,
    physical: bool = False,
    qubit_model: str = DEFAULT_QUBIT_MODEL,
    qec_scheme: str = DEFAULT_QEC_SCHEME,
    error_budget: float = DEFAULT_ERROR_BUDGET,
    flag: Callable[[str], str] = lambda name: name,
) -> EstimateOptions:
    """:class:`EstimateOptions` from user input, every value checked: what ``qcpp estimate`` and
    ``qcpp.estimate`` both call, so that a bad value gets one message in both.

    Args:
        plan: The circuit construction options.
        epsilon: Rotation synthesis precision of the fault-tolerant model.
        toffoli_t: T per Toffoli of the fault-tolerant model: 7 or 4.
        depth: ``auto``, ``exact``, ``bound`` or ``none``.
        depth_budget: The lowered gates per layer up to which ``auto`` computes the exact depth.
        physical: Add the physical estimates of the QDK resource estimator.
        qubit_model: The QDK qubit model.
        qec_scheme: The QDK error-correction scheme.
        error_budget: The QDK error budget.
        flag: How an option is named in a message (the command line: ``--epsilon``; Python: ``epsilon``).

    Returns:
        The options.

    Raises:
        qcpp.errors.OptionError: naming the option (``epsilon: must be in (0, 1), got 2.0``).

    Example:
        >>> checked_estimate_options(epsilon=1e-4).epsilon
        0.0001
        >>> checked_estimate_options(depth_budget=-1, flag=lambda n: "--" + n.replace("_", "-"))
        Traceback (most recent call last):
        ...
        qcpp.errors.OptionError: --depth-budget: must be at least 0, got -1
    """
    for name, value in (("epsilon", epsilon), ("error_budget", error_budget)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0.0 < value < 1.0:
            raise OptionError(flag(name), f"must be in (0, 1), got {value!r}")
    check_count(depth_budget, flag("depth_budget"), 0)
    for name, value, allowed in (
        ("depth", depth, DEPTH_MODES), ("toffoli_t", toffoli_t, TOFFOLI_T_CHOICES),
        ("qubit_model", qubit_model, QUBIT_MODELS), ("qec_scheme", qec_scheme, QEC_SCHEMES),
    ):  # fmt: skip
        check_choice(value, allowed, flag(name))
    pair = model_scheme_error(qubit_model, qec_scheme, flag("qubit_model"))
    if pair is not None:  # before the QDK is called, which would fail with its own error name
        raise OptionError(flag("qec_scheme"), pair)
    if not isinstance(physical, bool):
        raise OptionError(flag("physical"), f"expected True or False, got {physical!r}")
    return EstimateOptions(
        plan=plan, epsilon=float(epsilon), toffoli_t=toffoli_t, depth=depth,  # type: ignore[arg-type]
        depth_budget=depth_budget, physical=physical, qubit_model=qubit_model, qec_scheme=qec_scheme,
        error_budget=float(error_budget),
    )  # fmt: skip


@dataclass(frozen=True)
class Point:
    """One circuit: the default scenario of a grid and robot count (or a given scenario) with ``p`` layers.

    A given scenario must have the point's grid and robot count (the rows label them): build such a point with
    :meth:`from_scenario`; a mismatch raises :class:`~qcpp.errors.OptionError`.

    Attributes:
        rows, cols, robots: the grid and robot count.
        scenario_json: canonical JSON text of a given scenario, or ``None`` for
            :func:`qcpp.problem.presets.default_scenario`.
    """

    rows: int
    cols: int
    robots: int
    p: int
    scenario_json: str | None = None

    def __post_init__(self) -> None:
        if self.scenario_json is None:
            return
        data = json.loads(self.scenario_json)
        grid, robots = data.get("grid", {}), data.get("robots", [])
        given = (grid.get("rows"), grid.get("cols"), len(robots))
        if given != (self.rows, self.cols, self.robots):
            raise OptionError(
                "scenario_json",
                f"the scenario is {given[0]}x{given[1]} with {given[2]} robot(s), but the point says "
                f"{self.rows}x{self.cols} with {self.robots} (use Point.from_scenario)",
            )

    def build_scenario(self) -> Scenario:
        """The scenario of this point."""
        return _scenario(self.rows, self.cols, self.robots, self.scenario_json)

    @classmethod
    def from_scenario(cls, scenario: Scenario, p: int) -> Point:
        """A point for a given scenario."""
        text = json.dumps(scenario_to_dict(scenario), sort_keys=True)
        g = scenario.grid
        return cls(g.rows, g.cols, scenario.num_robots, p, text)

    @property
    def label(self) -> str:
        """Short text such as ``3x4 r2 p1``."""
        return f"{self.rows}x{self.cols} r{self.robots} p{self.p}" + ("" if self.scenario_json is None else " (custom)")


@lru_cache(maxsize=SCENARIOS_KEPT)
def _scenario(rows: int, cols: int, robots: int, text: str | None) -> Scenario:
    """Pure memo: ``_scenario.cache_clear()`` empties it."""
    return default_scenario(rows, cols, robots) if text is None else scenario_from_dict(json.loads(text))


@lru_cache(maxsize=3 * SCENARIOS_KEPT)  # plans with 0, 1 and 2 layers
def _plan(scenario: Scenario, options: PlanOptions, layers: int = 1) -> QaoaPlan:
    """The plan with ``layers`` (0, 1, or 2 without the first phase separator: the first layer then differs from
    the others) layers, shared by the costs, the registers and the depths.
    Pure memo: ``_plan.cache_clear()`` empties it."""
    return qaoa_plan(scenario, layers, options)


def _alike_from(options: PlanOptions) -> int:
    """The layers after which every circuit has the same registers and its layers repeat alike: 1, or 2 without
    the first phase separator (its first layer has no phase separator, every later one has)."""
    return 1 if options.first_phase else 2


def layer_costs(scenario: Scenario, options: PlanOptions = DEFAULT_PLAN) -> CallGraph:
    """The call graph of a scenario's plan with one layer, whose sums give every ``p`` (cached with the plan: its
    kinds' examples keep their plan alive).

    Args:
        scenario: the scenario.
        options: circuit construction options.
    """
    return _plan(scenario, options).call_graph()


def registers_for(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> tuple[tuple[str, int], ...]:
    """``(name, size)`` of the lowered circuit's registers with ``p`` layers (no gate is built)."""
    layers = min(p, _alike_from(options))
    plan = _plan(scenario, options) if layers == 1 else _plan(scenario, options, layers)  # the cache keys by the args
    return tuple((r.name, r.size) for r in plan.registers)


@dataclass(frozen=True)
class Estimate:
    """Counts and estimates of one point.

    Attributes:
        point: the point.
        options: the options used.
        registers: ``(name, size)`` of every register.
        cost: lowered gate counts (exact).
        logical: logical gate counts (ANDs and Toffolis whole; exact).
        parts: lowered costs per part (``initial_state``; one layer's ``phase`` and ``mixer``).
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
    parts: Mapping[str, Cost]
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


def compiled_depth(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Depth:
    """Depths of the compiled, lowered circuit (builds it: mind its size; the tests' reference)."""
    circ = lower(qaoa_circuit(scenario, p, options))
    return depths(circ.gates, circ.num_qubits)


@lru_cache(maxsize=SCENARIOS_KEPT)
def layered_depth(scenario: Scenario, options: PlanOptions = DEFAULT_PLAN) -> LayeredDepth:
    """The scenario's :class:`~qcpp.estimators.depth_compose.LayeredDepth` (cached: consecutive points of a sweep,
    ``p = 1, 2, ...`` of one scenario, carry one frontier). Pure memo: ``layered_depth.cache_clear()`` empties it."""
    layers = _alike_from(options)
    plan = _plan(scenario, options) if layers == 1 else _plan(scenario, options, layers)
    return LayeredDepth.from_sections(plan.sections(), tuple(plan.registers))


def exact_depth(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Depth:
    """Exact depths of the lowered circuit with ``p`` layers, composed from per-gadget transfer profiles
    (:mod:`qcpp.estimators.depth_compose`; equal to :func:`compiled_depth`, without building the circuit).

    >>> from qcpp.problem.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> exact_depth(s, 2) == compiled_depth(s, 2)
    True
    """
    return layered_depth(scenario, options).depth(p)


_OWN_DEPTH_GATES = 5_000
"""A kind of more lowered gates than this (the balance arithmetic, over every variable) enters the bound by its
gate counts (or its shape): its own depth would need its gates emitted and lowered, ``O(variables)``."""


def _by_counts(c: Cost) -> Depth:
    return Depth(c.total, c.two_qubit, c.rotations, "bound")


def _example_registers(kind: GadgetKind) -> tuple[Register, ...]:
    """Registers that hold a kind's example (its own depth does not depend on where it sits)."""
    top = max((q + 1 for g in kind.example.emit() for q in g.qubits), default=1)
    return (Register("q", top), Register(WORK_REGISTER, kind.work)) if kind.work else (Register("q", top),)


_DEPTH_BOUNDS = COSTS.table("depth bound")
"""Per kind, in the kinds' one cache: :func:`kind_depth_bound` of a kind that is not :class:`Deferred` (whose
key is one scenario's)."""


def kind_depth_bound(kind: GadgetKind) -> Depth:
    """A bound on the depths of any gadget of ``kind``, cached per kind: its own depths (from its example, or
    known per anchored kind), one layer for gates on distinct data qubits, and for a kind of more than
    :data:`_OWN_DEPTH_GATES` gates its shape's bound (:func:`_arithmetic_depth_bound`) or its gate counts."""
    if isinstance(kind.example, Deferred):
        return _kind_depth_bound(kind)
    hit = _DEPTH_BOUNDS.get(kind.cache_key)
    if hit is None:
        hit = _kind_depth_bound(kind)
        COSTS.remember("depth bound", kind.cache_key, hit)
    return hit


def _kind_depth_bound(kind: GadgetKind) -> Depth:
    ex = kind.example
    key = kind.key
    if isinstance(ex, Deferred) and isinstance(key, IsingKind) and not key.couplings:
        return Depth(1, 0, 1) if kind.cost().total else Depth()  # one rz on each of distinct data qubits
    if isinstance(key, XLayerKind):  # X gates on distinct qubits: one layer
        return Depth(1, 0, 0) if key.count else Depth()
    d = known_depth(ex)
    if d is not None:
        return d
    cost = kind.cost()
    if isinstance(ex, VisitBatch) and cost.total > _OWN_DEPTH_GATES:
        # its nodes share no edge, so their halves run side by side: one node alone (with the phase of its own
        # products), then the phase of all products by its shape
        one = VisitBatch(ex.gamma, ex.coefficient, ex.nodes[:1], ex.ancillas)
        top = max(q + 1 for g in one.emit() for q in g.qubits)
        alone = gadget_depth(one, (Register("q", top),))
        return replace(alone + _arithmetic_depth_bound(ex.hamming().shape), kind="bound")
    if cost.total <= _OWN_DEPTH_GATES:
        return gadget_depth(ex.build() if isinstance(ex, Deferred) else ex, _example_registers(kind))
    shape = getattr(ex, "shape", None)
    return _arithmetic_depth_bound(shape) if isinstance(shape, SumsShape) else _by_counts(cost)


@lru_cache(maxsize=SCENARIOS_KEPT)
def _layer_depth_bounds(scenario: Scenario, options: PlanOptions) -> dict[str, Depth]:
    """The depth bound of each part: the state preparation's, one layer's phase separator's and mixer's (see
    :func:`depth_bound`). Pure memo: ``_layer_depth_bounds.cache_clear()`` empties it."""
    graph = _plan(scenario, options).call_graph()
    sums = {part: [0, 0, 0] for part in graph.parts}  # plain integers: a sum over thousands of kinds
    for part, kind, n in graph.kinds():
        d, total = kind_depth_bound(kind), sums[part]
        total[0] += n * d.depth
        total[1] += n * d.two_qubit_depth
        total[2] += n * d.rotation_depth
    return {part: Depth(*total, "bound") for part, total in sums.items()}  # type: ignore[arg-type]


def _arithmetic_depth_bound(shape: SumsShape) -> Depth:
    """A bound on a balance arithmetic gadget's depths from its shape, nothing emitted: its forms' trees run side by
    side (disjoint qubits), so the largest compute half, the register phase and the largest uncompute half, each
    by its gate counts (:meth:`~qcpp.gadgets.phase_sums.SumsShape.halves`)."""
    halves = shape.halves()

    def widest(costs: list[Cost]) -> Depth:
        return Depth(max((c.total for c in costs), default=0), max((c.two_qubit for c in costs), default=0),
                     max((c.rotations for c in costs), default=0), "bound")  # fmt: skip

    return widest([h[0] for h in halves]) + _by_counts(shape.phase_cost()) + widest([h[1] for h in halves])


def depth_bound(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Depth:
    """An upper bound on the depths of ``p`` layers: ASAP layering can only shorten a concatenation, so the sum
    over the call graph of each kind's :func:`kind_depth_bound` times its multiplicity, one layer ``p`` times (its
    phase separator ``p - 1`` times without the first).

    >>> from qcpp.problem.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> depth_bound(s, 2).depth >= exact_depth(s, 2).depth
    True
    """
    part = _layer_depth_bounds(scenario, options)
    total = part["initial_state"] + p * part["mixer"] + options.phase_layers(p) * part["phase"]
    return replace(total, kind="bound")


def estimate_depth(
    scenario: Scenario, p: int, options: EstimateOptions = DEFAULT_OPTIONS, graph: CallGraph | None = None
) -> Depth | None:
    """The depths :func:`estimate_point` reports, as ``options.depth`` says (see the module docstring).

    Args:
        scenario: the scenario.
        p: layers.
        options: the options.
        graph: the scenario's :func:`layer_costs` (looked up if not given).

    Returns:
        The depths, or ``None`` for ``depth="none"``.

    >>> from qcpp.problem.presets import default_scenario
    >>> estimate_depth(default_scenario(3, 3, 1), 2).kind
    'exact'
    """
    mode = options.depth
    if mode == "auto":  # the state preparation and one whole layer (also without the first phase separator)
        lc = graph if graph is not None else layer_costs(scenario, options.plan)
        mode = "exact" if sum(c.total for c in lc.cost_by_part().values()) <= options.depth_budget else "bound"
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

    Raises:
        qcpp.problem.errors.ScenarioError: the grid cannot host the robots.
        qcpp.estimators.physical.PhysicalEstimateError: the physical estimator refused the counts.
    """
    start = time.perf_counter()
    scenario = point.build_scenario()
    graph = layer_costs(scenario, options.plan)
    p = point.p
    cost, logical, parts = graph.cost(p), graph.cost(p, logical=True), graph.cost_by_part()
    depth = estimate_depth(scenario, p, options, graph)
    ft = fault_tolerant_from_cost(logical, options.epsilon, options.synthesis, options.toffoli_t)
    est = Estimate(point, options, registers_for(scenario, p, options.plan), cost, logical, parts, depth, ft, None, 0)
    if options.physical:
        phys = physical_estimate(est.logical_counts, options.qubit_model, options.qec_scheme, options.error_budget)
        est = replace(est, physical=phys)
    return replace(est, seconds=time.perf_counter() - start)
