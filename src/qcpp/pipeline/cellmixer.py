"""Partial mixers planned for the heavy-hex cells: of equally cheap parity-basis plans, the one that routes cheapest.

:func:`~qcpp.gadgets.partial_mixer.plan_parity_mixer` finds the fewest CNOTs for a partial mixer's parity
network, but many networks are equally cheap (which qubit carries the flip, which pairs the CNOTs join) and the
A* returns the first it meets. On an all-to-all machine they cost the same; on a heavy-hex cell
(:mod:`qcpp.layout.heavy_hex`) they do not: a cell is a 12-cycle with three of a plaquette's four edges on one row
line and the fourth on the row line above, 2 to 6 steps apart, so a network whose CNOTs join near edges routes to
fewer SWAPs.

**Variants** (:func:`relabelled_plans`). The A* is run on the program with the plaquette's four positions relabelled
(all 24 relabellings) and each plan is mapped back: a relabelling is an isomorphism of the search, so every
variant has the optimum's CNOTs and the same ANDs and rotation (the same two-qubit count, equal to the default
plan's; only the one-qubit X gates of the polarity tracking may differ) and implements the same partial mixer
``exp(-i beta/2 XXXX)`` on the move condition. The QAOA operator, the order of the partial mixers and the
all-to-all counts are unchanged.

**Choice** (:func:`cell_mixers`). On a heavy-hex lattice device with the cell layout, each partial mixer's
section is replaced by the variant whose window routes to the fewest two-qubit gates from home, allocated and routed
exactly as :func:`qcpp.pipeline.device_compile.medial_compile` then does it
(:func:`qcpp.layout.medial.allocate_ancillas` with compile's search, :func:`qcpp.routing.windows.route_window`), the
default plan on ties. The allocation search is the costly part, so every variant is first routed with the greedy
allocation and the search runs on the default plan and the
:attr:`~qcpp.routing.options.RoutingOptions.cell_screen` variants that route cheapest that way (the chosen plan never
routes to more than the default plan; ``benchmarks/hex_compile_speed.py --screen`` compares the choice with the
search run on every variant). Then the operands of one AND
at a time (its mirror follows) or the rotation's two controls are exchanged, each exchange kept if it routes to
fewer, until none does: the same logic, but a lowered AND uses its first operand twice
(:func:`qcpp.ir.gates.and_`) and the rotation alternates its controls, so the order decides which qubits SABRE
brings together. An exchange moves no ancilla, so it is first routed on the sites the search found for the plan it
is tried against, and searched only where it routes to no more there
(:attr:`~qcpp.routing.options.RoutingOptions.cell_swap_screen`; ``hex_compile_speed.py --screen`` compares).
The choice is memoised in the run's :class:`~qcpp.routing.context.RoutingContext` per *cell class*
(the gadget's kind, its data qubits' coordinates relative to an anchor on the lattice's translation grid, and the
occupied and existing qubits within :data:`MARGIN` of them), so the interior plaquettes of a large grid are scored
once. A cached choice is only a choice: the chosen section is routed afresh by compile, so the written circuit and
its counts stay exact. A kind whose relabellings all give the
default plan is left as compiled. The cost is compile time: every variant is allocated with the search and routed
(most of a heavy-hex compile's time; the routed windows are memoised on their physical gates up to the lattice's
translations, :func:`qcpp.routing.windows.route_window`, so equal windows of other plaquettes and the final
allocation and routing of the chosen variants are mostly look-ups; a variant met again in the exchanges is not
scored again, and the 24 relabelled A* runs of a program share one search's states).

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.problem.sbf import sbf_logic
    >>> from qcpp.gadgets.partial_mixer import abstract_program, plan_parity_mixer
    >>> s = default_scenario(2, 3, 1)
    >>> program, _ = abstract_program(sbf_logic(s, 0, s.grid.plaquettes[0], "exact"), s.grid.plaquettes[0])
    >>> plans = relabelled_plans(program, "nisq")
    >>> plans[0] == plan_parity_mixer(program, "nisq"), len(plans)
    (True, 6)
    >>> {p.cost().cx for p in plans}
    {16}
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Callable, Hashable, Mapping, Sequence

import numpy as np

from qcpp.gadgets.partial_mixer import (
    MOVES,
    AbstractProgram,
    MixerPlan,
    ParityPartialMixer,
    Slot,
    parity_search,
)
from qcpp.hardware.device import Device, heavy_hex_coordinates, heavy_hex_distance
from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, Section
from qcpp.layout.medial import allocate_section
from qcpp.lowering.passes import lower
from qcpp.plan.qaoa import QaoaPlan
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.windows import route_window_cx

__all__ = ["MARGIN", "cell_mixers", "relabelled", "relabelled_plans", "variant_section"]

MARGIN = 6
"""Lattice coordinates around a partial mixer's data whose qubits (present, occupied) key its cell class: the
allocation puts its ancillas within two steps of their partners and a window routes within two steps of them."""


def _relabel_program(program: AbstractProgram, sigma: Sequence[int]) -> AbstractProgram:
    """The program with plaquette position ``k`` renamed ``sigma[k]``."""

    def mask(m: int) -> int:
        return sum(1 << sigma[k] for k in range(4) if m >> k & 1)

    steps = tuple(
        tuple(("form", mask(ref), v) if kind == "form" else (kind, ref, v) for kind, ref, v in lits)  # type: ignore[arg-type]
        for lits in program.steps
    )
    return dataclasses.replace(program, steps=steps)


def _relabel_plan(plan: MixerPlan, sigma: Sequence[int]) -> MixerPlan:
    """A plan of the relabelled program as a plan of the original (slot ``("p", sigma[k])`` is position ``k``)."""
    back = {sigma[k]: k for k in range(4)}

    def slot(s: Slot) -> Slot:
        return ("p", back[s[1]]) if s[0] == "p" else s

    compute = tuple((name, tuple(slot(s) for s in slots)) for name, slots in plan.compute)
    rotation = (plan.rotation[0], tuple(slot(s) for s in plan.rotation[1]))
    return MixerPlan(compute, rotation, plan.num_temps)


def relabelled_plans(
    program: AbstractProgram,
    target: str = "nisq",
    known: dict[Hashable, MixerPlan] | None = None,
) -> tuple[MixerPlan, ...]:
    """The distinct parity-basis plans of ``program`` found under the 24 relabellings of the plaquette's positions
    (see the module docs), the default plan (:func:`plan_parity_mixer`) first.

    The A* of a relabelled program is the program's own A* with its CNOTs tried in the relabelled order
    (:class:`~qcpp.gadgets.partial_mixer.ParitySearch`), so the 24 runs share one search's states (with
    :func:`~qcpp.gadgets.partial_mixer.plan_parity_mixer`'s run: :func:`~qcpp.gadgets.partial_mixer.parity_search`).

    Args:
        program: An ``exact`` rule's abstract program.
        target: ``nisq`` or ``ft``.
        known: The plans of relabelled programs, keyed ``(relabelled program, target)``, read and filled (the
            relabellings of one plaquette's program are often relabellings of another's); ``None``: none.

    Returns:
        The plans, each with the default plan's two-qubit gates count.
    """
    search = parity_search(program, target)  # type: ignore[arg-type]
    out: list[MixerPlan] = []
    for sigma in itertools.permutations(range(4)):
        back = [0] * 4
        for k in range(4):
            back[sigma[k]] = k
        key = (_relabel_program(program, sigma), target) if known is not None else None
        if key is not None and key in known:  # type: ignore[operator]
            plan = _relabel_plan(known[key], sigma)  # type: ignore[index]
        else:  # the relabelled program's A*: position sigma[k] there is position k here
            plan = search.plan([(back[c], back[t]) for c, t in MOVES])
            if key is not None:
                known[key] = _relabel_plan(plan, back)  # type: ignore[index]
        if plan not in out:
            out.append(plan)
    return tuple(out)


def _operand_swaps(plan: MixerPlan) -> list[MixerPlan]:
    """The plan with the two operands of one AND (and of its mirror) or the rotation's two controls exchanged, one
    plan per such gate: the same logic, but the lowered AND uses its first operand twice and the rotation
    alternates its controls, so which qubit comes first changes what routes."""
    out = []
    for k, (name, slots) in enumerate(plan.compute):
        if name == "and":
            compute = (*plan.compute[:k], (name, (slots[1], slots[0], slots[2])), *plan.compute[k + 1 :])
            out.append(dataclasses.replace(plan, compute=compute))
    name, slots = plan.rotation
    if name == "ccrx":
        out.append(dataclasses.replace(plan, rotation=(name, (slots[1], slots[0], slots[2]))))
    return out


def _class_key(gadget: ParityPartialMixer, homes: Sequence[int], coords: Sequence[tuple[int, int]],
               occupied: set[tuple[int, int]]) -> Hashable:  # fmt: skip
    """The gadget's cell class (see the module docs): kind, data coordinates relative to an anchor that keeps the
    lattice's translation class (multiples of 4 in both coordinates), and the neighbourhood's qubits."""
    data = [coords[homes[q]] for q in (*gadget.plaquette_qubits, *gadget.outer_qubits)]
    y0, x0 = min(y for y, _ in data), min(x for _, x in data)
    y1, x1 = max(y for y, _ in data), max(x for _, x in data)
    ay, ax = y0 - y0 % 4, x0 - x0 % 4
    around = tuple(sorted(
        (y - ay, x - ax, (y, x) in occupied)
        for y, x in coords
        if y0 - MARGIN <= y <= y1 + MARGIN and x0 - MARGIN <= x <= x1 + MARGIN
    ))  # fmt: skip
    return gadget.kind, tuple((y - ay, x - ax) for y, x in data), around


def _window_cx(section: Section, homes: Sequence[int], device: Device, dist: np.ndarray,
               routing: RoutingOptions, context: RoutingContext) -> int:  # fmt: skip
    """Two-qubit gates of ``section``'s window routed from home, allocated as compile allocates it
    (:func:`~qcpp.layout.medial.allocate_section`, what :func:`~qcpp.layout.medial.allocate_ancillas` does per
    section), the window given by its physical pairs."""
    return _allocated_cx(section, homes, device, dist, routing, context)[0]


Scored = tuple[int, dict[int, int]]
"""A section's routed CX and the sites of its ancillas (logical ancilla -> device qubit) it routed with."""


def _allocated_cx(section: Section, homes: Sequence[int], device: Device, dist: np.ndarray,
                  routing: RoutingOptions, context: RoutingContext) -> Scored:  # fmt: skip
    """:func:`_window_cx` and the ancillas' sites it routed with."""
    home = allocate_section(section, homes, device, dist, routing.allocation_search, routing, context)
    return _sited_cx(section, homes, home, device, dist, routing, context), home


def _sited_cx(section: Section, homes: Sequence[int], home: Mapping[int, int], device: Device, dist: np.ndarray,
              routing: RoutingOptions, context: RoutingContext) -> int:  # fmt: skip
    """Two-qubit gates of ``section``'s window routed from home with its ancillas at ``home`` (logical ancilla ->
    device qubit)."""
    n_data = len(homes)
    pairs = [tuple(int(homes[q]) if q < n_data else home[q] for q in g[1]) for g in section.gates if len(g[1]) == 2]
    return route_window_cx(pairs, None, device, dist, 0, routing, context)  # type: ignore[arg-type]


def variant_section(circuit: Circuit, name: str, gadget: ParityPartialMixer, plan: MixerPlan,
                    bindings: Mapping[str, float] | None) -> Section:  # fmt: skip
    """The lowered section ``name`` of ``circuit`` (a partial mixer's, ``gadget``) written with ``plan`` instead,
    bound by ``bindings`` as the circuit was."""
    g = dataclasses.replace(gadget, plan=plan, beta=Angle.symbol(name.replace("mixer", "beta")))
    lowered = lower(Circuit(circuit.registers, [Section(name, tuple(g.emit()))]))
    return (lowered.bind(bindings) if bindings else lowered).sections[0]


def relabelled(context: RoutingContext, program: AbstractProgram, target: str) -> tuple[MixerPlan, ...]:
    """:func:`relabelled_plans`, memoised in ``context``, with the plan of each relabelled program memoised there too
    where the context reuses answers (4x4/2: 144 distinct programs among the 13 programs' 312 relabellings)."""
    hit = context.relabelled.get((program, target))
    if hit is None:
        known = context.plans if context.reuse else None
        hit = context.relabelled[program, target] = relabelled_plans(program, target, known)
    return hit  # type: ignore[no-any-return]


def cell_mixers(
    plan: QaoaPlan,
    circuit: Circuit,
    device: Device,
    homes: Sequence[int],
    dist: np.ndarray,
    bindings: Mapping[str, float] | None = None,
    stage: Callable[[str], None] | None = None,
    routing: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> Circuit:
    """``circuit`` with every parity-basis partial mixer's section replaced by its cheapest variant on ``device``
    (see the module docs); unchanged where ``device`` is not a heavy-hex lattice or the circuit is not the plan's.

    Args:
        plan: The plan the circuit was compiled from (:attr:`qcpp.plan.compile.CompileResult.plan`; ``fuse=False``).
        circuit: The plan's lowered circuit (one section per gadget; angles bound by ``bindings``).
        device: The device (a heavy-hex lattice, :func:`qcpp.layout.heavy_hex.heavy_hex_distance`).
        homes: Physical qubit of every data qubit (the cell layout).
        dist: The device's all-pairs distances.
        bindings: The angle values the circuit was bound with.
        stage: Called before each partial mixer's choice with ``choosing partial-mixer plans on the cells (i / n)``.
        routing: The settings compile allocates and routes with.
        context: The run's memos (default: a fresh one): choices are memoised there per cell class.

    Returns:
        The circuit, with the same sections in the same order.
    """
    context = RoutingContext() if context is None else context
    d = heavy_hex_distance(device)
    if d is None or plan.options.rule != "exact" or plan.options.fuse:
        return circuit
    named = list(plan.sections())
    if [n for n, _ in named] != [s.name for s in circuit.sections]:
        return circuit  # not the plan's circuit (e.g. p = 0 or another construction)
    screen = routing.cell_screen if routing.allocation_search else 0
    screen_routing = dataclasses.replace(routing, allocation_search=False)
    coords = heavy_hex_coordinates(d)
    occupied = {coords[h] for h in homes}
    sections = list(circuit.sections)
    mixers = sum(isinstance(gadget, ParityPartialMixer) for _, gadget in named)
    seen = 0
    for i, (name, gadget) in enumerate(named):
        if not isinstance(gadget, ParityPartialMixer):
            continue
        if stage is not None:
            stage(f"choosing partial-mixer plans on the cells ({seen} / {mixers})")
        seen += 1
        program, target = gadget.kind.program, gadget.kind.target  # type: ignore[union-attr]
        plans = relabelled(context, program, target)
        if len(plans) < 2:  # one network only: kept as compiled, operands included
            continue

        def variant(plan: MixerPlan, gadget: ParityPartialMixer = gadget, name: str = name) -> Section:
            return variant_section(circuit, name, gadget, plan, bindings)

        emitted: dict[MixerPlan, Section] = {gadget.plan: sections[i]}  # the screen and the search share them
        costs: dict[tuple[MixerPlan, bool], Scored] = {}  # the operand exchanges come back to plans already scored

        def section_of(plan: MixerPlan, emitted: dict[MixerPlan, Section] = emitted) -> Section:
            if plan not in emitted:
                emitted[plan] = variant(plan)
            return emitted[plan]

        def scored(plan: MixerPlan, search: bool = True, costs: dict[tuple[MixerPlan, bool], Scored] = costs) -> Scored:
            if (plan, search) not in costs:
                options = routing if search else screen_routing
                costs[plan, search] = _allocated_cx(section_of(plan), homes, device, dist, options, context)
            return costs[plan, search]

        def cost(plan: MixerPlan, search: bool = True) -> int:
            return scored(plan, search)[0]

        key = (_class_key(gadget, homes, coords, occupied), routing)
        chosen = context.cell_choices.get(key)
        if chosen is None:
            candidates = range(len(plans))
            if screen:  # the default plan and the variants that route cheapest with the greedy allocation
                by_greedy = sorted((cost(plan, search=False), j) for j, plan in enumerate(plans))
                candidates = sorted({0, *(j for _, j in by_greedy[:screen])})
            best, k = min((cost(plans[j]), j) for j in candidates)
            chosen = plans[k]
            improved = True
            while improved:  # operands exchanged one gate at a time, each kept if it routes to fewer
                improved = False
                at_sites, sites = scored(chosen)  # the round's plan and the sites its search routed it on
                for swapped in _operand_swaps(chosen):
                    if routing.cell_swap_screen and routing.allocation_search and _sited_cx(
                            section_of(swapped), homes, sites, device, dist, routing, context) > at_sites:
                        continue  # routes to more on the same sites: not searched
                    c = cost(swapped)
                    if c < best:
                        best, chosen, improved = c, swapped, True
            context.cell_choices[key] = chosen
        if chosen != gadget.plan:
            sections[i] = emitted[chosen] if chosen in emitted else variant(chosen)
    return Circuit(circuit.registers, sections)
