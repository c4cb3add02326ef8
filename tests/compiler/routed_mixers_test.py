"""Partial mixers planned for a whole-circuit routing (:mod:`qcpp.pipeline.routed_mixers`).

Evidence: on 3x3/1 and heavy-hex:3 the chosen circuit differs from the plan's circuit only in partial-mixer sections,
each with the plan's two-qubit count; it acts exactly as the plan's circuit on random data states with clean
ancillas (statevector); the shorter search it is chosen by routes it to fewer two-qubit gates; compile writes it as
its logical circuit and routes it to fewer two-qubit gates than with the choice turned off. Where there is nothing
to choose (all-to-all, above the placement search's limit, turned off) the circuit is returned unchanged. The
routed circuits compile writes are checked against their logical circuits in ``tests/compiler/routing_test.py`` and
``tests/compiler/routing_qcec_test.py``.
"""

from __future__ import annotations

import doctest
import importlib
from dataclasses import replace

import numpy as np
import pytest

from qcpp import grid_scenario
from qcpp.hardware.device import get_device
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import rx, ry
from qcpp.layout.placement_search import search_ranking
from qcpp.pipeline.device_compile import compile_for_device
from qcpp.pipeline.routed_mixers import routed_mixers
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario
from qcpp.routing.options import DEFAULT_ROUTING
from qcpp.simulate.statevector import simulate_statevector

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
OPTIONS = PlanOptions(fuse=False)
SCENARIO = default_scenario(3, 3, 1)


def _twoq(section: Section) -> int:
    return sum(1 for g in section.gates if len(g[1]) == 2)


@pytest.fixture(scope="module")
def chosen() -> tuple[Circuit, Circuit]:
    """The plan's circuit of 3x3/1 and the one chosen for heavy-hex:3."""
    compiled = compile_scenario(SCENARIO, 1, OPTIONS, lowered=True, bindings=BIND)
    return compiled.circuit, routed_mixers(compiled.plan, compiled.circuit, get_device("heavy-hex:3"), BIND)


def test_doctests() -> None:
    result = doctest.testmod(importlib.import_module("qcpp.pipeline.routed_mixers"))
    assert result.failed == 0 and result.attempted > 0


def test_only_partial_mixers_change_and_keep_their_counts(chosen: tuple[Circuit, Circuit]) -> None:
    circuit, variant = chosen
    assert [s.name for s in variant.sections] == [s.name for s in circuit.sections]
    changed = [i for i, (a, b) in enumerate(zip(circuit.sections, variant.sections)) if a.gates != b.gates]
    assert changed and all(circuit.sections[i].name.startswith("mixer_") for i in changed)
    assert all(_twoq(circuit.sections[i]) == _twoq(variant.sections[i]) for i in changed)


def test_the_chosen_circuit_is_the_plans_circuit_as_an_operator(chosen: tuple[Circuit, Circuit]) -> None:
    circuit, variant = chosen
    n_data = SCENARIO.num_variables
    for seed in range(3):
        rng = np.random.default_rng(seed)
        angles = rng.uniform(0, 3, size=(n_data, 2))
        prep = Section("prep", tuple(g for q in range(n_data) for g in (ry(angles[q, 0], q), rx(angles[q, 1], q))))
        states = [simulate_statevector(Circuit(c.registers, [prep, *c.sections])) for c in (circuit, variant)]
        assert np.allclose(states[0], states[1], atol=1e-9)


def test_the_choice_routes_to_fewer_by_its_own_search(chosen: tuple[Circuit, Circuit]) -> None:
    circuit, variant = chosen
    dev = get_device("heavy-hex:3")

    def routed(c: Circuit) -> int:
        return search_ranking(c, dev, layouts=DEFAULT_ROUTING.mixer_variant_layouts,
                              seeds=DEFAULT_ROUTING.mixer_variant_seeds)[0][0]  # fmt: skip

    assert routed(variant) < routed(circuit)


def test_compile_writes_the_chosen_circuit_and_routes_it_to_fewer() -> None:
    off = replace(DEFAULT_ROUTING, mixer_variant_layouts=0)
    results = [compile_for_device(SCENARIO, 1, "heavy-hex:3", lowered=True, bindings=BIND, routing=r)
               for r in (DEFAULT_ROUTING, off)]  # fmt: skip
    on_twoq, off_twoq = (sum(1 for g in r.routed.circuit.gates if len(g[1]) == 2) for r in results)
    assert on_twoq < off_twoq
    on_logical, off_logical = (list(r.logical.gates) for r in results)
    assert on_logical != off_logical  # the chosen plans are what was routed
    assert off_logical == list(results[1].compiled.circuit.gates)


def test_nothing_to_choose_returns_the_circuit() -> None:
    compiled = compile_scenario(SCENARIO, 1, OPTIONS, lowered=True, bindings=BIND)
    plan, circuit = compiled.plan, compiled.circuit
    hex3 = get_device("heavy-hex:3")
    assert routed_mixers(plan, circuit, get_device("all-to-all:15"), BIND) is circuit
    off = replace(DEFAULT_ROUTING, mixer_variant_layouts=0)
    assert routed_mixers(plan, circuit, hex3, BIND, off) is circuit
    small = replace(DEFAULT_ROUTING, placement_max_twoq=10)
    assert routed_mixers(plan, circuit, hex3, BIND, small) is circuit
    fused = compile_scenario(SCENARIO, 1, PlanOptions(), lowered=True, bindings=BIND)
    assert routed_mixers(fused.plan, fused.circuit, hex3, BIND) is fused.circuit
    two_layers = compile_scenario(SCENARIO, 2, OPTIONS, lowered=True)  # not the circuit of this plan
    assert routed_mixers(plan, two_layers.circuit, hex3) is two_layers.circuit
    ring = grid_scenario(2, 2, robots=[((0, 1), (1, 0))], obstacles=[(0, 0)], hard_obstacles=True)
    no_twoq = compile_scenario(ring, 1, OPTIONS, lowered=True, bindings=BIND)  # no plaquette left: no CX
    assert routed_mixers(no_twoq.plan, no_twoq.circuit, get_device("grid:3x3"), BIND) is no_twoq.circuit
