"""The balance arithmetic's one large window on the medial layout: routed CX per SABRE seeds and trials.

Run: ``python benchmarks/balance_window.py [--quick]`` (``--quick``: 4x4/2 only);
``python benchmarks/balance_window.py --cells``: the same window of 4x4/2 on the heavy-hex cells (``qcpp compile
--device heavy-hex``'s path) per number of SABRE seeds and trials of its large-window search
(``cell_large_window_seeds``, ``cell_large_window_trials``; compile's is 32 x 64): the window's routed CX and the
seconds its routing takes.

Per two-robot default scenario (p = 1, angles bound, ``qcpp compile --device grid``'s path: the medial layout,
``phase_layout="medial"``), and per setting of the wider search on the large window
(``wide_window_seeds`` seeds of ``wide_window_trials`` SABRE trials of :class:`qcpp.routing.options.RoutingOptions`,
tried after the ``large_window_seeds`` = 8 seeds of 16 trials; 0 seeds: none;
the cheapest whole window wins), columns:

* ``balance cx``: the routed CX of the largest window (the balance gadget: compute, register phase, uncompute),
  routed from home as :func:`qcpp.routing.windows.route_windows` routes it (the register phase's blocks in any
  order where that is cheaper: :mod:`qcpp.routing.commuting`);
* ``in written order``: the same window with the register phase routed by SABRE in the order written
  (``commuting_phases=False``);
* ``compile cx``: the routed CX of the whole circuit (what ``qcpp compile SCEN --device grid --lowered`` writes);
* ``s``: seconds of the compile (wall time on a shared machine: indicative only).
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace

from qcpp.hardware.device import distances
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.problem.presets import default_scenario
from qcpp.routing.options import DEFAULT_ROUTING
from qcpp.routing.sabre import window_cx
from qcpp.routing.windows import Positions, commuting_middle, route_window

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
SETTINGS = ((0, 128), (8, 128), (16, 16), (16, 128))


CELL_SETTINGS = ((8, 16), (32, 16), (8, 64), (16, 64), (32, 64), (64, 64), (128, 64))


def cells() -> None:
    """The balance window of 4x4/2 on the heavy-hex cells, routed per (seeds, trials) of its search."""
    from qcpp.routing.context import RoutingContext

    r = compile_for_device(default_scenario(4, 4, 2), p=1, device="heavy-hex", lowered=True, bindings=BIND)
    dev = r.routed.device
    dist = distances(dev)
    window = max(r.logical.sections, key=lambda s: sum(1 for g in s.gates if len(g[1]) == 2))
    pairs = [g[1] for g in window.gates if len(g[1]) == 2]
    commuting = commuting_middle(window.gates) is not None
    print(f"4x4/2 on {dev.name}: the balance window ({len(pairs):,} two-qubit gates all-to-all)\n")
    print("| seeds | trials | balance cx | s |")
    print("|---:|---:|---:|---:|")
    for seeds, trials in CELL_SETTINGS:
        routing = replace(DEFAULT_ROUTING, cell_large_window_seeds=seeds, cell_large_window_trials=trials).for_cells()
        start = time.perf_counter()
        pos = Positions(tuple(r.routed.initial_layout), dev.num_qubits)
        ops = route_window(pairs, pos, dev, dist, options=routing, context=RoutingContext(), commuting=commuting)  # type: ignore[arg-type]
        print(f"| {seeds} | {trials} | {window_cx(ops):,} | {time.perf_counter() - start:.1f} |", flush=True)


def main(argv: list[str]) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="4x4/2 only")
    parser.add_argument("--cells", action="store_true", help="the window of 4x4/2 on the heavy-hex cells")
    args = parser.parse_args(argv)
    if args.cells:
        cells()
        return
    shapes = [(4, 4, 2)] if args.quick else [(4, 4, 2), (5, 5, 2)]
    print("| scenario | wide seeds | wide trials | balance cx | in written order | compile cx | s |")
    print("|---|---:|---:|---:|---:|---:|---:|")
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
            commuting = commuting_middle(window.gates) is not None
            routed = []
            for options in (routing, replace(routing, commuting_phases=False)):
                pos = Positions(tuple(r.routed.initial_layout), dev.num_qubits)
                ops = route_window(pairs, pos, dev, distances(dev), options=options, commuting=commuting)  # type: ignore[arg-type]
                routed.append(window_cx(ops))
            print(f"| {rows}x{cols}/{robots} | {seeds} | {trials} | {routed[0]:,} | {routed[1]:,} | {total:,} | "
                  f"{seconds:.1f} |", flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
