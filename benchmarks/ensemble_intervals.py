"""How precise are the ensemble study's medians? Seeded bootstrap 95% intervals from the committed records.

The ensemble study (``examples/experiments/ensembles.py``) reports medians and quartiles over each cell's random
instances. The quartiles describe the spread of the instances; they say nothing about how well 30, 100 or 300
instances pin the median down. This script reads a results file of the study (default: the committed
``docs/results/ensembles.json``; nothing is re-run) and prints, per cell and depth, each median beside a percentile
bootstrap 95% interval: ``RESAMPLES`` resamples of the cell's instances with replacement (numpy's
``default_rng(seed)``, seed 0 unless ``--seed``), the median of each, and the 2.5% and 97.5% order statistics of
those medians. Medians as the study computes them (its ``quartiles``: numpy's linear interpolation, order statistics
when an infinite time is among the values). The instances of a cell are independent draws, so the interval is the
usual nonparametric one; where a median sits on a point mass (P(optimum) 0 or 1 on many instances) the interval is
narrow or collapses to that point.

Tables (Markdown):

1. **P(optimum)**: the default training's and the best found's (median [quartiles], then the median's 95%
   interval) and the share of instances where the default reaches half the best found (``p_opt >= 0.5 x
   best_p_opt``), with a bootstrap interval of that share.
2. **Time to the optimum with 99% probability** (seconds, median and its 95% interval): DFS, CP-SAT, SA, GA
   (wall-clock, so they move with the machine's load: the file's load average is printed) and QAOA (projected ideal
   device, training counted) at the chosen depths.
3. **Sampling only at the best-found angles over the fastest classical time**, per instance: median [quartiles]
   and the median's 95% interval. The numerator is a projected ideal-device shot time (the gate model of
   ``qcpp.simulate.time_to_solution``, readout included, no reset or repetition delay between shots) x the shots
   for 99% at the angles of a search that knows the optimum; the denominator is the wall-clock time of Python DFS
   or CP-SAT etc. on the machine that ran the study.
4. **<C> and a normalised approximation ratio**: the median of ``<C> - C_opt`` of the default training's state and
   of ``AR = (C_max - <C>) / (C_max - C_opt)`` (1 at the optimum, 0 at the worst feasible assignment), with the
   median's interval, and on how many instances ``<C>`` rose from the previous depth shown while P(optimum) rose
   too. ``<C>`` and ``C_opt`` are the records' ``expectation`` and ``optimum``; ``C_max``, the largest cost over the
   same basis (the simulator's feasible subspace), is not in the records and is computed here from each record's
   scenario (:meth:`qcpp.simulate.subspace.SubspaceQAOA.cost_diagonal`; a classical enumeration, seconds). Costs
   can be negative or zero, so ``<C> / C_opt`` is no measure; the range-normalised ratio is.

Run: ``python benchmarks/ensemble_intervals.py [docs/results/ensembles.json] [--depths 1,2,4,8] [--seed 0]``
(about half a minute: the ``C_max`` enumeration; ``--no-ar`` skips table 4).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections import defaultdict
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples" / "experiments"))
from ensembles import quartiles  # the study's own median

ROOT = Path(__file__).resolve().parents[1]
RESAMPLES = 2000
CLASSICAL = (("dfs", "DFS"), ("cpsat", "CP-SAT"), ("anneal", "SA"), ("genetic", "GA"))


def fmt(x: float) -> str:
    """Three significant digits, as the study's tables print them.

    >>> fmt(0.04751), fmt(math.inf), fmt(1234.0)
    ('0.0475', 'inf', '1.23e+03')
    """
    return f"{x:.3g}"


def median(values: Sequence[float]) -> float:
    """The study's median (linear interpolation; order statistics when ``inf`` is among the values)."""
    return quartiles(values)[0]


def bootstrap_median(values: Sequence[float], rng: np.random.Generator,
                     resamples: int = RESAMPLES) -> tuple[float, float]:
    """The percentile bootstrap 95% interval of the median of ``values``.

    Args:
        values: One value per instance (``inf`` allowed).
        rng: The generator the resamples draw from (seeded by the caller: the same seed gives the same interval).
        resamples: How many resamples of ``len(values)`` instances with replacement.

    Returns:
        ``(low, high)``: the 2.5% and 97.5% order statistics of the resamples' medians.

    Example:
        >>> lo, hi = bootstrap_median([0.0] * 10 + [1.0] * 10, np.random.default_rng(0))
        >>> 0.0 <= lo <= 0.5 <= hi <= 1.0
        True
    """
    a = np.asarray(values, dtype=float)
    draws = a[rng.integers(0, len(a), size=(resamples, len(a)))]
    # no interpolation through inf (which gives nan): the study's order statistics
    meds = np.percentile(draws, 50, axis=1, method="lower") if np.isinf(a).any() else np.median(draws, axis=1)
    meds.sort()
    return float(meds[int(0.025 * resamples)]), float(meds[math.ceil(0.975 * resamples) - 1])


def bootstrap_share(hits: Sequence[bool], rng: np.random.Generator, resamples: int = RESAMPLES) -> tuple[float, float]:
    """The percentile bootstrap 95% interval of the share of ``True`` among ``hits``.

    >>> bootstrap_share([True] * 10, np.random.default_rng(0))
    (1.0, 1.0)
    """
    a = np.asarray(hits, dtype=float)
    shares = np.sort(a[rng.integers(0, len(a), size=(resamples, len(a)))].mean(axis=1))
    return float(shares[int(0.025 * resamples)]), float(shares[math.ceil(0.975 * resamples) - 1])


def quartile_text(values: Sequence[float]) -> str:
    """``median [lower quartile, upper quartile]`` as the study prints it."""
    m, lo, hi = quartiles(values)
    return f"{fmt(m)} [{fmt(lo)}, {fmt(hi)}]"


def interval(values: Sequence[float], rng: np.random.Generator) -> str:
    lo, hi = bootstrap_median(values, rng)
    return f"{fmt(lo)}-{fmt(hi)}"


def table(head: Sequence[str], rows: list[Sequence[str]]) -> str:
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def qaoa_rows(rows: list[dict[str, Any]]) -> dict[tuple[str, int], list[dict[str, Any]]]:
    """The QAOA records by (cell, p), in instance order."""
    out: dict[tuple[str, int], list[dict[str, Any]]] = defaultdict(list)
    for r in rows:
        if r["method"] == "qaoa":
            out[(r["cell"], int(r["p"]))].append(r)
    for v in out.values():
        v.sort(key=lambda r: r["index"])
    return out


def levels(q: dict[tuple[str, int], list[dict[str, Any]]], cells: Sequence[str],
           depths: Sequence[int]) -> Iterator[tuple[str, int, list[dict[str, Any]]]]:
    """``(cell, p, records)`` for every cell and depth shown that has QAOA records, cell by cell."""
    for cell in cells:
        for p in depths:
            if q.get((cell, p)):
                yield cell, p, q[(cell, p)]


def tts(r: dict[str, Any]) -> float:
    return math.inf if r["tts_99"] is None else float(r["tts_99"])


def best_classical(rows: list[dict[str, Any]]) -> dict[str, float]:
    """The fastest classical 99% time per instance label."""
    best: dict[str, float] = {}
    for r in rows:
        if r["method"] in dict(CLASSICAL):
            best[r["instance"]] = min(best.get(r["instance"], math.inf), tts(r))
    return best


def cost_maxima(rows: list[dict[str, Any]]) -> dict[str, tuple[float, float]]:
    """``(C_min, C_max)`` over the simulator's basis per instance label, from the records' scenarios."""
    from qcpp.problem.scenario import scenario_from_dict
    from qcpp.simulate.subspace import SubspaceQAOA

    out: dict[str, tuple[float, float]] = {}
    for r in rows:
        if r["method"] == "qaoa" and r["instance"] not in out:
            c = SubspaceQAOA(scenario_from_dict(r["scenario"])).cost_diagonal()
            out[r["instance"]] = (float(c.min()), float(c.max()))
    return out


def main(argv: Sequence[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="?", type=Path, default=ROOT / "docs" / "results" / "ensembles.json")
    ap.add_argument("--depths", default="1,2,4,8", help="comma-separated depths to show (default 1,2,4,8)")
    ap.add_argument("--seed", type=int, default=0, help="the bootstrap's seed (default 0)")
    ap.add_argument("--no-ar", action="store_true", help="skip table 4 (its C_max enumeration)")
    args = ap.parse_args(argv)
    data = json.loads(args.results.read_text(encoding="utf-8"))
    rows, cfg = data["rows"], data["config"]
    depths = [int(d) for d in args.depths.split(",")]
    q = qaoa_rows(rows)
    cells = [c for c in cfg["cells"] if any((c, p) in q for p in depths)]
    rng = np.random.default_rng(args.seed)
    load = data.get("load_average") or [math.nan, math.nan]
    print(f"{args.results.name}: qcpp {data['qcpp_version']}, ensemble seed {cfg['seed']}; bootstrap: {RESAMPLES} "
          f"resamples, seed {args.seed}; percentile 95% intervals of the median")
    print()

    print("1. P(optimum): median [quartiles] and the median's 95% interval; share with default >= half the best "
          "found, and its 95% interval")
    print()
    out = []
    for cell, p, sel in levels(q, cells, depths):
        d, b = [r["p_opt"] for r in sel], [r["best_p_opt"] for r in sel]
        hits = [r["p_opt"] >= 0.5 * r["best_p_opt"] - 1e-12 for r in sel]
        lo, hi = bootstrap_share(hits, rng)
        out.append((cell, p, quartile_text(d), interval(d, rng), quartile_text(b), interval(b, rng),
                    f"{100 * sum(hits) / len(hits):.0f}% ({100 * lo:.0f}-{100 * hi:.0f}%)"))
    print(table(["cell", "p", "default P(opt)", "95% interval", "best found P(opt)", "95% interval",
                 "default >= half the best found"], out))
    print()

    print("2. Time to the optimum with 99% probability, seconds: median (95% interval of the median); classical: "
          f"wall-clock, load average {load[0]:.1f} at the study's start and {load[1]:.1f} at its end")
    print()
    out = []
    for cell in cells:
        cols = []
        for m, _ in CLASSICAL:
            v = [tts(r) for r in rows if r["method"] == m and r["cell"] == cell]
            cols.append(f"{fmt(median(v))} ({interval(v, rng)})")
        for p in depths:
            v = [tts(r) for r in q.get((cell, p), [])]
            cols.append(f"{fmt(median(v))} ({interval(v, rng)})" if v else "-")
        out.append((cell, *cols))
    print(table(["cell", *(label for _, label in CLASSICAL), *(f"QAOA p = {p}" for p in depths)], out))
    print()

    print("3. Sampling only at the best-found angles (projected ideal-device shots, no reset or repetition delay) over "
          "the fastest classical wall-clock time, per instance: median [quartiles], the median's 95% interval, "
          "instances below 1")
    print()
    classical = best_classical(rows)
    out = []
    for cell, p, sel in levels(q, cells, depths):
        ratio = [r["best_sampling_99"] / classical[r["instance"]] for r in sel]
        below = f"{sum(x < 1 for x in ratio)} of {len(ratio)}"
        out.append((cell, p, quartile_text(ratio), interval(ratio, rng), below))
    print(table(["cell", "p", "sampling / best classical", "95% interval", "below 1"], out))
    if args.no_ar:
        return
    print()

    print("4. The default training's <C>: median of <C> - C_opt, and of AR = (C_max - <C>) / (C_max - C_opt) with "
          "the median's 95% interval; instances where <C> rose from the previous depth shown while P(opt) rose")
    print()
    span = cost_maxima(rows)
    out = []
    for cell in cells:
        prev: list[dict[str, Any]] | None = None
        for p in depths:
            sel = q.get((cell, p), [])
            if not sel:
                continue
            for r in sel:  # the records' optimum is the minimum over the same basis
                assert abs(span[r["instance"]][0] - r["optimum"]) < 1e-9, (r["instance"], span[r["instance"]])
            gap = [r["expectation"] - r["optimum"] for r in sel]
            ar = [(span[r["instance"]][1] - r["expectation"]) / (span[r["instance"]][1] - r["optimum"])
                  if span[r["instance"]][1] > r["optimum"] else 1.0 for r in sel]
            rose = "-" if prev is None else str(sum(
                a["expectation"] > b["expectation"] + 1e-9 and a["p_opt"] > b["p_opt"] + 1e-12
                for a, b in zip(sel, prev)))
            out.append((cell, p, fmt(median(gap)), quartile_text(ar), interval(ar, rng), rose))
            prev = sel
    print(table(["cell", "p", "<C> - C_opt", "AR", "95% interval", "<C> up, P(opt) up"], out))


if __name__ == "__main__":
    main()
