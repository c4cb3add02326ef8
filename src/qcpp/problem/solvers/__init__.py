"""Classical solvers for the coverage-path-planning cost (the paper's baselines) and a method registry.

* :func:`dfs` -- exhaustive search over all combinations of the robots' simple paths (exact optimum);
* :func:`anneal` -- simulated annealing with SBF moves;
* :func:`genetic` -- the paper's genetic algorithm with SBF mutations;
* :func:`cpsat` -- the cost modelled for OR-Tools CP-SAT (exact optimum with a proof, or best found and a bound
  at a time limit; the full answer is a :class:`CpSatResult`);

all returning a :class:`Solution`. :data:`SOLVERS` maps method names to callables with one uniform
signature (:class:`SolveMethod`), which is what front ends dispatch on; :func:`solve` is the shortcut.
Methods living in higher layers (QAOA) are added by the front end with a function of the same signature.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> sorted(SOLVERS)
    ['anneal', 'cpsat', 'dfs', 'genetic']
    >>> solve(s, "dfs").cost.total == solve(s, "anneal", seed=2).cost.total == solve(s, "cpsat").cost.total
    True
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Mapping
from types import MappingProxyType, ModuleType
from typing import TYPE_CHECKING, Any, Protocol

from qcpp.problem.sbf import Rule
from qcpp.problem.scenario import Scenario
from qcpp.problem.solvers.annealing import anneal
from qcpp.problem.solvers.exhaustive import dfs
from qcpp.problem.solvers.genetic_algorithm import genetic
from qcpp.problem.solvers.moves import AUTO_COMPONENT_NODES, CostCache, MoveSpace
from qcpp.problem.solvers.result import ProgressFn, Solution, solution_to_dict

if TYPE_CHECKING:
    from qcpp.problem.solvers.cpsat import CpSatResult, cpsat

__all__ = [
    "AUTO_COMPONENT_NODES",
    "SOLVERS",
    "CostCache",
    "CpSatResult",
    "MoveSpace",
    "ProgressFn",
    "Solution",
    "SolveMethod",
    "anneal",
    "cpsat",
    "dfs",
    "genetic",
    "solution_to_dict",
    "solve",
]


class SolveMethod(Protocol):
    """The uniform solver signature front ends call (options a method does not use are ignored)."""

    def __call__(
        self, scenario: Scenario, *, seed: int, rule: Rule, progress: ProgressFn | None
    ) -> Solution: ...


def _dfs(scenario: Scenario, *, seed: int, rule: Rule, progress: ProgressFn | None) -> Solution:
    # exhaustive search is deterministic and scores every feasible path: seed and rule do not apply
    return dfs(scenario, progress=progress)


def _cpsat(scenario: Scenario, *, seed: int, rule: Rule, progress: ProgressFn | None) -> Solution:
    # an exact model of the cost: no moves, so no rule; runs until the optimum is proven
    from qcpp.problem.solvers.cpsat import cpsat as run_cpsat

    return run_cpsat(scenario, seed=seed, progress=progress).solution


def __getattr__(name: str) -> Any:
    # OR-Tools is slow to import: cpsat and CpSatResult load on first use, not with the package
    if name not in ("cpsat", "CpSatResult"):
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    module = importlib.import_module("qcpp.problem.solvers.cpsat")
    globals().update(cpsat=module.cpsat, CpSatResult=module.CpSatResult)
    return globals()[name]


class _Package(ModuleType):
    """This package's module type: importing the submodule ``cpsat`` does not replace the function ``cpsat``."""

    def __setattr__(self, name: str, value: Any) -> None:
        if name == "cpsat" and isinstance(value, ModuleType):
            value = value.cpsat
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package


SOLVERS: Mapping[str, SolveMethod] = MappingProxyType(
    {"dfs": _dfs, "anneal": anneal, "genetic": genetic, "cpsat": _cpsat}
)
"""Method name -> :class:`SolveMethod` with default settings (read-only)."""


def solve(
    scenario: Scenario, method: str, *, seed: int = 0, rule: Rule = "exact", progress: ProgressFn | None = None
) -> Solution:
    """Run the registered classical method ``method`` with its default settings.

    Raises:
        ValueError: if ``method`` is not in :data:`SOLVERS`.
    """
    try:
        fn = SOLVERS[method]
    except KeyError:
        raise ValueError(f"unknown method {method!r} (expected one of {', '.join(SOLVERS)})") from None
    return fn(scenario, seed=seed, rule=rule, progress=progress)
