"""OpenQASM 3 export profiles: the same circuit in the part of OpenQASM 3 a client accepts.

OpenQASM 3 clients disagree on what they accept. Qiskit, Cirq and the QDK require ``include "stdgates.inc"``
for standard gates (the QDK: ``StdGateCalledButNotIncluded``; Cirq without it knows only ``U`` and ``CX``).
Amazon Braket's local simulator and PennyLane's ``from_qasm3`` reject that include (Braket reads it from the
working directory; PennyLane: ``unsupported QASM instruction Include``); PennyLane mis-handles user ``gate``
definitions and does not know the built-in ``U``; Braket knows ``cnot``, ``si``, ``ti``, ``ccnot``, not
``cx``, ``sdg``, ``tdg``, ``ccx``, and its simulator can fail on gate modifiers (``ctrl @``) in longer
circuits. So no one text loads everywhere (``benchmarks/qasm_clients.py`` measures it), and a profile says
which text to write:

============ ============================================================================================
``default``  :func:`qcpp.lowering.qasm.iter_qasm`: ``include "stdgates.inc"``, ``qcpp_*`` gate definitions,
             ``ctrl``/``negctrl`` modifiers for a multi-controlled X; one statement per IR gate (the most
             faithful: a reader's gate counts equal qcpp's).
``portable`` no include, no gate definitions, no modifiers: only gates Braket and PennyLane both know by name
             (``x z h s t rx ry rz cz``): cx is ``h; cz; h`` on the target, sdg ``z; s``, tdg ``z; s; t``;
             every other gate its exact decomposition (:func:`qcpp.lowering.passes.decompose_gate`).
``braket``   no include, no gate definitions, no modifiers: Braket's native names (``cnot``, ``ccnot``,
             ``si``, ``ti``, ``x h s t rx ry rz cz``), one statement per gate of a lowered circuit; every
             other gate its exact decomposition.
============ ============================================================================================

Every profile declares an unbound symbol as ``input float[64] <name>;`` (a client that takes no input as a gate
argument, such as pyqasm, needs the symbols bound first), writes the same unitary as ``default`` (every rewrite
is exact, without a global phase), on the same register ``q``, with the same ``// section`` comments. A
multi-controlled X with three or more controls (some initial states) has no form without modifiers or
ancillas: ``portable`` and ``braket`` refuse it (:class:`QasmProfileError`); its lowered circuit has none.

>>> from qcpp.ir.circuit import Circuit, Section
>>> from qcpp.ir.gates import cx, mcx, sdg
>>> c = Circuit([("data", 3)], [Section("s", [cx(0, 1), sdg(1), mcx([0, 1], 2, "10")])])
>>> print(to_qasm3_profile(c, "braket"), end="")
OPENQASM 3.0;
qubit[3] q;
// section s
cnot q[0],q[1];
si q[1];
x q[1];
ccnot q[0],q[1],q[2];
x q[1];
>>> print(to_qasm3_profile(Circuit([("data", 2)], [Section("s", [cx(0, 1), sdg(1)])]), "portable"), end="")
OPENQASM 3.0;
qubit[2] q;
// section s
h q[1];
cz q[0],q[1];
h q[1];
z q[1];
s q[1];
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Iterable, Iterator, Mapping, Sequence
from types import MappingProxyType
from typing import Literal

from qcpp.errors import OptionError, QcppError, choice_reason
from qcpp.io.atomic import atomic_open
from qcpp.ir.angles import Param, format_angle
from qcpp.ir.circuit import Circuit, Section
from qcpp.ir.gates import Gate
from qcpp.lowering import qasm as _qasm
from qcpp.lowering.passes import decompose_gate
from qcpp.lowering.qasm import Version, _check_symbol_names
from qcpp.lowering.qasm_measure import check_measured, with_measurements

__all__ = [
    "PROFILES",
    "ZERO_START_NOTE",
    "Profile",
    "QasmProfileError",
    "Statement",
    "check_profile",
    "iter_qasm_profile",
    "iter_qasm_profile_body",
    "to_qasm3_profile",
    "with_note",
    "write_qasm_profile",
]

Profile = Literal["default", "portable", "braket"]

PROFILES: tuple[Profile, ...] = ("default", "portable", "braket")
"""The export profiles, the faithful one first."""

_SAME = frozenset({"x", "h", "s", "t", "rx", "ry", "rz", "cz"})

_BRAKET_NAMES: Mapping[str, str] = MappingProxyType(
    {**{n: n for n in _SAME}, "sdg": "si", "tdg": "ti", "cx": "cnot", "ccx": "ccnot"}
)
"""IR gate name -> Braket's name for it (the ``braket`` profile); any other gate is decomposed."""

# Braket's native gate names: a symbol must not shadow one
_BRAKET_TEXT = """i h x y z s si t ti v vi rx ry rz phaseshift cnot cy cz cv swap iswap pswap xy xx yy zz ccnot cswap
    cphaseshift cphaseshift00 cphaseshift01 cphaseshift10 ecr gpi gpi2 ms prx unitary gphase U"""
_TAKEN = frozenset(_BRAKET_TEXT.split())

_CHUNK = 1 << 15  # gates per text chunk

Statement = tuple[str, tuple[int, ...], tuple[Param, ...]]
"""A written statement: gate name, qubits, parameters."""


class QasmProfileError(QcppError):
    """A circuit a profile cannot write (a multi-controlled X with three or more controls)."""


def _portable(gate: Gate) -> list[Statement] | None:
    name, qubits = gate[0], gate[1]
    if name in _SAME:
        return [(name, qubits, gate[2])]
    if name == "cx":  # H Z H = X on the target
        target = (qubits[1],)
        return [("h", target, ()), ("cz", qubits, ()), ("h", target, ())]
    if name == "sdg":  # diag(1, -1) diag(1, i) = diag(1, -i)
        return [("z", qubits, ()), ("s", qubits, ())]
    if name == "tdg":  # diag(1, -1) diag(1, i) diag(1, e^{i pi/4}) = diag(1, e^{-i pi/4})
        return [("z", qubits, ()), ("s", qubits, ()), ("t", qubits, ())]
    return None


def _braket(gate: Gate) -> list[Statement] | None:
    name = _BRAKET_NAMES.get(gate[0])
    return None if name is None else [(name, gate[1], gate[2])]


_NATIVE = {"portable": _portable, "braket": _braket}


def _statements(gate: Gate, profile: str, out: list[Statement]) -> None:
    """``gate`` as the profile's statements: its own form, else its exact decomposition, recursively."""
    native = _NATIVE[profile](gate)
    if native is not None:
        out.extend(native)
        return
    if gate[0] == "mcx" and len(gate[1]) > 3:
        raise QasmProfileError(
            f"the {profile} OpenQASM 3 profile has no form for a multi-controlled X with {len(gate[1]) - 1} controls "
            "(no gate modifiers, no ancillas): lower the circuit first (--lowered, lowered=True) or use the default "
            "profile"
        )
    for sub in decompose_gate(gate):  # raises on a gate without a rule
        _statements(sub, profile, out)


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


def _check_symbols(symbols: tuple[str, ...]) -> None:
    _check_symbol_names(symbols)
    bad = [s for s in symbols if s in _TAKEN]
    if bad:
        raise ValueError(f"symbol names clash with gate names of the OpenQASM 3 profiles: {bad}")


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
        QasmProfileError: a gate the profile cannot write (before any chunk is produced).
        UnboundParameterError: ``version == 2`` with unbound symbols.
    """
    check_profile(profile, version)
    if profile == "default":
        return _qasm.iter_qasm(circuit, version)  # looked up at call time: the one emitter of the default text
    symbols = circuit.symbols
    _check_symbols(symbols)
    seen: set[tuple[str, int]] = set()
    for sec in circuit.sections:  # every gate has a form: fail before any chunk is produced
        for g in sec.gates:
            key = (g[0], len(g[1]))
            if key not in seen:
                seen.add(key)
                _statements(g, profile, [])
    head = ["OPENQASM 3.0;", *(f"input float[64] {s};" for s in symbols), f"qubit[{circuit.num_qubits}] q;", ""]
    return itertools.chain(("\n".join(head),), _body(circuit.sections, circuit.num_qubits, profile))


def iter_qasm_profile_body(
    sections: Iterable[Section], num_qubits: int, version: Version = 3, profile: Profile = "default"
) -> Iterator[str]:
    """The statements of ``sections`` in ``profile`` as text chunks: what :func:`iter_qasm_profile` writes after
    its header, with the sections taken one at a time as they come (``default``:
    :func:`qcpp.lowering.qasm.iter_qasm_body`).

    Args:
        sections: the sections, in order (any iterable: a generator is consumed lazily, one section held).
        num_qubits: the register size ``q[num_qubits]`` of the header they follow.
        version: 2 or 3 (a profile other than ``default`` needs 3).
        profile: one of :data:`PROFILES`.

    Returns:
        An iterator of text chunks: ``"".join(iter_qasm_profile_body(c.sections, c.num_qubits, v, profile))`` is
        :func:`iter_qasm_profile` of ``c`` without its first chunk.

    Raises:
        qcpp.errors.OptionError: as :func:`check_profile`.
        QasmProfileError: a gate the profile cannot write, when its section is reached. Symbols are not checked:
            the header of the same sections checks them (:func:`iter_qasm_profile`).
    """
    check_profile(profile, version)
    if profile == "default":
        return _qasm.iter_qasm_body(sections, num_qubits, version)
    return _body(sections, num_qubits, profile)


def _body(sections: Iterable[Section], num_qubits: int, profile: str) -> Iterator[str]:
    qn = [f"q[{i}]" for i in range(num_qubits)]  # once per body, however many sections
    for sec in sections:
        gates = sec.gates
        for start in range(0, max(len(gates), 1), _CHUNK):
            lines = [f"// section {sec.name}"] if start == 0 else []
            statements: list[Statement] = []
            for g in itertools.islice(gates, start, start + _CHUNK):
                _statements(g, profile, statements)
            for name, qubits, params in statements:
                head = f"{name}({','.join(format_angle(p, 'qasm3') for p in params)})" if params else name
                lines.append(f"{head} {','.join(qn[i] for i in qubits)};")
            lines.append("")
            yield "\n".join(lines)


def to_qasm3_profile(circuit: Circuit, profile: Profile = "default") -> str:
    """OpenQASM 3 text of ``circuit`` in ``profile`` (``default``: :func:`qcpp.lowering.qasm.to_qasm3`)."""
    return "".join(iter_qasm_profile(circuit, 3, profile))


ZERO_START_NOTE = (
    "simplified for the all-|0> start (qcpp --zero-start): equal to the logical circuit on that input only; "
    "put no gates before it"
)
"""The comment under the version line of a circuit that equals its logical circuit on the all-|0> input only."""


def with_note(chunks: Iterable[str], note: str | None) -> Iterator[str]:
    """The chunks of an OpenQASM text with ``// note`` as its second line (under ``OPENQASM ...;``), so a file
    that is valid only under a condition says so wherever it is taken; ``None`` passes the chunks through.

    Example:
        >>> chunks = ["OPENQASM 3.0;", chr(10), "qubit[1] q;", chr(10), "x q[0];", chr(10)]
        >>> print("".join(with_note(["".join(chunks[:4]), "".join(chunks[4:])], "from |0> only")), end="")
        OPENQASM 3.0;
        // from |0> only
        qubit[1] q;
        x q[0];
    """
    it = iter(chunks)
    if note is None:
        yield from it
        return
    first = next(it, "")
    head, sep, rest = first.partition("\n")
    yield f"{head}\n// {note}" + (sep + rest if sep else "\n")
    yield from it


def write_qasm_profile(
    circuit: Circuit,
    path: str | os.PathLike[str],
    version: Version = 3,
    profile: Profile = "default",
    measured: Sequence[int] | None = None,
    note: str | None = None,
) -> None:
    """Write :func:`iter_qasm_profile` to ``path`` atomically: whole or not at all.

    Args:
        measured: With qubits, also measure ``measured[i]`` into bit ``i`` of a classical register at the end
            (:func:`qcpp.lowering.qasm_measure.with_measurements`); ``None`` (the default) writes no measurement.
        note: A comment line put under the version line (:func:`with_note`; e.g. :data:`ZERO_START_NOTE`).
    """
    chunks = iter_qasm_profile(circuit, version, profile)  # argument errors surface before any file is made
    if measured is not None:
        chunks = with_measurements(chunks, check_measured(measured, circuit.num_qubits), version)
    chunks = with_note(chunks, note)
    with atomic_open(path) as f:
        for chunk in chunks:
            f.write(chunk)
