"""The QUBO solver pipeline (qcpp.qubo.solve): cycle dropping, the annealers, the missing-package message."""

from __future__ import annotations

import sys

import pytest

from qcpp.problem.paths import initial_path, path_from_nodes
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import cpsat
from qcpp.qubo.solve import INSTALL_HINT, MissingAnnealer, drop_cycles, require_annealer, solve_qubo


def test_drop_cycles_keeps_the_path_and_refuses_wrong_degrees() -> None:
    s = default_scenario(3, 4, 1)
    g = s.grid
    path = path_from_nodes(g, [(0, 0), (1, 0), (2, 0), (2, 1), (2, 2), (2, 3)])
    ring = path_from_nodes(g, [(0, 1), (0, 2), (1, 2), (1, 1), (0, 1)])
    assert drop_cycles(s, 0, path) == path
    assert drop_cycles(s, 0, path | ring) == path
    spur = path_from_nodes(g, [(0, 2), (0, 3)])
    assert drop_cycles(s, 0, path | spur) is None  # degree 1 away from the ends
    assert drop_cycles(s, 0, ring) is None  # the ends are not on it
    assert drop_cycles(s, 0, initial_path(s, 0)) == initial_path(s, 0)


@pytest.mark.parametrize("name", ["two_robots_4x4.toml", "two_robots_5x5.toml"])
def test_qubo_method_returns_the_proven_optimum(name: str) -> None:
    pytest.importorskip("dwave.samplers")
    s = load_scenario(f"examples/{name}")
    run = solve_qubo(s, seed=0)
    assert run.solution.cost.total == cpsat(s).solution.cost.total
    assert 0 <= run.feasible <= run.repairable <= run.reads == 100
    assert run.penalty > 0 and run.sampler == "tabu"


def test_simulated_annealing_sampler_and_no_polish() -> None:
    pytest.importorskip("dwave.samplers")
    s = default_scenario(3, 3, 1)
    run = solve_qubo(s, sampler="sa", reads=20, sweeps=200, polish=0, seed=3)
    assert run.reads == 20 and run.sampler == "sa"
    assert run.solution.rule is None
    assert run.solution.cost.total >= cpsat(s).solution.cost.total


def test_missing_annealer_says_what_to_install(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "dwave.samplers", None)
    with pytest.raises(MissingAnnealer, match=r"pip install 'qcpp\[annealing\]'") as info:
        require_annealer()
    assert isinstance(info.value, ValueError) and INSTALL_HINT in str(info.value)
    assert isinstance(info.value, ImportError)  # `except ImportError` around an optional feature keeps working
    assert str(info.value).startswith("the qubo method needs")  # no --flag: the API raises it too
    with pytest.raises(MissingAnnealer):
        solve_qubo(default_scenario(2, 2, 1))
