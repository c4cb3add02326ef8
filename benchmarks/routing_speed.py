"""The two speed goals of hardware-aware compilation, timed as a user runs them (fresh processes, wall time).

Run: ``python benchmarks/routing_speed.py``. Prints one table row per command:

* ``qcpp estimate --grid 30x30 --robots 8 -p 3 --device heavy-hex --json`` (goal: under 10 s);
* ``qcpp compile <6x6, 3 robots> --device grid --bind ... --qasm FILE --json`` (goal: under 30 s), with the
  routed two-qubit count, the device and the layout it reports.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from gridcover.presets import default_scenario
from gridcover.scenario import scenario_to_dict


def timed(args: list[str]) -> tuple[float, str]:
    """Wall seconds and standard output of ``python -m qcpp ARGS``."""
    start = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "qcpp", *args], capture_output=True, text=True, check=True)
    return time.perf_counter() - start, out.stdout


def main() -> None:
    print("| command | goal | wall time | result |")
    print("|---|---:|---:|---|")
    seconds, out = timed(["estimate", "--grid", "30x30", "--robots", "8", "-p", "3", "--device", "heavy-hex", "--json"])
    (row,) = json.loads(out)
    print(
        f"| `qcpp estimate --grid 30x30 --robots 8 -p 3 --device heavy-hex --json` | 10 s | {seconds:.1f} s "
        f"| {row['device']}, routed_kind {row['routed_kind']}, routed_twoq {row['routed_twoq']:,} |",
        flush=True,
    )
    with tempfile.TemporaryDirectory() as tmp:
        scen = Path(tmp) / "default_6x6_3.json"
        scen.write_text(json.dumps(scenario_to_dict(default_scenario(6, 6, 3))))
        qasm = Path(tmp) / "routed.qasm"
        args = ["compile", str(scen), "--device", "grid", "--bind", "gamma_0=0.3", "beta_0=0.7", "--qasm", str(qasm)]
        seconds, out = timed([*args, "--json"])
    summary = json.loads(out)
    routed = summary["routed"]
    print(
        f"| `qcpp compile <default 6x6/3> --device grid --qasm FILE --json` | 30 s | {seconds:.1f} s "
        f"| {summary['device']['name']}, layout {routed['layout']}, {routed['two_qubit']:,} two-qubit gates |",
        flush=True,
    )


if __name__ == "__main__":
    main()
