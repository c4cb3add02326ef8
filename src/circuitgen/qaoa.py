"""The whole constrained-mixer QAOA circuit.

``qaoa_circuit(scenario, p)`` returns a :class:`~circuitgen.circuit.Circuit` with

* registers ``data`` (qubit ``i`` = decision variable ``i``, see :mod:`gridcover.scenario`) and ``logic``
  (the SBF logic ancillas, shared by every partial mixer because each returns them to |0>);
* sections ``initial_state``, then ``phase_k`` and ``mixer_k`` for ``k = 0 .. p-1``; every partial mixer is a
  section of its own (all named ``mixer_k``), so lowering passes never act across two partial mixers and each
  partial mixer's lowered cost is self-contained (see ``docs/architecture.md``);
* ``2p`` symbols ``gamma_0, beta_0, ..., gamma_{p-1}, beta_{p-1}``, bound later with ``Circuit.bind``.

The circuit applied to |0...0> gives ``prod_k U_M(beta_k) exp(-i gamma_k (C - c0)) |x_0>``; the
feasible-subspace simulator (:mod:`simulate.subspace`) implements the very same operator.

Example:
    >>> from gridcover.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> c = qaoa_circuit(s, p=1)
    >>> c.symbols, [sec.name for sec in c.sections]
    (('gamma_0', 'beta_0'), ['initial_state', 'phase_0', 'mixer_0', 'mixer_0', 'mixer_0', 'mixer_0'])
"""

from __future__ import annotations

import dataclasses
from collections import Counter
from collections.abc import Hashable, Iterator
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from gridcover.hamiltonian import ising_hamiltonian
from gridcover.sbf import Rule
from gridcover.scenario import Scenario

from .angles import Angle
from .circuit import Circuit, Register, Section
from .cost import Cost, Target
from .gadgets import Gadget
from .gadgets.blocks import StatePrep, WholeSpacePhase
from .gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer, partial_mixer
from .lowering import WORK_REGISTER


@dataclass(frozen=True)
class QubitMap:
    """Where each qubit of a compiled circuit comes from.

    Attributes:
        data: For each data qubit ``i``: ``(robot, grid edge index)``.
        ancillas: Indices of every other qubit (``logic`` and, after lowering, ``work``).
    """

    data: tuple[tuple[int, int], ...]
    ancillas: tuple[int, ...]


def qubit_map(scenario: Scenario, circuit: Circuit) -> QubitMap:
    """The :class:`QubitMap` of a circuit built by :func:`qaoa_circuit` (lowered or not)."""
    n = scenario.num_variables
    return QubitMap(
        tuple(scenario.variable_of(i) for i in range(n)),
        tuple(range(n, circuit.num_qubits)),
    )


@dataclass(frozen=True)
class QaoaPlan:
    """The QAOA circuit as gadgets: what :func:`qaoa_circuit` emits, and its cost without emitting it.

    Attributes:
        scenario: The scenario.
        p: Layers.
        rule: SBF rule.
        initial: Initial state.
        target: ``nisq`` or ``ft`` (which partial-mixer construction is cheapest).
        options: Reserved for the phase separator's options.
    """

    scenario: Scenario
    p: int
    rule: Rule = "exact"
    initial: str = "initial_path"
    target: Target = "nisq"
    options: tuple[tuple[str, Any], ...] = field(default=())

    # -- layout
    @cached_property
    def _mixers(self) -> tuple[ParityPartialMixer | McxPartialMixer, ...]:
        s, n = self.scenario, self.scenario.num_variables
        out = []
        for r in range(s.num_robots):
            for q in s.grid.plaquettes:
                m = partial_mixer(s, r, q, Angle.symbol("beta"), n, self.rule, self.target)
                if m is not None:
                    out.append(m)
        return tuple(out)

    @cached_property
    def _prep(self) -> StatePrep:
        s = self.scenario
        ancilla = s.num_variables if self.initial == "representatives" else None
        return StatePrep.build(s, self.initial, self.rule, ancilla)

    @cached_property
    def _phase(self) -> WholeSpacePhase | None:
        return WholeSpacePhase(ising_hamiltonian(self.scenario), "gamma") if self.p else None

    @cached_property
    def logic_width(self) -> int:
        """Shared clean ``logic`` ancillas: the largest partial mixer (at least 1 for ``representatives``)."""
        width = max((m.num_temps for m in self._mixers), default=0)
        return max(width, 1 if self.initial == "representatives" else 0)

    @cached_property
    def work_width(self) -> int:
        """``work`` ancillas the lowering adds for multi-controlled X with three or more controls."""
        mixer = max((len(sl) - 3 for m in self._mixers for name, sl in m.plan.compute if name == "mcx"), default=0)
        prep = max((len(g.qubits) - 3 for g in self._prep.gates if g.name == "mcx"), default=0)
        return max(mixer if self.p else 0, prep, 0)

    @property
    def registers(self) -> tuple[Register, ...]:
        """``data``, ``logic`` (if any), and the ``work`` register the lowering adds (if any)."""
        regs = [Register("data", self.scenario.num_variables)]
        if self.logic_width:
            regs.append(Register("logic", self.logic_width))
        if self.work_width:
            regs.append(Register(WORK_REGISTER, self.work_width))
        return tuple(regs)

    @property
    def num_qubits(self) -> int:
        """All qubits of the lowered circuit."""
        return sum(r.size for r in self.registers)

    # -- the call graph
    def sections(self) -> Iterator[tuple[str, Gadget]]:
        """``(section name, gadget)`` in circuit order: the state preparation, then per layer the phase
        separator and one section per partial mixer (robot-major, plaquettes row-major)."""
        yield "initial_state", self._prep
        for k in range(self.p):
            assert self._phase is not None
            yield f"phase_{k}", WholeSpacePhase(self._phase.hamiltonian, f"gamma_{k}")
            beta = Angle.symbol(f"beta_{k}")
            for m in self._mixers:
                yield f"mixer_{k}", dataclasses.replace(m, beta=beta)

    def kinds(self) -> dict[str, Counter[Hashable]]:
        """Gadget kinds and multiplicities of one layer's parts: ``initial_state``, ``phase``, ``mixer``."""
        out: dict[str, Counter[Hashable]] = {
            "initial_state": Counter([self._prep.kind]),
            "phase": Counter([self._phase.kind] if self._phase else []),
            "mixer": Counter(m.kind for m in self._mixers),
        }
        return out

    def _part_costs(self, logical: bool) -> dict[str, Cost]:
        def of(g: Any) -> Cost:
            return g.logical_cost() if logical else g.cost()

        by_kind: dict[Hashable, Cost] = {}
        for m in self._mixers:
            if m.kind not in by_kind:
                by_kind[m.kind] = of(m)
        mixer = Cost.sum(by_kind[m.kind] for m in self._mixers)
        phase = of(self._phase) if self._phase else Cost()
        return {"initial_state": of(self._prep), "phase": phase, "mixer": mixer}

    def cost_by_section(self, logical: bool = False) -> dict[str, Cost]:
        """Cost of the state preparation and of ONE layer's phase separator and mixer (keys ``initial_state``,
        ``phase``, ``mixer``); multiply the last two by ``p`` for the circuit."""
        return self._part_costs(logical)

    def cost(self) -> Cost:
        """Lowered cost of the whole circuit: state preparation + ``p`` x (phase separator + mixer)."""
        parts = self._part_costs(False)
        return parts["initial_state"] + self.p * (parts["phase"] + parts["mixer"])

    def logical_cost(self) -> Cost:
        """Like :meth:`cost` with ANDs and Toffolis kept whole (the fault-tolerant view)."""
        parts = self._part_costs(True)
        return parts["initial_state"] + self.p * (parts["phase"] + parts["mixer"])

    def circuit(self) -> Circuit:
        """The high-level circuit (one section per gadget)."""
        regs = [r for r in self.registers if r.name != WORK_REGISTER]
        sections = []
        for name, g in self.sections():
            blocks = g.emit_blocks() if isinstance(g, McxPartialMixer | ParityPartialMixer) else [g.emit()]
            sections.extend(Section(name, tuple(b)) for b in blocks)
        return Circuit(regs, sections)


def qaoa_plan(
    scenario: Scenario,
    p: int,
    rule: Rule = "exact",
    initial: str = "initial_path",
    target: Target = "nisq",
) -> QaoaPlan:
    """The :class:`QaoaPlan` (gadgets and costs) of the QAOA circuit; see :func:`qaoa_circuit`."""
    if not isinstance(p, int) or isinstance(p, bool) or p < 0:
        raise ValueError(f"p must be a non-negative integer, got {p!r}")
    if initial not in ("initial_path", "representatives"):
        raise ValueError(f"unknown initial state {initial!r} (expected 'initial_path' or 'representatives')")
    if target not in ("nisq", "ft"):
        raise ValueError(f"unknown target {target!r} (expected 'nisq' or 'ft')")
    return QaoaPlan(scenario, p, rule, initial, target)


def qaoa_circuit(
    scenario: Scenario,
    p: int,
    rule: Rule = "exact",
    initial: str = "initial_path",
    target: Target = "nisq",
) -> Circuit:
    """Build the parameterised QAOA circuit (high level: and/and_dg, crx, cx, x, rz, rzz, mcx, csbf, ...).

    Args:
        scenario: The scenario.
        p: Number of layers (>= 0).
        rule: SBF logic rule, ``exact`` (default) or ``paper``.
        initial: ``initial_path`` (default) or ``representatives`` (see :mod:`circuitgen.initial_state`).
        target: ``nisq`` (default) or ``ft``: which partial-mixer construction is cheapest
            (see :mod:`circuitgen.gadgets.partial_mixer`).

    Returns:
        The circuit (see the module docstring for its layout).
    """
    return qaoa_plan(scenario, p, rule, initial, target).circuit()
