"""One checker over the registered examples of every gadget class (the gadget protocol, Qualtran style)."""

from __future__ import annotations

import dataclasses

import pytest

from qcpp.estimators.crosscheck import every_plan_option, interior_endpoints, one_plan_option_at_a_time
from qcpp.ir.cost import Cost
from qcpp.plan.gadget_examples import REGISTRY, check_gadget, gadget_examples
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.presets import default_scenario

EXAMPLES = list(gadget_examples())


@pytest.mark.parametrize(("label", "gadget"), EXAMPLES, ids=[label for label, _ in EXAMPLES])
def test_every_registered_example_keeps_the_gadget_protocol(label: str, gadget: object) -> None:
    assert check_gadget(gadget) == []  # type: ignore[arg-type]


def test_every_class_has_examples() -> None:
    counts = {cls: len(build()) for cls, build in REGISTRY.items()}
    assert all(n >= 1 for n in counts.values()), counts


def test_every_gadget_class_a_plan_emits_is_registered() -> None:
    emitted: set[type] = set()
    gadget_fields = ("rule", "initial", "target", "phase", "optimize", "ancilla_budget")  # which gadgets are built
    plans = [*every_plan_option((None, 0), gadget_fields), *one_plan_option_at_a_time((None, 0))]  # and how placed
    for s in (default_scenario(3, 3, 2), interior_endpoints(4, 4, "soft")):
        for options in plans:
            if options.initial == "representatives" and s.grid.rows > 3:
                continue  # exhaustive path enumeration: small grids only
            emitted |= {type(g) for _, g in qaoa_plan(s, 1, options).sections()}
            emitted |= {type(k.example) for _, k, _ in qaoa_plan(s, 1, options).call_graph().kinds()}
    emitted |= {type(g) for _, g in qaoa_plan(default_scenario(3, 3, 1), 1, PlanOptions(fuse=False)).sections()}
    assert emitted <= set(REGISTRY), emitted - set(REGISTRY)


def test_the_checker_finds_a_wrong_cost() -> None:
    _, good = next((label, g) for label, g in EXAMPLES if label.startswith("VisitPhase"))

    @dataclasses.dataclass(frozen=True)
    class Liar:
        inner: object

        @property
        def kind(self) -> object:
            return ("liar", self.inner.kind)  # type: ignore[attr-defined]

        def cost(self) -> Cost:
            return self.inner.cost() + Cost.of(cx=1)  # type: ignore[attr-defined]

        def logical_cost(self) -> Cost:
            return self.inner.logical_cost()  # type: ignore[attr-defined]

        def needs(self) -> tuple[int, int]:
            return self.inner.needs()  # type: ignore[attr-defined,no-any-return]

        def emit(self) -> list:
            return self.inner.emit()  # type: ignore[attr-defined]

    findings = check_gadget(Liar(good))  # type: ignore[arg-type]
    assert len(findings) == 1 and "cost()" in findings[0]
