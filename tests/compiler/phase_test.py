"""The compiled phase separator: exact on feasible states, ancillas clean on every input, costs as reported.

* For every scenario of the sweep (``tests/problem/feasible_cost_test.py``: grids up to 4x4, 1-3 robots,
  obstacles, both balance and degree modes, non-default weights) and both targets: on feasible assignments
  (a sample here, all of them in the ``heavy`` test) the lowered circuit of ``phase_plan(s).gadgets(...)``
  maps the basis state to itself, ancillas back at 0, with phase ``exp(-i gamma (C(x) - reference_constant))``
  (sparse simulation of basis states).
* Random non-feasible basis states: still a phase only (the whole separator is diagonal) with clean ancillas.
* Hypothesis: random scenarios up to 5x5 with obstacles and non-default weights.
* Per gadget kind: ``cost()`` and ``logical_cost()`` equal the counts of the emitted, lowered gates.
"""

from __future__ import annotations

import cmath
import itertools
import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.estimators.fault_tolerant import rotation_t_cost
from qcpp.gadgets.phase_ising import IsingPhase
from qcpp.gadgets.phase_sums import SumsAccumulate, SumsPhase, SumsRegister
from qcpp.gadgets.phase_visits import VisitPhase, visit_ancillas
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.phase import ROTATION_T_COST, PhasePlan, phase_plan, phase_separator_gates
from qcpp.problem.cost import cost
from qcpp.problem.hamiltonian import ising_hamiltonian
from qcpp.problem.paths import enumerate_paths, path_bits
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario
from qcpp.simulate.sparse import simulate_sparse

from ..problem.conftest import scenario_dicts
from ..problem.feasible_cost_test import sweep


def gadgets_cost(plan: PhasePlan, logical: bool = False) -> Cost:
    """The plan's gadgets' summed cost (what the call graph lists for the phase part)."""
    return Cost.sum(g.logical_cost() if logical else g.cost() for g in plan.gadgets("gamma"))

GAMMA = 0.731
TOL = 1e-8


def lowered(plan: PhasePlan, n: int) -> Circuit:
    """The plan's gadgets, one section each, lowered and bound (data 0..n-1, ancillas after)."""
    secs = [Section("phase_0", tuple(g.emit())) for g in plan.gadgets("gamma_0")]
    c = Circuit([("data", n), ("logic", max(1, plan.num_ancillas))], secs)
    return lower(c)


def check_states(s: Scenario, plan: PhasePlan, circuit: Circuit, combos, others=()) -> None:  # type: ignore[no-untyped-def]
    """Assert the circuit maps each basis state of ``combos`` to itself with the plan's phase, and each of ``others``
    to itself with some phase (ancillas back at 0 in both).

    The basis states are run as one superposition with distinct amplitudes ``(1 + j/N) e^{i j}`` (a diagonal map is
    linear, so every state must come back with its own amplitude times its phase, and any state the circuit moves
    or any ancilla it leaves set shows up as a basis index not put in); the first state of each list is also run
    alone. One simulation of N states costs about a sixth of N simulations of one.
    """
    n = s.num_variables
    bound = circuit.bind({"gamma_0": GAMMA})
    wants: dict[int, complex] = {}
    for combo in combos:
        bits = np.concatenate([path_bits(s, m) for m in combo])
        idx = sum(int(b) << i for i, b in enumerate(bits))
        wants[idx] = cmath.exp(-1j * GAMMA * (cost(s, list(combo)) - plan.reference_constant))
    free = {sum(int(b) << i for i, b in enumerate(bits[:n])) for bits in others} - set(wants)
    for states, exact in ((list(wants), True), (sorted(free), False)):
        if not states:
            continue
        amps = {idx: (1 + j / len(states)) * cmath.exp(1j * j) for j, idx in enumerate(states)}
        for initial in ({states[0]: 1.0}, amps):
            out = simulate_sparse(bound, initial)
            assert {k for k, a in out.items() if abs(a) > TOL} == set(initial)
            for idx, a in initial.items():
                if exact:
                    assert abs(out[idx] - a * wants[idx]) < TOL, (idx, out[idx], a * wants[idx])
                else:
                    assert abs(abs(out[idx]) - abs(a)) < TOL


def sample_combos(s: Scenario, k: int, seed: int = 0) -> list[tuple[int, ...]]:
    pl = [enumerate_paths(s, r) for r in range(s.num_robots)]
    rng = random.Random(seed)
    return [tuple(rng.choice(p) for p in pl) for _ in range(k)]


def _id(s: Scenario) -> str:
    return f"{s.grid.rows}x{s.grid.cols}-{s.num_robots}-{s.objective.obstacles}-{s.objective.balance}"


@pytest.mark.parametrize("target", ["nisq", "ft"])
@pytest.mark.parametrize("s", sweep(), ids=_id)
def test_sweep_sampled(s: Scenario, target: str) -> None:
    plan = phase_plan(s, target=target)  # type: ignore[arg-type]
    circ = lowered(plan, s.num_variables)
    assert Cost.count(circ.gates) == gadgets_cost(plan)
    rng = random.Random(3)
    others = [[rng.randint(0, 1) for _ in range(s.num_variables)] for _ in range(4)]
    check_states(s, plan, circ, sample_combos(s, 12), others)


@pytest.mark.heavy
@pytest.mark.parametrize("target", ["nisq", "ft"])  # ft: the balance folded per pair, visit batches
@pytest.mark.parametrize("s", sweep(), ids=_id)
def test_sweep_every_feasible_assignment(s: Scenario, target: str) -> None:
    """Every feasible assignment where the sweep has at most 600, else a fixed sample of 600 (seed 7), all run as
    one superposition by :func:`check_states`."""
    plan = phase_plan(s, target=target)  # type: ignore[arg-type]
    circ = lowered(plan, s.num_variables)
    pl = [enumerate_paths(s, r) for r in range(s.num_robots)]
    combos = list(itertools.product(*pl))
    if len(combos) > 600:  # the larger products: a fixed random sample keeps this step near a minute
        combos = sample_combos(s, 600, seed=7)
    check_states(s, plan, circ, combos)


def test_depth_option_uses_couplings_only_and_stays_exact() -> None:
    s = default_scenario(3, 4, 2)
    plan = phase_plan(s, optimize="depth")
    assert {type(g) for g in plan.gadgets("gamma_0")} == {IsingPhase}
    check_states(s, plan, lowered(plan, s.num_variables), sample_combos(s, 10))


def test_whole_space_is_todays_circuit() -> None:
    s = default_scenario(3, 3, 2)
    plan = phase_plan(s, representation="whole-space")
    ham = ising_hamiltonian(s)
    assert plan.reference_constant == ham.c0
    (g,) = plan.gadgets("gamma_0")
    assert list(g.emit()) == phase_separator_gates(ham, "gamma_0")
    rng = random.Random(0)
    n = s.num_variables
    circ = lowered(plan, n).bind({"gamma_0": GAMMA})
    for _ in range(20):  # exact on every bit string, not only feasible ones
        bits = [rng.randint(0, 1) for _ in range(n)]
        idx = sum(b << i for i, b in enumerate(bits))
        want = cmath.exp(-1j * GAMMA * (float(ham.evaluate(np.array(bits))) - ham.c0))
        assert abs(simulate_sparse(circ, idx)[idx] - want) < TOL


def test_feasible_beats_whole_space_and_explains_itself() -> None:
    s = default_scenario(4, 4, 3)
    ours, today = phase_plan(s), phase_plan(s, representation="whole-space")
    assert gadgets_cost(ours).cx < gadgets_cost(today).cx / 2
    rows = ours.explain()
    assert {r["group"] for r in rows} >= {"linear + couplings", "node visits", "balance"}
    bal = next(r for r in rows if r["group"] == "balance")
    assert bal["construction"] == "arithmetic"
    assert bal["cost"]["cx"] < bal["alternatives"]["couplings"]["cx"]
    assert gadgets_cost(phase_plan(s, target="ft"), True).rotations <= gadgets_cost(ours, True).rotations


def test_non_integer_lengths_fall_back_to_couplings() -> None:
    from ..problem.conftest import make_scenario

    s = make_scenario(3, 3, [((0, 0), (2, 2)), ((0, 2), (2, 0))], edge_lengths=[[[0, 0], [0, 1], 2**0.5]])
    plan = phase_plan(s)
    bal = next(r for r in plan.explain() if r["group"].startswith("balance"))
    assert bal["construction"] == "couplings" and "non-integer" in bal["group"]
    check_states(s, plan, lowered(plan, s.num_variables), sample_combos(s, 10))


def test_rotation_price_matches_the_estimators() -> None:
    assert rotation_t_cost(1e-3) == ROTATION_T_COST


def test_bad_options() -> None:
    s = default_scenario(3, 3, 1)
    for kw in ({"target": "gpu"}, {"representation": "half"}, {"optimize": "speed"}):
        with pytest.raises(ValueError):
            phase_plan(s, **kw)  # type: ignore[arg-type]


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    d=scenario_dicts(max_size=5, max_robots=3),
    target=st.sampled_from(["nisq", "ft"]),
    budget=st.sampled_from([None, None, 0, 6, 24, 40]),
    seed=st.integers(0, 99),
)
def test_random_scenarios(d, target, budget, seed) -> None:  # type: ignore[no-untyped-def]
    from qcpp.problem.scenario import scenario_from_dict

    s = scenario_from_dict(d)
    if any(not enumerate_paths(s, r) for r in range(s.num_robots)):
        return
    plan = phase_plan(s, target=target, ancilla_budget=budget)
    assert budget is None or plan.num_ancillas <= budget
    circ = lowered(plan, s.num_variables)
    assert Cost.count(circ.gates) == gadgets_cost(plan)
    rng = random.Random(seed)
    others = [[rng.randint(0, 1) for _ in range(s.num_variables)] for _ in range(2)]
    check_states(s, plan, circ, sample_combos(s, 4, seed), others)


# ------------------------------------------------------------------ per gadget kind


def _counts(g) -> tuple[Cost, Cost]:  # type: ignore[no-untyped-def]
    qubits = 1 + max(q for gate in g.emit() for q in gate.qubits)
    c = Circuit([("q", qubits)], [Section("phase_0", tuple(g.emit()))])
    return Cost.count(lower(c).gates), Cost.count(lower(c, basis=LOGICAL_BASIS).gates)


@pytest.mark.parametrize("products", [False, True])
@pytest.mark.parametrize("sizes", [s for k in (2, 3, 4) for s in itertools.product((2, 3, 4), repeat=k)])
def test_visit_gadget_cost(sizes: tuple[int, ...], products: bool) -> None:
    q = iter(range(100))
    visitors = tuple(tuple(next(q) for _ in range(k)) for k in sizes)
    g = VisitPhase("gamma_0", 8.0, visitors, tuple(range(100, 100 + visit_ancillas(sizes, products))), products)
    assert _counts(g) == (g.cost(), g.logical_cost())


@pytest.mark.parametrize("products", [False, True])
def test_visit_gadget_is_exact_with_clean_ancillas(products: bool) -> None:
    visitors = ((0, 1, 2, 3), (4, 5, 6), (7, 8))
    anc = tuple(range(9, 9 + visit_ancillas((4, 3, 2), products)))
    g = VisitPhase("gamma_0", 3.5, visitors, anc, products)
    c = lower(Circuit([("q", 9 + len(anc))], [Section("phase_0", tuple(g.emit()))])).bind({"gamma_0": GAMMA})
    for bits in itertools.product((0, 1), repeat=9):
        idx = sum(b << i for i, b in enumerate(bits))
        out = simulate_sparse(c, idx)
        assert {k for k, a in out.items() if abs(a) > TOL} == {idx}
        if all(sum(bits[i] for i in v) in (0, 2) for v in visitors):
            ys = [sum(bits[i] for i in v) / 2 for v in visitors]
            val = 3.5 * sum(ys[a] * ys[b] for a in range(3) for b in range(a + 1, 3))
            assert abs(out[idx] - cmath.exp(-1j * GAMMA * (val - g.constant))) < TOL


@st.composite
def sums_gadgets(draw: st.DrawFn, max_terms: int = 5, ancillas: int = 60, placed: bool = False) -> SumsPhase:
    """A balance gadget of 1-3 random integer forms; ``placed``: each data qubit also gets a random grid site,
    and each form a random sink or none (:func:`qcpp.plan.phase_layout.balance_sinks`)."""
    n_forms = draw(st.integers(1, 3))
    qubits = iter(range(64))
    forms = tuple(
        tuple(
            (next(qubits), w)
            for w in draw(st.lists(st.integers(-5, 6).filter(bool), min_size=0, max_size=max_terms))
        )
        for _ in range(n_forms)
    )
    coef = st.sampled_from([0.0, 1.0, -0.5, 2.25, 0.3])
    m = [[draw(coef) for _ in range(n_forms)] for _ in range(n_forms)]
    sym = tuple(tuple((m[a][b] + m[b][a]) / 2 for b in range(n_forms)) for a in range(n_forms))
    lin = tuple(draw(coef) for _ in range(n_forms))
    used = sum(len(f) for f in forms)
    if not placed:
        return SumsPhase("gamma_0", forms, sym, lin, tuple(range(used, used + ancillas)))
    site = st.tuples(st.integers(0, 9), st.integers(0, 9))
    sites = tuple((q, *draw(site)) for f in forms for q, _ in f)
    sink = st.one_of(st.none(), st.tuples(st.floats(0, 9), st.floats(0, 9)))
    sinks = tuple(draw(sink) for _ in forms)
    return SumsPhase("gamma_0", forms, sym, lin, tuple(range(used, used + ancillas)), sites, sinks)


@settings(max_examples=60, deadline=None)
@given(g=sums_gadgets())
def test_sums_gadget_cost_and_exactness(g: SumsPhase) -> None:
    n_data = sum(len(f) for f in g.forms)
    if n_data == 0 or not list(g.emit()):
        return
    assert _counts(g) == (g.cost(), g.logical_cost())
    check_sums_phase_on_random_inputs(g, samples=12)


def check_sums_phase_on_random_inputs(g: SumsPhase, samples: int) -> None:
    """The lowered gadget keeps every sampled basis input and multiplies it by ``exp(-i gamma (form - constant))``."""
    n_data = sum(len(f) for f in g.forms)
    c = lower(Circuit([("q", n_data + g.num_ancillas)], [Section("phase_0", tuple(g.emit()))]))
    c = c.bind({"gamma_0": GAMMA})
    rng = random.Random(n_data)
    for _ in range(samples):
        bits = [rng.randint(0, 1) for _ in range(n_data)]
        idx = sum(b << i for i, b in enumerate(bits))
        out = simulate_sparse(c, idx)
        assert {k for k, a in out.items() if abs(a) > TOL} == {idx}
        gs = [sum(w * bits[q] for q, w in f) for f in g.forms]
        n = len(gs)
        val = sum(g.matrix[a][b] * gs[a] * gs[b] for a in range(n) for b in range(n))
        val += sum(g.linear[a] * gs[a] for a in range(n))
        assert abs(out[idx] - cmath.exp(-1j * GAMMA * (val - g.constant))) < TOL


def test_ising_gadget_cost() -> None:
    g = IsingPhase("gamma_0", ((0, 0.5), (2, -1.0)), ((0, 1, 0.25), (1, 2, 2.0), (0, 2, -0.5)))
    assert _counts(g) == (g.cost(), g.logical_cost())


@pytest.mark.parametrize("budget", [0, 4, 26, 31, 40])
def test_ancilla_budget_is_respected_and_exact(budget: int) -> None:
    grid = {40: (5, 5, 2), 31: (4, 4, 3)}.get(budget, (4, 4, 2))
    s = default_scenario(*grid)
    plan = phase_plan(s, ancilla_budget=budget)
    assert plan.num_ancillas <= budget
    circ = lowered(plan, s.num_variables)
    assert Cost.count(circ.gates) == gadgets_cost(plan)
    rng = random.Random(budget)
    others = [[rng.randint(0, 1) for _ in range(s.num_variables)] for _ in range(3)]
    check_states(s, plan, circ, sample_combos(s, 8, budget), others)
    if budget == 31:  # the arithmetic needs 48: the register variant (one tree at a time) fits
        assert any(r["construction"] == "registers" for r in plan.explain())
    if budget == 40:  # 5x5: arithmetic 64, registers 44, accumulator 38
        assert any(r["construction"] == "accumulator" for r in plan.explain())


@settings(max_examples=30, deadline=None)
@given(weights=st.lists(st.integers(-5, 7).filter(bool), min_size=1, max_size=7))
def test_sums_register_gadget(weights: list[int]) -> None:
    form = tuple(enumerate(weights))
    n = len(form)
    probe = SumsRegister(form, ())
    g = SumsRegister(form, tuple(range(n, n + probe.width)), tuple(range(n + probe.width, n + probe.width + 40)))
    assert _counts(g) == (g.cost(), g.logical_cost())
    c = lower(Circuit([("q", n + probe.width + probe.num_ancillas)], [Section("s", tuple(g.emit()))]))
    for bits in itertools.islice(itertools.product((0, 1), repeat=n), 40):
        idx = sum(b << i for i, b in enumerate(bits))
        out = simulate_sparse(c, idx)
        ((key, amp),) = [(k, a) for k, a in out.items() if abs(a) > TOL]
        assert abs(amp - 1) < TOL and key & ((1 << n) - 1) == idx
        assert key >> (n + probe.width) == 0  # tree ancillas clean
        value = sum(abs(w) * (b ^ (w < 0)) for b, (_, w) in zip(bits, form))
        reg = key >> n
        cols = [k for k, p in enumerate(probe._count[3]) if p]
        assert sum(((reg >> j) & 1) << k for j, k in enumerate(cols)) == value


@settings(max_examples=40, deadline=None)
@given(
    weights=st.lists(st.sampled_from([1, 1, 1, 2, 3, -1, 5, -2]), min_size=1, max_size=6),
    extra=st.integers(0, 2),
    subtract=st.booleans(),
    seed=st.integers(0, 99),
)
def test_sums_accumulate_gadget(weights: list[int], extra: int, subtract: bool, seed: int) -> None:
    n = len(weights)
    chunk = tuple(enumerate(weights))
    width = sum(abs(w) for w in weights).bit_length() + extra
    acc = tuple(range(n, n + width))
    anc = tuple(range(n + width, n + width + SumsAccumulate(chunk, acc).num_ancillas))
    g = SumsAccumulate(chunk, acc, anc, subtract)
    assert _counts(g) == (g.cost(), g.logical_cost())
    c = lower(Circuit([("q", n + width + len(anc))], [Section("s", tuple(g.emit()))]))
    rng = random.Random(seed)
    for _ in range(6):
        bits = [rng.randint(0, 1) for _ in range(n)]
        val = sum(abs(w) * (b ^ (w < 0)) for b, w in zip(bits, weights))
        a0 = rng.randint(val, (1 << width) - 1) if subtract else rng.randint(0, (1 << width) - 1 - val)
        idx = sum(b << i for i, b in enumerate(bits)) | (a0 << n)
        ((key, amp),) = [(k, a) for k, a in simulate_sparse(c, idx).items() if abs(a) > TOL]
        assert abs(amp - 1) < TOL and key & ((1 << n) - 1) == idx & ((1 << n) - 1)
        assert key >> (n + width) == 0  # tree ancillas and carries clean
        assert (key >> n) & ((1 << width) - 1) == (a0 - val if subtract else a0 + val)


def _every_candidate(s: Scenario, target: str, budget: int | None) -> list[tuple[tuple[str, ...], PhasePlan]]:
    """Every balance choice of ``s``'s feasible plan, assembled (what the plan compares, with no pruning)."""
    from qcpp.plan.phase import _assemble, _sums_options
    from qcpp.problem.feasible_cost import feasible_cost

    fc = feasible_cost(s)
    balance = [_sums_options(g, fc.num_variables, target, "cx", budget, True) for g in fc.sums]  # type: ignore[arg-type]
    choices: list[tuple[str, ...]] = [()]
    for opts in balance:
        choices = [(*c, k) for c in choices for k in opts["options"]]
    return [(c, _assemble(fc, target, "cx", budget, balance, c)) for c in choices]  # type: ignore[arg-type]


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    d=scenario_dicts(max_size=5, max_robots=3),
    target=st.sampled_from(["nisq", "ft"]),
    budget=st.sampled_from([None, None, 0, 24]),
)
def test_couplings_floor_bounds_the_couplings_plan(d, target, budget) -> None:  # type: ignore[no-untyped-def]
    """The plan skips a candidate whose couplings floor is above a score already met: the floor is below the
    candidate's own score, and the plan picks what comparing every candidate picks."""
    from qcpp.plan.phase import _couplings_floor
    from qcpp.problem.feasible_cost import feasible_cost
    from qcpp.problem.scenario import scenario_from_dict

    s = scenario_from_dict(d)
    if any(not enumerate_paths(s, r) for r in range(s.num_robots)):
        return
    fc = feasible_cost(s)
    candidates = _every_candidate(s, target, budget)
    for choice, plan in candidates:
        assert _couplings_floor(fc, choice, target) <= plan.score()[0]  # type: ignore[arg-type]
    best = min(range(len(candidates)), key=lambda i: (candidates[i][1].score(), i))
    assert phase_plan(s, target=target, ancilla_budget=budget).explain() == candidates[best][1].explain()


def test_couplings_floor_skips_the_couplings_candidate_on_a_default_scenario() -> None:
    """On the default 5x5 / 2 robots the balance's couplings cannot beat its arithmetic: the floor says so."""
    from qcpp.plan.phase import _couplings_floor
    from qcpp.problem.feasible_cost import feasible_cost

    s = default_scenario(5, 5, 2)
    (arith, a_plan), (coup, c_plan) = _every_candidate(s, "nisq", None)
    assert (arith, coup) == (("arithmetic",), ("couplings",))
    floor = _couplings_floor(feasible_cost(s), coup, "nisq")
    assert a_plan.score()[0] < floor <= c_plan.score()[0]
    assert phase_plan(s).explain() == a_plan.explain()
