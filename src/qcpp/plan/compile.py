"""One call from a scenario to a finished circuit and its summary (what ``qcpp compile`` prints).

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> result = compile_scenario(default_scenario(3, 3, 1), 1, lowered=True, bindings={"gamma_0": 0.3})
    >>> result.circuit.symbols, result.summary()["qubits"]
    (('beta_0',), 15)
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from qcpp.errors import OptionError
from qcpp.ir.circuit import Circuit, Register
from qcpp.lowering.passes import WORK_REGISTER, lower
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.plan.qaoa import QaoaPlan, QubitMap, qaoa_plan, qubit_map
from qcpp.problem.scenario import Scenario

if TYPE_CHECKING:
    from qcpp.problem.solvers.result import ProgressFn


@dataclass(frozen=True)
class CompileResult:
    """A compiled QAOA circuit with where its qubits come from.

    Attributes:
        scenario: The scenario compiled.
        circuit: The circuit (high level, or lowered to {cx, x, h, rz, t, tdg, s, sdg}).
        qubit_map: Data qubit -> (robot, edge); ancilla qubits.
        lowered: Whether :func:`qcpp.lowering.passes.lower` was applied.
        seconds: Wall time of building, lowering and binding.
        plan: The plan the circuit was emitted from: its sections are ``plan.sections()``, gadget by gadget, for a
            later pass that rewrites a gadget's section (:mod:`qcpp.pipeline.routed_mixers`).
        phase_explain: The phase plan's choice per term group (:meth:`qcpp.plan.phase.PhasePlan.explain`).
    """

    scenario: Scenario
    circuit: Circuit
    qubit_map: QubitMap
    lowered: bool
    seconds: float
    plan: QaoaPlan
    phase_explain: list[dict] = field(default_factory=list)

    def summary(self) -> dict[str, Any]:
        """JSON-ready summary (:func:`compile_summary`)."""
        c = self.circuit
        return compile_summary(self.scenario, c.registers, c.count_ops(), c.symbols, self.lowered, self.seconds)


def compile_summary(
    scenario: Scenario,
    registers: Sequence[Register],
    ops: Mapping[str, int],
    symbols: Sequence[str],
    lowered: bool,
    seconds: float,
) -> dict[str, Any]:
    """What ``qcpp compile`` prints of a circuit of :func:`~qcpp.plan.qaoa.qaoa_circuit` (whole, or streamed
    section by section).

    Args:
        scenario: The scenario compiled.
        registers: The circuit's registers.
        ops: Its gate count per name.
        symbols: Its unbound symbols.
        lowered: Whether it was lowered.
        seconds: Wall time of building it.

    Returns:
        JSON-ready: ``qubits``, ``gates`` (count per name), ``total_gates``, ``lowered``, ``symbols``,
        ``registers``, ``seconds`` and ``qubit_map`` (``data``: list of ``{qubit, robot, edge: [[r, c], [r, c]]}``;
        ``ancillas``).
    """
    edges = scenario.grid.edges
    num_qubits = sum(r.size for r in registers)
    qmap = qubit_map(scenario, num_qubits)
    data = [
        {"qubit": q, "robot": r, "edge": [list(edges[e][0]), list(edges[e][1])]} for q, (r, e) in enumerate(qmap.data)
    ]
    return {
        "qubits": num_qubits,
        "gates": dict(sorted(ops.items())),
        "total_gates": sum(ops.values()),
        "lowered": lowered,
        "symbols": list(symbols),
        "registers": {r.name: r.size for r in registers},
        "seconds": seconds,
        "qubit_map": {"data": data, "ancillas": list(qmap.ancillas)},
    }


def compile_scenario(
    scenario: Scenario,
    p: int,
    options: PlanOptions = DEFAULT_PLAN,
    *,
    lowered: bool = False,
    bindings: Mapping[str, float] | None = None,
    bind_field: str = "bind",
    progress: ProgressFn | None = None,
    stage: Callable[[str], None] | None = None,
) -> CompileResult:
    """Build (and optionally lower and bind) the QAOA circuit of a scenario.

    Args:
        options: How the circuit is built (:class:`~qcpp.plan.options.PlanOptions`).
        lowered: Lower to the CNOT + single-qubit basis.
        bindings: Values for some or all of the symbols ``gamma_k``, ``beta_k``.
        bind_field: The argument that gave ``bindings``, starting the message of a bad one (``--bind`` in the CLI).
        progress: Called as ``progress(gates, None)`` after each section is built (lowered, if ``lowered``), with
            the gates built so far. With it (or ``stage``) the circuit is built section by section
            (:meth:`~qcpp.plan.qaoa.QaoaPlan.emit_sections`, lowered one by one), the same circuit as lowering
            the whole one.
        stage: Called with ``planning the circuit`` and ``building the sections`` as each starts.

    Raises:
        qcpp.errors.OptionError: if ``bindings`` names a symbol the circuit does not have.
    """
    start = time.perf_counter()
    if stage is not None:
        stage("planning the circuit")
    plan = qaoa_plan(scenario, p, options)
    if progress is None and stage is None:
        circuit = plan.circuit()
        if bindings:
            plan.check_bindings(bindings, bind_field)
        if lowered:
            circuit = lower(circuit)
    else:
        if bindings:
            plan.check_bindings(bindings, bind_field)
        if stage is not None:
            stage("building the sections")
        # the lowered circuit has the plan's registers (work included); the high-level one has no work register
        registers = plan.registers if lowered else tuple(r for r in plan.registers if r.name != WORK_REGISTER)
        sections = []
        built = 0
        for sec in plan.emit_sections(lowered):
            sections.append(sec)
            built += len(sec.gates)
            if progress is not None:
                progress(built, None)
        circuit = Circuit(registers, sections)
    if bindings:
        circuit = circuit.bind(bindings)
    explain = plan.phase_plan.explain() if plan.phase_plan is not None else []
    qmap = qubit_map(scenario, circuit.num_qubits)
    return CompileResult(scenario, circuit, qmap, lowered, time.perf_counter() - start, plan, explain)


def parse_bindings(items: list[str]) -> dict[str, float]:
    """Parse ``["gamma_0=0.3", "beta_0=0.7"]`` (also comma-separated) into a mapping.

    Raises:
        ValueError: naming the malformed item, or a name given twice (even with the same value: a repeated name
            is a typo for another angle more often than not).

    Example:
        >>> parse_bindings(["gamma_0=0.3", "beta_0=0.7,gamma_1=1"])
        {'gamma_0': 0.3, 'beta_0': 0.7, 'gamma_1': 1.0}
    """
    out: dict[str, float] = {}
    for item in items:
        for part in filter(None, (s.strip() for s in item.split(","))):
            name, sep, value = part.partition("=")
            name = name.strip()
            if not sep or not name:
                raise ValueError(f"--bind: expected NAME=VALUE, got {part!r}")
            try:
                number = float(value)
            except ValueError:
                raise ValueError(f"--bind: {name} needs a number, got {value!r}") from None
            if name in out:
                raise ValueError(f"--bind: {name} is given twice ({out[name]:g} and {number:g}); bind each name once")
            out[name] = number
    return out


def check_binding_values(bindings: Mapping[str, object], flag: str = "--bind") -> dict[str, float]:
    """``bindings`` as ``{name: float}`` if every name is text and every value a finite number (the check of
    ``qcpp compile --bind`` and of ``qcpp.compile(bind=...)``; the names are checked against the circuit's
    symbols when it is built, :meth:`qcpp.plan.qaoa.QaoaPlan.check_bindings`).

    Args:
        bindings: Symbol name -> value.
        flag: The option's name in messages.

    Returns:
        The bindings, values as floats.

    Raises:
        qcpp.errors.OptionError: naming the option and the symbol.

    Example:
        >>> check_binding_values({"gamma_0": 1})
        {'gamma_0': 1.0}
        >>> check_binding_values({"beta_0": float("nan")}, "bind")
        Traceback (most recent call last):
        ...
        qcpp.errors.OptionError: bind: beta_0 needs a finite number, got nan
    """
    if not isinstance(bindings, Mapping):
        raise OptionError(flag, f"expected a mapping of symbol name to value, got {bindings!r}")
    out: dict[str, float] = {}
    for name, value in bindings.items():
        if not isinstance(name, str):
            raise OptionError(flag, f"expected symbol names as text, got {name!r}")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise OptionError(flag, f"{name} needs a finite number, got {value!r}")
        out[name] = float(value)
    return out
