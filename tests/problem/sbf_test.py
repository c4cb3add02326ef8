"""SBF logic, exhaustively: every simple path of every start/goal pair on small grids, every plaquette.

The sweep covers all unordered start/goal pairs on 2x2, 2x3, 3x3, 3x4 and 4x4 and the two kinds of
corner-to-corner pairs on 5x5 (diagonal corners and corners on one side; the other corner pairs are mirror
images). Unordered pairs suffice: a path is an undirected edge set, so (s, g) and (g, s) have the same
feasible paths, and both rules read the endpoints only as a set -- ``test_rules_ignore_the_direction``
checks this for every pair instead of assuming it.

For speed each compiled :class:`~qcpp.problem.sbf.SbfLogic` program is run once per plaquette on a numpy bit
matrix of all paths (``run_program``; checked against ``SbfLogic.evaluate``). Whether a flip is feasible is
looked up in the set of enumerated paths (``enumerate_paths`` equals networkx's simple paths, see
paths_test).

Claims checked here and quoted in docs/paper-notes.md:

* ``exact`` is sound (never allows a flip that leaves the feasible set) and complete except for the
  two-opposite-edges pattern; the feasible flips it misses are all of that pattern;
* ``exact``'s compiled network equals its specification :func:`~qcpp.problem.sbf.exact_rule_value`;
* ``paper`` is unsound exactly when one of the robot's endpoints is a corner without plaquette edges (the
  flip gives it two more edges); it misses every feasible opposite-edges flip;
* no local rule can be exact on the opposite-edges pattern: two paths with identical neighbourhoods, one
  flip feasible and one not (the smallest such pair is drawn in the notes);
* uncompute symmetry: an allowed flip x -> y is allowed back and leaves every temporary unchanged -- on
  feasible paths for both rules, but not for ``paper`` on the infeasible states its leaks reach.
"""

from __future__ import annotations

import functools
import itertools
import random
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import Grid, Node, Plaquette
from qcpp.problem.paths import enumerate_paths, is_feasible
from qcpp.problem.sbf import (
    RULES,
    SbfLogic,
    allowed_moves,
    apply_sbf,
    direct_exact_logic,
    exact_rule_value,
    reachable_paths,
    sbf_logic,
)
from qcpp.problem.scenario import Scenario, scenario_from_dict

NOTES = Path(__file__).resolve().parents[2] / "docs" / "paper-notes.md"

FULL_GRIDS = [(2, 2), (2, 3), (3, 3), (3, 4), (4, 4)]
FIVE = [((0, 0), (4, 4)), ((0, 0), (0, 4))]
CORNER_EDGES = ((0, 3), (0, 1), (1, 2), (2, 3))  # corner a, b, c, d -> positions of its edges in (ab, bc, cd, da)


def scenario(rows: int, cols: int, start: Node, goal: Node, obstacles: tuple[Node, ...] = (), mode: str = "soft"):
    return scenario_from_dict(
        {
            "grid": {"rows": rows, "cols": cols, "obstacles": [list(o) for o in obstacles]},
            "robots": [{"start": list(start), "goal": list(goal)}],
            "objective": {"obstacles": mode},
        }
    )


def pairs_of(rows: int, cols: int) -> list[tuple[Node, Node]]:
    if (rows, cols) == (5, 5):
        return FIVE
    return list(itertools.combinations(Grid(rows, cols).nodes, 2))


def run_program(logic: SbfLogic, bits: np.ndarray) -> np.ndarray:
    """Run the straight-line program on many inputs at once: ``bits`` (N, edges) bool -> temps (N, T) bool."""
    temps = np.zeros((len(bits), logic.num_temps), dtype=bool)
    for step in logic.steps:
        cond = np.ones(len(bits), dtype=bool)
        for lit in step.literals:
            col = temps[:, lit.temp] if lit.is_temp else bits[:, lit.signal]
            if lit.xor is not None:
                col = col ^ bits[:, lit.xor]
            cond &= col == lit.value
        temps[:, step.target] ^= cond
    return temps


def bit_matrix(masks: np.ndarray, num_edges: int) -> np.ndarray:
    return ((masks[:, None] >> np.arange(num_edges, dtype=np.int64)) & 1).astype(bool)


@dataclass(frozen=True)
class Case:
    """One (scenario, plaquette) of the sweep; arrays run over the scenario's feasible paths ``x``."""

    scenario: Scenario
    plaquette: Plaquette
    masks: np.ndarray  # x (int64 edge masks)
    feasible: np.ndarray  # the flipped path y = x ^ plaquette is feasible
    opposite: np.ndarray  # x has exactly two opposite plaquette edges
    pattern_full: np.ndarray  # x has all four plaquette edges
    endpoint_q0: np.ndarray  # some corner is the robot's start or goal and has no plaquette edge in x
    allowed: dict[str, np.ndarray]
    spec: np.ndarray  # exact_rule_value on x's local configuration
    symmetric: dict[str, np.ndarray]  # allowed -> (allowed on y and every temp equal on x and y)
    diagonal: bool


def spec_values(pb: np.ndarray, outer_counts: np.ndarray, endpoints: list[bool], diagonal: bool) -> np.ndarray:
    """:func:`exact_rule_value` on every row, called once per distinct local configuration."""
    codes = pb.astype(int) @ (1 << np.arange(4)) + (outer_counts @ (3 ** np.arange(4))) * 16
    uniq, inverse = np.unique(codes, return_inverse=True)
    values = []
    for code in uniq.tolist():
        p_bits = [(code >> k) & 1 for k in range(4)]
        counts = [(code // 16 // 3**k) % 3 for k in range(4)]
        values.append(exact_rule_value(p_bits, counts, endpoints, diagonal))
    return np.array(values, dtype=bool)[inverse.ravel()]


def build_case(
    s: Scenario, q: Plaquette, masks: np.ndarray, sorted_masks: np.ndarray, with_spec: bool = True
) -> Case:
    g = s.grid
    rb = s.robots[0]
    bits = bit_matrix(masks, g.num_edges)
    y = masks ^ q.edge_mask
    pos = np.searchsorted(sorted_masks, y).clip(0, len(sorted_masks) - 1)
    feasible = sorted_masks[pos] == y
    pb = bits[:, list(q.edges)]
    opposite = (pb[:, 0] == pb[:, 2]) & (pb[:, 1] == pb[:, 3]) & (pb[:, 0] != pb[:, 1])
    endpoints = [c in (rb.start, rb.goal) for c in q.corners]
    q_count = np.stack([pb[:, i].astype(int) + pb[:, j] for i, j in CORNER_EDGES], axis=1)
    endpoint_q0 = np.zeros(len(masks), dtype=bool)
    for v in range(4):
        if endpoints[v]:
            endpoint_q0 |= q_count[:, v] == 0
    outer_counts = np.stack([bits[:, list(oe)].sum(axis=1) if oe else np.zeros(len(masks), int)
                             for oe in q.outer_edges], axis=1)
    diagonal = {rb.start, rb.goal} in ({q.corners[0], q.corners[2]}, {q.corners[1], q.corners[3]})
    spec = spec_values(pb, outer_counts, endpoints, diagonal) if with_spec else np.zeros(0, dtype=bool)
    allowed, symmetric = {}, {}
    ybits = bit_matrix(y, g.num_edges)
    for rule in RULES:
        lg = sbf_logic(s, 0, q, rule)
        tx, ty = run_program(lg, bits), run_program(lg, ybits)
        allowed[rule] = tx[:, lg.output]
        symmetric[rule] = ~allowed[rule] | (ty[:, lg.output] & (tx == ty).all(axis=1))
    return Case(s, q, masks, feasible, opposite, pb.all(axis=1), endpoint_q0, allowed, spec, symmetric, diagonal)


@functools.cache
def sweep(rows: int, cols: int) -> tuple[Case, ...]:
    out = []
    for start, goal in pairs_of(rows, cols):
        s = scenario(rows, cols, start, goal)
        masks = np.array(enumerate_paths(s, 0), dtype=np.int64)
        sorted_masks = np.sort(masks)
        out += [build_case(s, q, masks, sorted_masks) for q in s.grid.plaquettes]
    return tuple(out)


ALL_SIZES = [*FULL_GRIDS, (5, 5)]


def total(cases: tuple[Case, ...], f: Any) -> int:
    return int(sum(int(np.count_nonzero(f(c))) for c in cases))


# ---------------------------------------------------------------- the harness itself


def test_run_program_agrees_with_evaluate() -> None:
    for rows, cols in [(2, 3), (3, 3), (3, 4)]:
        for c in sweep(rows, cols):
            for rule in RULES:
                lg = sbf_logic(c.scenario, 0, c.plaquette, rule)
                want = [lg.evaluate(int(m)) for m in c.masks]
                assert c.allowed[rule].tolist() == want


def test_flip_feasibility_lookup_agrees_with_is_feasible() -> None:
    for c in sweep(3, 3) + sweep(2, 3):
        for m, f in zip(c.masks, c.feasible, strict=True):
            assert is_feasible(c.scenario, 0, apply_sbf(int(m), c.plaquette)) == f


def test_rules_ignore_the_direction() -> None:
    """Swapping start and goal changes neither the feasible paths nor either rule's compiled program."""
    for rows, cols in [(3, 3), (3, 4), (4, 4)]:
        for start, goal in pairs_of(rows, cols):
            a, b = scenario(rows, cols, start, goal), scenario(rows, cols, goal, start)
            assert set(enumerate_paths(a, 0)) == set(enumerate_paths(b, 0))
            for q in a.grid.plaquettes:
                for rule in RULES:
                    assert sbf_logic(a, 0, q, rule).steps == sbf_logic(b, 0, q, rule).steps


def test_soft_obstacles_change_neither_paths_nor_rules() -> None:
    """Soft obstacles only cost: the feasible paths and both compiled programs are those of the free grid."""
    for rows, cols, obstacles in [(3, 3, ((1, 1),)), (3, 4, ((0, 1), (1, 2))), (4, 4, ((1, 1), (2, 2), (3, 0)))]:
        g = Grid(rows, cols)
        free = [n for n in g.nodes if n not in obstacles]
        for start, goal in itertools.combinations(free, 2):
            a, b = scenario(rows, cols, start, goal), scenario(rows, cols, start, goal, obstacles, "soft")
            assert enumerate_paths(a, 0) == enumerate_paths(b, 0)
            for q in g.plaquettes:
                for rule in RULES:
                    assert sbf_logic(a, 0, q, rule).steps == sbf_logic(b, 0, q, rule).steps


# ---------------------------------------------------------------- the exact rule


@pytest.mark.parametrize(("rows", "cols"), ALL_SIZES)
def test_exact_is_sound(rows: int, cols: int) -> None:
    cases = sweep(rows, cols)
    assert total(cases, lambda c: c.allowed["exact"] & ~c.feasible) == 0
    assert total(cases, lambda c: c.allowed["exact"]) > 0


@pytest.mark.parametrize(("rows", "cols"), ALL_SIZES)
def test_exact_is_complete_except_opposite_edges(rows: int, cols: int) -> None:
    cases = sweep(rows, cols)
    assert total(cases, lambda c: c.feasible & ~c.opposite & ~c.allowed["exact"]) == 0
    # (c) the feasible flips it misses are all opposite-edge patterns, and never with diagonal endpoints
    missed = total(cases, lambda c: c.feasible & ~c.allowed["exact"])
    assert missed == total(cases, lambda c: c.feasible & c.opposite & ~c.allowed["exact"])
    assert all(not c.diagonal for c in cases if np.any(c.feasible & ~c.allowed["exact"]))


@pytest.mark.parametrize(("rows", "cols"), ALL_SIZES)
def test_exact_network_equals_specification(rows: int, cols: int) -> None:
    for c in sweep(rows, cols):
        assert np.array_equal(c.allowed["exact"], c.spec)


def test_exact_allows_opposite_edges_exactly_when_endpoints_are_diagonal() -> None:
    for rows, cols in ALL_SIZES:
        for c in sweep(rows, cols):
            on = c.allowed["exact"] & c.opposite
            assert not on.any() or c.diagonal
            if c.diagonal:  # then every opposite-edges flip is feasible, and allowed
                assert np.array_equal(c.opposite & c.feasible, c.opposite)
                assert np.array_equal(on, c.opposite)


@pytest.mark.slow
def test_exact_sound_and_complete_with_hard_obstacles() -> None:
    """The same two checks with one hard obstacle anywhere on 3x3 and 3x4 (edges at it are not variables)."""
    checked = 0
    for rows, cols in [(3, 3), (3, 4)]:
        g = Grid(rows, cols)
        for ob in g.nodes:
            free = [n for n in g.nodes if n != ob]
            for start, goal in itertools.combinations(free, 2):
                s = scenario(rows, cols, start, goal, (ob,), "hard")
                masks = np.array(enumerate_paths(s, 0), dtype=np.int64)
                bits = bit_matrix(masks, g.num_edges)
                for q in g.plaquettes:
                    lg = sbf_logic(s, 0, q, "exact")
                    if ob in q.corners:
                        assert lg.never and sbf_logic(s, 0, q, "paper").never
                        continue
                    allowed = run_program(lg, bits)[:, lg.output]
                    feasible = np.isin(masks ^ q.edge_mask, masks)
                    pb = bits[:, list(q.edges)]
                    opposite = (pb[:, 0] == pb[:, 2]) & (pb[:, 1] == pb[:, 3]) & (pb[:, 0] != pb[:, 1])
                    assert not np.any(allowed & ~feasible)
                    assert not np.any(feasible & ~opposite & ~allowed)
                    checked += len(masks)
    assert checked > 0


# ---------------------------------------------------------------- the paper rule


@pytest.mark.parametrize(("rows", "cols"), ALL_SIZES)
def test_paper_rule_failures_are_endpoint_corners(rows: int, cols: int) -> None:
    """``paper`` leaves the feasible set exactly when an endpoint corner has no plaquette edge (it gains
    two), misses exactly the feasible opposite-edges flips, and otherwise agrees with ``exact``."""
    for c in sweep(rows, cols):
        paper, exact = c.allowed["paper"], c.allowed["exact"]
        leaks = paper & ~c.feasible
        assert np.array_equal(leaks, paper & c.endpoint_q0)
        assert np.array_equal(c.feasible & ~paper, c.feasible & c.opposite)
        assert np.array_equal(paper, (exact & ~c.opposite) | leaks)


def test_rules_agree_on_corner_to_corner_scenarios() -> None:
    """A grid corner has no outer edges, so an endpoint there always has a plaquette edge in the one
    plaquette it belongs to: with both endpoints at grid corners (the paper's experiments, the default
    presets) ``paper`` cannot leak. On the swept grids it then agrees with ``exact`` on every feasible path."""
    checked = 0
    for rows, cols in ALL_SIZES:
        corners = {(0, 0), (0, cols - 1), (rows - 1, 0), (rows - 1, cols - 1)}
        for c in sweep(rows, cols):
            rb = c.scenario.robots[0]
            if rb.start in corners and rb.goal in corners:
                assert not np.any(c.endpoint_q0)
                assert np.array_equal(c.allowed["paper"], c.allowed["exact"])
                checked += len(c.masks)
    assert checked > 0


def draw(grid: Grid, mask: int, start: Node, goal: Node, mark: Plaquette | None = None) -> list[str]:
    """ASCII picture: ``S``/``G`` endpoints, ``o`` other nodes, ``---``/``|`` path edges, ``*`` inside the
    flipped plaquette."""
    lines = []
    for r in range(grid.rows):
        row = ""
        for c in range(grid.cols):
            n = (r, c)
            row += "S" if n == start else "G" if n == goal else "o"
            if c + 1 < grid.cols:
                row += "---" if mask >> grid.edge_index(n, (r, c + 1)) & 1 else "   "
        lines.append(row)
        if r + 1 < grid.rows:
            row = ""
            for c in range(grid.cols):
                row += "|" if mask >> grid.edge_index((r, c), (r + 1, c)) & 1 else " "
                if c + 1 < grid.cols:
                    row += " * " if mark is not None and mark.corners[0] == (r, c) else "   "
            lines.append(row.rstrip())
    return lines


def side_by_side(left: list[str], right: list[str], gap: str = "   =>   ") -> str:
    width = max(map(len, left))
    return "\n".join(f"{a.ljust(width)}{gap if i == len(left) // 2 else ' ' * len(gap)}{b}".rstrip()
                     for i, (a, b) in enumerate(zip(left, right, strict=True)))


def notes_text() -> str:
    return NOTES.read_text(encoding="utf-8")


def smallest_paper_counterexample() -> tuple[Case, int]:
    for rows, cols in FULL_GRIDS:  # ordered by grid size
        found = [(int(m).bit_count(), int(m), c) for c in sweep(rows, cols)
                 for m in c.masks[c.allowed["paper"] & ~c.feasible]]
        if found:
            _, m, c = min(found, key=lambda t: (t[0], t[1], t[2].plaquette.index))
            return c, m
    raise AssertionError("the paper rule never left the feasible set")


def test_paper_rule_smallest_counterexample_is_documented() -> None:
    leaks = {size: total(sweep(*size), lambda c: c.allowed["paper"] & ~c.feasible) for size in ALL_SIZES}
    assert sum(leaks.values()) > 0  # the rule is leaky ...
    c, m = smallest_paper_counterexample()
    rb = c.scenario.robots[0]
    y = m ^ c.plaquette.edge_mask
    assert not is_feasible(c.scenario, 0, y) and is_feasible(c.scenario, 0, m)
    # ... and the smallest case is the documented picture
    picture = side_by_side(draw(c.scenario.grid, m, rb.start, rb.goal, c.plaquette),
                           draw(c.scenario.grid, y, rb.start, rb.goal, c.plaquette))
    assert picture in notes_text(), "\n" + picture


# ---------------------------------------------------------------- opposite edges: no local rule is exact


def neighbourhood(q: Plaquette) -> list[int]:
    """Every edge a local rule reads: the plaquette's own edges and all its corners' outer edges."""
    return list(q.edges) + [e for oe in q.outer_edges for e in oe]


def ambiguous_opposite_pairs(rows: int, cols: int) -> list[tuple[Case, int, int]]:
    """(case, x with a feasible flip, x' with an infeasible flip) sharing scenario, plaquette and every
    neighbourhood bit."""
    out = []
    for c in sweep(rows, cols):
        nb = neighbourhood(c.plaquette)
        groups: dict[tuple[int, ...], list[tuple[bool, int]]] = {}
        for m, f in zip(c.masks[c.opposite], c.feasible[c.opposite], strict=True):
            key = tuple(int(m) >> e & 1 for e in nb)
            groups.setdefault(key, []).append((bool(f), int(m)))
        for members in groups.values():
            good = [m for f, m in members if f]
            bad = [m for f, m in members if not f]
            if good and bad:
                out.append((c, min(good, key=lambda m: (m.bit_count(), m)), min(bad, key=lambda m: (m.bit_count(), m))))
    return out


def test_no_local_rule_is_exact_on_opposite_edges() -> None:
    found = {size: ambiguous_opposite_pairs(*size) for size in FULL_GRIDS}
    smallest = next(size for size in FULL_GRIDS if found[size])
    for c, good, bad in found[smallest]:
        for e in neighbourhood(c.plaquette):
            assert (good >> e & 1) == (bad >> e & 1)
        assert is_feasible(c.scenario, 0, good ^ c.plaquette.edge_mask)
        assert not is_feasible(c.scenario, 0, bad ^ c.plaquette.edge_mask)
        # whatever a local rule decides, it is wrong on one of the two, and exact forbids both
        lg = sbf_logic(c.scenario, 0, c.plaquette, "exact")
        assert not lg.evaluate(good) and not lg.evaluate(bad)
    c, good, bad = min(found[smallest], key=lambda t: (t[1].bit_count() + t[2].bit_count(), t[1], t[2]))
    rb = c.scenario.robots[0]
    g = c.scenario.grid
    pictures = [
        side_by_side(draw(g, good, rb.start, rb.goal, c.plaquette),
                     draw(g, good ^ c.plaquette.edge_mask, rb.start, rb.goal, c.plaquette)),
        side_by_side(draw(g, bad, rb.start, rb.goal, c.plaquette),
                     draw(g, bad ^ c.plaquette.edge_mask, rb.start, rb.goal, c.plaquette)),
    ]
    text = notes_text()
    for p in pictures:
        assert p in text, "\n" + p


# ---------------------------------------------------------------- uncompute symmetry


@pytest.mark.parametrize(("rows", "cols"), ALL_SIZES)
def test_uncompute_symmetry_on_feasible_paths(rows: int, cols: int) -> None:
    for c in sweep(rows, cols):
        for rule in RULES:
            assert c.symmetric[rule].all(), (rule, c.scenario.robots, c.plaquette.index)


def _temps(lg: SbfLogic, mask: int, num_edges: int) -> list[bool]:
    return run_program(lg, bit_matrix(np.array([mask], dtype=np.int64), num_edges))[0].tolist()


def test_paper_rule_breaks_uncompute_symmetry_off_the_feasible_set() -> None:
    """Once ``paper`` has leaked, it can reach a state with all four edges of a plaquette set; it allows
    that flip (f1 sees an edge) but not the flip back from 0000, so the uncompute in the circuit would leave
    f1's ancilla dirty. Every asymmetric case found is of that kind."""
    asymmetric = full = before = 0
    for rows, cols in [(2, 3), (3, 3)]:
        g = Grid(rows, cols)
        states = infeasible = 0
        for start, goal in itertools.combinations(g.nodes, 2):
            s = scenario(rows, cols, start, goal)
            logics = [sbf_logic(s, 0, q, "paper") for q in g.plaquettes]
            reached = reachable_paths(s, 0, "paper")
            states += len(reached)
            infeasible += sum(not is_feasible(s, 0, m) for m in reached)
            for m in reached:
                for q, lg in zip(g.plaquettes, logics, strict=True):
                    if not lg.evaluate(m):
                        continue
                    y = m ^ q.edge_mask
                    sym = lg.evaluate(y) and _temps(lg, m, g.num_edges) == _temps(lg, y, g.num_edges)
                    is_full = m & q.edge_mask == q.edge_mask
                    assert sym != is_full
                    asymmetric += not sym
                    full += is_full
        print(f"\n{rows}x{cols} paper-reachable states: {states} ({infeasible} infeasible), "
              f"asymmetric (state, plaquette) cases: {asymmetric - before}")
        before = asymmetric
    assert asymmetric == full > 0


def test_allowed_moves_lists_the_allowed_plaquettes() -> None:
    for c in sweep(3, 4)[:40]:
        for m in c.masks[:10]:
            moves = allowed_moves(c.scenario, 0, int(m))
            assert moves == [q.index for q in c.scenario.grid.plaquettes
                             if sbf_logic(c.scenario, 0, q).evaluate(int(m))]


def test_unknown_rule_is_rejected() -> None:
    s = scenario(2, 2, (0, 0), (1, 1))
    with pytest.raises(ValueError, match="unknown SBF rule"):
        sbf_logic(s, 0, s.grid.plaquettes[0], "greedy")  # type: ignore[arg-type]


def test_sweep_totals_add_up() -> None:
    """The sweep's totals are consistent (exact is sound: allowed + missed = feasible flips; paper: allowed =
    feasible - missed + leaks); they are printed for docs/paper-notes.md (see them with ``pytest -s``)."""
    lines = []
    for size in ALL_SIZES:
        cases = sweep(*size)
        n = {
            "path-plaquette": total(cases, lambda c: c.masks >= 0),
            "feasible-flips": total(cases, lambda c: c.feasible),
            "opposite-feasible": total(cases, lambda c: c.feasible & c.opposite),
            "exact-allowed": total(cases, lambda c: c.allowed["exact"]),
            "exact-missed": total(cases, lambda c: c.feasible & ~c.allowed["exact"]),
            "paper-allowed": total(cases, lambda c: c.allowed["paper"]),
            "paper-leaks": total(cases, lambda c: c.allowed["paper"] & ~c.feasible),
            "paper-missed": total(cases, lambda c: c.feasible & ~c.allowed["paper"]),
        }
        assert n["exact-allowed"] + n["exact-missed"] == n["feasible-flips"]
        assert n["paper-allowed"] == n["feasible-flips"] - n["paper-missed"] + n["paper-leaks"]
        assert n["paper-missed"] == n["opposite-feasible"] >= n["exact-missed"]
        paths = sum(len(c.masks) for c in cases[:: max(1, (size[0] - 1) * (size[1] - 1))])
        amb = len(ambiguous_opposite_pairs(*size))
        lines.append(f"{size[0]}x{size[1]}: pairs={len(pairs_of(*size))} paths={paths} "
                     + " ".join(f"{k}={v}" for k, v in n.items()) + f" ambiguous-opposite-classes={amb}")
    print("\n" + "\n".join(lines))


# ---------------------------------------------------------------- the parity form (what the circuit computes)


@pytest.mark.parametrize(("rows", "cols"), ALL_SIZES)
def test_parity_program_equals_the_direct_network_on_every_feasible_path(rows: int, cols: int) -> None:
    """The exact rule's parity-basis program equals qcpp 0.1's plain-edge network on every feasible path."""
    for c in sweep(rows, cols):
        direct = direct_exact_logic(c.scenario, 0, c.plaquette)
        bits = bit_matrix(c.masks, c.scenario.grid.num_edges)
        assert np.array_equal(run_program(direct, bits)[:, direct.output], c.allowed["exact"])


def random_simple_path(s: Scenario, robot: int, rng: random.Random) -> int:
    """A random simple start-goal path: the tree path of a randomised depth-first search over the free graph, which
    visits every node once (so it ends, path or not, in linear time: a search over all simple paths runs for ever
    when hard obstacles cut the goal off a large region)."""
    g, rb = s.grid, s.robots[robot]
    adj: dict[Node, list[tuple[Node, int]]] = {n: [] for n in g.nodes}
    for e, (a, b) in enumerate(g.edges):
        if (s.variable_mask >> e) & 1:
            adj[a].append((b, e))
            adj[b].append((a, e))
    visited: set[Node] = set()
    stack = [(rb.start, 0)]
    while stack:
        node, mask = stack.pop()
        if node in visited:
            continue
        visited.add(node)  # the nodes of mask's path were all visited before it: the path stays simple
        if node == rb.goal:
            return mask
        nxt = [(n, e) for n, e in adj[node] if n not in visited]
        rng.shuffle(nxt)
        stack.extend((n, mask | 1 << e) for n, e in nxt)
    raise AssertionError("no path")


@settings(max_examples=60, deadline=None)
@given(
    rows=st.integers(2, 7),
    cols=st.integers(2, 7),
    seed=st.integers(0, 2**32 - 1),
    mode=st.sampled_from(["soft", "hard"]),
)
def test_parity_program_equals_specification_on_random_feasible_paths(
    rows: int, cols: int, seed: int, mode: str
) -> None:
    """Beyond the exhaustive sweep: random grids up to 7x7 with obstacles, random endpoints, random simple paths."""
    rng = random.Random(seed)
    g = Grid(rows, cols)
    nodes = list(g.nodes)
    start, goal = rng.sample(nodes, 2)
    obstacles = tuple(n for n in rng.sample(nodes, min(2, len(nodes) - 2)) if n not in (start, goal))
    try:
        s = scenario(rows, cols, start, goal, obstacles, mode)
        path = random_simple_path(s, 0, rng)
    except (ScenarioError, AssertionError):
        return
    assert is_feasible(s, 0, path)
    for q in g.plaquettes:
        lg = sbf_logic(s, 0, q)
        if lg.never:
            continue
        pbits = [(path >> e) & 1 for e in q.edges]
        counts = [sum((path >> e) & 1 for e in oe if (s.variable_mask >> e) & 1) for oe in q.outer_edges]
        rb = s.robots[0]
        endpoints = [c in (rb.start, rb.goal) for c in q.corners]
        diagonal = {rb.start, rb.goal} in ({q.corners[0], q.corners[2]}, {q.corners[1], q.corners[3]})
        assert lg.evaluate(path) == exact_rule_value(pbits, counts, endpoints, diagonal)
        assert lg.evaluate(path) == direct_exact_logic(s, 0, q).evaluate(path)


@settings(max_examples=60, deadline=None)
@given(rows=st.integers(2, 6), cols=st.integers(2, 6), seed=st.integers(0, 2**32 - 1))
def test_parity_program_is_unchanged_by_its_own_flip_on_every_input(rows: int, cols: int, seed: int) -> None:
    """On ANY edge set (feasible or not) the exact program reads only parities, outer edges and temporaries, so
    flipping the plaquette does not change it: the circuit's compute and uncompute see the same value."""
    rng = random.Random(seed)
    g = Grid(rows, cols)
    start, goal = rng.sample(list(g.nodes), 2)
    s = scenario(rows, cols, start, goal)
    for q in g.plaquettes:
        lg = sbf_logic(s, 0, q)
        for _ in range(8):
            m = rng.getrandbits(g.num_edges)
            assert lg.evaluate(m) == lg.evaluate(m ^ q.edge_mask)
