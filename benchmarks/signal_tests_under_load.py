"""Run every test that touches signals, subprocesses or threads N times in a row beside CPU-bound jobs.

A test that waits on a real process or thread can pass alone and fail when the machine is busy (a signal that
lands before the work it should interrupt, a fixed sleep that is too short, a deadline). This script finds those
tests (:func:`select_tests`: a test function whose source, or the source of a helper of its module that it calls,
names ``signal``, ``subprocess``, ``Popen``, ``threading``, ``Thread``, ``multiprocessing`` or ``os.kill``),
plus every test of :data:`WHOLE_FILES`), starts ``--hogs`` busy-looping Python processes and runs the selected
tests ``--runs`` times in a row (``python -m pytest -n 0 -p no:randomly``, heavy tests included), then prints one
row per test with its pass, fail and skip counts. The full output of every run with a failure is kept in ``--keep``.

Usage::

    python benchmarks/signal_tests_under_load.py                 # 20 runs beside 2 CPU-bound jobs
    python benchmarks/signal_tests_under_load.py --runs 3 -k qcec # 3 runs of the tests matching 'qcec'
    python benchmarks/signal_tests_under_load.py --list           # only print the selected tests
    python benchmarks/signal_tests_under_load.py --runs 2 --skip guard_peaks   # without the memory measurements
    python benchmarks/signal_tests_under_load.py --minutes 90    # as many of the 20 runs as start within 90 min
    python benchmarks/signal_tests_under_load.py --workers 2     # each run on two pytest-xdist workers

``--workers 2`` runs each pass of the tests on two pytest-xdist workers beside the same CPU-bound jobs: each test
then shares the two cores with three other busy processes instead of two, a harsher load than one worker.

Exit code 0 when every run of every selected test passed (or was skipped), 1 otherwise.
"""

from __future__ import annotations

import argparse
import ast
import os
import re
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from collections import Counter
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
MARKERS = re.compile(r"(?<![\w.])(signal|subprocess|threading|multiprocessing)\b|\b(Popen|Thread|os\.kill)\b")
"""Source text that makes a test (or a helper it calls) one that touches signals, subprocesses or threads."""
WHOLE_FILES = ("tests/cli/progress_test.py",)
"""Files whose every test runs a thread inside the code under test (the progress heartbeat)."""


def _names_called(node: ast.AST) -> set[str]:
    return {n.func.id for n in ast.walk(node) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}


def select_tests(path: Path) -> list[str]:
    """Node ids (``path::test`` or ``path::Class::test``) of the tests in ``path`` that touch signals,
    subprocesses or threads, directly or through a module-level helper of the same file (transitively).

    Example:
        >>> tests = select_tests(REPO / "tests" / "qcpp" / "interrupt_test.py")
        >>> any("qcec" in t for t in tests)
        True
    """
    text = path.read_text(encoding="utf-8")
    tree = ast.parse(text)
    helpers = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef | ast.AsyncFunctionDef)}

    def direct(node: ast.AST) -> bool:
        src = ast.get_source_segment(text, node) or ""
        return MARKERS.search(src) is not None

    touching = {name for name, node in helpers.items() if direct(node)}
    changed = True
    while changed:  # a helper that calls a touching helper touches too
        changed = False
        for name, node in helpers.items():
            if name not in touching and _names_called(node) & touching:
                touching.add(name)
                changed = True
    rel = path.relative_to(REPO).as_posix()
    out = []
    for node in tree.body:
        cases: list[tuple[str, ast.AST]] = []
        if isinstance(node, ast.FunctionDef) and node.name.startswith("test"):
            cases.append((f"{rel}::{node.name}", node))
        elif isinstance(node, ast.ClassDef) and node.name.startswith("Test"):
            cases += [(f"{rel}::{node.name}::{m.name}", m) for m in node.body
                      if isinstance(m, ast.FunctionDef) and m.name.startswith("test")]
        for node_id, fn in cases:
            if rel in WHOLE_FILES or direct(fn) or _names_called(fn) & touching:
                out.append(node_id)
    return out


def all_selected(keyword: str | None, skip: list[str] | None = None) -> list[str]:
    """Every selected test under ``tests/`` (optionally only ids containing ``keyword``, none containing an item
    of ``skip``)."""
    ids = [t for p in sorted((REPO / "tests").rglob("*_test.py")) for t in select_tests(p)]
    return [t for t in ids if (keyword is None or keyword in t) and not any(s in t for s in skip or [])]


def _outcomes(junit: Path) -> dict[str, str]:
    """Test name -> ``passed``, ``failed`` or ``skipped`` from a JUnit XML report (parametrised ids kept)."""
    out: dict[str, str] = {}
    if not junit.exists():
        return out
    for case in ET.parse(junit).getroot().iter("testcase"):
        name = f"{case.get('classname', '')}::{case.get('name', '')}"
        if case.find("failure") is not None or case.find("error") is not None:
            out[name] = "failed"
        elif case.find("skipped") is not None:
            out[name] = "skipped"
        else:
            out[name] = "passed"
    return out


def main(argv: list[str] | None = None) -> int:
    """Run the selected tests ``--runs`` times beside ``--hogs`` CPU-bound jobs and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=20, help="runs in a row (default 20)")
    parser.add_argument("--hogs", type=int, default=2, help="CPU-bound jobs beside the tests (default 2)")
    parser.add_argument("--workers", type=int, default=1,
                        help="pytest-xdist workers per run (default 1: the tests run one after another)")
    parser.add_argument("-k", dest="keyword", default=None, help="only test ids containing this text")
    parser.add_argument("--skip", action="append", default=[], help="leave out test ids containing this (repeat)")
    parser.add_argument("--keep", type=Path, default=None, help="folder for the output of failed runs")
    parser.add_argument("--list", action="store_true", help="print the selected tests and stop")
    parser.add_argument("--minutes", type=float, default=None,
                        help="start no further run after this many minutes (the table counts the runs made)")
    args = parser.parse_args(argv)
    tests = all_selected(args.keyword, args.skip)
    if args.list or not tests:
        print("\n".join(tests) or "no test selected")
        return 0
    keep = args.keep or Path(tempfile.mkdtemp(prefix="signal_tests_"))
    keep.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, "PYTHONPATH": str(REPO / "src"), "MPLBACKEND": "Agg"}
    counts: dict[str, Counter[str]] = {}
    hogs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(args.hogs)]
    start = time.monotonic()
    done = 0
    try:
        for run in range(1, args.runs + 1):
            if args.minutes is not None and run > 1 and time.monotonic() - start > 60 * args.minutes:
                print(f"stopping after {done} run(s): the {args.minutes:g}-minute budget is spent", flush=True)
                break
            junit = keep / f"run{run}.xml"
            workers = str(args.workers if args.workers > 1 else 0)
            cmd = [sys.executable, "-m", "pytest", "-n", workers, "-q", "-p", "no:randomly", "-p", "no:cacheprovider",
                   f"--junitxml={junit}", *tests]
            res = subprocess.run(cmd, cwd=REPO, env=env, capture_output=True, text=True, check=False)
            outcomes = _outcomes(junit)
            for name, outcome in outcomes.items():
                counts.setdefault(name, Counter())[outcome] += 1
            failed = sorted(n for n, o in outcomes.items() if o == "failed")
            if res.returncode != 0:
                (keep / f"run{run}.log").write_text(res.stdout + res.stderr, encoding="utf-8")
            else:
                junit.unlink(missing_ok=True)
            done += 1
            print(f"run {run}/{args.runs}: exit {res.returncode}, {len(outcomes)} tests, "
                  f"{len(failed)} failed{': ' + ', '.join(failed) if failed else ''}", flush=True)
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()
    width = max(len(n) for n in counts) if counts else 4
    print(f"\n{len(tests)} test functions selected; {done} run(s) on {max(args.workers, 1)} pytest worker(s) beside "
          f"{args.hogs} CPU-bound job(s) on {os.cpu_count()} cores, {time.monotonic() - start:.0f} s; "
          f"failed runs kept in {keep}")
    print(f"{'test':<{width}}  passed  failed  skipped")
    for name in sorted(counts):
        c = counts[name]
        print(f"{name:<{width}}  {c['passed']:>6}  {c['failed']:>6}  {c['skipped']:>7}")
    bad = any(c["failed"] for c in counts.values()) or len(counts) == 0
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
