"""The state preparation as a gadget (partial mixers: :mod:`.partial_mixer`; phase separator: :mod:`.phase_ising`,
:mod:`.phase_visits`, :mod:`.phase_sums`).

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> prep = StatePrep.build(s)
    >>> prep.cost().to_dict()
    {'x': 4}
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

from qcpp.gadgets.initial_state import initial_state_gates
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.problem.sbf import Rule
from qcpp.problem.scenario import Scenario

__all__ = ["StatePrep", "XLayerKind"]


class XLayerKind(NamedTuple):
    """Kind key of a state preparation that is one layer of X gates on distinct qubits.

    Attributes:
        gadget: ``"x_layer"``.
        count: the number of X gates.
    """

    gadget: str
    count: int


@dataclass(frozen=True)
class StatePrep:
    """The initial state (:mod:`qcpp.gadgets.initial_state`) as a gadget.

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
        """The state preparation of ``scenario`` (see :func:`~qcpp.gadgets.initial_state.initial_state_gates`)."""
        gates = tuple(initial_state_gates(scenario, initial, rule, ancilla))
        n = max((q + 1 for g in gates for q in g.qubits), default=scenario.num_variables)
        return cls(gates, max(n, scenario.num_variables))

    @property
    def kind(self) -> Hashable:
        """``("x_layer", n)`` for ``n`` X gates on distinct qubits (equal up to qubit names), else the gate list
        itself (a state preparation is one of a kind)."""
        if all(g.name == "x" for g in self.gates) and len({g.qubits for g in self.gates}) == len(self.gates):
            return XLayerKind("x_layer", len(self.gates))
        return ("state_prep", self.gates)

    def needs(self) -> tuple[int, int]:
        """No temporaries; the lowering of an mcx with ``k`` controls needs ``k - 2`` work ancillas."""
        return 0, max([0, *(len(g.qubits) - 3 for g in self.gates if g.name == "mcx")])

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
