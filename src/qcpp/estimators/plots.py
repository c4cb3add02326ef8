"""Plot of the exact counts against the paper's estimates (matplotlib, Agg backend, saved atomically).

Two panels share the x axis, the grid size as its number of nodes ``rows * cols``: the CNOT count and the qubit
count, on log-log axes. Each robot count gets one colour; our exact counts are solid lines with dots, the
paper's estimates (:mod:`qcpp.estimators.paper`, ``re + 8r`` qubits) dashed lines with crosses. When several grids
have the same number of nodes (``3x4`` and ``4x3``), their mean is plotted. Only the smallest ``p`` and the first
SBF rule of the rows are drawn (named in the title).

Example:
    >>> import tempfile, os
    >>> from qcpp.estimators.estimate import Point, estimate_point
    >>> from qcpp.estimators.tables import make_rows
    >>> rows = make_rows([estimate_point(Point(2, 2, 1, 1)), estimate_point(Point(2, 3, 1, 1))], True)
    >>> path = os.path.join(tempfile.mkdtemp(), "plot.png")
    >>> plot_rows(rows, path) == path, os.path.getsize(path) > 1000
    (True, True)
"""

from __future__ import annotations

import os
from collections import defaultdict
from collections.abc import Sequence
from typing import Any

from qcpp.estimators.paper import paper_estimate
from qcpp.io.atomic import save_figure_atomic

__all__ = ["plot_rows"]


def _series(rows: Sequence[dict[str, Any]], key: str) -> dict[int, tuple[list[int], list[float]]]:
    acc: dict[int, dict[int, list[float]]] = defaultdict(lambda: defaultdict(list))
    for r in rows:
        acc[r["robots"]][r["rows"] * r["cols"]].append(float(r[key]))
    return {k: (sorted(v), [sum(v[n]) / len(v[n]) for n in sorted(v)]) for k, v in sorted(acc.items())}


def plot_rows(rows: Sequence[dict[str, Any]], path: str | os.PathLike[str]) -> str:
    """Draw the comparison plot and save it atomically as PNG (temporary file + ``os.replace``).

    Args:
        rows: rows from :func:`qcpp.estimators.tables.make_rows` (paper columns are computed if absent).
        path: output file.

    Returns:
        The path written, as a string.

    Raises:
        ValueError: no rows.
    """
    if not rows:
        raise ValueError("nothing to plot: no rows")
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    p_min = min(r["p"] for r in rows)
    rule = rows[0].get("rule", "exact")
    sel = [dict(r) for r in rows if r["p"] == p_min and r.get("rule", "exact") == rule]
    for r in sel:
        if "paper_cx" not in r:
            est = paper_estimate(r["rows"], r["cols"], r["robots"], r["p"])
            r["paper_cx"], r["paper_qubits"] = est.cx, est.qubits
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    panels = (("cx", "paper_cx", "CNOT count"), ("qubits", "paper_qubits", "qubits"))
    for ax, (ours, paper, label) in zip(axes, panels):
        ours_s, paper_s = _series(sel, ours), _series(sel, paper)
        for i, (k, (xs, ys)) in enumerate(ours_s.items()):
            colour = colours[i % len(colours)]
            ax.plot(xs, ys, "o-", color=colour, label=f"ours, {k} robot{'s' if k > 1 else ''}")
            pxs, pys = paper_s[k]
            ax.plot(pxs, pys, "x--", color=colour, alpha=0.7, label=f"paper, {k} robot{'s' if k > 1 else ''}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("grid size: nodes = rows x cols (log scale)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.set_title(f"{label}: ours (lowered) vs the paper's estimate")
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle(f"QAOA coverage path planning, p = {p_min}, rule = {rule}")
    fig.tight_layout()
    target = os.fspath(path)
    try:  # the folder must exist (qcpp.io.atomic: one rule for every output option)
        save_figure_atomic(fig, target, dpi=120)
    finally:
        plt.close(fig)
    return target
