"""The spatial phase layout (``PlanOptions(phase_layout="spatial")``): exact, same counts, more local.

* Every feasible assignment of small scenarios (3x3 with 2 robots, a 3x4 with an obstacle and interior ends,
  a sample on 4x4/2 and 4x4/3): the lowered spatial phase separator maps the basis state to itself with phase
  ``exp(-i gamma (C(x) - K))`` and returns every ancilla to |0>; random infeasible states stay put, clean.
* Hypothesis: a :class:`SumsPhase` with random forms and random sites costs what its lowered gates count, and
  applies the exact phase of its quadratic form on random inputs with clean ancillas.
* The pass adds exactly one CX per adder each way (star-shaped adders) and changes nothing else; no adder gate
  joins two data bits; estimate == compiled circuit (:func:`qcpp.estimators.crosscheck.crosscheck`) with the option,
  over two layers, on obstacles and interior ends.
* Locality, measured on the problem grid: the adders' total wire length (lattice distance between the operands
  of every two-qubit gate) is smaller than ``pooled``'s, and each visit gadget's ancillas are nearer its node.
"""

from __future__ import annotations

import itertools
import json
import random

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.estimators.crosscheck import Case, crosscheck, interior_endpoints
from qcpp.gadgets.phase_sums import (
    SumsPhase,
    column_counts,
    hilbert_key,
    popcount_layout,
    spatial_popcount_layout,
)
from qcpp.gadgets.phase_visits import VisitPhase
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import lower
from qcpp.plan.options import PlanOptions
from qcpp.plan.phase_layout import balance_sinks, spatial_phase, variable_sites
from qcpp.plan.qaoa import qaoa_circuit, qaoa_plan
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict

from ..cli.clirun import run
from .phase_test import check_states, check_sums_phase_on_random_inputs, sample_combos, sums_gadgets

SPATIAL = PlanOptions(phase_layout="spatial")
MEDIAL = PlanOptions(phase_layout="medial")
OBSTACLE_INTERIOR = {
    "grid": {"rows": 3, "cols": 4, "obstacles": [[0, 3]]},
    "robots": [{"start": [1, 1], "goal": [2, 3]}, {"start": [0, 0], "goal": [2, 0]}],
    "objective": {"obstacles": "hard"},
}


def _phase_circuit(s: Scenario, options: PlanOptions) -> tuple[Circuit, object]:
    """One layer's phase separator as the QAOA circuit has it (data, then the logic register), lowered."""
    plan = qaoa_plan(s, 1, options)
    secs = [Section(name, tuple(g.emit())) for name, g in plan.sections() if name == "phase_0"]
    n = s.num_variables
    return lower(Circuit([("data", n), ("logic", max(1, plan.phase_plan.num_ancillas))], secs)), plan.phase_plan


def _every(s: Scenario) -> list[tuple[int, ...]]:
    return list(itertools.product(*(enumerate_paths(s, r) for r in range(s.num_robots))))


@pytest.mark.parametrize(
    "which", ["3x3/2 every", "3x4 obstacle interior every", "4x4/2 sample", "4x4/3 sample", "5x5/2 sample"]
)
def test_spatial_phase_separator_is_exact_on_feasible_states(which: str) -> None:
    s = {
        "3x3/2 every": lambda: default_scenario(3, 3, 2),
        "3x4 obstacle interior every": lambda: scenario_from_dict(OBSTACLE_INTERIOR),
        "4x4/2 sample": lambda: default_scenario(4, 4, 2),
        "4x4/3 sample": lambda: default_scenario(4, 4, 3),
        "5x5/2 sample": lambda: default_scenario(5, 5, 2),
    }[which]()
    circuit, plan = _phase_circuit(s, SPATIAL if "every" in which else MEDIAL)  # medial: spatial with balance sinks
    combos = _every(s) if "every" in which else sample_combos(s, 25, seed=3)
    rng = random.Random(1)
    others = [tuple(rng.randint(0, 1) for _ in range(s.num_variables)) for _ in range(5)]
    check_states(s, plan, circuit, combos, others)


def test_the_pass_adds_one_cx_per_adder_each_way_and_nothing_else() -> None:
    for s in (default_scenario(4, 4, 2), default_scenario(5, 5, 3), interior_endpoints(4, 4, "hard")):
        pooled, spatial = qaoa_plan(s, 1), qaoa_plan(s, 1, SPATIAL)
        a = [g for name, g in pooled.sections() if name == "phase_0"]
        b = [g for name, g in spatial.sections() if name == "phase_0"]
        assert [type(g) for g in a] == [type(g) for g in b]
        extra = 0
        for x, y in zip(a, b):
            if isinstance(x, SumsPhase):
                fa, ha, _ = x.adders()
                assert y.sites and Cost.count(y.emit()) == Cost.count(x.emit()) + Cost.of(cx=2 * (fa + ha))
                extra += 2 * (fa + ha)
            else:
                assert x.kind == y.kind and Cost.count(x.emit()) == Cost.count(y.emit())
        assert extra > 0
        hi, lo = lower(qaoa_circuit(s, 1, SPATIAL)), lower(qaoa_circuit(s, 1))
        assert hi.num_qubits == lo.num_qubits
        assert Cost.count(hi.gates) == Cost.count(lo.gates) + Cost.of(cx=extra)
        assert spatial.cost() == Cost.count(hi.gates) and pooled.cost() == Cost.count(lo.gates)


@pytest.mark.parametrize(
    "options", [SPATIAL, PlanOptions(phase_layout="spatial", target="ft"),
                PlanOptions(phase_layout="spatial", ancilla_budget=5)], ids=["nisq", "ft", "budget5"],
)  # fmt: skip
@pytest.mark.parametrize("which", ["open 3x3/2", "soft 4x4 interior", "hard 4x4 interior"])
def test_estimate_equals_compiled_with_the_spatial_layout(which: str, options: PlanOptions) -> None:
    s = {
        "open 3x3/2": lambda: default_scenario(3, 3, 2),
        "soft 4x4 interior": lambda: interior_endpoints(4, 4, "soft"),
        "hard 4x4 interior": lambda: interior_endpoints(4, 4, "hard"),
    }[which]()
    assert crosscheck(Case(s, 2, options)) == []


# --- the popcount by place --------------------------------------------------------------------------------------
def placed_sums() -> st.SearchStrategy[SumsPhase]:
    return sums_gadgets(max_terms=8, ancillas=80, placed=True)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(g=placed_sums())
def test_placed_sums_gadget_cost_and_exactness(g: SumsPhase) -> None:
    n_data = sum(len(f) for f in g.forms)
    if n_data == 0 or not list(g.emit()):
        return
    c = lower(Circuit([("q", n_data + g.num_ancillas)], [Section("phase_0", tuple(g.emit()))]))
    assert Cost.count(c.gates) == g.cost()
    assert max(q for gate in c.gates for q in gate.qubits) < n_data + g.num_ancillas
    check_sums_phase_on_random_inputs(g, samples=10)


@settings(max_examples=80, deadline=None)
@given(
    weights=st.lists(st.integers(-9, 9).filter(bool), min_size=1, max_size=30),
    seed=st.integers(0, 1000),
    sink=st.one_of(st.none(), st.tuples(st.floats(0, 12), st.floats(0, 12))),
)
def test_the_placed_popcount_has_the_counted_adders(weights: list[int], seed: int, sink: tuple | None) -> None:
    rng = random.Random(seed)
    form = tuple(enumerate(weights))
    sites = {q: (rng.randint(0, 12), rng.randint(0, 12)) for q, _ in form}
    top = len(form) + 200
    gates, reg, home = spatial_popcount_layout(form, iter(range(len(form), top)), sites, sink)
    plain, plain_reg = popcount_layout(form, iter(range(len(form), top)))
    fa, ha, cp, present = column_counts([abs(w) for w in weights])
    assert Cost.count(gates) == Cost.count(plain) + Cost.of(cx=fa + ha)
    assert [q is None for q in reg] == [q is None for q in plain_reg]
    # every adder gate touches an ancilla: no gate joins two data bits (copies are the data -> ancilla CX)
    assert all(any(q >= len(form) for q in g.qubits) for g in gates if len(g.qubits) > 1)
    assert sorted(home) == list(range(len(form), len(form) + fa + ha + cp))
    assert [q is not None for q in reg] == list(present)


def test_hilbert_keys_visit_every_point_once_in_unit_steps() -> None:
    order = 8
    walk = sorted(((y, x) for y in range(order) for x in range(order)), key=lambda p: hilbert_key(*p, order))
    assert sorted(hilbert_key(y, x, order) for y, x in walk) == list(range(order * order))
    assert all(abs(a[0] - b[0]) + abs(a[1] - b[1]) == 1 for a, b in zip(walk, walk[1:]))


# --- locality -----------------------------------------------------------------------------------------------------
def wire_length(gates: list[Gate], sites: dict[int, tuple[int, int]]) -> int:
    """Lattice distance summed over the operand pairs of every multi-qubit gate; an ancilla sits where the first
    sited qubit it meets sits (the same rule for both layouts)."""
    where = dict(sites)
    total = 0
    for g in gates:
        qs = g.qubits
        if len(qs) < 2:
            continue
        anchor = next((where[q] for q in qs if q in where), None)
        for q in qs:
            if q not in where and anchor is not None:
                where[q] = anchor
        for a, b in itertools.combinations(qs, 2):
            total += abs(where[a][0] - where[b][0]) + abs(where[a][1] - where[b][1])
    return total


@pytest.mark.parametrize(("rows", "robots", "ratio"), [(4, 2, 1.0), (5, 2, 0.98), (6, 3, 0.9)])
def test_spatial_adders_are_shorter_wired_and_visit_ancillas_nearer(rows: int, robots: int, ratio: float) -> None:
    """Wire length of the balance gadget, spatial / pooled, measured: 1530 / 1556 (4x4/2), 3800 / 3960 (5x5/2),
    9952 / 11254 (6x6/3): small grids gain little, the gain grows with the grid."""
    s = default_scenario(rows, rows, robots)
    sites = variable_sites(s)
    pooled = [g for n, g in qaoa_plan(s, 1).sections() if n == "phase_0"]
    spatial = [g for n, g in qaoa_plan(s, 1, SPATIAL).sections() if n == "phase_0"]
    sums = [(a, b) for a, b in zip(pooled, spatial) if isinstance(a, SumsPhase)]
    assert sums
    for a, b in sums:
        assert wire_length(b.emit(), sites) < ratio * wire_length(a.emit(), sites)
    # visit gadgets: ancillas borrowed near the node (their home is an adder's site) and never shared in a gadget
    homes = {**sites, **next(b for _, b in sums).ancilla_sites()}

    def spread(gs: list) -> float:
        d = []
        for g in gs:
            if isinstance(g, VisitPhase) and g.ancillas:
                assert len(set(g.ancillas)) == len(g.ancillas)
                es = [sites[q] for v in g.visitors for q in v]
                at = (sum(e[0] for e in es) / len(es), sum(e[1] for e in es) / len(es))
                d += [abs(homes[a][0] - at[0]) + abs(homes[a][1] - at[1]) for a in g.ancillas if a in homes]
        return sum(d) / len(d)

    assert spread(spatial) < 0.6 * spread(pooled)


def test_spatial_phase_keeps_gadgets_without_sums_or_pool() -> None:
    s = default_scenario(3, 3, 1)  # no balance, no visits: nothing to move
    n = s.num_variables
    gs = qaoa_plan(s, 1).phase_plan.gadgets("gamma_0")
    assert spatial_phase(gs, s, range(n, n)) == gs


def test_cli_phase_layout_flag_changes_no_count() -> None:
    where = "examples/paper_3x3.toml"
    rows = []
    for layout in ("pooled", "spatial"):
        res = run("compile", where, "--phase-layout", layout, "--lowered", "--json")
        assert res.exit_code == 0, res.output
        rows.append(json.loads(res.stdout)["gates"])
        est = run("estimate", "--scenario", where, "--phase-layout", layout, "--json")
        assert est.exit_code == 0, est.output
        rows.append(json.loads(est.stdout)[0]["cx"])
    assert rows[0] == rows[2] and rows[1] == rows[3]


def test_device_compiles_default_to_the_spatial_layout() -> None:
    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.pipeline.device_plan import device_plan_options

    s = interior_endpoints(4, 4, "hard")
    spatial = Cost.count(lower(qaoa_circuit(s, 1, PlanOptions(fuse=False, phase_layout="spatial"))).gates)
    pooled = Cost.count(lower(qaoa_circuit(s, 1, PlanOptions(fuse=False, phase_layout="pooled"))).gates)
    assert spatial.cx > pooled.cx
    assert Cost.count(compile_for_device(s, 1, "grid", lowered=True).compiled.circuit.gates) == spatial
    assert Cost.count(compile_for_device(s, 1, "all-to-all", lowered=True).compiled.circuit.gates) == pooled
    explicit = compile_for_device(s, 1, "grid", PlanOptions(phase_layout="pooled"), lowered=True)
    assert Cost.count(explicit.compiled.circuit.gates) == pooled
    assert device_plan_options(PlanOptions(), "quantinuum_helios").phase_layout == "pooled"
    devices = ("grid", "google_willow", "heavy-hex", "ibm_fez")
    settled = [device_plan_options(PlanOptions(), d).phase_layout for d in devices]
    assert settled == ["medial", "medial", "medial", "spatial"]  # heavy-hex: the cells' balance sinks
    assert device_plan_options(PlanOptions(), "heavy-hex", layout_method="greedy").phase_layout == "spatial"
    assert qaoa_plan(s, 1).cost() == qaoa_plan(s, 1, PlanOptions(phase_layout="pooled")).cost()  # auto unrouted


def test_a_sink_pulls_the_register_bits_towards_it() -> None:
    """With the sinks :func:`balance_sinks` gives two robots (the middle of the side their patches share), every
    form's register bits end nearer that side than without a sink, at the same gate counts."""
    s = default_scenario(5, 5, 2)
    g = next(g for n, g in qaoa_plan(s, 1, MEDIAL).sections() if n == "phase_0" and isinstance(g, SumsPhase))
    assert g.sinks == balance_sinks(s, [0, 1], g.matrix) == ((8.0, 4.0), (0.0, 4.0))
    spatial = next(g for n, g in qaoa_plan(s, 1, SPATIAL).sections() if n == "phase_0" and isinstance(g, SumsPhase))
    assert spatial.sinks == () and spatial.kind == g.kind and spatial.cost() == g.cost()
    sites = variable_sites(s)
    for form, sink in zip(g.forms, g.sinks, strict=True):
        spread = []
        for target in (None, sink):
            gates, reg, home = spatial_popcount_layout(form, iter(range(1000, 1200)), sites, target)
            where = {**sites, **home}
            spread.append(sum(abs(where[q][0] - sink[0]) + abs(where[q][1] - sink[1]) for q in reg if q is not None))
            assert Cost.count(gates) == Cost.count(spatial_popcount_layout(form, iter(range(1000, 1200)), sites)[0])
        assert spread[1] < spread[0]
    assert balance_sinks(default_scenario(4, 4, 1), [0], ((1.0,),)) == (None,)


def _local_first_reference(
    form: tuple[tuple[int, int], ...], first: int, sites: dict[int, tuple[int, int]], sink: tuple[float, float]
) -> list[Gate]:
    """The local-first popcount written plainly (no copies: unit weights): every step searches every bit of every
    column for its tightest triple, as the docs of :func:`spatial_popcount_layout` describe it."""
    from qcpp.gadgets.phase_sums import star_full_adder, star_half_adder

    order = 1
    while order <= max(max(sites[q]) for q, _ in form):
        order <<= 1

    def key(it: tuple[int, tuple[int, int]]) -> tuple[int, int]:
        return hilbert_key(it[1][0], it[1][1], order), it[0]

    def apart(a: tuple[float, float], b: tuple[float, float]) -> float:
        return abs(a[0] - b[0]) + abs(a[1] - b[1])

    cols: dict[int, list[tuple[int, tuple[int, int]]]] = {0: [(q, sites[q]) for q, _ in form]}
    fresh = itertools.count(first)
    gates: list[Gate] = []

    def tightest(k: int) -> tuple | None:
        col = cols.get(k, [])
        found = []
        for it in col:
            near = sorted((o for o in col if o is not it), key=lambda o: (apart(o[1], it[1]), key(o)))[:2]
            if len(near) == 2:
                trio = [it, *near]
                diameter = max(apart(a[1], b[1]) for a, b in itertools.combinations(trio, 2))
                found.append(((diameter, -apart(it[1], sink), key(it)), k, trio))
        return min(found, key=lambda f: (f[0], f[1])) if found else None

    def full_adder(k: int, trio: list) -> None:
        mid = min(trio, key=lambda it: (apart(it[1], sink), key(it)))
        a, c = (it[0] for it in trio if it is not mid)
        t = next(fresh)
        gates.extend(star_full_adder(a, mid[0], c, t))
        cols[k] = [it for it in cols[k] if it[0] not in (a, c)]
        cols.setdefault(k + 1, []).append((t, mid[1]))

    while (best := min(filter(None, (tightest(k) for k in list(cols))), default=None, key=lambda f: (f[0], f[1]))):
        full_adder(best[1], best[2])
    k = 0
    while k <= max(cols):
        while (best := tightest(k)) is not None:
            full_adder(k, best[2])
        col = sorted(cols.get(k, []), key=key)
        if len(col) == 2:
            if apart(sink, col[1][1]) < apart(sink, col[0][1]):
                col.reverse()
            t = next(fresh)
            gates.extend(star_half_adder(col[0][0], col[1][0], t))
            cols[k] = col[:1]
            cols.setdefault(k + 1, []).append((t, col[0][1]))
        k += 1
    return gates


@settings(max_examples=40, deadline=None)
@given(
    n=st.integers(1, 40),
    seed=st.integers(0, 1000),
    sink=st.tuples(st.floats(0, 12), st.floats(0, 12)),
)
def test_local_first_adders_are_the_plain_searchs(n: int, seed: int, sink: tuple[float, float]) -> None:
    """With a sink, :func:`spatial_popcount_layout` keeps every bit's tightest triple and refreshes only what an
    adder changed: it picks exactly the adders the plain search over every bit of every column picks."""
    rng = random.Random(seed)
    form = tuple((q, 1) for q in range(n))
    sites = {q: (rng.randint(0, 12), rng.randint(0, 12)) for q in range(n)}
    gates, _, _ = spatial_popcount_layout(form, iter(range(n, n + 200)), sites, sink)
    assert gates == _local_first_reference(form, n, sites, sink)


def test_local_first_joins_nearer_bits_than_the_passes() -> None:
    """On the medial layout's balance forms (4x4/2, 5x5/2) the local-first adders' wire length (lattice distance
    between the operands of every two-qubit gate, ancillas at their sites) is below the passes' with the same sink."""
    from .layout_reference import _LocalFirst, reference_popcount_layout

    for s in (default_scenario(4, 4, 2), default_scenario(5, 5, 2)):
        g = next(g for n, g in qaoa_plan(s, 1, MEDIAL).sections() if n == "phase_0" and isinstance(g, SumsPhase))
        sites = variable_sites(s)
        for form, sink in zip(g.forms, g.sinks, strict=True):
            local, _, home = spatial_popcount_layout(form, iter(range(1000, 1200)), sites, sink)
            passes = []
            original = _LocalFirst.next_triple
            try:  # without local first (the old code's passes along the curve, sums kept nearest the sink)
                _LocalFirst.next_triple = lambda self, column=None: None  # type: ignore[method-assign]
                passes, _, home_passes = reference_popcount_layout(form, iter(range(1000, 1200)), sites, sink)
            finally:
                _LocalFirst.next_triple = original  # type: ignore[method-assign]
            assert Cost.count(local) == Cost.count(passes)
            assert wire_length(local, {**sites, **home}) < wire_length(passes, {**sites, **home_passes})
