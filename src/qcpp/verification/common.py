"""What both methods share: the plan checked, angles, feasibility of decoded basis states, naming edges, gadgets and
plaquettes."""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Hashable, Iterable
from typing import Any

import numpy as np

from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import QaoaPlan, qaoa_plan
from qcpp.problem.grid import Plaquette
from qcpp.problem.paths import edges_of, is_feasible
from qcpp.problem.sbf import LocalPicture, Rule
from qcpp.problem.scenario import Scenario

ProgressFn = Callable[[int, int], None]
"""``progress(done, total)``: how far a check got (the CLI passes :meth:`qcpp.io.progress.Progress.update`)."""

TOLERANCE = 1e-9
"""Amplitudes at most this large (in modulus) count as zero; larger ones are compared to this precision."""


def verified_plan(scenario: Scenario, p: int, rule: Rule, options: PlanOptions | None) -> QaoaPlan:
    """The plan of the circuit a verifier checks: built with ``options``, or ``PlanOptions(rule=rule)`` when there
    are none (so ``options``' rule replaces ``rule``; the report names ``plan.options.rule``).

    Raises:
        ValueError: ``p < 1`` (a circuit without layers has no mixer to check).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> verified_plan(default_scenario(2, 2, 1), 1, "paper", None).options.rule
        'paper'
        >>> verified_plan(default_scenario(2, 2, 1), 0, "exact", None)
        Traceback (most recent call last):
        ...
        ValueError: p must be at least 1, got 0
    """
    if p < 1:
        raise ValueError(f"p must be at least 1, got {p}")
    return qaoa_plan(scenario, p, PlanOptions(rule=rule) if options is None else options)


def random_angle(rng: random.Random) -> float:
    """A seeded angle in ``[0.1, pi - 0.1]``: nonzero, so no rotation is the identity by accident."""
    return rng.uniform(0.1, math.pi - 0.1)


def edge_names(scenario: Scenario, mask: int) -> tuple[tuple[tuple[int, int], tuple[int, int]], ...]:
    """The grid edges set in ``mask`` as node pairs."""
    edges = scenario.grid.edges
    return tuple((tuple(edges[e][0]), tuple(edges[e][1])) for e in edges_of(mask))  # type: ignore[misc]


def kind_text(gadget: Any) -> str:
    """A gadget's class and kind key, shortened for reports."""
    key = repr(getattr(gadget, "kind", None))
    return f"{type(gadget).__name__} {key[:100]}{'...' if len(key) > 100 else ''}"


def plaquette_of_qubits(scenario: Scenario, qubits: Iterable[int]) -> tuple[int, Plaquette] | None:
    """``(robot, plaquette)`` whose four edges are the data qubits ``qubits`` (a partial mixer's), if any."""
    owners = [scenario.variable_of(q) for q in qubits if q < scenario.num_variables]
    if len(owners) != 4 or len({r for r, _ in owners}) != 1:
        return None
    edges = {e for _, e in owners}
    for q in scenario.grid.plaquettes:
        if set(q.edges) == edges:
            return owners[0][0], q
    return None


class FeasibleTest:
    """Whether the data part of basis states is a feasible assignment and the ancillas are clean, vectorised over
    keys; per robot, each distinct path is tested once (:func:`~qcpp.problem.paths.is_feasible`)."""

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario
        self.v = scenario.edges_per_robot
        self.n = scenario.num_variables
        self._known: list[dict[int, bool]] = [{} for _ in scenario.robots]

    def robot_bits_to_mask(self, bits: int) -> int:
        """A robot's variable bits (bit ``k`` = its ``k``-th variable edge) as a grid edge mask."""
        mask = 0
        for k, e in enumerate(self.scenario.variable_edges):
            if (bits >> k) & 1:
                mask |= 1 << e
        return mask

    def masks(self, key: int) -> tuple[int, ...]:
        """Per robot, the grid edge mask of basis state ``key``."""
        full = (1 << self.v) - 1
        return tuple(self.robot_bits_to_mask((key >> (r * self.v)) & full) for r in range(len(self._known)))

    def path_ok(self, robot: int, bits: int) -> bool:
        """Whether robot bits ``bits`` form a feasible path (memoised)."""
        hit = self._known[robot].get(bits)
        if hit is None:
            hit = self._known[robot][bits] = is_feasible(self.scenario, robot, self.robot_bits_to_mask(bits))
        return hit

    def bad(self, keys: np.ndarray) -> np.ndarray:
        """Per key: True when an ancilla is set or some robot's path is infeasible."""
        out = (keys >> self.n) != 0
        full = (1 << self.v) - 1
        for r in range(len(self._known)):
            part = (keys >> (r * self.v)) & full
            uniq, inverse = np.unique(part, return_inverse=True)
            ok = np.array([self.path_ok(r, int(u)) for u in uniq], dtype=bool)
            out |= ~ok[inverse]
        return out

    def dirty(self, key: int) -> tuple[int, ...]:
        """Ancilla qubits set in ``key``."""
        rest, out, q = key >> self.n, [], self.n
        while rest:
            if rest & 1:
                out.append(q)
            rest, q = rest >> 1, q + 1
        return tuple(out)


def gadget_label(gadget: Any, picture_of: Callable[[Hashable], str | None]) -> str:
    """A short name of a gadget for reports: partial mixers and junctions by the local pictures
    (:attr:`qcpp.problem.sbf.LocalPicture.label`) of their partial mixers' kinds (``picture_of(kind)``), others
    by class and kind key (:func:`kind_text`)."""
    from qcpp.gadgets.junction import MixerJunction, MixerRotation
    from qcpp.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer

    def pic(m: Any) -> str:
        return "-" if m is None else picture_of(m.kind) or "?"

    if isinstance(gadget, ParityPartialMixer | McxPartialMixer):
        return f"{type(gadget).__name__} {pic(gadget)}"
    if isinstance(gadget, MixerRotation):
        return f"MixerRotation {gadget.kind[1]} of {pic(gadget.mixer)}"  # type: ignore[index]
    if isinstance(gadget, MixerJunction):
        overlap = f" overlap {list(gadget.overlap)}" if gadget.left is not None and gadget.right is not None else ""
        return f"MixerJunction {pic(gadget.left)} -> {pic(gadget.right)}{overlap}"
    return kind_text(gadget)


def picture_label(scenario: Scenario, robot: int, plaq: Plaquette) -> str:
    """The label of the plaquette's local picture for ``robot`` (``EBBN``: endpoint, busy-able, plain corners)."""
    return plaquette_picture(scenario, robot, plaq)[0].label


def plaquette_picture(
    scenario: Scenario, robot: int, plaq: Plaquette
) -> tuple[LocalPicture, tuple[tuple[int, ...], ...]]:
    """The plaquette's :class:`~qcpp.problem.sbf.LocalPicture` for ``robot`` and each corner's variable outer edges."""
    vmask = scenario.variable_mask
    outer = tuple(tuple(e for e in oe if (vmask >> e) & 1) for oe in plaq.outer_edges)
    rb = scenario.robots[robot]
    return LocalPicture.of(plaq.corners, rb.start, rb.goal, [len(o) for o in outer]), outer
