"""The balance arithmetic's one large window on the medial layout: routed CX per SABRE seeds and trials.

Run: ``python benchmarks/balance_window.py [--quick]`` (``--quick``: 4x4/2 only).

Per two-robot default scenario (p = 1, angles bound, ``qcpp compile --device grid``'s path: the medial layout,
``phase_layout="medial"``), and per setting of the wider search on the large window
(:data:`qcpp.routing.sabre.WIDE_WINDOW_SEEDS` seeds of :data:`qcpp.routing.sabre.WIDE_WINDOW_TRIALS` SABRE
trials, tried after the :data:`qcpp.routing.sabre.LARGE_WINDOW_SEEDS` = 8 seeds of 16 trials; 0 seeds: none;
the cheapest whole window wins), columns:

* ``balance cx``: the routed CX of the largest window (the balance gadget: compute, register phase, uncompute),
  routed from home as :func:`qcpp.routing.sabre.route_windows` routes it;
* ``compile cx``: the routed CX of the whole circuit (what ``qcpp compile SCEN --device grid --lowered`` writes);
* ``s``: seconds of the compile (wall time on a shared machine: indicative only).
"""

from __future__ import annotations

import sys
import time

from qcpp.devices.device import distances
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.problem.presets import default_scenario
from qcpp.routing import sabre as routing

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
SETTINGS = ((0, 128), (8, 128), (16, 16), (16, 128))


def main(argv: list[str]) -> None:
    shapes = [(4, 4, 2)] if "--quick" in argv else [(4, 4, 2), (5, 5, 2)]
    kept = routing.WIDE_WINDOW_SEEDS, routing.WIDE_WINDOW_TRIALS
    print("| scenario | wide seeds | wide trials | balance cx | compile cx | s |")
    print("|---|---:|---:|---:|---:|---:|")
    try:
        for rows, cols, robots in shapes:
            for seeds, trials in SETTINGS:
                routing.WIDE_WINDOW_SEEDS, routing.WIDE_WINDOW_TRIALS = seeds, trials
                start = time.perf_counter()
                r = compile_for_device(default_scenario(rows, cols, robots), p=1, device="grid", lowered=True,
                                       bindings=BIND)  # fmt: skip
                seconds = time.perf_counter() - start
                total = sum(1 for g in r.routed.circuit.gates if len(g[1]) == 2)
                dev = r.routed.device
                window = max(r.logical.sections, key=lambda s: sum(1 for g in s.gates if len(g[1]) == 2))
                pairs = [g[1] for g in window.gates if len(g[1]) == 2]
                pos = routing.Positions(tuple(r.routed.initial_layout), dev.num_qubits)
                ops = routing.route_window(pairs, pos, dev, distances(dev))  # type: ignore[arg-type]
                print(f"| {rows}x{cols}/{robots} | {seeds} | {trials} | {routing.window_cx(ops):,} | {total:,} | "
                      f"{seconds:.1f} |", flush=True)  # fmt: skip
    finally:
        routing.WIDE_WINDOW_SEEDS, routing.WIDE_WINDOW_TRIALS = kept


if __name__ == "__main__":
    main(sys.argv[1:])
