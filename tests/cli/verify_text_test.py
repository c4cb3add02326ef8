"""``qcpp verify``'s text names each robot's edges, spells out a local picture's corner letters and draws the
counterexample on the grid as ``qcpp solve`` draws paths; its JSON keeps its keys."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

import qcpp
from qcpp.cli.app import app
from qcpp.cli.commands.verify import drawn_counterexample
from qcpp.verification.report import Counterexample

LEAK = Path(__file__).resolve().parents[2] / "examples" / "paper_rule_leak.toml"
TWO_ROBOTS = ("--grid", "2x3", "--robot", "0,2:1,1", "--robot", "0,0:1,0")
"""The leak's robot and a second one beside it: the paper rule fails on robot 0's plaquette."""

REPORT_KEYS = {"scenario", "p", "rule", "method", "holds", "checks", "counterexample", "seconds", "seed", "target",
               "unresolved", "outcome", "exhaustive"}  # fmt: skip
COUNTEREXAMPLE_KEYS = {"method", "check", "kind", "robot", "plaquette", "input_paths", "output_paths",
                       "dirty_ancillas", "amplitude", "reason", "reachable"}  # fmt: skip


def verify(*args: str) -> tuple[str, dict]:
    """The text (80 columns) and the JSON of one failing ``qcpp verify``."""
    text = CliRunner().invoke(app, ["verify", *args, "--rule", "paper"], env={"COLUMNS": "80"})
    data = CliRunner().invoke(app, ["verify", *args, "--rule", "paper", "--json"])
    assert text.exit_code == data.exit_code == 1, text.output
    return text.stdout, json.loads(data.stdout)


def drawn_edges(lines: list[str]) -> dict[tuple[tuple[int, int], tuple[int, int]], str]:
    """Edge -> its character in a drawing (node ``(r, c)`` at row ``2r``, column ``4c``; blank: not drawn)."""
    out = {}
    for r, line in enumerate(lines):
        for c, ch in enumerate(line):
            if ch in " -":
                continue
            if r % 2 == 0 and c % 4 == 2:
                out[((r // 2, c // 4), (r // 2, c // 4 + 1))] = ch
            elif r % 2 == 1 and c % 4 == 0:
                out[((r // 2, c // 4), (r // 2 + 1, c // 4))] = ch
    return out


def drawing(text: str, name: str, rows: int) -> list[str]:
    """The grid of ``rows`` rows drawn under ``<name>, drawn:``, its indent taken off."""
    lines = text.splitlines()
    start = lines.index(f"{name}, drawn:") + 1
    return [line[2:] for line in lines[start:start + 2 * rows - 1]]


@pytest.mark.parametrize("args", [(str(LEAK),), TWO_ROBOTS], ids=["one robot", "two robots"])
def test_each_robot_s_edges_are_labelled_and_drawn(args: tuple[str, ...]) -> None:
    text, data = verify(*args)
    cx = data["counterexample"]
    robots = len(cx["input_paths"])
    assert robots == (2 if args == TWO_ROBOTS else 1)
    lines = text.splitlines()
    first = next(i for i, line in enumerate(lines) if line.startswith("  input:  "))
    block = lines[first:lines.index("input, drawn:")]
    labels = [line[10:19] for line in block if line[10:16] == "robot "]  # each robot's edges after its label
    assert labels == [f"robot {r}: " for r in range(robots)] * 2, block
    assert [line[:10] for line in block if line[10:16] == "robot "][robots] == "  output: "
    assert not any("; " in line for line in block)  # no robots joined by ';'
    for name in ("input", "output"):
        drawn = drawn_edges(drawing(text, name, 2))
        expected = {}
        for r, edges in enumerate(cx[f"{name}_paths"]):
            for a, b in edges:
                e = (tuple(a), tuple(b))
                expected[e] = "*" if e in expected else str(r)
        assert drawn == expected
    assert "robot 0: (0, 2) -> (1, 1), 2 edges" in text  # the legend of qcpp solve's drawing, after the input
    assert max(map(len, text.splitlines())) <= 80
    assert set(data) == REPORT_KEYS and set(cx) == COUNTEREXAMPLE_KEYS


def test_the_corner_letters_are_spelled_out_on_the_plaquette() -> None:
    text, data = verify(str(LEAK))
    cx = data["counterexample"]
    s = qcpp.load_scenario(LEAK)
    ends = {s.robots[0].start, s.robots[0].goal}
    letters = ["E" if tuple(c) in ends else "?" for c in cx["plaquette"]]
    code = next(w for w in cx["kind"].split() if len(w) in (4, 5) and set(w) <= set("EBND"))
    assert code.endswith("D") and [ch if ch == "E" else "?" for ch in code[:4]] == letters
    spelled = ", ".join(f"({c[0]}, {c[1]}) {ch}" for c, ch in zip(cx["plaquette"], code, strict=False))
    words = " ".join(text.split())
    assert f"picture: {code} = corners {spelled}; D: start and goal on diagonal corners" in words
    assert "E the robot's start or goal, B two outer edges, N fewer" in words


def test_the_gadget_method_says_what_the_pictures_of_its_checks_are() -> None:
    text, data = verify(str(LEAK), "--method", "gadgets")
    assert any(c["subject"].startswith("rule paper ") for c in data["checks"])
    assert "pictures (four corner letters, as NNEN): a plaquette's corners a, b, c, d in order" in " ".join(
        text.split())
    assert "input, drawn:" in text and set(data["counterexample"]) == COUNTEREXAMPLE_KEYS


def test_nothing_is_drawn_without_edges_or_room() -> None:
    s = qcpp.grid_scenario(2, 12, robots=[((0, 0), (1, 11))])
    edge = (((0, 0), (0, 1)),)
    cx = Counterexample("state", "mixer_0", None, 0, None, (edge,), (edge,), (), 1.0, "a reason")
    assert drawn_counterexample(s, cx, 80) is not None
    assert drawn_counterexample(s, cx, 40) is None  # 45 columns of grid
    phase = Counterexample("gadgets", "phase x", "x", None, None, ((),), ((),), (1,), 1.0, "moves a basis state")
    assert drawn_counterexample(s, phase, 80) is None
