"""An exception or Ctrl-C inside a public function leaves no poisoned cache behind: the next call gives the answer a
fresh process gives (the estimators and the plan cache per scenario; an interrupted computation must not be kept)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

import qcpp
from qcpp.ir.cost import Cost

SRC = Path(__file__).resolve().parents[2] / "src"
ARGS = ("--grid", "4x5", "--robots", "2", "--obstacle", "1,2", "-p", "2")


def fresh_json(*args: str) -> Any:
    """``qcpp ARGS --json`` in a new interpreter (no cache shared with this test process)."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")])}
    res = subprocess.run([sys.executable, "-m", "qcpp", *args, "--json"], capture_output=True, text=True, env=env,
                         timeout=300, check=True)  # fmt: skip
    return json.loads(res.stdout)


@pytest.mark.parametrize("after", [1, 40])
def test_an_interrupted_estimate_leaves_the_caches_sound(monkeypatch: pytest.MonkeyPatch, after: int) -> None:
    s = qcpp.grid_scenario(4, 5, robots=2, obstacles=[(1, 2)], hard_obstacles=after == 40)  # cold caches per case
    calls = {"n": 0}
    add = Cost.__add__

    def interrupting_add(self: Cost, other: Cost) -> Cost:
        calls["n"] += 1
        if calls["n"] == after:
            raise KeyboardInterrupt
        return add(self, other)

    monkeypatch.setattr(Cost, "__add__", interrupting_add)
    with pytest.raises(KeyboardInterrupt):
        qcpp.estimate(s, 2)
    calls["n"] = -(10**12)  # no further interruption
    hard = ("--hard-obstacles",) if after == 40 else ()
    [row] = fresh_json("estimate", *ARGS, *hard)
    assert qcpp.estimate(s, 2).to_dict() == row
    monkeypatch.setattr(Cost, "__add__", add)
    compiled = fresh_json("compile", *ARGS[:-2], *hard, "-p", "2", "--lowered")
    assert qcpp.compile(s, 2, lowered=True).counts() == compiled["gates"]
