"""Cross-check: the counts summed from the call graph equal the counts of the compiled, lowered circuit.

:func:`crosscheck` compares every number :func:`qcpp.estimators.estimate.estimate_point` reports without building
anything (registers, gate counts of the whole circuit and of each part and layer, logical gate counts, and the
``exact`` depths composed by :mod:`qcpp.estimators.depth_compose`) with :func:`qcpp.estimators.counts.count` of the
compiled circuit, lowered to the basis and to ``LOGICAL_BASIS``. The scenarios the tests and
``benchmarks/estimate_speed.py`` check are :func:`qcpp.testing.crosscheck_cases`.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.testing import Case
    >>> crosscheck(Case(default_scenario(2, 3, 2), 2))
    []
"""

from __future__ import annotations

from qcpp.estimators.counts import count
from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import LOGICAL_BASIS, lower
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.testing import Case

__all__ = ["crosscheck"]


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
        check(what, est.parts[part].to_dict(), dict(have.ops) if have else {})
    if est.depth is not None and est.depth.kind == "exact":
        check("depth", (est.depth.depth, est.depth.two_qubit_depth), (rc.depth, rc.two_qubit_depth))
    return out
