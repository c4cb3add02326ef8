"""The gadget method: certify feasibility preservation from the plan's call graph, at any grid size.

The circuit is its call graph expanded (:meth:`qcpp.plan.qaoa.QaoaPlan.call_graph`): every gadget it emits is one of
a few kinds (equal kinds, equal gates up to qubit names), so checking every kind on every one of its local inputs
checks the whole circuit. Four groups of checks, each a :class:`~qcpp.verification.report.Check`:

``rule`` (one per local picture of the scenario, :class:`qcpp.problem.sbf.LocalPicture`)
    The rule's compiled program (:func:`qcpp.problem.sbf.sbf_logic`) on every *locally feasible* input of the
    plaquette: the four plaquette edges and every variable outer edge of its corners, with each corner's degree 1
    at the robot's endpoints and 0 or 2 elsewhere (every feasible path looks like one of these near the
    plaquette). Wherever the program allows the flip, the ``exact`` rule's specification
    (:func:`qcpp.problem.sbf.exact_rule_value`) must allow it too; that specification only allows flips whose result
    is again a feasible path. Closed loops (all four plaquette edges set) are not checked: a feasible path is a
    simple path, so no feasible assignment has one (see "closed loops" below). A failing input is named by what the
    flip does: it leaves a corner with a wrong degree, or adds all four plaquette edges (a closed loop), or swaps
    two opposite edges for the other two (which can split the path into a path and a loop). Whether a feasible
    path of the robot contains the input is then looked up among its first :data:`REACH_PATHS` paths
    (:class:`_PathIndex`): a feasible path that contains it and whose flip is not feasible is a counterexample (its
    input is that path); any other failing input is *unresolved* (no feasible path shown to contain it, or none
    shown to flip out), and the check goes on looking for a real one.
``mixer`` (one per partial-mixer kind, junction kind and rotation kind)
    The lowered gates of each partial-mixer kind on **all** ``2^k`` inputs of its ``k`` data qubits (plaquette
    and outer edges it reads), ancillas ``|0>``, closed loops excepted: where the kind's program allows the flip,
    exactly ``cos(b/2)|x> - i sin(b/2)|x xor plaquette>``, elsewhere ``|x>``, with every ancilla back in ``|0>``.
    An input where the gates differ is a counterexample when a feasible path contains it on the scenario's
    plaquette of that kind, else unresolved. In a
    fused layer (:mod:`qcpp.gadgets.junction`) the partial mixer is its opening junction, rotation and closing
    junction, and the closing junction alone must clean the state the opening one made; every junction kind
    ``J(l, r)`` must turn the state ``l``'s opening made into the one ``r``'s opening makes, on every input.
    Then the fused layer equals the product of the partial mixers, each an SBF rotation where its program allows
    it. Every partial mixer of the scenario must be of a checked kind (a coverage check).
``phase`` (one per phase-separator kind)
    Structurally: every gate of the gadget is diagonal or a permutation, and the permutations alone cancel in
    pairs (compute, phase, mirrored uncompute); then the gadget is diagonal in the computational basis, which
    keeps every basis state and returns every ancilla to ``|0>``. Kinds with at most :data:`EXHAUSTIVE_PHASE_QUBITS`
    data qubits are also run lowered on every input.
``initial_state``
    The state preparation run from ``|0...0>``: every robot on a feasible path, ancillas ``|0>``.

A partial mixer's program is what the rule check certifies and what the mixer checks hold the gates to, so
together they show: on every feasible path, each partial mixer either does nothing or rotates into a feasible path,
with clean ancillas; the phase separator only changes phases; so every layer, and the whole circuit, keeps the
span of feasible assignments.

Closed loops
    Leaving out inputs with all four plaquette edges set is sound without any reachability argument: what is
    certified is that each part maps every feasible basis state into the span of feasible ones, and a feasible
    basis state has one simple path per robot, which contains no cycle, so its local input at a plaquette is never
    a closed loop. By linearity only those inputs matter, whatever the gates do on the others (the paper rule's
    gadget computes its condition from single plaquette edges, which the flip of a closed loop changes, and leaves
    an ancilla set there). In a fused layer the state between two partial mixers is the next one's opening
    applied to such a state, so the junction checks (on every input) compose the same way.

Three outcomes (:attr:`~qcpp.verification.report.VerifyReport.outcome`): ``holds`` when every check held;
``fails`` with a counterexample; ``not_certified`` when only unresolved inputs were found. The checks go on past
an unresolved input so that a counterexample elsewhere is still found.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> r = verify_gadgets(default_scenario(4, 4, 2), p=2)
    >>> r.holds, sorted({c.part for c in r.checks})
    (True, ['initial_state', 'mixer', 'phase', 'rule'])
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import random
import time
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from qcpp.gadgets.junction import MixerJunction, MixerRotation
from qcpp.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer, abstract_program, partial_mixer
from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import GATE_SPECS, Gate
from qcpp.lowering.passes import WORK_REGISTER, lower
from qcpp.plan.call_graph import Deferred, GadgetKind
from qcpp.plan.options import PlanOptions
from qcpp.problem.grid import Plaquette
from qcpp.problem.paths import is_feasible, iter_paths
from qcpp.problem.sbf import LocalPicture, Rule, SbfLogic, exact_rule_value, sbf_logic
from qcpp.problem.scenario import Scenario
from qcpp.verification.batch import MAX_QUBITS, Batch
from qcpp.verification.common import (
    TOLERANCE,
    FeasibleTest,
    ProgressFn,
    edge_names,
    gadget_label,
    kind_text,
    plaquette_picture,
    random_angle,
    verified_plan,
)
from qcpp.verification.report import Check, Counterexample, VerifyReport
from qcpp.verification.state import _scenario_name

__all__ = ["EXHAUSTIVE_PHASE_QUBITS", "REACH_PATHS", "verify_gadgets"]

EXHAUSTIVE_PHASE_QUBITS = 12
"""Phase kinds with at most this many data qubits are also run, lowered, on every data input."""

REACH_PATHS = 20_000
"""A failed check looks for a feasible path containing its local input among this many of the robot's paths
(about half a second); a robot with more paths leaves the question open when none of them does."""

ALL_LOCAL_INPUTS = ("The gadget method checks every locally feasible input, reachable or not; --method state runs "
                    "the circuit on its real inputs.")  # fmt: skip


class _PathIndex:
    """The first :data:`REACH_PATHS` feasible paths of each robot, indexed by their local input on a set of edges
    (built on the first question about that robot and edge set; only failing checks ask)."""

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario
        self._paths: dict[int, tuple[list[int], bool]] = {}
        self._by_local: dict[tuple[int, int], dict[int, list[int]]] = {}

    def paths(self, robot: int) -> tuple[list[int], bool]:
        """The robot's first paths and whether they are all of them."""
        if robot not in self._paths:
            found = list(itertools.islice(iter_paths(self.scenario, robot), REACH_PATHS + 1))
            self._paths[robot] = (found[:REACH_PATHS], len(found) <= REACH_PATHS)
        return self._paths[robot]

    def containing(self, robot: int, local: int, mask: int) -> tuple[list[int], bool]:
        """The robot's paths (among the first :data:`REACH_PATHS`) equal to ``mask`` on the edges of ``local``, and
        whether every path of the robot was looked at."""
        key = (robot, local)
        if key not in self._by_local:
            table: dict[int, list[int]] = {}
            for path in self.paths(robot)[0]:
                table.setdefault(path & local, []).append(path)
            self._by_local[key] = table
        return self._by_local[key].get(mask, []), self.paths(robot)[1]


Mixer = ParityPartialMixer | McxPartialMixer
_CORNER_EDGES = ((0, 3), (0, 1), (1, 2), (2, 3))  # corner a, b, c, d -> its plaquette edges in (ab, bc, cd, da)


class _Failure(Exception):
    """A check found a counterexample after ``inputs`` inputs (the failing one included; 0 for a structural or
    coverage check)."""

    def __init__(self, counterexample: Counterexample, part: str = "mixer", inputs: int = 0) -> None:
        super().__init__(counterexample.reason)
        self.counterexample, self.part, self.inputs = counterexample, part, inputs
        self.leak = True  # a rule failure sets it: whether a feasible path flips out here


# --------------------------------------------------------------------------------------------- the rule, per picture
def _degrees(pbits: Sequence[int], obits: Sequence[Sequence[int]]) -> list[int]:
    return [pbits[i] + pbits[j] + sum(o) for (i, j), o in zip(_CORNER_EDGES, obits, strict=True)]


def _locally_feasible(degrees: Sequence[int], endpoints: Sequence[bool]) -> bool:
    return all(d == 1 if e else d in (0, 2) for d, e in zip(degrees, endpoints, strict=True))


def _check_rule(
    scenario: Scenario, robot: int, plaq: Plaquette, logic: SbfLogic, picture: LocalPicture,
    outer: tuple[tuple[int, ...], ...], index: _PathIndex, others: Sequence[tuple[int, Plaquette]] = (),
) -> tuple[int, int, _Failure | None]:  # fmt: skip
    """Check the program on every locally feasible input but closed loops (see the module docstring).

    The program is read in the form the gates are checked against (:func:`_program_value` of the partial mixer's
    abstract program), and must agree with the rule's own :meth:`~qcpp.problem.sbf.SbfLogic.evaluate` there.

    A failing input is looked up on ``plaq`` and on ``others`` (the scenario's other robots and plaquettes with
    this picture): a feasible path with that input whose flip is infeasible is a counterexample; when every
    robot involved has at most :data:`REACH_PATHS` paths and none is found, the input is harmless on every
    feasible path (decided); otherwise it is unresolved.

    Returns:
        ``(inputs checked, unresolved inputs, the first unresolved one's failure or None)``.

    Raises:
        _Failure: a counterexample (a failing input a feasible path contains and flips out of, or a disagreement
            of the two programs).
    """
    edges = list(plaq.edges) + [e for o in outer for e in o]
    sizes = [len(o) for o in outer]
    program, slots = abstract_program(logic, plaq)
    count, unresolved, first = 0, 0, None
    for bits in itertools.product((0, 1), repeat=len(edges)):
        pbits, rest, obits = bits[:4], list(bits[4:]), []
        for n in sizes:
            obits.append(rest[:n])
            rest = rest[n:]
        if sum(pbits) == 4 or not _locally_feasible(_degrees(pbits, obits), picture.endpoints):
            continue
        count += 1
        mask = sum(1 << e for e, b in zip(edges, bits, strict=True) if b)
        allowed = _program_value(program, pbits, [(mask >> e) & 1 for e in slots])
        if allowed != logic.evaluate(mask):
            raise _Failure(
                Counterexample(
                    "gadgets", f"rule {logic.rule} {picture.label}", f"SbfLogic {logic.rule} {picture.label}", robot,
                    tuple(plaq.corners), (edge_names(scenario, mask),), (edge_names(scenario, mask),), (), 0.0,
                    "the partial mixer's abstract program and the rule's program disagree",
                ),
                "rule",
                count,
            )
        if not allowed:
            continue
        if exact_rule_value(pbits, [sum(o) for o in obits], picture.endpoints, picture.diagonal):
            continue
        failure = _rule_failure(scenario, robot, plaq, logic, picture, edges, mask, pbits, obits, count, index)
        if failure.leak:
            raise failure
        decided = index.paths(robot)[1]  # every path of the robot looked at, none flips out here
        if decided:  # the other places of the picture: a leak there, or every path of theirs looked at too
            for r2, q2 in others:
                if not index.paths(r2)[1]:
                    decided = False
                    break
                outer2 = plaquette_picture(scenario, r2, q2)[1]
                edges2 = list(q2.edges) + [e for o in outer2 for e in o]
                mask2 = sum(1 << e for e, b in zip(edges2, bits, strict=True) if b)
                elsewhere = _rule_failure(scenario, r2, q2, sbf_logic(scenario, r2, q2, logic.rule), picture, edges2,
                                          mask2, pbits, obits, count, index)  # fmt: skip
                if elsewhere.leak:
                    raise elsewhere
        if decided:
            continue
        unresolved += 1
        if first is None and index.paths(robot)[1]:  # undecided elsewhere: say so
            cx = failure.counterexample
            more = (f"It is undecided on other plaquettes with picture {picture.label}, whose robots have more than "
                    f"{REACH_PATHS:,} paths.")  # fmt: skip
            failure.counterexample = dataclasses.replace(cx, reason=f"{cx.reason} {more}")
        first = first or failure
    return count, unresolved, first


def _rule_failure(
    scenario: Scenario, robot: int, plaq: Plaquette, logic: SbfLogic, picture: LocalPicture, edges: Sequence[int],
    mask: int, pbits: Sequence[int], obits: Sequence[Sequence[int]], count: int, index: _PathIndex | None = None,
) -> _Failure:  # fmt: skip
    """The failure of a rule check: the program allows the flip of local input ``mask`` (the ``count``-th input;
    not a closed loop) where the ``exact`` rule does not. The reason says what the flip does and whether a feasible
    path contains the input (:func:`_reach`); such a path whose flip is infeasible replaces the local input and
    output, and the failure's ``leak`` is then true (a counterexample; otherwise the input is unresolved)."""
    degrees = _degrees([1 - b for b in pbits], obits)
    wrong = [
        f"corner {'abcd'[v]} {plaq.corners[v]} gets degree {d}"
        for v, (d, e) in enumerate(zip(degrees, picture.endpoints, strict=True))
        if not (d == 1 if e else d in (0, 2))
    ]
    k = sum(pbits)
    if wrong:
        what = f"the rule allows a flip that leaves the feasible set: {wrong[0]}"
    elif k == 0:
        what = ("the rule allows a flip that adds all four plaquette edges: the output holds a closed loop around the "
                "plaquette, which no feasible path does")  # fmt: skip
    else:  # two opposite edges (exact_rule_value allows every other flip whose corners keep their degrees)
        what = ("the rule allows a flip of two opposite plaquette edges into the other two, where the exact rule "
                "does not: that can split the path into a path and a closed loop")  # fmt: skip
    local = sum(1 << e for e in edges)
    reachable, path, checked = _reach(scenario, robot, local, mask, plaq.edge_mask, index=index)
    leak = path is not None and not is_feasible(scenario, robot, path ^ plaq.edge_mask)
    if leak:
        how = "A real leak: the input shown is a feasible path with this local input, and its flip is not."
        shown = path
    elif reachable is False:
        how = f"No feasible path of robot {robot} contains this input (all {checked:,} checked). {ALL_LOCAL_INPUTS}"
        shown = mask
    elif reachable:
        how = (f"Feasible paths contain this input; those among robot {robot}'s first {checked:,} paths flip to "
               f"feasible paths. {ALL_LOCAL_INPUTS}")  # fmt: skip
        shown = mask
    else:
        how = (f"Whether a feasible path contains this input was not decided (robot {robot} has more than "
               f"{checked:,} paths). {ALL_LOCAL_INPUTS}")  # fmt: skip
        shown = mask
    failure = _Failure(
        Counterexample(
            "gadgets", f"rule {logic.rule} {picture.label}", f"SbfLogic {logic.rule} {picture.label}", robot,
            tuple(plaq.corners), (edge_names(scenario, shown),), (edge_names(scenario, shown ^ plaq.edge_mask),),
            (), 1.0, f"{what}. {how}", reachable,
        ),
        "rule",
        count,
    )
    failure.leak = leak
    return failure


def _reach(
    scenario: Scenario, robot: int, local: int, mask: int, flip: int | None, index: _PathIndex | None = None
) -> tuple[bool | None, int | None, int]:
    """Whether a feasible path of ``robot`` equals ``mask`` on the edges of ``local``.

    Args:
        flip: Edges the check flips (a path whose flip ``path ^ flip`` is infeasible is preferred); ``None``: any.
        index: The paths looked up (a new :class:`_PathIndex` if none).

    Returns:
        ``(reachable, path, paths looked at)``: ``reachable`` is ``False`` when none of the robot's paths does
        and there are at most :data:`REACH_PATHS`, ``None`` when more paths were not looked at; ``path`` is the
        first such path whose flip is not feasible, else the first such path, else ``None``.
    """
    index = _PathIndex(scenario) if index is None else index
    found, complete = index.containing(robot, local, mask)
    checked = len(index.paths(robot)[0])
    if not found:
        return (False if complete else None), None, checked
    if flip is not None:
        for path in found:
            if not is_feasible(scenario, robot, path ^ flip):
                return True, path, checked
    return True, found[0], checked


# ------------------------------------------------------------------------------------------- gates, per gadget kind
def _lowered(blocks: Sequence[Sequence[Gate]], work: int, beta: float) -> list[list[Gate]]:
    """Each block lowered as a section of its own (as the circuit lowers its gadgets), every symbol bound to
    ``beta``."""
    top = max((q + 1 for b in blocks for g in b for q in g.qubits), default=1)
    registers: list[tuple[str, int]] = [("q", top)] + ([(WORK_REGISTER, work)] if work else [])
    circuit = lower(Circuit(registers, [Section(f"b{i}", tuple(b)) for i, b in enumerate(blocks)]))
    circuit = circuit.bind({s: beta for s in circuit.symbols})
    return [list(sec.gates) for sec in circuit.sections]


def _compact(blocks: Sequence[Sequence[Gate]], data: Sequence[int]) -> tuple[list[list[Gate]], int]:
    """Renumber qubits: ``data`` to ``0..k-1`` in order, every other qubit after them. Returns the blocks and the
    number of qubits."""
    where = {q: i for i, q in enumerate(data)}
    for b in blocks:
        for g in b:
            for q in g.qubits:
                where.setdefault(q, len(where))
    if len(where) > MAX_QUBITS:
        raise ValueError(f"a gadget touches {len(where)} qubits; at most {MAX_QUBITS} can be simulated")
    return [[g._replace(qubits=tuple(where[q] for q in g.qubits)) for g in b] for b in blocks], len(where)


def _first_difference(got: Batch, want: Batch) -> int | None:
    """The first input whose outputs differ (beyond the tolerance), or ``None``."""

    def table(b: Batch) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        keep = np.abs(b.amps) > TOLERANCE
        o, k, a = b.owners[keep], b.keys[keep], b.amps[keep]
        order = np.lexsort((k, o))
        return o[order], k[order], a[order]

    go, gk, ga = table(got)
    wo, wk, wa = table(want)
    if len(go) == len(wo) and (go == wo).all() and (gk == wk).all():
        close = np.abs(ga - wa) <= TOLERANCE
        if close.all():
            return None
        return int(go[np.argmin(close)])
    owners = np.union1d(go, wo)
    for o in owners:  # the first input that differs
        a, b = got.of_input(int(o)), want.of_input(int(o))
        keys = {k for k, v in a.items() if abs(v) > TOLERANCE} | {k for k, v in b.items() if abs(v) > TOLERANCE}
        if any(abs(a.get(k, 0) - b.get(k, 0)) > TOLERANCE for k in keys):
            return int(o)
    return None  # pragma: no cover - the tables differ, so some input does


def _differing(got: Batch, want: Batch) -> list[int]:
    """Every input whose outputs differ (beyond the tolerance), in order."""
    owners = np.concatenate([got.owners, want.owners])
    keys = np.concatenate([got.keys, want.keys])
    amps = np.concatenate([got.amps, -want.amps])
    if not len(owners):
        return []
    order = np.lexsort((keys, owners))
    owners, keys, amps = owners[order], keys[order], amps[order]
    start = np.ones(len(keys), dtype=bool)
    start[1:] = (owners[1:] != owners[:-1]) | (keys[1:] != keys[:-1])
    idx = np.flatnonzero(start)
    summed = np.add.reduceat(amps, idx)  # got - want per (input, key)
    return [int(o) for o in np.unique(owners[idx][np.abs(summed) > TOLERANCE])]


def _closed_loop(key: int) -> bool:
    """Whether a local input (plaquette edges ``ab, bc, cd, da`` in bits 0..3) is a closed loop."""
    return key & 0b1111 == 0b1111


def _program_value(program: Any, pbits: Sequence[int], obits: Sequence[int]) -> bool:
    """An abstract SBF program (:class:`qcpp.gadgets.partial_mixer.AbstractProgram`) on local bits."""
    temps: dict[int, bool] = {}
    for target, lits in zip(program.targets, program.steps, strict=True):
        ok = True
        for tag, what, value in lits:
            if tag == "form":
                v = sum(pbits[i] for i in range(4) if (what >> i) & 1) % 2 == 1
            elif tag == "slot":
                v = bool(obits[what[1]])
            else:
                v = temps.get(what, False)
            if v != value:
                ok = False
                break
        if ok:
            temps[target] = not temps.get(target, False)
    return temps.get(program.targets[-1], False)


class _MixerChecker:
    """Checks partial-mixer kinds and junction kinds on their gates (see the module docstring)."""

    def __init__(
        self, scenario: Scenario, fused: bool, beta: float, where: dict[Any, tuple[int, Plaquette]],
        pictures: dict[Any, str], index: _PathIndex, places: dict[Any, list[tuple[int, Plaquette]]] | None = None,
    ) -> None:  # fmt: skip
        self.scenario, self.fused, self.beta, self.where, self.index = scenario, fused, beta, where, index
        self.pictures = dict(pictures)
        self.places = {} if places is None else places  # kind -> every (robot, plaquette) with a mixer of it

    def picture_of(self, kind: Any) -> str:
        """The local picture of a partial-mixer kind on this scenario (a number for a kind it does not have)."""
        if kind not in self.pictures:
            self.pictures[kind] = f"kind {len(self.pictures) + 1}"
        return self.pictures[kind]

    def label(self, gadget: Any) -> str:
        """A short name for reports (:func:`~qcpp.verification.common.gadget_label`)."""
        return gadget_label(gadget, self.picture_of)

    @staticmethod
    def data(m: Mixer) -> tuple[int, ...]:
        return (*m.plaquette_qubits, *m.outer_qubits)

    def opening(self, m: Mixer) -> list[Gate]:
        return MixerJunction(None, m).emit()  # type: ignore[arg-type]

    def edges(self, m: Mixer, place: tuple[int, Plaquette] | None = None) -> tuple[int | None, Plaquette | None,
                                                                                   list[int]]:  # fmt: skip
        """A robot and plaquette of the scenario with a partial mixer of ``m``'s kind (``place``, else the first)
        and the grid edges of its data qubits (slot order: plaquette, outer); ``(None, None, [])`` when the
        scenario has none."""
        robot, plaq = place or self.where.get(m.kind, (None, None))
        if plaq is None or robot is None:
            return None, None, []
        return robot, plaq, list(plaq.edges) + _outer_slots(self.scenario, robot, plaq, m)

    def reachable(self, m: Mixer, key: int) -> tuple[bool | None, tuple[int, Plaquette] | None]:
        """Whether a feasible path contains local input ``key`` at some place of ``m``'s kind, and that place.

        ``False`` only when every place's robot has at most :data:`REACH_PATHS` paths and none does; ``None``
        when that was not decided (a robot with more paths is looked at only at the kind's first place)."""
        places = self.places.get(m.kind) or ([self.where[m.kind]] if m.kind in self.where else [])
        decided: bool | None = bool(places)
        for place in places:
            robot, _, edges = self.edges(m, place)
            assert robot is not None
            complete = self.index.paths(robot)[1]
            if not complete and place is not places[0]:
                return None, None
            mask = sum(1 << e for i, e in enumerate(edges) if (key >> i) & 1)
            if self.index.containing(robot, sum(1 << e for e in edges), mask)[0]:
                return True, place
            if not complete:
                return None, None
        return (False if decided else None), None

    def fail(self, subject: str, m: Mixer | None, kind: str, key_in: int, key_out: int, data: Sequence[int],
             amp: float, reason: str, reachable: bool | None = None,
             place: tuple[int, Plaquette] | None = None) -> _Failure:  # fmt: skip
        """A counterexample on local inputs, named on ``place`` (else the scenario's first plaquette of that kind,
        if it has one); the inputs run in the order ``0, 1, ...`` (closed loops left out), so those up to
        ``key_in`` were checked."""
        robot, plaq, edges = self.edges(m, place) if m is not None else (None, None, [])
        ins = outs = ((),)
        if edges:  # local bits -> the scenario's edges
            ins = (edge_names(self.scenario, sum(1 << e for i, e in enumerate(edges) if (key_in >> i) & 1)),)
            outs = (edge_names(self.scenario, sum(1 << e for i, e in enumerate(edges) if (key_out >> i) & 1)),)
        dirty = tuple(i for i in range(len(data), 64) if (key_out >> i) & 1)
        cx = Counterexample("gadgets", subject, kind, robot, None if plaq is None else tuple(plaq.corners), ins, outs,
                            dirty, amp, reason, reachable)  # fmt: skip
        return _Failure(cx, "mixer", key_in + 1 - (key_in + 1) // 16)

    def classify(self, subject: str, m: Mixer, kind: str, got: Batch, bad: Sequence[int], data: Sequence[int],
                 what: str) -> tuple[int, _Failure | None]:  # fmt: skip
        """Inputs ``bad`` (in order), where ``got`` is wrong, against the scenario's feasible paths
        (:meth:`reachable`): one that a feasible path contains raises a counterexample; one that none contains
        (decided) is harmless; the others are unresolved.

        Returns:
            ``(unresolved inputs, the first one's failure or None)``.

        Raises:
            _Failure: the counterexample.
        """
        first, count = None, 0
        for key in bad:
            reachable, place = self.reachable(m, key)
            if reachable is False:
                continue
            count += 1
            if reachable or first is None:
                out = got.of_input(key)
                key_out = max((k for k in out if k != key), key=lambda k: abs(out[k]), default=key)
                if reachable:
                    how = "A feasible path contains this input on the plaquette shown."
                else:
                    how = ("Unresolved: whether a feasible path contains this input was not decided (a robot has "
                           f"more than {REACH_PATHS:,} paths). {ALL_LOCAL_INPUTS}")  # fmt: skip
                failure = self.fail(subject, m, kind, key, key_out, data, abs(out.get(key_out, 0)), f"{what}. {how}",
                                    reachable, place)  # fmt: skip
                if reachable:
                    raise failure
                first = first or failure
        return count, first

    def partial_mixer(self, m: Mixer, work: int) -> tuple[int, int, _Failure | None]:
        """Check one partial-mixer kind on every local input but closed loops (see the module docstring).

        Returns:
            ``(inputs checked, unresolved inputs, the first unresolved one's failure or None)``.

        Raises:
            _Failure: a counterexample (the gates wrong on an input a feasible path contains).
        """
        data = self.data(m)
        if self.fused:
            assert isinstance(m, ParityPartialMixer)
            blocks = [self.opening(m), MixerRotation(m).emit(), MixerJunction(m, None).emit()]
        else:
            blocks = m.emit_blocks()
        lowered, _ = _compact(_lowered(blocks, work, self.beta), data)
        k = len(data)
        inputs = Batch.of_inputs(np.arange(1 << k, dtype=np.int64))
        got = inputs.run(g for b in lowered for g in b)
        program = m.kind[1]  # type: ignore[index]
        c, s = math.cos(self.beta / 2), -1j * math.sin(self.beta / 2)
        owners, keys, amps = [], [], []
        for d in range(1 << k):
            bits = [(d >> i) & 1 for i in range(k)]
            if _program_value(program, bits[:4], bits[4:]):
                owners += [d, d]
                keys += [d, d ^ 0b1111]
                amps += [c, s]
            else:
                owners.append(d)
                keys.append(d)
                amps.append(1.0)
        want = Batch(np.array(owners, dtype=np.int64), np.array(keys, dtype=np.int64), np.array(amps, dtype=complex))
        bad = [d for d in _differing(got, want) if not _closed_loop(d)]
        subject = self.label(m)
        checked = (1 << k) - (1 << (k - 4))
        if bad:
            allowed = _program_value(program, [(bad[0] >> i) & 1 for i in range(4)],
                                     [(bad[0] >> i) & 1 for i in range(4, k)])  # fmt: skip
            expected = "cos(b/2)|x> - i sin(b/2)|x xor plaquette>" if allowed else "|x> (the flip is forbidden here)"
            what = f"the gadget does not do what its program says: expected {expected} with clean ancillas"
            count, failure = self.classify(subject, m, self.label(m), got, bad, data, what)
            if failure is not None:
                return checked, count, failure
        if self.fused:  # the closing junction alone cleans what the opening one made
            opened = inputs.run(g for g in lowered[0])
            closed = opened.run(lowered[2])
            bad = [d for d in _differing(closed, inputs) if not _closed_loop(d)]
            if bad:
                count, failure = self.classify(subject, m, self.label(MixerJunction(m, None)), closed, bad, data,
                                               "the closing junction does not undo the opening one")  # fmt: skip
                if failure is not None:
                    return checked, count, failure
        return checked, 0, None

    def junction(self, j: MixerJunction, work: int) -> int:
        """Check ``J(l, r)``: from the state ``l``'s opening makes, the one ``r``'s opening makes, on every input of
        both partial mixers' data qubits; returns the number of inputs."""
        left, right = j.left, j.right
        assert left is not None and right is not None
        data = list(dict.fromkeys((*self.data(left), *self.data(right))))
        blocks = [self.opening(left), j.emit(), self.opening(right)]
        lowered, _ = _compact(_lowered(blocks, work, self.beta), data)
        inputs = Batch.of_inputs(np.arange(1 << len(data), dtype=np.int64))
        got = inputs.run(lowered[0]).run(lowered[1])
        want = inputs.run(lowered[2])
        bad = _first_difference(got, want)
        if bad is not None:
            out = got.of_input(bad)
            key_out = max(out, key=lambda key: abs(out[key]))
            raise self.fail(self.label(j), left, self.label(j), bad, key_out, data, abs(out[key_out]),
                            "the junction does not turn one partial mixer's computed state into the next one's")
        return 1 << len(data)


def _outer_slots(scenario: Scenario, robot: int, plaq: Plaquette, m: Mixer) -> list[int]:
    """The grid edges of a partial mixer's outer slots on the scenario's ``plaq`` (the edges of the qubits of the
    scenario's own partial mixer of that kind, which has the same slots)."""
    own = partial_mixer(scenario, robot, plaq, 0.0, scenario.num_variables, m.kind[1].rule)  # type: ignore[index]
    assert own is not None
    return [scenario.variable_of(q)[1] for q in own.outer_qubits]


# ------------------------------------------------------------------------------------------------------ phase kinds
def _cancelling_skeleton(gates: Sequence[Gate]) -> str | None:
    """``None`` if every gate is diagonal or a permutation and the permutations cancel in pairs; else why not."""
    stack: list[Gate] = []
    for g in gates:
        spec = GATE_SPECS[g.name]
        if spec.diagonal:
            continue
        if not spec.permutation:
            return f"{g.name} on {g.qubits} is neither diagonal nor a permutation"
        if stack and stack[-1] == g.inverse():
            stack.pop()
        else:
            stack.append(g)
    if not stack:
        return None
    return f"{len(stack)} permutation gates do not cancel (first: {stack[0].name} on {stack[0].qubits})"


def _check_phase(kind: GadgetKind, beta: float) -> tuple[str, int, str]:
    """Check one phase kind: ``(how, inputs, detail)``; raises :class:`_Failure`."""
    g = kind.example.build() if isinstance(kind.example, Deferred) else kind.example
    gates = list(g.emit())
    why = _cancelling_skeleton(gates)
    if why is not None:
        raise _Failure(Counterexample("gadgets", f"phase {kind_text(g)}", kind_text(g), None, None, ((),), ((),), (),
                                      0.0, f"not shown diagonal: {why}"), "phase")  # fmt: skip
    ancillas = {q for gt in gates if gt.name in ("and", "and_dg") for q in gt.qubits[-1:]}
    data = sorted({q for gt in gates for q in gt.qubits} - ancillas)
    if len(data) > EXHAUSTIVE_PHASE_QUBITS:
        return "structural", 0, "diagonal and permutation gates; the permutations cancel in pairs"
    lowered, _ = _compact(_lowered([gates], kind.work, beta), data)
    inputs = Batch.of_inputs(np.arange(1 << len(data), dtype=np.int64))
    got = inputs.run(lowered[0])
    keep = np.abs(got.amps) > TOLERANCE
    moved = keep & (got.keys != got.owners)
    if moved.any():
        i = int(np.flatnonzero(moved)[0])
        dirty = tuple(q for q in range(len(data), 64) if (int(got.keys[i]) >> q) & 1)
        reason = "the lowered phase gadget moves a basis state"
        cx = Counterexample("gadgets", f"phase {kind_text(g)}", kind_text(g), None, None, ((),), ((),), dirty,
                            float(abs(got.amps[i])), reason)  # fmt: skip
        raise _Failure(cx, "phase", int(got.owners[i]) + 1)
    return "exhaustive", 1 << len(data), "also structural: diagonal and permutation gates that cancel in pairs"


# ---------------------------------------------------------------------------------------------------- initial state
def _check_initial(scenario: Scenario, kind: GadgetKind, num_qubits: int, registers: tuple) -> int:
    g = kind.example.build() if isinstance(kind.example, Deferred) else kind.example
    gates = list(g.emit())
    test = FeasibleTest(scenario)
    if all(GATE_SPECS[gt.name].permutation for gt in gates):
        key = 0
        for gt in gates:
            controls, state, target = gt.qubits[:-1], gt[3] or "1" * (len(gt.qubits) - 1), gt.qubits[-1]
            if all(((key >> c) & 1) == int(b) for c, b in zip(controls, state, strict=True)):
                key ^= 1 << target
        outs = [key]
    else:
        if num_qubits > MAX_QUBITS:
            raise ValueError(f"the state preparation is not classical and the circuit has {num_qubits} qubits: "
                             "check it with --method state on a smaller scenario")  # fmt: skip
        low = lower(Circuit(registers, [Section("initial_state", tuple(gates))]))
        out = Batch.of_inputs([0]).run(low.gates)
        outs = [int(k) for k, a in zip(out.keys, out.amps) if abs(a) > TOLERANCE]
    for key in outs:
        masks = test.masks(key)
        bad = [r for r, m in enumerate(masks) if not is_feasible(scenario, r, m)]
        if bad or key >> scenario.num_variables:
            raise _Failure(Counterexample(
                "gadgets", "initial_state", kind_text(g), bad[0] if bad else None, None, ((),),
                tuple(edge_names(scenario, m) for m in masks), test.dirty(key), 1.0,
                f"robot {bad[0]} does not start on a feasible path" if bad else "an ancilla is left in |1>",
            ), "initial_state", 1)  # fmt: skip
    return 1


# ------------------------------------------------------------------------------------------------------------ verify
def _mixers_in(g: Any) -> list[Any]:
    """The partial mixers a mixer-part gadget is made of (a junction's sides, a rotation's mixer, or itself)."""
    if isinstance(g, MixerJunction):
        return [m for m in (g.left, g.right) if m is not None]
    if isinstance(g, MixerRotation):
        return [g.mixer]
    return [g]


def verify_gadgets(
    scenario: Scenario,
    p: int,
    rule: Rule = "exact",
    *,
    seed: int = 0,
    progress: ProgressFn | None = None,
    options: PlanOptions | None = None,
) -> VerifyReport:
    """Certify feasibility preservation kind by kind (see the module docstring).

    Args:
        p: QAOA layers (>= 1; every layer has the same kinds).
        rule: The SBF rule to compile with.
        seed: Seed of the rotation angle the mixer kinds are checked at.
        options: How the circuit is built (:class:`~qcpp.plan.options.PlanOptions`; its rule replaces ``rule``).
        progress: Called as ``progress(done, total)`` over the checks.

    Returns:
        The :class:`~qcpp.verification.report.VerifyReport` (method ``gadgets``); every check is exhaustive on its
        local inputs or structural, so when it holds it holds for every feasible input. Its ``outcome`` is
        ``not_certified`` (``unresolved`` set, no counterexample) when checks failed only on local inputs that no
        feasible path was shown to contain.
    """
    start = time.perf_counter()
    plan = verified_plan(scenario, p, rule, options)
    options, rule = plan.options, plan.options.rule
    graph = plan.call_graph()
    beta = random_angle(random.Random(seed))
    index = _PathIndex(scenario)
    survey = _survey(scenario, rule, options.target)
    mixer_kinds = graph.parts["mixer"]
    fused = any(isinstance(k.example, MixerJunction | MixerRotation) for k in mixer_kinds)
    mixers = _partial_mixer_kinds(mixer_kinds)
    work_items = len(survey.pictures) + len(mixers) + len(mixer_kinds) + len(graph.parts["phase"]) + 1
    tally = _Tally(work_items, progress)
    checker = _MixerChecker(scenario, fused, beta, dict(survey.scenario_kinds), survey.kind_pictures, index,
                            survey.kind_places)  # fmt: skip
    counterexample = None
    try:
        _check_rules(scenario, rule, survey, index, tally)
        _check_partial_mixers(checker, mixers, fused, tally)
        _check_coverage(survey.scenario_kinds, mixers)
        _check_mixer_part(checker, mixer_kinds, mixers, tally)
        for kind, mult in graph.parts["phase"].items():
            how, n, detail = _check_phase(kind, beta)
            tally.held(Check(kind_text(kind.example), "phase", how, n, True, mult, detail))
        for kind, mult in graph.parts["initial_state"].items():
            n = _check_initial(scenario, kind, plan.num_qubits, plan.registers)
            tally.held(Check(kind_text(kind.example), "initial_state", "exhaustive", n, True, mult, "from |0...0>"),
                       tick=False)  # fmt: skip
        tally.tick()
    except _Failure as failure:
        counterexample = failure.counterexample
        how = "structural" if failure.part == "phase" and not failure.inputs else "exhaustive"
        tally.checks.append(Check(counterexample.check, failure.part, how, failure.inputs, False, 1,
                                  "stopped at the first failing input" if failure.inputs else ""))  # fmt: skip
    return VerifyReport(
        _scenario_name(scenario), p, rule, "gadgets", counterexample is None and tally.unresolved is None,
        tuple(tally.checks), counterexample, time.perf_counter() - start, seed, options.target, tally.unresolved,
    )  # fmt: skip


@dataclasses.dataclass(frozen=True)
class _Survey:
    """What the scenario's plaquettes hold, read once before the checks.

    Attributes:
        pictures: Per local picture, its first place (robot, plaquette), rule program and outer edges.
        places: Per local picture, every (robot, plaquette) with it, the first one first.
        scenario_kinds: Per partial-mixer kind of the scenario, the first place it stands.
        kind_places: Per partial-mixer kind, every place of the pictures whose first place has that kind.
        kind_pictures: Per partial-mixer kind, the label of its first place's picture.
    """

    pictures: dict[LocalPicture, tuple[int, Plaquette, SbfLogic, tuple[tuple[int, ...], ...]]]
    places: dict[LocalPicture, list[tuple[int, Plaquette]]]
    scenario_kinds: dict[Any, tuple[int, Plaquette]]
    kind_places: dict[Any, list[tuple[int, Plaquette]]]
    kind_pictures: dict[Any, str]


def _survey(scenario: Scenario, rule: Rule, target: str) -> _Survey:
    """The scenario's local pictures (what the rule checks run on) and the partial-mixer kind of each picture's
    first place (what the coverage check holds the call graph's kinds to), robots and plaquettes in order;
    plaquettes whose rule never allows a flip are left out."""
    pictures: dict[LocalPicture, tuple[int, Plaquette, SbfLogic, tuple[tuple[int, ...], ...]]] = {}
    places: dict[LocalPicture, list[tuple[int, Plaquette]]] = {}  # every (robot, plaquette) with that picture
    picture_kinds: dict[LocalPicture, Any] = {}
    scenario_kinds: dict[Any, tuple[int, Plaquette]] = {}
    beta_sym = Angle.symbol("beta")
    for r in range(scenario.num_robots):
        for q in scenario.grid.plaquettes:
            logic = sbf_logic(scenario, r, q, rule)
            if logic.never:
                continue
            picture, outer = plaquette_picture(scenario, r, q)
            places.setdefault(picture, []).append((r, q))
            if picture not in pictures:
                pictures[picture] = (r, q, logic, outer)
                m = partial_mixer(scenario, r, q, beta_sym, scenario.num_variables, rule, target)
                if m is not None:
                    scenario_kinds.setdefault(m.kind, (r, q))
                    picture_kinds[picture] = m.kind
    kind_places: dict[Any, list[tuple[int, Plaquette]]] = {}
    for picture, kd in picture_kinds.items():
        kind_places.setdefault(kd, []).extend(places[picture])
    kind_pictures = {kd: plaquette_picture(scenario, r, q)[0].label for kd, (r, q) in scenario_kinds.items()}
    return _Survey(pictures, places, scenario_kinds, kind_places, kind_pictures)


def _partial_mixer_kinds(mixer_kinds: Mapping[GadgetKind, int]) -> dict[Any, tuple[Mixer, int]]:
    """Every partial-mixer kind the mixer part is made of (inside junctions and rotations too), first seen
    first: one partial mixer of the kind and its work qubits."""
    mixers: dict[Any, tuple[Mixer, int]] = {}
    for kind in mixer_kinds:
        for m in _mixers_in(kind.example):
            if m is not None and m.kind not in mixers:
                mixers[m.kind] = (m, GadgetKind.of(m).work)
    return mixers


class _Tally:
    """The checks of one :func:`verify_gadgets` run so far, the first unresolved input, and the progress: the
    run's one mutable value, so the checks that held before a failure stay in its report."""

    def __init__(self, total: int, progress: ProgressFn | None) -> None:
        """No checks yet, ``total`` work items to report to ``progress`` (if any)."""
        self.checks: list[Check] = []
        self.unresolved: Counterexample | None = None
        self.done, self.total, self.progress = 0, total, progress

    def tick(self) -> None:
        """One work item done: report ``progress(done, total)``."""
        self.done += 1
        if self.progress is not None:
            self.progress(self.done, self.total)

    def held(self, check: Check, *, tick: bool = True) -> None:
        """Record a check (and, with ``tick``, its work item done)."""
        self.checks.append(check)
        if tick:
            self.tick()

    def open(self, subject: str, part: str, n: int, mult: int, count: int, failure: _Failure) -> None:
        """Record a check that failed on ``count`` inputs none of which is shown harmless or leaking (its first
        such input becomes the run's unresolved one unless one came earlier), and its work item done."""
        self.unresolved = self.unresolved or failure.counterexample
        self.held(Check(subject, part, "exhaustive", n, False, mult,
                        f"{count} input{'s' if count > 1 else ''} unresolved: neither shown harmless nor on a leaking "
                        "feasible path", True))  # fmt: skip


def _check_rules(scenario: Scenario, rule: Rule, survey: _Survey, index: _PathIndex, tally: _Tally) -> None:
    """The rule check of every local picture (:func:`_check_rule`), its failing inputs looked up at every place
    with the picture.

    Raises:
        _Failure: a counterexample.
    """
    for picture, (r, q, logic, outer) in survey.pictures.items():
        subject = f"rule {rule} {picture.label}"
        places = survey.places[picture]
        n, count, failure = _check_rule(scenario, r, q, logic, picture, outer, index, places[1:])
        if failure is not None:
            tally.open(subject, "rule", n, len(places), count, failure)
        else:
            tally.held(Check(subject, "rule", "exhaustive", n, True, len(places),
                             "locally feasible inputs but closed loops"))  # fmt: skip


def _check_partial_mixers(
    checker: _MixerChecker, mixers: Mapping[Any, tuple[Mixer, int]], fused: bool, tally: _Tally
) -> None:
    """The gate check of every partial-mixer kind on all its inputs (:meth:`_MixerChecker.partial_mixer`).

    Raises:
        _Failure: a counterexample.
    """
    for m, work in mixers.values():
        n, count, failure = checker.partial_mixer(m, work)
        if failure is not None:
            tally.open(checker.label(m), "mixer", n, 1, count, failure)
        else:
            blocks = "opening junction, rotation, closing junction" if fused else "all blocks"
            tally.held(Check(checker.label(m), "mixer", "exhaustive", n, True, 1, blocks))


def _check_coverage(scenario_kinds: Mapping[Any, tuple[int, Plaquette]], mixers: Mapping[Any, Any]) -> None:
    """Every partial-mixer kind of the scenario is among the checked ones.

    Raises:
        _Failure: the first kind that is not, at its first place.
    """
    missing = [kd for kd in scenario_kinds if kd not in mixers]
    if missing:
        r, q = scenario_kinds[missing[0]]
        raise _Failure(Counterexample("gadgets", "coverage", repr(missing[0])[:100], r, tuple(q.corners), ((),),
                                      ((),), (), 0.0, "a partial mixer of the scenario is of no checked kind"))


def _check_mixer_part(
    checker: _MixerChecker, mixer_kinds: Mapping[GadgetKind, int], mixers: Mapping[Any, tuple[Mixer, int]],
    tally: _Tally,
) -> None:  # fmt: skip
    """Every kind of the mixer part: a junction between two partial mixers checked on all inputs
    (:meth:`_MixerChecker.junction`), any other kind covered by its partial mixers' checks.

    Raises:
        _Failure: a counterexample.
    """
    for kind, mult in mixer_kinds.items():
        g = kind.example
        if isinstance(g, MixerJunction) and g.left is not None and g.right is not None:
            n = checker.junction(g, max(kind.work, mixers[g.left.kind][1], mixers[g.right.kind][1]))
            tally.held(Check(checker.label(g), "mixer", "exhaustive", n, True, mult))
        else:
            rotation = isinstance(g, MixerRotation)
            inner = "each partial mixer's check" if rotation else checker.label(_mixers_in(g)[0])
            tally.held(Check(checker.label(g), "mixer", "covered", 0, True, mult, f"within {inner}"))
