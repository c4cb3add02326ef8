"""Run the docstring examples of the estimators modules."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "estimators.counts",
    "estimators.paper",
    "estimators.formulas",
    "estimators.fault_tolerant",
    "estimators.physical",
    "estimators.depth",
    "estimators.depth_compose",
    "estimators.estimate",
    "estimators.crosscheck",
    "estimators.sweep",
    "estimators.tables",
    "estimators.plots",
    "estimators.report",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name: str) -> None:
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0
    assert result.failed == 0
