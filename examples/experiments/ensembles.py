"""QAOA and the classical solvers on seeded random ensembles: P(optimum) by depth, the training's gap, 99% times.

Instances: :func:`qcpp.ensemble` cells ``RxC/N`` (grid, robots) at obstacle density ``density`` (soft obstacles,
random distinct endpoints, every instance feasible), ``instances`` per cell (more where ``CELL_INSTANCES`` says),
seeded by ``--seed``. Per instance (``_ensemble_tasks.run_instance``, one Dask task each):

* **DFS, CP-SAT, SA, GA, QAOA**: the time to the optimum with 99% probability under the rules of
  ``time_to_solution.py`` (QAOA: the default training to a depth fixed in advance, training shots counted,
  projected on an ideal all-to-all device), at every depth ``p = 1 .. p_max``;
* **training quality apart from ansatz quality**: at every depth the default training's ``P(optimum)`` beside the
  best any angles gave in an expensive search that knows the optimum (:func:`qcpp.training.angle_search.
  search_p_optimum`: L-BFGS-B on ``P(optimum)`` from the default's angles, the level below's best (extended and
  INTERP), ``random_starts`` random angles and ``hops`` basin-hopping steps, at most ``maxiter`` iterations each),
  and the upper bound on the ansatz's ceiling (0 below the depth at which an optimum can carry amplitude, else 1).

Summaries: medians and quartiles over each cell's instances. The tasks run on a Dask cluster: a
``dask.distributed.LocalCluster`` of ``--workers`` single-threaded processes by default, or the scheduler at
``--scheduler ADDRESS``. Ctrl-C cancels the tasks and writes nothing. ``--reuse FILE`` takes over the records of
an earlier run's instances that this run would compute again (:func:`reusable_rows`: same settings, qcpp version and
scenarios), so growing a cell from 30 to 100 instances computes only the 70 new ones.

Outputs (only when every task finished): ``results/ensembles.md``, ``results/ensembles.json`` (one record per
instance and method, and per instance and depth for QAOA) and ``figures/ensembles.png``.
Run: ``python examples/experiments/ensembles.py [--quick] [--cells 3x3/1 3x3/2] [--instances N 3x3/1=N]
[--p-max P] [--reuse results/ensembles.json]``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import _ensemble_tasks
import numpy as np
from _common import Options, Table, fresh_output_folder, pyplot, save_figure, write_results

import qcpp
from qcpp.io.atomic import write_text_atomic
from qcpp.problem.ensembles import ensemble
from qcpp.problem.scenario import scenario_to_dict

NAME = "ensembles"
TOL = 1e-9
CELL_INSTANCES = (("3x3/1", 300), ("3x3/2", 100), ("4x4/2", 100))
"""The full study's larger cells, where 30 instances do not pin the median down: P(optimum) at p = 1 and 2 has a
point mass at 0 (an optimum those depths cannot reach; on 3x3 also one at 1), and a median of 30 can sit on its
edge, so two seeds disagree by far more than the sampling spread of the rest (docs/ensembles.md, "Does it hold on a
fresh draw?"). The 3x3 cells cost seconds per instance, 4x4/2 about a minute."""


@dataclass(frozen=True)
class Config:
    cells: tuple[str, ...]
    density: float
    instances: int
    p_max: int
    runs: int
    sa_iterations: int
    ga_generations: int
    cpsat_limit: float
    search: dict[str, float]
    seed: int = 0
    cell_instances: tuple[tuple[str, int], ...] = ()
    """``(cell, count)`` pairs that override ``instances`` for a cell."""

    def instances_in(self, cell: str) -> int:
        """The cell's instance count: its override, else ``instances``.

        >>> replace(QUICK, cell_instances=(("3x3/1", 5),)).instances_in("3x3/1"), QUICK.instances_in("3x3/2")
        (5, 3)
        """
        return dict(self.cell_instances).get(cell, self.instances)


FULL = Config(("3x3/1", "3x3/2", "4x4/1", "4x4/2", "5x5/1", "3x3/3"), 0.1, 30, 8, 8, 2000, 10, 10.0,
              {"random_starts": 4, "hops": 2, "maxiter": 50}, cell_instances=CELL_INSTANCES)
QUICK = Config(("3x3/1", "3x3/2"), 0.1, 3, 3, 3, 500, 3, 2.0, {"random_starts": 1, "hops": 1, "maxiter": 20})


def parse_cell(text: str) -> tuple[int, int, int]:
    """``RxC/N`` -> ``(rows, cols, robots)``; one clear line on bad input."""
    try:
        grid, robots = text.split("/")
        rows, cols = grid.lower().split("x")
        out = (int(rows), int(cols), int(robots))
    except ValueError:
        raise argparse.ArgumentTypeError(f"a cell is RxC/N (e.g. 3x3/2), got {text!r}") from None
    if min(out[:2]) < 2 or out[2] < 1:
        raise argparse.ArgumentTypeError(f"a cell needs a grid of at least 2x2 and one robot, got {text!r}")
    return out


def parse_count(text: str) -> tuple[str | None, int]:
    """``N`` -> ``(None, N)``, ``RxC/R=N`` -> ``("RxC/R", N)``; one clear line on bad input.

    >>> parse_count("40"), parse_count("3x3/1=300")
    ((None, 40), ('3x3/1', 300))
    """
    cell, _, count = text.rpartition("=")
    try:
        n = int(count)
    except ValueError:
        raise argparse.ArgumentTypeError(f"an instance count is N or RxC/N=N (e.g. 3x3/1=300), got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"an instance count must be at least 1, got {text!r}")
    if not cell:
        return None, n
    r, c, k = parse_cell(cell)
    return f"{r}x{c}/{k}", n


def parse_args(argv: Sequence[str] | None) -> tuple[Options, Config, str | None, int, str, str, Path | None]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="reduced run (under 2 minutes), for the smoke test")
    ap.add_argument("--out", type=Path, default=None,
                    help="output root (figures/ and results/ below it); default: a new qcpp-experiments-* folder "
                         "here; --out docs regenerates the committed results")
    ap.add_argument("--seed", type=int, default=0, help="the ensembles' seed (and the search's)")
    ap.add_argument("--cells", nargs="+", type=parse_cell, default=None, metavar="RxC/N",
                    help="ensemble cells (default: all of the full study, or 3x3/1 3x3/2 with --quick)")
    ap.add_argument("--instances", nargs="+", type=parse_count, default=None, metavar="N|RxC/N=N",
                    help="instances per cell, and per-cell overrides such as 3x3/1=300 (default 30, "
                         + ", ".join(f"{c}={n}" for c, n in CELL_INSTANCES) + "; quick 3)")
    ap.add_argument("--p-max", type=int, default=None, help="deepest QAOA (default 8; quick 3)")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="a running Dask scheduler (default: a LocalCluster on this machine)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes, one thread each")
    ap.add_argument("--name", default=NAME, help=f"results/NAME.md, .json and figures/NAME.png (default {NAME})")
    ap.add_argument("--reuse", type=Path, default=None, metavar="FILE",
                    help="an earlier run's results JSON: its records of the instances this run would compute again "
                         "(same settings, qcpp version and scenarios) are taken over, the rest computed")
    ns = ap.parse_args(argv)
    for name in ("p_max", "workers"):
        value = getattr(ns, name)
        if value is not None and value < 1:
            ap.error(f"--{name.replace('_', '-')} must be at least 1, got {value}")
    cfg = replace(QUICK if ns.quick else FULL, seed=ns.seed)
    command = "python examples/experiments/ensembles.py" + (" --quick" if ns.quick else "")
    if ns.cells is not None:
        cfg = replace(cfg, cells=tuple(f"{r}x{c}/{n}" for r, c, n in ns.cells))
        command += " --cells " + " ".join(cfg.cells)
    if ns.instances is not None:
        counts = dict(cfg.cell_instances)
        for cell, n in ns.instances:
            if cell is None:
                cfg = replace(cfg, instances=n)
                counts = {}  # a new default count replaces the default overrides; later CELL=N entries apply
            else:
                counts[cell] = n
        cfg = replace(cfg, cell_instances=tuple(counts.items()))
        command += " --instances " + " ".join(str(n) if c is None else f"{c}={n}" for c, n in ns.instances)
        if stray := sorted(c for c, _ in ns.instances if c is not None and c not in cfg.cells):
            ap.error(f"--instances: {', '.join(stray)} is not among the cells ({' '.join(cfg.cells)})")
    cfg = replace(cfg, cell_instances=tuple((c, n) for c, n in cfg.cell_instances if c in cfg.cells))
    if ns.p_max is not None:
        cfg = replace(cfg, p_max=ns.p_max)
        command += f" --p-max {ns.p_max}"
    if ns.seed:
        command += f" --seed {ns.seed}"
    if not ns.name.replace("_", "").isalnum():
        ap.error(f"--name takes letters, digits and underscores, got {ns.name!r}")
    if ns.name != NAME:
        command += f" --name {ns.name}"
    opts = Options(quick=ns.quick, out=fresh_output_folder() if ns.out is None else ns.out, seed=ns.seed)
    if ns.reuse is not None and not ns.reuse.is_file():
        ap.error(f"--reuse: no results file at {ns.reuse}")
    return opts, cfg, ns.scheduler, ns.workers, command, ns.name, ns.reuse


def instances_of(cfg: Config) -> list[tuple[str, int, dict[str, Any]]]:
    """``(cell, index, scenario dict)`` of every instance, cells in order."""
    out = []
    for cell in cfg.cells:
        rows, cols, robots = parse_cell(cell)
        count = cfg.instances_in(cell)
        for i, s in enumerate(ensemble(rows, cols, robots, cfg.density, count=count, seed=cfg.seed)):
            out.append((cell, i, scenario_to_dict(s)))
    return out


REUSE_FREE = ("cells", "instances", "cell_instances")
"""Config fields two runs may differ in and still share an instance's records (they choose instances, not results)."""


class ReuseError(ValueError):
    """A ``--reuse`` file whose records this run cannot take over (other settings, version or scenarios)."""


def reusable_rows(data: dict[str, Any], cfg: Config,
                  tasks: Sequence[tuple[str, int, dict[str, Any]]]) -> dict[tuple[str, int], list[dict[str, Any]]]:
    """The records of an earlier run (``data``: its results JSON) for the tasks it already computed, by
    ``(cell, index)``; every record of an instance, in the earlier run's order.

    The study is seeded throughout (generator, training and search; the only unseeded fields are wall-clock times):
    on one machine an instance computed under the same settings and qcpp version has the same records. On another
    machine floating-point rounding can end the deep levels' local optimizers elsewhere on a few instances
    (``benchmarks/ensemble_rerun.py`` compares two runs), so the records taken over are those of the machine that
    computed them. Taking them over
    is refused, never guessed, when the settings other than the instance counts differ, the version differs, or an
    instance both runs share has another scenario (the generator changed).

    Raises:
        ReuseError: one line naming the first difference.

    Example:
        >>> cfg = replace(QUICK, cells=("3x3/1",), instances=2)
        >>> tasks = [("3x3/1", 0, {"s": 0}), ("3x3/1", 1, {"s": 1})]
        >>> rows = [{"cell": "3x3/1", "index": 0, "scenario": {"s": 0}, "method": m} for m in ("dfs", "qaoa")]
        >>> old = {"qcpp_version": qcpp.__version__, "config": json.loads(json.dumps(asdict(cfg))), "rows": rows}
        >>> {k: [r["method"] for r in v] for k, v in reusable_rows(old, cfg, tasks).items()}
        {('3x3/1', 0): ['dfs', 'qaoa']}
        >>> reusable_rows(old | {"config": old["config"] | {"seed": 1}}, cfg, tasks)
        Traceback (most recent call last):
        ...
        ensembles.ReuseError: --reuse: the earlier run's seed is 1, this run's 0
    """
    if data.get("qcpp_version") != qcpp.__version__:
        raise ReuseError(f"--reuse: the earlier run is qcpp {data.get('qcpp_version')}, this is {qcpp.__version__}")
    ours = json.loads(json.dumps(asdict(cfg)))
    theirs = data.get("config", {})
    for key in sorted(set(ours) | set(theirs)):
        if key not in REUSE_FREE and ours.get(key) != theirs.get(key):
            raise ReuseError(f"--reuse: the earlier run's {key} is {theirs.get(key)}, this run's {ours.get(key)}")
    wanted = {(cell, i): json.loads(json.dumps(s)) for cell, i, s in tasks}
    out: dict[tuple[str, int], list[dict[str, Any]]] = {}
    for r in data.get("rows", []):
        key = (r["cell"], r["index"])
        if key not in wanted:
            continue
        if r["scenario"] != wanted[key]:
            raise ReuseError(f"--reuse: instance {key[0]} #{key[1]} has another scenario in the earlier run")
        out.setdefault(key, []).append(r)
    return out


def dump_reused(earlier: dict[str, Any], reused: dict[tuple[str, int], Any]) -> dict[str, Any]:
    """The provenance of records taken over from ``earlier`` (a results JSON): how many, the run's command,
    seconds and load, and where that run took records over from in turn (``reused``: the same form, or ``None``)."""
    return {"instances": len(reused), "command": earlier["command"], "seconds": earlier["seconds"],
            "load_average": earlier.get("load_average"), "reused": earlier.get("reused")}


def taken_over(provenance: dict[str, Any]) -> str:
    """A results note's account of :func:`dump_reused`'s provenance, the earlier runs' own in turn.

    >>> first = {"instances": 90, "command": "ensembles.py --cells 4x4/2", "seconds": 2786.2, "reused": None}
    >>> text = taken_over({"instances": 160, "command": "ensembles.py", "seconds": 4495.0, "reused": first})
    >>> for part in text.split(", which "):
    ...     print(part)
    took over the records of 160 instances from an earlier run (`ensembles.py`, 4495 s)
    took over 90 from an earlier run (2786 s)
    """
    def load(run: dict[str, Any]) -> str:
        pair = run.get("load_average")
        return f", load average {pair[0]:.1f} to {pair[1]:.1f}" if pair else ""

    text = (f"took over the records of {provenance['instances']} instances from an earlier run "
            f"(`{provenance['command']}`, {provenance['seconds']:.0f} s{load(provenance)})")
    earlier = provenance.get("reused")
    while earlier:
        text += (f", which took over {earlier['instances']} from an earlier run ({earlier['seconds']:.0f} s"
                 f"{load(earlier)})")
        earlier = earlier.get("reused")
    return text


def run_on_dask(tasks: list[tuple[str, int, dict[str, Any]]], cfg: Any, scheduler: str | None,
                workers: int, fn: Any = None) -> list[dict[str, Any]]:
    """``fn(cell, index, scenario, asdict(cfg))`` (default ``_ensemble_tasks.run_instance``) for every task on the
    cluster, with a progress bar; returns the results in task order. Ctrl-C cancels the tasks."""
    import cloudpickle
    from dask.distributed import as_completed
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from qcpp.simulate.cluster import dask_client

    cloudpickle.register_pickle_by_value(_ensemble_tasks)  # workers need qcpp, not this folder
    try:
        client = dask_client("local" if scheduler is None else scheduler, workers=workers)
    except OSError as err:  # an unreachable --scheduler: one line and exit 2, as the qcpp commands do
        print(f"error: {err}", file=sys.stderr)
        raise SystemExit(2) from None
    futures = []
    try:
        payload = asdict(cfg)
        fn = _ensemble_tasks.run_instance if fn is None else fn
        futures = [client.submit(fn, cell, i, s, payload, key=f"{fn.__name__}-{cell}-{i}", pure=False)
                   for cell, i, s in tasks]
        results: dict[str, dict[str, Any]] = {}
        columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
        with Progress(*columns, transient=False) as bar:
            job = bar.add_task(f"{len(tasks)} instances", total=len(tasks))
            for fut in as_completed(futures):
                r = fut.result()
                results[fut.key] = r
                done = f"{r['cell']} #{r['index']} ({r['seconds']:.0f} s)"
                bar.update(job, advance=1, description=done)
                if not bar.console.is_terminal:  # a log: one line per finished instance
                    print(f"{len(results)}/{len(tasks)} {done}", file=sys.stderr, flush=True)
        return [results[f.key] for f in futures]
    except KeyboardInterrupt:
        client.cancel(futures, force=True)
        raise
    finally:
        client.close(timeout=5)  # a local cluster closes with its client


# ---------------------------------------------------------------------------------------------- records


def result_rows(results: list[dict[str, Any]], cfg: Config) -> list[dict[str, Any]]:
    """One record per instance and classical method, and per instance and depth for QAOA."""
    from qcpp.simulate.time_to_solution import GATE_MODEL
    from qcpp.training.layerwise import DEFAULT_MAXITER, DEFAULT_RANDOM_STARTS, SHOTS_PER_ESTIMATE
    from qcpp.training.objectives import GIBBS_SCALE

    options = {
        "dfs": {},
        "cpsat": {"workers": 1, "time_limit": cfg.cpsat_limit},
        "anneal": {"iterations": cfg.sa_iterations, "components": "initial", "seeds": cfg.runs},
        "genetic": {"generations": cfg.ga_generations, "components": "initial", "seeds": cfg.runs},
        "qaoa": {"training": "layerwise", "objective": "gibbs", "gibbs_eta_sigma": GIBBS_SCALE,
                 "maxiter": DEFAULT_MAXITER, "random_starts": DEFAULT_RANDOM_STARTS, "restart_every_level": True,
                 "shots_per_estimate": SHOTS_PER_ESTIMATE, "gate_model": GATE_MODEL, "device": "ideal all-to-all",
                 "search": cfg.search | {"seed": cfg.seed}},
    }
    rows = []
    for r in results:
        base = {"cell": r["cell"], "index": r["index"], "instance": f"{r['cell']} #{r['index']}",
                "scenario": r["scenario"], "qcpp_version": qcpp.__version__, "optimum": r["optimum"],
                "ensemble": {"density": cfg.density, "seed": cfg.seed}}
        d, c = r["dfs"], r["cpsat"]
        rows.append({**base, "method": "dfs", "options": options["dfs"], **d, "tts_99": d["seconds"]})
        first = next((s for s, v in c["improvements"] if v <= r["optimum"] + TOL), None)
        rows.append({**base, "method": "cpsat", "options": options["cpsat"], **c, "tts_99": first})
        for m in ("anneal", "genetic"):
            rows.append({**base, "method": m, "options": options[m], **r[m]})
        q = r["qaoa"]
        for lv in q["levels"]:
            rows.append({**base, "method": "qaoa", "options": options["qaoa"] | {"p": lv["p"]},
                         "dimension": q["dimension"], "optimum_in_basis": q["optimum_in_basis"], **lv})
    return rows


# ---------------------------------------------------------------------------------------------- summaries


def quartiles(values: Sequence[float]) -> tuple[float, float, float]:
    """Median and the lower and upper quartiles (numpy's linear interpolation; inf allowed)."""
    a = np.asarray(values, dtype=float)
    # with an inf among the values: order statistics (no interpolation through inf, which gives nan)
    q = np.percentile(a, [50, 25, 75], method="lower" if np.isinf(a).any() else "linear")
    return float(q[0]), float(q[1]), float(q[2])


def _mqq(values: Sequence[float], fmt: str = "{:.3g}") -> str:
    m, lo, hi = quartiles(values)
    return f"{fmt.format(m)} [{fmt.format(lo)}, {fmt.format(hi)}]"


def quality_table(rows: list[dict[str, Any]], cfg: Config) -> Table:
    t = Table("P(optimum) by depth: the default training beside the best found by the expensive search "
              "(median [lower quartile, upper quartile] over the cell's instances)",
              ["cell", "p", "instances", "default P(opt)", "best found P(opt)", "default / best",
               "default >= best/2", "ceiling bound 0 (unreachable)"])
    for cell in cfg.cells:
        for p in range(1, cfg.p_max + 1):
            sel = [r for r in rows if r["method"] == "qaoa" and r["cell"] == cell and r["p"] == p]
            if not sel:
                continue
            ratios = [r["p_opt"] / r["best_p_opt"] for r in sel if r["best_p_opt"] > 1e-12]
            half = sum(r["p_opt"] >= 0.5 * r["best_p_opt"] - 1e-12 for r in sel)
            t.add(cell, p, len(sel), _mqq([r["p_opt"] for r in sel]), _mqq([r["best_p_opt"] for r in sel]),
                  _mqq(ratios) if ratios else "-", f"{half} of {len(sel)} ({100 * half / len(sel):.0f}%)",
                  sum(r["ceiling_upper"] == 0 for r in sel))
    return t


def tts_table(rows: list[dict[str, Any]], cfg: Config) -> Table:
    t = Table("Time to the optimum with 99% probability, seconds (median [quartiles]); QAOA: default training to "
              "a depth fixed in advance, projected on an IDEAL all-to-all device, training counted",
              ["cell", "method", "instances", "99% time s", "reached (finite)"])
    for cell in cfg.cells:
        for m, label in (("dfs", "DFS"), ("cpsat", "CP-SAT first optimum"), ("anneal", "SA"), ("genetic", "GA")):
            vals = [math.inf if r["tts_99"] is None else r["tts_99"] for r in rows
                    if r["method"] == m and r["cell"] == cell]
            if vals:
                t.add(cell, label, len(vals), _mqq(vals), sum(math.isfinite(v) for v in vals))
        for p in range(1, cfg.p_max + 1):
            vals = [r["tts_99"] for r in rows if r["method"] == "qaoa" and r["cell"] == cell and r["p"] == p]
            if vals:
                t.add(cell, f"QAOA p={p}", len(vals), _mqq(vals), sum(math.isfinite(v) for v in vals))
    return t


CLASSICAL = ("dfs", "cpsat", "anneal", "genetic")


def best_classical_times(rows: Sequence[dict[str, Any]]) -> dict[str, float]:
    """The fastest classical method's 99% time per instance label (``inf`` where none reached the optimum).

    >>> best_classical_times([{"instance": "a", "method": "dfs", "tts_99": 2.0},
    ...                       {"instance": "a", "method": "anneal", "tts_99": None},
    ...                       {"instance": "a", "method": "qaoa", "tts_99": 0.5}])
    {'a': 2.0}
    """
    best: dict[str, float] = {}
    for r in rows:
        if r["method"] in CLASSICAL:
            t = math.inf if r["tts_99"] is None else r["tts_99"]
            best[r["instance"]] = min(best.get(r["instance"], math.inf), t)
    return best


def verdict_table(rows: list[dict[str, Any]], cfg: Config) -> Table:
    t = Table("QAOA (ideal device, training counted) against the fastest classical method per instance: "
              "ratio of 99% times (median [quartiles]) and how often QAOA is faster",
              ["cell", "p", "QAOA / best classical", "QAOA faster on", "QAOA sampling only (best angles, no "
               "training) / best classical"])
    classical = best_classical_times(rows)
    for cell in cfg.cells:
        for p in range(1, cfg.p_max + 1):
            sel = [r for r in rows if r["method"] == "qaoa" and r["cell"] == cell and r["p"] == p]
            if not sel:
                continue
            ratio = [r["tts_99"] / classical[r["instance"]] for r in sel]
            ideal = [r["best_sampling_99"] / classical[r["instance"]] for r in sel]
            t.add(cell, p, _mqq(ratio), f"{sum(x < 1 for x in ratio)} of {len(sel)}", _mqq(ideal))
    return t


def figure(opts: Options, rows: list[dict[str, Any]], cfg: Config, name: str = NAME) -> None:
    """P(optimum) by depth per cell, three cells to a row; each panel's y axis fits its cell (the larger cells'
    medians stay below 0.25, invisible on a shared 0..1 axis)."""
    plt = pyplot()
    ncols = min(3, len(cfg.cells))
    nrows = math.ceil(len(cfg.cells) / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.2 * ncols, 3.4 * nrows), squeeze=False)
    flat = [ax for row in axes for ax in row]
    ps = list(range(1, cfg.p_max + 1))
    for ax, cell in zip(flat, cfg.cells):
        top = 0.0
        for key, colour, label in (("p_opt", "tab:blue", "default training"),
                                   ("best_p_opt", "tab:orange", "best found (expensive search)")):
            stats = [quartiles([r[key] for r in rows if r["method"] == "qaoa" and r["cell"] == cell
                                and r["p"] == p] or [math.nan]) for p in ps]
            med, lo, hi = zip(*stats)
            ax.plot(ps, med, marker="o", color=colour, label=label)
            ax.fill_between(ps, lo, hi, color=colour, alpha=0.2)
            top = max([top, *(h for h in hi if math.isfinite(h))])
        ax.set_title(f"{cell}, density {cfg.density:g}, {cfg.instances_in(cell)} instances", fontsize=9)
        ax.set_xlabel("p")
        if top > 0.5:
            ax.set_ylim(-0.02, 1.02)
        else:
            ax.set_ylim(0, max(1.1 * top, 0.01))
        ax.grid(alpha=0.3)
    for ax in flat[len(cfg.cells):]:
        ax.set_visible(False)
    for row in axes:
        row[0].set_ylabel("P(optimum): median, quartiles")
    flat[0].legend(frameon=False, fontsize=8, loc="lower right")
    fig.tight_layout()
    save_figure(fig, opts.figures / f"{name}.png")
    plt.close(fig)


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    opts, cfg, scheduler, workers, command, name, reuse = parse_args(argv)
    t_all = time.perf_counter()
    load_before = os.getloadavg()[0]
    tasks = instances_of(cfg)
    reused: dict[tuple[str, int], list[dict[str, Any]]] = {}
    earlier: dict[str, Any] = {}
    if reuse is not None:
        try:
            earlier = json.loads(reuse.read_text(encoding="utf-8"))
            reused = reusable_rows(earlier, cfg, tasks)
        except ReuseError as err:
            print(err, file=sys.stderr)
            raise SystemExit(2) from None
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as err:  # not JSON, or not our results
            print(f"--reuse: {reuse} is not a results file of this study ({type(err).__name__}: {err})",
                  file=sys.stderr)
            raise SystemExit(2) from None
    todo = [t for t in tasks if (t[0], t[1]) not in reused]
    try:
        results = run_on_dask(todo, cfg, scheduler, workers) if todo else []
    except KeyboardInterrupt:
        print("interrupted: nothing written", file=sys.stderr)
        raise SystemExit(130) from None
    seconds = time.perf_counter() - t_all
    load = (load_before, os.getloadavg()[0])
    provenance = dump_reused(earlier, reused) if reused else None
    computed = result_rows(results, cfg)
    order = {(cell, i): k for k, (cell, i, _) in enumerate(tasks)}
    rows = sorted(computed + [r for v in reused.values() for r in v], key=lambda r: order[(r["cell"], r["index"])])
    opts.figures.mkdir(parents=True, exist_ok=True)
    opts.results.mkdir(parents=True, exist_ok=True)
    tables = [quality_table(rows, cfg), tts_table(rows, cfg), verdict_table(rows, cfg)]
    where = (f"a LocalCluster of {workers} single-threaded worker{'s' if workers > 1 else ''}" if scheduler is None
             else "a Dask cluster")
    notes = [
        f"qcpp {qcpp.__version__}. Ensembles: qcpp.ensemble(rows, cols, robots, density={cfg.density:g}, "
        f"count=N, seed={cfg.seed}): random distinct endpoints, soft obstacles; every instance feasible. N: "
        + ", ".join(f"{cell} {cfg.instances_in(cell)}" for cell in cfg.cells) + ".",
        "Rules of time_to_solution.py: DFS its run time; CP-SAT (1 worker, limit "
        f"{cfg.cpsat_limit:g} s) when it first found the optimum; SA ({cfg.sa_iterations} iterations) and GA "
        f"({cfg.ga_generations} generations) over {cfg.runs} seeded runs: mean run time x runs needed for 99% "
        "('inf': no run succeeded). QAOA: default training (Gibbs objective, L-BFGS-B layer by layer) to a depth "
        "fixed in advance; IDEAL ALL-TO-ALL DEVICE PROJECTION (the compiler's exact depth, training shots = "
        "objective estimates x shots per estimate, all at the final depth's shot time).",
        f"Best found: qcpp.training.angle_search.search_p_optimum per depth, budget {cfg.search} (L-BFGS-B on "
        "P(optimum) with its exact gradient from the default's angles, the level below's best extended and "
        "INTERP, random starts and basin-hopping steps; a level that reaches 0.999 ends the search). It knows the "
        "optimum: a yardstick for the training, no algorithm. The ansatz's ceiling at p lies between the best "
        "found and its upper bound (0 below the depth at which an optimum can carry amplitude, else 1).",
        f"Tasks run on {where} on a {os.cpu_count()}-core machine, load average (1 min) {load[0]:.1f} at the "
        f"start and {load[1]:.1f} at the end (the study's own workers count; other jobs inflate every wall-clock "
        f"time). "
        + (f"Whole study: {seconds:.0f} s." if provenance is None else
           f"This run computed {len(todo)} instances in {seconds:.0f} s and {taken_over(provenance)}."),
    ]
    write_results(opts, name, command, tables, notes)
    dump = {"qcpp_version": qcpp.__version__, "command": command, "config": asdict(cfg), "seconds": seconds,
            "load_average": list(load), "rows": rows}
    if provenance:
        dump["reused"] = provenance
    write_text_atomic(opts.results / f"{name}.json", json.dumps(dump, indent=1) + "\n")
    print(f"wrote {opts.results / f'{name}.json'}")
    figure(opts, rows, cfg, name)
    return {"config": cfg, "rows": rows, "results": results, "seconds": seconds}


if __name__ == "__main__":
    main()
