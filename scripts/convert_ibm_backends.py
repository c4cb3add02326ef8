"""Convert IBM Heron calibration snapshots (qiskit-ibm-runtime's fake backends) into qcpp device files, once.

Writes ``src/qcpp/hardware/data/ibm_fez.json`` and ``ibm_torino.json``: the coupling map (couplers whose
CZ error the snapshot gives as 1.0, i.e. marked faulty, are dropped), per-qubit sx / x errors and durations,
per-coupler CZ error and duration, per-qubit readout error and duration, per-qubit T1 and T2 (seconds, ``null``
where the snapshot has none). ``rz`` is virtual (error 0, duration 0). qiskit-ibm-runtime is needed only here,
not by qcpp::

    pip install qiskit-ibm-runtime==0.51.0
    python scripts/convert_ibm_backends.py
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

OUT = Path(__file__).resolve().parent.parent / "src" / "qcpp" / "hardware" / "data"


def convert(backend: Any) -> dict:
    import qiskit_ibm_runtime

    target = backend.target
    n = backend.num_qubits
    cz = target["cz"]
    coupling, err2, dur2, faulty = [], [], [], []
    for (a, b), props in sorted(cz.items()):
        if a > b:
            continue
        if props.error is not None and props.error >= 1.0:
            faulty.append([a, b])
            continue
        coupling.append([a, b])
        err2.append(props.error)
        dur2.append(props.duration)

    def per_qubit(name: str, attr: str) -> list[float]:
        return [getattr(target[name][(q,)], attr) for q in range(n)]

    def coherence(attr: str) -> list[float | None]:
        props = target.qubit_properties or [None] * n
        return [None if p is None or getattr(p, attr) is None else float(getattr(p, attr)) for p in props]

    date = str(backend.properties().last_update_date)
    return {
        "name": "ibm_" + backend.name.removeprefix("fake_"),
        "family": "heavy-hex",
        "source": (
            f"IBM calibration snapshot shipped as qiskit_ibm_runtime.fake_provider.{type(backend).__name__} "
            f"(qiskit-ibm-runtime {qiskit_ibm_runtime.__version__}, backend version "
            f"{getattr(backend, 'backend_version', '?')}), converted by scripts/convert_ibm_backends.py; "
            f"{len(faulty)} faulty couplers (CZ error 1.0) dropped: {faulty}"
        ),
        "date": date,
        "num_qubits": n,
        "native_gates": ["cz", "rz", "sx", "x"],
        "two_qubit_gate": "cz",
        "coupling": coupling,
        "gate_error": {"cz": err2, "sx": per_qubit("sx", "error"), "x": per_qubit("x", "error"), "rz": 0.0},
        "gate_duration_s": {
            "cz": dur2,
            "sx": per_qubit("sx", "duration"),
            "x": per_qubit("x", "duration"),
            "rz": 0.0,
        },
        "readout_error": per_qubit("measure", "error"),
        "readout_duration_s": per_qubit("measure", "duration"),
        "t1_s": coherence("t1"),
        "t2_s": coherence("t2"),
    }


def main() -> None:
    from qiskit_ibm_runtime.fake_provider import FakeFez, FakeTorino

    for cls in (FakeFez, FakeTorino):
        data = convert(cls())
        path = OUT / f"{data['name']}.json"
        path.write_text(json.dumps(data, indent=1) + "\n")
        print(f"wrote {path} ({data['num_qubits']} qubits, {len(data['coupling'])} couplers)")


if __name__ == "__main__":
    main()
