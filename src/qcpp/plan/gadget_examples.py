"""Registered examples of every gadget class and one checker over all of them (Qualtran's ``bloq_example`` style).

Each gadget class the compiler emits registers a function that builds a few examples of it (:func:`example`);
:func:`gadget_examples` lists them all and :func:`check_gadget` checks the whole gadget protocol on one:

* ``emit()`` (and ``emit_blocks()`` where a class has it) gives gates on the qubits the gadget names;
* ``cost()`` equals the count of the emitted gates lowered with the ``work`` register its kind asks for, and
  ``logical_cost()`` the count lowered to :data:`~qcpp.lowering.passes.LOGICAL_BASIS`;
* ``kind`` is hashable, and the kind's needs (:class:`~qcpp.plan.call_graph.GadgetKind`: temporaries, work
  ancillas) are enough to lower it.

Every gadget class a plan emits must have registered examples (the tests run the checker on all of them).

Example:
    >>> names = {type(g).__name__ for _, g in gadget_examples()}
    >>> {"ParityPartialMixer", "MixerJunction", "VisitPhase", "SumsPhase"} <= names
    True
    >>> all(check_gadget(g) == [] for _, g in gadget_examples() if type(g).__name__ == "MixerRotation")
    True
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from functools import cache
from typing import Any

from qcpp.gadgets import Gadget
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.cost import Cost
from qcpp.lowering.passes import LOGICAL_BASIS, WORK_REGISTER, lower
from qcpp.plan.call_graph import GadgetKind
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario import Scenario, scenario_from_dict

__all__ = ["REGISTRY", "check_gadget", "example", "gadget_examples"]

REGISTRY: dict[type, Callable[[], list[Gadget]]] = {}
"""Gadget class -> a function building examples of it."""


def example(cls: type) -> Callable[[Callable[[], list[Gadget]]], Callable[[], list[Gadget]]]:
    """Register a function that builds examples of the gadget class ``cls``."""

    def register(build: Callable[[], list[Gadget]]) -> Callable[[], list[Gadget]]:
        REGISTRY[cls] = build
        return build

    return register


def gadget_examples() -> Iterator[tuple[str, Gadget]]:
    """``(label, gadget)`` for every registered example, class by class."""
    for cls, build in REGISTRY.items():
        for i, g in enumerate(build()):
            yield f"{cls.__name__}[{i}]", g


def _blocks(g: Any) -> list[tuple[Any, ...]]:
    return list(g.emit_blocks()) if hasattr(g, "emit_blocks") else [g.emit()]


def check_gadget(g: Gadget) -> list[str]:
    """Check the gadget protocol on ``g`` (see the module docstring).

    Returns:
        One line per violation (empty when the gadget keeps every promise).
    """
    out = []
    kind = GadgetKind.of(g)
    hash(kind.key)
    blocks = _blocks(g)
    top = max((q + 1 for b in blocks for gate in b for q in gate.qubits), default=1)
    registers = [Register("q", top)]
    if kind.work:
        registers.append(Register(WORK_REGISTER, kind.work))
    circuit = Circuit(registers, [Section("g", tuple(b)) for b in blocks])
    try:
        lowered, logical = Cost.count(lower(circuit).gates), Cost.count(lower(circuit, LOGICAL_BASIS).gates)
    except Exception as exc:
        return [f"{type(g).__name__}: cannot be lowered with {kind.work} work ancillas: {exc}"]
    if g.cost() != lowered:
        out.append(f"{type(g).__name__} {kind.key!r:.80}: cost() {g.cost()} != lowered {lowered}")
    if g.logical_cost() != logical:
        out.append(f"{type(g).__name__}: logical_cost() {g.logical_cost()} != lowered {logical}")
    return out


# --- the examples -------------------------------------------------------------------------------------------------
@cache
def _scenarios() -> tuple[Scenario, ...]:
    """Pure memo: ``_scenarios.cache_clear()`` empties it."""
    interior = scenario_from_dict(
        {
            "grid": {"rows": 4, "cols": 4, "obstacles": [[2, 1]]},
            "robots": [{"start": [1, 1], "goal": [3, 3]}, {"start": [0, 3], "goal": [1, 2]}],
            "objective": {"obstacles": "hard"},
        }
    )
    return default_scenario(3, 3, 2), default_scenario(4, 4, 3), interior


@cache
def _gadgets(options: Any, arithmetic: bool) -> tuple[Gadget, ...]:
    """Pure memo: ``_gadgets.cache_clear()`` empties it."""
    from qcpp.plan.qaoa import qaoa_plan

    out: list[Gadget] = []
    # the balance's register and accumulator variants appear under a tight ancilla budget on larger grids
    for s in (default_scenario(6, 6, 2),) if arithmetic else _scenarios():
        out.extend(g for _, g in qaoa_plan(s, 1, options).sections())
    return tuple(out)


def _of(cls_name: str, *options: Any, limit: int = 6, arithmetic: bool = False) -> list[Gadget]:
    """Up to ``limit`` gadgets of distinct kinds of the class named ``cls_name`` from small plans."""
    from qcpp.plan.options import PlanOptions

    seen: dict[Any, Gadget] = {}
    for o in options or (PlanOptions(),):
        for g in _gadgets(o, arithmetic):
            if type(g).__name__ == cls_name and g.kind not in seen:
                seen[g.kind] = g
    return list(seen.values())[:limit]


def _register_all() -> None:
    from qcpp.gadgets.blocks import StatePrep
    from qcpp.gadgets.junction import MixerJunction, MixerRotation
    from qcpp.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer
    from qcpp.gadgets.phase_ising import IsingPhase
    from qcpp.gadgets.phase_sums import SumsAccumulate, SumsPhase, SumsRegister
    from qcpp.gadgets.phase_visits import VisitPhase
    from qcpp.gadgets.visit_batch import VisitBatch
    from qcpp.plan.call_graph import Deferred
    from qcpp.plan.options import PlanOptions
    from qcpp.plan.phase_classes import phase_layer

    ft, paper, unfused = PlanOptions(target="ft"), PlanOptions(rule="paper"), PlanOptions(fuse=False)
    whole = PlanOptions(phase="whole-space")
    example(ParityPartialMixer)(lambda: _of("ParityPartialMixer", unfused, PlanOptions(target="ft", fuse=False)))
    example(McxPartialMixer)(lambda: _of("McxPartialMixer", paper))
    example(MixerJunction)(lambda: _of("MixerJunction", PlanOptions(), ft))
    example(MixerRotation)(lambda: _of("MixerRotation", PlanOptions(), ft))
    example(StatePrep)(lambda: _of("StatePrep", PlanOptions(), PlanOptions(initial="representatives"),
                                   PlanOptions(initial="local_search_mix")))
    example(IsingPhase)(lambda: _of("IsingPhase", PlanOptions(), whole, PlanOptions(optimize="depth")))
    spatial = PlanOptions(phase_layout="spatial")  # same kinds, adders paired by place: examples of their own
    example(VisitPhase)(lambda: _of("VisitPhase", PlanOptions(), ft) + _of("VisitPhase", spatial, limit=2))
    example(SumsPhase)(lambda: _of("SumsPhase", PlanOptions(), ft) + _of("SumsPhase", spatial, limit=2))
    example(VisitBatch)(lambda: _of("VisitBatch", ft))
    example(SumsRegister)(lambda: _of("SumsRegister", PlanOptions(ancilla_budget=70), arithmetic=True))
    example(SumsAccumulate)(lambda: _of("SumsAccumulate", PlanOptions(ancilla_budget=40), arithmetic=True))

    def deferred() -> list[Gadget]:
        out: list[Gadget] = []
        for target in ("nisq", "ft"):
            layer = phase_layer(default_scenario(6, 6, 3), target)
            assert layer is not None
            out += [k.example for k, _ in layer.kinds() if isinstance(k.example, Deferred)]
        return out

    example(Deferred)(deferred)


_register_all()
