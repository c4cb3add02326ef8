"""The phase separator: ``exp(-i gamma (C - K))`` on every state the QAOA circuit can hold.

Two representations of the cost ``C``:

* ``whole-space`` -- the exact Ising Hamiltonian ``C = c0 + sum h_i Z_i + sum J_ij Z_i Z_j``
  (:func:`qcpp.problem.hamiltonian.ising_hamiltonian`): ``RZ(2 gamma h_i)`` on each qubit and ``RZZ(2 gamma J_ij)``
  on each coupled pair (:func:`phase_separator_gates`), ``K = c0``. Exact on every bit string; its balance
  term couples every edge of two robots, so it costs ``O((re)^2)`` CX.
* ``feasible`` (default) -- :func:`qcpp.problem.feasible_cost.feasible_cost`, exact on every feasible assignment
  (the only states the constrained mixer ever produces). Each term group gets the cheapest exact construction
  for the target (:func:`phase_plan`): the linear part as RZ gates, each node that several robots can pass as
  visit bits (:class:`~qcpp.gadgets.phase_visits.VisitPhase`) or couplings, the balance term as
  arithmetic on path-length registers (:class:`~qcpp.gadgets.phase_sums.SumsPhase`; on ``ft`` one register
  per balanced pair, the difference of two robots' lengths) or couplings, and on the ``ft`` target equal-angle
  rotations merged by Hamming-weight phasing, the nodes' visit products too
  (:class:`~qcpp.gadgets.visit_batch.VisitBatch`). ``O(re log re)`` CX.

Cost models (:func:`~qcpp.plan.phase_choice.score`): ``nisq`` minimises CX, then rotations; ``ft`` minimises T
gates with an AND at 4 T (its uncompute 0 T: measurement-based), a Toffoli at 7 T and an arbitrary rotation at
:data:`ROTATION_T_COST` T, then CX.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> from qcpp.problem.hamiltonian import ising_hamiltonian
    >>> from qcpp.ir.angles import Angle
    >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
    >>> gates = phase_separator_gates(ising_hamiltonian(s), "gamma_0")
    >>> sorted({g.name for g in gates}), str(gates[0].params[0])
    (['rz', 'rzz'], '3.0*gamma_0')
    >>> from qcpp.problem.presets import default_scenario
    >>> plan = phase_plan(default_scenario(4, 4, 2))   # the first of a nisq score is the CX count
    >>> plan.score()[0] < phase_plan(default_scenario(4, 4, 2), representation="whole-space").score()[0]
    True
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache

from qcpp.gadgets import Gadget
from qcpp.gadgets.phase_ising import COEFFICIENT_TOLERANCE, IsingPhase, ising_form
from qcpp.gadgets.phase_sums import SumsAccumulate, SumsPhase, SumsRegister
from qcpp.gadgets.phase_visits import VisitPhase, visit_ancillas
from qcpp.gadgets.visit_batch import VisitBatch, visit_batch_ancillas
from qcpp.ir.angles import Angle
from qcpp.ir.cost import TARGETS, Cost, Target
from qcpp.ir.gates import Gate, rz, rzz
from qcpp.plan.options import Optimize, Phase
from qcpp.plan.phase_choice import (
    EXACT_EXPANSION_LIMIT,
    ROTATION_T_COST,
    SUMS_VARIANTS,
    coupling_cost,
    couplings_floor,
    ft_t_count,
    hamming_groups,
    plan_score,
    prefer_folded,
    score,
    sums_constructions,
    visit_batches,
    visit_choice,
)
from qcpp.problem.feasible_cost import FeasibleCost, SumsGroup, VisitGroup, feasible_cost
from qcpp.problem.hamiltonian import IsingHamiltonian, ising_hamiltonian
from qcpp.problem.scenario import Scenario

__all__ = [
    "COEFFICIENT_TOLERANCE",
    "EXACT_EXPANSION_LIMIT",
    "ROTATION_T_COST",
    "PhasePlan",
    "coupling_products",
    "ft_t_count",
    "phase_plan",
    "phase_separator_gates",
    "score",
]


def phase_separator_gates(hamiltonian: IsingHamiltonian, gamma: str) -> list[Gate]:
    """RZ and RZZ gates implementing ``exp(-i gamma (C - c0))``.

    Args:
        hamiltonian: The Ising Hamiltonian (variable ``i`` on qubit ``i``).
        gamma: Name of the layer's symbol, e.g. ``"gamma_0"``.

    Returns:
        The gate list (linear terms first).
    """
    tol = COEFFICIENT_TOLERANCE
    out = [rz(Angle.symbol(gamma, 2.0 * hi), i) for i, hi in hamiltonian.linear_terms(tol)]
    return out + [rzz(Angle.symbol(gamma, 2.0 * jij), i, j) for i, j, jij in hamiltonian.quadratic_terms(tol)]


# ----------------------------------------------------------------------------- plans

Representation = Phase


def _summary(cost: Cost, logical: Cost, ancillas: int | None = None) -> dict[str, int]:
    out = {"cx": cost.cx, "rotations": cost.rotations, "t_ft": ft_t_count(logical)}
    if ancillas is not None:
        out["ancillas"] = ancillas
    return out


def _visit_products(grp: VisitGroup) -> dict[tuple[int, int], float]:
    """``y_a y_b = (sum E_a)(sum E_b) / 4`` as products of edge bits."""
    q = grp.coefficient / 4
    out: dict[tuple[int, int], float] = {}
    for i, a in enumerate(grp.visitors):
        for b in grp.visitors[i + 1 :]:
            for e in a:
                for f in b:
                    key = (e, f) if e < f else (f, e)
                    out[key] = out.get(key, 0.0) + q
    return out


def _new_couplings(quad: dict[tuple[int, int], float], extra: dict[tuple[int, int], float]) -> int:
    """How many couplings adding ``extra`` to ``quad`` creates (net of those it cancels)."""
    tol = COEFFICIENT_TOLERANCE
    delta = 0
    for k, v in extra.items():
        old = quad.get(k, 0.0)
        delta += (abs(old + v) > tol) - (abs(old) > tol)
    return max(delta, 0)


@dataclass(frozen=True, eq=False)
class PhasePlan:
    """The phase separator of one scenario: which construction implements which term group.

    Build it with :func:`phase_plan`. On every feasible assignment ``x`` (every bit string for ``whole-space``)
    the gadgets, in order, apply ``exp(-i gamma (C(x) - reference_constant))`` and return every ancilla to
    |0> (on every input).

    Attributes:
        num_ancillas: Clean ancillas the gadgets need (reused by each gadget in turn).
        reference_constant: ``K`` above.
        representation, target, optimize: As requested.
    """

    num_ancillas: int
    reference_constant: float
    representation: Representation
    target: Target
    optimize: Optimize
    num_variables: int
    _data_linear: tuple[tuple[int, float], ...]
    _data_couplings: tuple[tuple[int, int, float], ...]
    _hamming: tuple[tuple[float, tuple[int, ...]], ...]
    _visits: tuple[tuple[VisitGroup, bool], ...]
    _sums: tuple[tuple[SumsGroup, str], ...]
    _explain: tuple[dict, ...]
    _visit_batches: tuple[tuple[VisitGroup, ...], ...] = ()

    def gadgets(self, gamma: str) -> tuple[Gadget, ...]:
        """The gadgets, each meant for its own section.

        Args:
            gamma: The layer's symbol name (e.g. ``"gamma_0"``).

        Returns:
            The gadgets in application order; run them consecutively, each in its own section. Every gadget but
            those of a balance term in the ``registers`` or ``accumulator`` variant is diagonal and returns its
            ancillas to |0> on every input; those variants are runs (``SumsRegister..., phase,
            SumsRegister...`` or ``SumsAccumulate..., phase, SumsAccumulate(subtract)...``) whose register
            ancillas hold the path lengths between their own gadgets and are |0> again after the run.
        """
        n = self.num_variables
        anc = tuple(range(n, n + self.num_ancillas))  # variable i on qubit i, the clean ancillas right after
        out: list[Gadget] = []
        if self._data_linear or self._data_couplings:
            out.append(
                IsingPhase(
                    gamma,
                    self._data_linear,
                    self._data_couplings,
                )
            )
        for coeff, qs in self._hamming:
            out.append(SumsPhase(gamma, (tuple((q, 1) for q in qs),), ((0.0,),), (coeff,), anc))
        # each node's visit bits go to the next ancillas of the pool (round robin): gadgets of different nodes
        # then share no qubit and can run side by side when the pool is larger than one gadget's need
        start = 0
        for grp, products in self._visits:
            need = visit_ancillas(tuple(len(v) for v in grp.visitors), products)
            if start + need > len(anc):
                start = 0
            window = anc[start : start + need]
            start += need
            out.append(VisitPhase(gamma, grp.coefficient, grp.visitors, window, products))
        out += [_batch_gadget(gamma, batch, anc) for batch in self._visit_batches]
        for grp, variant in self._sums:
            forms = tuple(tuple((q, int(w)) for q, w in f) for f in grp.forms)
            if variant == "registers":
                out.extend(_register_gadgets(gamma, forms, grp.matrix, anc))
            elif variant == "accumulator":
                out.extend(_accumulator_gadgets(gamma, forms, grp.matrix, anc)[0])
            else:
                out.append(SumsPhase(gamma, forms, grp.matrix, (0.0,) * len(forms), anc))
        return tuple(out)

    def score(self) -> tuple[int, ...]:
        """The plan's sort key under its target (:func:`~qcpp.plan.phase_choice.plan_score` of its gadgets): what
        :func:`phase_plan` compares candidate plans by. Not a count: the counts qcpp reports are the call graph's
        (:meth:`qcpp.plan.qaoa.QaoaPlan.call_graph`, which lists these gadgets' kinds)."""
        return plan_score(((g, 1) for g in self.gadgets("gamma")), self.target)

    def explain(self) -> list[dict]:
        """Per term group: ``group``, chosen ``construction``, its ``cost`` (``cx``, ``rotations``, ``t_ft``),
        ``alternatives`` (construction -> the same figures) and ``count`` (groups of that kind); the balance
        rows also give each construction's ``ancillas``."""
        return copy.deepcopy(list(self._explain))


def phase_plan(
    scenario: Scenario,
    *,
    target: Target = "nisq",
    representation: Representation = "feasible",
    optimize: Optimize = "cx",
    ancilla_budget: int | None = None,
    pooled: bool = True,
) -> PhasePlan:
    """Choose the phase separator's constructions for a scenario.

    Args:
        target: ``nisq`` (minimise CX) or ``ft`` (minimise T, rotations priced at :data:`ROTATION_T_COST`).
        representation: ``feasible`` (exact on feasible assignments, cheap) or ``whole-space`` (the exact Ising
            Hamiltonian's RZ/RZZ circuit).
        optimize: ``cx`` (cheapest under the target) or ``depth`` (couplings only: shallow RZZ layers, no
            arithmetic).
        ancilla_budget: Most clean ancillas the plan may use (``None``: no limit). Constructions that need more
            are not considered; the balance term then tries its ``registers`` variant (one tree at a time, the
            sums copied into small registers: about twice the arithmetic's CX), then its ``accumulator``
            variant (chunks added into ``B``-bit registers: ``O(robots log e)`` ancillas), then couplings.
        pooled: The pooled layout: constructions may gather terms from anywhere on the grid (where
            :mod:`qcpp.plan.phase_choice` takes them, the ``ft`` target): the balance's arithmetic on each
            balanced pair's difference ``G_a - G_b`` as one form
            (:meth:`~qcpp.problem.feasible_cost.SumsGroup.folded`: one register per pair, one pair's ancillas at a
            time), and the node visits' pair products phased in Hamming-weight batches
            (:class:`~qcpp.gadgets.visit_batch.VisitBatch`). ``False`` keeps each term on its own edges: a form
            per robot and a gadget per node, which the ``spatial`` and ``medial`` layouts place
            (:mod:`qcpp.plan.phase_layout`).

    Raises:
        ValueError: for an unknown option.
    """
    if target not in TARGETS:
        raise ValueError(f"unknown target {target!r}; expected one of {', '.join(TARGETS)}")
    if representation not in ("feasible", "whole-space"):
        raise ValueError(f"unknown representation {representation!r}; expected feasible or whole-space")
    if optimize not in ("cx", "depth"):
        raise ValueError(f"unknown optimize {optimize!r}; expected cx or depth")
    if ancilla_budget is not None and (not isinstance(ancilla_budget, int) or ancilla_budget < 0):
        raise ValueError(f"ancilla_budget must be a non-negative integer or None, got {ancilla_budget!r}")
    if representation == "whole-space":
        return _whole_space_plan(scenario, target, optimize)
    return _feasible_plan(scenario, target, optimize, ancilla_budget, pooled)


def _register_gadgets(
    gamma: str, forms: tuple[tuple[tuple[int, int], ...], ...], matrix: tuple[tuple[float, ...], ...],
    anc: tuple[int, ...],
) -> list[Gadget]:
    """The register variant of a sums group: copy each sum into a register (one tree at a time), phase the
    registers, clear them again (the same gadgets in reverse order)."""
    whole = SumsPhase(gamma, forms, matrix, (0.0,) * len(forms))
    regs: list[SumsRegister] = []
    registers: list[list[int | None]] = []
    nxt = 0
    active = [f for f, on in zip(forms, whole._active) if on]
    widths = [SumsRegister(f, ()).width for f in active]
    pool = anc[sum(widths) :]
    for f, on in zip(forms, whole._active):
        if not on:
            registers.append([])
            continue
        present = SumsRegister(f, ())._count[3]
        row: list[int | None] = []
        qubits = []
        for p in present:
            if p:
                row.append(anc[nxt])
                qubits.append(anc[nxt])
                nxt += 1
            else:
                row.append(None)
        registers.append(row)
        regs.append(SumsRegister(f, tuple(qubits), pool))
    _, phase = whole.phase(registers)
    return [*regs, phase, *reversed(regs)]


def _accumulator_layout(
    forms: tuple[tuple[tuple[int, int], ...], ...], active: tuple[bool, ...]
) -> tuple[list[tuple[int, list[tuple[tuple[int, int], ...]]]], int]:
    """Per active form ``(B, chunks)`` (``B`` accumulator bits, chunks of ``4 B`` terms, at least 8) and the
    ancillas the accumulator variant needs (registers + the largest chunk's tree and carries)."""
    out = []
    regs = work = 0
    for f, on in zip(forms, active):
        if not on:
            continue
        width = max(1, sum(abs(w) for _, w in f).bit_length())
        size = max(8, 4 * width)
        chunks = [f[i : i + size] for i in range(0, len(f), size)]
        out.append((width, chunks))
        regs += width
        for ch in chunks:
            work = max(work, SumsAccumulate(ch, tuple(range(width))).num_ancillas)
    return out, regs + work


def _accumulator_gadgets(
    gamma: str, forms: tuple[tuple[tuple[int, int], ...], ...], matrix: tuple[tuple[float, ...], ...],
    anc: tuple[int, ...],
) -> tuple[list[Gadget], float]:
    """The accumulator variant of a sums group: each form's chunks added into a ``B``-bit register (tree per
    chunk, ripple-carry adder), the registers phased, the chunks subtracted again. Returns the gadgets and the
    constant ``c0`` of the register phase."""
    whole = SumsPhase(gamma, forms, matrix, (0.0,) * len(forms))
    layout, _ = _accumulator_layout(forms, whole._active)
    nregs = sum(width for width, _ in layout)
    pool = anc[nregs:]
    nxt = 0
    adds: list[SumsAccumulate] = []
    registers: list[list[int | None]] = []
    it = iter(layout)
    for on in whole._active:
        if not on:
            registers.append([])
            continue
        width, chunks = next(it)
        acc = anc[nxt : nxt + width]
        nxt += width
        registers.append(list(acc))
        adds += [SumsAccumulate(ch, acc, pool) for ch in chunks]
    c0, phase = whole.phase(registers)
    subs = [SumsAccumulate(g.chunk, g.accumulator, g.ancillas, subtract=True) for g in reversed(adds)]
    return [*adds, phase, *subs], c0


def _register_ancillas(forms: tuple[tuple[tuple[int, int], ...], ...], active: tuple[bool, ...]) -> int:
    trees = [SumsRegister(f, ()) for f, on in zip(forms, active) if on]
    return sum(t.width for t in trees) + max((t.num_ancillas for t in trees), default=0)


def _whole_space_plan(scenario: Scenario, target: Target, optimize: Optimize) -> PhasePlan:
    ham = ising_hamiltonian(scenario)
    tol = COEFFICIENT_TOLERANCE
    lin = tuple(ham.linear_terms(tol))
    quad = tuple(ham.quadratic_terms(tol))
    g = IsingPhase("gamma", lin, quad)
    row = {"group": "whole-space Ising", "construction": "couplings", "count": 1,
           "cost": _summary(g.cost(), g.logical_cost()), "alternatives": {}}  # fmt: skip
    return PhasePlan(0, ham.c0, "whole-space", target, optimize, scenario.num_variables, lin, quad, (), (), (), (row,))


def _feasible_plan(
    scenario: Scenario, target: Target, optimize: Optimize, budget: int | None, pooled: bool
) -> PhasePlan:
    """Choose the balance construction by building the whole plan for each candidate (the couplings of the
    balance and of the node visits overlap, so the groups are not independent), the rest greedily."""
    fc = feasible_cost(scenario)
    balance: list[dict] = []
    for grp in fc.sums:
        balance.append(_sums_options(grp, fc.num_variables, target, optimize, budget, pooled))
    # candidates: every combination is too many in general; there is one balance group at most
    choices: list[tuple[str, ...]] = [()]
    for opts in balance:
        choices = [(*c, k) for c in choices for k in opts["options"]]
    if len(choices) == 1:
        return _assemble(fc, target, optimize, budget, balance, choices[0], pooled)
    best: PhasePlan | None = None
    best_key: tuple[int, ...] | None = None
    for choice in choices:
        if best_key is not None and _couplings_floor(fc, choice, target) > best_key[0]:
            continue  # it cannot win (its floor is above a score already met): not worth assembling
        plan = _assemble(fc, target, optimize, budget, balance, choice, pooled)
        key = plan.score()
        if best_key is None or key < best_key:
            best, best_key = plan, key
    assert best is not None
    return best


def _couplings_floor(fc: FeasibleCost, choice: tuple[str, ...], target: Target) -> int:
    """A lower bound on the first entry of the score of the plan that makes ``choice`` (one construction per
    balance group): :func:`~qcpp.plan.phase_choice.couplings_floor` of each group expanded into couplings whose
    own products stay above the coefficient tolerance, else 0."""
    floor = 0
    for grp, pick in zip(fc.sums, choice, strict=True):
        if pick != "couplings":
            continue
        diagonal = [grp.matrix[a][a] for a in range(len(grp.forms))]
        # a form's own product (i, j) becomes the coupling M_aa w_i w_j / 2 (the term is met twice in the square)
        if all(abs(m) * min((w * w for _, w in f), default=1.0) / 2 > 1e3 * COEFFICIENT_TOLERANCE
               for f, m in zip(grp.forms, diagonal, strict=True) if abs(m) > 0):  # fmt: skip
            floor = max(floor, couplings_floor([len(f) for f in grp.forms], diagonal, target))
    return floor


def coupling_products(sizes: Sequence[int], matrix: Sequence[Sequence[float]]) -> int:
    """Products of two variables in ``sum_ab M_ab G_a G_b`` over forms of these sizes: the couplings its expansion
    can have (pairs within a form where ``M_aa != 0``, pairs across forms where ``M_ab != 0``).

    >>> coupling_products([3, 2], [[1.0, -1.0], [-1.0, 1.0]])
    10
    """
    n = len(sizes)
    within = sum(sizes[a] * (sizes[a] - 1) // 2 for a in range(n) if abs(matrix[a][a]) > 0)
    return within + sum(sizes[a] * sizes[b] for a in range(n) for b in range(a + 1, n) if abs(matrix[a][b]) > 0)


def _sums_options(
    grp: SumsGroup, n: int, target: Target, optimize: Optimize, budget: int | None, pooled: bool
) -> dict:
    """The constructions a sums group may use, with their own costs, ancillas and the groups each builds on: the
    group itself, or (``pooled``) its difference forms (:meth:`~qcpp.problem.feasible_cost.SumsGroup.folded`, one
    gadget or run each, one after the other) where :func:`~qcpp.plan.phase_choice.prefer_folded` says so."""
    m = grp.matrix
    prods = coupling_products([len(f) for f in grp.forms], m)
    out: dict = {"prods": prods, "costs": {}, "ancillas": {}, "options": [], "groups": {"couplings": (grp,)}}
    out["costs"]["couplings"] = (coupling_cost(prods), coupling_cost(prods))
    out["ancillas"]["couplings"] = 0
    if grp.integral and optimize == "cx":
        out["constants"] = {}
        own = _arithmetic_variants(grp, n)
        parts = grp.folded() if pooled else None

        @cache
        def pairs() -> list[dict[str, tuple[Cost, Cost, int, float]]]:  # priced only where the fold is considered
            assert parts is not None
            return [_arithmetic_variants(part, n) for part in parts]

        def folded(variant: str) -> tuple[Cost, Cost, int, float]:
            each = [p[variant] for p in pairs()]
            return (Cost.sum(e[0] for e in each), Cost.sum(e[1] for e in each), max(e[2] for e in each),
                    sum(e[3] for e in each))  # fmt: skip

        for variant in SUMS_VARIANTS:
            cost, logical, anc, const = own[variant]
            use: tuple[SumsGroup, ...] = (grp,)
            if parts and prefer_folded((cost, logical, anc), lambda v=variant: folded(v)[:3], target, budget):
                (cost, logical, anc, const), use = folded(variant), parts
            out["costs"][variant] = (cost, logical)
            out["ancillas"][variant] = anc
            out["constants"][variant] = const
            out["groups"][variant] = use
    out["options"] = list(sums_constructions(grp.integral, prods, optimize, budget, out["ancillas"].__getitem__))
    return out


def _arithmetic_variants(grp: SumsGroup, n: int) -> dict[str, tuple[Cost, Cost, int, float]]:
    """Per arithmetic variant of an integral group (:data:`~qcpp.plan.phase_choice.SUMS_VARIANTS`): lowered cost,
    logical cost, clean ancillas and the constant ``c0`` its phase leaves."""
    m = grp.matrix
    forms = tuple(tuple((q, int(w)) for q, w in f) for f in grp.forms)
    gad = SumsPhase("gamma", forms, m, (0.0,) * len(forms))
    out = {"arithmetic": (gad.cost(), gad.logical_cost(), gad.num_ancillas, gad.constant)}
    reg_anc = _register_ancillas(forms, gad._active)
    reg_gads = _register_gadgets("gamma", forms, m, tuple(range(n, n + reg_anc)))
    out["registers"] = (
        Cost.sum(g.cost() for g in reg_gads), Cost.sum(g.logical_cost() for g in reg_gads), reg_anc, gad.constant
    )
    _, acc_anc = _accumulator_layout(forms, gad._active)
    acc_gads, acc_c0 = _accumulator_gadgets("gamma", forms, m, tuple(range(n, n + acc_anc)))
    out["accumulator"] = (
        Cost.sum(g.cost() for g in acc_gads), Cost.sum(g.logical_cost() for g in acc_gads), acc_anc, acc_c0
    )
    return out


def _assemble(
    fc: FeasibleCost,
    target: Target,
    optimize: Optimize,
    budget: int | None,
    balance: list[dict],
    choice: tuple[str, ...],
    pooled: bool = True,
) -> PhasePlan:
    n = fc.num_variables
    lin: dict[int, float] = dict(fc.linear)
    quad: dict[tuple[int, int], float] = {}
    rows: list[dict] = []
    ancillas = 0
    const = fc.constant

    # squared sums (balance) first: their couplings, when chosen, make most visit couplings free
    chosen_sums: list[tuple[SumsGroup, str]] = []
    for grp, opts, pick in zip(fc.sums, balance, choice):
        costs = dict(opts["costs"])
        if pick == "couplings":
            el, eq = grp.expanded()
            new = _new_couplings(quad, eq)
            costs["couplings"] = (coupling_cost(new), coupling_cost(new))
            for i, v in el.items():
                lin[i] = lin.get(i, 0.0) + v
            for k, v in eq.items():
                quad[k] = quad.get(k, 0.0) + v
        else:
            chosen_sums += [(part, pick) for part in opts["groups"][pick]]
            const += opts["constants"][pick]
            ancillas = max(ancillas, opts["ancillas"][pick])
        note = "" if grp.integral else " (non-integer lengths: couplings only)"
        if opts["groups"][pick] != (grp,):
            note = " (folded: one form per balanced pair)"
        alternatives = {k: _summary(*c, opts["ancillas"][k]) for k, c in costs.items() if k != pick}
        rows.append({"group": grp.name + note, "count": 1, "construction": pick,
                     "cost": _summary(*costs[pick], opts["ancillas"][pick]), "alternatives": alternatives})  # fmt: skip
    # node visits
    chosen_visits: list[tuple[VisitGroup, bool]] = []
    names = ("visit bits", "visit pairs", "couplings")
    v_rows = dict.fromkeys(names, 0)
    alt_costs: dict[str, tuple[list[Cost], list[Cost]]] = {k: ([], []) for k in names}  # summed once, below
    chosen_costs: tuple[list[Cost], list[Cost]] = ([], [])
    for grp in fc.visits:
        sizes = tuple(len(v) for v in grp.visitors)
        products: dict[tuple[int, int], float] | None = None
        if quad:
            products = _visit_products(grp)
            new = _new_couplings(quad, products)
        else:  # within one node every product pairs two different robots' edges: all distinct
            new = sum(a * b for i, a in enumerate(sizes) for b in sizes[i + 1 :])
        choice = visit_choice(sizes, grp.coefficient, new, target, optimize, budget)
        for name, (c, log) in choice.costs.items():
            alt_costs[name][0].append(c)
            alt_costs[name][1].append(log)
        v_rows[choice.construction] += 1
        chosen_costs[0].append(choice.costs[choice.construction][0])
        chosen_costs[1].append(choice.costs[choice.construction][1])
        if choice.gadget is not None:
            chosen_visits.append((grp, choice.gadget.products))
            if not (choice.gadget.products and target == "ft"):  # those wait for the batches (their constant too)
                const += VisitPhase("gamma", grp.coefficient, grp.visitors, (), choice.gadget.products).constant
            ancillas = max(ancillas, choice.ancillas)
        else:
            for key, v in (products if products is not None else _visit_products(grp)).items():
                quad[key] = quad.get(key, 0.0) + v
    visits_row = len(rows)
    # ft: equal-angle rotations of qubits without couplings merged by Hamming-weight phasing
    hamming: list[tuple[float, tuple[int, ...]]] = []
    if target == "ft" and optimize == "cx":
        coupled = {q for k in quad for q in k}
        uncoupled = [(q, v) for q, v in sorted(lin.items()) if q not in coupled]
        hw_cost, hw_log, plain = Cost(), Cost(), 0
        for hw, qs in hamming_groups(uncoupled, target, optimize, budget):
            hamming.append((lin[qs[0]], tuple(qs)))
            const += hw.constant
            for q in qs:
                del lin[q]
            ancillas = max(ancillas, hw.num_ancillas)
            hw_cost += hw.cost()
            hw_log += hw.logical_cost()
            plain += len(qs)
        if hamming:
            rows.append({"group": "equal-angle rotations", "count": len(hamming),
                         "construction": "hamming-weight phasing", "cost": _summary(hw_cost, hw_log),
                         "alternatives": {"rotations": _summary(Cost.of(rz=plain), Cost.of(rz=plain))}})  # fmt: skip
    # ft: nodes of equal kind phased in Hamming-weight batches, in the ancillas the plan holds anyway
    batches: list[tuple[VisitGroup, ...]] = []
    if pooled:
        batches, chosen_visits = _visit_batches(chosen_visits, ancillas, target, optimize, budget)
    batched = {id(grp) for batch in batches for grp in batch}
    for grp, products in chosen_visits:
        if products and target == "ft":
            const += VisitPhase("gamma", grp.coefficient, grp.visitors, (), products).constant
    for batch in batches:
        gad = _batch_gadget("gamma", batch, ())
        const += gad.constant
        chosen_costs[0].append(gad.cost())
        chosen_costs[1].append(gad.logical_cost())
    if batched:  # their nodes' own costs give way to the batches'
        keep = [id(grp) not in batched for grp in fc.visits] + [True] * len(batches)
        for costs in chosen_costs:
            costs[:] = [c for c, k in zip(costs, keep, strict=True) if k]
    if fc.visits:
        used = [k for k, r in v_rows.items() if r]
        note = f"; {len(batched)} in {len(batches)} hamming-weight batches" if batches else ""
        rows.insert(visits_row, {
            "group": "node visits", "count": len(fc.visits), "cost": _summary(*map(Cost.sum, chosen_costs)),
            "construction": " + ".join(f"{k} ({v_rows[k]})" for k in used) + note,
            "alternatives": {f"each by {k}": _summary(*map(Cost.sum, alt_costs[k])) for k in alt_costs},
        })  # fmt: skip
    c0, h, j = ising_form(lin, quad)
    const += c0
    data_lin = tuple(sorted(h.items()))
    data_quad = tuple(sorted((a, b, v) for (a, b), v in j.items()))
    ising = IsingPhase("gamma", data_lin, data_quad)
    rows.insert(0, {"group": "linear + couplings", "count": 1, "construction": "rz/rzz",
                    "cost": _summary(ising.cost(), ising.logical_cost()), "alternatives": {}})  # fmt: skip
    return PhasePlan(
        ancillas, const, "feasible", target, optimize, n, data_lin, data_quad,
        tuple(hamming), tuple(chosen_visits), tuple(chosen_sums), tuple(rows), tuple(batches),
    )  # fmt: skip


def _visit_batches(
    visits: list[tuple[VisitGroup, bool]], pool: int, target: Target, optimize: Optimize, budget: int | None
) -> tuple[list[tuple[VisitGroup, ...]], list[tuple[VisitGroup, bool]]]:
    """The nodes whose pair products go in Hamming-weight batches (:func:`~qcpp.plan.phase_choice.visit_batches`,
    per kind and colour of node in order of first appearance, its nodes in their order: nodes of one colour share
    no edge, so a batch's nodes run side by side) and the visit gadgets left, in their order."""
    kinds: dict[tuple[tuple[int, ...], float, int], list[VisitGroup]] = {}
    for grp, products in visits:
        if products:
            kinds.setdefault((tuple(len(v) for v in grp.visitors), grp.coefficient, grp.colour), []).append(grp)
    batches: list[tuple[VisitGroup, ...]] = []
    for (sizes, coefficient, _), grps in kinds.items():
        start = 0
        for size in visit_batches(sizes, coefficient, len(grps), pool, target, optimize, budget):
            batches.append(tuple(grps[start : start + size]))
            start += size
    batched = {id(grp) for batch in batches for grp in batch}
    return batches, [(grp, products) for grp, products in visits if id(grp) not in batched]


def _batch_gadget(gamma: str, batch: tuple[VisitGroup, ...], pool: tuple[int, ...]) -> VisitBatch:
    """A batch's gadget on the first ancillas of ``pool`` it needs (all of them if fewer)."""
    need = visit_batch_ancillas(tuple(len(v) for v in batch[0].visitors), len(batch))
    return VisitBatch(gamma, batch[0].coefficient, tuple(grp.visitors for grp in batch), pool[:need])
