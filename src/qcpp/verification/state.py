"""The state method: run the compiled, lowered circuit on feasible basis inputs and look at every output amplitude.

The circuit is :func:`qcpp.plan.compile.compile_scenario` lowered, with every angle bound to a seeded random value
in ``[0.1, pi - 0.1]`` (no rotation is the identity by accident). Its parts are checked as units:

* ``initial_state`` from ``|0...0>``;
* every layer's ``phase_k`` and ``mixer_k``, each on every feasible assignment (ancillas ``|0>``): exhaustively
  while the number of feasible assignments is at most ``samples``, else on ``samples`` of them drawn with the
  seed;
* ``circuit``: the whole circuit from ``|0...0>``.

A unit holds when, for every input, every output amplitude larger than :data:`~qcpp.verification.common.TOLERANCE`
lies on a feasible assignment with every ancilla in ``|0>``. The inputs run together
(:class:`qcpp.verification.batch.Batch`),
one amplitude list per input, so a failure names its input. Since each unit maps every feasible basis state into
the span of feasible assignments, so does any product of them (linearity): with every input checked, the whole
circuit keeps every feasible superposition feasible.

On a failure the input is re-run gadget by gadget (:meth:`qcpp.plan.qaoa.QaoaPlan.sections`) to name the gadget:
the first one after which the state, at a point where the ancillas must be clean, leaves the feasible span. In a
fused mixer layer (:mod:`qcpp.gadgets.junction`) that point is after a rotation followed by the closing junction of
its partial mixer.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> r = verify_state(default_scenario(2, 3, 2), p=1)
    >>> r.holds, [c.subject for c in r.checks]
    (True, ['initial_state', 'phase_0', 'mixer_0', 'circuit'])
"""

from __future__ import annotations

import itertools
import math
import random
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from qcpp.gadgets.junction import MixerJunction, MixerRotation
from qcpp.gadgets.partial_mixer import McxPartialMixer, ParityPartialMixer
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import lower
from qcpp.plan.compile import compile_scenario
from qcpp.plan.options import PlanOptions
from qcpp.plan.qaoa import qaoa_plan
from qcpp.problem.paths import count_paths, iter_paths
from qcpp.problem.sbf import Rule
from qcpp.problem.scenario import Scenario
from qcpp.verification.batch import MAX_QUBITS, Batch
from qcpp.verification.common import (
    TOLERANCE,
    FeasibleTest,
    ProgressFn,
    edge_names,
    gadget_label,
    picture_label,
    plaquette_of_qubits,
    random_angle,
    verified_plan,
)
from qcpp.verification.report import Check, Counterexample, VerifyReport

__all__ = ["DEFAULT_SAMPLES", "state_fits", "verify_state"]

DEFAULT_SAMPLES = 2000
"""Feasible inputs checked per unit: all of them up to this many, else a seeded sample of this size."""

CHUNK = 128
"""Inputs simulated together (the mixer spreads each over many paths: a bound on memory)."""


@dataclass(frozen=True)
class _Piece:
    """One gadget of the plan with its lowered, bound gates."""

    section: str
    gadget: object
    gates: tuple[Gate, ...]


def state_fits(scenario: Scenario, p: int, options: PlanOptions | None = None) -> bool:
    """Whether the state method can run: the lowered circuit has at most :data:`~qcpp.verification.batch.MAX_QUBITS`
    qubits (a basis state is one 64-bit key)."""
    return qaoa_plan(scenario, p, options or PlanOptions()).num_qubits <= MAX_QUBITS


def _scenario_name(s: Scenario) -> str:
    return s.name or f"{s.grid.rows}x{s.grid.cols}, {s.num_robots} robot{'s' if s.num_robots != 1 else ''}"


def _pieces(scenario: Scenario, p: int, options: PlanOptions, bindings: dict[str, float]) -> list[_Piece]:
    """The compiled, lowered circuit's sections grouped by the gadget that emitted them."""
    plan = qaoa_plan(scenario, p, options)
    circuit = compile_scenario(scenario, p, options, lowered=True, bindings=bindings).circuit
    sections = iter(circuit.sections)
    out = []
    for name, g in plan.sections():
        blocks = len(g.emit_blocks()) if isinstance(g, McxPartialMixer) else 1
        gates: list[Gate] = []
        for _ in range(blocks):
            sec = next(sections)
            assert sec.name == name, (sec.name, name)
            gates += sec.gates
        out.append(_Piece(name, g, tuple(gates)))
    assert next(sections, None) is None
    return out


def _inputs(scenario: Scenario, samples: int, rng: random.Random) -> tuple[list[int], bool]:
    """Feasible assignments as basis keys, and whether they are all of them (at most ``samples``; paths are
    counted no further than that). A sample draws each robot's path from its first ``50 * samples`` paths in
    :func:`~qcpp.problem.paths.iter_paths` order."""
    v = scenario.edges_per_robot
    counts = [count_paths(scenario, r, cap=samples + 1) for r in range(scenario.num_robots)]
    total = math.prod(counts)
    pos = {e: k for k, e in enumerate(scenario.variable_edges)}

    def bits(mask: int) -> int:
        out = 0
        while mask:
            low = mask & -mask
            out |= 1 << pos[low.bit_length() - 1]
            mask ^= low
        return out

    if total <= samples:
        per_robot = [[bits(m) << (r * v) for m in iter_paths(scenario, r)] for r in range(scenario.num_robots)]
        return [sum(c) for c in itertools.product(*per_robot)], True
    pools = []
    for r in range(scenario.num_robots):  # a robot with many paths: a pool of its first ones, then random walks
        pool = list(itertools.islice(iter_paths(scenario, r), 50 * samples))
        pools.append([bits(m) << (r * v) for m in pool])
    keys = {sum(rng.choice(pool) for pool in pools) for _ in range(samples)}
    return sorted(keys), False


def _first_bad(out: Batch, test: FeasibleTest) -> int | None:
    """Index of the largest offending entry of ``out``, or ``None``."""
    big = np.abs(out.amps) > TOLERANCE
    if not big.any():
        return None
    bad = np.zeros(len(out), dtype=bool)
    bad[big] = test.bad(out.keys[big])
    if not bad.any():
        return None
    idx = np.flatnonzero(bad)
    return int(idx[np.argmax(np.abs(out.amps[idx]))])


def _chunks(keys: Sequence[int]) -> Iterator[Sequence[int]]:
    for i in range(0, len(keys), CHUNK):
        yield keys[i : i + CHUNK]


def _closing(piece: _Piece, registers: tuple, bindings: dict[str, float]) -> tuple[Gate, ...] | None:
    """Gates that bring a fused mixer back to clean ancillas after ``piece`` (its partial mixer's closing junction,
    lowered), ``()`` when the piece ends clean already, ``None`` inside a junction."""
    g = piece.gadget
    if isinstance(g, MixerRotation):
        sec = Section(piece.section, tuple(MixerJunction(g.mixer, None).emit()))
        return tuple(lower(Circuit(registers, [sec])).bind(bindings).gates)
    if isinstance(g, MixerJunction) and g.right is not None:
        return None
    return ()


def _blame(
    scenario: Scenario, pieces: list[_Piece], key: int, registers: tuple, bindings: dict[str, float]
) -> tuple[object | None, int | None, float]:
    """The gadget after which input ``key`` first leaves the feasible span at a clean point, with the offending
    output there and its amplitude's modulus (``None, None, 0`` if no single gadget shows it)."""
    test = FeasibleTest(scenario)
    state = Batch.of_inputs([key])
    for piece in pieces:
        state = state.run(piece.gates)
        closing = _closing(piece, registers, bindings)
        if closing is None:
            continue
        probe = state.run(closing) if closing else state
        if _first_bad(probe, test) is not None:  # the offending output nearest to the input
            big = np.flatnonzero(np.abs(probe.amps) > TOLERANCE)
            bad = big[test.bad(probe.keys[big])]
            near = min(bad, key=lambda i: ((int(probe.keys[i]) ^ key).bit_count(), -abs(probe.amps[i])))
            return piece.gadget, int(probe.keys[near]), float(abs(probe.amps[near]))
    return None, None, 0.0


def _label(scenario: Scenario, gadget: object) -> str:
    """The gadget's name for reports, its partial mixers by their own plaquettes' local pictures."""
    pictures: dict[object, str] = {}
    for m in (gadget.left, gadget.right) if isinstance(gadget, MixerJunction) else (getattr(gadget, "mixer", gadget),):
        if isinstance(m, ParityPartialMixer | McxPartialMixer):
            found = plaquette_of_qubits(scenario, m.plaquette_qubits)
            if found is not None:
                pictures.setdefault(m.kind, picture_label(scenario, *found))
    return gadget_label(gadget, pictures.get)


def _counterexample(
    scenario: Scenario, name: str, gadget: object | None, key_in: int, key_out: int, amp: float,
    test: FeasibleTest,
) -> Counterexample:  # fmt: skip
    robot, plaquette = _where(scenario, gadget)
    ins, outs = test.masks(key_in), test.masks(key_out)
    full = (1 << test.v) - 1
    broken = [r for r in range(len(outs)) if not test.path_ok(r, (key_out >> (r * test.v)) & full)]
    reason = f"robot {broken[0]}'s path leaves the feasible set" if broken else "an ancilla is left in |1>"
    if robot is None and broken:
        robot = broken[0]
    return Counterexample(
        "state", name, None if gadget is None else _label(scenario, gadget), robot, plaquette,
        tuple(edge_names(scenario, m) for m in ins), tuple(edge_names(scenario, m) for m in outs),
        test.dirty(key_out), amp, reason, None if name in ("initial_state", "circuit") else True,
    )  # fmt: skip


def _where(scenario: Scenario, gadget: object | None) -> tuple[int | None, tuple[tuple[int, int], ...] | None]:
    mixer = gadget.mixer if isinstance(gadget, MixerRotation) else gadget
    if isinstance(gadget, MixerJunction):
        mixer = gadget.left
    if isinstance(mixer, ParityPartialMixer | McxPartialMixer):
        found = plaquette_of_qubits(scenario, mixer.plaquette_qubits)
        if found is not None:
            return found[0], tuple(found[1].corners)
    return None, None


def verify_state(
    scenario: Scenario,
    p: int,
    rule: Rule = "exact",
    *,
    samples: int = DEFAULT_SAMPLES,
    seed: int = 0,
    progress: ProgressFn | None = None,
    options: PlanOptions | None = None,
) -> VerifyReport:
    """Check feasibility preservation on the compiled circuit (see the module docstring).

    Args:
        p: QAOA layers (>= 1).
        rule: The SBF rule to compile with.
        samples: Most feasible inputs per unit (all of them when there are no more; a seeded sample otherwise).
        seed: Seed of the angles and of the sample.
        options: How the circuit is built (:class:`~qcpp.plan.options.PlanOptions`; its rule replaces ``rule``).
        progress: Called as ``progress(done, total)`` over all inputs of all units.

    Returns:
        The :class:`~qcpp.verification.report.VerifyReport` (method ``state``).

    Raises:
        ValueError: the lowered circuit is wider than :data:`~qcpp.verification.batch.MAX_QUBITS` qubits, or ``p < 1``.
    """
    start = time.perf_counter()
    plan = verified_plan(scenario, p, rule, options)
    options, rule = plan.options, plan.options.rule
    if plan.num_qubits > MAX_QUBITS:
        raise ValueError(
            f"the state method needs at most {MAX_QUBITS} qubits; this circuit has {plan.num_qubits} "
            "(use --method gadgets)"
        )
    rng = random.Random(seed)
    bindings = {name: random_angle(rng) for name in plan.parameter_names}
    pieces = _pieces(scenario, p, options, bindings)
    registers = plan.registers
    keys, exhaustive = _inputs(scenario, samples, rng)
    test = FeasibleTest(scenario)
    units: list[tuple[str, list[_Piece], list[int]]] = [
        ("initial_state", [pc for pc in pieces if pc.section == "initial_state"], [0])
    ]
    for k in range(p):
        for part in ("phase", "mixer"):
            units.append((f"{part}_{k}", [pc for pc in pieces if pc.section == f"{part}_{k}"], keys))
    units.append(("circuit", pieces, [0]))
    work = sum(len(inputs) for _, _, inputs in units)
    done = 0
    checks: list[Check] = []
    counterexample = None
    for name, unit, inputs in units:
        gates = [g for pc in unit for g in pc.gates]
        how = "sampled" if inputs is keys and not exhaustive else "exhaustive"  # |0...0> is one input: all of them
        held = True
        for chunk in _chunks(inputs):
            out = Batch.of_inputs(chunk).run(gates)
            bad = _first_bad(out, test)
            done += len(chunk)
            if progress is not None:
                progress(done, work)
            if bad is not None:
                held = False
                key_in, key_out = int(chunk[int(out.owners[bad])]), int(out.keys[bad])
                gadget, key_at, amp_at = _blame(scenario, unit, key_in, registers, bindings)
                amp = float(abs(out.amps[bad]))
                if key_at is not None:  # the output right after the gadget at fault
                    key_out, amp = key_at, amp_at
                counterexample = _counterexample(scenario, name, gadget, key_in, key_out, amp, test)
                break
        detail = "" if how == "exhaustive" else f"seeded sample; more than {samples} feasible assignments"
        checks.append(Check(name, "state", how, len(inputs), held, 1, detail))
        if not held:
            break
    return VerifyReport(
        _scenario_name(scenario), p, rule, "state", counterexample is None, tuple(checks), counterexample,
        time.perf_counter() - start, seed, options.target,
    )  # fmt: skip
