"""Run the docstring examples of the CLI modules and of the shared guards they rely on."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "qcpp.cli",
    "qcpp.interrupt",
    "qcpp.render",
    "qcpp.streams",
    "fileio.atomic",
    "fileio.inputs",
    "fileio.capture",
    "gridcover.limits",
    "gridcover.cost_range",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name: str) -> None:
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0
    assert result.failed == 0
