"""Counts summed from the gadgets equal the counts of the compiled circuit; depth is exact or a true bound."""

from __future__ import annotations

import pytest

from qcpp.estimators.counts import count
from qcpp.estimators.crosscheck import Case, crosscheck, crosscheck_cases, with_obstacles
from qcpp.estimators.depth import Depth, depths
from qcpp.estimators.estimate import (
    EstimateOptions,
    Point,
    depth_bound,
    estimate_point,
    exact_depth,
    layer_costs,
    registers_for,
)
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.errors import ScenarioError
from qcpp.problem.presets import default_scenario, max_default_robots


@pytest.mark.parametrize("case", list(crosscheck_cases()), ids=lambda c: c.label)
def test_gadget_counts_equal_compiled_counts_sample(case: Case) -> None:
    assert crosscheck(case) == []


def _checked(case: Case) -> bool:
    """Whether the heavy test checks ``case``: all but the default scenarios with 4 or 5 robots on grids of more
    than 16 nodes where more robots fit (there 1-3 robots and the most, up to 6, are checked). A robot beyond the
    third adds more pairs of the kinds three robots already have, and these 60 cases were a fifth of the time."""
    s = case.scenario
    most = min(6, max_default_robots(s.grid.rows, s.grid.cols))
    default = case.plan == PlanOptions() and s == default_scenario(s.grid.rows, s.grid.cols, s.num_robots)
    return not (default and s.grid.rows * s.grid.cols > 16 and 3 < s.num_robots < most)


FULL = list(crosscheck_cases(full=True))
CHECKED = [c for c in FULL if _checked(c)]


@pytest.mark.heavy
@pytest.mark.parametrize("part", range(8))
def test_gadget_counts_equal_compiled_counts_everywhere(part: int) -> None:
    """The cases of :data:`CHECKED`, an eighth per part: every case of ``crosscheck_cases(full=True)`` but those
    :func:`_checked` leaves out."""
    assert len(FULL) > 500 and len(CHECKED) > 400
    mismatches = [m for c in CHECKED[part::8] for m in crosscheck(c)]
    assert mismatches == []


def test_p_layers_cost_state_preparation_plus_p_times_a_layer() -> None:
    s = default_scenario(3, 4, 2)
    lc = layer_costs(s, PlanOptions())
    for p in (0, 1, 3):
        circ = qaoa_circuit(s, p)
        assert lc.cost(p) == Cost.count(lower(circ).gates)
        assert lc.cost(p, logical=True) == Cost.count(lower(circ, LOGICAL_BASIS).gates)
        assert dict(registers_for(s, p)) == {r.name: r.size for r in lower(circ).registers}


def test_depth_modes() -> None:
    s = default_scenario(3, 3, 2)
    rc = count(lower(qaoa_circuit(s, 2)))
    exact = estimate_point(Point(3, 3, 2, 2), EstimateOptions(depth="exact")).depth
    assert exact == Depth(rc.depth, rc.two_qubit_depth, exact.rotation_depth, "exact")
    auto_small = estimate_point(Point(3, 3, 2, 2)).depth
    assert auto_small == exact
    auto_big = estimate_point(Point(3, 3, 2, 2), EstimateOptions(depth_budget=10)).depth
    bound = estimate_point(Point(3, 3, 2, 2), EstimateOptions(depth="bound")).depth
    assert auto_big == bound and bound.kind == "bound"
    assert bound.depth >= exact.depth and bound.two_qubit_depth >= exact.two_qubit_depth
    assert bound.rotation_depth >= exact.rotation_depth
    assert estimate_point(Point(3, 3, 2, 2), EstimateOptions(depth="none")).depth is None


@pytest.mark.parametrize("rows, cols, robots, p", [(2, 2, 1, 1), (3, 3, 1, 3), (3, 4, 3, 2), (4, 4, 2, 1)])
def test_depth_bound_is_an_upper_bound(rows: int, cols: int, robots: int, p: int) -> None:
    s = default_scenario(rows, cols, robots)
    b, e = depth_bound(s, p), exact_depth(s, p)
    assert (b.depth, b.two_qubit_depth, b.rotation_depth) >= (0, 0, 0)
    assert b.depth >= e.depth and b.two_qubit_depth >= e.two_qubit_depth and b.rotation_depth >= e.rotation_depth


def test_obstacle_scenario_and_rotation_depth_against_a_direct_count() -> None:
    s = with_obstacles(default_scenario(4, 4, 2), "hard")
    assert s is not None and s.obstacles
    est = estimate_point(Point.from_scenario(s, 1))
    low = lower(qaoa_circuit(s, 1))
    assert est.depth == depths(low.gates, low.num_qubits)
    rz_only = [g for g in low.gates if g[0] == "rz"]
    assert 0 < est.depth.rotation_depth <= len(rz_only)


def test_too_many_robots_for_the_grid() -> None:
    with pytest.raises(ScenarioError):
        estimate_point(Point(2, 2, 5, 1))


@pytest.mark.parametrize(("rows", "cols", "robots"), [(3, 4, 1), (4, 4, 2), (5, 5, 2), (4, 6, 3)])
def test_soft_obstacles_leave_qubits_cx_t_and_depth_as_without_obstacles(rows: int, cols: int, robots: int) -> None:
    """Soft obstacles change the cost's weights only (the estimate guide says so): any number of them, on the border
    or inside, keeps the qubits, CNOTs, T gates and depth of the field without obstacles; hard ones shrink them."""
    import random

    import qcpp

    free = qcpp.grid_scenario(rows, cols, robots=robots)
    ends = {n for r in free.robots for n in (r.start, r.goal)}
    cells = [(r, c) for r in range(rows) for c in range(cols) if (r, c) not in ends]
    rng = random.Random(rows * 100 + cols * 10 + robots)
    fields = [list(rng.sample(cells, k)) for k in (1, 2, len(cells) // 3)]
    fields = [obs for obs in fields if obs]
    for p in (1, 2):
        want = qcpp.estimate(free, p=p, depth="exact")
        for obs in fields:
            soft = qcpp.estimate(qcpp.grid_scenario(rows, cols, robots=robots, obstacles=obs), p=p, depth="exact")
            assert (soft.qubits, soft.cx, soft.t, soft.depth) == (want.qubits, want.cx, want.t, want.depth), obs
        hard = qcpp.grid_scenario(rows, cols, robots=[(r.start, r.goal) for r in free.robots], obstacles=fields[0][:1],
                                  hard_obstacles=True)  # fmt: skip
        assert qcpp.estimate(hard, p=p).cx < want.cx
