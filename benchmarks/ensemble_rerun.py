"""Does a rerun of the ensemble study give the committed records? Compare two results files of the same instances.

``examples/experiments/ensembles.py`` is seeded throughout, so two runs of one qcpp version with one seed compute
the same instances with the same starts. On one machine they give the same records but for the wall-clock fields;
on another machine (another CPU, another numpy or scipy build) floating-point rounding differs in the last bits, and
the local optimizers of the training and the search, run for many iterations on the deeper circuits, can amplify
that into another local optimum. This script shows how far that goes, row by row:

* per cell and depth: the QAOA rows whose default P(optimum) or best-found P(optimum) differ by more than a
  relative ``1e-6`` between the two files, and the largest relative difference;
* every classical record's fields that are not wall-clock times (costs, optima, counts of assignments and
  successes, CP-SAT's sequence of improving costs): equal or not;
* the two runs' whole-study seconds and load averages.

The exit code is 0 when both files hold the same instances (same scenarios) and every classical record agrees.

Usage::

    python examples/experiments/ensembles.py --out /tmp/rerun
    python benchmarks/ensemble_rerun.py docs/results/ensembles.json /tmp/rerun/results/ensembles.json
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

WALL_CLOCK = frozenset({"seconds", "tts_99", "run_seconds", "tts_99_range", "improvements"})
"""Record fields measured in wall-clock time (CP-SAT's ``improvements`` pair a time with a cost: the costs are
compared apart)."""

Key = tuple[str, int, str, int]
"""(cell, index, method, p): one record; ``p`` is 0 for the classical methods."""


def records(path: Path) -> tuple[dict[Key, dict[str, Any]], dict[str, Any]]:
    """The records of one results file by :data:`Key`, and the file's top-level fields other than its rows."""
    data = json.loads(path.read_text(encoding="utf-8"))
    rows = {(r["cell"], int(r["index"]), r["method"], int(r.get("p", 0))): r for r in data["rows"]}
    return rows, {k: v for k, v in data.items() if k != "rows"}


def relative(a: float, b: float) -> float:
    """``|a - b| / |b|`` (0 when equal, ``a`` itself when ``b`` is 0).

    >>> relative(1.0, 1.0), relative(1.5, 1.0), relative(0.25, 0.0)
    (0.0, 0.5, 0.25)
    """
    if a == b:
        return 0.0
    return abs(a - b) / abs(b) if b else abs(a)


def classical_fields(r: dict[str, Any]) -> dict[str, Any]:
    """A classical record without its wall-clock fields (CP-SAT's improving costs kept, their times dropped).

    >>> classical_fields({"method": "cpsat", "cost": 2.0, "seconds": 0.1, "improvements": [[0.01, 8.0], [0.02, 2.0]]})
    {'method': 'cpsat', 'cost': 2.0, 'improving_costs': [8.0, 2.0]}
    """
    out = {k: v for k, v in r.items() if k not in WALL_CLOCK}
    if "improvements" in r:
        out["improving_costs"] = [cost for _, cost in r["improvements"]]
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("committed", type=Path, help="the committed results file (docs/results/ensembles.json)")
    ap.add_argument("rerun", type=Path, help="a results file of the same study, seed and version")
    ap.add_argument("--tolerance", type=float, default=1e-6, help="relative difference that counts (default 1e-6)")
    args = ap.parse_args(argv)
    old, old_meta = records(args.committed)
    new, new_meta = records(args.rerun)
    for label, meta in (("committed", old_meta), ("rerun", new_meta)):
        load = meta.get("load_average") or ["?", "?"]
        print(f"{label}: qcpp {meta.get('qcpp_version')}, seed {meta.get('config', {}).get('seed')}, "
              f"{meta.get('seconds', 0):.0f} s, load average {load[0]}-{load[1]}")
    shared = sorted(set(old) & set(new))
    scenarios_differ = sum(old[k]["scenario"] != new[k]["scenario"] for k in shared)
    classical_differ = [k for k in shared if k[2] != "qaoa" and classical_fields(old[k]) != classical_fields(new[k])]
    per: dict[tuple[str, int], list[float]] = defaultdict(list)
    for k in shared:
        if k[2] == "qaoa":
            per[(k[0], k[3])].append(max(relative(new[k]["p_opt"], old[k]["p_opt"]),
                                         relative(new[k]["best_p_opt"], old[k]["best_p_opt"])))
    print(f"\n{len(shared)} records in both files ({len(old)} committed, {len(new)} rerun); "
          f"{scenarios_differ} with another scenario")
    first = f", first {classical_differ[0]}" if classical_differ else ""
    print(f"classical records (wall-clock fields aside): {len(classical_differ)} of "
          f"{sum(k[2] != 'qaoa' for k in shared)} differ{first}")
    print(f"\n| cell | p | QAOA rows | P(optimum) or best found differs by > {args.tolerance:g} | largest relative |")
    print("|---|---:|---:|---:|---:|")
    total = differ = 0
    cells = list(dict.fromkeys(k[0] for k in old))  # the study's order of cells
    for (cell, p), diffs in sorted(per.items(), key=lambda kv: (cells.index(kv[0][0]), kv[0][1])):
        n = sum(d > args.tolerance for d in diffs)
        total += len(diffs)
        differ += n
        print(f"| {cell} | {p} | {len(diffs)} | {n} | {max(diffs):.2g} |")
    print(f"\n{differ} of {total} QAOA rows differ by more than {args.tolerance:g} in P(optimum) or the best found")
    return 0 if shared and not scenarios_differ and not classical_differ else 1


if __name__ == "__main__":
    sys.exit(main())
