"""Cross-check: the counts summed from the call graph equal the counts of the compiled, lowered circuit.

:func:`crosscheck` compares every number :func:`qcpp.estimators.estimate.estimate_point` reports without building
anything (registers, gate counts of the whole circuit, of each part and layer, logical gate counts, and ``exact``
depths) with :func:`qcpp.estimators.counts.count` of the compiled circuit, lowered to the basis and to
``LOGICAL_BASIS``. :func:`crosscheck_cases` lists the scenarios the tests and ``benchmarks/estimate_speed.py`` check;
:func:`every_plan_option`, :func:`one_plan_option_at_a_time`, :func:`with_obstacles` and
:func:`interior_endpoints` build more of them. Plain values
only, so production code may import this module (the random inputs of property tests live in :mod:`qcpp.testing`).

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> crosscheck(Case(default_scenario(2, 3, 2), 2))
    []
"""

from __future__ import annotations

import dataclasses
import itertools
import typing
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from qcpp.estimators.counts import count
from qcpp.estimators.depth import depths
from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.presets import default_scenario, max_default_robots
from qcpp.problem.scenario import Scenario, scenario_from_dict, scenario_to_dict
from qcpp.problem.scenario_io import load_scenario

__all__ = [
    "Case", "crosscheck", "crosscheck_cases", "every_plan_option", "interior_endpoints", "one_plan_option_at_a_time",
    "plan_option_values", "with_obstacles",
]


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


def plan_option_values(budgets: tuple[int | None, ...] = (None, 0, 3)) -> dict[str, tuple[object, ...]]:
    """Every value of every :class:`~qcpp.plan.options.PlanOptions` field, the default first: a ``Literal``
    field's values from its type (a value added to the type is covered here too), a ``bool`` field's ``True`` and
    ``False``, and ``ancilla_budget`` those of ``budgets``.

    Raises:
        TypeError: a field of another type (say how to cover it here).

    Example:
        >>> values = plan_option_values()
        >>> values["initial"], values["first_phase"], values["ancilla_budget"]
        (('initial_path', 'representatives', 'local_search', 'local_search_mix'), (True, False), (None, 0, 3))
    """
    hints = typing.get_type_hints(PlanOptions)
    out: dict[str, tuple[object, ...]] = {}
    for f in dataclasses.fields(PlanOptions):
        hint, default = hints[f.name], getattr(DEFAULT_PLAN, f.name)
        if typing.get_origin(hint) is Literal:
            values: tuple[object, ...] = typing.get_args(hint)
        elif hint is bool:
            values = (True, False)
        elif f.name == "ancilla_budget":
            values = budgets
        else:
            raise TypeError(f"plan_option_values: no values for field {f.name} of type {hint}")
        out[f.name] = (default, *(v for v in values if v != default))
    return out


def every_plan_option(
    budgets: tuple[int | None, ...] = (None, 0, 3), fields: tuple[str, ...] | None = None
) -> Iterator[PlanOptions]:
    """Every combination of the values of ``fields`` (:func:`plan_option_values`; default: every field of
    :class:`~qcpp.plan.options.PlanOptions`, which is every plan flag and ``fuse``), the other fields at their
    defaults. Print the count with ``python -c "from qcpp.estimators.crosscheck import every_plan_option as e;
    print(len(list(e())))"``.

    Some combinations are refused by a scenario whose start is a superposition (``first_phase=False`` with
    ``representatives`` or ``local_search_mix``, :attr:`qcpp.plan.qaoa.QaoaPlan.basis_start`): :func:`crosscheck`
    raises :class:`~qcpp.errors.OptionError` for them.
    """
    values = plan_option_values(budgets)
    names = tuple(values) if fields is None else fields
    for combo in itertools.product(*(values[name] for name in names)):
        yield PlanOptions(**dict(zip(names, combo)))  # type: ignore[arg-type]


def one_plan_option_at_a_time(budgets: tuple[int | None, ...] = (None, 0, 3)) -> Iterator[PlanOptions]:
    """The default plan, then every other value of every field (:func:`plan_option_values`) with the other fields
    at their defaults: each option against the default, far fewer than :func:`every_plan_option`."""
    yield DEFAULT_PLAN
    for name, values in plan_option_values(budgets).items():
        for value in values[1:]:
            yield PlanOptions(**{name: value})  # type: ignore[arg-type]


def crosscheck_cases(full: bool = False) -> Iterator[Case]:
    """The scenarios to cross-check (a sample, or all of them with ``full``).

    Args:
        full: every default grid 2x2..8x8 with 1..6 robots at p = 1, and p = 2, 3 on grids of up to 16 nodes,
            plus obstacles (soft and hard), the example files (``examples/`` of the source tree, if present),
            the ``paper`` rule, the ``ft`` target and no first phase separator (minutes; count them with
            ``python -c "from qcpp.estimators.crosscheck import crosscheck_cases as c; print(len(list(c(True))))"``);
            otherwise a sample of each kind (seconds).

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
    for s, p in [(default_scenario(3, 3, 2), 1), (default_scenario(3, 4, 2), 3)]:  # no first phase separator
        yield Case(s, p, PlanOptions(first_phase=False))
    folder = Path(__file__).resolve().parents[3] / "examples"
    if full and folder.is_dir():
        for path in sorted(folder.glob("*.toml")):
            yield Case(load_scenario(path), 1)


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
    sections = [("state preparation", "initial_state", "initial_state")] if p else []
    sections += [(f"{part} of layer {k}", part, f"{part}_{k}") for k in range(p) for part in ("phase", "mixer")]
    for what, part, name in sections:
        have = rc.sections.get(name)
        want = {} if name == "phase_0" and not plan.first_phase else est.parts[part].to_dict()  # no such section
        check(what, want, dict(have.ops) if have else {})
    if est.depth is not None and est.depth.kind == "exact":
        check("depth", est.depth, depths(low.gates, low.num_qubits))  # rotation depth too
    return out
