"""Partial mixers as gadgets: one robot, one plaquette, ``exp(-i beta/2 XXXX)`` where the SBF rule allows it.

Two constructions, both compiled from the rule's own :class:`~qcpp.problem.sbf.SbfLogic` program (the classical
move test, the solvers and the subspace simulator run the very same program; the compiler never re-derives the
rule):

**Parity basis** (:class:`ParityPartialMixer`, the ``exact`` rule). A CNOT network ``L`` on the four plaquette
qubits maps ``XXXX`` to ``X`` on one *carrier* qubit: after ``L`` the carrier holds an odd combination of the
four edges and the other three hold even ones (corner parities ``s_v = e1 XOR e2`` or the opposite-edge parities
``ab XOR cd``, ``bc XOR da``), which the flip leaves unchanged. The exact rule's program reads only such parities,
outer edges and temporaries, so the move condition ``f`` is computed once with clean relative-phase ANDs
(:func:`qcpp.ir.gates.and_`), ``RX(beta)`` is applied to the carrier controlled by ``f`` (``crx``, or for
``target="nisq"`` the last AND merged into a two-control phase polynomial ``ccrx``), and everything is mirrored.
:func:`plan_parity_mixer` searches (A* over GF(2) states) for the fewest CNOTs of ``L`` that bring every parity
onto some qubit when it is read; X gates are placed only right before a read that needs them, so no two gates of
the result cancel and the cost is a plain sum of leaf costs.

**Controlled-X network** (:class:`McxPartialMixer`, the ``paper`` rule, kept for the comparison with the
paper). Each program step is a multi-controlled X (``x``/``cx``/``ccx``/clean-AND ladder) into a ``logic``
temporary, then ``csbf`` (``XXXX`` rotation controlled by the output; 8 CX), then the mirror.

The cost of both is computed from the plan (a short list of leaf kinds), cached per *kind* (the program with
grid edges replaced by local positions), never from emitted gates. In a circuit, consecutive parity-basis
partial mixers are fused at their boundaries (:mod:`qcpp.gadgets.junction`).

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> m = partial_mixer(s, 0, s.grid.plaquettes[0], 0.7, logic_offset=s.num_variables)
    >>> m.cost().cx, [g.name for g in m.emit()][:4]
    (32, ['cx', 'cx', 'cx', 'x'])
"""

from __future__ import annotations

import heapq
from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import NamedTuple

from qcpp.gadgets.leaves import ccrx_gates, leaf_cost, leaf_logical_cost
from qcpp.ir.angles import Param
from qcpp.ir.cost import Cost, Target
from qcpp.ir.gates import Gate, and_, and_dg, crx, csbf, cx, mcx, x
from qcpp.problem.grid import Plaquette
from qcpp.problem.sbf import Lit, Rule, SbfLogic, sbf_logic
from qcpp.problem.scenario import Scenario

__all__ = [
    "MOVES",
    "McxMixerKind",
    "McxPartialMixer",
    "MixerPlan",
    "ParityMixerKind",
    "ParityPartialMixer",
    "ParitySearch",
    "emit_plan",
    "logic_width",
    "parity_search",
    "partial_mixer",
    "plan_parity_mixer",
    "plan_slots",
]

# --- abstract programs ------------------------------------------------------------------------
# A slot names a qubit of the gadget: ("p", i) plaquette edge i of (ab, bc, cd, da); ("o", j) the j-th outer edge
# the program reads; ("t", k) logic temporary k.
Slot = tuple[str, int]
# An abstract literal: ("form", mask, value) a parity of plaquette edges (mask over positions 0..3);
# ("slot", slot, value) a fixed qubit (outer edge) ; ("temp", step, value) the output of an earlier step.
ALit = tuple[str, int | Slot, bool]


@dataclass(frozen=True)
class AbstractProgram:
    """An SBF program with grid edges replaced by local positions (what the cost depends on).

    Attributes:
        rule: ``exact`` or ``paper``.
        targets: per step, the temporary it XORs into; the last step writes the output.
        steps: per step, its abstract literals (``("temp", k, value)`` reads temporary ``k``).
        num_outer: outer edges read.
    """

    rule: Rule
    targets: tuple[int, ...]
    steps: tuple[tuple[ALit, ...], ...]
    num_outer: int


def abstract_program(logic: SbfLogic, plaquette: Plaquette) -> tuple[AbstractProgram, tuple[int, ...]]:
    """The program's kind and the grid edges of its outer slots (in slot order)."""
    pos = {e: i for i, e in enumerate(plaquette.edges)}
    outer: list[int] = []
    steps = tuple(tuple(_abstract_lit(lit, pos, outer) for lit in st.literals) for st in logic.steps)
    if logic.steps[-1].target != logic.output:
        raise ValueError("the last step of an SBF program must write its output")
    targets = tuple(st.target for st in logic.steps)
    return AbstractProgram(logic.rule, targets, steps, len(outer)), tuple(outer)


def _abstract_lit(lit: Lit, pos: dict[int, int], outer: list[int]) -> ALit:
    if lit.is_temp:
        return ("temp", lit.temp, lit.value)
    if all(e in pos for e in lit.edges):
        mask = 0
        for e in lit.edges:
            mask ^= 1 << pos[e]
        return ("form", mask, lit.value)  # a plaquette edge or the parity of two
    if lit.xor is not None:
        raise ValueError(f"parity literal {lit} mixes plaquette and outer edges")
    if lit.signal not in outer:
        outer.append(lit.signal)
    return ("slot", ("o", outer.index(lit.signal)), lit.value)


# --- the parity-basis plan ---------------------------------------------------------------------
@dataclass(frozen=True)
class MixerPlan:
    """A partial mixer as abstract leaves on slots (see the module docstring).

    Attributes:
        compute: ``(leaf, slots)`` in time order: ``("cx", (c, t))``, ``("x", (q,))``, ``("and", (a, b, t))``,
            ``("mcx", controls + (t,))``.
        rotation: ``("crx", (control, carrier))``, ``("ccrx", (a, b, carrier))`` or ``("csbf", (control, p0..p3))``.
        num_temps: logic temporaries used.
    """

    compute: tuple[tuple[str, tuple[Slot, ...]], ...]
    rotation: tuple[str, tuple[Slot, ...]]
    num_temps: int

    def _sum(self, leaf: Callable[[str, int], Cost]) -> Cost:
        """Compute leaves, their mirrors (an AND is undone by ``and_dg``, everything else by itself) and the
        rotation, priced by ``leaf`` (:func:`leaf_cost` or :func:`leaf_logical_cost`)."""
        total = leaf(self.rotation[0], 0)
        for name, slots in self.compute:
            k = len(slots) - 1 if name == "mcx" else 0
            total += leaf(name, k) + leaf("and_dg" if name == "and" else name, k)
        return total

    def cost(self) -> Cost:
        """Lowered cost: the compute leaves, their mirrors and the rotation."""
        return self._sum(leaf_cost)

    def logical_cost(self) -> Cost:
        """The same with ANDs and Toffolis kept whole."""
        return self._sum(leaf_logical_cost)


def _carrier(forms: tuple[int, ...]) -> int | None:
    """The one qubit holding an odd form when the other three hold even ones (then XXXX = X on it)."""
    odd = [i for i, f in enumerate(forms) if bin(f).count("1") % 2]
    return odd[0] if len(odd) == 1 else None


MOVES: tuple[tuple[int, int], ...] = tuple((c, t) for c in range(4) for t in range(4) if c != t)
"""The A*'s CNOTs ``(control, target)`` on the plaquette positions, in the order :func:`plan_parity_mixer` tries
them from each state (the first of equally cheap plans it meets depends on this order)."""


_G_SHIFT, _G_MASK = 32, (1 << 16) - 1  # an A* heap entry's fields: push number, g, f (ParitySearch.plan)
_N_MASK, _F_SHIFT = (1 << _G_SHIFT) - 1, 48

PARITY_SEARCHES_KEPT = 64
"""Programs whose :class:`ParitySearch` (with every state it expanded) :func:`parity_search` keeps."""


class ParitySearch:
    """The A* of :func:`plan_parity_mixer` for one program, runnable with any order of the CNOTs tried from each
    state (:meth:`plan`); each state's expansion (the greedy ANDs after each CNOT, the bound, the goal test) is
    computed once and shared by every run, and the cheapest plan's length, once found, keeps later runs from pushing
    states that cannot lie on such a plan (:meth:`plan`), so the runs of one program under several orders cost
    little more than one.

    Running it with the order of :data:`MOVES` relabelled is the A* of the program with its plaquette positions
    relabelled, plan mapped back: the search graphs are isomorphic (the ANDs and reads follow the inner steps' and
    output literals' order, which a relabelling keeps) and the heap breaks ties by push order, so both searches
    pop the same states in the same order (:func:`qcpp.pipeline.cellmixer.relabelled_plans` relies on it;
    ``tests/compiler/cellmixer_test.py`` compares the two).

    Args:
        program: As :func:`plan_parity_mixer`'s.
        target: ``nisq`` or ``ft``.

    Raises:
        ValueError: a program the parity basis cannot plan (as :func:`plan_parity_mixer`).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> s = default_scenario(2, 3, 1)
        >>> program, _ = abstract_program(sbf_logic(s, 0, s.grid.plaquettes[0], "exact"), s.grid.plaquettes[0])
        >>> search = ParitySearch(program, "nisq")
        >>> search.plan() == plan_parity_mixer(program, "nisq")
        True
        >>> search.plan(MOVES[::-1]).cost() == search.plan().cost()
        True
    """

    def __init__(self, program: AbstractProgram, target: Target = "nisq") -> None:
        inner, final = program.steps[:-1], program.steps[-1]
        if any(len(lits) != 2 for lits in inner) or program.targets != tuple(range(len(program.steps))):
            raise ValueError("parity-basis mixers need two-literal inner steps, each into a fresh temporary")
        if any(kind == "form" and bin(ref).count("1") % 2 for lits in program.steps for kind, ref, _ in lits):  # type: ignore[arg-type]
            raise ValueError("parity-basis mixers read only even parities (the flip must not change them)")
        self.program = program
        self.target = target
        self._final = final
        temp_lits = [j for j, lit in enumerate(final) if lit[0] != "form"]
        if target == "nisq" and temp_lits:
            self._reserved = {temp_lits[-1]}
        elif target == "nisq" and len(final) <= 2:
            self._reserved = set(range(len(final)))  # corner literals only: they control the rotation directly
        else:
            self._reserved = set()
        self._all_inner = (1 << len(inner)) - 1
        # a literal as the masks it needs: parities (bit f: parity f on some qubit) and temporaries (bit i: inner
        # step i done); an outer slot needs neither. A state's parities as such a mask decide every test below.
        self._inner_need = [self._need(lits) for lits in inner]
        self._final_need = [self._need((lit,)) for lit in final]
        self._open_final = [j for j in range(len(final)) if j not in self._reserved]
        self._ids: dict[tuple, int] = {}  # a state's number: the search runs on numbers (hashed faster)
        self._states: list[tuple] = []
        self._expanded: list[tuple[bool, list[tuple[int, tuple, int]]] | None] = []
        self._closures: dict[tuple[int, int, int], tuple[int, int, tuple]] = {}
        self._needs: dict[tuple[int, int], int] = {}
        self._cheapest: int | None = None  # a cheapest plan's CNOTs, once a run has found one

    @staticmethod
    def _need(lits: Sequence[ALit]) -> tuple[int, int]:
        """``(parities, temporaries)`` masks the literals ``lits`` need present."""
        forms = temps = 0
        for kind, ref, _ in lits:
            if kind == "form":
                forms |= 1 << ref  # type: ignore[operator]
            elif kind == "temp":
                temps |= 1 << ref  # type: ignore[operator]
        return forms, temps

    def _id(self, state: tuple) -> int:
        """The number of ``state`` (numbered when first met)."""
        i = self._ids.get(state)
        if i is None:
            i = self._ids[state] = len(self._states)
            self._states.append(state)
            self._expanded.append(None)
        return i

    def _closure(self, present: int, done: int, absorbed: int) -> tuple[int, int, tuple]:
        """Greedy ANDs: inner steps whose literals are present, then output literals into the chain (``present``:
        the mask of parities held, bit ``f`` for parity ``f``; kept per ``(present, done, absorbed)``)."""
        key = (present, done, absorbed)
        hit = self._closures.get(key)
        if hit is not None:
            return hit
        inner_need, final_need, open_final = self._inner_need, self._final_need, self._open_final
        events: list[tuple[str, tuple[int, ...]]] = []
        while True:
            progressed = False
            for i, (forms, temps) in enumerate(inner_need):
                if not done >> i & 1 and present & forms == forms and done & temps == temps:
                    done |= 1 << i
                    events.append(("inner", (i,)))
                    progressed = True
            ready = []
            for j in open_final:
                forms, temps = final_need[j]
                if not absorbed >> j & 1 and present & forms == forms and done & temps == temps:
                    ready.append(j)
            if ready and (absorbed or len(ready) >= 2):
                if not absorbed:
                    events.append(("absorb", (ready[0], ready[1])))
                    absorbed |= 1 << ready[0] | 1 << ready[1]
                    ready = ready[2:]
                for j in ready:
                    events.append(("absorb", (j,)))
                    absorbed |= 1 << j
                progressed = True
            if not progressed:
                break
        hit = self._closures[key] = (done, absorbed, tuple(events))
        return hit

    def _missing(self, present: int, done: int, absorbed: int) -> int:
        """Admissible A* bound: each CNOT changes one qubit, so it brings at most one absent parity."""
        need = self._needs.get((done, absorbed))
        if need is None:
            need = 0
            for i, (forms, _) in enumerate(self._inner_need):
                if not done >> i & 1:
                    need |= forms
            for j, (forms, _) in enumerate(self._final_need):
                if not absorbed >> j & 1:
                    need |= forms
            self._needs[done, absorbed] = need
        return (need & ~present).bit_count()

    def _expand(self, sid: int) -> tuple[bool, list[tuple[int, tuple, int]]]:
        """Whether state number ``sid`` is a goal, and per CNOT ``c * 4 + t`` (``c != t``; ``None`` elsewhere) the
        number of the state it leads to, the ANDs done on the way and that state's bound."""
        hit = self._expanded[sid]
        if hit is not None:
            return hit
        forms, done, absorbed = self._states[sid]
        present = 1 << forms[0] | 1 << forms[1] | 1 << forms[2] | 1 << forms[3]
        goal = False
        if done == self._all_inner and _carrier(forms) is not None:
            remaining = [j for j in range(len(self._final)) if not absorbed >> j & 1]
            controls = len(remaining) + (1 if absorbed else 0)
            goal = controls <= (2 if self.target == "nisq" else 1) and all(
                present & self._final_need[j][0] == self._final_need[j][0]
                and done & self._final_need[j][1] == self._final_need[j][1]
                for j in remaining
            )
        successors: list = [None] * 16
        for c, t in MOVES:
            nf = list(forms)
            nf[t] ^= forms[c]
            nforms = tuple(nf)
            npresent = present ^ (1 << forms[t]) ^ (1 << nf[t])
            nd, na, events = self._closure(npresent, done, absorbed)
            successors[c * 4 + t] = (self._id((nforms, nd, na)), events, self._missing(npresent, nd, na))
        hit = self._expanded[sid] = (goal, successors)
        return hit

    def plan(self, moves: Sequence[tuple[int, int]] = MOVES) -> MixerPlan:
        """The first cheapest plan the A* meets trying the CNOTs of each state in the order ``moves`` (a
        permutation of :data:`MOVES`).

        Raises:
            ValueError: no plan exists.
        """
        start = (1, 2, 4, 8)
        present = 1 << 1 | 1 << 2 | 1 << 4 | 1 << 8
        d0, a0, e0 = self._closure(present, 0, 0)
        init = self._id((start, d0, a0))
        far = 1 << 30
        dist = [far] * len(self._states)  # per state number: the fewest CNOTs found to it
        dist[init] = 0
        came: dict[int, tuple[int, int]] = {}  # state -> (the state before it, the CNOT c * 4 + t that led there)
        # a heap entry is one int, (f, g, push number) in bit fields, so ties go to the earlier push; the state
        # of push number n is pushed[n]
        pushed = [init]
        heap = [self._missing(present, d0, a0) << _F_SHIFT]
        goal = None
        order = [c * 4 + t for c, t in moves]
        pop, push, expand, states = heapq.heappop, heapq.heappush, self._expand, self._states
        # every order ends at a cheapest plan (the bound is admissible), whose goal has f = its CNOTs, and an entry
        # of a larger f would be popped after that goal. So once a run has found it, later runs push no such entry:
        # the others keep their order (push numbers only grow), and a state so skipped is pushed again only from a
        # shorter path, as it would have been (a longer one has a larger f too): the same pops, the same plan
        limit = far if self._cheapest is None else self._cheapest
        while heap:
            entry = pop(heap)
            state, g = pushed[entry & _N_MASK], entry >> _G_SHIFT & _G_MASK
            if g > dist[state]:
                continue
            is_goal, successors = expand(state)
            if is_goal:
                goal = state
                break
            if len(dist) < len(states):  # the expansion numbered new states
                dist.extend([far] * (len(states) - len(dist)))
            g1 = g + 1
            for k in order:
                nstate, _, bound = successors[k]
                if g1 < dist[nstate] and g1 + bound <= limit:
                    dist[nstate] = g1
                    came[nstate] = (state, k)
                    push(heap, (g1 + bound) << _F_SHIFT | g1 << _G_SHIFT | len(pushed))
                    pushed.append(nstate)
        if goal is None:
            raise ValueError("no parity-basis plan found")
        self._cheapest = dist[goal]
        parent: dict[int, tuple] = {init: (None, ("start", None, e0))}
        state = goal
        while state != init:
            prev, k = came[state]
            parent[state] = (prev, ("cx", divmod(k, 4), self._expanded[prev][1][k][1]))  # type: ignore[index]
            state = prev
        return _build_plan(self.program, goal, parent, self.target)


@lru_cache(maxsize=1024)
def plan_parity_mixer(program: AbstractProgram, target: Target = "nisq") -> MixerPlan:
    """Cheapest parity-basis partial mixer for an abstract ``exact`` program (see the module docstring).

    The search is an A* over the GF(2) states of the four plaquette qubits (one CNOT per edge of the
    search graph; :class:`ParitySearch`). ANDs are placed greedily (an AND costs 3 CNOTs whenever it is done, and
    its temporary stays available), so only the CNOTs of the linear network are searched: every inner step is done
    as soon as its parities are on some qubit, and every literal of the output AND is folded into the AND chain as
    soon as it is available. For ``nisq`` one temporary literal is held back and becomes the second control of the
    rotation (``ccrx``); with no temporary literal and at most two corner literals, both control it directly.

    Args:
        program: every step but the last has two literals and writes a fresh temporary; literals read even
            parities of the plaquette edges, outer slots or temporaries.
        target: ``nisq`` lets the rotation take two controls (``ccrx``); ``ft`` keeps one (``crx``).

    Pure memo: ``plan_parity_mixer.cache_clear()`` empties it (and ``parity_search.cache_clear()`` the searches)."""
    return parity_search(program, target).plan()


@lru_cache(maxsize=PARITY_SEARCHES_KEPT)
def parity_search(program: AbstractProgram, target: Target = "nisq") -> ParitySearch:
    """The :class:`ParitySearch` of a program, kept so that every run of it shares the states expanded so far
    (:func:`plan_parity_mixer`'s run and the relabelled runs of :func:`qcpp.pipeline.cellmixer.relabelled_plans`):
    an expansion is a pure function of its state, so a kept search plans exactly as a fresh one.

    Pure memo: ``parity_search.cache_clear()`` empties it.

    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.problem.sbf import sbf_logic
    >>> s = default_scenario(2, 3, 1)
    >>> program, _ = abstract_program(sbf_logic(s, 0, s.grid.plaquettes[0], "exact"), s.grid.plaquettes[0])
    >>> parity_search(program, "nisq") is parity_search(program, "nisq")
    True
    """
    return ParitySearch(program, target)


def _build_plan(program: AbstractProgram, goal: Hashable, parent: dict, target: Target) -> MixerPlan:
    actions = []
    state = goal
    while state is not None:
        prev, action = parent[state]
        actions.append(action)
        state = prev
    actions.reverse()
    inner, final = program.steps[:-1], program.steps[-1]
    forms = [1, 2, 4, 8]
    temps_of_step: dict[int, int] = {}
    num_temps = 0
    ops: list[tuple[str, tuple[Slot, ...]]] = []
    polarity: dict[Slot, bool] = {}  # True: the qubit currently holds its value negated

    def read(lit: ALit) -> Slot:
        """The qubit of ``lit``, made to read 1 when the literal holds (an X only when its polarity must change)."""
        kind, ref, value = lit
        if kind == "form":
            slot: Slot = ("p", forms.index(ref))  # type: ignore[arg-type]
        elif kind == "temp":
            slot = ("t", temps_of_step[ref])  # type: ignore[index]
        else:
            slot = ref  # type: ignore[assignment]
        if polarity.get(slot, False) != (not value):
            ops.append(("x", (slot,)))
            polarity[slot] = not value
        return slot

    def and_into_fresh(a: Slot, b: Slot) -> Slot:
        nonlocal num_temps
        t: Slot = ("t", num_temps)
        num_temps += 1
        ops.append(("and", (a, b, t)))
        return t

    acc: Slot | None = None
    absorbed: set[int] = set()
    for kind, arg, events in actions:
        if kind == "cx":
            c, t = arg
            ops.append(("cx", (("p", c), ("p", t))))
            forms[t] ^= forms[c]
            # t XOR (NOT c) = NOT (t XOR c): a negated control negates the target
            polarity[("p", t)] = polarity.get(("p", t), False) ^ polarity.get(("p", c), False)
        for ev, idx in events:
            if ev == "inner":
                a, b = (read(lit) for lit in inner[idx[0]])
                temps_of_step[idx[0]] = and_into_fresh(a, b)[1]
            elif acc is None:
                a, b = (read(final[j]) for j in idx)
                acc = and_into_fresh(a, b)
            else:
                acc = and_into_fresh(acc, read(final[idx[0]]))
            if ev == "absorb":
                absorbed.update(idx)
    controls = [read(final[j]) for j in range(len(final)) if j not in absorbed]
    if acc is not None:
        controls.append(acc)
    # RX commutes with X, so the carrier's polarity does not matter
    carrier: Slot = ("p", _carrier(tuple(forms)))  # type: ignore[arg-type]
    assert 1 <= len(controls) <= (2 if target == "nisq" else 1), controls
    rotation = ("crx", (controls[0], carrier)) if len(controls) == 1 else ("ccrx", (*controls, carrier))
    return MixerPlan(tuple(ops), rotation, num_temps)  # type: ignore[arg-type]


@lru_cache(maxsize=1024)
def plan_mcx_mixer(program: AbstractProgram) -> MixerPlan:
    """The controlled-X network plan (any rule; used for ``paper``): one multi-controlled X per step.
    Pure memo: ``plan_mcx_mixer.cache_clear()`` empties it."""
    ops: list[tuple[str, tuple[Slot, ...]]] = []
    polarity: dict[Slot, bool] = {}
    for target_temp, lits in zip(program.targets, program.steps):
        slots = []
        for kind, ref, value in lits:
            if kind == "form":
                if bin(ref).count("1") != 1:  # type: ignore[arg-type]
                    raise ValueError("controlled-X mixers read single plaquette edges")
                slot: Slot = ("p", int(ref).bit_length() - 1)  # type: ignore[arg-type]
            elif kind == "temp":
                slot = ("t", ref)  # type: ignore[assignment]
            else:
                slot = ref  # type: ignore[assignment]
            if polarity.get(slot, False) != (not value):
                ops.append(("x", (slot,)))
                polarity[slot] = not value
            slots.append(slot)
        target: Slot = ("t", target_temp)
        if polarity.get(target, False):
            ops.append(("x", (target,)))
            polarity[target] = False
        name = {0: "x", 1: "cx", 2: "ccx"}.get(len(slots), "mcx")
        ops.append((name, (*slots, target)))
    out: Slot = ("t", program.targets[-1])
    rotation = ("csbf", (out, ("p", 0), ("p", 1), ("p", 2), ("p", 3)))
    return MixerPlan(tuple(ops), rotation, max(program.targets) + 1)  # type: ignore[arg-type]


# --- gadgets -----------------------------------------------------------------------------------
def plan_slots(plan: MixerPlan, num_outer: int) -> tuple[Slot, ...]:
    """Every qubit slot of a plan in a fixed order: plaquette edges, outer edges, temporaries."""
    return (
        *(("p", i) for i in range(4)),
        *(("o", j) for j in range(num_outer)),
        *(("t", k) for k in range(plan.num_temps)),
    )


def emit_plan(plan: MixerPlan, qubit: dict[Slot, int], beta: Param) -> tuple[list[Gate], list[Gate], list[Gate]]:
    """The plan's gates on the qubits ``qubit`` gives every slot: compute leaves, rotation, mirrored leaves."""
    compute: list[Gate] = []
    for name, slots in plan.compute:
        qs = [qubit[s_] for s_ in slots]
        if name == "cx":
            compute.append(cx(*qs))
        elif name == "x":
            compute.append(x(*qs))
        elif name == "and":
            compute.append(and_(*qs))
        else:  # x / cx / ccx / mcx with positive controls
            compute.append(mcx(qs[:-1], qs[-1]))
    name, slots = plan.rotation
    qs = [qubit[s_] for s_ in slots]
    if name == "crx":
        rotation = [crx(beta, *qs)]
    elif name == "ccrx":
        rotation = ccrx_gates(beta, *qs)
    else:
        rotation = [csbf(beta, *qs)]
    mirror = [and_dg(*g.qubits) if g.name == "and" else g for g in reversed(compute)]
    return compute, rotation, mirror


class ParityMixerKind(NamedTuple):
    """Kind key of a :class:`ParityPartialMixer`: equal programs and targets, equal plans and costs.

    Attributes:
        gadget: ``"parity"``.
        program: the abstract program (:func:`abstract_program`).
        target: what the plan was searched for (:func:`plan_parity_mixer`).
    """

    gadget: str
    program: AbstractProgram
    target: Target


class McxMixerKind(NamedTuple):
    """Kind key of a :class:`McxPartialMixer`: equal programs, equal plans and costs.

    Attributes:
        gadget: ``"mcx"``.
        program: the abstract program (:func:`abstract_program`).
    """

    gadget: str
    program: AbstractProgram


@dataclass(frozen=True)
class _PartialMixerBase:
    """Shared fields: the plan (cost) and where its slots live (emission)."""

    plan: MixerPlan
    kind_key: ParityMixerKind | McxMixerKind
    plaquette_qubits: tuple[int, int, int, int]
    outer_qubits: tuple[int, ...]
    logic_offset: int
    beta: Param

    @property
    def kind(self) -> ParityMixerKind | McxMixerKind:
        """The abstract program and target: equal kinds have equal plans and costs."""
        return self.kind_key

    def cost(self) -> Cost:
        """Lowered cost (from the plan's leaves; nothing is emitted)."""
        return self.plan.cost()

    def logical_cost(self) -> Cost:
        """Cost with ANDs and Toffolis kept whole."""
        return self.plan.logical_cost()

    @property
    def num_temps(self) -> int:
        """Logic temporaries used (from ``logic_offset`` on)."""
        return self.plan.num_temps

    def needs(self) -> tuple[int, int]:
        """The plan's logic temporaries and the work ancillas of its mcx leaves (:func:`mixer_work_need`)."""
        return self.num_temps, mixer_work_need([self])  # type: ignore[list-item]

    @property
    def slot_qubits(self) -> tuple[int, ...]:
        """The qubit of every slot, in :func:`plan_slots` order (plaquette edges, outer edges, temporaries)."""
        temps = range(self.logic_offset, self.logic_offset + self.plan.num_temps)
        return (*self.plaquette_qubits, *self.outer_qubits, *temps)

    def parts(self) -> tuple[list[Gate], list[Gate], list[Gate]]:
        """The gates as compute leaves, rotation, mirrored leaves (:mod:`.junction` fuses the mirror of one
        partial mixer with the compute of the next)."""
        compute, rotation, mirror = self._parts
        return list(compute), list(rotation), list(mirror)

    @cached_property
    def _parts(self) -> tuple[tuple[Gate, ...], tuple[Gate, ...], tuple[Gate, ...]]:
        # built once: a fused layer asks each partial mixer for its parts three times (two junctions, a rotation)
        slots = plan_slots(self.plan, len(self.outer_qubits))
        compute, rotation, mirror = emit_plan(self.plan, dict(zip(slots, self.slot_qubits, strict=True)), self.beta)
        return tuple(compute), tuple(rotation), tuple(mirror)

    def emit(self) -> list[Gate]:
        """The gates: compute, rotation, mirror."""
        compute, rotation, mirror = self.parts()
        return [*compute, *rotation, *mirror]

    def emit_blocks(self) -> list[list[Gate]]:
        """The gates in blocks that the compiler lowers separately (a section each): the whole partial mixer for
        the parity construction; one block per leaf for the controlled-X network, whose consecutive
        clean-AND ladders would otherwise partly cancel and make the cost depend on the neighbours."""
        compute, rotation, mirror = self.parts()
        if isinstance(self, McxPartialMixer):
            return [[g] for g in compute] + [rotation] + [[g] for g in mirror]
        return [[*compute, *rotation, *mirror]]


@dataclass(frozen=True)
class ParityPartialMixer(_PartialMixerBase):
    """Parity-basis partial mixer (the ``exact`` rule); see the module docstring."""


@dataclass(frozen=True)
class McxPartialMixer(_PartialMixerBase):
    """Controlled-X network partial mixer (the ``paper`` rule); see the module docstring."""


def partial_mixer(
    scenario: Scenario,
    robot: int,
    plaquette: Plaquette,
    beta: Param,
    logic_offset: int,
    rule: Rule = "exact",
    target: Target = "nisq",
) -> ParityPartialMixer | McxPartialMixer | None:
    """The partial-mixer gadget of ``robot`` on ``plaquette`` (``None`` when the flip is never allowed).

    Args:
        beta: The mixing angle (e.g. ``Angle.symbol("beta_0")``).
        logic_offset: Qubit index of the first ``logic`` ancilla.
        rule: ``exact`` (parity basis) or ``paper`` (controlled-X network).
        target: ``nisq`` or ``ft`` (see :func:`plan_parity_mixer`).
    """
    logic = sbf_logic(scenario, robot, plaquette, rule)
    if logic.never:
        return None
    program, outer = abstract_program(logic, plaquette)
    data = tuple(scenario.variable_index(robot, e) for e in plaquette.edges)
    outer_q = tuple(scenario.variable_index(robot, e) for e in outer)
    if rule == "exact":
        plan = plan_parity_mixer(program, target)
        kind = ParityMixerKind("parity", program, target)
        return ParityPartialMixer(plan, kind, data, outer_q, logic_offset, beta)  # type: ignore[arg-type]
    plan = plan_mcx_mixer(program)
    return McxPartialMixer(plan, McxMixerKind("mcx", program), data, outer_q, logic_offset, beta)  # type: ignore[arg-type]


def logic_width(scenario: Scenario, rule: Rule = "exact", target: Target = "nisq") -> int:
    """``logic`` ancillas the full mixer needs (the largest partial mixer; they are shared)."""
    widths = [
        m.num_temps
        for r in range(scenario.num_robots)
        for q in scenario.grid.plaquettes
        if (m := partial_mixer(scenario, r, q, 0.0, 0, rule, target)) is not None
    ]
    return max(widths, default=0)


def mixer_work_need(gadgets: Sequence[McxPartialMixer | ParityPartialMixer]) -> int:
    """Work ancillas the mcx leaves need (``k - 2`` for the largest)."""
    return max((len(s) - 3 for g in gadgets for name, s in g.plan.compute if name == "mcx"), default=0)
