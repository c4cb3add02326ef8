"""A shorter search on the calibrated devices, for tests of what holds whatever the search finds.

A compile on a named IBM device runs every step of its pipeline (compile's own routings, partial mixers planned for
the routing, the searches on the defect-free lattices, Qiskit's O3 passes on every candidate, its three seeds, our
placements, the choice by ESP) with the search sizes of :data:`qcpp.routing.options.DEFAULT_ROUTING`: tens of
CPU-seconds for one robot on 3x3. A property that holds of whatever the searches return (a routed circuit equals
its logical circuit; Qiskit's O3 is a candidate, so the choice is never worse than it) is checked as well with
:data:`SHORT_SEARCH`: every step still runs, on fewer starts, a few times faster. What the default search finds is
checked where it is the claim: the committed results (``tests/simulate/results_freshness_test.py`` and the
experiments' quick runs). The named-candidate tests of ``tests/compiler/noise_aware_test.py`` run it too where the
candidate they name does not come from the shortened steps (the cells routed on a lattice), or wins with either
search (the searches on the lattices, kept at the default's reach; the search on the other IBM device).

>>> SHORT_SEARCH.for_calibrated().placement_layouts
16
"""

from __future__ import annotations

from dataclasses import replace

from qcpp.routing.options import DEFAULT_ROUTING

SHORT_SEARCH = replace(
    DEFAULT_ROUTING,
    calibrated_routings=3,
    calibrated_placement_layouts=16,
    calibrated_placement_refine=3,
    mixer_variant_budget=2_000,
    lattice_search_max_distance=5,
)
"""The default routing options with a shorter search on the named devices (module docs)."""
