"""Cross-check: the counts summed from the gadgets equal the counts of the compiled, lowered circuit.

:func:`crosscheck` builds the circuit (:func:`circuitgen.qaoa.qaoa_circuit`), lowers it
(:func:`circuitgen.lowering.lower`, and once more with ``LOGICAL_BASIS``), counts it
(:func:`estimators.counts.count`) and compares every number :func:`estimators.estimate.estimate_point` reports
without building anything: qubits and registers, gate counts per name (whole circuit, state preparation, each
layer's phase separator and mixer), the logical gate counts, and the depths (asked ``exact``: composed from the
gadgets' transfer profiles, :mod:`estimators.depth_compose`). :func:`crosscheck_cases` lists the scenarios the
tests and ``benchmarks/estimate_speed.py`` check: the default scenarios of every grid 2x2..8x8 with 1..6 robots,
the same with interior obstacles (soft and hard mode), the example files, the ``paper`` rule and the ``ft``
target, for p = 1..3.

Example:
    >>> from gridcover.presets import default_scenario
    >>> crosscheck(Case(default_scenario(2, 3, 2), 2))
    []
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from circuitgen.cost import TARGETS, Cost
from circuitgen.lowering import LOGICAL_BASIS, lower
from circuitgen.options import DEFAULT_PLAN, INITIAL_STATES, OPTIMIZE, PHASES, PlanOptions
from circuitgen.qaoa import qaoa_circuit
from gridcover.presets import default_scenario, max_default_robots
from gridcover.sbf import RULES
from gridcover.scenario import Scenario, load_scenario, scenario_from_dict, scenario_to_dict

from .counts import count
from .estimate import EstimateOptions, Point, estimate_point

__all__ = ["Case", "crosscheck", "crosscheck_cases", "every_plan_option", "interior_endpoints", "with_obstacles"]


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


def crosscheck(case: Case) -> list[str]:
    """Compare the gadget-summed estimate with the compiled circuit's counts.

    Args:
        case: what to check.

    Returns:
        One line per mismatch (empty when everything agrees).
    """
    s, p, plan = case.scenario, case.p, case.plan
    est = estimate_point(Point.from_scenario(s, p), EstimateOptions(plan=plan, depth="exact"))
    circ = qaoa_circuit(s, p, plan)
    low = lower(circ)
    rc = count(low)
    out = []

    def check(what: str, got: object, want: object) -> None:
        if got != want:
            out.append(f"{case.label}: {what}: gadgets {got} != compiled {want}")

    check("registers", est.registers, rc.registers)
    check("gates", est.cost.to_dict(), dict(rc.ops))
    check("logical gates", est.logical, Cost.count(lower(circ, LOGICAL_BASIS).gates))
    if p:
        check(
            "state preparation",
            est.parts["initial_state"].to_dict(),
            dict(rc.sections["initial_state"].ops) if "initial_state" in rc.sections else {},
        )
        for k in range(p):
            for part in ("phase", "mixer"):
                have = rc.sections.get(f"{part}_{k}")
                check(f"{part} of layer {k}", est.parts[part].to_dict(), dict(have.ops) if have else {})
    if est.depth is not None and est.depth.kind == "exact":
        check("depth", (est.depth.depth, est.depth.two_qubit_depth), (rc.depth, rc.two_qubit_depth))
    return out


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


def crosscheck_cases(full: bool = False, examples: Path | None = None) -> Iterator[Case]:
    """The scenarios to cross-check (a sample, or all of them with ``full``).

    Args:
        full: every default grid 2x2..8x8 with 1..6 robots at p = 1, and p = 2, 3 on grids of up to 16 nodes,
            plus obstacles (soft and hard), the example files and the ``paper`` rule and ``ft`` target (about 400
            cases, minutes); otherwise a sample of each kind (seconds).
        examples: folder of example scenario files (default: ``examples/`` of the source tree, if present).

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
    folder = examples if examples is not None else Path(__file__).resolve().parents[2] / "examples"
    if full and folder.is_dir():
        for path in sorted(folder.glob("*.toml")):
            yield Case(load_scenario(path), 1)
