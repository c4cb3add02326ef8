"""Which OpenQASM 3 client loads which export profile, and does it simulate qcpp's state?

Run: ``python benchmarks/qasm_clients.py [--cache DIR] [--quick | --constructs]``.

qcpp writes each scenario's p = 1 circuit in every profile (:data:`qcpp.lowering.qasm_profiles.PROFILES`), bound
(``gamma_0 = 0.3``, ``beta_0 = 0.7``) and unbound (``input float[64]``), high level and ``--lowered``, and hands each
file unchanged to each client:

* beside qcpp (this interpreter): Qiskit (``qiskit.qasm3.loads``), Cirq (``cirq.contrib.qasm_import``), the QDK
  (``qdk.openqasm.import_openqasm``; and its resource estimator, ``qdk.openqasm.estimate``), pyqasm (``loads``,
  ``validate``, ``unroll``), openqasm3 (the reference parser, ``parse``);
* in their own virtual environments under the cache folder (default ``~/.cache/qcpp-qasm-clients``; their pins
  conflict with qcpp's quimb and dask), created and filled with :data:`PINS` on first use: Amazon Braket's local
  simulator (``LocalSimulator("braket_sv")`` on ``braket.ir.openqasm.Program``) and PennyLane's ``from_qasm3``
  (``default.qubit``).

A client that simulates gives its final state (an unbound file with the same values through the client's own
inputs: Qiskit ``assign_parameters``, Cirq ``ParamResolver``, Braket ``inputs``, PennyLane keyword arguments); the
fidelity ``|<qcpp|client>|^2`` against :func:`qcpp.simulate.statevector.simulate_statevector` of the circuit is
1.0 up to rounding for an exact load (global phase does not count). The first table counts files loaded and the
lowest fidelity per client and profile; the second gives each distinct error's first line.

``--constructs`` asks instead why no one profile serves every client: each client gets one tiny two-qubit file per
way of writing a gate (:data:`CONSTRUCTS`: the standard library by include, its names without the include,
OpenQASM 2's built-in ``CX``, the specification's built-ins ``U`` and ``ctrl @``, Braket's names, a ``gate``
definition, an ``input`` as a gate argument), and the script prints which client loads which, with the fidelity to
the state the file prepares, then which clients each way of writing an entangling gate reaches.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from qcpp.api.compiling import compile as qcpp_compile
from qcpp.api.scenarios import grid_scenario
from qcpp.lowering.qasm_profiles import PROFILES
from qcpp.simulate.statevector import simulate_statevector

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
SCENARIOS = ((3, 3, 1), (2, 3, 2))
PINS: dict[str, list[str]] = {
    "braket": ["amazon-braket-sdk==1.127.5", "amazon-braket-default-simulator==1.41.2"],
    "pennylane": ["pennylane==0.45.1", "openqasm3[parser]==1.0.1"],
}
"""Client -> the pip requirements of its virtual environment."""

# Runs inside a client's virtual environment: reads a JSON job list, writes one JSON result per job (and the
# state as .npy, big-endian as both clients give it).
RUNNER = r'''
import json, sys, warnings
import numpy as np

def first_line(exc):
    lines = [s for s in f"{type(exc).__name__}: {exc}".splitlines() if s.strip()]
    return lines[0][:200] if lines else type(exc).__name__

def braket_state(text, n, inputs):
    from braket.devices import LocalSimulator
    from braket.ir.openqasm import Program
    src = text + "\n#pragma braket result state_vector\n"
    result = LocalSimulator("braket_sv").run(Program(source=src, inputs=inputs), shots=0).result()
    return np.asarray(result.values[0])

def pennylane_state(text, n, inputs):
    import pennylane as qml
    fn = qml.from_qasm3(text)
    dev = qml.device("default.qubit", wires=[f"q[{i}]" for i in range(n)])

    @qml.qnode(dev)
    def circuit():
        fn(**inputs)
        return qml.state()

    return np.asarray(circuit())

run = {"braket": braket_state, "pennylane": pennylane_state}[sys.argv[1]]
with open(sys.argv[2]) as f:
    jobs = json.load(f)
for job in jobs:
    out = {"id": job["id"], "ok": False, "error": None}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            with open(job["path"]) as f:
                text = f.read()
            state = run(text, job["qubits"], job["inputs"])
            np.save(job["path"] + ".npy", state)
            out["ok"] = True
        except BaseException as exc:
            out["error"] = first_line(exc)
    print(json.dumps(out), flush=True)
'''


@dataclass(frozen=True)
class Case:
    """One file: a scenario's circuit in one profile."""

    scenario: str
    bound: bool
    lowered: bool
    profile: str
    path: Path
    qubits: int
    reference: np.ndarray = field(repr=False, compare=False)

    @property
    def id(self) -> str:
        return f"{self.scenario} {'bound' if self.bound else 'unbound'} {'lowered' if self.lowered else 'high'}"


@dataclass
class Outcome:
    """What one client did with one file."""

    loaded: bool
    fidelity: float | None = None
    error: str | None = None


def first_line(exc: BaseException) -> str:
    lines = [s for s in f"{type(exc).__name__}: {exc}".splitlines() if s.strip()]
    return lines[0][:200] if lines else type(exc).__name__


def little_endian(state: np.ndarray, n: int) -> np.ndarray:
    """A big-endian state (qubit 0 the most significant bit) in qcpp's and Qiskit's order."""
    return np.asarray(state).reshape([2] * n).transpose(list(range(n))[::-1]).reshape(-1)


def fidelity(reference: np.ndarray, state: np.ndarray) -> float:
    state = np.asarray(state, dtype=complex).reshape(-1)
    if state.shape != reference.shape:
        raise ValueError(f"state has {state.size} amplitudes, qcpp's {reference.size}")
    norms = np.vdot(state, state).real * np.vdot(reference, reference).real
    return float(abs(np.vdot(reference, state)) ** 2 / norms)


# --- clients beside qcpp ---------------------------------------------------------------------------------------
def qiskit_client(text: str, case: Case) -> np.ndarray | None:
    import qiskit.qasm3
    from qiskit.quantum_info import Statevector

    qc = qiskit.qasm3.loads(text)
    if qc.parameters:
        qc = qc.assign_parameters({p: BIND[p.name] for p in qc.parameters})
    return np.asarray(Statevector(qc).data)


def cirq_client(text: str, case: Case) -> np.ndarray | None:
    import cirq
    from cirq.contrib.qasm_import import circuit_from_qasm

    circuit = circuit_from_qasm(text)
    order = [cirq.NamedQubit(f"q_{i}") for i in range(case.qubits)]
    resolver = cirq.ParamResolver(BIND)
    result = cirq.Simulator(dtype=np.complex128).simulate(circuit, param_resolver=resolver, qubit_order=order)
    return little_endian(result.final_state_vector, case.qubits)


def qdk_client(text: str, case: Case) -> np.ndarray | None:
    from qdk import qsharp
    from qdk.openqasm import ProgramType, import_openqasm

    qsharp.init()
    if not case.bound:  # the inputs become the parameters of an operation: loading is all it does
        import_openqasm(text, name="program")
        return None
    import_openqasm(text, program_type=ProgramType.Fragments)
    return little_endian(np.asarray(qsharp.dump_machine().as_dense_state()), case.qubits)


def qdk_estimate_client(text: str, case: Case) -> np.ndarray | None:
    import warnings

    from qdk import openqasm

    from qcpp.estimators.qdk_reading import LEGACY_QRE_WARNING

    with warnings.catch_warnings():  # the legacy estimator qdk_read uses (see its docstring); no other is silenced
        warnings.filterwarnings("ignore", message=LEGACY_QRE_WARNING, category=DeprecationWarning)
        openqasm.estimate(text)  # the QDK's resource estimator (default qubit model and QEC scheme)
    return None


def pyqasm_client(text: str, case: Case) -> np.ndarray | None:
    import pyqasm

    limit = getattr(sys, "tracebacklimit", None)
    try:
        module = pyqasm.loads(text)
        module.validate()
        module.unroll()
    finally:  # pyqasm sets sys.tracebacklimit = 0 for the whole process when it raises
        sys.tracebacklimit = limit  # type: ignore[assignment]
    return None


def openqasm3_client(text: str, case: Case) -> np.ndarray | None:
    import openqasm3

    openqasm3.parse(text)
    return None


LOCAL: dict[str, Callable[[str, Case], np.ndarray | None]] = {
    "qiskit": qiskit_client,
    "cirq": cirq_client,
    "qdk": qdk_client,
    "qdk estimate": qdk_estimate_client,
    "pyqasm": pyqasm_client,
    "openqasm3": openqasm3_client,
}


def run_local(name: str, case: Case) -> Outcome:
    text = case.path.read_text()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            state = LOCAL[name](text, case)
        except BaseException as exc:  # the QDK raises BaseException subclasses
            if isinstance(exc, KeyboardInterrupt):
                raise
            return Outcome(False, error=first_line(exc))
    return Outcome(True, None if state is None else fidelity(case.reference, state))


# --- clients in their own virtual environments -----------------------------------------------------------------
def venv_python(cache: Path, client: str) -> Path:
    """The client's environment's interpreter, created and filled with :data:`PINS` if missing."""
    env = cache / client
    python = env / "bin" / "python"
    stamp = env / "qcpp-pins.txt"
    pins = "\n".join(PINS[client])
    if python.exists() and stamp.exists() and stamp.read_text() == pins:
        return python
    print(f"creating {env} with {' '.join(PINS[client])}", file=sys.stderr)
    subprocess.run([sys.executable, "-m", "venv", "--clear", str(env)], check=True)
    subprocess.run([str(python), "-m", "pip", "install", "-q", *PINS[client]], check=True)
    stamp.write_text(pins)
    return python


def run_venv(cache: Path, client: str, cases: list[Case], work: Path) -> dict[str, Outcome]:
    jobs = [
        {"id": str(c.path), "path": str(c.path), "qubits": c.qubits, "inputs": {} if c.bound else BIND} for c in cases
    ]
    (work / f"{client}-jobs.json").write_text(json.dumps(jobs))
    (work / "runner.py").write_text(RUNNER)
    proc = subprocess.run(
        [str(venv_python(cache, client)), str(work / "runner.py"), client, str(work / f"{client}-jobs.json")],
        capture_output=True,
        text=True,
        check=False,
    )
    results = {}
    for line in proc.stdout.splitlines():
        if line.startswith("{"):
            r = json.loads(line)
            results[r["id"]] = r
    out = {}
    for c in cases:
        r = results.get(str(c.path))
        if r is None:
            out[str(c.path)] = Outcome(False, error=f"runner failed: {proc.stderr.strip().splitlines()[-1:]}")
            continue
        fid = None
        if r["ok"]:
            fid = fidelity(c.reference, little_endian(np.load(str(c.path) + ".npy"), c.qubits))
        out[str(c.path)] = Outcome(r["ok"], fid, r["error"])
    return out


# --- one construct per file ---------------------------------------------------------------------------------------
BELL = np.array([1, 0, 0, 1]) / np.sqrt(2)
PLUS0 = np.array([1, 1, 0, 0]) / np.sqrt(2)  # (|0> + |1>) on q[0], |0> on q[1]; little-endian
CONSTRUCTS: dict[str, tuple[str, str, np.ndarray, bool]] = {
    "std gates by include": (
        'include "stdgates.inc";\nqubit[2] q;\nh q[0];\ncx q[0], q[1];\n', "entangler", BELL, True),
    "std gate names, no include": ("qubit[2] q;\nh q[0];\ncx q[0], q[1];\n", "entangler", BELL, True),
    "built-in CX (OpenQASM 2)": ("qubit[2] q;\nU(pi/2, 0, pi) q[0];\nCX q[0], q[1];\n", "entangler", BELL, True),
    "built-ins U and ctrl @": (
        "qubit[2] q;\nU(pi/2, 0, pi) q[0];\nctrl @ U(pi, 0, pi) q[0], q[1];\n", "entangler", BELL, True),
    "Braket names (cnot)": ("qubit[2] q;\nh q[0];\ncnot q[0], q[1];\n", "entangler", BELL, True),
    "built-in U alone": ("qubit[2] q;\nU(pi/2, 0, pi) q[0];\nU(0, 0, 0) q[1];\n", "one-qubit", PLUS0, True),
    "gate definition": (
        "gate hh a { U(pi/2, 0, pi) a; }\nqubit[2] q;\nhh q[0];\nhh q[1];\nhh q[1];\n", "one-qubit", PLUS0, True),
    "input as gate argument": (
        "input float[64] gamma_0;\ninput float[64] beta_0;\nqubit[2] q;\nU(gamma_0 + beta_0 + pi/2 - 1, 0, pi) q[0];\n"
        "U(gamma_0 + beta_0 - 1, 0, 0) q[1];\n",
        "one-qubit", PLUS0, False),
    "gate definition, std names": (
        "gate hh a { h a; }\nqubit[2] q;\nhh q[0];\nhh q[1];\nhh q[1];\n", "one-qubit", PLUS0, True),
    "input as gate argument, std names": (
        "input float[64] gamma_0;\ninput float[64] beta_0;\nqubit[2] q;\nry(gamma_0 + beta_0 + pi/2 - 1) q[0];\n"
        "ry(gamma_0 + beta_0 - 1) q[1];\n",
        "one-qubit", PLUS0, False),
}  # fmt: skip
"""Name -> (program after ``OPENQASM 3.0;``, kind, the state it prepares, bound). Each file uses one construct
beside the fewest others and acts on both qubits (a simulator may drop an idle one); the unbound ones, given
:data:`BIND` (``gamma_0 + beta_0 = 1``), prepare the same state."""


def constructs(cache: Path) -> None:
    """The ``--constructs`` tables (module docs). The QDK's estimator is left out: it reads the file as the QDK does,
    then refuses a program without a magic state or a measurement (``AlgorithmHasNoResources``), as these are."""
    local = [name for name in LOCAL if name != "qdk estimate"]
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        cases = []
        for i, (name, (body, _, state, bound)) in enumerate(CONSTRUCTS.items()):
            path = work / f"construct{i}.qasm"
            path.write_text("OPENQASM 3.0;\n" + body)
            cases.append(Case(name, bound, True, "construct", path, 2, state))
        outcomes: dict[tuple[str, str], Outcome] = {}
        for client in local:
            for c in cases:
                outcomes[(client, c.scenario)] = run_local(client, c)
        for client in PINS:
            for c, o in zip(cases, run_venv(cache, client, cases, work).values(), strict=True):
                outcomes[(client, c.scenario)] = o
    clients = [*local, *PINS]
    print("Cell: loaded (with the fidelity to the state the file prepares, where the client simulates) or the error's "
          "first words.\n")  # fmt: skip
    print("| construct | " + " | ".join(clients) + " |")
    print("|---|" + "---|" * len(clients))
    for c in cases:
        row = []
        for client in clients:
            o = outcomes[(client, c.scenario)]
            if o.loaded:
                row.append("yes" if o.fidelity is None else f"yes, {o.fidelity:.6f}")
            else:
                row.append("no: " + (o.error or "").split(":")[0].replace("|", "/"))
        print(f"| {c.scenario} | " + " | ".join(row) + " |")
    print()
    entanglers = [c for c in cases if CONSTRUCTS[c.scenario][1] == "entangler"]
    for c in entanglers:
        missing = [client for client in clients if not outcomes[(client, c.scenario)].loaded]
        print(f"- {c.scenario}: refused by {', '.join(missing) or 'none'}")
    print("\n| client | construct | error (first line) |\n|---|---|---|")
    for client in clients:
        for c in cases:
            o = outcomes[(client, c.scenario)]
            if o.error:
                print(f"| {client} | {c.scenario} | `{o.error.replace('|', '/')[:110]}` |")
    every = [c.scenario for c in entanglers if all(outcomes[(k, c.scenario)].loaded for k in clients)]
    print(f"\nWays to write an entangling gate that every client loads: {', '.join(every) or 'none'}.")
    print(f"\nclients: {', '.join(f'{k} ({v})' for k, v in client_versions(cache).items())}")


# --- cases and the tables ---------------------------------------------------------------------------------------
def make_cases(work: Path, scenarios: tuple[tuple[int, int, int], ...]) -> list[Case]:
    cases = []
    for rows, cols, robots in scenarios:
        name = f"{rows}x{cols}/{robots}"
        for lowered in (False, True):
            for bound in (True, False):
                compiled = qcpp_compile(
                    grid_scenario(rows, cols, robots=robots), lowered=lowered, bind=BIND if bound else None
                )
                reference = simulate_statevector(compiled.circuit.bind(BIND) if not bound else compiled.circuit)
                for profile in PROFILES:
                    tag = f"{rows}x{cols}_{robots}_{'b' if bound else 'u'}_{'l' if lowered else 'h'}_{profile}"
                    path = work / f"{tag}.qasm"
                    compiled.write_qasm(path, profile=profile)
                    cases.append(Case(name, bound, lowered, profile, path, compiled.qubits, reference))
    return cases


def cell(outcomes: list[Outcome]) -> str:
    loaded = sum(o.loaded for o in outcomes)
    fids = [o.fidelity for o in outcomes if o.fidelity is not None]
    text = f"{loaded}/{len(outcomes)}"
    if fids:
        text += f", fidelity {min(fids):.6f} ({len(fids)} states)"
    return text


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", type=Path, default=Path.home() / ".cache" / "qcpp-qasm-clients")
    parser.add_argument("--quick", action="store_true", help="the 3x3 one-robot scenario only")
    parser.add_argument("--constructs", action="store_true", help="one tiny file per way of writing a gate")
    args = parser.parse_args(argv)
    cache: Path = args.cache.expanduser()
    cache.mkdir(parents=True, exist_ok=True)
    if args.constructs:
        constructs(cache)
        return 0
    scenarios = SCENARIOS[:1] if args.quick else SCENARIOS
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        cases = make_cases(work, scenarios)
        outcomes: dict[tuple[str, str], Outcome] = {}
        for name in LOCAL:
            for c in cases:
                outcomes[(name, str(c.path))] = run_local(name, c)
        for client in PINS:
            for key, o in run_venv(cache, client, cases, work).items():
                outcomes[(client, key)] = o
    clients = [*LOCAL, *PINS]
    scen = ", ".join(f"{r}x{c}/{k}" for r, c, k in scenarios)
    print(f"Files per cell: {len(cases) // len(PROFILES)} ({scen}; bound and unbound; high level and lowered), p = 1.")
    print("Cell: files loaded / files, and the lowest fidelity to qcpp's state over the states the client gave.\n")
    print("| client | " + " | ".join(PROFILES) + " |")
    print("|---|" + "---|" * len(PROFILES))
    for client in clients:
        row = [cell([outcomes[(client, str(c.path))] for c in cases if c.profile == prof]) for prof in PROFILES]
        print(f"| {client} | " + " | ".join(row) + " |")
    print("\n| client | profile | files | error (first line) |\n|---|---|---|---|")
    for client in clients:
        for prof in PROFILES:
            errors: dict[str, list[str]] = {}
            for c in cases:
                o = outcomes[(client, str(c.path))]
                if c.profile == prof and o.error:
                    errors.setdefault(o.error, []).append(c.id)
            for err, ids in errors.items():
                which = "all" if len(ids) == len(cases) // len(PROFILES) else "; ".join(ids)
                print(f"| {client} | {prof} | {which} | `{err.replace('|', '/')}` |")
    versions = {"python": sys.version.split()[0], "platform": sys.platform, "cpus": os.cpu_count()}
    print(f"\nclients: {', '.join(f'{k} ({v})' for k, v in client_versions(cache).items())}; {versions}")
    return 0


def client_versions(cache: Path) -> dict[str, str]:
    from importlib.metadata import PackageNotFoundError, version

    out: dict[str, Any] = {}
    for dist in ("qiskit", "qiskit-qasm3-import", "cirq-core", "qdk", "pyqasm", "openqasm3"):
        try:
            out[dist] = version(dist)
        except PackageNotFoundError:
            out[dist] = "not installed"
    for pins in PINS.values():
        for pin in pins:
            out[pin.split("==")[0]] = pin.split("==")[1] + " (own venv)"
    return out


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
