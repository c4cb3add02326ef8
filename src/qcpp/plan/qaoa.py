"""The whole constrained-mixer QAOA circuit.

``qaoa_circuit(scenario, p)`` returns a :class:`~qcpp.ir.circuit.Circuit` with registers ``data`` (qubit ``i``
= decision variable ``i``) and ``logic`` (clean ancillas shared by every gadget); sections ``initial_state``, then
``phase_k`` and ``mixer_k`` for ``k = 0 .. p-1``, every gadget a section of its own (so lowering passes never act
across two gadgets and each gadget's lowered cost is its reported cost; the parity-basis partial mixers are cut at
their rotations into :class:`~qcpp.gadgets.junction.MixerJunction` sections); and the symbols ``gamma_k``,
``beta_k`` (with ``PlanOptions(angles="multi")`` one beta per partial mixer and layer instead,
:func:`~qcpp.ir.angles.mixer_symbol`), bound later with ``Circuit.bind``. :class:`QaoaPlan` holds the same
circuit as gadgets, and :meth:`QaoaPlan.call_graph` lists it as gadget kinds, which every count sums.
With ``PlanOptions(first_phase=False)`` there is no section ``phase_0`` (``gamma_0`` names no gate): on the basis
state the preparation gives, the first phase separator is a global phase, and :func:`qaoa_plan` refuses any
other start (:attr:`QaoaPlan.basis_start`).

On the feasible assignments it reaches, the circuit applied to |0...0> gives
``prod_k U_M(beta_k) exp(-i gamma_k (C - K)) |x_0>``, ``K`` = :attr:`QaoaPlan.reference_constant`: the operator
the feasible-subspace simulator (:mod:`qcpp.simulate.subspace`) implements.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> c = qaoa_circuit(s, p=1)
    >>> c.symbols, [sec.name for sec in c.sections][:4], len(c.sections)
    (('gamma_0', 'beta_0'), ['initial_state', 'phase_0', 'mixer_0', 'mixer_0'], 11)
    >>> from qcpp.lowering.passes import lower
    >>> plan = qaoa_plan(s, p=1)
    >>> plan.cost() == Cost.count(lower(c).gates)
    True
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from functools import cached_property, partial

from qcpp.errors import OptionError
from qcpp.gadgets import Gadget
from qcpp.gadgets.blocks import StatePrep, XLayerKind
from qcpp.gadgets.initial_state import initial_path_count
from qcpp.gadgets.junction import mixer_pieces
from qcpp.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer, partial_mixer
from qcpp.ir.angles import Angle, mixer_symbol, symbol_sort_key
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import WORK_REGISTER, lower
from qcpp.plan.call_graph import CallGraph, Deferred, GadgetKind
from qcpp.plan.mixer_classes import MixerPart, mixer_part
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.plan.phase import PhasePlan, phase_plan
from qcpp.plan.phase_classes import phase_layer
from qcpp.plan.phase_layout import placed_sums, spatial_phase
from qcpp.problem.scenario import Scenario


@dataclass(frozen=True)
class QubitMap:
    """Where each qubit of a compiled circuit comes from.

    Attributes:
        data: For each data qubit ``i``: ``(robot, grid edge index)``.
        ancillas: Indices of every other qubit (``logic`` and, after lowering, ``work``).
    """

    data: tuple[tuple[int, int], ...]
    ancillas: tuple[int, ...]


def qubit_map(scenario: Scenario, num_qubits: int) -> QubitMap:
    """The :class:`QubitMap` of a circuit of ``num_qubits`` qubits built by :func:`qaoa_circuit` (lowered or
    not): data first, ancillas after."""
    n = scenario.num_variables
    return QubitMap(tuple(scenario.variable_of(i) for i in range(n)), tuple(range(n, num_qubits)))


@dataclass(frozen=True)
class QaoaPlan:
    """The QAOA circuit as gadgets: what :func:`qaoa_circuit` emits, and its cost without emitting it.

    Attributes:
        options: How it is built (:class:`~qcpp.plan.options.PlanOptions`).
    """

    scenario: Scenario
    p: int
    options: PlanOptions = DEFAULT_PLAN

    def __post_init__(self) -> None:
        if not self.options.first_phase and not self.basis_start:
            raise OptionError(
                "first_phase",
                "the first phase separator can be omitted from a basis state only, and the initial state "
                f"{self.options.initial} prepares a superposition of paths here (initial_path and local_search "
                "always start from one)",
            )

    @property
    def basis_start(self) -> bool:
        """Whether the state preparation gives a basis state (X gates only: ``initial_path``, ``local_search``,
        and ``representatives`` or ``local_search_mix`` where every robot has one path to put in superposition),
        on which the first phase separator is a global phase (:attr:`PlanOptions.first_phase
        <qcpp.plan.options.PlanOptions.first_phase>`)."""
        if self.options.initial in ("initial_path", "local_search"):  # X gates by construction: nothing built
            return True
        return all(g.name == "x" for g in self.state_prep.gates)

    # -- layout
    @cached_property
    def _planned_mixers(self) -> tuple[tuple[tuple[int, int], ParityPartialMixer | McxPartialMixer], ...]:
        """Every partial mixer (robot-major, plaquettes row-major) with its ``(robot, plaquette index)``."""
        s, n = self.scenario, self.scenario.num_variables
        out = []
        for r in range(s.num_robots):
            for q in s.grid.plaquettes:
                m = partial_mixer(s, r, q, Angle.symbol("beta"), n, self.options.rule, self.options.target)
                if m is not None:
                    out.append(((r, q.index), m))
        return tuple(out)

    def _mixer_layer(self, k: int | None) -> list[Gadget]:
        """Layer ``k``'s mixer pieces (``None``: with the placeholder angle ``beta``): the partial mixers
        (robot-major, plaquettes row-major) as junctions and rotations
        (:func:`~qcpp.gadgets.junction.mixer_pieces`), or themselves unfused."""
        def beta(r: int, q: int) -> str:
            if k is None:
                return "beta"
            return mixer_symbol(k, r, q) if self.options.angles == "multi" else f"beta_{k}"

        mixers = [dataclasses.replace(m, beta=Angle.symbol(beta(*rq))) for rq, m in self._planned_mixers]
        return list(mixer_pieces(mixers)) if self.options.fuse else mixers  # type: ignore[arg-type]

    @cached_property
    def state_prep(self) -> StatePrep:
        """The initial-state gadget."""
        s, o = self.scenario, self.options
        ancilla = s.num_variables if o.initial == "representatives" else None
        return StatePrep.build(s, o.initial, o.rule, ancilla)

    @cached_property
    def phase_plan(self) -> PhasePlan | None:
        """The phase separator's plan (``None`` when ``p = 0``)."""
        if not self.p:
            return None
        o = self.options
        return phase_plan(
            self.scenario,
            target=o.target,
            representation=o.phase,
            optimize=o.optimize,
            ancilla_budget=o.ancilla_budget,
            pooled=o.phase_layout not in ("spatial", "medial"),  # those place each term on its own edges
        )

    @property
    def reference_constant(self) -> float:
        """On every feasible ``x`` a layer applies ``exp(-i gamma (C(x) - reference_constant))`` before its mixer
        (pass it to the subspace simulator as ``phase_offset`` to compare amplitudes)."""
        return self.phase_plan.reference_constant if self.phase_plan else 0.0

    @cached_property
    def logic_width(self) -> int:
        """Shared clean ``logic`` ancillas (the call graph's)."""
        return self.call_graph().logic_width

    @cached_property
    def work_width(self) -> int:
        """``work`` ancillas the lowering adds (the call graph's)."""
        return self.call_graph().work_width

    @property
    def registers(self) -> tuple[Register, ...]:
        """``data``, ``logic`` (if any), and the ``work`` register the lowering adds (if any)."""
        sizes = (("data", self.scenario.num_variables), ("logic", self.logic_width), (WORK_REGISTER, self.work_width))
        return tuple(Register(name, size) for name, size in sizes if size or name == "data")

    @property
    def num_qubits(self) -> int:
        """All qubits of the lowered circuit."""
        return sum(r.size for r in self.registers)

    # -- the call graph
    def sections(self, layers: int | None = None) -> Iterator[tuple[str, Gadget]]:
        """``(section name, gadget)`` in circuit order: the state preparation, then per layer the phase
        separator (none in layer 0 without :attr:`~qcpp.plan.options.PlanOptions.first_phase`) and the mixer's
        pieces (:meth:`_mixer_layer`); only the first ``layers`` layers if given (a layer's gadgets are planned as a
        whole when it starts)."""
        yield "initial_state", self.state_prep
        for k in range(self.p if layers is None else min(layers, self.p)):
            assert self.phase_plan is not None
            if k or self.options.first_phase:
                for g in self._phase_gadgets(f"gamma_{k}"):
                    yield f"phase_{k}", g
            for g in self._mixer_layer(k):
                yield f"mixer_{k}", g

    def layer_sections(self, p: int | None = None) -> Iterator[tuple[str, Gadget, int]]:
        """``(section name, gadget, multiplicity)``: sections that stand for the whole circuit of ``p`` layers
        (default: this plan's ``p``; the plan needs at least ``min(p, 2)`` layers without the first phase
        separator, else ``min(p, 1)``), each with how many like it that circuit has (layers differ in their angles
        only): the state preparation once, layer 0's mixer ``p`` times and its phase separator ``p`` times, or,
        without the first, layer 1's phase separator ``p - 1`` times.

        Example:
            >>> from qcpp.problem.presets import default_scenario
            >>> plan = qaoa_plan(default_scenario(3, 3, 1), 2, PlanOptions(first_phase=False))
            >>> sorted({(name, n) for name, _, n in plan.layer_sections(5)})
            [('initial_state', 1), ('mixer_0', 5), ('phase_1', 4)]
        """
        p = self.p if p is None else p
        o = self.options
        for name, g in self.sections(layers=1 if o.first_phase else 2):
            if name == "initial_state":
                yield name, g, 1
            elif name.endswith("_0"):
                yield name, g, p
            elif name.startswith("phase_"):  # layer 1's, without the first phase separator
                yield name, g, o.phase_layers(p)

    def _phase_gadgets(self, gamma: str) -> tuple[Gadget, ...]:
        """One layer's phase separator gadgets, laid out as :attr:`PlanOptions.phase_layout` asks."""
        assert self.phase_plan is not None
        n = self.scenario.num_variables
        gadgets = self.phase_plan.gadgets(gamma)
        if self.options.phase_layout in ("spatial", "medial"):
            gadgets = spatial_phase(gadgets, self.scenario, range(n, n + self.phase_plan.num_ancillas),
                                    sinks=self.options.phase_layout == "medial")  # fmt: skip
        return gadgets

    def call_graph(self, by_classes: bool = True) -> CallGraph:
        """The circuit as gadget kinds with multiplicities, per part (``phase`` and ``mixer``: one layer's, empty
        ``phase`` for ``p = 0``; :meth:`~qcpp.plan.call_graph.CallGraph.cost` counts ``p - 1`` phase separators without
        :attr:`~qcpp.plan.options.PlanOptions.first_phase`), nothing emitted: counted by classes of plaquettes
        (:mod:`qcpp.plan.mixer_classes`) and of nodes (:mod:`qcpp.plan.phase_classes`) on a grid without obstacles,
        ``O(robots)`` per scenario, else (or where :func:`~qcpp.plan.phase_classes.phase_layer` leaves a choice to the
        plan) listed from the planned gadgets.

        Args:
            by_classes: count by classes where that is exact (default); ``False`` lists the planned gadgets
                (the reference the tests compare with).

        Returns:
            The :class:`~qcpp.plan.call_graph.CallGraph` (cached for the default).
        """
        return self._graph if by_classes else self._build_graph(False)

    @cached_property
    def _graph(self) -> CallGraph:
        return self._build_graph(True)

    def _build_graph(self, by_classes: bool) -> CallGraph:
        s, o = self.scenario, self.options
        classes = by_classes and not s.obstacles
        if classes and o.initial == "initial_path":  # X gates on distinct qubits: built only if emitted
            n = initial_path_count(s)
            xs = Cost.of(x=n)
            # built from the scenario, not from this plan: a closure over the plan, which holds the call graph,
            # would be a reference cycle, freed only by full collections (a sweep's plans would pile up until one)
            build = partial(StatePrep.build, s, o.initial, o.rule, None)
            prep = GadgetKind(XLayerKind("x_layer", n), Deferred(XLayerKind("x_layer", n), xs, xs, build))
        else:
            prep = GadgetKind.of(self.state_prep)
        if classes:
            mixer = mixer_part(s, o.rule, o.target, o.fuse)
        else:
            mixer = MixerPart(tuple((GadgetKind.of(g), 1) for g in self._mixer_layer(None)))
        phase: list[tuple[GadgetKind, int]] = []
        phase_width = 0
        if self.p:
            # the classes price the pooled layout; the spatial one's adders are kinds of their own
            by_phase_classes = classes and o.phase_layout not in ("spatial", "medial")
            layer = phase_layer(s, o.target, o.phase, o.optimize, o.ancilla_budget) if by_phase_classes else None
            if layer is not None:
                phase, phase_width = layer.kinds(), layer.num_ancillas
            else:  # the plan decides, term group by term group
                assert self.phase_plan is not None
                gadgets = self.phase_plan.gadgets("gamma")
                if o.phase_layout in ("spatial", "medial"):  # the kinds only: no ancilla needs choosing
                    gadgets = placed_sums(gadgets, s)
                phase = [(GadgetKind.of(g), 1) for g in gadgets]
                phase_width = self.phase_plan.num_ancillas
        if not o.phase_layers(self.p):  # listed for the sums over p, but no phase separator is in this circuit
            phase_width = 0
        logic = max(mixer.logic_width, phase_width, 1 if o.initial == "representatives" else 0)
        work = max(mixer.work_need if self.p else 0, prep.work)
        parts = {"initial_state": [(prep, 1)], "phase": phase, "mixer": mixer.kinds}
        return CallGraph.build(parts, logic, work, o.first_phase)

    def cost_by_part(self, logical: bool = False) -> dict[str, Cost]:
        """Cost of the state preparation and of ONE layer's phase separator and mixer (keys ``initial_state``,
        ``phase``, ``mixer``); multiply the mixer by ``p`` and the phase separator by
        :meth:`PlanOptions.phase_layers(p) <qcpp.plan.options.PlanOptions.phase_layers>` for the circuit."""
        return self.call_graph().cost_by_part(logical)

    def cost(self) -> Cost:
        """Lowered cost of the whole circuit: state preparation + ``p`` x (phase separator + mixer), one phase
        separator fewer without the first."""
        return self.call_graph().cost(self.p)

    def logical_cost(self) -> Cost:
        """Like :meth:`cost` with ANDs and Toffolis kept whole (the fault-tolerant view)."""
        return self.call_graph().cost(self.p, logical=True)

    def emit_sections(self, lowered: bool = False) -> Iterator[Section]:
        """The circuit's sections in order, one gadget at a time (``emit_blocks()`` where a gadget has several),
        lowered one by one if asked: equal to lowering the whole circuit, as passes never cross sections and the
        ``work`` register is already among :attr:`registers` (what streaming OpenQASM writes)."""
        registers = self.registers
        for name, g in self.sections():
            secs = [Section(name, tuple(b)) for b in gadget_blocks(g)]
            yield from lower(Circuit(registers, secs)).sections if lowered else secs

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """The operator's angles in circuit order: per layer ``gamma_k``, then ``beta_k`` or (``angles="multi"``)
        one :func:`~qcpp.ir.angles.mixer_symbol` per partial mixer. A name may have no gate (a phase separator
        left empty by a constant cost, or ``gamma_0`` without the first phase separator) and is still a valid
        binding."""
        out: list[str] = []
        for k in range(self.p):
            out.append(f"gamma_{k}")
            if self.options.angles == "multi":
                out += [mixer_symbol(k, r, q) for (r, q), _ in self._planned_mixers]
            else:
                out.append(f"beta_{k}")
        return tuple(out)

    def check_bindings(self, names: Iterable[str], field: str = "bind") -> None:
        """Refuse angle names the operator does not have (see :attr:`parameter_names`).

        Args:
            names: The names a user binds.
            field: The argument that gave them, starting the message (``bind``; the command line's ``--bind``).

        Raises:
            qcpp.errors.OptionError: naming the unknown names and listing the known ones.
        """
        known = set(self.parameter_names)
        unknown = sorted(set(names) - known)
        if unknown:
            have = ", ".join(sorted(known, key=symbol_sort_key)) or "none"
            raise OptionError(field, f"unknown symbol(s) {', '.join(unknown)} (this circuit has: {have})")

    def circuit(self) -> Circuit:
        """The high-level circuit (one section per gadget)."""
        regs = [r for r in self.registers if r.name != WORK_REGISTER]
        return Circuit(regs, list(self.emit_sections()))


def gadget_blocks(gadget: Gadget) -> list[Sequence[Gate]]:
    """The gate blocks of a planned gadget that the circuit holds as sections of their own (lowered one by one):
    one per leaf and the rotation for a controlled-X partial mixer (``emit_blocks()``), else the whole gadget.

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> _, g = next(qaoa_plan(default_scenario(3, 3, 1), 1).sections())
        >>> gadget_blocks(g) == [g.emit()]
        True
    """
    return gadget.emit_blocks() if isinstance(gadget, McxPartialMixer) else [gadget.emit()]


def qaoa_plan(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> QaoaPlan:
    """The :class:`QaoaPlan` (gadgets and costs) of the QAOA circuit; see :func:`qaoa_circuit`.

    Raises:
        ValueError: ``p`` is not a non-negative integer.
        qcpp.errors.OptionError: ``first_phase=False`` with a start that is not a basis state
            (:attr:`QaoaPlan.basis_start`).
    """
    if not isinstance(p, int) or isinstance(p, bool) or p < 0:
        raise ValueError(f"p must be a non-negative integer, got {p!r}")
    if not isinstance(options, PlanOptions):
        raise TypeError(f"options must be a PlanOptions, got {type(options).__name__}")
    return QaoaPlan(scenario, p, options)


def qaoa_circuit(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> Circuit:
    """Build the parameterised QAOA circuit (high level: and/and_dg, crx, cx, x, rz, rzz, mcx, csbf, ...).

    Args:
        p: Number of layers (>= 0).
        options: How it is built (rule, initial state, target, phase separator, ancilla budget, fusion; see
            :class:`~qcpp.plan.options.PlanOptions`).

    Returns:
        The circuit (see the module docstring for its layout).
    """
    return qaoa_plan(scenario, p, options).circuit()
