"""qcpp verify: the exact rule holds, the paper's rule leaks where the paper notes say, and both methods can fail."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest
from hypothesis import given, settings

from qcpp.cli.app import app
from qcpp.estimators.crosscheck import interior_endpoints, with_obstacles
from qcpp.gadgets.partial_mixer import ParityPartialMixer
from qcpp.gadgets.phase_visits import VisitPhase
from qcpp.ir.gates import Gate, mcx
from qcpp.plan.options import PlanOptions
from qcpp.problem.paths import is_feasible
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict
from qcpp.testing import plaquette_flips, scenarios
from qcpp.verification import choose_method, verify, verify_gadgets, verify_state

LEAK = {"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 2], "goal": [1, 1]}]}
LEAK_PLAQUETTE = ((0, 1), (0, 2), (1, 2), (1, 1))


def leak_scenario() -> Scenario:
    return scenario_from_dict(LEAK)


def mask_of(s: Scenario, edges: tuple) -> int:
    """Edge mask of a path given as node pairs (as a counterexample names it)."""
    index = {(tuple(a), tuple(b)): e for e, (a, b) in enumerate(s.grid.edges)}
    return sum(1 << index[(tuple(a), tuple(b))] for a, b in edges)


def assert_exhaustive_hold(report) -> None:  # type: ignore[no-untyped-def]
    assert report.holds, report.summary()
    assert report.exhaustive and report.counterexample is None
    assert all(c.held for c in report.checks)


# ------------------------------------------------------------------------------------------------ the exact rule
SMALL = [default_scenario(r, c, k) for r, c in ((2, 2), (2, 3), (3, 2), (3, 3)) for k in (1, 2)]


@pytest.mark.parametrize("scenario", SMALL, ids=[s.name for s in SMALL])
def test_exact_rule_holds_by_state_checks_on_every_feasible_input(scenario: Scenario) -> None:
    report = verify_state(scenario, p=1)
    assert_exhaustive_hold(report)
    parts = {c.subject: c.inputs for c in report.checks}
    assert set(parts) == {"initial_state", "phase_0", "mixer_0", "circuit"}
    assert parts["mixer_0"] >= 1


@settings(max_examples=6)
@given(scenarios(max_side=3, max_robots=2))
def test_exact_rule_holds_on_random_small_scenarios(scenario: Scenario) -> None:
    assert_exhaustive_hold(verify_state(scenario, p=1, samples=200))


def _up_to_3x4() -> list[Scenario]:
    out = [default_scenario(r, c, k) for r in (2, 3, 4) for c in (2, 3, 4) if r * c <= 12 for k in (1, 2)]
    out.append(interior_endpoints(3, 4))
    out += [s for mode in ("soft", "hard") if (s := with_obstacles(default_scenario(3, 4, 2), mode)) is not None]
    return out


@pytest.mark.heavy
@pytest.mark.parametrize("scenario", _up_to_3x4(), ids=[s.name for s in _up_to_3x4()])
def test_exact_rule_holds_on_every_scenario_up_to_3x4_with_two_robots(scenario: Scenario) -> None:
    report = verify_state(scenario, p=1, samples=10_000)
    assert_exhaustive_hold(report)


def test_exact_rule_holds_at_p_2_on_every_part() -> None:
    report = verify(default_scenario(3, 3, 1), p=2, method="state")
    assert_exhaustive_hold(report)
    subjects = [c.subject for c in report.checks]
    assert subjects == ["initial_state", "phase_0", "mixer_0", "phase_1", "mixer_1", "circuit"]


def test_gadget_method_certifies_what_the_state_method_checks() -> None:
    s = default_scenario(3, 3, 2)
    report = verify_gadgets(s, p=1)
    assert_exhaustive_hold(report)
    parts = {c.part for c in report.checks}
    assert parts == {"rule", "mixer", "phase", "initial_state"}
    assert any(c.how == "exhaustive" and c.subject.startswith("MixerJunction") for c in report.checks)
    assert verify_state(s, p=1).holds


@pytest.mark.parametrize(
    "options",
    [PlanOptions(target="ft"), PlanOptions(fuse=False), PlanOptions(phase="whole-space"), PlanOptions(angles="multi")],
    ids=["ft", "unfused", "whole-space", "multi-angles"],
)
def test_both_methods_hold_for_other_constructions(options: PlanOptions) -> None:
    s = default_scenario(3, 3, 2)
    for method in ("state", "gadgets"):
        report = verify(s, p=1, method=method, options=options)  # type: ignore[arg-type]
        assert_exhaustive_hold(report)
    if not options.fuse:
        kinds = [c.subject for c in verify_gadgets(s, p=1, options=options).checks if c.part == "mixer"]
        assert kinds and all(k.startswith("ParityPartialMixer") for k in kinds)


@pytest.mark.parametrize("initial", ["representatives", "local_search_mix"])
def test_both_methods_check_other_initial_states(initial: str) -> None:
    for method in ("state", "gadgets"):
        report = verify(default_scenario(3, 3, 1), p=1, method=method, options=PlanOptions(initial=initial))  # type: ignore[arg-type]
        assert_exhaustive_hold(report)


@pytest.mark.parametrize("mode", ["soft", "hard"])
def test_gadget_method_on_obstacles(mode: str) -> None:
    s = with_obstacles(default_scenario(4, 4, 2), mode)
    assert s is not None
    assert_exhaustive_hold(verify(s, p=2, method="gadgets"))


# ------------------------------------------------------------------------------------------------ the paper rule
def test_paper_rule_leak_on_2x3_is_found_by_the_state_method() -> None:
    s = leak_scenario()
    report = verify(s, p=1, rule="paper")
    assert report.method == "state" and not report.holds
    cx = report.counterexample
    assert cx is not None and cx.method == "state" and cx.check == "mixer_0"
    assert cx.robot == 0 and cx.plaquette == LEAK_PLAQUETTE
    assert cx.kind is not None and cx.kind.startswith("McxPartialMixer")
    assert is_feasible(s, 0, mask_of(s, cx.input_paths[0]))
    assert not is_feasible(s, 0, mask_of(s, cx.output_paths[0]))
    assert cx.amplitude > 1e-3


def test_paper_rule_leak_on_2x3_is_found_by_the_gadget_method() -> None:
    s = leak_scenario()
    report = verify(s, p=1, rule="paper", method="gadgets")
    cx = report.counterexample
    assert not report.holds and cx is not None and cx.method == "gadgets"
    assert cx.check.startswith("rule paper") and cx.plaquette == LEAK_PLAQUETTE
    assert "leaves the feasible set" in cx.reason
    assert not is_feasible(s, 0, mask_of(s, cx.output_paths[0]))


def test_cli_exit_codes_and_json(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    path = tmp_path / "leak.json"
    path.write_text(json.dumps(LEAK))
    runner = CliRunner()
    res = runner.invoke(app, ["verify", str(path), "-p", "1", "--rule", "paper"])
    assert res.exit_code == 1, res.output
    assert "counterexample" in res.stdout and str(LEAK_PLAQUETTE) in " ".join(res.stdout.split())  # may wrap
    res = runner.invoke(app, ["verify", str(path), "-p", "1", "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["holds"] and data["exhaustive"] and data["method"] == "state" and data["counterexample"] is None
    res = runner.invoke(app, ["verify", str(path), "-p", "1", "--rule", "paper", "--method", "gadgets", "--json"])
    assert res.exit_code == 1
    assert json.loads(res.stdout)["counterexample"]["plaquette"] == [list(c) for c in LEAK_PLAQUETTE]
    for bad in (["--method", "fast"], ["--samples", "0"], ["-p", "0"], ["--rule", "loose"]):
        res = runner.invoke(app, ["verify", str(path), *bad])
        assert res.exit_code == 2 and res.stderr.startswith("error: ") and len(res.stderr.splitlines()) == 1


def test_cli_reports_progress_on_stderr(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    path = tmp_path / "leak.json"
    path.write_text(json.dumps(LEAK))
    env = {"QCPP_PROGRESS": "lines", "QCPP_PROGRESS_INTERVAL": "0"}
    res = CliRunner().invoke(app, ["verify", str(path), "--method", "gadgets", "--json"], env=env)
    assert res.exit_code == 0, res.output
    lines = [line for line in res.stderr.splitlines() if line.startswith("verify leak.json: ")]
    assert len(lines) >= 3 and "checks" in lines[-1]
    assert json.loads(res.stdout)["method"] == "gadgets"  # stdout stays one JSON object


def test_bad_input_to_the_library_is_a_value_error() -> None:
    s = leak_scenario()
    for kwargs in ({"p": 0}, {"rule": "loose"}, {"method": "fast"}, {"samples": 0}):
        with pytest.raises(ValueError):
            verify(s, **kwargs)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="at most 62 qubits"):
        verify(default_scenario(6, 6, 2), p=1, method="state")


def test_auto_picks_state_where_every_input_fits_and_gadgets_beyond() -> None:
    assert choose_method(default_scenario(3, 3, 2), 1) == "state"
    assert choose_method(default_scenario(3, 3, 2), 1, samples=10) == "gadgets"
    assert choose_method(default_scenario(3, 3, 2), 1, PlanOptions(rule="paper")) == "state"
    assert choose_method(default_scenario(8, 8, 3), 1) == "gadgets"


def test_sampled_inputs_are_reported_as_samples() -> None:
    report = verify_state(default_scenario(3, 3, 2), p=1, samples=20, seed=3)
    assert report.holds and not report.exhaustive
    mixer = next(c for c in report.checks if c.subject == "mixer_0")
    assert mixer.how == "sampled" and mixer.inputs <= 20 and "more than 20" in mixer.detail


# ---------------------------------------------------------------------------------------------- mutations caught
def _drop_one_control(monkeypatch: pytest.MonkeyPatch, from_qubit: int = 0) -> None:
    """Every AND of every parity-basis partial mixer on data qubits ``from_qubit`` and up (``v``: every robot but
    the first) loses its second control (in its compute and its mirror)."""
    original = ParityPartialMixer.parts

    def mutated(self: ParityPartialMixer) -> tuple[list[Gate], list[Gate], list[Gate]]:
        compute, rotation, mirror = original(self)
        if min(self.plaquette_qubits) < from_qubit:
            return compute, rotation, mirror
        for i, g in enumerate(compute):
            if g.name == "and":
                a, _, t = g.qubits
                weaker = mcx([a], t, g.ctrl_state[0])
                compute[i] = mirror[len(mirror) - 1 - i] = weaker
        return compute, rotation, mirror

    monkeypatch.setattr(ParityPartialMixer, "parts", mutated)


def test_the_state_method_catches_a_dropped_control(monkeypatch: pytest.MonkeyPatch) -> None:
    s = default_scenario(3, 3, 2)
    assert verify_state(s, p=1).holds
    _drop_one_control(monkeypatch)
    report = verify_state(s, p=1)
    assert not report.holds
    cx = report.counterexample
    assert cx is not None and cx.check == "mixer_0" and cx.kind is not None and cx.plaquette is not None
    assert cx.kind.startswith(("MixerRotation", "MixerJunction"))
    html = report._repr_html_()  # a notebook shows the verdict, the failed row and the counterexample
    assert "<caption>feasibility preservation FAILS: " in html and "<td>FAILS</td>" in html
    assert "<pre>counterexample (state, mixer_0): " in html


def test_the_gadget_method_catches_a_dropped_control(monkeypatch: pytest.MonkeyPatch) -> None:
    s = default_scenario(3, 3, 2)
    _drop_one_control(monkeypatch)
    report = verify_gadgets(s, p=1)
    assert not report.holds and report.outcome == "fails"  # a broken gadget is a counterexample, not "undecided"
    cx = report.counterexample
    assert cx is not None and cx.method == "gadgets" and cx.kind.startswith("ParityPartialMixer")
    assert "does not do what its program says" in cx.reason
    assert cx.reachable is True and "A feasible path contains this input" in cx.reason


def _forget_last_uncompute(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every visit phase gadget loses its last ``and_dg``: the paths and their phases stay as they were, an
    ancilla is left holding an AND."""
    original = VisitPhase.emit

    def no_uncompute(self: VisitPhase) -> list[Gate]:
        gates = list(original(self))
        last = max(i for i, g in enumerate(gates) if g.name == "and_dg")
        return gates[:last] + gates[last + 1 :]

    monkeypatch.setattr(VisitPhase, "emit", no_uncompute)


def test_the_gadget_method_catches_a_phase_gadget_that_is_not_diagonal(monkeypatch: pytest.MonkeyPatch) -> None:
    _forget_last_uncompute(monkeypatch)
    report = verify_gadgets(default_scenario(3, 3, 2), p=1)
    assert not report.holds and report.outcome == "fails"
    cx = report.counterexample
    assert cx is not None and cx.check.startswith("phase VisitPhase") and "not shown diagonal" in cx.reason


def test_the_gadget_method_pairs_an_uncompute_with_its_own_compute(monkeypatch: pytest.MonkeyPatch) -> None:
    """A visit phase gadget whose last uncompute reads a wrong control: its permutations do not cancel, so it is not
    shown diagonal (the structural check is all the gadget method has for phase kinds too large to run, so a pair of
    gates must match on their qubits, not only on their names)."""
    original = VisitPhase.emit

    def wrong_control(self: VisitPhase) -> list[Gate]:
        gates = list(original(self))
        last = max(i for i, g in enumerate(gates) if g.name == "and_dg")
        a, b, t = gates[last].qubits
        other = next(q for g in gates for q in g.qubits if q not in (a, b, t))
        gates[last] = gates[last]._replace(qubits=(a, other, t))
        return gates

    monkeypatch.setattr(VisitPhase, "emit", wrong_control)
    report = verify_gadgets(default_scenario(3, 3, 2), p=1)
    assert not report.holds and report.outcome == "fails"
    cx = report.counterexample
    assert cx is not None and cx.check.startswith("phase VisitPhase") and "not shown diagonal" in cx.reason


def test_the_state_method_catches_an_ancilla_left_set(monkeypatch: pytest.MonkeyPatch) -> None:
    """A forgotten uncompute keeps every path feasible and leaves an ancilla in |1> (the next gadget that takes it
    as clean computes garbage): only the check of the ancillas sees it, and it must fail the unit."""
    s = default_scenario(3, 3, 2)
    _forget_last_uncompute(monkeypatch)
    report = verify_state(s, p=1)
    assert not report.holds
    cx = report.counterexample
    assert cx is not None and cx.check == "phase_0" and cx.reason == "an ancilla is left in |1>"
    assert cx.output_paths == cx.input_paths  # the paths are kept: the ancillas alone show the fault
    assert cx.dirty_ancillas and min(cx.dirty_ancillas) >= s.num_variables


def test_the_state_method_checks_the_paths_of_every_robot(monkeypatch: pytest.MonkeyPatch) -> None:
    """A dropped control in the second robot's partial mixers only: the state method must look at that robot's
    path too, not only the first robot's."""
    s = default_scenario(3, 3, 2)
    _drop_one_control(monkeypatch, from_qubit=s.edges_per_robot)
    report = verify_state(s, p=1)
    assert not report.holds
    cx = report.counterexample
    assert cx is not None and cx.check == "mixer_0" and cx.robot == 1
    assert "robot 1's path leaves the feasible set" in cx.reason
    assert not is_feasible(s, 1, mask_of(s, cx.output_paths[1])) and is_feasible(s, 0, mask_of(s, cx.output_paths[0]))


def _close_the_u_turn(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every parity-basis partial mixer starts by flipping its fourth plaquette edge where the other three are set:
    wrong only on inputs with three of the four plaquette edges (a path turning around the plaquette), which
    feasible paths contain; the closed loop it makes of them is no feasible path."""
    original = ParityPartialMixer.parts

    def mutated(self: ParityPartialMixer) -> tuple[list[Gate], list[Gate], list[Gate]]:
        compute, rotation, mirror = original(self)
        a, b, c, d = self.plaquette_qubits
        return [mcx([a, b, c], d), *compute], rotation, mirror

    monkeypatch.setattr(ParityPartialMixer, "parts", mutated)


def test_both_methods_check_inputs_with_three_plaquette_edges(monkeypatch: pytest.MonkeyPatch) -> None:
    """Only closed loops (all four plaquette edges) may be left out of a partial mixer's local inputs: a fault
    seen only where three edges are set is a counterexample for the gadget method and for the state method."""
    s = default_scenario(3, 3, 2)
    options = PlanOptions(fuse=False)  # each partial mixer whole: the partial-mixer check alone sees the fault
    _close_the_u_turn(monkeypatch)
    gadgets = verify_gadgets(s, p=1, options=options)
    assert gadgets.outcome == "fails", gadgets.summary()
    cx = gadgets.counterexample
    assert cx is not None and cx.kind is not None and cx.kind.startswith("ParityPartialMixer")
    assert "does not do what its program says" in cx.reason and cx.reachable is True
    state = verify_state(s, p=1, options=options)
    assert not state.holds and state.counterexample is not None and state.counterexample.check == "mixer_0"


# ------------------------------------------------------------------------------------ strategies of qcpp.testing
@settings(max_examples=40)
@given(plaquette_flips(scenarios(max_side=4, max_robots=2), rule="exact"))
def test_exact_rule_flips_stay_feasible(flip) -> None:  # type: ignore[no-untyped-def]
    assert is_feasible(flip.scenario, flip.robot, flip.path)
    assert not flip.allowed or is_feasible(flip.scenario, flip.robot, flip.result)
    assert flip.result == flip.path ^ flip.scenario.grid.plaquettes[flip.plaquette].edge_mask


def test_paper_rule_flip_strategy_finds_the_leak() -> None:
    """The strategy can produce the counterexample the paper's rule has (hypothesis searches for it)."""
    from hypothesis import find

    flip = find(
        plaquette_flips(leak_scenario(), rule="paper"),
        lambda f: f.allowed and not is_feasible(f.scenario, f.robot, f.result),
        settings=settings(max_examples=500, database=None),
    )
    assert flip.scenario.grid.plaquettes[flip.plaquette].corners == LEAK_PLAQUETTE


# ------------------------------------------------------------------------------------------------ at scale
@pytest.mark.heavy
def test_gadget_method_certifies_a_30x30_field_with_8_robots_at_p_3() -> None:
    start = time.perf_counter()
    report = verify_gadgets(default_scenario(30, 30, 8), p=3)
    print(f"30x30, 8 robots, p = 3: gadget certification in {time.perf_counter() - start:.1f} s")
    assert_exhaustive_hold(report)
    assert {c.part for c in report.checks} == {"rule", "mixer", "phase", "initial_state"}


def test_the_command_verifies_the_ft_circuit_and_refuses_an_unknown_target() -> None:
    from ..cli.clirun import run

    for method in ("state", "gadgets"):
        res = run("verify", "--grid", "3x3", "--robots", "2", "--target", "ft", "--method", method, "--json")
        assert res.exit_code == 0, res.stderr
        report = json.loads(res.stdout)
        assert report["target"] == "ft" and report["holds"] and report["method"] == method
        if method == "gadgets":  # the ft circuit's own phase kinds are among those checked
            assert any(c["subject"].startswith("VisitBatch") for c in report["checks"])
    bad = run("verify", "--grid", "3x3", "--target", "xx")
    assert bad.exit_code == 2 and bad.stderr.count("\n") == 1 and "--target" in bad.stderr


def test_the_summary_names_what_each_method_checked() -> None:
    """The gadget method checks each gadget kind on its local inputs (a verdict on every feasible input by
    composition); the state method runs the circuit on every feasible input: the first line says which."""
    s = default_scenario(2, 3, 1)
    gadgets = verify_gadgets(s, 1).summary().splitlines()[0]
    state = verify_state(s, 1).summary().splitlines()[0]
    assert "method gadgets (every gadget kind on each of its local inputs; " in gadgets
    assert "method state (every feasible input; " in state


def test_the_public_verify_takes_the_construction_as_keywords() -> None:
    """``qcpp.verify`` builds the circuit as ``qcpp.compile`` does from the same keywords: the paper rule leaks,
    the fault-tolerant target is verified as such, and the keywords equal an explicit ``options`` value."""
    import qcpp

    leak = leak_scenario()
    by_keyword = qcpp.verify(leak, 1, rule="paper", method="gadgets")
    assert not by_keyword.holds and by_keyword.rule == "paper"
    assert by_keyword.to_dict() | {"seconds": 0} == qcpp.verify(
        leak, 1, method="gadgets", options=PlanOptions(rule="paper")).to_dict() | {"seconds": 0}
    assert qcpp.verify(default_scenario(2, 3, 1), 1, target="ft").target == "ft"
