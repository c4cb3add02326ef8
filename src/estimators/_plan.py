"""TEMPORARY: the ``qaoa_plan`` contract, built from a materialised circuit, until ``circuitgen.qaoa.qaoa_plan``
lands on main (then this module re-exports it and the fallback below is deleted).

The fallback builds the whole circuit and lowers it: it has the contract's interface, not its speed.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from circuitgen.circuit import Circuit, Register, Section
from circuitgen.cost import Cost
from circuitgen.lowering import LOGICAL_BASIS, lower

try:  # pragma: no cover - which branch runs depends on circuitgen's version
    from circuitgen.qaoa import qaoa_plan  # type: ignore[attr-defined]
except ImportError:  # pragma: no cover
    from circuitgen.qaoa import qaoa_circuit

    @dataclass(frozen=True)
    class _SectionGadget:
        name: str
        gates: tuple[Any, ...]
        registers: tuple[Register, ...]

        @property
        def kind(self) -> Any:
            return (self.name, self.gates)

        def emit(self) -> tuple[Any, ...]:
            return self.gates

        def _lowered(self, basis: frozenset[str]) -> Cost:
            return Cost.count(lower(Circuit(self.registers, [Section(self.name, self.gates)]), basis).gates)

        def cost(self) -> Cost:
            return self._lowered(frozenset({"cx", "x", "h", "rz", "t", "tdg", "s", "sdg"}))

        def logical_cost(self) -> Cost:
            return self._lowered(LOGICAL_BASIS)

    @dataclass(frozen=True)
    class _CircuitPlan:
        circuit: Circuit
        registers: tuple[Register, ...] = field(default=())

        def sections(self) -> Iterator[tuple[str, _SectionGadget]]:
            for sec in self.circuit.sections:
                yield sec.name, _SectionGadget(sec.name, sec.gates, self.registers)

        def cost(self) -> Cost:
            return Cost.count(lower(self.circuit).gates)

        def logical_cost(self) -> Cost:
            return Cost.count(lower(self.circuit, LOGICAL_BASIS).gates)

        def cost_by_section(self) -> dict[str, Cost]:
            low = lower(self.circuit)
            out: dict[str, Cost] = {}
            for sec in low.sections:
                key = sec.name.split("_")[0] if sec.name != "initial_state" else sec.name
                if sec.name in ("initial_state", "phase_0", "mixer_0"):
                    out[key] = out.get(key, Cost()) + Cost.count(sec.gates)
            return out

        @property
        def num_qubits(self) -> int:
            return sum(r.size for r in self.registers)

    def qaoa_plan(  # type: ignore[no-redef]
        scenario: Any,
        p: int,
        *,
        rule: str = "exact",
        initial: str = "initial_path",
        target: str = "nisq",
        phase: str = "feasible",
        optimize: str = "cx",
    ) -> _CircuitPlan:
        circ = qaoa_circuit(scenario, p, rule=rule, initial=initial)  # type: ignore[arg-type]
        return _CircuitPlan(circ, lower(circ).registers)


__all__ = ["qaoa_plan"]
