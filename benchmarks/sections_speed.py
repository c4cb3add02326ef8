"""How long building the QAOA plan's sections takes on the device layouts, by size, and whether the gates change.

Run: ``python benchmarks/sections_speed.py [--sizes 10x10/4,16x16/8,20x20/8,30x30/8] [--against REV]
[--limit S]``.

Each row builds exactly the sections ``qcpp compile --device`` and the routed estimate build before routing:
``qaoa_plan(default_scenario(rows, cols, robots), 1, device_plan_options(PlanOptions(), device)).sections()``, on
``grid`` (the ``medial`` phase layout: local-first adders drifting to the balance sinks,
:func:`qcpp.gadgets.phase_sums.spatial_popcount_layout`) and ``heavy-hex`` (the ``spatial`` layout:
passes along the Hilbert curve), in a fresh process with the tree's ``src`` first on the path. Printed per row:
the build's wall and CPU seconds (the sections listed, nothing emitted), the seconds to emit every section's gates
afterwards, the number of gates and a hash of every section's name and gates and every balance gadget's ancilla
sites (the hash is computed after the timings).

With ``--against REV`` the same rows run on ``REV``'s ``src/`` (``git archive`` into a temporary directory) in the
same run, alternating which tree goes first, and ``same`` says whether both trees emitted the same gates in the
same order (equal hashes). A build past ``--limit`` seconds (default 600) is stopped and shown as ``>limit``.
The load average is printed before and after (the machine has 2 cores shared with other jobs).

``--compile SPEC:VARIANT,...`` (with ``--against``) instead runs ``qcpp compile SCENARIO --lowered --qasm -`` on
both trees and compares the OpenQASM bytes (a hash of standard output) and the wall seconds; ``VARIANT`` is
``grid`` or ``heavy-hex`` (``--device``), or ``medial`` / ``spatial`` (``--phase-layout`` on the all-to-all
compile, two layers), on ``default_scenario`` of ``SPEC`` (e.g. ``8x8/3:grid``).
"""

from __future__ import annotations

import argparse
import hashlib
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from estimate_speed import _export

from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario_io import save_scenario

ROOT = Path(__file__).resolve().parents[1]
SIZES = "10x10/4,16x16/8,20x20/8,30x30/8"
DEVICES = ("grid", "heavy-hex")

CHILD = """
import hashlib, sys, time
from qcpp.gadgets.phase_sums import SumsPhase
from qcpp.plan.options import PlanOptions
from qcpp.pipeline.device_plan import device_plan_options
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.presets import default_scenario
rows, cols, robots, device = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
plan = qaoa_plan(default_scenario(rows, cols, robots), 1, device_plan_options(PlanOptions(), device))
wall, cpu = time.perf_counter(), time.process_time()
sections = list(plan.sections())
wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
emit = time.perf_counter()
emitted = [(name, g.emit()) for name, g in sections]
emit = time.perf_counter() - emit
h = hashlib.sha256()
for (name, gates), (_, g) in zip(emitted, sections):
    h.update(name.encode())
    for gate in gates:
        h.update(repr(gate).encode())
    if isinstance(g, SumsPhase):
        h.update(repr(sorted(g.ancilla_sites().items())).encode())
print(wall, cpu, emit, sum(len(gates) for _, gates in emitted), h.hexdigest()[:16])
"""


def _build(src: Path, spec: str, device: str, limit: float) -> tuple[float, float, float, int, str] | None:
    """``(build wall s, build CPU s, emit s, gates, hash)`` of one size on one device with ``src`` first on the
    path, ``None`` past ``limit`` seconds."""
    grid, robots = spec.split("/")
    rows, cols = grid.split("x")
    env = {**os.environ, "PYTHONPATH": str(src) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    try:
        out = subprocess.run(
            [sys.executable, "-c", CHILD, rows, cols, robots, device],
            env=env, capture_output=True, text=True, timeout=limit, check=True,
        )  # fmt: skip
    except subprocess.TimeoutExpired:
        return None
    wall, cpu, emit, gates, digest = out.stdout.split()
    return float(wall), float(cpu), float(emit), int(gates), digest


def _compile(src: Path, spec: str, variant: str, limit: float, tmp: Path) -> tuple[float, str] | None:
    """``(wall s, hash of the OpenQASM)`` of ``qcpp compile`` on ``default_scenario`` of ``spec`` with ``src``
    first on the path, ``None`` past ``limit`` seconds or on failure."""
    grid, robots = spec.split("/")
    rows, cols = grid.split("x")
    path = tmp / f"{rows}x{cols}_{robots}.json"
    save_scenario(default_scenario(int(rows), int(cols), int(robots)), path)
    flags = ["--device", variant] if variant in DEVICES else ["--phase-layout", variant, "-p", "2"]
    env = {**os.environ, "PYTHONPATH": str(src) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    start = time.perf_counter()
    try:
        out = subprocess.run(
            [sys.executable, "-m", "qcpp", "compile", str(path), "--lowered", "--qasm", "-", *flags],
            env=env, capture_output=True, timeout=limit, cwd=ROOT,
        )  # fmt: skip
    except subprocess.TimeoutExpired:
        return None
    if out.returncode != 0 or not out.stdout:
        return None
    return time.perf_counter() - start, hashlib.sha256(out.stdout).hexdigest()[:16]


def compare_compiles(rev: str, cases: list[str], limit: float) -> None:
    """Print, per ``SPEC:VARIANT``, both trees' ``qcpp compile`` seconds and whether their OpenQASM is equal."""
    with tempfile.TemporaryDirectory() as tmp:
        trees = {"this tree": ROOT / "src", rev: _export(rev, Path(tmp))}
        print(" | ".join(["scenario", "variant", "this tree s", f"{rev} s", "qasm hash", "same"]))
        for i, case in enumerate(cases):
            spec, variant = case.split(":")
            order = list(trees.items()) if i % 2 == 0 else list(reversed(trees.items()))
            got = {name: _compile(src, spec, variant, limit, Path(tmp)) for name, src in order}
            ours, theirs = got["this tree"], got[rev]
            same = "?" if ours is None or theirs is None else "yes" if ours[1] == theirs[1] else "no"
            print(" | ".join([
                spec, variant, f"{ours[0]:.1f}" if ours else f">{limit:.0f}", f"{theirs[0]:.1f}" if theirs else
                f">{limit:.0f}", ours[1] if ours else "", same,
            ]), flush=True)  # fmt: skip


def _cell(r: tuple[float, float, float, int, str] | None, limit: float) -> list[str]:
    if r is None:
        return [f">{limit:.0f}", "", "", "", ""]
    return [f"{r[0]:.2f}", f"{r[1]:.2f}", f"{r[2]:.2f}", f"{r[3]:,}", r[4]]


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default=SIZES, help="comma-separated ROWSxCOLS/ROBOTS")
    ap.add_argument("--against", metavar="REV", help="also run REV's src/ and compare")
    ap.add_argument("--limit", type=float, default=600.0, help="seconds before a build is stopped")
    ap.add_argument("--compile", metavar="SPEC:VARIANT,...", help="compare qcpp compile output instead")
    args = ap.parse_args(argv)
    load = os.getloadavg()
    print(f"machine: {os.cpu_count()} cores, load average {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f}")
    if args.compile:
        if not args.against:
            ap.error("--compile needs --against REV")
        compare_compiles(args.against, args.compile.split(","), args.limit)
        load = os.getloadavg()
        print(f"load average after: {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f}")
        return 0
    head = ["size", "device", "build s", "cpu s", "emit s", "gates", "hash"]
    with tempfile.TemporaryDirectory() as tmp:
        trees = {"this tree": ROOT / "src"}
        if args.against:
            trees[args.against] = _export(args.against, Path(tmp))
            head += [f"{args.against} build s", "cpu s", "emit s", "gates", "hash", "same"]
        print(" | ".join(head))
        for i, spec in enumerate(args.sizes.split(",")):
            for device in DEVICES:
                order = list(trees.items()) if i % 2 == 0 else list(reversed(trees.items()))
                got = {name: _build(src, spec, device, args.limit) for name, src in order}
                row = [spec, device, *_cell(got["this tree"], args.limit)]
                if args.against:
                    theirs = got[args.against]
                    both = got["this tree"] is not None and theirs is not None
                    same = "yes" if both and got["this tree"][4] == theirs[4] else "no" if both else "?"
                    row += [*_cell(theirs, args.limit), same]
                print(" | ".join(row), flush=True)
    load = os.getloadavg()
    print(f"load average after: {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
