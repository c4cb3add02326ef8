"""Every docstring example of every module runs and prints what it says (examples are documentation: a stale one
misleads, so none is left out of the run)."""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import pytest

PACKAGES = ("qcpp",)


def _modules() -> list[str]:
    names: list[str] = []
    for package in PACKAGES:
        root = importlib.import_module(package)
        names.append(package)
        names += [m.name for m in pkgutil.walk_packages(root.__path__, package + ".") if m.name != "qcpp.__main__"]
    return names


MODULES = _modules()

QUIMB_MODULES = frozenset({"qcpp.simulate.tensor", "qcpp.simulate.contraction_paths"})
"""Modules whose examples run quimb: in the xdist group of the tests that do (tests/conftest.py)."""


def test_the_module_list_is_complete() -> None:
    expected = {"qcpp.plan.qaoa", "qcpp.problem.sbf", "qcpp.estimators.estimate", "qcpp.simulate.subspace",
                "qcpp.cli.app"}
    assert expected <= set(MODULES)


@pytest.mark.parametrize(
    "name", [pytest.param(m, marks=pytest.mark.xdist_group("quimb")) if m in QUIMB_MODULES else m for m in MODULES]
)
def test_docstring_examples(name: str) -> None:
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS, report=True)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples of {name} failed (output above)"
