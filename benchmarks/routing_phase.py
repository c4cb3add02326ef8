"""Routed two-qubit gates of the phase separator and of the whole circuit: pooled vs spatial phase layout.

Run: ``python benchmarks/routing_phase.py [--quick]`` (``--quick``: 3x3/1, 4x4/2 and 4x4/2 with interior endpoints
and a hard obstacle).

Per scenario (p = 1, angles bound), device family (the smallest square grid and the smallest heavy-hex that
:func:`qcpp.pipeline.device_compile.compile_for_device` picks) and phase layout (``PlanOptions.phase_layout``:
``pooled``, today's default, or ``spatial``, :mod:`qcpp.plan.phase_layout`), columns:

* ``a2a phase`` / ``a2a all``: CX of the lowered, unrouted circuit that ``compile_for_device`` routes (unfused
  mixer), phase separator sections and whole circuit;
* ``routed phase`` / ``routed all``: CX of what ``compile_for_device(..., lowered=True)`` writes (SWAPs as 3 CX,
  1 where fused with a CX on their pair; a SWAP counts to the section of the gate before it), phase separator
  sections and whole circuit;
* ``ratio``: routed / a2a of the same circuit; ``vs pooled a2a``: routed over the *pooled* circuit's a2a count
  (the spatial adders cost 2 CX more per adder all-to-all, so this is the fair figure for the goal of
  routed / all-to-all <= 2 on a grid and <= 3 on heavy-hex);
* ``s``: seconds of ``compile_for_device``.
"""

from __future__ import annotations

import argparse
import time

from qcpp.estimators.crosscheck import interior_endpoints
from qcpp.ir.circuit import Circuit
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
OBSTACLES_HARD = {
    "name": "5x5/2, hard obstacles",
    "grid": {"rows": 5, "cols": 5, "obstacles": [[1, 3], [2, 2]]},
    "robots": [{"start": [0, 0], "goal": [4, 4]}, {"start": [0, 4], "goal": [4, 0]}],
    "objective": {"obstacles": "hard"},
}
LAYOUTS = ("pooled", "spatial")


def scenarios(quick: bool) -> list[tuple[str, Scenario]]:
    """Default scenarios and two with obstacles and interior endpoints (those of ``benchmarks/mixer_cost.py``
    have a phase separator to route: two robots)."""
    out = [("3x3/1", default_scenario(3, 3, 1)), ("4x4/2", default_scenario(4, 4, 2))]
    out.append(("4x4/2 interior, hard obst", interior_endpoints(4, 4, "hard")))
    if not quick:
        out += [("5x5/2", default_scenario(5, 5, 2)), ("6x6/3", default_scenario(6, 6, 3))]
        out += [("5x5/2 hard obstacles", scenario_from_dict(OBSTACLES_HARD))]
        out += [("5x5/2 interior, soft obst", interior_endpoints(5, 5, "soft"))]
    return out


def cx_of(circuit: Circuit, prefix: str | None = None) -> int:
    """CX in the sections whose name starts with ``prefix`` (all sections if ``None``)."""
    return sum(
        1
        for sec in circuit.sections
        if prefix is None or sec.name.startswith(prefix)
        for g in sec.gates
        if g[0] == "cx"
    )


def ratio(a: int, b: int) -> str:
    return f"{a / b:.2f}" if b else "-"


def rows(label: str, s: Scenario, family: str) -> list[str]:
    """One table row per phase layout."""
    out = []
    pooled_a2a: tuple[int, int] | None = None
    for layout in LAYOUTS:
        options = PlanOptions(phase_layout=layout)
        unrouted = compile_scenario(s, 1, PlanOptions(fuse=False, phase_layout=layout), lowered=True, bindings=BIND)
        a2a = (cx_of(unrouted.circuit, "phase"), cx_of(unrouted.circuit))
        pooled_a2a = pooled_a2a or a2a
        start = time.perf_counter()
        res = compile_for_device(s, 1, family, options, lowered=True, bindings=BIND)
        seconds = time.perf_counter() - start
        routed = (cx_of(res.routed.circuit, "phase"), cx_of(res.routed.circuit))
        out.append(
            f"| {label} | {res.routed.device.name} | {layout} | {a2a[0]:,} | {routed[0]:,} "
            f"| {ratio(routed[0], a2a[0])} | {ratio(routed[0], pooled_a2a[0])} | {a2a[1]:,} | {routed[1]:,} "
            f"| {ratio(routed[1], a2a[1])} | {ratio(routed[1], pooled_a2a[1])} | {seconds:.1f} |"
        )
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer scenarios (module docs)")
    quick = parser.parse_args().quick
    print(
        "| scenario | device | phase layout | a2a phase | routed phase | ratio | vs pooled a2a | a2a all "
        "| routed all | ratio | vs pooled a2a | s |"
    )
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for label, s in scenarios(quick):
        for family in ("grid", "heavy-hex"):
            for line in rows(label, s, family):
                print(line, flush=True)


if __name__ == "__main__":
    main()
