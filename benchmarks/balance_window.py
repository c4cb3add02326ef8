"""The balance arithmetic's one large window on the medial layout: routed CX per SABRE seeds and trials.

Run: ``python benchmarks/balance_window.py [--quick]`` (``--quick``: 4x4/2 only).

Per two-robot default scenario (p = 1, angles bound, ``qcpp compile --device grid``'s path: the medial layout,
``phase_layout="medial"``), and per setting of the wider search on the large window
(``wide_window_seeds`` seeds of ``wide_window_trials`` SABRE trials of :class:`qcpp.routing.options.RoutingOptions`,
tried after the ``large_window_seeds`` = 8 seeds of 16 trials; 0 seeds: none;
the cheapest whole window wins), columns:

* ``balance cx``: the routed CX of the largest window (the balance gadget: compute, register phase, uncompute),
  routed from home as :func:`qcpp.routing.windows.route_windows` routes it;
* ``compile cx``: the routed CX of the whole circuit (what ``qcpp compile SCEN --device grid --lowered`` writes);
* ``s``: seconds of the compile (wall time on a shared machine: indicative only).
"""

from __future__ import annotations

import sys
import time
from dataclasses import replace

from qcpp.hardware.device import distances
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.problem.presets import default_scenario
from qcpp.routing.options import DEFAULT_ROUTING
from qcpp.routing.sabre import window_cx
from qcpp.routing.windows import Positions, route_window

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
SETTINGS = ((0, 128), (8, 128), (16, 16), (16, 128))


def main(argv: list[str]) -> None:
    shapes = [(4, 4, 2)] if "--quick" in argv else [(4, 4, 2), (5, 5, 2)]
    print("| scenario | wide seeds | wide trials | balance cx | compile cx | s |")
    print("|---|---:|---:|---:|---:|---:|")
    for rows, cols, robots in shapes:
        for seeds, trials in SETTINGS:
            routing = replace(DEFAULT_ROUTING, wide_window_seeds=seeds, wide_window_trials=trials)
            start = time.perf_counter()
            r = compile_for_device(default_scenario(rows, cols, robots), p=1, device="grid", lowered=True,
                                   bindings=BIND, routing=routing)  # fmt: skip
            seconds = time.perf_counter() - start
            total = sum(1 for g in r.routed.circuit.gates if len(g[1]) == 2)
            dev = r.routed.device
            window = max(r.logical.sections, key=lambda s: sum(1 for g in s.gates if len(g[1]) == 2))
            pairs = [g[1] for g in window.gates if len(g[1]) == 2]
            pos = Positions(tuple(r.routed.initial_layout), dev.num_qubits)
            ops = route_window(pairs, pos, dev, distances(dev), options=routing)  # type: ignore[arg-type]
            print(f"| {rows}x{cols}/{robots} | {seeds} | {trials} | {window_cx(ops):,} | {total:,} | "
                  f"{seconds:.1f} |", flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
