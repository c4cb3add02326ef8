"""Estimate == compiled circuit for every plan option a user can pass, on obstacles and interior endpoints.

The estimate (:func:`qcpp.estimators.estimate.estimate_point`) and the compiled circuit take the same
:class:`~qcpp.plan.options.PlanOptions`; :func:`qcpp.estimators.crosscheck.crosscheck` compares qubits, registers,
gate counts (whole circuit, per part, logical) and exact depths. The default run checks every value of every field
one at a time (:func:`~qcpp.estimators.crosscheck.one_plan_option_at_a_time`) on hard obstacles and interior
endpoints, and over two layers on three scenarios; the heavy step checks the combinations of every field
(:func:`~qcpp.estimators.crosscheck.every_plan_option`) on 4x3, all but ``angles="multi"`` with a layout other than
``auto`` (:data:`CHECKED`), and every combination of the fields that choose gadgets (:data:`GADGET_FIELDS`) on 4x4.
"""

from __future__ import annotations

import dataclasses
import math

import pytest

from qcpp.errors import OptionError
from qcpp.estimators.counts import count
from qcpp.estimators.crosscheck import (
    Case,
    crosscheck,
    every_plan_option,
    interior_endpoints,
    one_plan_option_at_a_time,
    plan_option_values,
    with_obstacles,
)
from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.ir.cost import TARGETS
from qcpp.lowering.passes import lower
from qcpp.plan.options import ANGLES, DEFAULT_PLAN, INITIAL_STATES, OPTIMIZE, PHASE_LAYOUTS, PHASES, PlanOptions
from qcpp.plan.qaoa import qaoa_circuit, qaoa_plan
from qcpp.problem.presets import default_scenario
from qcpp.problem.sbf import RULES

ALL = list(every_plan_option())
GADGET_FIELDS = ("rule", "initial", "target", "phase", "optimize", "ancilla_budget")
"""The fields that choose which gadgets are built; ``fuse``, ``phase_layout``, ``angles`` and ``first_phase``
shape, place, name or drop the same gadgets."""
GADGETS = list(every_plan_option(fields=GADGET_FIELDS))
CHECKED = [o for o in ALL if o.angles == "layer" or o.phase_layout == "auto"]
"""The combinations the heavy 4x3 test checks: all of them with ``angles="layer"``, and with ``angles="multi"``
those with ``phase_layout="auto"`` (3840 of 6144). ``angles`` only names the mixer's symbols (same gates, counts
and depths) and ``phase_layout`` only places the phase gadgets, so ``multi`` still meets every value of every other
field together, and each layout still meets every other combination."""


def test_the_values_are_every_field_s_checked_values() -> None:
    """The values come from the fields' types; here they equal the tuples ``PlanOptions`` checks against, so a
    value added to one and not the other fails, and a new field without values fails too."""
    values = plan_option_values()
    assert list(values) == [f.name for f in dataclasses.fields(PlanOptions)]
    assert (values["rule"], values["initial"], values["target"], values["phase"], values["optimize"]) == (
        RULES, INITIAL_STATES, TARGETS, PHASES, OPTIMIZE
    )
    assert (values["phase_layout"], values["angles"]) == (PHASE_LAYOUTS, ANGLES)
    assert values["fuse"] == values["first_phase"] == (True, False) and values["ancilla_budget"] == (None, 0, 3)
    assert all(v[0] == getattr(DEFAULT_PLAN, name) for name, v in values.items())


def test_every_plan_option_lists_each_combination_of_every_field_once() -> None:
    values = plan_option_values()
    assert len(ALL) == len(set(ALL)) == math.prod(len(v) for v in values.values())
    for name, vs in values.items():
        assert {getattr(o, name) for o in ALL} == set(vs), name
    assert len(GADGETS) == len(set(GADGETS)) == math.prod(len(values[n]) for n in GADGET_FIELDS)
    one = list(one_plan_option_at_a_time())
    assert len(one) == len(set(one)) == 1 + sum(len(v) - 1 for v in values.values())
    assert all(sum(getattr(o, n) != getattr(DEFAULT_PLAN, n) for n in values) == 1 for o in one[1:])


def _crosscheck_or_refused(s: object, options: PlanOptions) -> list[str]:
    """:func:`crosscheck`, or ``[]`` where the scenario's start is a superposition and ``first_phase=False``
    is refused as documented."""
    try:
        return crosscheck(Case(s, 1, options))  # type: ignore[arg-type]
    except OptionError as exc:
        assert not options.first_phase and "prepares a superposition" in str(exc), (options, exc)
        return []


def test_estimate_equals_compiled_for_every_option_one_at_a_time_on_hard_obstacles_and_interior_endpoints() -> None:
    s = interior_endpoints(4, 3, "hard")
    assert s.obstacles and any(0 < rb.start[0] < 3 and 0 < rb.start[1] < 2 for rb in s.robots)
    assert [m for o in one_plan_option_at_a_time() for m in _crosscheck_or_refused(s, o)] == []


@pytest.mark.heavy
@pytest.mark.parametrize("part", range(8))
def test_estimate_equals_compiled_for_every_combination_of_every_field_on_4x3(part: int) -> None:
    """The combinations of :data:`CHECKED`, an eighth per part."""
    s = interior_endpoints(4, 3, "hard")
    assert [m for o in CHECKED[part::8] for m in _crosscheck_or_refused(s, o)] == []


@pytest.mark.heavy
@pytest.mark.parametrize("part", range(4))
def test_estimate_equals_compiled_for_every_gadget_combination_on_4x4(part: int) -> None:
    s = interior_endpoints(4, 4, "hard")
    assert [m for o in GADGETS[part::4] for m in _crosscheck_or_refused(s, o)] == []


ONE_AT_A_TIME = [
    *one_plan_option_at_a_time(budgets=(None, 0, 5)),
    PlanOptions(phase="whole-space", target="ft", optimize="depth", ancilla_budget=0),
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


def test_plan_options_take_keywords_only_so_a_new_field_cannot_shift_the_others() -> None:
    with pytest.raises(TypeError):
        PlanOptions("paper")  # type: ignore[misc]
    assert PlanOptions(rule="paper").rule == "paper"
