"""Predicted peak memory and run time of the simulators, before anything is built (the size guards' models).

Every figure is the peak resident memory of a whole ``qcpp`` process, as ``/usr/bin/time -v`` reports it, so a
guard can compare it with the memory the machine has available (:func:`qcpp.problem.limits.check_need`). The
models are linear in the sizes that dominate, with coefficients fitted to measured peaks
(``tests/cli/guard_peaks_test.py`` checks them, each within 1.5x):

* the feasible subspace holds ``A`` amplitudes, the product of the robots' path counts (a bound on the
  simulator's reachable basis: :func:`qcpp.simulate.validate.validate_size` counts them without enumerating);
* **simulate** (:class:`qcpp.simulate.subspace.SubspaceQAOA`): :data:`SUBSPACE_BYTES_PER_AMPLITUDE` per amplitude,
  :data:`PAIR_BYTES` per entry of the pairwise cost matrices between robots
  (:func:`qcpp.problem.cost.separable_cost`); :data:`SUBSPACE_SECONDS_PER_AMPLITUDE` per amplitude and layer plus
  once more for the basis and the cost diagonal;
* the gate-level methods (``statevector``, ``tensor``) also list every feasible assignment with its bits
  (:data:`ASSIGNMENT_LIST_BYTES` per assignment plus 8 bytes per decision variable);
* **validate**: :data:`VALIDATE_BYTES_PER_ASSIGNMENT` and :data:`VALIDATE_SECONDS_PER_ASSIGNMENT`;
* **training** (``qcpp solve --method qaoa``): :data:`TRAINING_BYTES_PER_AMPLITUDE` per amplitude and
  :data:`TRAINING_PAIR_BYTES` per pairwise cost entry.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> need = simulate_need(default_scenario(4, 4, 2), 1)
    >>> need.what, round(need.bytes / 1e9, 2)
    ('simulating 184 x 184 paths = 33,856 feasible assignments', 0.21)
"""

from __future__ import annotations

import itertools

from qcpp.problem.limits import Need, available_memory
from qcpp.problem.scenario import Scenario
from qcpp.simulate.validate import ValidationSize, validate_size

__all__ = [
    "ASSIGNMENT_LIST_BYTES",
    "BASE_BYTES",
    "PAIR_BYTES",
    "SUBSPACE_BYTES_PER_AMPLITUDE",
    "SUBSPACE_SECONDS_PER_AMPLITUDE",
    "TRAINING_BYTES_PER_AMPLITUDE",
    "TRAINING_PAIR_BYTES",
    "VALIDATE_BYTES_PER_ASSIGNMENT",
    "VALIDATE_SECONDS_PER_ASSIGNMENT",
    "feasible_size",
    "simulate_need",
    "training_need",
    "validate_need",
]

BASE_BYTES = 205_000_000
"""Peak of a ``qcpp simulate`` / ``validate`` process on a tiny scenario: the interpreter, numpy, scipy, numba."""

SUBSPACE_BYTES_PER_AMPLITUDE = 27
"""State (16), cost level (1-2), probabilities and phase temporaries, per amplitude of the subspace simulator."""

PAIR_BYTES = 12
"""Per entry of the pairwise cost matrices between two robots (float64 plus its temporaries)."""

SUBSPACE_SECONDS_PER_AMPLITUDE = 3e-7
"""Seconds per amplitude and layer of the subspace simulator (and once more for the basis and costs)."""

ASSIGNMENT_LIST_BYTES = 200
"""Per feasible assignment listed by the gate-level methods: its tuple, bits and cost (plus 8 per variable)."""

VALIDATE_BYTES_PER_ASSIGNMENT = 1600
"""Per feasible assignment of a validation: the subspace state, the assignment tuples, their basis-state
indices (Python integers) and reference amplitudes, the sparse state of the circuit, the comparison."""

VALIDATE_SECONDS_PER_ASSIGNMENT = 1e-3
"""Per feasible assignment of a validation: the circuit simulation (sparse state) and the Python loops."""

TRAINING_BYTES_PER_AMPLITUDE = 34
"""Per amplitude of the subspace simulator while training (the state and the adjoint gradient's)."""

TRAINING_PAIR_BYTES = 96
"""Per entry of the pairwise cost matrices between two robots while training."""


def feasible_size(scenario: Scenario, max_assignments: int | None = None) -> ValidationSize:
    """The robots' path counts; counting stops once the assignments exceed ``max_assignments`` (default: more
    than :func:`qcpp.problem.limits.available_memory` holds at 16 bytes each, the least any model needs), and
    the counts are then lower bounds."""
    if max_assignments is None:
        memory = available_memory()
        max_assignments = (1 << 40) if memory is None else memory // 16
    return validate_size(scenario, max_assignments=max_assignments)


def _pairs(size: ValidationSize) -> int:
    return sum(a * b for a, b in itertools.combinations(size.paths_per_robot, 2))


def _what(verb: str, size: ValidationSize) -> str:
    paths = " x ".join(f"{n:,}" for n in size.paths_per_robot)
    if size.exact:
        return f"{verb} {paths} paths = {size.assignments:,} feasible assignments"
    return f"{verb} at least {size.assignments:,} feasible assignments (paths counted: {paths})"


def simulate_need(scenario: Scenario, p: int, method: str = "subspace", size: ValidationSize | None = None) -> Need:
    """Predicted peak memory and time of ``qcpp simulate`` (see the module docstring).

    Args:
        p: QAOA layers.
        method: ``subspace``, ``statevector`` or ``tensor`` (the last two also list every feasible assignment).
        size: The path counts, if already known (default :func:`feasible_size`).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> s = default_scenario(4, 4, 2)
        >>> simulate_need(s, 4).seconds > simulate_need(s, 1).seconds
        True
    """
    size = feasible_size(scenario) if size is None else size
    a = size.assignments
    memory = BASE_BYTES + SUBSPACE_BYTES_PER_AMPLITUDE * a + PAIR_BYTES * _pairs(size)
    if method != "subspace":
        memory += a * (ASSIGNMENT_LIST_BYTES + 8 * scenario.num_variables)
    seconds = 1.0 + SUBSPACE_SECONDS_PER_AMPLITUDE * a * (p + 1)
    return Need(_what("simulating", size), memory, seconds, not size.exact)


def validate_need(scenario: Scenario, size: ValidationSize | None = None) -> Need:
    """Predicted peak memory and time of ``qcpp validate`` (the reference state, the comparison and the
    sparse state of the circuit; a fit to few measurements, see the module docstring).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> round(validate_need(default_scenario(4, 4, 2)).bytes / 1e9, 2)
        0.26
    """
    size = feasible_size(scenario) if size is None else size
    a = size.assignments
    memory = BASE_BYTES + VALIDATE_BYTES_PER_ASSIGNMENT * a + PAIR_BYTES * _pairs(size)
    return Need(_what("validating", size), memory, 1.0 + VALIDATE_SECONDS_PER_ASSIGNMENT * a, not size.exact)


def training_need(scenario: Scenario, p: int, size: ValidationSize | None = None) -> Need:
    """Predicted peak memory of training QAOA on the subspace simulator (``qcpp solve --method qaoa``); no time
    model (the optimiser decides how many evaluations it makes).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> need = training_need(default_scenario(3, 3, 1), 2)
        >>> need.bytes < 10**9, need.seconds is None
        (True, True)
    """
    size = feasible_size(scenario) if size is None else size
    a = size.assignments
    memory = BASE_BYTES + TRAINING_BYTES_PER_AMPLITUDE * a + TRAINING_PAIR_BYTES * _pairs(size)
    return Need(_what("training QAOA on", size), memory, None, not size.exact)
