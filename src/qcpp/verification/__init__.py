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
    one local configuration of edges; where a failing local input is on no feasible path it can find, and it
    cannot show that none has it, the verdict is ``not_certified`` (neither a proof nor a counterexample).
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

from qcpp.errors import check_choice, check_count
from qcpp.plan.options import PlanOptions
from qcpp.problem.limits import API_OVERRIDE, check_layers
from qcpp.problem.paths import count_paths
from qcpp.problem.sbf import RULES, Rule
from qcpp.problem.scenario import Scenario
from qcpp.verification.common import ProgressFn
from qcpp.verification.gadgets import verify_gadgets
from qcpp.verification.report import METHODS, OUTCOMES, Check, Counterexample, Method, Outcome, VerifyReport
from qcpp.verification.state import DEFAULT_SAMPLES, state_fits, verify_state

__all__ = [
    "DEFAULT_SAMPLES",
    "METHODS",
    "OUTCOMES",
    "Check",
    "Counterexample",
    "Method",
    "Outcome",
    "VerifyReport",
    "choose_method",
    "resolve_method",
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


def resolve_method(
    scenario: Scenario, p: int, rule: Rule, method: Method, samples: int, options: PlanOptions | None = None
) -> Method:
    """The method :func:`verify` runs (``auto`` resolved by :func:`choose_method`), after checking the arguments
    as :func:`verify` does (so a caller can name what progress counts before the work starts).

    Raises:
        qcpp.errors.OptionError: an unknown rule or method, or ``p`` or ``samples`` not an integer of at least 1.
        qcpp.problem.limits.SizeError: ``p`` over :data:`qcpp.problem.limits.MAX_LAYERS` outside
            :func:`qcpp.problem.limits.allow_large`.
    """
    check_choice(rule, RULES, "rule")
    check_choice(method, METHODS, "method")
    check_layers(check_count(p, "p"), "p", API_OVERRIDE)
    check_count(samples, "samples")
    if method == "auto":
        return choose_method(scenario, p, PlanOptions(rule=rule) if options is None else options, samples)
    return method


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
        progress: Called as ``progress(done, total)`` while checking: checks done (``gadgets``) or inputs run
            (``state``); their costs differ too much for the share done to predict the time left.
        options: How the circuit is built (:class:`~qcpp.plan.options.PlanOptions`: target, fusion, initial state,
            phase separator, ...); its rule replaces ``rule``. Default: ``PlanOptions(rule=rule)``.

    Returns:
        The :class:`~qcpp.verification.report.VerifyReport`; ``holds`` is false with a ``counterexample`` when the
        circuit does not preserve feasibility.

    Raises:
        qcpp.errors.OptionError: an unknown rule or method, or ``p`` or ``samples`` not an integer of at least 1
            (the messages of the other public functions: ``p: must be at least 1, got 0``).
        qcpp.problem.limits.SizeError: ``p`` over :data:`qcpp.problem.limits.MAX_LAYERS` outside
            :func:`qcpp.problem.limits.allow_large`.
        ValueError: ``state`` on a circuit wider than 62 qubits.
    """
    options = PlanOptions(rule=rule) if options is None else options
    method = resolve_method(scenario, p, rule, method, samples, options)
    if method == "state":
        return verify_state(scenario, p, samples=samples, seed=seed, progress=progress, options=options)
    return verify_gadgets(scenario, p, seed=seed, progress=progress, options=options)


