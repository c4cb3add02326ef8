"""``--device PATH``: a device file on the command line, read and validated; a malformed one is one line, exit 2."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from qcpp.hardware import device as hw

from .clirun import assert_one_line_error, run

DATA = Path(hw.__file__).resolve().parent / "data"


def fez(**changes: object) -> dict:
    raw = json.loads((DATA / "ibm_fez.json").read_text()) | {"name": "my_fez"}
    raw.update(changes)
    return raw


@pytest.mark.parametrize(
    ("raw", "fragment"),
    [
        ({k: v for k, v in fez().items() if k != "family"}, "x.json: missing field family"),
        (fez(gate_error=fez()["gate_error"] | {"cz": fez()["gate_error"]["cz"] + [0.01]}),
         "x.json: gate_error.cz: expected 169 values (one per coupler), got 170"),
        ("not a device", "x.json: expected a JSON object of device fields"),
    ],
)  # fmt: skip
@pytest.mark.parametrize("command", ["estimate", "compile"])
def test_a_malformed_device_file_is_one_line(tmp_path: Path, raw: object, fragment: str, command: str) -> None:
    path = tmp_path / "x.json"
    path.write_text(json.dumps(raw))
    assert_one_line_error(run(command, "--grid", "2x3", "--robots", "1", "--device", str(path)), "--device", fragment)


def as_file(name: str, device: str) -> dict:
    """The device file of a family member's figures (one number where every qubit or coupler has the same)."""
    d = hw.get_device(device)

    def one(values: tuple[float, ...] | None) -> float | None:
        return None if values is None else values[0]

    return {
        "name": name, "family": d.family, "source": "test", "date": "2026-01-01", "num_qubits": d.num_qubits,
        "native_gates": list(d.native_gates), "two_qubit_gate": d.two_qubit_gate, "coupling": "all",
        "gate_error": {d.two_qubit_gate: one(d.error_2q)} | {g: v[0] for g, v in d.error_1q},
        "readout_error": one(d.readout_error),
    }  # fmt: skip


def test_a_device_file_routes_as_the_device_it_copies(tmp_path: Path) -> None:
    path = tmp_path / "ions.json"
    path.write_text(json.dumps(as_file("ions", "all-to-all:8")))
    mine = run("estimate", "--grid", "2x3", "--robots", "1", "--device", str(path), "--format", "json")
    family = run("estimate", "--grid", "2x3", "--robots", "1", "--device", "all-to-all:8", "--format", "json")
    assert mine.exit_code == 0 and family.exit_code == 0, mine.output + family.output
    a, b = json.loads(mine.stdout), json.loads(family.stdout)
    a, b = (a[0] if isinstance(a, list) else a), (b[0] if isinstance(b, list) else b)
    assert a["device"] == "ions" and b["device"] == "all-to-all:8" and a["routed_twoq"] > 0
    assert {k: v for k, v in a.items() if k != "device"} == {k: v for k, v in b.items() if k != "device"}


def test_compile_help_lists_the_shipped_devices() -> None:
    res = run("compile", "--help")
    text = " ".join(res.stdout.replace("│", " ").split())
    assert all(name in text for name in hw.device_names()) and "device file" in text
