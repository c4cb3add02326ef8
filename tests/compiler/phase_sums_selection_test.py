"""The near-linear place-aware layouts pick exactly the old ones' adders and ancillas.

:func:`qcpp.gadgets.phase_sums.spatial_popcount_layout` keeps, for the local-first choice (with a sink), a
bucket index of every column, the bits whose triple holds each bit, an index by second-nearest distance and one
heap per column, where the code it replaced rescanned whole columns (``layout_reference.py``, that code
verbatim). Both must emit the same gates in the same order, the same register and the same ancilla sites:

* hypothesis: random forms (weights of either sign up to 7, so copies and complemented bits), random sites on a
  lattice from 1x1 (every bit on one site: ties everywhere) to 40x40 (sparse), with and without a sink;
* the balance forms of the medial layout (every robot's edges, dense) with their sinks, and the edges or the
  points of a 14x14 square thinned at random, so the columns are large enough for the buckets to matter;
* the visit gadgets' ancillas (:func:`qcpp.plan.phase_layout.spatial_phase`): random scenarios (hypothesis)
  with and without sinks, and 9x9/3's pool of hundreds.
"""

from __future__ import annotations

import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.gadgets.phase_sums import SumsPhase, spatial_popcount_layout
from qcpp.gadgets.phase_visits import VisitPhase
from qcpp.plan.options import PlanOptions
from qcpp.plan.phase import phase_plan
from qcpp.plan.phase_layout import spatial_phase, variable_sites
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.grid import Grid
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario

from .conftest import scenarios
from .layout_reference import reference_popcount_layout, reference_spatial_phase


def _both(form: tuple[tuple[int, int], ...], sites: dict, sink: tuple[float, float] | None) -> tuple:
    first = max(q for q, _ in form) + 1
    new = spatial_popcount_layout(form, iter(range(first, first + 4 * len(form) + 8)), sites, sink)
    old = reference_popcount_layout(form, iter(range(first, first + 4 * len(form) + 8)), sites, sink)
    return new, old


@settings(max_examples=150, deadline=None)
@given(
    weights=st.lists(st.integers(-7, 7).filter(bool), min_size=1, max_size=70),
    side=st.integers(1, 40),
    seed=st.integers(0, 2**16),
    sink=st.one_of(st.none(), st.tuples(st.floats(-2, 42), st.floats(-2, 42))),
)
def test_random_forms_get_the_old_adders(weights: list[int], side: int, seed: int, sink: tuple | None) -> None:
    rng = random.Random(seed)
    qubits = rng.sample(range(3 * len(weights)), len(weights))  # qubit numbers in no particular order
    form = tuple(zip(qubits, weights, strict=True))
    sites = {q: (rng.randrange(side), rng.randrange(side)) for q in qubits}
    new, old = _both(form, sites, sink)
    assert new == old


@pytest.mark.parametrize("lattice", ["edges", "points"])
@pytest.mark.parametrize("seed", range(3))
def test_thinned_lattices_get_the_old_adders(lattice: str, seed: int) -> None:
    """Edge midpoints of a 14x14 grid (the lattice a robot's form covers; all distances even) or every point of a
    14x14 square (odd distances too), a random half to all of them kept, unit weights and some 2s and 3s, a
    random sink: columns of up to 364 bits, where the buckets and the rings' stopping rule decide."""
    rng = random.Random(seed)
    points = list(Grid(14, 14).edge_sites) if lattice == "edges" else [(y, x) for y in range(14) for x in range(14)]
    keep = rng.sample(points, rng.randint(len(points) // 2, len(points)))
    form = tuple((q, rng.choice((1, 1, 1, 2, 3))) for q in range(len(keep)))
    sites = dict(enumerate(keep))
    sink = (rng.uniform(0, 26), rng.uniform(0, 26))
    new, old = _both(form, sites, sink)
    assert new == old


def test_medial_balance_forms_get_the_old_adders() -> None:
    """The balance gadget of 6x6/3 on the medial layout: every robot's edge form with its sink."""
    s = default_scenario(6, 6, 3)
    plan = qaoa_plan(s, 1, PlanOptions(phase_layout="medial"))
    g = next(g for n, g in plan.sections() if n == "phase_0" and isinstance(g, SumsPhase))
    sites = variable_sites(s)
    assert any(sink is not None for sink in g.sinks)
    for form, sink in zip(g.forms, g.sinks, strict=True):
        new, old = _both(form, sites, sink)
        assert new == old


def _spatial_both(s: Scenario, sinks: bool) -> tuple[tuple, tuple]:
    plan = phase_plan(s)
    n = s.num_variables
    gadgets = plan.gadgets("gamma_0")
    pool = range(n, n + plan.num_ancillas)
    return spatial_phase(gadgets, s, pool, sinks), reference_spatial_phase(gadgets, s, pool, sinks)


@settings(max_examples=25, deadline=None)
@given(s=scenarios(max_side=5, max_robots=3), sinks=st.booleans())
def test_visit_gadgets_borrow_the_old_ancillas(s: Scenario, sinks: bool) -> None:
    """:func:`qcpp.plan.phase_layout.spatial_phase` (ancilla homes in buckets, searched ring by ring) gives
    every visit gadget the ancillas the old sort of the whole pool per node gave, in the same order."""
    new, old = _spatial_both(s, sinks)
    assert new == old


def test_visit_gadgets_borrow_the_old_ancillas_on_a_big_pool() -> None:
    """9x9/3: pools of hundreds of ancillas, where the rings (not the whole-pool fallback) decide."""
    s = default_scenario(9, 9, 3)
    new, old = _spatial_both(s, True)
    assert sum(len(g.ancillas) for g in new if isinstance(g, VisitPhase)) > 100
    assert new == old


@pytest.mark.heavy
def test_a_16x16_8_medial_phase_layer_is_the_old_one() -> None:
    """16x16/8 (eight balance forms of 480 edges, a pool of thousands): the whole medial phase layer, adders
    and visit ancillas, equals the old code's (which takes seconds here)."""
    s = default_scenario(16, 16, 8)
    new, old = _spatial_both(s, True)
    assert new == old
    sites = variable_sites(s)
    for g in new:
        if isinstance(g, SumsPhase):
            for form, sink in zip(g.forms, g.sinks, strict=True):
                fast, slow = _both(form, sites, sink)
                assert fast == slow
