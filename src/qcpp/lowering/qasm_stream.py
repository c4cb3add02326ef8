"""Write OpenQASM section by section, so that peak memory does not grow with the number of sections.

:func:`write_qasm_sections` takes the register layout and a *factory* of sections (called twice: the first
pass collects what the header needs, the symbols and the custom gate definitions; the second writes the
statements of every section in one body, :func:`qcpp.lowering.qasm_profiles.iter_qasm_profile_body`), and never
holds more than one section. The file equals :func:`qcpp.lowering.qasm.write_qasm` of the whole circuit
byte for byte, and is written atomically (whole or not at all).

Example:
    >>> import os, tempfile
    >>> from qcpp.ir.circuit import Circuit, Register, Section
    >>> from qcpp.ir.gates import cx, h
    >>> from qcpp.lowering.qasm import to_qasm3
    >>> regs = (Register("data", 2),)
    >>> secs = [Section("a", (h(0),)), Section("b", (cx(0, 1),))]
    >>> path = os.path.join(tempfile.mkdtemp(), "c.qasm")
    >>> write_qasm_sections(regs, lambda: iter(secs), path)
    ({'h': 1, 'cx': 1}, ())
    >>> open(path).read() == to_qasm3(Circuit(regs, secs))
    True
"""

from __future__ import annotations

import itertools
import os
from collections import Counter
from collections.abc import Callable, Iterable, Iterator, Sequence

from qcpp.io.atomic import atomic_open
from qcpp.ir.angles import Angle, UnboundParameterError, symbol_sort_key
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate, rz
from qcpp.lowering.qasm import Version
from qcpp.lowering.qasm_measure import check_measured, with_measurements
from qcpp.lowering.qasm_profiles import Profile, iter_qasm_profile, iter_qasm_profile_body

__all__ = ["write_qasm_sections"]


def _header(
    registers: Sequence[Register], make_sections: Callable[[], Iterable[Section]], version: Version, profile: Profile
) -> tuple[str, tuple[str, ...]]:
    """The header of the whole circuit, from one gate per definition-relevant kind and one rz per symbol."""
    reps: dict[tuple[str, int, str | None], Gate] = {}
    symbols: set[str] = set()
    for sec in make_sections():
        symbols.update(Circuit(registers, [sec]).symbols)
        for g in sec.gates:
            key = (g[0], len(g[1]), g[3])
            if key not in reps:
                reps[key] = tuple.__new__(Gate, (g[0], g[1], tuple(0.0 for _ in g[2]), g[3]))
    ordered = tuple(sorted(symbols, key=symbol_sort_key))
    if version == 2 and ordered:
        raise UnboundParameterError(ordered, "OpenQASM 2 has no symbolic parameters")
    skeleton = [*reps.values(), *(rz(Angle.symbol(s), 0) for s in ordered)]
    return next(iter_qasm_profile(Circuit(registers, [Section("header", skeleton)]), version, profile)), ordered


def write_qasm_sections(
    registers: Sequence[Register],
    make_sections: Callable[[], Iterable[Section]],
    path: str | os.PathLike[str],
    version: Version = 3,
    profile: Profile = "default",
    measured: Sequence[int] | None = None,
) -> tuple[dict[str, int], tuple[str, ...]]:
    """Stream the circuit ``Circuit(registers, make_sections())`` to an OpenQASM file, one section at a time.

    Args:
        registers: the register layout.
        make_sections: returns a fresh iterable of the sections, in order (called twice).
        path: destination file.
        version: 2 or 3.
        profile: the OpenQASM 3 export profile (:mod:`qcpp.lowering.qasm_profiles`); the file equals
            :func:`qcpp.lowering.qasm_profiles.write_qasm_profile` of the whole circuit.
        measured: As :func:`qcpp.lowering.qasm_profiles.write_qasm_profile`: measure ``measured[i]`` into bit ``i``
            at the end (``None``: no measurement).

    Returns:
        Gates per name (in order of first appearance) and the unbound symbols (ordered as :attr:`Circuit.symbols`).

    Raises:
        UnboundParameterError: ``version == 2`` and some section has unbound symbols (before any file is made).
        qcpp.errors.OptionError: an unknown profile, or a profile other than ``default`` with version 2.
    """
    registers = tuple(registers)
    header, symbols = _header(registers, make_sections, version, profile)
    ops: Counter[str] = Counter()
    num_qubits = sum(r.size for r in registers)
    chunks: Iterable[str] = itertools.chain(
        (header,), iter_qasm_profile_body(_counted(make_sections(), ops), num_qubits, version, profile)
    )
    if measured is not None:
        chunks = with_measurements(chunks, check_measured(measured, num_qubits), version)
    with atomic_open(path) as f:
        for chunk in chunks:
            f.write(chunk)
    return dict(ops), symbols


def _counted(sections: Iterable[Section], ops: Counter[str]) -> Iterator[Section]:
    """``sections`` passed through, each section's gates added to ``ops`` by name as it is handed out."""
    for sec in sections:
        ops.update(g[0] for g in sec.gates)
        yield sec
