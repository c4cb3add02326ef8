"""The size prediction the simulators' guards refuse by (:func:`qcpp.simulate.validate.validate_size`)."""

from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st

import qcpp
from qcpp.problem.paths import count_paths
from qcpp.simulate.validate import COUNT_CAP_GROWTH, FIRST_COUNT_CAP, validate_size


def test_robots_with_many_paths_each_are_known_too_large_after_few_paths_per_robot() -> None:
    """Three robots with millions of paths each on a 7x6 field: the guard's question (more than 10^7 assignments?)
    is answered with at most :data:`FIRST_COUNT_CAP` x :data:`COUNT_CAP_GROWTH` paths counted per robot, not by
    counting the first robot's paths up to 10^7 (minutes; a guard's limit is 10^9 and more: hours)."""
    field = qcpp.grid_scenario(7, 6, robots=[((0, 0), (6, 5)), ((0, 5), (6, 0)), ((3, 0), (3, 5))],
                               obstacles=[(2, 2), (2, 3), (4, 1), (5, 4)])  # fmt: skip
    size = validate_size(field, max_assignments=10**7)
    assert not size.exact and size.assignments > 10**7
    assert all(n <= FIRST_COUNT_CAP * COUNT_CAP_GROWTH for n in size.paths_per_robot), size.paths_per_robot


@settings(max_examples=25, deadline=None)
@given(rows=st.integers(2, 4), cols=st.integers(2, 4), robots=st.integers(1, 3),
       limit=st.integers(1, 10**6))  # fmt: skip
def test_the_prediction_is_exact_within_the_limit_and_a_lower_bound_over_it(
    rows: int, cols: int, robots: int, limit: int
) -> None:
    """Exact counts whenever counting finished; otherwise lower bounds whose product is over the limit."""
    s = qcpp.grid_scenario(rows, cols, robots=robots)
    full = [count_paths(s, r) for r in range(s.num_robots)]
    size = validate_size(s, max_assignments=limit)
    if size.exact:
        assert list(size.paths_per_robot) == full
    else:
        assert size.assignments > limit
        assert all(0 < n <= f for n, f in zip(size.paths_per_robot, full, strict=True))
    assert size.exact or math.prod(full) > limit
    assert validate_size(s).paths_per_robot == tuple(full) and validate_size(s).exact
