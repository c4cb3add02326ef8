"""Partial mixers planned for a whole-circuit routing: of equally cheap parity-basis plans, those the circuit routes
cheapest with.

A small circuit (at most :attr:`~qcpp.routing.options.RoutingOptions.placement_max_twoq` lowered two-qubit gates:
one robot on small grids, two on 3x3) is routed whole by the placement search
(:func:`qcpp.layout.placement_search.search_route`), not window by window. Its partial mixers have many parity
networks of the same cost (:func:`qcpp.pipeline.cellmixer.relabelled_plans`: the same CNOT count, ANDs and rotation;
the same partial mixer ``exp(-i beta/2 XXXX)`` on the move condition), and which qubits their CNOTs join decides
much of what SABRE must bring together. :func:`routed_mixers` chooses them by coordinate descent: in circuit order,
each partial mixer's section is tried with every relabelled plan and kept with the one whose whole circuit the
search routes to the fewest two-qubit gates (a shorter search than compile's:
:attr:`~qcpp.routing.options.RoutingOptions.mixer_variant_layouts` ``SabreLayout`` starts, each routed with
:attr:`~qcpp.routing.options.RoutingOptions.mixer_variant_seeds` seeds), the plan already chosen on ties. Each
scoring routes the whole circuit, so the descent stops once the circuits it has scored hold
:attr:`~qcpp.routing.options.RoutingOptions.mixer_variant_budget` two-qubit gates in all (the first layers'
partial mixers are chosen first; a deep or two-robot circuit keeps the plan's networks for the rest).

The QAOA operator, the order of the partial mixers and the all-to-all counts are unchanged; only which of the
equally cheap networks each partial mixer uses. Compile routes the chosen circuit with its own search and keeps it
only where it routes to fewer two-qubit gates than the plan's own circuit
(:func:`qcpp.pipeline.device_compile.compile_for_device`), so the choice never adds a two-qubit gate (on a named
device the candidates are then the kept circuit's routings, chosen by ESP as always); the written circuit is an
ordinary routing of the chosen circuit, so its counts are exact. ``python benchmarks/routing.py`` and
``python benchmarks/routing_verdict.py --calibrated`` show what it gives.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.plan.compile import compile_scenario
    >>> from qcpp.plan.options import PlanOptions
    >>> from qcpp.hardware.device import get_device
    >>> compiled = compile_scenario(default_scenario(2, 3, 1), 1, PlanOptions(fuse=False), lowered=True)
    >>> c = compiled.circuit
    >>> chosen = routed_mixers(compiled.plan, c, get_device("heavy-hex:3"))
    >>> [sec.name for sec in chosen.sections] == [sec.name for sec in c.sections]
    True
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

from qcpp.gadgets.partial_mixer import ParityPartialMixer
from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Section
from qcpp.layout.placement_search import search_ranking, two_qubit_count
from qcpp.pipeline.cellmixer import relabelled, variant_section
from qcpp.plan.qaoa import QaoaPlan
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions

__all__ = ["routed_mixers"]


def routed_mixers(
    plan: QaoaPlan,
    circuit: Circuit,
    device: Device,
    bindings: Mapping[str, float] | None = None,
    routing: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
    stage: Callable[[str], None] | None = None,
) -> Circuit:
    """``circuit`` with each parity-basis partial mixer written with the equally cheap plan that the whole circuit
    routes to the fewest two-qubit gates with on ``device`` (module docs).

    Args:
        plan: The plan the circuit was compiled from (:attr:`qcpp.plan.compile.CompileResult.plan`; ``fuse=False``).
        circuit: The plan's lowered circuit (one section per gadget; angles bound by ``bindings``).
        device: The device the circuit is routed on whole.
        bindings: The angle values the circuit was bound with.
        routing: The settings (``mixer_variant_layouts=0`` turns the choice off).
        context: The run's memos (default: a fresh one).
        stage: Called before each partial mixer's choice with ``choosing partial-mixer plans for the routing on
            DEVICE (i / n)`` (a compile that searches several devices counts again on each, named).

    Returns:
        A circuit with the same sections in the same order, equal to ``circuit`` as an operator; ``circuit`` itself
        where nothing routes cheaper, where the device is all-to-all, where the circuit has no two-qubit gate or more
        than ``routing.placement_max_twoq``, or where it is not the plan's parity-basis circuit.
    """
    twoq = two_qubit_count(circuit)
    if (routing.mixer_variant_layouts < 1 or device.is_all_to_all or plan.options.rule != "exact"
            or plan.options.fuse or not 0 < twoq <= routing.placement_max_twoq):  # fmt: skip
        return circuit
    named = list(plan.sections())
    if [n for n, _ in named] != [s.name for s in circuit.sections]:
        return circuit  # not the plan's circuit
    context = RoutingContext() if context is None else context
    sections = list(circuit.sections)

    def routed_twoq(candidate_sections: list[Section]) -> int:
        candidate = Circuit(circuit.registers, candidate_sections)
        return search_ranking(candidate, device, layouts=routing.mixer_variant_layouts,
                              seeds=routing.mixer_variant_seeds, options=routing, context=context)[0][0]  # fmt: skip

    best = routed_twoq(sections)
    scorings = routing.mixer_variant_budget // twoq - 1  # the plan's own circuit was one
    mixers = [i for i, (_, gadget) in enumerate(named) if isinstance(gadget, ParityPartialMixer)]
    for seen, i in enumerate(mixers):
        name, gadget = named[i]
        assert isinstance(gadget, ParityPartialMixer)
        if stage is not None:
            stage(f"choosing partial-mixer plans for the routing on {device.name} ({seen} / {len(mixers)})")
        for network in relabelled(context, gadget.kind.program, gadget.kind.target):
            if network == gadget.plan:
                continue
            if scorings < 1:
                return Circuit(circuit.registers, sections)
            scorings -= 1
            trial = [*sections[:i], variant_section(circuit, name, gadget, network, bindings), *sections[i + 1 :]]
            routed = routed_twoq(trial)
            if routed < best:
                best, sections = routed, trial
    return Circuit(circuit.registers, sections)
