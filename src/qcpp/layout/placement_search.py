"""Placement search for small circuits: many initial layouts, each routed whole by SABRE with several seeds.

One SABRE routing of a circuit with a few hundred two-qubit gates (one robot at p = 1: 3x3/1, the obstacle and
interior-start scenarios, 100-130 CX) takes milliseconds, so compile can afford to try many and keep the
cheapest. Where a routing starts decides most of its SWAPs, and no single layout heuristic wins everywhere (our
greedy placement, Qiskit's ``SabreLayout`` from one random start or another; ``benchmarks/placement_search.py``:
3x3/1 on heavy-hex:3 routes to 354 CX from the best of our layouts, to 287 from the best of the search's).
:func:`search_route` routes:

* the layouts it is given (compile passes :func:`qcpp.pipeline.device_compile.best_layout`'s choice, so the search never
  does worse than the single greedy routing), then
* ``layouts`` runs of Qiskit's ``SabreLayout``, each from one random start (seeds ``seed, seed + 1, ...``),

each with SABRE routing seed ``seed`` and the ``placement_refine`` cheapest also with ``seeds - 1`` more,
whole-circuit, with SWAPs fused into an adjacent ``cx`` on their pair (:func:`qcpp.routing.sabre.route`
``fuse=True``: ``cx a b`` then ``SWAP a b`` is two ``cx``), and keeps the routed circuit with the fewest
two-qubit gates (ties: the first layout in that order, then the lowest seed). Every seed is fixed and every
Qiskit pass gets an explicit trial count (Qiskit's default is the machine's CPU count), so the result is the
same on every machine and ``qcpp estimate --device`` (which compiles small rows) reports exactly what
``qcpp compile --device`` writes. The routed circuit is an ordinary SABRE routing of the unchanged gates: the
checks of :mod:`qcpp.routing.sabre` (coupling edges, statevector and QCEC equivalence up to the layouts) apply.

Compile searches only on circuits of at most :attr:`~qcpp.routing.options.RoutingOptions.placement_max_twoq`
two-qubit gates (its cost grows with the gate count times ``layouts x seeds``; larger circuits keep one routing from
the best layout). The settings come in one :class:`~qcpp.routing.options.RoutingOptions` value.

Example:
    >>> from dataclasses import replace
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.plan.compile import compile_scenario
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.plan.options import PlanOptions
    >>> c = compile_scenario(default_scenario(2, 3, 1), 1, PlanOptions(fuse=False), lowered=True).circuit
    >>> dev = get_device("heavy-hex:3")
    >>> best = search_route(c, dev, layouts=4, seeds=2)
    >>> one = route(c, dev, qiskit_sabre_layout(c, dev, seed=0))
    >>> two_qubit_count(best.circuit) <= two_qubit_count(one.circuit)
    True
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit
from qcpp.routing.context import RoutingContext
from qcpp.routing.options import DEFAULT_ROUTING, RoutingOptions
from qcpp.routing.patches import patch_sabre, placed_dags, run_sabre
from qcpp.routing.routed_circuit import RoutedCircuit, coupling_map, sabre_target
from qcpp.routing.sabre import cx_dag, dag_cx, route

__all__ = ["qiskit_sabre_layout", "ranked_routes", "search_ranking", "search_route", "two_qubit_count"]


def two_qubit_count(circuit: Circuit) -> int:
    """Two-qubit gates of ``circuit``."""
    return sum(1 for g in circuit.gates if len(g[1]) == 2)


def qiskit_sabre_layout(
    circuit: Circuit, device: Device, seed: int = 0, options: RoutingOptions = DEFAULT_ROUTING
) -> tuple[int, ...]:
    """Qiskit's ``SabreLayout`` (forward-backward SABRE from ``options.sabre_layout_trials`` random starts) on the
    two-qubit gates of ``circuit``.

    Args:
        circuit: A lowered circuit.
        device: The target (at least ``circuit.num_qubits`` qubits).
        seed: ``SabreLayout``'s seed.
        options: The routing settings.

    Returns:
        Logical qubit ``i`` -> physical qubit.
    """
    dag = cx_dag(circuit.num_qubits, [g[1] for g in circuit.gates if len(g[1]) == 2])
    return _sabre_layouts(dag, sabre_target(coupling_map(device)), [seed], options)[0]


def _sabre_layouts(
    dag: Any, target: Any, seeds: Sequence[int], options: RoutingOptions
) -> list[tuple[int, ...]]:
    """:func:`qiskit_sabre_layout` for each of ``seeds``: one pass on ``dag`` (the circuit's two-qubit gates,
    :func:`qcpp.routing.sabre.cx_dag`), its seed set per run. ``target`` is the one the pass would build from the
    device's (symmetric) coupling map itself (:func:`~qcpp.routing.routed_circuit.sabre_target`), built once by the
    caller; the layouts are the ones a pass manager running a fresh pass per seed finds."""
    from qiskit.passmanager import PropertySet
    from qiskit.transpiler.passes import SabreLayout

    trials = options.sabre_layout_trials
    sabre = SabreLayout(target, skip_routing=True, layout_trials=trials, swap_trials=trials)
    layouts = []
    for seed in seeds:
        sabre.seed, sabre.property_set = seed, PropertySet()
        sabre.run(dag)
        layout = sabre.property_set["layout"]
        layouts.append(tuple(int(layout[q]) for q in dag.qubits))
    return layouts


def search_route(
    circuit: Circuit,
    device: Device,
    starts: Sequence[Sequence[int]] = (),
    seed: int = 0,
    measured: Sequence[int] | None = None,
    layouts: int | None = None,
    seeds: int | None = None,
    options: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> RoutedCircuit:
    """The cheapest whole-circuit SABRE routing over ``starts`` and ``layouts`` ``SabreLayout`` runs, SWAPs fused
    (module docs).

    Args:
        circuit: A lowered circuit (one- and two-qubit gates).
        device: The target (not all-to-all: nothing to search there).
        starts: Layouts to try first (logical qubit ``i`` -> physical qubit).
        seed: First seed of ``SabreLayout`` and of the routings.
        measured: Logical qubits measured at the end (:func:`qcpp.routing.sabre.route`).
        layouts: ``SabreLayout`` runs (seeds ``seed .. seed + layouts - 1``; default ``options.placement_layouts``).
        seeds: Routing seeds (``seed .. seed + seeds - 1``; default ``options.placement_seeds``): every layout is
            routed with the first, the ``options.placement_refine`` cheapest with all.
        options: The search's settings.
        context: The run's memos (default: a fresh one): the winner is memoised per circuit, device and settings,
            so compiling the same circuit again in the run routes only the winner.

    Returns:
        The routed circuit with the fewest two-qubit gates (ties: the first layout in the order above, then the
        lowest seed).

    Raises:
        ValueError: nothing to try (no ``starts`` and ``layouts == 0``, or ``seeds == 0``).
    """
    layout, routing_seed = search_ranking(circuit, device, starts, seed, layouts, seeds, options, context)[0][1:]
    return route(circuit, device, layout, seed=routing_seed, measured=measured, trials=options.trials, fuse=True)


def search_ranking(
    circuit: Circuit,
    device: Device,
    starts: Sequence[Sequence[int]] = (),
    seed: int = 0,
    layouts: int | None = None,
    seeds: int | None = None,
    options: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> list[tuple[int, tuple[int, ...], int]]:
    """Every routing :func:`search_route` tries (arguments as there), as ``(two-qubit gates, layout, routing
    seed)``, cheapest first, counted without writing a circuit: for a caller that compares circuits by what the
    search routes them to."""
    layouts = options.placement_layouts if layouts is None else layouts
    seeds = options.placement_seeds if seeds is None else seeds
    if (not starts and layouts < 1) or seeds < 1:
        raise ValueError("the placement search needs at least one layout and one seed")
    return _ranked(circuit, device, starts, seed, layouts, seeds, options, context)


def ranked_routes(
    circuit: Circuit,
    device: Device,
    starts: Sequence[Sequence[int]] = (),
    seed: int = 0,
    measured: Sequence[int] | None = None,
    count: int = 6,
    options: RoutingOptions = DEFAULT_ROUTING,
    context: RoutingContext | None = None,
) -> list[RoutedCircuit]:
    """The ``count`` cheapest distinct routings of :func:`search_route`'s search (fewest two-qubit gates first; the
    first is :func:`search_route`'s), for a caller that scores them by more than their two-qubit count (the
    calibrated candidates of :mod:`qcpp.pipeline.candidates`). Arguments as :func:`search_route`, with its default
    numbers of layouts and seeds."""
    layouts, seeds = options.placement_layouts, options.placement_seeds
    ranked = _ranked(circuit, device, starts, seed, layouts, seeds, options, context)
    return [route(circuit, device, layout, seed=s, measured=measured, trials=options.trials, fuse=True)
            for _, layout, s in ranked[:count]]  # fmt: skip


def _ranked(
    circuit: Circuit,
    device: Device,
    starts: Sequence[Sequence[int]],
    seed: int,
    layouts: int,
    seeds: int,
    options: RoutingOptions,
    context: RoutingContext | None,
) -> list[tuple[int, tuple[int, ...], int]]:
    """:func:`_search`'s ranking of (cost, layout, seed), memoised in ``context.placements`` under the settings it
    reads (so compiles that differ in other settings share it)."""
    context = RoutingContext() if context is None else context
    pairs = tuple(g[1] for g in circuit.gates if len(g[1]) == 2)
    settings = (options.sabre_layout_trials, options.trials, options.placement_refine)
    key = (pairs, circuit.num_qubits, device.coupling, device.num_qubits, tuple(map(tuple, starts)), seed, layouts,
           seeds, settings)  # fmt: skip
    ranked = context.placements.get(key)
    if ranked is None:
        ranked = _search(pairs, circuit, device, starts, seed, layouts, seeds, options, context)
        context.placements[key] = ranked
    return ranked


def _search(
    pairs: tuple[tuple[int, ...], ...],
    circuit: Circuit,
    device: Device,
    starts: Sequence[Sequence[int]],
    seed: int,
    layouts: int,
    seeds: int,
    options: RoutingOptions,
    context: RoutingContext,
) -> list[tuple[int, tuple[int, ...], int]]:
    """``(two-qubit gates, layout, routing seed)`` of every routing :func:`search_route` tries, cheapest first (the
    first is its choice; one entry per layout and seed): every layout routed with ``seed``, then the
    ``options.placement_refine`` cheapest of them with the other seeds. A candidate is scored by
    :func:`qcpp.routing.sabre.dag_cx` of SABRE's routing (in one window that is the two-qubit count
    :func:`qcpp.routing.sabre.route` writes with ``fuse=True``), without assembling the circuit. SABRE runs as
    :func:`qcpp.routing.patches.run_sabre` runs it (the context's pass for the device's couplings, without the
    pass's per-run checks: the same routing)."""
    shape = patch_sabre(context, device.coupling, device.num_qubits)  # its target serves SabreLayout too
    logical = cx_dag(circuit.num_qubits, pairs)
    candidates = list(dict.fromkeys(tuple(int(p) for p in s) for s in starts))
    for layout in _sabre_layouts(logical, shape.sabre.target, range(seed, seed + layouts), options):
        if layout not in candidates:  # SabreLayout may converge to a layout already found
            candidates.append(layout)
    dags = placed_dags(shape, logical, pairs, candidates)
    trials = shape.trials if options.trials is None else options.trials

    def routed_cx(dag: Any, seed: int) -> int:
        """Two-qubit gates of SABRE's routing of ``dag`` (physical qubits), SWAPs fused as :func:`route` fuses
        them."""
        return dag_cx(run_sabre(shape, dag, seed, trials, context.parallel_trials))

    first = sorted((routed_cx(dag, seed), i) for i, dag in enumerate(dags))
    tried = [(cx, i, seed) for cx, i in first]
    for _, i in first[: options.placement_refine]:
        for s in range(seed + 1, seed + seeds):
            tried.append((routed_cx(dags[i], s), i, s))
    return [(cx, candidates[i], s) for cx, i, s in sorted(tried)]
