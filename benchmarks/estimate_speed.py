"""Speed and memory of ``qcpp estimate`` / the compile guard, and the gadget-vs-compiled cross-check.

Run: ``python benchmarks/estimate_speed.py [--quick] [--sweep-seconds S]`` (the sweep is interrupted after
``S`` seconds, default 150, and the rows it printed by then are reported), or
``python benchmarks/estimate_speed.py --against REV [--repeats N]`` to compare this tree with revision ``REV`` in
the same run: ``REV``'s ``src/`` is exported (``git archive``) into a temporary directory, and the estimate and the
sweep run ``N`` times (default 2) with each tree's ``src`` first on ``PYTHONPATH``, alternating the trees (this
tree first in odd rounds, ``REV`` first in even ones) so that both share whatever else loads the machine; the
table gives per command and tree the fastest run's wall time and the least CPU time (user + system of the
child: less sensitive to a shared machine than wall time), every run's wall time, the peak memory (the largest of
the runs) and whether both trees printed the same bytes; the load average is printed before and after.
Each command runs in its own process
(``python -m qcpp``,
measured from outside: wall clock, and peak resident memory from ``getrusage`` of that child), so start-up is
included. Prints one table with the speed and memory goals:

* ``qcpp estimate --grid 30x30 --robots 8 -p 3 --json``: < 5 s wall, < 1 GB peak;
* ``qcpp estimate --grid 2x2..40x40 --robots 1..8 -p 1..5 --format csv`` (60,840 requested rows; grids too
  small for the robots are skipped): < 120 s, with the time to the first row (rows stream out as computed);
* ``qcpp compile`` of a 50x50 / 8 robots / p = 40 scenario (predicted over an hour): refused within 10 s, one line,
  exit 2; and the prediction for 40x40 / 8 robots / p = 5, which the guard lets run (printed, not run: minutes);
* counts from gadgets == counts of the compiled circuit (:mod:`qcpp.estimators.crosscheck`): 0 mismatches, on every
  cross-check case (``--quick``: the sample the default test run uses), on all cores (minutes).
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from qcpp.estimators.crosscheck import crosscheck, crosscheck_cases
from qcpp.estimators.guard import compile_need
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario_io import save_scenario

ROOT = Path(__file__).resolve().parents[1]


def _run(
    args: list[str], limit: float | None = None, src: Path = ROOT / "src", cpu: list[float] | None = None
) -> tuple[float, float, float | None, int, str, str]:
    """Wall seconds, peak RSS in GB, seconds to the first stdout line, exit code, stdout, stderr (the command is
    killed once ``limit`` seconds have passed; its exit code is then negative), with ``src`` first on the path;
    the child's CPU seconds (user + system) are appended to ``cpu`` if given."""
    env = {**os.environ, "PYTHONPATH": str(src) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    # GNU time reports this child's own peak RSS (getrusage of the waited process, KiB) and its CPU seconds
    cmd = ["/usr/bin/time", "-f", "%M %U %S", sys.executable, "-m", "qcpp", *args]
    start = time.perf_counter()
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, cwd=ROOT, start_new_session=True
    )
    assert proc.stdout is not None and proc.stderr is not None
    first = None
    chunks = []
    for line in proc.stdout:
        if first is None:
            first = time.perf_counter() - start
        chunks.append(line)
        if limit is not None and time.perf_counter() - start > limit:
            os.killpg(proc.pid, signal.SIGINT)  # our own session: qcpp says "interrupted", GNU time still reports
            break
    err = proc.stderr.read()
    code = proc.wait()
    wall = time.perf_counter() - start
    *err_lines, last = err.rstrip("\n").split("\n") if err.strip() else ["", "0 0 0"]
    err_lines = [line for line in err_lines if not line.startswith("Command ")]  # GNU time's own notes
    rss, user, system = [*last.split(), "0", "0", "0"][:3]
    rss_gb = int(rss) / 1e6 * 1.024 if rss.strip().isdigit() else float("nan")
    if cpu is not None:
        cpu.append(float(user) + float(system))
    return wall, rss_gb, first, code, "".join(chunks), "\n".join(err_lines)


ESTIMATE = ["estimate", "--grid", "30x30", "--robots", "8", "-p", "3", "--json"]
SWEEP = ["estimate", "--grid", "2x2..40x40", "--robots", "1..8", "-p", "1..5", "--format", "csv"]


def _export(rev: str, into: Path) -> Path:
    """``rev``'s ``src/`` tree, written into ``into`` (nothing in the repository changes). Returns its path."""
    archive = subprocess.run(["git", "archive", "--format=tar", rev, "src"], cwd=ROOT, capture_output=True, check=True)
    subprocess.run(["tar", "-x", "-C", str(into)], input=archive.stdout, check=True)
    return into / "src"


def compare(rev: str, repeats: int, sweep_limit: float) -> int:
    """Time :data:`ESTIMATE` and :data:`SWEEP` on this tree and on ``rev``, alternating (see the module docstring)."""
    label = subprocess.run(["git", "rev-parse", "--short", rev], cwd=ROOT, capture_output=True, text=True,
                           check=True).stdout.strip()  # fmt: skip
    here = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                          check=True).stdout.strip()  # fmt: skip
    dirty = subprocess.run(["git", "status", "--porcelain", "src"], cwd=ROOT, capture_output=True, text=True).stdout
    this = f"{here}{'+changes' if dirty.strip() else ''} (this tree)"
    commands = {"estimate 30x30 / 8 robots / p=3 --json": (ESTIMATE, None),
                "estimate 2x2..40x40 / 1..8 / p=1..5 csv": (SWEEP, sweep_limit)}  # fmt: skip
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        trees = {this: ROOT / "src", label: _export(rev, Path(tmp))}
        results: dict[tuple[str, str], list[tuple[float, float, int, str, float]]] = {}
        for i in range(repeats):
            order = list(trees.items()) if i % 2 == 0 else list(reversed(trees.items()))
            for name, src in order:
                for cmd, (args, limit) in commands.items():
                    cpu: list[float] = []
                    wall, rss, _, code, out, _ = _run(args, limit=limit, src=src, cpu=cpu)
                    results.setdefault((cmd, name), []).append((wall, rss, code, out, cpu[0]))
                    print(f"round {i + 1}/{repeats}: {name}: {cmd}: {wall:.2f} s wall, {cpu[0]:.2f} s CPU, "
                          f"{rss:.2f} GB (exit {code})", file=sys.stderr)  # fmt: skip
    print(f"| command | tree | wall (min of {repeats}) | CPU (min) | all runs (wall) | peak RSS | exit |")
    print("|---|---|---:|---:|---|---:|---|")
    best: dict[tuple[str, str], tuple[float, float]] = {}
    for (cmd, name), runs in results.items():
        walls = sorted(r[0] for r in runs)
        best[cmd, name] = (walls[0], min(r[4] for r in runs))
        codes = ",".join(sorted({str(r[2]) for r in runs}))
        print(f"| {cmd} | {name} | {walls[0]:.2f} s | {best[cmd, name][1]:.2f} s | "
              f"{' '.join(f'{w:.2f}' for w in walls)} | {max(r[1] for r in runs):.2f} GB | {codes} |")  # fmt: skip
    print()
    for cmd in commands:
        ratio, cpu_ratio = (best[cmd, this][k] / best[cmd, label][k] for k in (0, 1))
        outs = {name: {r[3] for r in results[cmd, name]} for name in trees}
        if any(len(o) > 1 for o in outs.values()):
            same = "DIFFERS between runs of one tree"
        elif outs[this] == outs[label]:
            same = "identical in every run of both trees"
        else:
            a, b = (next(iter(outs[n])).splitlines() for n in (this, label))
            changed = sum(x != y for x, y in zip(a, b)) + abs(len(a) - len(b))
            same = f"identical within each tree; the trees differ in {changed} of {max(len(a), len(b))} lines"
        print(f"{cmd}: {this} / {label} = {ratio:.2f} (min wall), {cpu_ratio:.2f} (min CPU); stdout {same}")
    load = " / ".join(f"{a:.1f}" for a in load_before), " / ".join(f"{a:.1f}" for a in os.getloadavg())
    print(f"machine: {os.cpu_count()} cores, load average (1 / 5 / 15 min) {load[0]} before, {load[1]} after")
    return 0


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="cross-check the default test run's sample only")
    parser.add_argument("--sweep-seconds", type=float, help="interrupt the sweep after S seconds (150; 900 --against)")
    parser.add_argument("--against", metavar="REV", help="compare this tree with revision REV")
    parser.add_argument("--repeats", type=int, default=2, help="--against: runs per tree (default 2)")
    args = parser.parse_args(argv)
    if args.against is not None:
        limit = 900.0 if args.sweep_seconds is None else args.sweep_seconds
        return compare(args.against, args.repeats, limit)
    quick = args.quick
    sweep_limit = 150.0 if args.sweep_seconds is None else args.sweep_seconds
    rows = []
    wall, rss, _, code, out, _ = _run(ESTIMATE)
    ok = code == 0 and wall < 5 and rss < 1
    rows.append(("estimate 30x30 / 8 robots / p=3 --json", f"{wall:.2f} s", f"{rss:.2f} GB", "< 5 s, < 1 GB", ok))
    wall, rss, first, code, out, err = _run(SWEEP, limit=sweep_limit)
    n = max(0, len(out.splitlines()) - 1)
    ok = code == 0 and wall < 120
    done = "done" if code == 0 else f"STOPPED after {sweep_limit:.0f} s"
    note = f"{n:,} of 60,800 rows ({done}), first row after {first or 0:.2f} s"
    rows.append(("estimate 2x2..40x40 / 1..8 / p=1..5 csv", f"{wall:.1f} s", f"{rss:.2f} GB", "< 120 s", ok))
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "big.toml"
        save_scenario(default_scenario(50, 50, 8), path)
        wall, rss, _, code, out, err = _run(["compile", str(path), "-p", "40", "--lowered", "--qasm", f"{tmp}/o.qasm"])
    lines = err.strip().splitlines()
    ok = code == 2 and wall < 10 and len(lines) == 1
    rows.append(("compile 50x50 / 8 robots / p=40 (refused)", f"{wall:.2f} s", f"{rss:.2f} GB",
                 "< 10 s, exit 2, 1 line", ok))  # fmt: skip
    refusal = lines[0] if lines else ""
    runs = compile_need(default_scenario(40, 40, 8), 5, streamed=True)  # what `qcpp compile ... --qasm` predicts
    t0 = time.perf_counter()
    cases = list(crosscheck_cases(full=not quick))
    with ProcessPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        mismatches = [m for found in pool.map(crosscheck, cases, chunksize=4) for m in found]
    check_s = time.perf_counter() - t0
    rows.append(
        (f"gadget counts == compiled counts ({len(cases)} cases)", f"{check_s:.0f} s", "",
         "0 mismatches", not mismatches)
    )  # fmt: skip
    print("| check | wall | peak RSS | goal | met |")
    print("|---|---:|---:|---|---|")
    for name, w, m, goal, met in rows:
        print(f"| {name} | {w} | {m} | {goal} | {'yes' if met else 'NO'} |")
    print()
    print(f"sweep: {note}")
    print(f"refusal: {refusal}")
    print(f"runs: compile 40x40 / 8 robots / p=5 --lowered --qasm: {runs.what}, predicted {runs.describe()}")
    print(f"cross-check: {len(mismatches)} mismatches over {len(cases)} cases" + ("" if not quick else " (--quick)"))
    for m in mismatches[:10]:
        print("  " + m)
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
