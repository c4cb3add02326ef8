"""Print a fingerprint of qcpp's observable behaviour: estimate rows and compiled OpenQASM, hashed per case.

Run it before and after a refactoring that must not change behaviour and diff the two outputs::

    python scripts/behaviour_fingerprint.py > before.txt
    # ... change the code ...
    python scripts/behaviour_fingerprint.py > after.txt && diff before.txt after.txt

Every case drives the ``qcpp`` command line (the interface users have), so the script runs unchanged across changes
of the import paths. Timing fields and output paths are dropped from JSON before hashing.
``--quick`` keeps the cases that finish in a few seconds each.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TIMING = {"path", "seconds", "wall_s", "cpu_s", "elapsed_s", "time_s", "build_s", "peak_rss_mb"}

ESTIMATES = [
    "--grid 3x3,4x4,5x5,6x6 --robots 1..3 --compare paper",
    "--grid 2x2..8x8 --robots 1..3 -p 1..2",
    "--grid 10x10 --robots 4 --target ft",
    "--grid 5x5 --robots 2 --rule paper",
    "--grid 4x4 --robots 2 --explain",
    "--grid 3x3..4x4 --robots 1..2 --device grid",
    "--grid 3x3 --robots 1..2 --device heavy-hex",
    "--grid 3x3 --robots 1 --device ibm_fez",
    "--grid 30x30 --robots 8 -p 3 --device grid",
]
COMPILES = [
    "examples/paper_3x3.toml -p 1",
    "examples/paper_3x3.toml -p 2 --lowered",
    "examples/paper_3x3.toml -p 1 --lowered --bind gamma_0=0.3 beta_0=0.7 --qasm-version 2",
    "examples/two_robots_4x4.toml -p 1 --lowered",
    "examples/two_robots_5x5.toml --target ft -p 1",
    "examples/obstacles_hard_4x4.toml -p 1 --lowered --rule paper",
    "examples/paper_3x3.toml -p 1 --device grid",
    "examples/paper_3x3.toml -p 1 --device heavy-hex",
    "examples/paper_3x3.toml -p 1 --device ibm_fez",
    "examples/two_robots_4x4.toml -p 1 --device grid",
    "examples/paper_3x3.toml -p 1 --device ibm_fez --optimize-for twoq",
    "examples/paper_3x3.toml -p 1 --device ibm_fez --zero-start",
]
SLOW = {
    "--grid 30x30 --robots 8 -p 3 --device grid",
    "examples/two_robots_4x4.toml -p 1 --device grid",
    "examples/paper_3x3.toml -p 1 --device ibm_fez --optimize-for twoq",
    "examples/paper_3x3.toml -p 1 --device ibm_fez --zero-start",
}


def _scrub(value: object) -> object:
    if isinstance(value, dict):
        return {k: _scrub(v) for k, v in value.items() if k not in TIMING and not k.endswith("_seconds")}
    if isinstance(value, list):
        return [_scrub(v) for v in value]
    return value


def _digest(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _run(args: list[str]) -> str:
    done = subprocess.run([sys.executable, "-m", "qcpp", *args], cwd=ROOT, capture_output=True, text=True)
    if done.returncode != 0:
        return f"exit {done.returncode}: {done.stderr.strip().splitlines()[-1] if done.stderr.strip() else ''}"
    return done.stdout


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="skip the cases that take more than a few seconds")
    quick = parser.parse_args().quick
    for case in ESTIMATES:
        if quick and case in SLOW:
            continue
        out = _run(["estimate", *case.split(), "--json"])
        try:
            print(f"estimate {case}: {_digest(json.dumps(_scrub(json.loads(out)), sort_keys=True))}")
        except json.JSONDecodeError:
            print(f"estimate {case}: {out.strip()[:200]}")
    with tempfile.TemporaryDirectory() as tmp:
        for case in COMPILES:
            if quick and case in SLOW:
                continue
            qasm = Path(tmp) / "out.qasm"
            out = _run(["compile", *case.split(), "--qasm", str(qasm), "--json"])
            try:
                summary = _digest(json.dumps(_scrub(json.loads(out)), sort_keys=True))
            except json.JSONDecodeError:
                summary = out.strip()[:200]
            text = qasm.read_text() if qasm.exists() else ""
            print(f"compile {case}: json {summary} qasm {_digest(text)} ({len(text)} bytes)")
            qasm.unlink(missing_ok=True)


if __name__ == "__main__":
    main()
