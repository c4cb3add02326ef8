"""Test inputs (needs the ``test`` extra): hypothesis strategies for random gates and circuits, and the scenarios
and plan options the estimate == compiled cross-checks run on (:func:`crosscheck_cases`, :func:`every_plan_option`,
:func:`with_obstacles`, :func:`interior_endpoints`; checked by :func:`qcpp.estimators.crosscheck.crosscheck`).

Used by the property tests and the benchmarks, and available to code built on the IR.

>>> from hypothesis import given, settings
>>> @settings(max_examples=5)
... @given(circuits(max_qubits=3))
... def check(c):
...     assert c.inverse().inverse() == c
>>> check()
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Collection, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

from hypothesis import strategies as st

from qcpp.ir.angles import Angle, Param
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.cost import TARGETS
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
from qcpp.plan.options import DEFAULT_PLAN, INITIAL_STATES, OPTIMIZE, PHASES, PlanOptions
from qcpp.problem.presets import default_scenario, max_default_robots
from qcpp.problem.sbf import RULES
from qcpp.problem.scenario import Scenario, scenario_from_dict, scenario_to_dict
from qcpp.problem.scenario_io import load_scenario

__all__ = [
    "ALL_GATE_NAMES",
    "CLEAN_TARGET_NAMES",
    "SYMBOLS",
    "Case",
    "angles",
    "circuits",
    "crosscheck_cases",
    "every_plan_option",
    "gates",
    "interior_endpoints",
    "with_obstacles",
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


# --- scenarios and options the estimate == compiled cross-checks run on --------------------------------------
@dataclass(frozen=True)
class Case:
    """One scenario, ``p`` and construction options to cross-check."""

    scenario: Scenario
    p: int
    plan: PlanOptions = DEFAULT_PLAN

    @property
    def label(self) -> str:
        """Short text for reports."""
        g = self.scenario.grid
        extra = "" if self.plan == DEFAULT_PLAN else " " + "/".join(str(v) for v in dataclasses.astuple(self.plan))
        return f"{self.scenario.name or f'{g.rows}x{g.cols}'} p{self.p}{extra}"




def with_obstacles(scenario: Scenario, mode: str) -> Scenario | None:
    """``scenario`` with obstacles on the interior nodes ``(1, 1)`` and ``(rows-2, cols-2)`` (``None`` if the
    grid has no interior node), in ``soft`` or ``hard`` mode."""
    g = scenario.grid
    if g.rows < 3 or g.cols < 3:
        return None
    d = scenario_to_dict(scenario)
    d["grid"]["obstacles"] = sorted({(1, 1), (g.rows - 2, g.cols - 2)})
    d.setdefault("objective", {})["obstacles"] = mode
    d["name"] = f"{scenario.name}, {mode} obstacles"
    return scenario_from_dict(d)


def interior_endpoints(rows: int = 3, cols: int = 4, obstacles: str | None = None) -> Scenario:
    """Two robots, each with an endpoint inside the grid (off its boundary), optionally with an obstacle at
    ``(rows - 2, 1)`` in ``soft`` or ``hard`` mode (needs ``rows >= 4``: away from the endpoints)."""
    d = {
        "name": f"{rows}x{cols} interior endpoints",
        "grid": {"rows": rows, "cols": cols},
        "robots": [{"start": [1, 1], "goal": [rows - 1, cols - 1]}, {"start": [0, cols - 1], "goal": [1, cols - 2]}],
    }
    if obstacles is not None:
        d["grid"]["obstacles"] = [[rows - 2, 1]]  # type: ignore[index]
        d["objective"] = {"obstacles": obstacles}
        d["name"] += f", {obstacles} obstacle"
    return scenario_from_dict(d)


def every_plan_option(budgets: tuple[int | None, ...] = (None, 0, 3)) -> Iterator[PlanOptions]:
    """Every combination of the plan flags a user can pass (``--rule``, ``--initial``, ``--target``,
    ``--phase``, ``--optimize``), each with every ancilla budget of ``budgets``."""
    for rule, initial, target, phase, optimize, budget in itertools.product(
        RULES, INITIAL_STATES, TARGETS, PHASES, OPTIMIZE, budgets
    ):
        yield PlanOptions(rule, initial, target, phase, optimize, budget)


def crosscheck_cases(full: bool = False) -> Iterator[Case]:
    """The scenarios to cross-check (a sample, or all of them with ``full``).

    Args:
        full: every default grid 2x2..8x8 with 1..6 robots at p = 1, and p = 2, 3 on grids of up to 16 nodes,
            plus obstacles (soft and hard), the example files (``examples/`` of the source tree, if present) and
            the ``paper`` rule and ``ft`` target (about 400 cases, minutes); otherwise a sample of each kind
            (seconds).

    Yields:
        The cases.
    """
    grids = [(r, c) for r in range(2, 9) for c in range(2, 9)] if full else [(2, 2), (2, 5), (3, 3), (4, 3)]
    robots = range(1, 7) if full else (1, 2, 5)
    for r, c in grids:
        for k in robots:
            if k > max_default_robots(r, c):
                continue
            s = default_scenario(r, c, k)
            for p in (1, 2, 3) if (full and r * c <= 16) or (not full and k == 2) else (1,):
                yield Case(s, p)
    for r, c in [(3, 3), (4, 4), (3, 5), (5, 5), (6, 4)] if full else [(3, 4)]:
        for k in (1, 2, 3) if full else (2,):
            for mode in ("soft", "hard"):
                s = with_obstacles(default_scenario(r, c, k), mode)
                if s is not None:
                    yield Case(s, 1)
                    if not full:
                        yield Case(s, 2)
    for s, p in [(default_scenario(3, 3, 1), 2), (default_scenario(3, 4, 2), 1)]:
        yield Case(s, p, PlanOptions(rule="paper"))
        yield Case(s, p, PlanOptions(target="ft"))
    folder = Path(__file__).resolve().parents[2] / "examples"
    if full and folder.is_dir():
        for path in sorted(folder.glob("*.toml")):
            yield Case(load_scenario(path), 1)
