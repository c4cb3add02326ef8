"""Partial mixers planned for the heavy-hex cells (:mod:`qcpp.pipeline.cellmixer`).

Evidence: every relabelled plan, and every plan with one AND's operands or the rotation's controls exchanged, has
the default plan's two-qubit count and acts exactly as the default plan on random data states with clean
ancillas (statevector: both partial mixers of 2x3/1 in the default run, every one of 3x3/1 in the heavy run); on a
heavy-hex lattice :func:`~qcpp.pipeline.cellmixer.cell_mixers` changes only partial-mixer sections, keeps their
two-qubit counts, changes at least one (2x3/1; 2x3/2 in the heavy run), and every changed window routes to no more
two-qubit gates than the default one; elsewhere it changes nothing. The routed circuits that use it are checked
against the compiled circuit in ``tests/compiler/hexlayout_test.py`` (statevector and QCEC).
"""

from __future__ import annotations

import dataclasses
import doctest
import importlib
import itertools

import numpy as np
import pytest

from qcpp.gadgets.partial_mixer import ParityPartialMixer, ParitySearch, plan_parity_mixer
from qcpp.hardware.device import distances, get_device
from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import rx, ry
from qcpp.layout.heavy_hex import hex_placement
from qcpp.lowering.passes import lower
from qcpp.pipeline.cellmixer import (
    _operand_swaps,
    _relabel_plan,
    _relabel_program,
    _window_cx,
    cell_mixers,
    relabelled_plans,
)
from qcpp.pipeline.device_compile import hex_device
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.presets import default_scenario
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING
from qcpp.simulate.statevector import simulate_statevector

BIND = {"gamma_0": 0.3, "beta_0": 0.7}
OPTIONS = PlanOptions(fuse=False, phase_layout="medial")


def test_doctests() -> None:
    result = doctest.testmod(importlib.import_module("qcpp.pipeline.cellmixer"))
    assert result.failed == 0 and result.attempted > 0


def _state(gadget: ParityPartialMixer, registers: tuple, n_data: int, seed: int) -> np.ndarray:
    """The gadget's lowered gates on a random product state of the data qubits, ancillas |0>."""
    rng = np.random.default_rng(seed)
    prep = [g for q in range(n_data) for g in (ry(float(rng.uniform(0, 3)), q), rx(float(rng.uniform(0, 3)), q))]
    body = lower(Circuit(registers, [Section("mixer_0", tuple(gadget.emit()))])).bind({"beta_0": 0.7})
    return simulate_statevector(Circuit(registers, [Section("prep", prep), *body.sections]))


@pytest.mark.parametrize("shape", [(2, 3, 1), pytest.param((3, 3, 1), marks=pytest.mark.heavy)], ids=["2x3/1", "3x3/1"])
def test_every_variant_is_the_same_partial_mixer(shape: tuple[int, int, int]) -> None:
    s = default_scenario(*shape)
    plan = qaoa_plan(s, 1, OPTIONS)
    mixers = [g for name, g in plan.sections() if isinstance(g, ParityPartialMixer)]
    registers = tuple(plan.circuit().registers)
    for k, m in enumerate(mixers):
        m = dataclasses.replace(m, beta=Angle.symbol("beta_0"))
        plans = relabelled_plans(m.kind.program, m.kind.target)  # type: ignore[union-attr]
        assert plans[0] == m.plan and len(plans) > 1
        swapped = [v for p in plans[:4] for v in _operand_swaps(p)]
        assert swapped
        want = _state(m, registers, s.num_variables, seed=k)
        for variant in (*plans, *swapped):
            assert variant.cost().cx == m.plan.cost().cx
            got = _state(dataclasses.replace(m, plan=variant), registers, s.num_variables, seed=k)
            assert np.allclose(got, want, atol=1e-9)


@pytest.mark.parametrize("shape", [(2, 3, 1), pytest.param((3, 3, 1), marks=pytest.mark.heavy),
                                   pytest.param((4, 4, 2), marks=pytest.mark.heavy)], ids=["2x3/1", "3x3/1", "4x4/2"])
def test_relabelled_plans_are_the_relabelled_programs_own_plans(shape: tuple[int, int, int]) -> None:
    """The shared search in the relabelled move order finds exactly the plan the A* finds on the relabelled
    program (mapped back), for every relabelling of every partial mixer's program and both targets; the memo of
    relabelled programs' plans changes nothing."""
    s = default_scenario(*shape)
    programs = {g.kind.program for _, g in qaoa_plan(s, 1, OPTIONS).sections() if isinstance(g, ParityPartialMixer)}
    known: dict = {}
    for program, target in itertools.product(sorted(programs, key=repr), ("nisq", "ft")):
        own = []
        for sigma in itertools.permutations(range(4)):
            plan = _relabel_plan(plan_parity_mixer(_relabel_program(program, sigma), target), sigma)
            if plan not in own:
                own.append(plan)
        assert relabelled_plans(program, target) == tuple(own)
        assert relabelled_plans(program, target, known) == tuple(own)
        assert ParitySearch(program, target).plan() == plan_parity_mixer(program, target)  # type: ignore[arg-type]
    assert known


def _on_cells(shape: tuple[int, int, int]) -> tuple:
    """The plan of the default scenario of ``shape`` (p = 1), its lowered circuit (bound), the smallest heavy-hex
    lattice that holds its cell layout, the layout's homes and the lattice's distances."""
    s = default_scenario(*shape)
    compiled = compile_scenario(s, 1, OPTIONS, lowered=True, bindings=BIND)
    dev = hex_device(s, "heavy-hex")
    assert dev is not None
    homes = hex_placement(s, dev)
    assert homes is not None
    return compiled.plan, compiled.circuit, dev, homes, distances(dev)


@pytest.mark.parametrize("shape", [(2, 3, 1), pytest.param((2, 3, 2), marks=pytest.mark.heavy)], ids=["2x3/1", "2x3/2"])
def test_cell_mixers_replace_only_partial_mixers_by_no_more_costly_windows(shape: tuple[int, int, int]) -> None:
    plan, circuit, dev, homes, dist = _on_cells(shape)
    planned = cell_mixers(plan, circuit, dev, homes, dist, BIND)  # a fresh context: every choice made here
    assert [sec.name for sec in planned.sections] == [sec.name for sec in circuit.sections]
    changed = 0
    for old, new in zip(circuit.sections, planned.sections, strict=True):
        if not old.name.startswith("mixer") or old == new:
            assert old == new
            continue
        changed += 1
        assert sum(len(g[1]) == 2 for g in new.gates) == sum(len(g[1]) == 2 for g in old.gates)
        context = RoutingContext()
        assert (_window_cx(new, homes, dev, dist, DEFAULT_ROUTING, context)
                <= _window_cx(old, homes, dev, dist, DEFAULT_ROUTING, context))  # fmt: skip
    assert changed > 0
    grid = get_device("grid:9x9")
    assert cell_mixers(plan, circuit, grid, homes, distances(grid), BIND) is circuit


@pytest.mark.parametrize("shape", [(2, 3, 1), pytest.param((3, 3, 2), marks=pytest.mark.heavy)], ids=["2x3/1", "3x3/2"])
def test_the_screen_only_narrows_the_variants_searched(shape: tuple[int, int, int]) -> None:
    """``cell_screen`` at least the number of variants searches every variant, as ``cell_screen=0`` does; the
    default screen routes fewer windows and keeps the default plan among them (the test above: no changed
    window routes to more)."""
    plan, circuit, dev, homes, dist = _on_cells(shape)

    def planned(screen: int) -> tuple[Circuit, int]:
        context = RoutingContext()
        routing = dataclasses.replace(DEFAULT_ROUTING, cell_screen=screen)
        out = cell_mixers(plan, circuit, dev, homes, dist, BIND, routing=routing, context=context)
        return out, len(context.windows)  # the windows routed (memo entries): the searches' work

    every, searched_every = planned(0)
    assert planned(24)[0] == every
    _, searched_screened = planned(DEFAULT_ROUTING.cell_screen)
    assert searched_screened < searched_every


@pytest.mark.parametrize("shape", [(2, 3, 1), pytest.param((3, 3, 2), marks=pytest.mark.heavy)], ids=["2x3/1", "3x3/2"])
def test_the_exchange_screen_searches_fewer_exchanges_and_keeps_the_default_bound(shape: tuple[int, int, int]) -> None:
    """``cell_swap_screen`` searches an operand exchange only where it routes to no more on the current plan's
    sites: fewer windows routed than searching every exchange, and still no chosen window above the default
    plan's (the choice only accepts what its search routes to fewer)."""
    plan, circuit, dev, homes, dist = _on_cells(shape)
    runs = {}
    for screen in (True, False):
        context = RoutingContext()
        routing = dataclasses.replace(DEFAULT_ROUTING, cell_swap_screen=screen)
        runs[screen] = (cell_mixers(plan, circuit, dev, homes, dist, BIND, routing=routing, context=context),
                        len(context.windows))  # fmt: skip
    assert runs[True][1] < runs[False][1]
    context = RoutingContext()
    for old, new in zip(circuit.sections, runs[True][0].sections, strict=True):
        if old.name.startswith("mixer"):
            assert (_window_cx(new, homes, dev, dist, DEFAULT_ROUTING, context)
                    <= _window_cx(old, homes, dev, dist, DEFAULT_ROUTING, context))  # fmt: skip
