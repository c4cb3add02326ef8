"""Size guard: predict what building a circuit takes, from the plan's cost, before building it.

``qcpp compile`` must materialise the circuit (to lower it and write OpenQASM), so it first asks the plan what
the lowered circuit costs (:func:`qcpp.estimators.estimate.layer_costs`: no gate is built) and refuses when the
prediction exceeds a limit. The memory model is measured, not guessed: an IR gate of a built circuit takes
about :data:`BYTES_PER_GATE` bytes at the peak of building and lowering (Python tuples; ``tracemalloc`` on
6x6/3 and 8x8/4 lowered circuits: 221-238 bytes, rounded up for the allocator's overhead). The high-level
circuit has fewer gates than the lowered one, so the lowered count bounds both.

:func:`compile_need` turns that into the peak memory of a ``qcpp compile`` process and its time, for
:func:`qcpp.problem.limits.check_need`: :data:`BASE_BYTES` plus :data:`BYTES_PER_GATE` per gate held at once --
every gate when the circuit is built whole, one layer's gates when it is streamed section by section (the peak
does not grow with ``p``) -- and :data:`GATES_PER_SECOND`; ``benchmarks/streamed_compile.py`` prints the
prediction beside the measured peak and time. ``--max-gates N`` sets a fixed
gate limit instead (:data:`DEFAULT_MAX_GATES` for callers that want one).

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
from qcpp.problem.limits import Need, SizeError, check_need
from qcpp.problem.scenario import Scenario

__all__ = [
    "BASE_BYTES",
    "BYTES_PER_GATE",
    "DEFAULT_MAX_GATES",
    "GATES_PER_SECOND",
    "SizePrediction",
    "check_size",
    "compile_need",
    "predict_size",
]

BYTES_PER_GATE = 300
"""Peak bytes per lowered gate while building, lowering and writing (measured: see the module docstring)."""

DEFAULT_MAX_GATES = 10_000_000
"""A gate limit of about 3 GB for a whole built circuit (for callers that want a fixed limit)."""

BASE_BYTES = 58_000_000
"""Peak resident memory of a ``qcpp compile`` process on a small scenario (interpreter and imports)."""

GATES_PER_SECOND = 50_000
"""Lowered gates built and written per second (streamed OpenQASM), for the predicted time: below the rate a
streamed compile keeps on a loaded 2-core machine once past start-up, so the predicted time of a long compile is an
over-estimate."""


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
        p: QAOA layers.
        options: circuit construction options.

    Returns:
        The :class:`SizePrediction`.
    """
    lc = layer_costs(scenario, options)
    gates = lc.cost(p).total
    qubits = sum(size for _, size in registers_for(scenario, p, options))
    return SizePrediction(gates, qubits, gates * BYTES_PER_GATE)


def compile_need(
    scenario: Scenario,
    p: int,
    options: PlanOptions = DEFAULT_PLAN,
    *,
    streamed: bool,
    size: SizePrediction | None = None,
) -> Need:
    """Predicted peak memory and time of ``qcpp compile`` (see the module docstring).

    Args:
        scenario: The scenario.
        p: QAOA layers.
        options: Circuit construction options.
        streamed: Whether the circuit is built and written section by section (else whole).
        size: :func:`predict_size` of the same arguments, if already known.

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> s = default_scenario(6, 6, 3)
        >>> whole, streamed = compile_need(s, 8, streamed=False), compile_need(s, 8, streamed=True)
        >>> whole.bytes > streamed.bytes, whole.seconds == streamed.seconds
        (True, True)
    """
    size = predict_size(scenario, p, options) if size is None else size
    # streamed: the state preparation and one whole layer (a later one, with its phase separator, also without the
    # first phase separator)
    one_layer = sum(c.total for c in layer_costs(scenario, options).cost_by_part().values())
    held = min(one_layer, size.gates) if streamed and p > 1 else size.gates
    what = f"compiling {size.gates:,} gates on {size.qubits:,} qubits"
    return Need(what, BASE_BYTES + BYTES_PER_GATE * held, size.gates / GATES_PER_SECOND)


def check_size(
    scenario: Scenario,
    p: int,
    options: PlanOptions,
    max_gates: int | None,
    override: str,
    force: bool = False,
    *,
    streamed: bool = False,
    allow_large_hint: str = "",
) -> SizePrediction:
    """The predicted size; unless ``force``, refuse what would not fit or would run for hours (the guard of
    ``qcpp compile`` and ``qcpp.compile``).

    With ``max_gates`` the limit is that many lowered gates; without it, :func:`compile_need`'s memory and time,
    against the available memory and :data:`qcpp.problem.limits.MAX_SECONDS` (:func:`qcpp.problem.limits.check_need`,
    lifted by :func:`qcpp.problem.limits.allow_large`).

    Args:
        scenario: The circuit's scenario.
        p: QAOA layers.
        options: Circuit construction options.
        max_gates: A fixed limit of lowered gates, or ``None`` for the memory and time prediction.
        override: How the caller lifts a ``max_gates`` limit, for the message (``raise it with --max-gates N, or
            pass --force``).
        force: Do not refuse.
        streamed: Whether the circuit is built and written section by section (:func:`compile_need`).
        allow_large_hint: How the caller lifts the memory and time guard, for the message (default: the CLI's
            ``pass --allow-large``).

    Returns:
        The prediction.

    Raises:
        qcpp.problem.limits.SizeError: one line naming the prediction, the limit and how to lift it.

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> check_size(default_scenario(3, 3, 1), 1, DEFAULT_PLAN, None, "").gates
        296
    """
    size = predict_size(scenario, p, options)
    if force:
        return size
    if max_gates is not None:
        if not size.fits(max_gates):
            limit = f"over the limit of {max_gates:,} gates ({override})"
            raise SizeError("", f"refusing to build {size.describe()}: {limit}")
        return size
    check_need(compile_need(scenario, p, options, streamed=streamed, size=size), override=allow_large_hint)
    return size
