"""Heavy-hex compile time against Qiskit O3's on the same circuit and coupling map, side by side in one run.

Run: ``python benchmarks/hex_compile_speed.py [--repeats N] [CASE ...]`` (cases ``ROWSxCOLS/ROBOTS`` of the
default scenarios, or a scenario file; default ``5x5/2 4x4/2``). Per case and repeat, two fresh processes, one
after the other:

* **qcpp**: ``qcpp.compile(scenario, device="heavy-hex")``, what ``qcpp compile --grid 5x5 --robots 2 --device
  heavy-hex`` runs (the smallest heavy-hex lattice that holds the cell layout, native gates);
* **Qiskit O3**: ``qiskit.transpile(lowered, coupling_map=<the same lattice's couplings, both directions>,
  optimization_level=3, seed_transpiler=0)``, where ``lowered`` is the unrouted circuit of ``qcpp compile
  --lowered`` loaded by Qiskit's OpenQASM 3 reader (built before the clock starts).

``--screen``: instead, per case, ``qcpp compile`` as above with the cells' plan choice as by default (searching the
allocation of the default plan and :attr:`~qcpp.routing.options.RoutingOptions.cell_screen` screened variants, and
of the operand exchanges that pass :attr:`~qcpp.routing.options.RoutingOptions.cell_swap_screen`), with every
exchange searched (``cell_swap_screen=False``), and with every variant and every exchange searched
(``cell_screen=0``, ``cell_swap_screen=False``), side by side: times, two-qubit gates and a hash of the routed
circuit's gates (equal hashes: the same circuit) of each.

Each process imports everything first (qcpp, Qiskit, SciPy) and then times only the call, wall
(``time.perf_counter``) and CPU (this process's and that of its children waited for: both compilers run
in-process, Qiskit's Rust passes may use more than one thread and qcpp routes its large windows in a forked
process, which CPU time counts and wall time hides). Fresh processes keep
in-process memos of one repeat (qcpp's A* cache, Qiskit's) out of the next. The table gives medians over the
repeats, the ratio qcpp / Qiskit of the median CPU and wall times, the two-qubit gates of each result (a SWAP counts
3) and the load average before and after (the machine is shared: CPU time is the steadier figure).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import statistics
import subprocess
import sys
import time
from typing import Any

DEFAULT_CASES = ("5x5/2", "4x4/2")


def _scenario(case: str) -> Any:
    """The scenario of a case: ``RxC/K`` is the default scenario (as ``--grid RxC --robots K``), else a file."""
    if "/" in case and "x" in case.split("/")[0] and not os.path.exists(case):
        from qcpp.problem.presets import default_scenario

        grid, robots = case.split("/")
        rows, cols = (int(v) for v in grid.split("x"))
        return default_scenario(rows, cols, int(robots))
    from qcpp.problem.scenario_io import load_scenario

    return load_scenario(case)


def _warm_imports() -> None:
    """Import what either compiler loads lazily, so the clock measures the compile only."""
    import qiskit
    import qiskit.qasm3  # noqa: F401
    import scipy.sparse.csgraph  # noqa: F401
    from qiskit.transpiler import CouplingMap  # noqa: F401

    import qcpp.pipeline.device_compile  # noqa: F401


def _cpu() -> float:
    """CPU seconds of this process and of its children waited for (qcpp's process routing ahead)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def _timed(fn: Any) -> tuple[Any, float, float]:
    wall, cpu = time.perf_counter(), _cpu()
    out = fn()
    return out, time.perf_counter() - wall, _cpu() - cpu


def _worker_qcpp(case: str) -> dict[str, Any]:
    import qcpp

    _warm_imports()
    scenario = _scenario(case)
    out, wall, cpu = _timed(lambda: qcpp.compile(scenario, 1, device="heavy-hex"))
    summary = out.to_dict()
    return {"wall": wall, "cpu": cpu, "device": out.device.name, "twoq": summary["routed"]["two_qubit"],
            "layout": summary["routed"]["layout"], "coupling": [list(e) for e in out.device.coupling]}  # fmt: skip


def _worker_screen(case: str, screen: int, swap_screen: bool) -> dict[str, Any]:
    from dataclasses import replace

    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.routing.options import DEFAULT_ROUTING

    _warm_imports()
    scenario = _scenario(case)
    routing = replace(DEFAULT_ROUTING, cell_screen=screen, cell_swap_screen=swap_screen)
    out, wall, cpu = _timed(lambda: compile_for_device(scenario, 1, "heavy-hex", routing=routing))
    twoq = sum(1 for g in out.routed.circuit.gates if len(g[1]) == 2)
    digest = hashlib.sha256(repr(list(out.routed.circuit.gates)).encode()).hexdigest()[:12]
    return {"wall": wall, "cpu": cpu, "device": out.routed.device.name, "twoq": twoq, "layout": out.layout_method,
            "hash": digest}


def screen_table(cases: list[str], repeats: int) -> None:
    """The ``--screen`` table (module docs)."""
    print("| case | device | variants searched | exchanges searched | qcpp CPU s | qcpp wall s | qcpp 2q "
          "| gates hash |")  # fmt: skip
    print("|---|---|---|---|---:|---:|---:|---|")
    from qcpp.routing.options import DEFAULT_ROUTING

    for case in cases:
        for screen, swap_screen in ((DEFAULT_ROUTING.cell_screen, True), (DEFAULT_ROUTING.cell_screen, False),
                                    (0, False)):  # fmt: skip
            runs = [_run(["screen", case, str(screen), str(int(swap_screen))]) for _ in range(repeats)]
            label = f"default + {screen} screened" if screen else "every variant"
            swaps = "screened" if swap_screen else "every exchange"
            cpu, wall = (statistics.median(r[k] for r in runs) for k in ("cpu", "wall"))
            print(f"| {case} | {runs[0]['device']} ({runs[0]['layout']}) | {label} | {swaps} | {cpu:.1f} | {wall:.1f} "
                  f"| {runs[0]['twoq']:,} | {runs[0]['hash']} |", flush=True)  # fmt: skip


def _worker_qiskit(case: str, coupling: list[list[int]]) -> dict[str, Any]:
    import qiskit
    from qiskit.transpiler import CouplingMap

    import qcpp

    _warm_imports()
    circuit = qcpp.compile(_scenario(case), 1, lowered=True).to_qiskit()
    cmap = CouplingMap([*coupling, *([b, a] for a, b in coupling)])
    out, wall, cpu = _timed(
        lambda: qiskit.transpile(circuit, coupling_map=cmap, optimization_level=3, seed_transpiler=0)
    )
    ops = out.count_ops()
    twoq = sum(n for name, n in ops.items() if name != "swap" and _arity(out, name) == 2) + 3 * ops.get("swap", 0)
    return {"wall": wall, "cpu": cpu, "twoq": twoq}


def _arity(circuit: Any, name: str) -> int:
    return next(len(inst.qubits) for inst in circuit.data if inst.operation.name == name)


def _run(args: list[str]) -> dict[str, Any]:
    out = subprocess.run([sys.executable, __file__, "--worker", *args], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])  # type: ignore[no-any-return]


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", default=list(DEFAULT_CASES))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--screen", action="store_true", help="the cells' screened plan choice against every variant")
    parser.add_argument("--worker", nargs="+", help=argparse.SUPPRESS)
    a = parser.parse_args(argv)
    if a.worker:
        kind, case, *rest = a.worker
        if kind == "qcpp":
            result = _worker_qcpp(case)
        elif kind == "screen":
            result = _worker_screen(case, int(rest[0]), bool(int(rest[1])))
        else:
            result = _worker_qiskit(case, json.loads(rest[0]))
        print(json.dumps(result))
        return 0
    import qiskit

    import qcpp

    print(f"qcpp from {os.path.dirname(qcpp.__file__)}, Qiskit {qiskit.__version__}, {os.cpu_count()} cores, "
          f"{a.repeats} repeats, medians; load average before: {os.getloadavg()[0]:.1f}")  # fmt: skip
    print()
    if a.screen:
        screen_table(a.cases, a.repeats)
        print()
        print(f"load average after: {os.getloadavg()[0]:.1f}")
        return 0
    print("| case | device | qcpp CPU s | qcpp wall s | Qiskit O3 CPU s | Qiskit O3 wall s | CPU ratio | "
          "wall ratio | qcpp 2q | Qiskit O3 2q |")  # fmt: skip
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for case in a.cases:
        ours: list[dict[str, Any]] = []
        theirs: list[dict[str, Any]] = []
        for _ in range(a.repeats):
            ours.append(_run(["qcpp", case]))
            theirs.append(_run(["qiskit", case, json.dumps(ours[0]["coupling"])]))
        q = {k: statistics.median(r[k] for r in ours) for k in ("cpu", "wall")}
        k = {k: statistics.median(r[k] for r in theirs) for k in ("cpu", "wall")}
        print(f"| {case} | {ours[0]['device']} ({ours[0]['layout']}) | {q['cpu']:.1f} | {q['wall']:.1f} | "
              f"{k['cpu']:.1f} | {k['wall']:.1f} | {q['cpu'] / k['cpu']:.1f}x | {q['wall'] / k['wall']:.1f}x | "
              f"{ours[0]['twoq']:,} | {theirs[0]['twoq']:,} |", flush=True)  # fmt: skip
    print()
    print(f"load average after: {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
