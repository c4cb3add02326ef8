"""Does the compiled circuit keep every feasible path feasible? ``qcpp verify`` and :func:`verify` answer it.

A constrained-mixer QAOA circuit is only correct if it never puts amplitude on an infeasible edge set and returns
every ancilla to ``|0>``: on every feasible assignment (one feasible path per robot, ancillas clean) it must give a
superposition of feasible assignments with clean ancillas. Two methods check that:

``state`` (:mod:`qcpp.verification.state`)
    Runs the compiled, lowered circuit (random nonzero angles) on every feasible assignment, or a seeded sample,
    part by part (state preparation, each layer's phase separator and mixer, the whole circuit), and looks at
    every output amplitude. A counterexample is a real input of the real circuit. Up to 62 qubits.
``gadgets`` (:mod:`qcpp.verification.gadgets`)
    Checks every gadget kind of the plan's call graph on all its local inputs (and the SBF rule on every local
    picture of the scenario); the circuit is its call graph expanded, so this certifies the whole circuit at any
    size (a 30x30 field with 8 robots takes seconds). A counterexample is local: one gadget kind, one plaquette,
    one local configuration of edges.
``auto``
    ``state`` when every feasible input can be checked (at most ``samples`` of them, at most 62 qubits), else
    ``gadgets``.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 2], "goal": [1, 1]}]})
    >>> verify(s, p=1).holds
    True
    >>> report = verify(s, p=1, rule="paper")     # the paper's rule lets a path leave the feasible set
    >>> report.holds, report.method, report.counterexample.plaquette
    (False, 'state', ((0, 1), (0, 2), (1, 2), (1, 1)))
"""

from __future__ import annotations

from qcpp.plan.options import PlanOptions
from qcpp.problem.paths import count_paths
from qcpp.problem.sbf import RULES, Rule
from qcpp.problem.scenario import Scenario
from qcpp.verification.common import ProgressFn
from qcpp.verification.gadgets import verify_gadgets
from qcpp.verification.report import METHODS, Check, Counterexample, Method, VerifyReport
from qcpp.verification.state import DEFAULT_SAMPLES, state_fits, verify_state

__all__ = [
    "DEFAULT_SAMPLES",
    "METHODS",
    "Check",
    "Counterexample",
    "Method",
    "VerifyReport",
    "choose_method",
    "verify",
    "verify_gadgets",
    "verify_state",
]


def choose_method(
    scenario: Scenario, p: int, options: PlanOptions | None = None, samples: int = DEFAULT_SAMPLES
) -> Method:
    """What ``auto`` runs: ``state`` when the circuit fits a 64-bit basis key and there are at most ``samples``
    feasible assignments (so every one is checked), else ``gadgets``.

    >>> from qcpp.problem.presets import default_scenario
    >>> choose_method(default_scenario(3, 3, 2), 1), choose_method(default_scenario(8, 8, 3), 1)
    ('state', 'gadgets')
    """
    total = 1
    for r in range(scenario.num_robots):
        total *= count_paths(scenario, r, cap=samples + 1)
        if total > samples:
            return "gadgets"
    return "state" if state_fits(scenario, p, options) else "gadgets"


def verify(
    scenario: Scenario,
    p: int = 1,
    rule: Rule = "exact",
    method: Method = "auto",
    samples: int = DEFAULT_SAMPLES,
    seed: int = 0,
    progress: ProgressFn | None = None,
    options: PlanOptions | None = None,
) -> VerifyReport:
    """Check that the compiled QAOA circuit of ``scenario`` preserves feasibility (see the module docstring).

    Args:
        p: QAOA layers (>= 1).
        rule: The SBF rule the mixer is compiled with (``exact`` or ``paper``).
        method: ``state``, ``gadgets`` or ``auto``.
        samples: ``state``: most feasible inputs per part (a seeded sample when there are more).
        seed: Seed of the angles and of any sample.
        progress: Called as ``progress(done, total)`` while checking.
        options: How the circuit is built (:class:`~qcpp.plan.options.PlanOptions`: target, fusion, initial state,
            phase separator, ...); its rule replaces ``rule``. Default: ``PlanOptions(rule=rule)``.

    Returns:
        The :class:`~qcpp.verification.report.VerifyReport`; ``holds`` is false with a ``counterexample`` when the
        circuit does not preserve feasibility.

    Raises:
        ValueError: an unknown rule or method, ``p < 1``, ``samples < 1``, or ``state`` on a circuit wider than 62
            qubits.
    """
    if rule not in RULES:
        raise ValueError(f"unknown rule {rule!r} (expected one of {', '.join(RULES)})")
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r} (expected one of {', '.join(METHODS)})")
    if not isinstance(p, int) or isinstance(p, bool) or p < 1:
        raise ValueError(f"p must be an integer of at least 1, got {p!r}")
    if samples < 1:
        raise ValueError(f"samples must be at least 1, got {samples}")
    options = PlanOptions(rule=rule) if options is None else options
    if method == "auto":
        method = choose_method(scenario, p, options, samples)
    if method == "state":
        return verify_state(scenario, p, samples=samples, seed=seed, progress=progress, options=options)
    return verify_gadgets(scenario, p, seed=seed, progress=progress, options=options)


