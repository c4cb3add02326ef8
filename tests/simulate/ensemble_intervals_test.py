"""benchmarks/ensemble_intervals.py: bootstrap intervals of the ensemble medians, and the docs that paste them.

docs/ensembles.md pastes the script's tables 1 to 3 (P(optimum), the 99% times, sampling alone against the best
classical time); the QAOA table of the README and of docs/index.md holds medians [quartiles] and times those tables
print.
"""

from __future__ import annotations

import functools
import io
import re
from contextlib import redirect_stdout
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from .script_module import load_script

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "benchmarks" / "ensemble_intervals.py"


@functools.cache
def _script() -> ModuleType:
    return load_script(SCRIPT, "ensemble_intervals")


@functools.cache
def _printed_tables() -> list[str]:
    """The Markdown tables the script prints for the committed records (table 4 left out: its C_max enumeration)."""
    out = io.StringIO()
    with redirect_stdout(out):
        _script().main(["--no-ar"])
    return [t.rstrip("\n") for t in re.findall(r"((?:^\|.*\n?)+)", out.getvalue(), flags=re.M)]


def test_the_interval_is_seeded_and_brackets_the_median() -> None:
    s = _script()
    values = np.random.default_rng(5).exponential(size=101)
    lo, hi = s.bootstrap_median(values, np.random.default_rng(0))
    assert (lo, hi) == s.bootstrap_median(values, np.random.default_rng(0))
    assert lo < np.median(values) < hi
    assert hi - lo < np.percentile(values, 75) - np.percentile(values, 25)  # the median is pinned tighter


def test_a_point_mass_collapses_the_interval_and_inf_is_no_nan() -> None:
    s = _script()
    assert s.bootstrap_median([0.25] * 40, np.random.default_rng(0)) == (0.25, 0.25)
    lo, hi = s.bootstrap_median([1.0, 2.0, np.inf, np.inf, np.inf], np.random.default_rng(0))
    assert lo <= 2.0 and hi == np.inf
    assert s.bootstrap_share([True, False] * 50, np.random.default_rng(0))[0] < 0.5


def test_ensembles_md_pastes_the_script_s_tables() -> None:
    page = (ROOT / "docs" / "ensembles.md").read_text(encoding="utf-8")
    tables = _printed_tables()
    assert len(tables) == 3
    for k, table in enumerate(tables, start=1):
        assert table in page, f"docs/ensembles.md does not paste table {k} of benchmarks/ensemble_intervals.py"


@pytest.mark.parametrize("page", ["README.md", "docs/index.md"])
def test_the_readme_qaoa_table_holds_the_script_s_medians(page: str) -> None:
    text = (ROOT / page).read_text(encoding="utf-8")
    start = text.index("| cell | p | P(opt), default training |")
    readme = [line.strip("|").split("|") for line in text[start:text.index("\n\n", start)].splitlines()[2:]]
    p_opt, times = ([[c.strip() for c in line.strip("|").split("|")] for line in t.splitlines()[2:]]
                    for t in _printed_tables()[:2])
    by_depth = {(r[0], r[1]): r for r in p_opt}
    by_cell = {r[0]: r for r in times}
    depths = [h.strip().removeprefix("QAOA p = ") for h in _printed_tables()[1].splitlines()[0].strip("|").split("|")]
    assert len(readme) >= 5
    for row in readme:
        cell, p, default, best, qaoa, dfs, cpsat = (c.strip() for c in row)
        key = cell.replace(" ", "")
        assert (default, best) == (by_depth[(key, p)][2], by_depth[(key, p)][4]), (page, row)
        median = {h: c.split(" (")[0] for h, c in zip(depths, by_cell[key])}
        assert (qaoa, dfs, cpsat) == (median[p], median["DFS"], median["CP-SAT"]), (page, row)
