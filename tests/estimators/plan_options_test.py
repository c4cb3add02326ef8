"""Estimate == compiled circuit for every plan option a user can pass, on obstacles and interior endpoints.

The estimate (:func:`qcpp.estimators.estimate.estimate_point`) and the compiled circuit take the same
:class:`~qcpp.plan.options.PlanOptions`; :func:`qcpp.estimators.crosscheck.crosscheck` compares qubits, registers,
gate counts (whole circuit, per part, logical) and exact depths.
"""

from __future__ import annotations

import dataclasses

import pytest

from qcpp.errors import OptionError
from qcpp.estimators.counts import count
from qcpp.estimators.crosscheck import Case, crosscheck, every_plan_option, interior_endpoints, with_obstacles
from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.lowering.passes import lower
from qcpp.plan.options import DEFAULT_PLAN, INITIAL_STATES, PlanOptions
from qcpp.plan.qaoa import qaoa_circuit, qaoa_plan
from qcpp.problem.presets import default_scenario

ALL = list(every_plan_option())


def test_every_plan_option_lists_each_combination_once() -> None:
    assert len(ALL) == len(set(ALL)) == 2 * len(INITIAL_STATES) * 2 * 2 * 2 * 3


@pytest.mark.parametrize("part", range(4))
@pytest.mark.parametrize("shape", [(4, 3), pytest.param((4, 4), marks=pytest.mark.heavy)], ids=["4x3", "4x4"])
def test_estimate_equals_compiled_for_every_combination_on_hard_obstacles_and_interior_endpoints(
    shape: tuple[int, int], part: int
) -> None:
    rows, cols = shape
    s = interior_endpoints(rows, cols, "hard")
    assert s.obstacles and any(0 < rb.start[0] < rows - 1 and 0 < rb.start[1] < cols - 1 for rb in s.robots)
    assert [m for o in ALL[part::4] for m in crosscheck(Case(s, 1, o))] == []


ONE_AT_A_TIME = [
    DEFAULT_PLAN,
    PlanOptions(rule="paper"),
    PlanOptions(initial="representatives"),
    PlanOptions(initial="local_search"),
    PlanOptions(initial="local_search_mix"),
    PlanOptions(target="ft"),
    PlanOptions(phase="whole-space"),
    PlanOptions(optimize="depth"),
    PlanOptions(ancilla_budget=0),
    PlanOptions(ancilla_budget=5),
    PlanOptions(angles="multi"),
    PlanOptions(phase="whole-space", target="ft", optimize="depth", ancilla_budget=0),
    PlanOptions(first_phase=False),
    PlanOptions(initial="local_search", first_phase=False),
    PlanOptions(phase="whole-space", target="ft", phase_layout="spatial", first_phase=False),
]


@pytest.mark.parametrize("options", ONE_AT_A_TIME, ids=lambda o: "/".join(map(str, dataclasses.astuple(o))))
@pytest.mark.parametrize("which", ["open 3x3/2", "soft 4x4 interior", "open 3x4 interior"])
def test_estimate_equals_compiled_per_option_over_two_layers(which: str, options: PlanOptions) -> None:
    s = {
        "open 3x3/2": lambda: default_scenario(3, 3, 2),
        "soft 4x4 interior": lambda: interior_endpoints(4, 4, "soft"),
        "open 3x4 interior": lambda: interior_endpoints(3, 4),
    }[which]()
    assert crosscheck(Case(s, 2, options)) == []


def test_crosscheck_compares_the_whole_space_circuit_with_the_whole_space_estimate() -> None:
    # the drift this fixes: crosscheck built the circuit from rule/initial/target only, so with
    # phase="whole-space" it compared the Ising estimate with the feasible-phase circuit (cx 676 vs 368)
    s = default_scenario(3, 3, 2)
    whole = PlanOptions(phase="whole-space")
    assert crosscheck(Case(s, 1, whole)) == []
    est = estimate_point(Point.from_scenario(s, 1), EstimateOptions(plan=whole, depth="none"))
    assert est.cost.cx == count(lower(qaoa_circuit(s, 1, whole))).cx != count(lower(qaoa_circuit(s, 1))).cx


@pytest.mark.parametrize("initial", INITIAL_STATES)
def test_without_the_first_phase_separator_the_estimate_equals_compiled_or_the_start_is_refused(initial: str) -> None:
    """On hard obstacles a robot's paths split into components and its descent path leaves its initial one, so
    ``representatives`` and ``local_search_mix`` start from a superposition here: refused, naming the option."""
    s = interior_endpoints(4, 3, "hard")
    options = PlanOptions(initial=initial, first_phase=False)  # type: ignore[arg-type]
    if initial in ("representatives", "local_search_mix"):
        with pytest.raises(OptionError, match=f"^first_phase: .*initial state {initial} prepares a superposition"):
            crosscheck(Case(s, 2, options))
    else:
        assert crosscheck(Case(s, 2, options)) == []


def test_a_mixed_start_whose_paths_agree_is_a_basis_state_and_may_omit_the_first_phase_separator() -> None:
    s = with_obstacles(default_scenario(3, 4, 2), "hard")
    assert s is not None
    options = PlanOptions(initial="local_search_mix", first_phase=False)
    assert qaoa_plan(s, 1, options).basis_start  # each robot's descent stays on its initial path: X gates only
    assert crosscheck(Case(s, 2, options)) == []
