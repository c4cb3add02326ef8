"""An exact solver: the coverage cost modelled for OR-Tools CP-SAT, with a proven optimum or a bound.

The model has the same feasible set and the same cost as :func:`qcpp.problem.cost.cost` (all three terms, soft
and hard obstacles, both balance modes, both degree-target modes, any weights), but is written in terms of
what feasible paths look like rather than in the edge bits alone:

* **Paths.** For each robot, a directed arc per direction of every variable edge (none into the start, none
  out of the goal), a fixed dummy arc goal -> start and, for every other node, a self-loop meaning "not
  visited"; ``AddCircuit`` then admits exactly the simple start-goal paths (one cycle through the dummy arc,
  so no detached loops). The edge variable is the sum of its two arcs.
* **Degrees from visits.** On a simple path an interior node has degree 2 and an endpoint degree 1, so the
  summed degree at node ``i`` is ``e_i + 2 k_i``: ``e_i`` the robots that start or end there, ``k_i`` the
  number of other robots that visit it. ``c3``'s term ``(e_i + 2 k_i - t_i)^2`` is a function of the integer
  ``k_i`` alone; with ``alpha2 > 0`` it enters as the epigraph of the chords between consecutive integers
  (exact at integers and the convex hull of the term, so the LP bound is tight), otherwise via a table.
* **Balance.** ``L_r - L_s`` in integer units; with ``alpha1 > 0`` its square is the epigraph of the chords
  (exact at integers), otherwise an exact product constraint.
* **Implied constraints** that strengthen the relaxation: degree equations per node and robot, ``edges =
  visited nodes - 1``, the grid's two-colouring (a path alternates colours) and the edge count's parity
  (Manhattan distance plus twice an integer).
* **Crossing cut**: two robots whose four endpoints lie on the outer boundary in interleaved order must share a
  node (planarity), which tightens the bound of the corner-to-corner placements.
* **Symmetry** (off by default, ``symmetry_breaking=True``): lex-leader constraints for the grid rotations and
  reflections that map the scenario onto itself.

CP-SAT runs with ``linearization_level = 2`` (the circuit and chord constraints fully in the LP, for a much
tighter root bound) and one worker by default (one thread, as the other solvers).

Integer objective: every weight is read as the rational of smallest denominator (at most
:data:`MAX_DENOMINATOR`) that is *exactly* the same float, and the objective is scaled by the least common
denominator; where that is impossible :func:`cpsat` raises ``ValueError`` rather than optimise a rounded
objective. The returned paths are re-scored with :func:`qcpp.problem.cost.cost_parts` like every solver's.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> res = cpsat(s, workers=1)
    >>> res.proven_optimal, res.solution.cost.total, res.bound
    (True, -8.0, -8.0)
"""

from __future__ import annotations

import math
import threading
import time
from dataclasses import dataclass
from fractions import Fraction

from ortools.sat.python import cp_model

from qcpp.problem.cost import balanced_pairs, cost_parts
from qcpp.problem.cost_range import COST_LIMIT, check_cost_range, weight_fields
from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import node_symmetries
from qcpp.problem.paths import initial_path, is_feasible, path_to_nodes
from qcpp.problem.presets import boundary_nodes
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers.result import ProgressFn, Solution
from qcpp.problem.solvers.stopping import INTERRUPTED, StopFn

MAX_DENOMINATOR = 10**6
"""Largest denominator accepted when reading a float weight as an exact rational."""

MAX_SCALE = 10**12
"""Largest common denominator of the objective (beyond it the integer objective would lose CP-SAT's precision)."""

STOP_POLL_SECONDS = 0.05
"""How often a running search asks its ``stop`` function (from a helper thread; CP-SAT itself runs in C++)."""

_EPIGRAPH_MAX_STEPS = 400
"""Most integer values of a balance difference for which its square is written as chords (else a product)."""


@dataclass(frozen=True)
class CpSatResult:
    """One CP-SAT run.

    Attributes:
        solution: The best assignment found (re-scored), as every solver returns it.
        proven_optimal: Whether CP-SAT proved it optimal.
        bound: The proven lower bound on the optimum (equal to the cost when ``proven_optimal``; ``-inf`` when
            CP-SAT stopped before finding any solution).
        status: CP-SAT's status name (``OPTIMAL``, ``FEASIBLE``, ...).
        improvements: ``(seconds, cost)`` of every improving solution CP-SAT reported, in time order.
        scale: The integer the objective was multiplied by.
    """

    solution: Solution
    proven_optimal: bool
    bound: float
    status: str
    improvements: tuple[tuple[float, float], ...]
    scale: int

    @property
    def gap(self) -> float:
        """Absolute gap ``cost - bound`` (0 when proven optimal, ``inf`` without a bound)."""
        return max(0.0, self.solution.cost.total - self.bound)

    @property
    def relative_gap(self) -> float:
        """The gap as OR-Tools measures it (its ``relative_gap_limit``): :func:`relative_gap` of cost and bound."""
        return relative_gap(self.solution.cost.total, self.bound)

    def time_to_cost(self, target: float, tol: float = 1e-9) -> float | None:
        """Seconds until the first solution of cost at most ``target + tol`` was found (``None``: never)."""
        return next((t for t, c in self.improvements if c <= target + tol), None)


def relative_gap(cost: float, bound: float) -> float:
    """``(cost - bound) / max(1, |cost|)``: the relative gap of OR-Tools (CP-SAT's ``relative_gap_limit``, whose
    ``max(1, .)`` keeps it finite at a cost of 0); 0 when proven optimal, ``inf`` without a bound.

    Example:
        >>> relative_gap(1336.0, -199.0), relative_gap(-20.0, -20.0), relative_gap(0.0, -3.0)
        (1.1489520958083832, 0.0, 3.0)
    """
    return max(0.0, cost - bound) / max(1.0, abs(cost))


def exact_rational(x: float, max_denominator: int = MAX_DENOMINATOR) -> Fraction:
    """The rational with the smallest denominator ``<= max_denominator`` whose float is exactly ``x``.

    Raises:
        ValueError: if there is none (``x`` is not a "short" decimal or fraction).

    Example:
        >>> exact_rational(0.1), exact_rational(-2.5), exact_rational(1 / 3)
        (Fraction(1, 10), Fraction(-5, 2), Fraction(1, 3))
    """
    f = Fraction(x).limit_denominator(max_denominator)
    if float(f) != x:
        raise ValueError(
            f"the weight {x!r} is no rational with a denominator up to {max_denominator}: CP-SAT needs an exact "
            "integer objective (use weights such as 0.25 or 1.3)"
        )
    return f


@dataclass
class _Model:
    """The CP-SAT model and the variables needed to read a solution back."""

    model: cp_model.CpModel
    edge_vars: list[list[cp_model.IntVar]]  # [robot][variable-edge position]
    objective_terms: list[tuple[Fraction, cp_model.LinearExprT]]
    constant: Fraction


class _Recorder(cp_model.CpSolverSolutionCallback):
    """Records ``(seconds, objective)`` of every improving solution."""

    def __init__(self, t_start: float, progress: ProgressFn | None) -> None:
        super().__init__()
        self.t_start = t_start
        self.events: list[tuple[float, float]] = []
        self.progress = progress

    def on_solution_callback(self) -> None:
        self.events.append((time.perf_counter() - self.t_start, self.ObjectiveValue()))
        if self.progress is not None:
            self.progress(len(self.events), None)


def _chords(values: list[int]) -> list[tuple[int, int]]:
    """``(slope, intercept)`` of the chords of ``j -> values[j]`` between consecutive integers."""
    return [(values[j + 1] - values[j], values[j] - (values[j + 1] - values[j]) * j) for j in range(len(values) - 1)]


Symmetry = tuple[tuple[int, ...], tuple[int, ...]]
"""``(perm, emap)``: robot ``r``'s edge ``e`` maps to robot ``perm[r]``'s edge ``emap[e]``."""


def scenario_symmetries(s: Scenario) -> list[Symmetry]:
    """The grid symmetries that map the scenario onto itself, with the robot permutation they induce.

    A map qualifies if it keeps the obstacles, every edge length, and the robots' endpoint pairs (as unordered
    pairs: a path and its reverse are the same edge set), and the induced robot permutation keeps the balanced
    pairs; the cost of every assignment is then equal to the cost of its image.

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> len(scenario_symmetries(default_scenario(4, 4, 2)))  # all 7: some swap the two robots
        7
    """
    g = s.grid
    out = []
    ends = [frozenset((rb.start, rb.goal)) for rb in s.robots]
    pairs = {frozenset(p) for p in balanced_pairs(s)}
    lengths = s.edge_lengths
    for phi in node_symmetries(g.rows, g.cols)[1:]:
        if {phi(o) for o in s.obstacles} != set(s.obstacles):
            continue
        emap = tuple(g.edge_index(phi(u), phi(v)) for u, v in g.edges)
        if any(lengths[emap[e]] != lengths[e] for e in range(g.num_edges)):
            continue
        perm = []
        for rb in s.robots:
            image = frozenset((phi(rb.start), phi(rb.goal)))
            match = [q for q, pq in enumerate(ends) if pq == image]
            if len(match) != 1:
                break
            perm.append(match[0])
        else:
            if len(set(perm)) == len(perm) and {frozenset((perm[a], perm[b])) for a, b in map(tuple, pairs)} == pairs:
                out.append((tuple(perm), emap))
    return out


def _break_symmetry(
    model: cp_model.CpModel, s: Scenario, edge_vars: list[list[cp_model.IntVar]], sym: Symmetry
) -> None:
    """Lex-leader on the first moved variable: ``x[i] >= x[sigma^-1(i)]`` for the first ``i`` (variable-index
    order) the symmetry moves. Among the images of any optimum, the lexicographically largest satisfies this
    for every symmetry at once, so adding it for all of them keeps an optimum."""
    perm, emap = sym
    pos = {e: k for k, e in enumerate(s.variable_edges)}
    inv_perm = {q: r for r, q in enumerate(perm)}
    inv_emap = {f: e for e, f in enumerate(emap)}
    for r in range(s.num_robots):
        for k, e in enumerate(s.variable_edges):
            src = (inv_perm[r], pos[inv_emap[e]])  # sigma(X)[r, e] = X[src]
            if src != (r, k):
                model.add(edge_vars[r][k] >= edge_vars[src[0]][src[1]])
                return


def _crossing_cuts(model: cp_model.CpModel, s: Scenario, visit: list[list[cp_model.IntVar | None]]) -> None:
    """Two robots whose four endpoints lie on the outer boundary in interleaved order must share a node.

    The grid is drawn in the plane inside its outer cycle; a path joining two boundary points splits the
    rectangle, so a path between points on either side must meet it, and grid paths meet only at nodes.
    """
    g = s.grid
    if g.rows < 2 or g.cols < 2:
        return
    position = {node: i for i, node in enumerate(boundary_nodes(g.rows, g.cols))}  # on the outer cycle, clockwise
    for r, q in ((a, b) for a in range(s.num_robots) for b in range(a + 1, s.num_robots)):
        ends = [s.robots[r].start, s.robots[r].goal, s.robots[q].start, s.robots[q].goal]
        pos = [position.get(n) for n in ends]
        if None in pos or len(set(ends)) < 4:
            continue
        lo, hi = sorted(pos[:2])
        if (lo < pos[2] < hi) == (lo < pos[3] < hi):
            continue  # not interleaved
        shared = []
        for i in range(g.num_nodes):
            pres = []
            for robot in (r, q):
                rb = s.robots[robot]
                if i in (g.node_index(rb.start), g.node_index(rb.goal)):
                    pres.append(None)  # always on the path
                elif visit[robot][i] is not None:
                    pres.append(visit[robot][i])
                else:
                    break
            else:
                lits = [p for p in pres if p is not None]
                both = model.new_bool_var(f"share{r}_{q}_{i}")
                for p in lits:
                    model.add_implication(both, p)
                shared.append(both)
        model.add_bool_or(shared)


def _build(scenario: Scenario, hint: tuple[int, ...] | None, symmetry_breaking: bool = False) -> _Model:
    s, g = scenario, scenario.grid
    model = cp_model.CpModel()
    a0, a1, a2 = (exact_rational(a) for a in s.objective.alpha)
    hard = s.objective.obstacles == "hard"
    usable = [not (hard and n in s.obstacle_set) for n in g.nodes]
    terms: list[tuple[Fraction, cp_model.LinearExprT]] = []
    constant = Fraction(0)

    # integer edge lengths: d_e * (common denominator) / gcd
    d_rat = [exact_rational(float(s.edge_lengths[e])) for e in s.variable_edges]
    den = math.lcm(*(d.denominator for d in d_rat)) if d_rat else 1
    d_int = [int(d * den) for d in d_rat]
    unit_div = math.gcd(*d_int) if d_int else 1
    d_int = [v // unit_div for v in d_int]
    length_unit = Fraction(unit_div, den)  # one integer length step in real length
    w_rat = [exact_rational(float(s.edge_weights[e])) for e in s.variable_edges]

    edge_vars: list[list[cp_model.IntVar]] = []
    visit: list[list[cp_model.IntVar | None]] = []  # [robot][node]; None: the robot's endpoint or unusable
    lengths = []
    hint_nodes = [path_to_nodes(g, m, rb.start) for m, rb in zip(hint, s.robots, strict=True)] if hint else None
    for r, rb in enumerate(s.robots):
        start, goal = g.node_index(rb.start), g.node_index(rb.goal)
        on_path = {g.node_index(n) for n in hint_nodes[r]} if hint_nodes else set()
        hint_arcs = set(zip((g.node_index(n) for n in hint_nodes[r]), (g.node_index(n) for n in hint_nodes[r][1:]))
                        ) if hint_nodes else set()
        vis: list[cp_model.IntVar | None] = [None] * g.num_nodes
        arcs: list[tuple[int, int, cp_model.LinearExprT]] = [(goal, start, model.new_constant(1))]
        for i in range(g.num_nodes):
            if usable[i] and i not in (start, goal):
                vis[i] = model.new_bool_var(f"v{r}_{i}")
                arcs.append((i, i, ~vis[i]))
                if hint_nodes:
                    model.add_hint(vis[i], i in on_path)
        xs = []
        incident: list[list[cp_model.IntVar]] = [[] for _ in range(g.num_nodes)]
        for e in s.variable_edges:
            u, v = g.edge_nodes[e]
            x = model.new_bool_var(f"x{r}_{e}")
            directed = []
            for a, b in ((u, v), (v, u)):
                if a == goal or b == start:
                    continue  # a start-goal path never enters its start or leaves its goal
                lit = model.new_bool_var(f"a{r}_{a}_{b}")
                arcs.append((a, b, lit))
                directed.append(lit)
                if hint_nodes:
                    model.add_hint(lit, (a, b) in hint_arcs)
            model.add(x == sum(directed))
            if hint:
                model.add_hint(x, (hint[r] >> e) & 1)
            xs.append(x)
            incident[u].append(x)
            incident[v].append(x)
        # AddCircuit wants consecutive node numbers: renumber the usable nodes
        number = {i: n for n, i in enumerate(i for i in range(g.num_nodes) if usable[i])}
        model.add_circuit([(number[a], number[b], lit) for a, b, lit in arcs])
        # implied constraints (redundant for the integer model, tightening its relaxation)
        for i in range(g.num_nodes):
            if not usable[i]:
                continue
            model.add(sum(incident[i]) == (1 if i in (start, goal) else 2 * vis[i]))
        interior = [(i, v) for i, v in enumerate(vis) if v is not None]
        model.add(sum(xs) == 1 + sum(v for _, v in interior))
        colour = [sum(n) % 2 for n in g.nodes]
        c_s, c_g = colour[start], colour[goal]
        # a path alternates colours: over all its nodes, (start's colour) - (other colour) is 1 if both ends
        # share a colour, else 0; the ends themselves contribute 2 or 0, so the interior nodes -1 or 0
        signed = sum((1 if colour[i] == c_s else -1) * v for i, v in interior)
        model.add(signed == (-1 if c_s == c_g else 0))
        # the number of edges has the parity of the Manhattan distance, as an explicit integer (branchable)
        manhattan = abs(rb.start[0] - rb.goal[0]) + abs(rb.start[1] - rb.goal[1])
        half = model.new_int_var(0, len(xs) // 2, f"half{r}")
        model.add(sum(xs) == manhattan + 2 * half)
        edge_vars.append(xs)
        visit.append(vis)
        lengths.append(sum(dk * x for dk, x in zip(d_int, xs, strict=True)))
        # c1
        for wk, x in zip(w_rat, xs, strict=True):
            terms.append((a0 * wk, x))

    _crossing_cuts(model, s, visit)
    if symmetry_breaking:
        for sym in scenario_symmetries(s):
            _break_symmetry(model, s, edge_vars, sym)

    # c2: (L_r - L_s)^2 for the balanced pairs
    max_len = sum(d_int)
    if a1 != 0:
        for r, q in balanced_pairs(s):
            diff = model.new_int_var(-max_len, max_len, f"diff{r}_{q}")
            model.add(diff == lengths[r] - lengths[q])
            sq = model.new_int_var(0, max_len * max_len, f"sq{r}_{q}")
            if a1 > 0 and max_len <= _EPIGRAPH_MAX_STEPS:
                # chords of z^2 between consecutive integers, both signs: exact at integers when minimised
                for j in range(max_len):
                    slope, icept = 2 * j + 1, -j * (j + 1)
                    model.add(sq >= slope * diff + icept)
                    model.add(sq >= -slope * diff + icept)
            else:
                model.add_multiplication_equality(sq, [diff, diff])
            terms.append((a1 * length_unit * length_unit, sq))

    # c3: per node, a function of how many robots pass through
    targets = s.degree_targets
    for i in range(g.num_nodes):
        t_i = targets[i]
        if math.isnan(t_i) or a2 == 0:
            continue
        ends = sum((g.node_index(rb.start) == i) + (g.node_index(rb.goal) == i) for rb in s.robots)
        through = [visit[r][i] for r in range(s.num_robots) if visit[r][i] is not None]
        f = [int((ends + 2 * k - int(t_i)) ** 2) for k in range(len(through) + 1)]
        if len(through) == 0:
            constant += a2 * f[0]
        elif len(through) == 1:
            constant += a2 * f[0]
            terms.append((a2 * (f[1] - f[0]), through[0]))
        else:
            k_i = sum(through)
            q_i = model.new_int_var(min(f), max(f), f"deg{i}")
            if a2 > 0:
                for slope, icept in _chords(f):
                    model.add(q_i >= slope * k_i + icept)
            else:
                k_var = model.new_int_var(0, len(through), f"k{i}")
                model.add(k_var == k_i)
                model.add_element(k_var, f, q_i)
            terms.append((a2, q_i))
    return _Model(model, edge_vars, terms, constant)


def cpsat(
    scenario: Scenario,
    *,
    time_limit: float | None = None,
    workers: int = 1,
    seed: int = 0,
    linearization: int = 2,
    symmetry_breaking: bool = False,
    progress: ProgressFn | None = None,
    stop: StopFn | None = None,
) -> CpSatResult:
    """Minimise the cost with CP-SAT (see the module docstring for the model).

    Args:
        time_limit: Wall-clock limit in seconds (``None``: run until the optimum is proven).
        workers: CP-SAT search workers (threads). One (the default) is deterministic: the same seed gives the
            same answer and proof on every run; more search in parallel and may answer differently run to run.
        seed: CP-SAT's random seed.
        linearization: CP-SAT's ``linearization_level`` (0-2).
        symmetry_breaking: Add lex-leader constraints for the grid symmetries that map the scenario onto
            itself (:func:`scenario_symmetries`). Off by default: it slows the proofs down.
        progress: Called as ``progress(solutions found, None)`` at every improving solution (how many
            there will be is not known).
        stop: A caller's stop request (the command line's Ctrl-C), asked every :data:`STOP_POLL_SECONDS` from a
            helper thread while CP-SAT searches; once it returns ``True`` the search ends as at a time limit and
            the result's ``solution.stopped`` is ``"interrupted"`` (unless CP-SAT had proven the optimum). With
            ``stop`` CP-SAT does not catch SIGINT itself, so the caller's handler sees it. ``True`` before the
            search starts: no search, the initial paths.

    Returns:
        A :class:`CpSatResult`; its ``solution.paths`` are the best paths found (the initial paths if CP-SAT
        found none within the limit, which a note then says).

    Raises:
        ValueError: if ``time_limit`` or ``workers`` is not positive.
        ScenarioError: naming the field, if the weights cannot be scaled exactly to integers within CP-SAT's
            range (see the module docstring and :mod:`qcpp.problem.cost_range`).
    """
    if time_limit is not None and not time_limit > 0:
        raise ValueError(f"time_limit must be positive, got {time_limit}")
    if workers < 1:
        raise ValueError(f"workers must be positive, got {workers}")
    t_start = time.perf_counter()
    check_cost_range(scenario)
    for f in weight_fields(scenario):
        try:
            exact_rational(f.value)
        except ValueError as exc:
            raise ScenarioError(f.name, f"{exc} (--method cpsat)") from None
    hint = tuple(initial_path(scenario, r) for r in range(scenario.num_robots))
    m = _build(scenario, hint, symmetry_breaking)
    coefs = [c for c, _ in m.objective_terms] + [m.constant]
    scale = math.lcm(*(c.denominator for c in coefs))
    if scale > MAX_SCALE:
        raise ScenarioError(
            "objective",
            f"the weights need a common denominator of {scale} (more than {MAX_SCALE}) to be integers for CP-SAT "
            "(--method cpsat; the other methods take them)",
        )
    # the integer objective must stay within CP-SAT's exact range: the same bound, in units of 1/scale
    check_cost_range(scenario, limit=COST_LIMIT / scale, solver=f"cpsat (objective scaled by {scale} to integers)")
    int_terms = [(int(c * scale), v) for c, v in m.objective_terms if c != 0]
    offset = int(m.constant * scale)
    m.model.minimize(sum(c * v for c, v in int_terms) + offset)
    recorder = _Recorder(t_start, progress)
    solver = cp_model.CpSolver()
    if stop is not None:
        solver.parameters.catch_sigint_signal = False  # the caller handles the signal and asks through stop
    solver.parameters.num_workers = workers
    # OR-Tools' own search log stays off (it would print straight to stdout): our notes say what matters
    solver.parameters.log_search_progress = False
    solver.parameters.log_to_stdout = False
    solver.parameters.random_seed = seed
    # level 2 linearises the circuit and product constraints fully: the LP bound for two robots on 6x6 moves
    # from -64 to -34 (optimum -28)
    solver.parameters.linearization_level = linearization
    if time_limit is not None:
        solver.parameters.max_time_in_seconds = max(0.0, time_limit - (time.perf_counter() - t_start))
    asked = stop is not None and stop()
    status = cp_model.UNKNOWN if asked else _solve_until_stopped(solver, m.model, recorder, stop)
    asked = asked or (stop is not None and stop())
    status_name = solver.status_name(status)
    if status in (cp_model.MODEL_INVALID, cp_model.INFEASIBLE):
        # validate() can be the whole model (100+ lines): its first line names the problem
        why = (m.model.validate().strip().splitlines() or [""])[0][:200]
        raise RuntimeError(f"CP-SAT: {status_name} ({why}); the model is wrong for this scenario")
    notes = [f"CP-SAT {status_name}, {workers} worker(s), objective scaled by {scale}"]
    if status in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        paths = tuple(
            sum(1 << e for e, x in zip(scenario.variable_edges, xs, strict=True) if solver.boolean_value(x))
            for xs in m.edge_vars
        )
        model_value = solver.objective_value / scale
    else:
        paths, model_value = hint, math.inf
        why = "before the search was interrupted" if asked else "within the time limit"
        notes.append(f"no solution found {why}: returning the initial paths")
    for r, p in enumerate(paths):
        if not is_feasible(scenario, r, p):
            raise RuntimeError(f"CP-SAT returned an infeasible path for robot {r}; the model is wrong")
    parts = cost_parts(scenario, paths)
    tol = 1e-6 * max(1.0, abs(parts.total))
    if parts.total > model_value + tol or (status == cp_model.OPTIMAL and abs(parts.total - model_value) > tol):
        raise RuntimeError(f"CP-SAT objective {model_value} disagrees with the cost {parts.total}; the model is wrong")
    proven = status == cp_model.OPTIMAL
    if proven:
        bound = parts.total
    elif status == cp_model.FEASIBLE:
        bound = min(parts.total, solver.best_objective_bound / scale)
    else:  # stopped before any solution: the response's bound is not reliable (0 before the search starts)
        bound = -math.inf
    seconds = time.perf_counter() - t_start
    improvements = tuple((t, v / scale) for t, v in recorder.events)
    sol = Solution(
        method="cpsat",
        paths=paths,
        cost=parts,
        seconds=seconds,
        evaluated=len(improvements),
        trace=tuple(v for _, v in improvements),
        seed=seed,
        notes=(*notes, f"bound {bound:g}, gap {max(0.0, parts.total - bound):g}"),
        details=_details(proven, bound, parts.total, status_name),
        stopped=INTERRUPTED if asked and not proven else None,
    )
    return CpSatResult(sol, proven, bound, status_name, improvements, scale)


def _details(proven: bool, bound: float, cost: float, status: str) -> tuple[tuple[str, object], ...]:
    """The JSON fields of a CP-SAT answer (``Solution.details``): JSON has no infinity, so no bound is ``null``.
    ``gap`` is ``cost - bound``, ``relative_gap`` :func:`relative_gap`."""
    known = math.isfinite(bound)
    gap = max(0.0, cost - bound)
    return (("proven_optimal", proven), ("bound", bound if known else None), ("gap", gap if known else None),
            ("relative_gap", relative_gap(cost, bound) if known else None), ("status", status))


def _solve_until_stopped(
    solver: cp_model.CpSolver, model: cp_model.CpModel, recorder: _Recorder, stop: StopFn | None
) -> int:
    """``solver.solve(model, recorder)``; with ``stop``, a helper thread asks it every :data:`STOP_POLL_SECONDS`
    and ends the search (``stop_search``, as a time limit would) once it answers ``True``. The thread keeps asking
    until the solve returns, so a request that comes while CP-SAT is still starting up is not lost."""
    if stop is None:
        return solver.solve(model, recorder)
    done = threading.Event()

    def watch() -> None:
        while not done.wait(STOP_POLL_SECONDS):
            if stop():
                solver.stop_search()

    watcher = threading.Thread(target=watch, name="qcpp-cpsat-stop", daemon=True)
    watcher.start()
    try:
        return solver.solve(model, recorder)
    finally:
        done.set()
        watcher.join()
