"""Device files: read and validated (the field named in one line), couplers sorted with their own figures, and
accepted wherever a device name is (``--device PATH``, ``device="PATH.json"``, a ``Device``)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import qcpp
from qcpp.hardware import device as hw
from qcpp.hardware.device import IBM_DEVICES, DeviceError, device_file, get_device, is_named, named_device

DATA = Path(hw.__file__).resolve().parent / "data"
BIND = {"gamma_0": 0.3, "beta_0": 0.7}


def chain(**changes: object) -> dict:
    """A three-qubit chain whose couplers are listed out of order and the wrong way round."""
    raw = {
        "name": "chain", "family": "grid", "source": "test", "date": "2026-01-01", "num_qubits": 3,
        "native_gates": ["cz", "rz", "sx", "x"], "two_qubit_gate": "cz", "coupling": [[2, 1], [0, 1]],
        "gate_error": {"cz": [0.5, 0.01], "rz": 0.0, "sx": 1e-4, "x": 1e-4},
        "gate_duration_s": {"cz": [9e-8, 6e-8], "rz": 0.0, "sx": 3e-8, "x": 3e-8},
        "readout_error": [0.01, 0.02, 0.03], "readout_duration_s": 1e-6,
    }  # fmt: skip
    raw.update(changes)
    return {k: v for k, v in raw.items() if v is not None or k == "gate_duration_s"}


def write(tmp_path: Path, raw: object, name: str = "chain.json") -> Path:
    path = tmp_path / name
    path.write_text(json.dumps(raw))
    return path


def test_each_coupler_keeps_its_own_error_and_duration_when_sorted(tmp_path: Path) -> None:
    d = device_file(write(tmp_path, chain()))
    assert d.coupling == ((0, 1), (1, 2))
    assert d.error_2q == (0.01, 0.5) and d.duration_2q_s == (6e-8, 9e-8)
    assert dict(d.error_1q)["sx"] == (1e-4,) * 3 and d.readout_error == (0.01, 0.02, 0.03)


def test_a_shipped_file_with_its_couplers_shuffled_is_the_same_device(tmp_path: Path) -> None:
    raw = json.loads((DATA / "ibm_torino.json").read_text())
    order = list(range(len(raw["coupling"])))[::-1]
    raw["coupling"] = [raw["coupling"][i][::-1] for i in order]
    for table in ("gate_error", "gate_duration_s"):
        raw[table]["cz"] = [raw[table]["cz"][i] for i in order]
    raw["name"] = "torino_shuffled"
    d, torino = device_file(write(tmp_path, raw)), named_device("ibm_torino")
    assert (d.coupling, d.error_2q, d.duration_2q_s) == (torino.coupling, torino.error_2q, torino.duration_2q_s)


@pytest.mark.parametrize(
    ("change", "fragment"),
    [
        ({"family": None}, "chain.json: missing field family"),
        ({"gate_error": {"cz": [0.5, 0.01, 0.1], "rz": 0, "sx": 0, "x": 0}},
         "chain.json: gate_error.cz: expected 2 values (one per coupler), got 3"),
        ({"gate_error": {"cz": 0.01, "rz": 0, "sx": 0}}, "chain.json: gate_error.x: missing"),
        ({"readout_error": [0.01, 0.02]}, "chain.json: readout_error: expected 3 values (one per qubit), got 2"),
        ({"coupling": [[0, 1], [1, 3]]}, "chain.json: coupling[1]: expected [a, b], two different qubits 0..2"),
        ({"coupling": [[0, 1], [1, 0]]}, "chain.json: coupling[1]: the coupler [0, 1] is listed twice"),
        ({"gate_error": {"cz": [0.5, 2], "rz": 0, "sx": 0, "x": 0}}, "gate_error.cz[1]: expected between 0 and 1"),
        ({"family": "ring"}, "chain.json: family: expected one of grid, heavy-hex, all-to-all, got 'ring'"),
        ({"t1": [1e-4] * 3}, "chain.json: unknown field 't1'"),
        ({"t1_s": [1e-4]}, "chain.json: t1_s: expected a list of 3 values"),
        ({"name": "ibm_fez"}, "chain.json: name: 'ibm_fez' is a shipped device's name"),
        ({"name": "grid:3x3"}, "chain.json: name: 'grid:3x3' is a family's name"),
    ],
)  # fmt: skip
def test_a_malformed_file_names_the_file_and_the_field(tmp_path: Path, change: dict, fragment: str) -> None:
    raw = chain()
    for key, value in change.items():
        if value is None:
            del raw[key]
        else:
            raw[key] = value
    path = write(tmp_path, raw)
    with pytest.raises(DeviceError) as exc:
        get_device(str(path))
    assert fragment in str(exc.value) and "\n" not in str(exc.value)


def test_a_file_that_is_not_json_or_is_missing_is_one_line(tmp_path: Path) -> None:
    (tmp_path / "bad.json").write_text('{"num_qubits": ')
    with pytest.raises(DeviceError, match=r"bad\.json: not a JSON device file \(line 1"):
        qcpp.device(str(tmp_path / "bad.json"))
    with pytest.raises(DeviceError, match=r"gone\.json: cannot read the device file"):
        qcpp.device(str(tmp_path / "gone.json"))


def test_a_file_with_ibm_fez_s_figures_compiles_as_ibm_fez(tmp_path: Path) -> None:
    raw = json.loads((DATA / "ibm_fez.json").read_text()) | {"name": "my_fez"}
    path = str(write(tmp_path, raw, "my_fez.json"))
    s = qcpp.grid_scenario(2, 2, robots=1)
    mine, fez = qcpp.compile(s, device=path, bind=BIND), qcpp.compile(s, device="ibm_fez", bind=BIND)
    assert mine.device.name == "my_fez" and is_named(mine.device)
    assert list(mine.circuit.gates) == list(fez.circuit.gates) and mine.initial_layout == fez.initial_layout


def test_a_device_value_is_accepted_where_a_name_is() -> None:
    s = qcpp.grid_scenario(2, 2, robots=1)
    by_value = qcpp.compile(s, device=qcpp.device("grid:3x3"), bind=BIND)
    by_name = qcpp.compile(s, device="grid:3x3", bind=BIND)
    assert list(by_value.circuit.gates) == list(by_name.circuit.gates) and by_value.final_layout == by_name.final_layout
    est = qcpp.estimate(s, device=qcpp.device("grid:3x3")).to_dict()
    assert est == qcpp.estimate(s, device="grid:3x3").to_dict() and est["device"] == "grid:3x3"


@pytest.mark.parametrize("call", [qcpp.compile, qcpp.estimate])
def test_a_device_of_another_type_is_named_by_its_type_in_a_short_line(call: object) -> None:
    s = qcpp.grid_scenario(2, 3, robots=1)
    with pytest.raises(qcpp.QcppError) as exc:
        call(s, device=[named_device("ibm_fez")])  # type: ignore[operator]
    assert "list" in str(exc.value) and len(str(exc.value)) < 200


def test_the_twoq_search_hosts_are_the_shipped_ibm_devices(monkeypatch: pytest.MonkeyPatch) -> None:
    from qcpp.pipeline import device_compile

    hosts: list[list[str]] = []
    monkeypatch.setattr(device_compile, "_searches_apply", lambda *_: True)
    monkeypatch.setattr(device_compile, "_searched_on", lambda devices, *_: hosts.append([d.name for d in devices]))
    for name in IBM_DEVICES:
        device_compile._searched_on_siblings(None, None, get_device(name), *[None] * 7)  # type: ignore[arg-type]
    assert hosts == [[n for n in IBM_DEVICES if n != name] for name in IBM_DEVICES]
    assert set(IBM_DEVICES) <= set(qcpp.devices())
    assert all(get_device(n).family == "heavy-hex" and is_named(get_device(n)) for n in IBM_DEVICES)
