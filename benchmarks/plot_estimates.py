"""Plot of the estimates against grid size: qubits, CNOTs, T gates and physical qubits, 1..8 robots, up to 40x40.

Run: ``python benchmarks/plot_estimates.py [MAX_SIDE] [OUT]`` (defaults ``40`` and
``docs/figures/estimates_scaling.png``). Square grids ``n x n`` for ``n = 2 .. MAX_SIDE`` (every second size above
10), default placement with 1..8 robots (where the grid hosts them), ``p = 1``, default options, from
:func:`qcpp.estimators.estimate.estimate_point` with ``--physical`` defaults (QDK estimator, ``qubit_gate_ns_e3``,
surface code, error budget 1e-3) and the depth bound (fast at every size; the physical qubits computed from it are
approximate, labelled so; ``qcpp estimate --physical --depth exact`` gives the exact-depth figures); T is the
logical-AND model's total (epsilon 1e-3). Prints the plotted numbers
as a Markdown table (every fourth size) and the time taken.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point
from qcpp.estimators.plots import PLOT_METRICS
from qcpp.io.atomic import save_figure_atomic
from qcpp.problem.presets import max_default_robots

ROOT = Path(__file__).resolve().parents[1]
PANELS = (
    ("qubits", "logical qubits", "qubits"),
    ("cx", "CNOT gates (lowered)", "cx"),
    ("t", "T gates (logical-AND model, eps 1e-3)", "ft_total_t"),
    ("physical", "physical qubits (QDK estimator, qubit_gate_ns_e3)", "physical_qubits"),
)
"""Series key, panel title, and the estimate column it plots (its axis label: qcpp.estimators.plots.PLOT_METRICS)."""


def sizes(max_side: int) -> list[int]:
    """2..10, then every second size up to ``max_side`` (and ``max_side`` itself)."""
    out = [n for n in range(2, min(max_side, 10) + 1)] + list(range(12, max_side + 1, 2))
    return sorted({*out, max_side})


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("max_side", type=int, nargs="?", default=40, help="largest grid side (default 40)")
    parser.add_argument("out", type=Path, nargs="?", default=ROOT / "docs" / "figures" / "estimates_scaling.png",
                        help="the figure (default docs/figures/estimates_scaling.png)")
    args = parser.parse_args(argv)
    max_side, out = args.max_side, args.out
    options = EstimateOptions(depth="bound", physical=True)
    start = time.perf_counter()
    data: dict[int, dict[str, list[float]]] = {}
    for robots in range(1, 9):
        series: dict[str, list[float]] = {"n": [], "qubits": [], "cx": [], "t": [], "physical": []}
        for n in sizes(max_side):
            if robots > max_default_robots(n, n):
                continue
            est = estimate_point(Point(n, n, robots, 1), options)
            assert est.physical is not None
            series["n"].append(n)
            series["qubits"].append(est.qubits)
            series["cx"].append(est.cost.cx)
            series["t"].append(est.fault_tolerant.total_t)
            series["physical"].append(est.physical.physical_qubits)
        data[robots] = series
    seconds = time.perf_counter() - start

    import matplotlib
    import matplotlib.ticker

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for ax, (key, label, column) in zip(axes.flat, PANELS):
        for robots, s in data.items():
            ax.plot(s["n"], s[key], "o-", ms=3, label=f"{robots} robot{'s' if robots > 1 else ''}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ticks = [n for n in (2, 3, 4, 6, 10, 20, 30, 40) if n <= max_side]
        ax.set_xticks(ticks, [str(n) for n in ticks])
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel("grid side n (n x n grid, log scale)")
        ax.set_ylabel(PLOT_METRICS[column].axis_label + ", log scale")
        ax.set_title(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=8, ncol=2)
    fig.suptitle(f"qcpp estimates, p = 1, default placement, grids 2x2..{max_side}x{max_side} (from gadget costs)")
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    try:
        save_figure_atomic(fig, str(out), dpi=110)
    finally:
        plt.close(fig)
    print("| grid | robots | qubits | CNOT | T, FT model (ft_total_t) | "
          "physical qubits (from the depth bound, approximate) |")
    print("|---|---:|---:|---:|---:|---:|")
    for robots in (1, 4, 8):
        s = data[robots]
        for i, n in enumerate(s["n"]):
            if n in (4, 10, 20, 30, 40) or n == max_side:
                print(
                    f"| {n}x{n} | {robots} | {s['qubits'][i]:,.0f} | {s['cx'][i]:,.0f} | {s['t'][i]:,.0f} | "
                    f"{s['physical'][i]:,.0f} |"
                )
    print(f"wrote {out} in {seconds:.1f} s of estimates")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
