"""Evaluate given QAOA angles with one of the simulators: the method dispatch behind ``qcpp simulate``.

Methods:

``subspace``
    :class:`~qcpp.simulate.subspace.SubspaceQAOA`: the exact state on the reachable feasible assignments. The
    probability held there is 1 by construction.
``statevector``
    The compiled, lowered circuit (:func:`qcpp.plan.compile.compile_scenario`) run by the dense simulator
    (:func:`qcpp.simulate.statevector.simulate_statevector`); refused above :data:`MAX_STATEVECTOR_QUBITS` qubits.
``tensor``
    Amplitudes of the compiled circuit from the tensor-network backend (:mod:`qcpp.simulate.tensor`), one per
    feasible assignment with clean ancillas.

Every method reports the same numbers for the same angles:

* ``expectation``: ``<C>`` of the measured data register (``tensor``: over the feasible assignments with clean
  ancillas, divided by ``amplitudes_held``);
* ``p_optimum``: probability that the data register reads an optimal feasible assignment;
* ``amplitudes_held``: total probability on feasible assignments with every ancilla back in ``|0>`` (1 for
  ``subspace`` by construction; for the gate-level methods 1 up to rounding when the circuit is right).

Random angles (no ``angles`` given): :func:`qcpp.training.training.initial_angles` with ``init="random"`` on the
exact-rule subspace simulator, so the same seed gives the same angles for every method.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 0], "goal": [1, 2]}]})
    >>> a = evaluate(s, 1, "subspace", angles=[0.4, 1.1])
    >>> b = evaluate(s, 1, "statevector", angles=[0.4, 1.1])
    >>> abs(a.expectation - b.expectation) < 1e-9, round(b.amplitudes_held, 9), a.method, b.qubits
    (True, 1.0, 'subspace', 8)
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from typing import Any, Literal

import numpy as np

from qcpp.gadgets.initial_state import INITIAL_STATES, Initial
from qcpp.plan.options import PlanOptions
from qcpp.problem.cost import cost_parts_bits
from qcpp.problem.paths import assignment_bits, enumerate_paths
from qcpp.problem.sbf import RULES, Rule
from qcpp.problem.scenario import Scenario
from qcpp.simulate.statevector import MAX_STATEVECTOR_QUBITS
from qcpp.simulate.subspace import SubspaceQAOA, angle_bindings, split_angles
from qcpp.training.training import check_at_least, initial_angles

__all__ = ["MAX_STATEVECTOR_QUBITS", "METHODS", "Evaluation", "evaluate", "feasible_assignments", "resolve_angles"]

Method = Literal["subspace", "statevector", "tensor"]
METHODS: tuple[Method, ...] = ("subspace", "statevector", "tensor")

_OPT_TOL = 1e-9


@dataclass(frozen=True)
class Evaluation:
    """One simulator's numbers at one angle vector.

    Attributes:
        method: ``subspace``, ``statevector`` or ``tensor``.
        angles: ``[gamma_0, beta_0, ...]``.
        expectation: ``<C>``.
        p_optimum: Probability of reading an optimal feasible assignment.
        amplitudes_held: Probability on feasible assignments with clean ancillas.
        seconds: Wall-clock time of the evaluation (compilation included).
        qubits: Qubits simulated (gate-level methods; ``None`` for ``subspace``).
        basis_states: Amplitudes the method computed (the subspace dimension, ``2**qubits``, or the number of
            feasible assignments for ``tensor``).
    """

    method: str
    p: int
    angles: tuple[float, ...]
    expectation: float
    p_optimum: float
    amplitudes_held: float
    seconds: float
    qubits: int | None
    basis_states: int

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready dict (``angles`` as a list)."""
        d = asdict(self)
        d["angles"] = list(self.angles)
        return d


def resolve_angles(
    scenario: Scenario, p: int, angles: Sequence[float] | None = None, seed: int | None = None
) -> np.ndarray:
    """The given angles (checked: ``2p`` finite values), or seeded random ones (see the module docstring).

    Raises:
        ValueError: if ``p < 1`` or the angles do not fit.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> resolve_angles(s, 1, [0.1, 0.2]).tolist(), len(resolve_angles(s, 2, seed=3))
        ([0.1, 0.2], 4)
    """
    check_at_least(p=(p, 1))
    if angles is None:
        return initial_angles(SubspaceQAOA(scenario), p, "random", seed)
    a = np.asarray(angles, dtype=float).reshape(-1)
    if a.size != 2 * p:
        raise ValueError(f"p={p} needs {2 * p} angles [gamma_0, beta_0, ...], got {a.size}")
    split_angles(a)  # finite values
    return a


def evaluate(
    scenario: Scenario,
    p: int,
    method: Method = "subspace",
    angles: Sequence[float] | None = None,
    seed: int | None = None,
    rule: Rule = "exact",
    client: Any = None,
    initial: Initial = "initial_path",
) -> Evaluation:
    """Simulate the QAOA state at the given (or seeded random) angles with ``method``.

    Args:
        p: Layers (>= 1).
        method: ``subspace``, ``statevector`` or ``tensor``.
        angles: ``2p`` angles; ``None`` for random ones from ``seed``.
        seed: Seed of the random angles.
        rule: SBF rule of the mixer.
        initial: The initial state (:data:`qcpp.gadgets.initial_state.INITIAL_STATES`): the subspace simulator
            starts from it and the gate-level methods compile its preparation, so angles trained from a state
            are evaluated on the state they were trained from.
        client: ``tensor``: a connected ``dask.distributed.Client`` that runs the slices of contractions wider than
            :data:`qcpp.simulate.tensor.DEFAULT_MAX_WIDTH` (:class:`~qcpp.simulate.tensor.TensorCircuit`).

    Raises:
        ValueError: unknown method or rule, angles that do not fit, too many qubits for ``statevector``, or
            a mixer the subspace simulator cannot represent (:class:`~qcpp.simulate.subspace.NonUnitaryMixerError`).
    """
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r} (expected one of {', '.join(METHODS)})")
    if rule not in RULES:
        raise ValueError(f"unknown SBF rule {rule!r} (expected one of {', '.join(RULES)})")
    if initial not in INITIAL_STATES:
        raise ValueError(f"unknown initial state {initial!r} (expected one of {', '.join(INITIAL_STATES)})")
    x = resolve_angles(scenario, p, angles, seed)
    t0 = time.perf_counter()
    if method == "subspace":
        q = SubspaceQAOA(scenario, rule=rule, initial=initial)
        psi = q.state(x)
        e, popt = q.expectation_from_state(psi), q.p_optimum_from_state(psi)
        held = float(np.sum(np.abs(psi[np.ix_(*q.feasible)]) ** 2)) if rule != "exact" else 1.0
        return Evaluation(method, p, _tup(x), e, popt, held, time.perf_counter() - t0, None, q.dimension)
    options = PlanOptions(rule=rule, initial=initial)
    if method == "statevector":
        return _statevector(scenario, p, x, options, t0)
    return _tensor(scenario, p, x, options, t0, client)


def _tup(x: np.ndarray) -> tuple[float, ...]:
    return tuple(float(v) for v in x)


def feasible_assignments(scenario: Scenario) -> tuple[np.ndarray, np.ndarray]:
    """Every feasible assignment of ``scenario`` (one path per robot) and which of them are optimal.

    Returns:
        ``(indices, optimal)``: the data-register integer of each feasible assignment (bit ``i`` = variable ``i``)
        and a boolean mask of those whose total cost is the minimum (within a relative ``1e-9``).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> indices, optimal = feasible_assignments(default_scenario(2, 2, 1))
        >>> len(indices), int(optimal.sum())
        (2, 2)
    """
    lists = [enumerate_paths(scenario, r) for r in range(scenario.num_robots)]
    weights = 1 << np.arange(scenario.num_variables, dtype=np.int64)
    combos = list(itertools.product(*lists))
    bits = np.array([assignment_bits(scenario, c) for c in combos], dtype=np.int64)
    costs = cost_parts_bits(scenario, bits)[:, 3]
    best = costs.min()
    return bits @ weights, costs <= best + _OPT_TOL * max(1.0, abs(best))


def _statevector(scenario: Scenario, p: int, x: np.ndarray, options: PlanOptions, t0: float) -> Evaluation:
    from qcpp.plan.compile import compile_scenario
    from qcpp.simulate.statevector import simulate_statevector

    if scenario.num_variables > MAX_STATEVECTOR_QUBITS:  # refuse before compiling
        n = scenario.num_variables
        raise ValueError(
            f"statevector: the circuit has at least {n} qubits (its data register), more than "
            f"{MAX_STATEVECTOR_QUBITS}; use --method subspace or tensor"
        )
    compiled = compile_scenario(scenario, p, options, lowered=True, bindings=angle_bindings(x))
    n = compiled.circuit.num_qubits
    if n > MAX_STATEVECTOR_QUBITS:
        raise ValueError(
            f"statevector: the compiled circuit has {n} qubits, more than {MAX_STATEVECTOR_QUBITS} "
            f"(2^{n} amplitudes would need {16 * 2.0**n / 2**30:.3g} GiB); use --method subspace or tensor"
        )
    psi = simulate_statevector(compiled.circuit)
    probs = psi.real * psi.real + psi.imag * psi.imag
    nd = scenario.num_variables
    support = np.flatnonzero(probs > 0.0)
    data = support & ((1 << nd) - 1)
    bits = (data[:, None] >> np.arange(nd)) & 1
    costs = cost_parts_bits(scenario, bits)[:, 3]
    expectation = float(np.dot(probs[support], costs))
    feasible, optimal = feasible_assignments(scenario)
    held = float(probs[feasible].sum())  # data index == full index when the ancillas (above the data) are 0
    p_opt = float(probs[support][np.isin(data, feasible[optimal])].sum())  # any ancilla value
    return Evaluation("statevector", p, _tup(x), expectation, p_opt, held, time.perf_counter() - t0, n, 1 << n)


def _tensor(
    scenario: Scenario, p: int, x: np.ndarray, options: PlanOptions, t0: float, client: Any = None
) -> Evaluation:
    from qcpp.plan.compile import compile_scenario

    try:
        from qcpp.simulate import tensor
    except ImportError as exc:  # pragma: no cover - the backend module is optional at import time
        raise ValueError(f"tensor: the tensor-network backend is unavailable ({exc})") from None
    compiled = compile_scenario(scenario, p, options, lowered=True, bindings=angle_bindings(x))
    feasible, optimal = feasible_assignments(scenario)
    circuit = tensor.TensorCircuit(compiled.circuit, client=client)
    amps = np.asarray(circuit.amplitudes(feasible.tolist()), dtype=complex)
    probs = amps.real * amps.real + amps.imag * amps.imag
    nd = scenario.num_variables
    bits = (feasible[:, None] >> np.arange(nd)) & 1
    costs = cost_parts_bits(scenario, bits)[:, 3]
    held = float(probs.sum())
    expectation = float(np.dot(probs, costs) / held) if held > 0 else math.nan
    return Evaluation(
        "tensor", p, _tup(x), expectation, float(probs[optimal].sum()), held, time.perf_counter() - t0,
        compiled.circuit.num_qubits, len(feasible),
    )
