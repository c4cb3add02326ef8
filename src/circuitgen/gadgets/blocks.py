"""Gadgets for the parts of a QAOA circuit that are not partial mixers: state preparation and the whole-space
phase separator.

Example:
    >>> from gridcover.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> prep = StatePrep.build(s)
    >>> prep.cost().to_dict()
    {'x': 4}
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass
from functools import cached_property

from gridcover.hamiltonian import IsingHamiltonian
from gridcover.sbf import Rule
from gridcover.scenario import Scenario

from ..angles import Angle
from ..circuit import Circuit, Section
from ..cost import Cost
from ..gates import Gate, rz, rzz
from ..initial_state import initial_state_gates
from ..lowering import LOGICAL_BASIS, lower

__all__ = ["COEFFICIENT_TOLERANCE", "StatePrep", "WholeSpacePhase"]

#: Coefficients smaller than this (absolute) are treated as zero: they only arise from float round-off.
COEFFICIENT_TOLERANCE = 1e-12


@dataclass(frozen=True)
class StatePrep:
    """The initial state (:mod:`circuitgen.initial_state`) as a gadget.

    Its cost is read from its own short lowered gate list (a few hundred gates at most: X gates of the initial
    paths, or the decision tree over a handful of representative paths), not from a closed form; the
    gadget test checks it like every other.

    Attributes:
        gates: the high-level gates.
        num_qubits: qubits the gates may touch (for lowering).
    """

    gates: tuple[Gate, ...]
    num_qubits: int

    @classmethod
    def build(
        cls, scenario: Scenario, initial: str = "initial_path", rule: Rule = "exact", ancilla: int | None = None
    ) -> StatePrep:
        """The state preparation of ``scenario`` (see :func:`~circuitgen.initial_state.initial_state_gates`)."""
        gates = tuple(initial_state_gates(scenario, initial, rule, ancilla))
        n = max((q + 1 for g in gates for q in g.qubits), default=scenario.num_variables)
        return cls(gates, max(n, scenario.num_variables))

    @property
    def kind(self) -> Hashable:
        """The gate list itself (state preparation is one of a kind)."""
        return ("state_prep", self.gates)

    @cached_property
    def _lowered(self) -> tuple[Cost, Cost]:
        c = Circuit([("q", self.num_qubits)], [Section("initial_state", self.gates)])
        return Cost.count(lower(c).gates), Cost.count(lower(c, LOGICAL_BASIS).gates)

    def cost(self) -> Cost:
        """Lowered cost."""
        if all(g.name == "x" for g in self.gates):
            return Cost.of(x=len(self.gates))
        return self._lowered[0]

    def logical_cost(self) -> Cost:
        """Cost with ANDs and Toffolis kept whole."""
        if all(g.name == "x" for g in self.gates):
            return Cost.of(x=len(self.gates))
        return self._lowered[1]

    def emit(self) -> list[Gate]:
        """The gates."""
        return list(self.gates)


@dataclass(frozen=True)
class WholeSpacePhase:
    """``exp(-i gamma (C - c0))`` on every basis state: one RZ per linear and one RZZ per quadratic term.

    Cost: ``rz`` per linear term; ``cx, rz, cx`` per quadratic term (2 CX each, the ``(re)^2`` growth).

    Attributes:
        hamiltonian: the exact Ising Hamiltonian.
        gamma: the layer's symbol.
        data_offset: qubit of variable 0.
    """

    hamiltonian: IsingHamiltonian
    gamma: str
    data_offset: int = 0

    @property
    def kind(self) -> Hashable:
        """Term counts (the cost depends on nothing else)."""
        return ("whole_space_phase", self._terms)

    @cached_property
    def _terms(self) -> tuple[int, int]:
        tol = COEFFICIENT_TOLERANCE
        return sum(1 for _ in self.hamiltonian.linear_terms(tol)), self.hamiltonian.num_quadratic_terms(tol)

    def cost(self) -> Cost:
        """``rz`` per linear term, ``2 cx + rz`` per coupling."""
        lin, quad = self._terms
        return Cost.of(rz=lin + quad, cx=2 * quad)

    def logical_cost(self) -> Cost:
        """Same as :meth:`cost` (no ANDs)."""
        return self.cost()

    def emit(self) -> list[Gate]:
        """RZ gates by qubit, then RZZ row-major by ``(i, j)``; all commute."""
        tol, off, gamma = COEFFICIENT_TOLERANCE, self.data_offset, self.gamma
        out = [rz(Angle.symbol(gamma, 2.0 * hi), off + i) for i, hi in self.hamiltonian.linear_terms(tol)]
        out += [
            rzz(Angle.symbol(gamma, 2.0 * jij), off + i, off + j)
            for i, j, jij in self.hamiltonian.quadratic_terms(tol)
        ]
        return out
