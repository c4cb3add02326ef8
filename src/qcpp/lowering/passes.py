"""Lowering passes: plain functions ``Circuit -> Circuit`` that preserve sections.

* :func:`lower_mcx` - multi-controlled X onto Toffoli v-chains with clean work ancillas.
* :func:`lower_to_basis` - rewrite every gate into a basis (default ``{cx, x, h, rz, t, tdg,
  s, sdg}``) with exact decompositions (equal matrices, not just up to global phase).
* :func:`peephole` - cancel adjacent inverse pairs and merge adjacent ``rz``, linear time.
* :func:`lower` - the three in sequence.

>>> from qcpp.ir.circuit import CircuitBuilder
>>> from qcpp.ir.gates import mcx, rzz
>>> b = CircuitBuilder([("data", 5)])
>>> b.append([mcx([0, 1, 2, 3], 4, "1011"), rzz(0.5, 0, 1)], section="mixer_0")
>>> low = lower(b.build())
>>> [r.name for r in low.registers], low.num_qubits
(['data', 'work'], 7)
>>> sorted(low.count_ops().items())
[('cx', 20), ('h', 10), ('rz', 1), ('s', 2), ('sdg', 2), ('t', 12), ('tdg', 11), ('x', 2)]
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Iterable, Sequence

from qcpp.ir._perf import gc_paused
from qcpp.ir.angles import Param
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import GATE_SPECS, Gate

__all__ = [
    "DEFAULT_BASIS",
    "LOGICAL_BASIS",
    "WORK_REGISTER",
    "decompose_gate",
    "lower",
    "lower_mcx",
    "lower_to_basis",
    "mcx_work_need",
    "peephole",
]

DEFAULT_BASIS: frozenset[str] = frozenset({"cx", "x", "h", "rz", "t", "tdg", "s", "sdg"})
"""Target gate set of :func:`lower`."""

LOGICAL_BASIS: frozenset[str] = DEFAULT_BASIS | {"and", "and_dg", "ccx"}
"""The fault-tolerant view's basis: ANDs (4 T to compute, a measurement and no T to uncompute) and full
Toffolis stay whole, everything else is lowered as usual."""

WORK_REGISTER = "work"
"""Name of the register of clean work ancillas used by :func:`lower_mcx`."""

_new = tuple.__new__


def _g(name: str, qubits: tuple[int, ...], params: tuple[Param, ...] = ()) -> Gate:
    return _new(Gate, (name, qubits, params, None))


# --- mcx ------------------------------------------------------------------------------------
def mcx_work_need(circuit: Circuit) -> int:
    """Peak number of work ancillas :func:`lower_mcx` needs: max over mcx of ``k - 2``.

    Args:
        circuit: any circuit.

    Returns:
        ``0`` if no mcx has three or more controls.
    """
    need = 0
    for sec in circuit.sections:
        for g in sec.gates:
            if g[0] == "mcx":
                need = max(need, len(g[1]) - 3)
    return need


def _work_layout(circuit: Circuit, need: int) -> tuple[tuple[Register, ...], range]:
    regs = circuit.registers
    if not circuit.has_register(WORK_REGISTER):
        regs = (*regs, Register(WORK_REGISTER, need))
    else:
        work = circuit.register(WORK_REGISTER)
        if work.size < need:
            if regs[-1].name != WORK_REGISTER:
                raise ValueError(
                    f"register {WORK_REGISTER!r} has {work.size} qubits, {need} are needed, "
                    "and it cannot grow because it is not the last register"
                )
            regs = (*regs[:-1], Register(WORK_REGISTER, need))
    start = Circuit._trusted(regs, ()).qubits_of(WORK_REGISTER).start
    return regs, range(start, start + need)


def _mcx_chain(controls: Sequence[int], target: int, work: Sequence[int], out: list[Gate]) -> None:
    """All-positive k-controlled X with k >= 3: ``k - 2`` clean ANDs into work, one Toffoli, the mirrors."""
    k = len(controls)
    ladder = [_new(Gate, ("and", (controls[0], controls[1], work[0]), (), "11"))]
    for i in range(1, k - 2):
        ladder.append(_new(Gate, ("and", (controls[i + 1], work[i - 1], work[i]), (), "11")))
    out.extend(ladder)
    out.append(_g("ccx", (controls[k - 1], work[k - 3], target)))
    out.extend(g.inverse() for g in reversed(ladder))


def _expand_mcx(g: Gate, work: Sequence[int], out: list[Gate]) -> None:
    qubits, state = g[1], g[3]
    controls, target = qubits[:-1], qubits[-1]
    k = len(controls)
    flips = [_g("x", (c,)) for c, bit in zip(controls, state or "1" * k, strict=True) if bit == "0"]
    out.extend(flips)
    if k == 1:
        out.append(_g("cx", qubits))
    elif k == 2:
        out.append(_g("ccx", qubits))
    else:
        _mcx_chain(controls, target, work, out)
    out.extend(flips)


@gc_paused()
def lower_mcx(circuit: Circuit) -> Circuit:
    """Replace every ``mcx`` by X-conjugated ``x``/``cx``/``ccx`` gates.

    A gate with ``k >= 3`` controls becomes a v-chain on ``k - 2`` clean work ancillas: a
    compute ladder of ``k - 2`` clean ``and`` gates (3 CX each once lowered), the one full
    Toffoli onto the target (which may hold data, 6 CX), and the ``and_dg`` mirrors: ``6k - 6``
    CX in all (Barenco et al. 1995's Lemma 7.2 needs ``4(k - 2)`` full Toffolis for *dirty*
    ancillas). Negative controls are conjugated by X. ``k = 1``/``2`` give ``cx``/``ccx``.

    The work ancillas are the register ``work`` (added at the end of the layout, or grown if
    it is already the last register) whose size is the peak need over the whole circuit; every
    ladder returns them to |0>, so all mcx gates reuse the same qubits. Gates must not touch
    the work qubits themselves.

    Args:
        circuit: any circuit.

    Returns:
        A circuit with no ``mcx`` gate (``circuit`` itself if it had none).

    >>> from qcpp.ir.gates import mcx
    >>> c = Circuit([("data", 6)], [Section("m", [mcx([0, 1, 2, 3, 4], 5)])])
    >>> low = lower_mcx(c)
    >>> low.count_ops(), list(low.qubits_of("work"))
    ({'and': 3, 'and_dg': 3, 'ccx': 1}, [6, 7, 8])
    """
    if not any(g[0] == "mcx" for g in circuit.gates):
        return circuit
    need = mcx_work_need(circuit)
    regs, work = _work_layout(circuit, need) if need else (circuit.registers, range(0))
    work_set = frozenset(work)
    secs = []
    for sec in circuit.sections:
        out: list[Gate] = []
        for g in sec.gates:
            if g[0] != "mcx":
                out.append(g)
                continue
            if work_set.intersection(g[1]):
                raise ValueError(f"{g} acts on a work ancilla of register {WORK_REGISTER!r}")
            _expand_mcx(g, work, out)
        secs.append(Section(sec.name, tuple(out)))
    return Circuit._trusted(regs, tuple(secs), circuit._symbols)


# --- basis decompositions -------------------------------------------------------------------
def _half(theta: Param) -> Param:
    return theta * 0.5 if type(theta) is float else theta / 2


def _ccx(g: Gate) -> list[Gate]:
    # Nielsen & Chuang Fig. 4.9: 6 cx + 9 single-qubit gates, exact (no global phase).
    a, b, c = g[1]
    return [
        _g("h", (c,)), _g("cx", (b, c)), _g("tdg", (c,)), _g("cx", (a, c)),
        _g("t", (c,)), _g("cx", (b, c)), _g("tdg", (c,)), _g("cx", (a, c)),
        _g("t", (b,)), _g("t", (c,)), _g("h", (c,)),
        _g("cx", (a, b)), _g("t", (a,)), _g("tdg", (b,)), _g("cx", (a, b)),
    ]  # fmt: skip


# Qiskit's RCCX (a Toffoli up to relative phases, 3 CX) then S-dagger on the target: on a target in |0> this
# is exactly |a, b, 0> -> |a, b, a AND b> (tests/compiler/lowering_test.py checks every input).
def _and_body(a: int, b: int, t: int) -> list[Gate]:
    return [
        _g("h", (t,)), _g("t", (t,)), _g("cx", (b, t)), _g("tdg", (t,)), _g("cx", (a, t)),
        _g("t", (t,)), _g("cx", (b, t)), _g("tdg", (t,)), _g("h", (t,)), _g("sdg", (t,)),
    ]  # fmt: skip


def _negated(g: Gate, body: list[Gate]) -> list[Gate]:
    flips = [_g("x", (c,)) for c, bit in zip(g[1][:2], g[3] or "11", strict=True) if bit == "0"]
    return [*flips, *body, *flips] if flips else body


def _and(g: Gate) -> list[Gate]:
    return _negated(g, _and_body(*g[1]))


def _and_dg(g: Gate) -> list[Gate]:
    return _negated(g, [x.inverse() for x in reversed(_and_body(*g[1]))])


def _crx(g: Gate) -> list[Gate]:
    c, t = g[1]
    return [_g("h", (t,)), *_crz(_g("crz", (c, t), g[2])), _g("h", (t,))]


def _crz(g: Gate) -> list[Gate]:
    c, t = g[1]
    half = _half(g[2][0])
    return [_g("rz", (t,), (half,)), _g("cx", (c, t)), _g("rz", (t,), (-half,)), _g("cx", (c, t))]


def _cry(g: Gate) -> list[Gate]:
    c, t = g[1]
    half = _half(g[2][0])
    return [_g("ry", (t,), (half,)), _g("cx", (c, t)), _g("ry", (t,), (-half,)), _g("cx", (c, t))]


def _rzz(g: Gate) -> list[Gate]:
    qubits = g[1]
    cx = _new(Gate, ("cx", qubits, (), None))  # immutable, so one object serves twice
    return [cx, _new(Gate, ("rz", (qubits[1],), g[2], None)), cx]


def _rx(g: Gate) -> list[Gate]:
    q = g[1]
    return [_g("h", q), _g("rz", q, g[2]), _g("h", q)]


def _ry(g: Gate) -> list[Gate]:
    # RY(θ) = S · RX(θ) · S†  (S X S† = Y), so in time order: sdg, h, rz, h, s.
    q = g[1]
    return [_g("sdg", q), _g("h", q), _g("rz", q, g[2]), _g("h", q), _g("s", q)]


def _cz(g: Gate) -> list[Gate]:
    a, b = g[1]
    return [_g("h", (b,)), _g("cx", (a, b)), _g("h", (b,))]


def _parity_rotation(qs: tuple[int, ...], core: Gate) -> list[Gate]:
    """H⊗4 maps X⊗4 to Z⊗4; the cx ladder collects the parity on the last qubit."""
    a, b, c, d = qs
    hs = [_g("h", (q,)) for q in qs]
    ladder = [_g("cx", (a, b)), _g("cx", (b, c)), _g("cx", (c, d))]
    return [*hs, *ladder, core, *reversed(ladder), *hs]


def _sbf(g: Gate) -> list[Gate]:
    return _parity_rotation(g[1], _g("rz", (g[1][3],), g[2]))


def _csbf(g: Gate) -> list[Gate]:
    ctrl, *rest = g[1]
    return _parity_rotation(tuple(rest), _g("crz", (ctrl, rest[3]), g[2]))


def _mcx_small(g: Gate) -> list[Gate]:
    if len(g[1]) > 3:
        raise ValueError(f"{g} needs work ancillas: run lower_mcx first")
    out: list[Gate] = []
    _expand_mcx(g, (), out)
    return out


_RULES: dict[str, Callable[[Gate], list[Gate]]] = {
    "ccx": _ccx,
    "and": _and,
    "and_dg": _and_dg,
    "crx": _crx,
    "crz": _crz,
    "cry": _cry,
    "rzz": _rzz,
    "rx": _rx,
    "ry": _ry,
    "cz": _cz,
    "sbf": _sbf,
    "csbf": _csbf,
    "mcx": _mcx_small,
}

# Gate names each rule can emit (lets lower_to_basis skip re-checking outputs).
_RULE_OUTPUTS: dict[str, frozenset[str]] = {
    "ccx": frozenset({"h", "cx", "t", "tdg"}),
    "and": frozenset({"x", "h", "cx", "t", "tdg", "sdg"}),
    "and_dg": frozenset({"x", "h", "cx", "t", "tdg", "s"}),
    "crx": frozenset({"h", "rz", "cx"}),
    "crz": frozenset({"rz", "cx"}),
    "cry": frozenset({"ry", "cx"}),
    "rzz": frozenset({"rz", "cx"}),
    "rx": frozenset({"h", "rz"}),
    "ry": frozenset({"sdg", "h", "rz", "s"}),
    "cz": frozenset({"h", "cx"}),
    "sbf": frozenset({"h", "cx", "rz"}),
    "csbf": frozenset({"h", "cx", "crz"}),
    "mcx": frozenset({"x", "cx", "ccx"}),
}


def decompose_gate(gate: Gate) -> list[Gate]:
    """One decomposition step of ``gate`` (the rule :func:`lower_to_basis` applies).

    Args:
        gate: a gate with a rule (``ccx, crz, cry, rzz, rx, ry, cz, sbf, csbf``, and ``mcx``
            with at most two controls).

    Returns:
        The replacement gates, in time order (they may need further decomposition).

    >>> [g.name for g in decompose_gate(Gate("rzz", (0, 1), (0.3,)))]
    ['cx', 'rz', 'cx']
    """
    rule = _RULES.get(gate[0])
    if rule is None:
        raise ValueError(f"no decomposition rule for {gate[0]!r}")
    return rule(gate)


def _expand(g: Gate, basis: frozenset[str], out: list[Gate]) -> None:
    for sub in decompose_gate(g):
        if sub[0] in basis:
            out.append(sub)
        else:
            _expand(sub, basis, out)


def _check_basis(basis: Iterable[str]) -> frozenset[str]:
    basis = frozenset(basis)
    unknown = basis - set(GATE_SPECS)
    if unknown:
        raise ValueError(f"unknown gate names in basis: {sorted(unknown)}")
    return basis


@gc_paused()
def lower_to_basis(circuit: Circuit, basis: Iterable[str] = DEFAULT_BASIS) -> Circuit:
    """Rewrite every gate not in ``basis`` with exact decompositions, recursively.

    Rules: ``ccx`` -> 6 cx + 9 of h/t/tdg (Nielsen-Chuang); ``and`` -> 3 cx + 7 of
    h/t/tdg/sdg, ``and_dg`` its inverse (exact on a clean target, see :func:`qcpp.ir.gates.and_`);
    ``crx(θ)`` -> h, crz(θ), h; ``crz(θ)`` -> rz(θ/2), cx,
    rz(-θ/2), cx; ``rzz`` -> cx, rz, cx; ``sbf`` -> H⊗4, cx ladder, rz, ladder back, H⊗4;
    ``csbf`` -> the same with ``crz`` from the control in place of the rz; ``rx`` -> h rz h;
    ``ry`` -> sdg h rz h s; ``cz`` -> h cx h; ``cry(θ)`` -> ry(θ/2), cx, ry(-θ/2), cx; ``mcx``
    with <= 2 controls -> X-conjugated cx/ccx. If ``mcx`` is not in ``basis``,
    :func:`lower_mcx` is applied first (which may add the ``work`` register).

    Args:
        circuit: any circuit.
        basis: gate names to keep.

    Returns:
        A circuit whose gate names are all in ``basis`` (same unitary, exactly).

    Raises:
        ValueError: a gate cannot be expressed in ``basis`` with the rules above.
    """
    basis = _check_basis(basis)
    if "mcx" not in basis:
        circuit = lower_mcx(circuit)
    secs = []
    # names whose one-step decomposition is already entirely in the basis
    direct = {name: rule for name, rule in _RULES.items() if _RULE_OUTPUTS[name] <= basis}
    for sec in circuit.sections:
        out: list[Gate] = []
        append, extend = out.append, out.extend
        for g in sec.gates:
            name = g[0]
            if name in basis:
                append(g)
            else:
                rule = direct.get(name)
                if rule is not None:
                    extend(rule(g))
                else:
                    _expand(g, basis, out)
        secs.append(Section(sec.name, tuple(out)))
    return Circuit._trusted(circuit.registers, tuple(secs), circuit._symbols)


# --- peephole -------------------------------------------------------------------------------
_INVERSE_NAME = {
    name: (name if spec.inverse in ("self", "negate") else spec.inverse) for name, spec in GATE_SPECS.items()
}
_NEGATE = frozenset(name for name, spec in GATE_SPECS.items() if spec.inverse == "negate")


def _cancels(prev: Gate, g: Gate) -> bool:
    """``prev`` followed by ``g`` is the identity (same qubits checked by the caller)."""
    if prev[0] != _INVERSE_NAME[g[0]] or prev[3] != g[3]:
        return False
    if g[0] in _NEGATE:
        return all(a == -b for a, b in zip(prev[2], g[2], strict=True))
    return True


def _peephole_gates(gates: Sequence[Gate]) -> list[Gate]:
    out: list[Gate | None] = []
    # stacks[q]: indices into ``out`` of the live gates on qubit q, latest last (a dict: a section touches few of
    # the circuit's qubits, and a circuit has many short sections)
    stacks: defaultdict[int, list[int]] = defaultdict(list)
    inverse_name = _INVERSE_NAME
    push = out.append
    for g in gates:
        name, qubits, params, _ = g
        if name == "rz" and params[0] == 0.0:
            continue
        st = stacks[qubits[0]]
        if st:
            j = st[-1]
            prev = out[j]
            # cheap name test first: almost every gate fails it
            if prev[0] == inverse_name[name] and prev[1] == qubits:  # type: ignore[index]
                n_q = len(qubits)
                if n_q == 1 or (
                    stacks[qubits[1]][-1] == j if n_q == 2 else all(stacks[q][-1] == j for q in qubits[1:])
                ):
                    if name == "rz":
                        total = prev[2][0] + params[0]  # type: ignore[index]
                        if total == 0.0:
                            out[j] = None
                            st.pop()
                        else:
                            out[j] = _new(Gate, ("rz", qubits, (total,), None))
                        continue
                    if _cancels(prev, g):  # type: ignore[arg-type]
                        out[j] = None
                        for q in qubits:
                            stacks[q].pop()
                        continue
        idx = len(out)
        push(g)
        for q in qubits:
            stacks[q].append(idx)
    return [g for g in out if g is not None]


@gc_paused()
def peephole(circuit: Circuit) -> Circuit:
    """Cancel adjacent inverse pairs and merge adjacent ``rz``, within each section.

    Two gates are adjacent when no live gate between them touches any of their qubits. A
    pair cancels when the second is the :meth:`Gate.inverse` of the first on the same qubit
    tuple (``x x``, ``h h``, ``cx cx``, ``t tdg``, ``s sdg``, ``rx(a) rx(-a)``, equal
    ``mcx``, ...). Removals cascade (``h x x h`` vanishes) thanks to a per-qubit stack of
    live gates, so the pass is linear in the number of gates. Adjacent ``rz`` on one qubit
    are merged by angle addition, and an ``rz`` whose angle is exactly 0 is dropped. Nothing
    is merged across a section boundary. The unitary is unchanged and no gate count grows.

    Args:
        circuit: any circuit.

    >>> from qcpp.ir.gates import h, rz, x
    >>> c = Circuit([("data", 1)], [Section("s", [h(0), x(0), x(0), h(0), rz(0.1, 0), rz(0.2, 0)])])
    >>> [str(g) for g in peephole(c).gates]
    ['rz(0.30000000000000004) 0']
    """
    secs = tuple(Section(sec.name, tuple(_peephole_gates(sec.gates))) for sec in circuit.sections)
    return Circuit._trusted(circuit.registers, secs)


@gc_paused()
def lower(circuit: Circuit, basis: Iterable[str] = DEFAULT_BASIS, peephole: bool = True) -> Circuit:
    """:func:`lower_mcx`, then :func:`lower_to_basis`, then (optionally) :func:`peephole`.

    Guarantees, for the result ``r``:

    * every gate name of ``r`` is in ``basis``;
    * ``r.registers`` is ``circuit.registers`` plus, if some mcx has ``k >= 3`` controls, a
      ``work`` register of size ``max(k - 2)`` at the end (or the existing last ``work``
      register grown to that size): qubit count = data + other registers + work peak;
    * sections keep their names and order, and no gate moves between sections;
    * on inputs whose work qubits are |0>, ``r`` acts exactly like ``circuit`` (same matrix,
      including global phase) and returns the work qubits to |0>.

    Args:
        circuit: any circuit.
        basis: target gate names (default :data:`DEFAULT_BASIS`).
        peephole: run :func:`peephole` at the end.
    """
    basis = _check_basis(basis)
    out = lower_to_basis(lower_mcx(circuit) if "mcx" not in basis else circuit, basis)
    return _peephole(out) if peephole else out


_peephole = peephole
