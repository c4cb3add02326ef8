"""Hypothesis strategies for property tests (needs hypothesis: the ``testing`` extra, ``pip install 'qcpp[testing]'``).

Strategies for scenarios, feasible paths and plaquette flips (:func:`scenarios`, :func:`feasible_paths`,
:func:`feasible_assignments`, :func:`plaquette_flips`: property-test your own mixer variant against the SBF rules
and :func:`qcpp.verify`), and for random angles, gates and circuits of the IR.

An optional module for property tests of the IR and of code built on it: no production module imports it. The
plain scenario lists the estimate == compiled checks run on are in :mod:`qcpp.estimators.crosscheck`.

A property test of feasibility preservation, in the form a mixer variant would use:

>>> from hypothesis import given, settings
>>> from qcpp.problem.paths import is_feasible
>>> @settings(max_examples=20)
... @given(plaquette_flips(scenarios(max_side=4), rule="exact"))
... def exact_flips_stay_feasible(flip):
...     assert not flip.allowed or is_feasible(flip.scenario, flip.robot, flip.result)
>>> exact_flips_stay_feasible()

Random circuits:

>>> from hypothesis import given, settings
>>> @settings(max_examples=5)
... @given(circuits(max_qubits=3))
... def check(c):
...     assert c.inverse().inverse() == c
>>> check()
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Collection, Sequence
from dataclasses import dataclass

from hypothesis import strategies as st

from qcpp.ir.angles import Angle, Param
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import (
    GATE_SPECS,
    Gate,
    ccx,
    crx,
    cry,
    crz,
    csbf,
    cx,
    cz,
    h,
    mcx,
    rx,
    ry,
    rz,
    rzz,
    s,
    sbf,
    sdg,
    t,
    tdg,
    x,
)
from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import Grid
from qcpp.problem.paths import iter_paths
from qcpp.problem.sbf import Rule, sbf_logic
from qcpp.problem.scenario import Objective, Robot, Scenario

__all__ = [
    "ALL_GATE_NAMES",
    "CLEAN_TARGET_NAMES",
    "SYMBOLS",
    "PlaquetteFlip",
    "angles",
    "circuits",
    "feasible_assignments",
    "feasible_paths",
    "gates",
    "plaquette_flips",
    "scenarios",
]

CLEAN_TARGET_NAMES = frozenset({"and", "and_dg"})
"""Gates whose lowering is exact only on a clean target (drawn only by tests that respect that contract)."""

ALL_GATE_NAMES: tuple[str, ...] = tuple(n for n in GATE_SPECS if n not in CLEAN_TARGET_NAMES)
"""Every gate name of the IR."""

SYMBOLS: tuple[str, ...] = ("gamma_0", "beta_0", "gamma_1")
"""Symbols used by :func:`angles` when ``symbolic=True``."""

_FIXED = {"x": x, "h": h, "t": t, "tdg": tdg, "s": s, "sdg": sdg}
_ONE = {"rz": rz, "rx": rx, "ry": ry}
_TWO = {"cx": cx, "cz": cz}
_TWO_P = {"crz": crz, "cry": cry, "crx": crx, "rzz": rzz}


def angles(symbolic: bool = False) -> st.SearchStrategy[Param]:
    """Floats in [-2π, 2π], or (if ``symbolic``) also affine angles over :data:`SYMBOLS`."""
    number = st.floats(-2 * math.pi, 2 * math.pi, allow_nan=False, allow_infinity=False)
    if not symbolic:
        return number
    coeff = st.floats(-2, 2, allow_nan=False).filter(lambda c: c != 0.0)
    symbolic_angle = st.builds(
        lambda name, c, const: Angle.symbol(name, c) + const,
        st.sampled_from(SYMBOLS),
        coeff,
        number,
    )
    return st.one_of(number, symbolic_angle)


@st.composite
def gates(
    draw: st.DrawFn,
    num_qubits: int,
    names: Collection[str] = ALL_GATE_NAMES,
    max_controls: int = 4,
    symbolic: bool = False,
    qubits: Sequence[int] | None = None,
) -> Gate:
    """One random gate on distinct qubits drawn from ``qubits`` (default ``range(num_qubits)``).

    Args:
        draw: supplied by hypothesis.
        num_qubits: size of the qubit pool when ``qubits`` is None.
        names: gate names to draw from (those needing more qubits than available are skipped).
        max_controls: most controls of an ``mcx``.
        symbolic: allow symbolic angles.
        qubits: explicit qubit pool.

    Returns:
        The gate (``mcx`` goes through the normalising constructor, so it may come out as
        ``x``/``cx``/``ccx``).
    """
    pool = list(range(num_qubits)) if qubits is None else list(qubits)
    size = len(pool)
    usable = [n for n in names if (GATE_SPECS[n].num_qubits or 2) <= size]
    if not usable:
        raise ValueError(f"no gate of {sorted(names)} fits on {size} qubits")
    name = draw(st.sampled_from(sorted(usable)))
    spec = GATE_SPECS[name]
    arity = spec.num_qubits if spec.num_qubits is not None else draw(st.integers(2, min(size, max_controls + 1)))
    qs = draw(st.permutations(pool))[:arity]
    theta = draw(angles(symbolic)) if spec.num_params else 0.0
    if name in _FIXED:
        return _FIXED[name](qs[0])
    if name in _ONE:
        return _ONE[name](theta, qs[0])
    if name in _TWO:
        return _TWO[name](*qs)
    if name in _TWO_P:
        return _TWO_P[name](theta, *qs)
    if name == "ccx":
        return ccx(*qs)
    if name == "sbf":
        return sbf(theta, *qs)
    if name == "csbf":
        return csbf(theta, *qs)
    state = "".join(draw(st.lists(st.sampled_from("01"), min_size=arity - 1, max_size=arity - 1)))
    return mcx(qs[:-1], qs[-1], state)


@st.composite
def circuits(
    draw: st.DrawFn,
    min_qubits: int = 1,
    max_qubits: int = 5,
    max_gates: int = 12,
    names: Collection[str] = ALL_GATE_NAMES,
    max_controls: int = 4,
    symbolic: bool = False,
) -> Circuit:
    """A random circuit: a ``data`` register, sometimes an ``anc`` register, 1-3 sections.

    Args:
        draw: supplied by hypothesis.
        min_qubits: fewest qubits in all.
        max_qubits: most qubits in all.
        max_gates: most gates per section.
        names: gate names to use.
        max_controls: most controls of an ``mcx``.
        symbolic: allow symbolic angles (over :data:`SYMBOLS`).

    Returns:
        The circuit.
    """
    n = draw(st.integers(min_qubits, max_qubits))
    n_anc = draw(st.integers(0, min(2, n - 1)))
    regs = [Register("data", n - n_anc)] + ([Register("anc", n_anc)] if n_anc else [])
    sections = []
    for i in range(draw(st.integers(1, 3))):
        body = draw(st.lists(gates(n, names, max_controls=max_controls, symbolic=symbolic), max_size=max_gates))
        sections.append(Section(draw(st.sampled_from([f"phase_{i}", f"mixer_{i}", "initial_state"])), body))
    return Circuit(regs, sections)


# --- scenarios, feasible paths and plaquette flips -------------------------------------------------------------
@st.composite
def scenarios(
    draw: st.DrawFn, min_side: int = 2, max_side: int = 5, max_robots: int = 1, obstacles: bool = True
) -> Scenario:
    """A random valid scenario: sides ``min_side..max_side``, up to three obstacles (soft or hard mode, when
    ``obstacles``), ``1..max_robots`` robots with distinct starts and random goals.

    A hard-mode scenario whose goal is cut off falls back to soft mode, so every draw is valid.
    """
    rows = draw(st.integers(min_side, max_side))
    cols = draw(st.integers(min_side, max_side))
    grid = Grid(rows, cols)
    nodes = list(grid.nodes)
    n_obs = draw(st.integers(0, min(3, len(nodes) - 2))) if obstacles else 0
    obs = sorted(draw(st.lists(st.sampled_from(nodes), min_size=n_obs, max_size=n_obs, unique=True)))
    free = [n for n in nodes if n not in obs]
    robots: list[Robot] = []
    starts: set[tuple[int, int]] = set()
    for _ in range(draw(st.integers(1, min(max_robots, len(free))))):
        start = draw(st.sampled_from([n for n in free if n not in starts]))
        goal = draw(st.sampled_from([n for n in free if n != start]))
        starts.add(start)
        robots.append(Robot(start, goal))
    mode = draw(st.sampled_from(["soft", "hard"]))
    try:
        return Scenario(grid, tuple(robots), tuple(obs), Objective(obstacles=mode))
    except ScenarioError:  # a goal cut off by hard obstacles
        return Scenario(grid, tuple(robots), tuple(obs), Objective(obstacles="soft"))


@functools.lru_cache(maxsize=64)
def _path_pool(scenario: Scenario, robot: int, limit: int) -> tuple[int, ...]:
    """Pure memo: ``_path_pool.cache_clear()`` empties it."""
    return tuple(itertools.islice(iter_paths(scenario, robot), limit))


def feasible_paths(scenario: Scenario, robot: int, limit: int = 2_000) -> st.SearchStrategy[int]:
    """One of the robot's feasible paths (an edge mask; :func:`qcpp.problem.paths.iter_paths` order), drawn from
    its first ``limit`` paths (every path on small grids; the pool is enumerated once per scenario and robot)."""
    return st.sampled_from(_path_pool(scenario, robot, limit))


@st.composite
def feasible_assignments(draw: st.DrawFn, scenario: Scenario, limit: int = 2_000) -> tuple[int, ...]:
    """One feasible path per robot (see :func:`feasible_paths`)."""
    return tuple(draw(feasible_paths(scenario, r, limit)) for r in range(scenario.num_robots))


@dataclass(frozen=True)
class PlaquetteFlip:
    """One SBF move tried on a feasible path.

    Attributes:
        scenario: The scenario.
        robot: The robot moved.
        path: Its feasible path (edge mask) before the move.
        plaquette: Index of the plaquette flipped.
        rule: The rule asked.
        allowed: Whether the rule allows the flip on ``path``.
        result: ``path`` with the plaquette's four edges flipped (whether allowed or not).
    """

    scenario: Scenario
    robot: int
    path: int
    plaquette: int
    rule: Rule
    allowed: bool
    result: int


@st.composite
def plaquette_flips(
    draw: st.DrawFn, scenario: Scenario | st.SearchStrategy[Scenario], rule: Rule = "exact",
    allowed_only: bool = False,
) -> PlaquetteFlip:  # fmt: skip
    """A random robot, one of its feasible paths and a plaquette, with what ``rule`` says of flipping it there.

    Args:
        draw: supplied by hypothesis.
        scenario: A scenario, or a strategy for one (e.g. :func:`scenarios`).
        rule: ``exact`` or ``paper``.
        allowed_only: Only draw flips the rule allows (rejects the others: keep it for rules that allow some).
    """
    s = draw(scenario) if isinstance(scenario, st.SearchStrategy) else scenario
    robot = draw(st.integers(0, s.num_robots - 1))
    path = draw(feasible_paths(s, robot))
    plaq = draw(st.sampled_from(s.grid.plaquettes))
    allowed = sbf_logic(s, robot, plaq, rule).evaluate(path)
    if allowed_only:
        from hypothesis import assume

        assume(allowed)
    return PlaquetteFlip(s, robot, path, plaq.index, rule, allowed, path ^ plaq.edge_mask)
