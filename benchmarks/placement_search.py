"""The placement search for small circuits (:mod:`qcpp.layout.placement_search`): routed CX against its budget.

Run: ``python benchmarks/placement_search.py [--family heavy-hex|grid]`` (default ``heavy-hex``).

Per one-robot scenario of ``benchmarks/routing.py`` (p = 1, angles bound; the circuit ``qcpp compile --device``
routes: unfused, the device's phase layout) on the smallest lattice of the family that holds it (where
``compile --device heavy-hex`` routes it), columns:

* ``a2a cx``: the lowered, fused circuit's CX (what ``qcpp compile --lowered`` writes; the ratio goal's base);
* ``one routing``: :func:`qcpp.pipeline.device_compile.best_layout` and one SABRE routing, every SWAP three
  CX (the greedy path before the search);
* ``fused``: the same routing with SWAPs fused into an adjacent ``cx`` on their pair (``route(fuse=True)``);
* ``search L``: :func:`qcpp.layout.placement_search.search_route` from that layout with ``L`` ``SabreLayout``
  starts (``placement_seeds`` routing seeds for the ``placement_refine`` best,
  :class:`qcpp.routing.options.RoutingOptions`): routed CX, CX / a2a, and the CPU seconds of the search (the
  process's CPU time: SABRE's trials run on threads), in a fresh routing context. The default budget is
  ``placement_layouts``;
* ``compile s``: CPU seconds of what ``qcpp compile --device FAMILY --lowered`` runs
  (:func:`qcpp.pipeline.device_compile.compile_for_device`, ``auto``: on heavy-hex the cell layout too, then the
  greedy
  path with the default search), in a fresh routing context.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

from routing import BIND, scenarios  # the routing benchmark's (this script's directory is on the path)

from qcpp.hardware.device import get_device
from qcpp.layout import placement_search
from qcpp.pipeline.device_compile import best_layout, compile_for_device
from qcpp.pipeline.device_plan import device_plan_options
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import DEFAULT_PLAN
from qcpp.problem.scenario import Scenario
from qcpp.routing.sabre import route

BUDGETS = (8, 16, 24, 32, 48)


def one_robot() -> list[tuple[str, Scenario]]:
    """The one-robot scenarios of ``benchmarks/routing.py``."""
    return [(label, s) for label, s in scenarios(quick=True) if s.num_robots == 1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--family", choices=("heavy-hex", "grid"), default="heavy-hex", help="the device family")
    family = parser.parse_args().family
    head = " | ".join(f"search {b}: cx, / a2a, s" for b in BUDGETS)
    print(f"| scenario | device | a2a cx | one routing | fused | {head} | compile s |")
    print("|---|---|---:|---:|---:|" + "---:|" * (len(BUDGETS) + 1))
    for label, s in one_robot():
        a2a = compile_scenario(s, 1, lowered=True, bindings=BIND).circuit.count_ops()["cx"]
        options = replace(device_plan_options(DEFAULT_PLAN, family, layout_method="greedy"), fuse=False)
        circuit = compile_scenario(s, 1, options, lowered=True, bindings=BIND).circuit
        device = get_device(family, min_qubits=circuit.num_qubits)
        start = best_layout(circuit, device)
        one = route(circuit, device, start).circuit.count_ops()["cx"]
        fused = route(circuit, device, start, fuse=True).circuit.count_ops()["cx"]
        cells = []
        for budget in BUDGETS:
            t = time.process_time()
            cx = placement_search.search_route(circuit, device, starts=(start,), layouts=budget).circuit
            seconds = time.process_time() - t
            n = cx.count_ops()["cx"]
            cells.append(f"{n:,}, {n / a2a:.2f}, {seconds:.2f}")
        t = time.process_time()
        compile_for_device(s, 1, family, lowered=True, bindings=BIND)
        compile_s = time.process_time() - t
        print(f"| {label} | {device.name} | {a2a:,} | {one:,} ({one / a2a:.2f}) | {fused:,} ({fused / a2a:.2f}) | "
              + " | ".join(cells) + f" | {compile_s:.2f} |", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
