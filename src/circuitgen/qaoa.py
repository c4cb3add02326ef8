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

from dataclasses import dataclass

from gridcover.hamiltonian import ising_hamiltonian
from gridcover.sbf import Rule
from gridcover.scenario import Scenario

from .angles import Angle
from .circuit import Circuit, Register, Section
from .initial_state import initial_state_gates
from .mixer import logic_width, partial_mixer_gates
from .phase import phase_separator_gates


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


def qaoa_circuit(
    scenario: Scenario,
    p: int,
    rule: Rule = "exact",
    initial: str = "initial_path",
) -> Circuit:
    """Build the parameterised QAOA circuit (high level: mcx, csbf, rz, rzz, x, ...).

    Args:
        scenario: The scenario.
        p: Number of layers (>= 0).
        rule: SBF logic rule, ``exact`` (default) or ``paper``.
        initial: ``initial_path`` (default) or ``representatives`` (see :mod:`circuitgen.initial_state`).

    Returns:
        The circuit (see the module docstring for its layout).
    """
    if not isinstance(p, int) or p < 0:
        raise ValueError(f"p must be a non-negative integer, got {p!r}")
    n = scenario.num_variables
    width = logic_width(scenario, rule)
    needs_prep_ancilla = initial == "representatives"
    width = max(width, 1 if needs_prep_ancilla else 0)
    registers = [Register("data", n)]
    if width:
        registers.append(Register("logic", width))
    ancilla = n if width else None
    sections = [Section("initial_state", tuple(initial_state_gates(scenario, initial, rule, ancilla)))]
    hamiltonian = ising_hamiltonian(scenario) if p else None
    for k in range(p):
        assert hamiltonian is not None
        sections.append(Section(f"phase_{k}", tuple(phase_separator_gates(hamiltonian, f"gamma_{k}"))))
        beta = Angle.symbol(f"beta_{k}")
        # one section per partial mixer (all named mixer_k): passes stay inside a partial mixer
        for r in range(scenario.num_robots):
            for q in scenario.grid.plaquettes:
                gates = partial_mixer_gates(scenario, r, q, beta, n, rule)
                if gates:
                    sections.append(Section(f"mixer_{k}", tuple(gates)))
    return Circuit(registers, sections)
