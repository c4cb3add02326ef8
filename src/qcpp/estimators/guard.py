"""Size guard: predict what building a circuit takes, from the plan's cost, before building it.

``qcpp compile`` must materialise the circuit (to lower it and write OpenQASM), so it first asks the plan what the
lowered circuit costs (:func:`qcpp.estimators.estimate.layer_costs`: no gate is built) and refuses when the
prediction exceeds a limit. An IR gate takes about :data:`BYTES_PER_GATE` bytes at the peak of building and
lowering; the high-level circuit has fewer gates than the lowered one, so the lowered count bounds both.
:data:`DEFAULT_MAX_GATES` keeps a whole built circuit at a few GB and a compile within minutes.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> size = predict_size(default_scenario(3, 3, 1), 1)
    >>> size.qubits, size.fits(DEFAULT_MAX_GATES), size.fits(100)
    (15, True, False)
    >>> predict_size(default_scenario(3, 3, 1), 4).gates > 3 * size.gates
    True
"""

from __future__ import annotations

from dataclasses import dataclass

from qcpp.estimators.estimate import layer_costs, registers_for
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.problem.limits import SizeError
from qcpp.problem.scenario import Scenario

__all__ = ["BYTES_PER_GATE", "DEFAULT_MAX_GATES", "SizePrediction", "check_size", "predict_size"]

BYTES_PER_GATE = 300
"""Peak bytes per lowered gate while building, lowering and writing (Python tuples, with the allocator's overhead)."""

DEFAULT_MAX_GATES = 10_000_000
"""Largest circuit ``qcpp compile`` builds without ``--force`` or a higher ``--max-gates``: about 3 GB predicted."""


@dataclass(frozen=True)
class SizePrediction:
    """What building a circuit would take.

    Attributes:
        gates: gates of the lowered circuit (exact, from the gadgets' costs).
        qubits: qubits.
        bytes: predicted peak memory of building it.
    """

    gates: int
    qubits: int
    bytes: int

    def fits(self, max_gates: int) -> bool:
        """Whether the circuit is within ``max_gates``."""
        return self.gates <= max_gates

    def describe(self) -> str:
        """``"1,630 gates on 18 qubits (about 0.0 GB of memory)"``."""
        return f"{self.gates:,} gates on {self.qubits:,} qubits (about {self.bytes / 1e9:.1f} GB of memory)"


def predict_size(scenario: Scenario, p: int, options: PlanOptions = DEFAULT_PLAN) -> SizePrediction:
    """Predict the lowered circuit's size from the plan's cost (builds nothing).

    Args:
        scenario: the scenario.
        options: circuit construction options.
    """
    lc = layer_costs(scenario, options)
    gates = lc.cost(p).total
    qubits = sum(size for _, size in registers_for(scenario, p, options))
    return SizePrediction(gates, qubits, gates * BYTES_PER_GATE)


def check_size(
    scenario: Scenario, p: int, options: PlanOptions, max_gates: int, override: str, force: bool = False
) -> SizePrediction:
    """The predicted size; unless ``force``, refuse a circuit predicted to exceed ``max_gates`` lowered gates (the
    guard of ``qcpp compile`` and ``qcpp.compile``).

    Args:
        scenario: The scenario.
        p: QAOA layers.
        options: How the circuit is built.
        max_gates: The limit.
        override: How the caller lifts the limit, for the message (``raise it with --max-gates N, or pass
            --force``).
        force: Do not refuse.

    Returns:
        The prediction.

    Raises:
        qcpp.problem.limits.SizeError: one line naming the predicted size, the limit and ``override``.
    """
    size = predict_size(scenario, p, options)
    if not force and not size.fits(max_gates):
        raise SizeError("", f"refusing to build {size.describe()}: over the limit of {max_gates:,} gates ({override})")
    return size
