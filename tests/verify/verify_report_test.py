"""qcpp verify's report: the text fits the terminal without cutting anything, a gadget-method counterexample says
what the flip does and whether a feasible path reaches its input, and progress shows no made-up time left."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

import qcpp
from qcpp.cli.app import app
from qcpp.cli.progress import Progress
from qcpp.problem.paths import is_feasible, iter_paths
from qcpp.problem.sbf import sbf_logic
from qcpp.verification import gadgets, verify_gadgets
from qcpp.verification.common import plaquette_picture
from qcpp.verification.report import Check, Counterexample, VerifyReport

from .verify_test import mask_of

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def field(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Three robots on 7x6 with four obstacles: many gadget kinds, long junction subjects."""
    s = qcpp.grid_scenario(7, 6, robots=[((0, 0), (6, 5)), ((0, 5), (6, 0)), ((3, 0), (3, 5))],
                           obstacles=[(2, 2), (2, 3), (4, 1), (5, 4)])  # fmt: skip
    path = tmp_path_factory.mktemp("verify") / "field.toml"
    qcpp.save_scenario(s, path)
    return path


def words(text: str) -> str:
    """The text with every run of whitespace (line breaks and indents included) made one space."""
    return " ".join(text.split())


# ------------------------------------------------------------------------------------------------- width
@pytest.mark.parametrize("rule", ["exact", "paper"])
def test_every_line_of_the_report_fits_80_columns_and_nothing_is_cut(field: Path, rule: str) -> None:
    res = CliRunner().invoke(app, ["verify", str(field), "-p", "1", "--rule", rule], env={"COLUMNS": "80"})
    assert res.exit_code == (0 if rule == "exact" else 1), res.output
    lines = res.stdout.splitlines()
    assert len(lines) > (20 if rule == "exact" else 10) and max(map(len, lines)) <= 80, max(lines, key=len)
    data = json.loads(CliRunner().invoke(app, ["verify", str(field), "-p", "1", "--rule", rule, "--json"]).stdout)
    text = words(res.stdout)
    for c in data["checks"]:  # every subject whole (a wrapped one continues on the next line)
        assert words(c["subject"]) in text
        assert bool(re.search(rf"(?<![0-9]){c['inputs']} inputs", text)) == bool(c["inputs"])
    if rule == "paper":
        cx = data["counterexample"]
        assert words(cx["reason"]) in text
        for a, b in cx["input_paths"][0]:  # an edge is never split across lines
            assert f"({a[0]}, {a[1]})-({b[0]}, {b[1]})" in res.stdout


def test_a_junction_subject_is_never_cut_mid_list(field: Path) -> None:
    report = verify_gadgets(qcpp.load_scenario(field), 1)
    junctions = [c.subject for c in report.checks if " overlap [" in c.subject]
    assert junctions and all(s.endswith("]") for s in junctions)
    for width in (None, 80, 120):
        text = report.summary(width)
        assert all(words(s) in words(text) for s in junctions)
        if width is not None:
            assert max(map(len, text.splitlines())) <= width
    wide = report.summary().splitlines()  # no width: one line per check (and the verdict, and the pictures' letters)
    assert len(wide) == len(report.checks) + 2


def test_a_narrow_width_wraps_every_row_and_the_counterexample() -> None:
    cx = Counterexample("gadgets", "rule paper NNBB", "SbfLogic paper NNBB", 0, ((0, 1), (0, 2), (1, 2), (1, 1)),
                        ((((0, 1), (0, 2)), ((0, 1), (1, 1)), ((0, 2), (1, 2)), ((1, 1), (1, 2))),), ((),), (), 1.0,
                        "a reason " * 12, False)  # fmt: skip
    check = Check("MixerJunction NNBB -> NNBB overlap [-1, -1, 4, 1, -1, 2, 6, 7, 8, 9]", "mixer", "exhaustive", 512,
                  False, 6, "opening junction, rotation, closing junction")  # fmt: skip
    report = VerifyReport("a scenario with a long name", 1, "paper", "gadgets", False, (check,), cx, 0.1, 0)
    text = report.summary(40)
    assert max(map(len, text.splitlines())) <= 40
    assert words(check.subject) in words(text) and "x6 exhaustive 512 inputs" in words(text)
    assert "(0, 1)-(0, 2)" in text and "(1, 1)-(1, 2)" in text  # edges whole
    assert "((0, 1), (0, 2), (1, 2), (1, 1))" in words(text) and "(0,\n" not in text  # corners whole
    assert report.verdict == report.summary().splitlines()[0]


# ------------------------------------------------------------------------------------- gadget counterexamples
def small_field() -> qcpp.Scenario:
    return qcpp.grid_scenario(3, 4, robots=[((0, 0), (2, 3))], obstacles=[(1, 1)])


def test_a_closed_loop_is_no_input_of_the_gadget_method() -> None:
    """A feasible path is simple, so no feasible assignment holds a closed loop around a plaquette: the paper rule
    (which flips a closed loop away, with its gadget leaving an ancilla set there) is certified where the state
    method holds, instead of failing on that input."""
    for s in (qcpp.load_scenario(ROOT / "examples" / "paper_3x3.toml"), small_field()):
        assert qcpp.verify(s, rule="paper", method="state").holds
        report = qcpp.verify(s, rule="paper", method="gadgets")
        assert report.holds and report.outcome == "holds" and report.unresolved is None, report.summary()
        mixer = next(c for c in report.checks if c.part == "mixer" and c.how == "exhaustive")
        k = (mixer.inputs * 16 // 15).bit_length() - 1  # 2^k inputs less the 2^(k-4) closed loops
        assert mixer.inputs == 2**k - 2 ** (k - 4)
    exact = {c.subject.split()[-1]: c.inputs for c in verify_gadgets(small_field(), 1).checks if c.part == "rule"}
    assert exact == {c.subject.split()[-1]: c.inputs for c in report.checks if c.part == "rule"}


def not_certified_field() -> qcpp.Scenario:
    """The paper rule on 6x6 with both endpoints on the bottom row: the goal's picture lets a flip give the start
    three edges, and none of the robot's first 20,000 paths (of more) has that input."""
    return qcpp.grid_scenario(6, 6, robots=[((5, 3), (5, 5))])


def test_inputs_no_path_is_shown_to_contain_give_not_certified() -> None:
    report = qcpp.verify(not_certified_field(), rule="paper", method="gadgets")
    assert report.outcome == "not_certified" and not report.holds and report.counterexample is None
    u = report.unresolved
    assert u is not None and u.reachable is None and "leaves the feasible set" in u.reason
    assert f"more than {gadgets.REACH_PATHS:,} paths" in u.reason
    open_checks = [c for c in report.checks if c.undecided]
    assert open_checks and all(not c.held and c.mark == "open" for c in open_checks)
    assert u.check in {c.subject for c in open_checks}
    assert report.verdict.startswith("feasibility preservation NOT CERTIFIED: ")
    text = report.summary(80)
    assert "unresolved input (gadgets, " in text and "--method state" in text and "counterexample (" not in text
    data = report.to_dict()
    assert data["outcome"] == "not_certified" and data["counterexample"] is None
    assert data["unresolved"]["reachable"] is None
    assert [c["undecided"] for c in data["checks"]] == [c.undecided for c in report.checks]  # each check says it
    assert any(c["undecided"] and not c["held"] for c in data["checks"])
    assert "<td>undecided</td>" in report._repr_html_()


def test_the_command_exits_3_when_not_certified_and_says_what_decides(tmp_path: Path) -> None:
    path = tmp_path / "six.toml"
    qcpp.save_scenario(not_certified_field(), path)
    res = CliRunner().invoke(app, ["verify", str(path), "--rule", "paper", "--method", "gadgets"],
                             env={"COLUMNS": "80"})  # fmt: skip
    assert res.exit_code == 3, res.output
    assert "NOT CERTIFIED" in res.stdout and "too large for --method state" in words(res.stdout)
    assert max(map(len, res.stdout.splitlines())) <= 80
    res = CliRunner().invoke(app, ["verify", str(path), "--rule", "paper", "--method", "gadgets", "--json"])
    assert res.exit_code == 3 and json.loads(res.stdout)["outcome"] == "not_certified"
    small = tmp_path / "small.toml"
    qcpp.save_scenario(small_field(), small)
    for rule, code, outcome in (("paper", 0, "holds"), ("exact", 0, "holds")):
        res = CliRunner().invoke(app, ["verify", str(small), "--rule", rule, "--method", "gadgets", "--json"])
        assert res.exit_code == code and json.loads(res.stdout)["outcome"] == outcome


def test_an_input_on_no_feasible_path_is_decided_within_the_path_budget(monkeypatch: pytest.MonkeyPatch) -> None:
    """On 3x4 with a hard obstacle the paper rule allows a flip that gives the start three edges, at an input none
    of the robot's five paths has: harmless, so the gadget method holds (as the state method does); with a path
    budget below five the same input is unresolved."""
    s = qcpp.grid_scenario(3, 4, robots=[((0, 0), (0, 2))], obstacles=[(1, 1)], hard_obstacles=True)
    assert qcpp.verify(s, rule="paper", method="state").holds
    assert qcpp.verify(s, rule="paper", method="gadgets").outcome == "holds"
    monkeypatch.setattr(gadgets, "REACH_PATHS", 2)
    report = qcpp.verify(s, rule="paper", method="gadgets")
    assert report.outcome == "not_certified" and report.unresolved is not None
    assert "degree 3" in report.unresolved.reason and report.unresolved.reachable is None


def test_the_gadget_method_agrees_with_the_state_method_on_every_one_robot_3x3_field() -> None:
    """Where every robot's paths can be listed, the gadget method decides: for both rules and every pair of
    endpoints, it holds exactly where the state method holds and fails exactly where it fails (so skipping closed
    loops and unreachable inputs never certifies a leaking circuit)."""
    nodes = [(r, c) for r in range(3) for c in range(3)]
    outcomes = set()
    for i, a in enumerate(nodes):
        for b in nodes[i + 1 :]:
            s = qcpp.grid_scenario(3, 3, robots=[(a, b)])
            for rule in ("exact", "paper"):
                state = qcpp.verify(s, rule=rule, method="state").holds
                report = qcpp.verify(s, rule=rule, method="gadgets")
                assert report.outcome == ("holds" if state else "fails"), (a, b, rule, report.summary())
                outcomes.add((rule, report.outcome))
    assert outcomes == {("exact", "holds"), ("paper", "holds"), ("paper", "fails")}


def test_a_reachable_input_becomes_a_real_counterexample() -> None:
    """A flip that adds a closed loop next to a feasible path: the input shown is that feasible path."""
    s = qcpp.grid_scenario(3, 3, robots=[((0, 0), (0, 2))])
    q = next(q for q in s.grid.plaquettes if q.corners[0] == (1, 1))
    picture, outer = plaquette_picture(s, 0, q)
    edges = list(q.edges) + [e for o in outer for e in o]
    failure = gadgets._rule_failure(s, 0, q, sbf_logic(s, 0, q, "paper"), picture, edges, 0, (0, 0, 0, 0),
                                    [[0] * len(o) for o in outer], 7)  # fmt: skip
    cx = failure.counterexample
    assert failure.inputs == 7 and failure.part == "rule"
    assert cx.reachable is True and "adds all four plaquette edges" in cx.reason and "A real leak" in cx.reason
    path, out = mask_of(s, cx.input_paths[0]), mask_of(s, cx.output_paths[0])
    assert is_feasible(s, 0, path) and not is_feasible(s, 0, out) and path ^ out == q.edge_mask


@pytest.mark.parametrize("pbits", [(1, 0, 1, 0), (0, 1, 0, 1)])
def test_a_flip_of_opposite_edges_is_named_and_checked_on_real_paths(pbits: tuple[int, ...]) -> None:
    """Two opposite edges of an interior plaquette, every corner with one outer edge: the flip can split the path
    into a path and a loop, and a feasible path where it does is the counterexample's input."""
    s = qcpp.grid_scenario(4, 4, robots=[((0, 0), (3, 3))])
    q = next(q for q in s.grid.plaquettes if q.corners[0] == (1, 1))
    picture, outer = plaquette_picture(s, 0, q)
    edges = list(q.edges) + [e for o in outer for e in o]
    mask = sum(1 << e for e, b in zip(q.edges, pbits, strict=True) if b) | sum(1 << o[0] for o in outer)
    obits = [[1] + [0] * (len(o) - 1) for o in outer]
    failure = gadgets._rule_failure(s, 0, q, sbf_logic(s, 0, q, "paper"), picture, edges, mask, pbits, obits, 1)
    cx = failure.counterexample
    assert "two opposite plaquette edges into the other two" in cx.reason and "closed loop" in cx.reason
    assert cx.reachable is True and "A real leak" in cx.reason
    path, out = mask_of(s, cx.input_paths[0]), mask_of(s, cx.output_paths[0])
    local = sum(1 << e for e in edges)
    assert path & local == mask and is_feasible(s, 0, path) and not is_feasible(s, 0, out)
    assert path ^ out == q.edge_mask


def test_reachability_is_decided_within_the_path_budget_and_left_open_beyond(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    s = qcpp.grid_scenario(4, 4, robots=[((0, 0), (3, 3))])  # 184 paths
    q = next(q for q in s.grid.plaquettes if q.corners[0] == (1, 1))
    local = sum(1 << e for e in q.edges)
    first = next(iter_paths(s, 0))
    mask = (first & local) ^ (1 << q.edges[0])  # not the first path's local input
    reachable, _, checked = gadgets._reach(s, 0, local, mask, q.edge_mask)
    assert reachable is not None and checked <= 184
    monkeypatch.setattr(gadgets, "REACH_PATHS", 1)
    assert gadgets._reach(s, 0, local, mask, q.edge_mask) == (None, None, 1)


def test_the_negative_control_still_fails_with_its_documented_message() -> None:
    s = qcpp.load_scenario(ROOT / "examples" / "paper_rule_leak.toml")
    report = qcpp.verify(s, 1, rule="paper", method="gadgets")
    cx = report.counterexample
    assert report.outcome == "fails" and cx is not None and cx.reachable is True
    assert cx.reason.startswith("the rule allows a flip that leaves the feasible set: corner d (1, 1) gets degree 3")
    assert is_feasible(s, 0, mask_of(s, cx.input_paths[0])) and not is_feasible(s, 0, mask_of(s, cx.output_paths[0]))
    doc = (ROOT / "docs" / "verify.md").read_text()
    assert words(cx.reason.split(". ")[0]) in words(doc)


def test_a_failed_gates_check_counts_its_inputs(monkeypatch: pytest.MonkeyPatch) -> None:
    from qcpp.problem.presets import default_scenario

    from .verify_test import _drop_one_control

    _drop_one_control(monkeypatch)
    report = verify_gadgets(default_scenario(3, 3, 2), p=1)
    failed = report.checks[-1]
    assert not failed.held and failed.part == "mixer"
    assert failed.inputs >= 1 and f"{failed.inputs} inputs" in words(report.summary(80))
    assert report.to_dict()["checks"][-1]["inputs"] == failed.inputs


# ------------------------------------------------------------------------------------------------- progress
@pytest.mark.parametrize(("method", "unit"), [("state", "inputs"), ("gadgets", "checks")])
def test_progress_names_what_it_counts_and_guesses_no_time_left(
    method: str, unit: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The state method's first inputs (phase separators) cost a hundredth of the mixer's: no time left is shown,
    even long after the start."""
    monkeypatch.setattr(Progress, "_elapsed", lambda self: 5.0)
    env = {"QCPP_PROGRESS": "lines", "QCPP_PROGRESS_INTERVAL": "0"}
    res = CliRunner().invoke(app, ["verify", "--grid", "2x3", "--robots", "1", "--method", method, "--json"], env=env)
    assert res.exit_code == 0, res.output
    lines = [line for line in res.stderr.splitlines() if line.startswith("verify ")]
    counts = [line for line in lines if " / " in line]
    assert len(counts) >= 3 and all(re.search(rf" / [0-9]+ {unit} ", line) for line in counts)
    assert f" {unit} done in " in lines[-1] and not any("left" in line for line in lines)


def test_progress_without_time_left_still_shows_the_share_done() -> None:
    import io

    for time_left in (True, False):
        bar = Progress("t", total=4, unit="inputs", stream=io.StringIO(), mode="lines", interval=0,
                       time_left=time_left)  # fmt: skip
        bar._start = 1.0  # entered long ago: two seconds elapsed and more
        bar.update(1)
        status = bar.status()
        assert "1 / 4 inputs (25.0%)" in status
        assert bool(re.search(r"about .* left", status)) == time_left
