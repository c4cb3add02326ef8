"""``qcpp compile --device`` and ``qcpp estimate --device``: the routed file, its JSON, bad names."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
import qiskit.qasm3
from qiskit import qasm2

from qcpp.hardware.device import get_device
from qcpp.lowering.qasm_profiles import ZERO_START_NOTE

from .clirun import assert_one_line_error, run

PAPER = str(Path(__file__).resolve().parents[2] / "examples" / "paper_3x3.toml")
BIND = ["--bind", "gamma_0=0.3", "beta_0=0.7"]


@pytest.mark.parametrize(("device", "lowered"), [("grid", True), ("heavy-hex:5", False), ("ibm_torino", False)])
def test_compile_device_writes_physical_qubits_on_couplings(tmp_path: Path, device: str, lowered: bool) -> None:
    out = tmp_path / "routed.qasm"
    args = ["compile", PAPER, "--device", device, "--qasm", str(out), "--qasm-version", "2", "--json", *BIND]
    res = run(*args, *(["--lowered"] if lowered else []))
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)
    dev = summary["device"]
    # the unsized square grid is sized for the medial layout (5x5 for 3x3); other devices: the smallest that fits
    assert dev["name"] == ("grid:5x5" if device == "grid" else get_device(device, min_qubits=15).name)
    # auto on a grid that holds the medial layout: small circuits are routed both ways, the fewer gates win
    assert summary["routed"]["layout"] in (("medial", "greedy") if device == "grid" else ("greedy",))
    edges = {tuple(e) for e in dev["coupling"]}
    qc = qasm2.loads(out.read_text())
    assert qc.num_qubits == dev["qubits"] == summary["qubits"]
    two = [tuple(sorted(qc.find_bit(b).index for b in inst.qubits)) for inst in qc.data if len(inst.qubits) == 2]
    assert two and all(pair in edges for pair in two)
    names = set(qc.count_ops())
    assert names <= ({"cx", "h", "rz", "t", "tdg", "s", "sdg", "x"} if lowered else {"cz", "rz", "rx", "x"})
    # logical qubits: the 12 data qubits, then the ancillas (medial: the device qubits its sections use)
    logical = len(summary["initial_layout"])
    assert logical == len(summary["final_layout"]) and logical >= 15
    assert len(set(summary["initial_layout"])) == logical and max(summary["final_layout"]) < dev["qubits"]
    assert 0 < summary["routed"]["esp"] < 1 and summary["routed"]["two_qubit"] == len(two)
    # on a named device the written routing is the best candidate, and the router's description says so
    chose = bool(summary["routed"]["candidates"])
    assert chose == (device == "ibm_torino") and ("chosen names it" in summary["routed"]["router"]) == chose


@pytest.mark.parametrize(
    ("device", "fragment"),
    [("nope", "unknown device 'nope'"), ("grid:3x3", "device grid:3x3 has 9"), ("heavy-hex:2", "odd")],
)
def test_compile_bad_device_is_one_line(device: str, fragment: str) -> None:
    assert_one_line_error(run("compile", PAPER, "--device", device), fragment)


def test_estimate_device_adds_routed_fields_equal_to_compile() -> None:
    res = run("estimate", "--scenario", PAPER, "--device", "heavy-hex", "--json")
    assert res.exit_code == 0, res.output
    (row,) = json.loads(res.stdout)
    assert row["fits"] is True and row["routed_kind"] == "exact"
    compiled = json.loads(run("compile", PAPER, "--device", "heavy-hex", "--json").stdout)
    assert row["device"] == compiled["device"]["name"]  # the cell layout's heavy-hex:7 or greedy's heavy-hex:3
    assert row["routed_twoq"] == compiled["routed"]["two_qubit"]
    for figure in ("esp", "esp_idle", "log10_esp", "log10_esp_idle"):  # one computation: equal, not just close
        assert row[figure] == compiled["routed"][figure], figure
    assert row["routed_twoq_depth"] <= row["routed_depth"]


def test_estimate_device_too_small_and_bound() -> None:
    res = run("estimate", "--grid", "5x5", "--robots", "2", "--device", "quantinuum_helios", "--json")
    (row,) = json.loads(res.stdout)
    assert row["fits"] is False and row["routed_twoq"] is None
    # 24x24 with 3 robots needs a 94x94 grid: too large for the window sum's whole-device windows
    res = run("estimate", "--grid", "24x24", "--robots", "3", "--device", "grid", "--json")
    (row,) = json.loads(res.stdout)
    assert row["routed_kind"] == "bound" and row["routed_twoq"] >= row["cx"] and 0 <= row["esp"] < 1
    assert row["routed_depth_kind"] == "bound" and row["routed_model"].startswith("bound:")


def test_estimate_bad_device_is_one_line() -> None:
    assert_one_line_error(run("estimate", "--device", "grid:x"), "--device", "grid:x")


@pytest.mark.parametrize(
    ("device", "layout", "fragment"),
    [
        ("grid", "nope", "--layout"),
        ("quantinuum_helios", "medial", "square-grid or heavy-hex lattice device; quantinuum_helios is neither"),
        ("heavy-hex:5", "medial", "needs heavy-hex:7"),
        ("grid:4x6", "medial", "needs a 5x5 grid"),
    ],
)
def test_compile_bad_layout_is_one_line(device: str, layout: str, fragment: str) -> None:
    assert_one_line_error(run("compile", PAPER, "--device", device, "--layout", layout), fragment)


@pytest.mark.slow
def test_compile_medial_on_an_ibm_device_places_the_cells_or_says_they_do_not_embed() -> None:
    """IBM's lattice is not a heavy-hex:D lattice: --layout medial routes the cells on one and writes them on the
    device where their couplers embed (one robot on 3x3), else one line (one robot on 4x4)."""
    res = run("compile", PAPER, "--device", "ibm_torino", "--layout", "medial", "--lowered", "--json", *BIND)
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)
    routed = summary["routed"]
    assert routed["layout"] == "medial" and routed["chosen"].startswith("cells on heavy-hex:"), routed["chosen"]
    assert all(c["name"].startswith("cells on heavy-hex:") for c in routed["candidates"])
    assert summary["device"]["name"] == "ibm_torino" and len(summary["initial_layout"]) > 15  # local ancillas
    assert_one_line_error(run("compile", "--grid", "4x4", "--device", "ibm_torino", "--layout", "medial"),
                          "do not embed in ibm_torino")  # fmt: skip


def test_compile_layout_choice_is_reported() -> None:
    for layout in ("medial", "greedy"):
        res = run("compile", PAPER, "--device", "grid:5x5", "--layout", layout, "--lowered", "--json", *BIND)
        assert res.exit_code == 0, res.output
        summary = json.loads(res.stdout)
        assert summary["routed"]["layout"] == layout
        assert (summary["initial_layout"] == summary["final_layout"]) == (layout == "medial")


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("--device", "ibm_fez", "--optimize-for", "depth"), "--optimize-for: expected esp or twoq, got 'depth'"),
        (("--optimize-for", "esp"), "--optimize-for esp: applies with --device only"),
        (("--device", "ibm_fez", "--effort", "fast"), "--effort: expected full or quick, got 'fast'"),
        (("--effort", "quick"), "--effort quick: applies with --device only (no device given)"),
    ],
)
def test_compile_bad_optimize_for_or_effort_is_one_line(args: tuple[str, ...], fragment: str) -> None:
    assert_one_line_error(run("compile", PAPER, *args), fragment)
    if "--effort" in args:  # estimate takes the option from compile, with the same refusals
        assert_one_line_error(run("estimate", "--scenario", PAPER, *args), fragment)


@pytest.mark.heavy
def test_compile_quick_effort_drops_only_the_partial_mixer_choice() -> None:
    """``--effort quick`` runs every stage ``full`` runs but the choice of partial-mixer plans for the routing (on
    each host), says so in ``routed.effort`` and the text, and writes what ``qcpp.compile(..., effort="quick")``
    returns."""
    import qcpp
    from qcpp.pipeline.device_compile import compile_for_device
    from qcpp.plan.options import PlanOptions
    from qcpp.routing.options import effort_routing

    scenario = qcpp.grid_scenario(2, 2, robots=1)
    stages = {}
    for effort in ("full", "quick"):
        seen: list[str] = []
        result = compile_for_device(scenario, 1, "ibm_fez", PlanOptions(), stage=seen.append,
                                    routing=effort_routing(effort))  # fmt: skip
        assert result.effort == effort
        stages[effort] = {text.split(" (")[0] for text in seen}
    choice = {s for s in stages["full"] if s.startswith("choosing partial-mixer plans for the routing on ")}
    assert "choosing partial-mixer plans for the routing on ibm_fez" in choice
    assert stages["quick"] == stages["full"] - choice
    res = run("compile", "--grid", "2x2", "--robots", "1", "--device", "ibm_fez", "--effort", "quick", "--json")
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)
    api = qcpp.compile(scenario, device="ibm_fez", effort="quick")
    assert summary["routed"]["effort"] == "quick" and summary["gates"] == api.counts()
    assert summary["initial_layout"] == api.initial_layout and summary["final_layout"] == api.final_layout
    text = run("compile", "--grid", "2x2", "--robots", "1", "--device", "ibm_fez", "--effort", "quick")
    assert text.exit_code == 0 and "effort quick" in " ".join(text.stdout.split()), text.output


@pytest.mark.heavy
def test_estimate_quick_effort_routes_as_compile_quick() -> None:
    """``estimate --effort quick`` routes what ``compile --effort quick`` writes, and its ``routed_model`` says so;
    the API's ``qcpp.estimate(..., effort="quick")`` gives the same row."""
    import qcpp
    from qcpp.estimators.routed import COMPILE_MODEL, COMPILE_QUICK_MODEL

    scenario = qcpp.grid_scenario(2, 3, robots=1)
    context = qcpp.RoutingContext()
    api = qcpp.estimate(scenario, device="ibm_fez", effort="quick", context=context).to_dict()
    compiled = qcpp.compile(scenario, device="ibm_fez", effort="quick", context=context)
    assert api["routed_model"] == COMPILE_QUICK_MODEL != COMPILE_MODEL
    assert api["routed_twoq"] == compiled.counts()["cz"] and api["esp_idle"] == compiled.to_dict()["routed"]["esp_idle"]
    res = run("estimate", "--grid", "2x3", "--robots", "1", "--device", "ibm_fez", "--effort", "quick", "--json")
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout) == [api]


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("--zero-start",), "--zero-start: applies with a named --device only (no device given)"),
        (("--device", "grid", "--zero-start"), "--zero-start: applies with a named device with couplers only"),
        (("--device", "quantinuum_helios", "--zero-start"), "not quantinuum_helios"),
        (("--device", "ibm_fez", "--lowered", "--zero-start"), "--zero-start: applies to the native-gate circuit"),
    ],
)
def test_compile_zero_start_off_a_named_device_is_one_line(args: tuple[str, ...], fragment: str) -> None:
    assert_one_line_error(run("compile", PAPER, *args), fragment)


@pytest.mark.slow
def test_compile_zero_start_says_so_in_json_and_text(tmp_path: Path) -> None:
    """``--zero-start`` is ``routed.zero_start`` in ``--json``; where a routing simplified for the all-|0> start is
    written, ``routed.equal_on_every_input`` is false, the text prints one note saying so, and the OpenQASM file says
    so in a comment under its version line (it loads in Qiskit all the same); without the option none of these."""
    small = ("--grid", "2x2", "--robots", "1", "--device", "ibm_fez", *BIND)
    for zero in (False, True):
        flag = ("--zero-start",) if zero else ()
        qasm = tmp_path / f"zero_{zero}.qasm"
        res = run("compile", *small, *flag, "--json", "--qasm", str(qasm))
        assert res.exit_code == 0, res.output
        lines = qasm.read_text().splitlines()
        assert (lines[1] == f"// {ZERO_START_NOTE}") is zero and sum(ZERO_START_NOTE in x for x in lines) == zero
        assert qiskit.qasm3.loads(qasm.read_text()).num_qubits > 0
        routed = json.loads(res.stdout)["routed"]
        assert routed["zero_start"] is zero and routed["equal_on_every_input"] is not zero, routed["chosen"]
        assert any("from |0>" in c["name"] for c in routed["candidates"]) is zero
        text = run("compile", *small, *flag)
        assert text.exit_code == 0, text.output
        flat = " ".join(text.stdout.split())
        assert ("equals the logical circuit only from that start" in flat) is zero


def test_compile_device_text_shows_the_layouts_and_the_verdict() -> None:
    """The text output prints the layouts its device note announces and reads the ESP against the verdict's bar,
    with the same figures as ``--json``."""
    text = run("compile", PAPER, "--device", "quantinuum_helios", *BIND)
    assert text.exit_code == 0, text.output
    summary = json.loads(run("compile", PAPER, "--device", "quantinuum_helios", "--json", *BIND).stdout)
    flat = " ".join(text.stdout.split())  # rich wraps long lines at the terminal width
    layouts = (f"initial layout {' '.join(map(str, summary['initial_layout']))}; "
               f"final layout {' '.join(map(str, summary['final_layout']))}")  # fmt: skip
    assert layouts in flat
    esp = summary["routed"]["esp"]
    assert summary["routed"]["esp_idle"] is None and f"(ESP {esp:.3g} >= 0.1: worth running)" in flat
    assert f"verdict: about {esp:.0%} of shots run without an error" in flat


@pytest.mark.heavy
def test_compile_on_ibm_names_qiskit_o3_best_seed_and_the_physical_qubits(tmp_path: Path) -> None:
    """On a calibrated device the text output sets the chosen circuit beside Qiskit O3's best seed (read from the
    same candidates ``--json`` lists), and the device note counts every physical qubit the routed circuit touches
    (the circuit the text run writes with ``--qasm``)."""
    args = ("compile", "--grid", "2x3", "--robot", "0,0:1,2", "--device", "ibm_torino", *BIND)
    qasm = tmp_path / "routed.qasm"
    text = run(*args, "--qasm", str(qasm))
    assert text.exit_code == 0, text.output
    summary = json.loads(run(*args, "--json").stdout)
    routed = summary["routed"]
    seeds = [c for c in routed["candidates"] if c["name"].startswith("qiskit O3 seed ") and "+" not in c["name"]]
    best = max(seeds, key=lambda c: (c["esp_idle"], -c["two_qubit"]))
    flat = " ".join(text.stdout.split())
    assert (f"Qiskit O3 (best of {len(seeds)} seeds by esp): {best['two_qubit']:,} two-qubit gates, "
            f"ESP {best['esp']:.3g} ({best['esp_idle']:.3g} idle); chosen: "
            f"{routed['two_qubit'] / best['two_qubit']:.2f}x its two-qubit gates") in flat  # fmt: skip
    touched = {q for line in qasm.read_text().splitlines() for q in re.findall(r"q\[(\d+)\]", line)
               if not line.startswith(("qubit", "bit", "input"))}  # fmt: skip
    assert f"logical on {len(touched)} physical)" in summary["device_note"]
    assert len(touched) >= len(summary["initial_layout"])
