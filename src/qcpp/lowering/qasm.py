"""OpenQASM 2 and 3 emitters for circuits at any level.

One qubit register ``q[n]``: IR qubit ``i`` is ``q[i]``. Each IR gate becomes exactly one
QASM statement, so the gate counts of a file equal the IR counts (see :func:`ir_gate_name`).
A ``// section <name>`` comment opens each section.

Gates with a standard equivalent keep their standard name (OpenQASM 2: the *original*
``qelib1.inc``; OpenQASM 3: ``stdgates.inc``). In OpenQASM 3 a multi-controlled X is one
statement with control modifiers, e.g. ``mcx([0, 1, 2, 3], 4, "1101")`` is ``ctrl(2) @ negctrl
@ ctrl @ x q[0],q[1],q[2],q[3],q[4];`` (one ``MCXGate`` for ``qiskit.qasm3.loads``). Every
other gate gets a ``gate`` definition from standard gates, emitted only if used:

=============================== =========================================================
``qcpp_rzz(θ) a,b``              cx, rz, cx
``qcpp_cry(θ) c,t``              ry(θ/2), cx, ry(-θ/2), cx (OpenQASM 2 only)
``qcpp_crx(θ) c,t``              h, crz(θ), h (OpenQASM 2 only)
``qcpp_sbf(θ) a,b,c,d``          H⊗4, cx ladder, rz(θ), ladder back, H⊗4
``qcpp_csbf(θ) k,a,b,c,d``       the same with crz(θ) k,d in place of the rz
``qcpp_and_<state> a,b,t``       X on the '0' controls around Qiskit's RCCX body
                                 (h t cx tdg cx t cx tdg h), then sdg t
``qcpp_and_dg_<state> a,b,t``    its inverse: s t, then the same RCCX body (self-inverse)
``qcpp_mcx<k>_<state>``          OpenQASM 2 only: mcx with k controls and that
                                 ``ctrl_state``: X on the '0' controls around cx / ccx /
                                 H·``qcpp_mcphase<k+1>(pi)``·H
``qcpp_mcphase<n>(λ)``           OpenQASM 2 only: phase e^{iλ} on |1...1> of n qubits,
                                 ancilla-free Gray-code construction: 2^(n-1)-1
                                 controlled phases and 2^(n-1)-2 cx
=============================== =========================================================

Every IR gate name has an entry in :data:`QASM_FORMS`; a name without one raises ``ValueError``.

Naming: every custom name starts with ``qcpp_``, so none collides with Qiskit's importers
(``qiskit.qasm2.loads`` with ``LEGACY_CUSTOM_INSTRUCTIONS`` *replaces* a file's own ``gate
rzz``/``c3x`` definition by its own class of that name). To compare counts, map Qiskit's
``count_ops()`` names back with :func:`ir_gate_name` (``qcpp_rzz`` -> ``rzz``, ``mcx_o5`` ->
``mcx``, ...); lowered circuits use standard names only, so their counts match directly.

Parameters are written with ``repr`` precision (round-trip exact). OpenQASM 2 needs every
symbol bound (:class:`UnboundParameterError` otherwise); OpenQASM 3 declares each unbound
symbol as ``input float[64] <name>;`` and writes affine expressions such as
``rz(2.5*gamma_0 + 0.1)``. ``rz`` is RZ(θ) = diag(e^{-iθ/2}, e^{iθ/2}), as in Qiskit.

>>> from qcpp.ir.circuit import CircuitBuilder
>>> from qcpp.ir.gates import h, mcx, rzz
>>> from qcpp.ir.angles import Angle
>>> b = CircuitBuilder([("data", 4)])
>>> b.append([h(0), rzz(Angle.symbol("gamma_0", 2.0), 0, 1), mcx([0, 1, 2], 3, "101")], section="phase_0")
>>> print(to_qasm3(b.build()))
OPENQASM 3.0;
include "stdgates.inc";
input float[64] gamma_0;
gate qcpp_rzz(theta) a, b { cx a, b; rz(theta) b; cx a, b; }
qubit[4] q;
// section phase_0
h q[0];
qcpp_rzz(2.0*gamma_0) q[0],q[1];
ctrl @ negctrl @ ctrl @ x q[0],q[1],q[2],q[3];
<BLANKLINE>
"""

from __future__ import annotations

import itertools
import os
import re
from collections.abc import Callable, Iterable, Iterator, Mapping
from types import MappingProxyType
from typing import Literal

from qcpp.io.atomic import atomic_open
from qcpp.ir._perf import gc_paused
from qcpp.ir.angles import Param, UnboundParameterError, format_angle, format_float
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate

__all__ = [
    "CUSTOM_PREFIX",
    "QASM_FORMS",
    "UnboundParameterError",
    "ir_gate_name",
    "iter_qasm",
    "iter_qasm_body",
    "qasm_gate_name",
    "to_qasm2",
    "to_qasm3",
    "write_qasm",
]

CUSTOM_PREFIX = "qcpp_"
"""Prefix of every gate defined by the emitted files."""

Version = Literal[2, 3]
Form = Literal["standard", "defined", "pattern", "modifier"]

QASM_FORMS: Mapping[str, tuple[Form, Form]] = MappingProxyType(
    {
        **{n: ("standard", "standard") for n in ("x", "h", "t", "tdg", "s", "sdg", "rz", "rx", "ry")},
        **{n: ("standard", "standard") for n in ("cx", "cz", "crz", "ccx")},
        "cry": ("defined", "standard"),
        "crx": ("defined", "standard"),
        "rzz": ("defined", "defined"),
        "sbf": ("defined", "defined"),
        "csbf": ("defined", "defined"),
        "and": ("pattern", "pattern"),
        "and_dg": ("pattern", "pattern"),
        "mcx": ("pattern", "modifier"),
    }
)
"""IR gate name -> how OpenQASM (2, 3) writes it: ``standard`` (the include's gate of that name), ``defined``
(``qcpp_<name>``, one definition), ``pattern`` (one definition per control polarity, ``qcpp_<name>_<state>``;
``qcpp_mcx<k>_<state>`` for mcx) or ``modifier`` (``ctrl``/``negctrl @ x``)."""

_NATIVE: dict[int, frozenset[str]] = {
    v: frozenset(n for n, forms in QASM_FORMS.items() if forms[v - 2] == "standard") for v in (2, 3)
}
_PHASE = {2: ("u1", "cu1"), 3: ("p", "cp")}

# Identifiers a symbol must not shadow in OpenQASM 3 (keywords, constants, our names).
_RESERVED_TEXT = """q pi tau euler input output qubit qreg creg bit bool int uint float angle complex const
    gate def defcal measure reset barrier if else for while in return break continue let box
    delay duration stretch extern include gphase ctrl negctrl inv pow array end U CX OPENQASM
    p x y z h s sdg t tdg sx rx ry rz cx cy cz cp crx cry crz ch swap ccx cswap cu phase cphase
    id u1 u2 u3 sin cos tan arcsin arccos arctan exp ln sqrt mod popcount rotl rotr sizeof real
    imag void mutable readonly opaque"""
_RESERVED = frozenset(_RESERVED_TEXT.split())
_IDENT_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
# Qiskit's names for a loaded `ctrl`/`negctrl @ x` statement with some negative control: mcx_o5, ccx_o1, cx_o0
_QISKIT_OPEN_CONTROL_RE = re.compile(r"^(?:mcx|ccx|cx)_o\d+$")

_CHUNK = 1 << 15  # gates per text chunk when streaming


def _form(name: str, version: Version) -> Form:
    forms = QASM_FORMS.get(name)
    if forms is None:
        raise ValueError(f"unknown gate {name!r}: no OpenQASM form (add it to qcpp.lowering.qasm.QASM_FORMS)")
    return forms[version - 2]


def ir_gate_name(qasm_name: str) -> str:
    """IR gate name of a gate name found in an emitted file, or in Qiskit's ``count_ops`` of a loaded one.

    Args:
        qasm_name: a statement name from :func:`to_qasm2` / :func:`to_qasm3` output, or Qiskit's name of an
            instruction loaded from it.

    Returns:
        The IR name (``qcpp_mcx4_1101`` -> ``mcx``, ``qcpp_rzz`` -> ``rzz``, ``qcpp_and_10`` -> ``and``,
        Qiskit's ``mcx_o2``/``ccx_o1``/``cx_o0`` -> ``mcx``, ``cx`` -> ``cx``).

    >>> ir_gate_name("qcpp_mcx3_101"), ir_gate_name("qcpp_csbf"), ir_gate_name("h"), ir_gate_name("ccx_o2")
    ('mcx', 'csbf', 'h', 'mcx')
    >>> ir_gate_name("qcpp_and_01"), ir_gate_name("qcpp_and_dg_11")
    ('and', 'and_dg')
    """
    if _QISKIT_OPEN_CONTROL_RE.match(qasm_name):
        return "mcx"
    if not qasm_name.startswith(CUSTOM_PREFIX):
        return qasm_name
    rest = qasm_name[len(CUSTOM_PREFIX) :]
    if re.match(r"^mcx\d+_[01]+$", rest):
        return "mcx"
    m = re.match(r"^(and|and_dg)_[01]+$", rest)
    if m:
        return m.group(1)
    return rest


def _state(gate: Gate) -> str:
    return gate[3] or "1" * (len(gate[1]) - 1)


def qasm_gate_name(gate: Gate, version: Version) -> str:
    """Statement name used for ``gate`` in an OpenQASM ``version`` file (with modifiers for an OpenQASM 3 mcx).

    >>> from qcpp.ir.gates import cry, mcx
    >>> qasm_gate_name(cry(0.1, 0, 1), 2), qasm_gate_name(cry(0.1, 0, 1), 3)
    ('qcpp_cry', 'cry')
    >>> qasm_gate_name(mcx([0, 1, 2], 3, "110"), 2), qasm_gate_name(mcx([0, 1, 2], 3, "110"), 3)
    ('qcpp_mcx3_110', 'ctrl(2) @ negctrl @ x')
    """
    name = gate[0]
    form = _form(name, version)
    if form == "standard":
        return name
    if form == "defined":
        return CUSTOM_PREFIX + name
    return _pattern_head(name, _state(gate), version)


def _pattern_head(name: str, state: str, version: Version) -> str:
    if name == "mcx":
        return _modifiers(state) + "x" if version == 3 else _mcx_name(len(state), state)
    return f"{CUSTOM_PREFIX}{name}_{state}"


def _modifiers(state: str) -> str:
    """``ctrl(n) @`` / ``negctrl(n) @`` per run of equal polarity, in control order."""
    out = []
    for bit, run in itertools.groupby(state):
        n = len(list(run))
        word = "ctrl" if bit == "1" else "negctrl"
        out.append(f"{word}({n}) @ " if n > 1 else f"{word} @ ")
    return "".join(out)


def _mcx_name(k: int, state: str) -> str:
    return f"{CUSTOM_PREFIX}mcx{k}_{state}"


# --- gate definitions -----------------------------------------------------------------------
def _gate_def(name: str, params: str, args: list[str], body: list[str]) -> str:
    p = f"({params})" if params else ""
    return f"gate {name}{p} {', '.join(args)} {{ {' '.join(body)} }}"


def _parity_body(qs: list[str], core: str) -> list[str]:
    a, b, c, d = qs
    hs = [f"h {x};" for x in qs]
    ladder = [f"cx {a}, {b};", f"cx {b}, {c};", f"cx {c}, {d};"]
    return [*hs, *ladder, core, *reversed(ladder), *hs]


_FIXED_DEFS = {
    "rzz": _gate_def("qcpp_rzz", "theta", ["a", "b"], ["cx a, b;", "rz(theta) b;", "cx a, b;"]),
    "cry": _gate_def("qcpp_cry", "theta", ["c", "t"], ["ry(theta/2) t;", "cx c, t;", "ry(-theta/2) t;", "cx c, t;"]),
    "crx": _gate_def("qcpp_crx", "theta", ["c", "t"], ["h t;", "crz(theta) c, t;", "h t;"]),
    "sbf": _gate_def("qcpp_sbf", "theta", ["a", "b", "c", "d"], _parity_body(["a", "b", "c", "d"], "rz(theta) d;")),
    "csbf": _gate_def(
        "qcpp_csbf", "theta", ["k", "a", "b", "c", "d"], _parity_body(["a", "b", "c", "d"], "crz(theta) k, d;")
    ),
}

# Qiskit's RCCXGate definition (u2(0, pi) = h, u1(±pi/4) = t/tdg exactly) on controls a, b and target c (a
# qubit argument must not be named like a gate, e.g. `t`): Toffoli up to a relative phase, and its own inverse
# (a real matrix whose square is the identity)
_RCCX_BODY = ["h c;", "t c;", "cx b, c;", "tdg c;", "cx a, c;", "t c;", "cx b, c;", "tdg c;", "h c;"]


def _and_def(name: str, state: str) -> str:
    flips = [f"x {q};" for q, bit in zip("ab", state, strict=True) if bit == "0"]
    core = [*_RCCX_BODY, "sdg c;"] if name == "and" else ["s c;", *_RCCX_BODY]
    return _gate_def(f"{CUSTOM_PREFIX}{name}_{state}", "", ["a", "b", "c"], [*flips, *core, *flips])


def _mcphase_def(n: int, version: Version) -> str:
    """Phase e^{iλ} on |1..1> of n qubits, no ancilla.

    With m = n - 1 controls x and target t: λ·t·∏x = Σ_{S≠∅} φ_S · t · parity_S(x) with
    φ_S = (-1)^(|S|-1) λ / 2^(m-1). Subsets are grouped by their highest element a; within a
    group, a Gray-code walk over the lower elements keeps parity_S in control a with one cx
    per step, and one cx at the end restores it.
    """
    p1, cp = _PHASE[version]
    m = n - 1
    cs = [f"c{i}" for i in range(m)]
    if m == 0:
        return _gate_def(f"{CUSTOM_PREFIX}mcphase1", "lam", ["t"], [f"{p1}(lam) t;"])
    scale = "" if m == 1 else f"/{1 << (m - 1)}"
    body: list[str] = []
    for a in range(m):
        prev = 0
        for j in range(1 << a):
            gray = j ^ (j >> 1)
            if j:
                changed = (gray ^ prev).bit_length() - 1
                body.append(f"cx {cs[changed]}, {cs[a]};")
            prev = gray
            sign = "" if bin(gray).count("1") % 2 == 0 else "-"  # |S| = popcount(gray) + 1
            body.append(f"{cp}({sign}lam{scale}) {cs[a]}, t;")
        if a:
            body.append(f"cx {cs[a - 1]}, {cs[a]};")
    return _gate_def(f"{CUSTOM_PREFIX}mcphase{n}", "lam", [*cs, "t"], body)


def _mcx_def(k: int, state: str) -> tuple[str, int | None]:
    """OpenQASM 2 definition of ``qcpp_mcx<k>_<state>`` and the mcphase size it needs (or None)."""
    cs = [f"c{i}" for i in range(k)]
    flips = [f"x {c};" for c, bit in zip(cs, state, strict=True) if bit == "0"]
    need = None
    if k == 1:
        core = ["cx c0, t;"]
    elif k == 2:
        core = ["ccx c0, c1, t;"]
    else:
        need = k + 1
        core = ["h t;", f"{CUSTOM_PREFIX}mcphase{k + 1}(pi) {', '.join(cs)}, t;", "h t;"]
    return _gate_def(_mcx_name(k, state), "", [*cs, "t"], [*flips, *core, *flips]), need


def _definitions(circuit: Circuit, version: Version) -> list[str]:
    names: set[str] = set()
    for sec in circuit.sections:
        names.update(g[0] for g in sec.gates)
    forms = {name: _form(name, version) for name in names}  # raises on a name without a form
    patterns: set[tuple[str, str]] = set()
    for sec in circuit.sections:
        patterns.update((g[0], _state(g)) for g in sec.gates if forms[g[0]] == "pattern")
    out = [_FIXED_DEFS[name] for name in sorted(names) if forms[name] == "defined"]
    mcx_defs = []
    phases: set[int] = set()
    for name, state in sorted(patterns):
        if name == "mcx":
            text, need = _mcx_def(len(state), state)
            if need is not None:
                phases.add(need)
        else:
            text = _and_def(name, state)
        mcx_defs.append(text)
    out.extend(_mcphase_def(n, version) for n in sorted(phases))  # before their users
    out.extend(mcx_defs)
    return out


# --- emission -------------------------------------------------------------------------------
def _check_symbol_names(symbols: tuple[str, ...]) -> None:
    bad = [s for s in symbols if s in _RESERVED or s.startswith(CUSTOM_PREFIX) or not _IDENT_RE.match(s)]
    if bad:
        raise ValueError(f"symbol names clash with OpenQASM 3 identifiers: {bad}")


def _param_formatter(version: Version) -> Callable[[Param], str]:
    style: Literal["qasm2", "qasm3"] = "qasm2" if version == 2 else "qasm3"

    def fmt(p: Param) -> str:
        return format_float(p) if type(p) is float else format_angle(p, style)

    return fmt


def iter_qasm_body(sections: Iterable[Section], num_qubits: int, version: Version = 3) -> Iterator[str]:
    """The statements of ``sections`` as text chunks, each section opened by its ``// section`` comment: what
    :func:`iter_qasm` writes after its header, with the sections taken one at a time as they come.

    Args:
        sections: the sections, in order (any iterable: a generator is consumed lazily, one section held).
        num_qubits: the register size ``q[num_qubits]`` of the header they follow (every gate's qubits below it).
        version: 2 or 3.

    Returns:
        An iterator of text chunks: ``"".join(iter_qasm_body(c.sections, c.num_qubits, v))`` is
        :func:`iter_qasm` of ``c`` without its first chunk.

    Raises:
        ValueError: a gate name without an OpenQASM form. Symbols are not checked: the header of the same
            sections checks them (:func:`iter_qasm`).
    """
    qn = [f"q[{i}]" for i in range(num_qubits)]  # once per body, however many sections
    heads = {name: name for name, forms in QASM_FORMS.items() if forms[version - 2] == "standard"}
    heads.update({n: CUSTOM_PREFIX + n for n, forms in QASM_FORMS.items() if forms[version - 2] == "defined"})
    pattern_heads: dict[tuple[str, str], str] = {}
    fmt = _param_formatter(version)
    for sec in sections:
        gates = sec.gates
        for start in range(0, max(len(gates), 1), _CHUNK):
            lines = [f"// section {sec.name}"] if start == 0 else []
            append = lines.append
            with gc_paused():  # never held across the yield below
                for name, qubits, params, state in itertools.islice(gates, start, start + _CHUNK):
                    head = heads.get(name)
                    if head is None:  # mcx, and, and_dg: the polarity is part of the statement
                        key = (name, state or "1" * (len(qubits) - 1))
                        head = pattern_heads.get(key)
                        if head is None:
                            _form(name, version)  # raises on an unknown name
                            head = pattern_heads[key] = _pattern_head(name, key[1], version)
                    if params:
                        if len(params) == 1:
                            p = params[0]
                            head = f"{head}({format_float(p) if type(p) is float else fmt(p)})"
                        else:
                            head = f"{head}({','.join(map(fmt, params))})"
                    if len(qubits) == 1:
                        append(f"{head} {qn[qubits[0]]};")
                    elif len(qubits) == 2:
                        append(f"{head} {qn[qubits[0]]},{qn[qubits[1]]};")
                    else:
                        append(f"{head} {','.join([qn[i] for i in qubits])};")
                lines.append("")
                text = "\n".join(lines)
            yield text


def iter_qasm(circuit: Circuit, version: Version = 3) -> Iterator[str]:
    """The OpenQASM text of ``circuit`` as a stream of chunks (header first).

    Args:
        circuit: any circuit, at any level.
        version: 2 or 3.

    Returns:
        An iterator of text chunks whose concatenation is the file.

    Raises:
        UnboundParameterError: ``version == 2`` and the circuit has unbound symbols (raised
            before any chunk is produced).
    """
    if version not in (2, 3):
        raise ValueError(f"unsupported OpenQASM version {version!r}")
    symbols = circuit.symbols
    if version == 2 and symbols:
        raise UnboundParameterError(symbols, "OpenQASM 2 has no symbolic parameters")
    _check_symbol_names(symbols)
    head = (
        ["OPENQASM 2.0;", 'include "qelib1.inc";']
        if version == 2
        else [
            "OPENQASM 3.0;",
            'include "stdgates.inc";',
            *(f"input float[64] {s};" for s in symbols),
        ]
    )
    head.extend(_definitions(circuit, version))
    n = circuit.num_qubits
    head.append(f"qreg q[{n}];" if version == 2 else f"qubit[{n}] q;")
    head.append("")
    return itertools.chain(("\n".join(head),), iter_qasm_body(circuit.sections, n, version))


def to_qasm2(circuit: Circuit) -> str:
    """OpenQASM 2.0 text (``include "qelib1.inc"``); every symbol must be bound.

    Raises:
        UnboundParameterError: naming the unbound symbols.

    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import rz
    >>> print(to_qasm2(Circuit([("data", 1)], [Section("s", [rz(0.5, 0)])])), end="")
    OPENQASM 2.0;
    include "qelib1.inc";
    qreg q[1];
    // section s
    rz(0.5) q[0];
    """
    return "".join(iter_qasm(circuit, 2))


def to_qasm3(circuit: Circuit) -> str:
    """OpenQASM 3.0 text (``include "stdgates.inc"``); unbound symbols become inputs.

    Clients that reject the include or the gate definitions (Amazon Braket, PennyLane) take one of the profiles of
    :mod:`qcpp.lowering.qasm_profiles`.
    """
    return "".join(iter_qasm(circuit, 3))


def write_qasm(circuit: Circuit, path: str | os.PathLike[str], version: Version = 3) -> None:
    """Write the OpenQASM file atomically: whole or not at all.

    The text is streamed into a temporary file in the destination directory, flushed to disk
    and moved over ``path`` with :func:`os.replace`. On any error the temporary file is
    removed and ``path`` is left as it was.

    Args:
        circuit: the circuit.
        path: destination file.
        version: 2 or 3.
    """
    chunks = iter_qasm(circuit, version)  # argument errors surface before any file is made
    with atomic_open(path) as f:
        for chunk in chunks:
            f.write(chunk)
