"""Run the docstring examples of the IR and simulator modules."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "circuitgen.angles",
    "circuitgen.gates",
    "circuitgen.circuit",
    "circuitgen.lowering",
    "circuitgen.qasm",
    "circuitgen.testing",
    "circuitgen._perf",
    "circuitgen.phase",
    "circuitgen.gadgets.phase_ising",
    "circuitgen.gadgets.phase_visits",
    "circuitgen.gadgets.phase_sums",
    "circuitgen.gadgets.partial_mixer",
    "circuitgen.gadgets.junction",
    "circuitgen.qaoa",
    "circuitgen.options",
    "circuitgen.call_graph",
    "circuitgen.mixer_classes",
    "circuitgen.phase_classes",
    "simulate.statevector",
    "simulate.sparse",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name: str) -> None:
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0
    assert result.failed == 0
