"""Do the committed ensemble medians hold on a fresh draw? Compare two results files of ``ensembles.py``.

The ensemble study's medians should describe the generator, not the seed: a fresh draw (the same cells, density and
training, other seeds) should give medians within a factor of 2 of the committed ones. This script compares two
``results/*.json`` files of ``examples/experiments/ensembles.py`` cell by cell:

* per depth ``p``: the median P(optimum) of the default training and of the expensive search's best angles;
* per method: the median time to the optimum with 99% probability (DFS, CP-SAT, SA, GA; QAOA at every depth).
  The classical times are wall-clock measurements, so they also move with the machine's load on the two days.

Medians as the study computes them (its ``quartiles``: numpy's linear interpolation, order statistics when an
infinite time is among the values).

It prints one row per median (committed, fresh, fresh / committed, within 2x) and a summary line; exit code 0 when
every median is within 2x (two infinite medians agree: neither draw reached the optimum there).

Usage::

    python examples/experiments/ensembles.py --seed 1 --cells 3x3/1 3x3/2 --out /tmp/fresh --name fresh
    python benchmarks/ensemble_fresh_draw.py docs/results/ensembles.json /tmp/fresh/results/fresh.json
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples" / "experiments"))
from ensembles import quartiles  # the study's own median

Key = tuple[str, str, int]
"""(cell, quantity, p): ``p`` is 0 for the classical methods."""

CLASSICAL = ("dfs", "cpsat", "anneal", "genetic")


def medians(path: Path) -> tuple[dict[Key, float], dict[str, Any]]:
    """The medians of one results file by (cell, quantity, p), and the file's config.

    Quantities: ``default P(opt)``, ``best P(opt)``, ``QAOA 99% s`` (per depth) and ``<method> 99% s``.

    Example:
        >>> import tempfile, os
        >>> rows = [{"cell": "3x3/1", "method": "qaoa", "p": 1, "p_opt": v, "best_p_opt": 1.0, "tts_99": 2.0}
        ...         for v in (0.1, 0.2, 0.9)]
        >>> f = os.path.join(tempfile.mkdtemp(), "r.json")
        >>> _ = open(f, "w").write(json.dumps({"config": {"seed": 0}, "rows": rows}))
        >>> medians(Path(f))[0][("3x3/1", "default P(opt)", 1)]
        0.2
    """
    data = json.loads(path.read_text(encoding="utf-8"))
    return medians_of(data["rows"]), data.get("config", {})


def medians_of(rows: list[dict[str, Any]]) -> dict[Key, float]:
    """The medians of a results file's ``rows`` by (cell, quantity, p) (:func:`medians`)."""
    values: dict[Key, list[float]] = defaultdict(list)
    for r in rows:
        cell, method = r["cell"], r["method"]
        if method == "qaoa":
            p = int(r["p"])
            values[(cell, "default P(opt)", p)].append(float(r["p_opt"]))
            values[(cell, "best P(opt)", p)].append(float(r["best_p_opt"]))
            values[(cell, "QAOA 99% s", p)].append(float(r["tts_99"]))
        elif method in CLASSICAL:
            values[(cell, f"{method} 99% s", 0)].append(float(r["tts_99"]))
    return {k: quartiles(v)[0] for k, v in values.items()}


def ratio(committed: float, fresh: float) -> float:
    """``fresh / committed``; 1 when both are infinite or both 0 (the draws agree), inf when only one is.

    >>> ratio(2.0, 3.0), ratio(math.inf, math.inf), ratio(0.0, 0.0), ratio(1.0, math.inf)
    (1.5, 1.0, 1.0, inf)
    """
    if committed == fresh:
        return 1.0
    if committed == 0 or math.isinf(committed) or math.isinf(fresh):
        return math.inf
    return fresh / committed


def within(r: float, factor: float = 2.0) -> bool:
    """Whether a ratio is within ``factor`` either way.

    >>> within(1.9), within(0.4), within(math.inf)
    (True, False, False)
    """
    return 1 / factor <= r <= factor


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("committed", type=Path, help="the committed results file (docs/results/ensembles.json)")
    ap.add_argument("fresh", type=Path, help="a results file of the same study with other seeds")
    ap.add_argument("--factor", type=float, default=2.0, help="the agreement asked for (default 2)")
    args = ap.parse_args(argv)
    old, old_cfg = medians(args.committed)
    new, new_cfg = medians(args.fresh)
    print(f"committed: {args.committed} (seed {old_cfg.get('seed')}); fresh: {args.fresh} (seed {new_cfg.get('seed')})")
    differ = [k for k in ("density", "p_max", "search", "runs") if old_cfg.get(k) != new_cfg.get(k)]
    if differ:
        print(f"warning: the two runs differ in {differ}")
    shared = sorted(set(old) & set(new))
    print("| cell | quantity | p | committed median | fresh median | fresh / committed | within |")
    print("|---|---|---:|---:|---:|---:|---|")
    agree = 0
    for key in shared:
        r = ratio(old[key], new[key])
        ok = within(r, args.factor)
        agree += ok
        cell, quantity, p = key
        print(f"| {cell} | {quantity} | {p or '-'} | {old[key]:.3g} | {new[key]:.3g} | {r:.3g} | "
              f"{'yes' if ok else 'NO'} |")
    print(f"\n{agree} of {len(shared)} medians within {args.factor:g}x")
    return 0 if agree == len(shared) and shared else 1


if __name__ == "__main__":
    sys.exit(main())
