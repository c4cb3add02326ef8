"""OpenQASM 3 export profiles: the same circuit in the part of OpenQASM 3 a client accepts.

OpenQASM 3 clients disagree on what they accept. Qiskit, Cirq and the QDK require ``include "stdgates.inc"``
for standard gates (the QDK: ``StdGateCalledButNotIncluded``; Cirq without it knows only ``U`` and ``CX``).
Amazon Braket's local simulator and PennyLane's ``from_qasm3`` reject that include (Braket reads it from the
working directory; PennyLane: ``unsupported QASM instruction Include``), PennyLane mis-handles user ``gate``
definitions and does not know the built-in ``U``, and Braket knows ``cnot``, ``si``, ``ti``, ``ccnot``, not
``cx``, ``sdg``, ``tdg``, ``ccx``. So no one text loads everywhere, and a profile says which text to write:

============ ============================================================================================
``default``  :func:`qcpp.lowering.qasm.iter_qasm`: ``include "stdgates.inc"``, ``qcpp_*`` gate definitions,
             ``ctrl``/``negctrl`` modifiers for a multi-controlled X; one statement per IR gate (the most
             faithful: a reader's gate counts equal qcpp's).
``portable`` no include and no gate definitions; only gates that Braket and PennyLane both know (``x h s t
             rx ry rz cz``) and gate modifiers: ``ctrl @ x`` (cx), ``ctrl @ ctrl @ x`` (ccx), ``inv @ s``
             (sdg), ``inv @ t`` (tdg), ``ctrl @ rz``/``ry``/``rx`` (crz/cry/crx), one ``ctrl @`` or ``negctrl @``
             per control of a multi-controlled X. Other gates are written as their exact decompositions
             (:func:`qcpp.lowering.passes.decompose_gate`).
``braket``   no include and no gate definitions; Braket's native names (``cnot``, ``ccnot``, ``si``, ``ti``,
             ``x h s t rx ry rz cz``), controlled rotations and ``rzz``/``sbf``/``and`` as their exact
             decompositions; only a multi-controlled X with three or more controls keeps modifiers (Braket
             has no native gate for it).
============ ============================================================================================

Every profile declares an unbound symbol as ``input float[64] <name>;`` (clients that take no inputs as gate
arguments, such as pyqasm, need the symbols bound first). Every profile writes the same unitary as ``default``
(the decompositions are exact, no global phase), on the same register ``q``, with the same ``// section``
comments.

>>> from qcpp.ir.circuit import Circuit, Section
>>> from qcpp.ir.gates import cx, mcx, sdg
>>> c = Circuit([("data", 3)], [Section("s", [cx(0, 1), sdg(1), mcx([0, 1], 2, "10")])])
>>> print(to_qasm3_profile(c, "portable"), end="")
OPENQASM 3.0;
qubit[3] q;
// section s
ctrl @ x q[0],q[1];
inv @ s q[1];
ctrl @ negctrl @ x q[0],q[1],q[2];
>>> print(to_qasm3_profile(c, "braket"), end="")
OPENQASM 3.0;
qubit[3] q;
// section s
cnot q[0],q[1];
si q[1];
x q[1];
ccnot q[0],q[1],q[2];
x q[1];
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Iterator, Mapping
from types import MappingProxyType
from typing import Literal

from qcpp.errors import OptionError, choice_reason
from qcpp.io.atomic import atomic_open
from qcpp.ir.angles import Param, format_angle
from qcpp.ir.circuit import Circuit
from qcpp.ir.gates import Gate
from qcpp.lowering.passes import decompose_gate
from qcpp.lowering.qasm import CUSTOM_PREFIX, Version, _check_symbol_names, iter_qasm

__all__ = [
    "PROFILES",
    "PROFILE_HEADS",
    "Profile",
    "check_profile",
    "iter_qasm_profile",
    "to_qasm3_profile",
    "write_qasm_profile",
]

Profile = Literal["default", "portable", "braket"]

PROFILES: tuple[Profile, ...] = ("default", "portable", "braket")
"""The export profiles, the faithful one first."""

PROFILE_HEADS: Mapping[str, Mapping[str, str]] = MappingProxyType(
    {
        "portable": MappingProxyType(
            {
                **{n: n for n in ("x", "h", "s", "t", "rx", "ry", "rz", "cz")},
                "sdg": "inv @ s",
                "tdg": "inv @ t",
                "cx": "ctrl @ x",
                "ccx": "ctrl @ ctrl @ x",
                "crz": "ctrl @ rz",
                "cry": "ctrl @ ry",
                "crx": "ctrl @ rx",
            }
        ),
        "braket": MappingProxyType(
            {
                **{n: n for n in ("x", "h", "s", "t", "rx", "ry", "rz", "cz")},
                "sdg": "si",
                "tdg": "ti",
                "cx": "cnot",
                "ccx": "ccnot",
            }
        ),
    }
)
"""Profile -> IR gate name -> the statement head written for it (a gate name, possibly after modifiers). An IR
gate without an entry is written as its exact decomposition, except ``mcx`` (see :func:`_mcx_head`)."""

# Braket's native gate names: a symbol must not shadow one in the braket profile
_BRAKET_TEXT = """i h x y z s si t ti v vi rx ry rz phaseshift cnot cy cz cv swap iswap pswap xy xx yy zz ccnot cswap
    cphaseshift cphaseshift00 cphaseshift01 cphaseshift10 ecr gpi gpi2 ms prx unitary"""
_BRAKET_NAMES = frozenset(_BRAKET_TEXT.split())

_CHUNK = 1 << 15  # gates per text chunk


def check_profile(profile: object, version: object, field: str = "profile", version_field: str = "version") -> Profile:
    """``profile`` if it is one of :data:`PROFILES` and fits OpenQASM ``version``, else :class:`OptionError`.

    Args:
        profile: The profile given.
        version: The OpenQASM version it is for (a profile other than ``default`` needs 3).
        field: The option's name in the message (``profile``, ``--qasm-profile``).
        version_field: The version option's name in the message.

    Returns:
        ``profile``.

    >>> check_profile("braket", 3)
    'braket'
    >>> check_profile("braket", 2)
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: profile: 'braket' is an OpenQASM 3 profile; with version 2 use 'default'
    """
    if profile not in PROFILES:
        raise OptionError(field, choice_reason(profile, PROFILES))
    if profile != "default" and version != 3:
        raise OptionError(field, f"{profile!r} is an OpenQASM 3 profile; with {version_field} {version} use 'default'")
    return profile  # type: ignore[return-value]


def _mcx_head(gate: Gate) -> str:
    """``ctrl @``/``negctrl @`` once per control (PennyLane counts ``ctrl(2) @`` as one control), then ``x``."""
    state = gate[3] or "1" * (len(gate[1]) - 1)
    return "".join("ctrl @ " if bit == "1" else "negctrl @ " for bit in state) + "x"


def _statements(gate: Gate, heads: Mapping[str, str], profile: str, qn: list[str], out: list[str]) -> None:
    name, qubits, params = gate[0], gate[1], gate[2]
    head = heads.get(name)
    if head is None:
        if name == "mcx" and (profile == "portable" or len(qubits) > 3):
            head = _mcx_head(gate)
        else:
            for sub in decompose_gate(gate):  # raises on a gate without a rule
                _statements(sub, heads, profile, qn, out)
            return
    if params:
        head = f"{head}({','.join(_fmt(p) for p in params)})"
    out.append(f"{head} {','.join(qn[i] for i in qubits)};")


def _fmt(p: Param) -> str:
    return format_angle(p, "qasm3")


def _check_symbols(symbols: tuple[str, ...], profile: str) -> None:
    _check_symbol_names(symbols)
    taken = set(PROFILE_HEADS[profile].values())
    if profile == "braket":
        taken |= _BRAKET_NAMES
    bad = [s for s in symbols if s in taken or s.startswith(CUSTOM_PREFIX)]
    if bad:
        raise ValueError(f"symbol names clash with {profile} profile gate names: {bad}")


def iter_qasm_profile(circuit: Circuit, version: Version = 3, profile: Profile = "default") -> Iterator[str]:
    """The OpenQASM text of ``circuit`` in ``profile``, as a stream of chunks (header first).

    Args:
        circuit: any circuit, at any level.
        version: 2 or 3 (a profile other than ``default`` needs 3).
        profile: one of :data:`PROFILES`.

    Returns:
        An iterator of text chunks whose concatenation is the file; ``default`` gives exactly
        :func:`qcpp.lowering.qasm.iter_qasm`.

    Raises:
        qcpp.errors.OptionError: an unknown profile, or a profile other than ``default`` with version 2.
        UnboundParameterError: ``version == 2`` with unbound symbols.
    """
    check_profile(profile, version)
    if profile == "default":
        return iter_qasm(circuit, version)
    symbols = circuit.symbols
    _check_symbols(symbols, profile)
    for sec in circuit.sections:  # every gate has a form: fail before any chunk is produced
        for g in sec.gates:
            if g[0] not in PROFILE_HEADS[profile] and g[0] != "mcx":
                decompose_gate(g)
    head = ["OPENQASM 3.0;", *(f"input float[64] {s};" for s in symbols), f"qubit[{circuit.num_qubits}] q;", ""]
    return itertools.chain(("\n".join(head),), _body(circuit, profile))


def _body(circuit: Circuit, profile: str) -> Iterator[str]:
    qn = [f"q[{i}]" for i in range(circuit.num_qubits)]
    heads = PROFILE_HEADS[profile]
    for sec in circuit.sections:
        gates = sec.gates
        for start in range(0, max(len(gates), 1), _CHUNK):
            lines = [f"// section {sec.name}"] if start == 0 else []
            for g in itertools.islice(gates, start, start + _CHUNK):
                _statements(g, heads, profile, qn, lines)
            lines.append("")
            yield "\n".join(lines)


def to_qasm3_profile(circuit: Circuit, profile: Profile = "default") -> str:
    """OpenQASM 3 text of ``circuit`` in ``profile`` (``default``: :func:`qcpp.lowering.qasm.to_qasm3`)."""
    return "".join(iter_qasm_profile(circuit, 3, profile))


def write_qasm_profile(
    circuit: Circuit, path: str | os.PathLike[str], version: Version = 3, profile: Profile = "default"
) -> None:
    """Write :func:`iter_qasm_profile` to ``path`` atomically: whole or not at all."""
    chunks = iter_qasm_profile(circuit, version, profile)  # argument errors surface before any file is made
    with atomic_open(path) as f:
        for chunk in chunks:
            f.write(chunk)
