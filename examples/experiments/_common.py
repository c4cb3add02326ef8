"""Shared plumbing of the experiment scripts: options, output paths, tables (terminal + Markdown), atomic PNGs,
and the per-row records (``results/<name>.json``) that ``tests/simulate/results_freshness_test.py`` recomputes.

Presentation only; every computation the scripts report lives in the library (``qcpp.simulate.success``,
``qcpp.simulate.state_measures``, ``qcpp.training.layerwise``, ``qcpp.training.training``, ``qcpp.problem.solvers``).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from qcpp.io.atomic import save_figure_atomic, write_text_atomic
from qcpp.training.qaoa_solver import SINGLE_START

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"


def two_robot_cases(quick: bool) -> list[tuple[str, Any]]:
    """The two-robot scenarios of the mixer-only studies, each with the source its rows record: two_robots_4x4,
    and unless ``quick`` also the open 4x4 and two_robots_5x5."""
    from qcpp.problem.presets import default_scenario
    from qcpp.problem.scenario_io import load_scenario

    cases: list[tuple[str, Any]] = [("examples/two_robots_4x4.toml", load_scenario(EXAMPLES / "two_robots_4x4.toml"))]
    if not quick:
        cases += [("default_scenario(4, 4, 2)", default_scenario(4, 4, 2)),
                  ("examples/two_robots_5x5.toml", load_scenario(EXAMPLES / "two_robots_5x5.toml"))]  # fmt: skip
    return cases


@dataclass(frozen=True)
class Options:
    quick: bool
    out: Path
    seed: int

    @property
    def figures(self) -> Path:
        return self.out / "figures"

    @property
    def results(self) -> Path:
        return self.out / "results"


def fresh_output_folder() -> Path:
    """A new folder name under the current directory (``qcpp-experiments-<date>-<time>``, numbered if taken): the
    scripts never overwrite the committed ``docs/results`` and ``docs/figures`` unless asked with ``--out docs``."""
    stem = Path.cwd() / f"qcpp-experiments-{time.strftime('%Y%m%d-%H%M%S')}"
    out, n = stem, 1
    while out.exists():
        n += 1
        out = stem.with_name(f"{stem.name}-{n}")
    return out


def parse(description: str, argv: Sequence[str] | None) -> Options:
    """``[--quick] [--out DIR] [--seed N]``; outputs go to ``DIR/figures`` and ``DIR/results`` (default: a fresh
    folder under the current directory, :func:`fresh_output_folder`; ``--out docs`` regenerates the committed
    results)."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--quick", action="store_true", help="reduced run (seconds), for the smoke test")
    ap.add_argument(
        "--out", type=Path, default=None,
        help="output root (figures/ and results/ below it); default: a new qcpp-experiments-* folder here; "
        "--out docs regenerates the committed results",
    )  # fmt: skip
    ap.add_argument("--seed", type=int, default=0, help="base seed")
    ns = ap.parse_args(argv)
    opts = Options(quick=ns.quick, out=fresh_output_folder() if ns.out is None else ns.out, seed=ns.seed)
    opts.figures.mkdir(parents=True, exist_ok=True)
    opts.results.mkdir(parents=True, exist_ok=True)
    return opts


@dataclass
class Table:
    """A titled table printed to the terminal (rich if available) and rendered as Markdown."""

    title: str
    headers: list[str]
    rows: list[list[Any]] = field(default_factory=list)

    def add(self, *cells: Any) -> None:
        self.rows.append([_fmt(c) for c in cells])

    def markdown(self) -> str:
        head = "| " + " | ".join(self.headers) + " |"
        sep = "|" + "|".join("---" for _ in self.headers) + "|"
        body = ["| " + " | ".join(str(c) for c in r) + " |" for r in self.rows]
        return "\n".join([f"**{self.title}**", "", head, sep, *body, ""])

    def show(self) -> None:
        try:
            from rich.console import Console
            from rich.table import Table as RichTable
        except ImportError:  # plain text
            print(self.title)
            print("\t".join(self.headers))
            for r in self.rows:
                print("\t".join(str(c) for c in r))
            return
        from rich.markup import escape

        t = RichTable(title=escape(self.title))
        for h in self.headers:
            t.add_column(escape(h))
        for r in self.rows:
            t.add_row(*(escape(str(c)) for c in r))
        Console(width=max(120, min(200, 20 * len(self.headers)))).print(t)


def _fmt(v: Any) -> str:
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        if v != v or v in (float("inf"), float("-inf")):
            return str(v)
        if v != 0 and (abs(v) < 1e-3 or abs(v) >= 1e6):
            return f"{v:.3g}"
        return f"{v:.4g}"
    return str(v)


def write_results(
    opts: Options, name: str, command: str, tables: Sequence[Table], notes: Sequence[str] = (), extra: str = ""
) -> Path:
    """Print the tables and write them (with the producing command, notes as bullets and ``extra`` Markdown)
    to ``results/<name>.md``."""
    for t in tables:
        t.show()
    import qcpp

    parts = [f"<!-- generated by `{command}` with qcpp {qcpp.__version__}; do not edit -->", ""]
    if opts.quick:
        parts += ["*(quick mode: reduced run, not the documented numbers)*", ""]
    for t in tables:
        parts += [t.markdown()]
    if notes:
        parts += [*(f"- {n}" for n in notes), ""]
    if extra:
        parts += [extra.rstrip("\n"), ""]
    path = opts.results / f"{name}.md"
    write_text_atomic(path, "\n".join(parts))
    print(f"wrote {path}")
    return path


def save_figure(fig: Any, path: Path, dpi: int = 130) -> Path:
    """Save a matplotlib figure as PNG, whole or not at all (:func:`qcpp.io.atomic.save_figure_atomic`)."""
    save_figure_atomic(fig, path, dpi=dpi, bbox_inches="tight")
    print(f"wrote {path}")
    return path


def command_line(script: str, opts: Options) -> str:
    extra = " --quick" if opts.quick else ""
    return f"python examples/experiments/{script}{extra}"


def record(scenario: Any, options: dict[str, Any], **fields: Any) -> dict[str, Any]:
    """One result row: its scenario (``qcpp.problem.scenario.scenario_to_dict``), its options, the qcpp version and
    ``fields`` (the results)."""
    import qcpp
    from qcpp.problem.scenario import scenario_to_dict

    return {"scenario": scenario_to_dict(scenario), "options": options, "qcpp_version": qcpp.__version__, **fields}


def write_records(opts: Options, name: str, command: str, rows: Sequence[dict[str, Any]], **extra: Any) -> Path:
    """``results/<name>.json``: ``{qcpp_version, command, **extra, rows}``, whole or not at all."""
    import json

    import numpy as np

    import qcpp

    def default(x: Any) -> Any:
        if isinstance(x, (np.floating, np.integer, np.bool_)):
            return x.item()
        if isinstance(x, np.ndarray):
            return x.tolist()
        raise TypeError(type(x))

    dump = {"qcpp_version": qcpp.__version__, "command": command, **extra, "rows": list(rows)}
    path = opts.results / f"{name}.json"
    write_text_atomic(path, json.dumps(dump, indent=1, default=default) + "\n")
    print(f"wrote {path}")
    return path


def circuit_columns(scenario: Any, p: int) -> dict[str, int]:
    """The compiled depth-``p`` circuit's qubits, exact depth, two-qubit depth and gate count (the cheap,
    recomputable part of a QAOA row; :func:`qcpp.estimators.estimate.estimate_point`)."""
    from qcpp.estimators.estimate import EstimateOptions, Point, estimate_point

    est = estimate_point(Point.from_scenario(scenario, p), EstimateOptions(depth="exact"))
    assert est.depth is not None
    return {"qubits": est.qubits, "depth": est.depth.depth, "two_qubit_depth": est.depth.two_qubit_depth,
            "gates": est.cost.total}


def pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    return plt


STUDY_SCHEDULE: dict[str, Any] = {"restart_every_level": SINGLE_START["restart_every_level"],
                                  "gibbs_eta_sigma": SINGLE_START["gibbs_scale"]}
"""The training schedule of the studies of training variants (``qaoa_training``, ``mixer_warm_start``,
``multi_angle``), as their records name it: :data:`qcpp.training.qaoa_solver.SINGLE_START`, levels ``p > 1`` from
the level below only and the Gibbs objective at ``eta = 5 / sigma``. Each variant there is measured against this
schedule; the default schedule (restarts at every level, ``eta = 40 / sigma``) is the one ``ensembles.py`` and
``time_to_solution.py`` measure, and ``training_restarts.py`` sets the two side by side on the ensembles."""


def study_gibbs(qaoa: Any) -> Any:
    """The Gibbs objective of :data:`STUDY_SCHEDULE` for one scenario's simulator."""
    from qcpp.training.objectives import make_objective
    from qcpp.training.training import cost_scale

    return make_objective("gibbs", cost_scale(qaoa), gibbs_scale=SINGLE_START["gibbs_scale"])


def study_training(qaoa: Any, p: int, objective: str = "gibbs", **options: Any) -> Any:
    """``train_layerwise(qaoa, p, objective, **options)`` on :data:`STUDY_SCHEDULE`."""
    from qcpp.training.layerwise import train_layerwise

    return train_layerwise(qaoa, p, objective, **SINGLE_START, **options)  # type: ignore[arg-type]


if __name__ == "__main__":  # pragma: no cover
    sys.exit("helper module of the experiment scripts; run one of them instead")
