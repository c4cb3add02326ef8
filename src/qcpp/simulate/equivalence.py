"""Independent equivalence checking with MQT QCEC: a lowered circuit against its high-level circuit.

QCEC (decision diagrams, ZX calculus and simulation, from the Munich Quantum Toolkit) is a checker we did not
write. :func:`to_qiskit` turns one of our circuits into a Qiskit ``QuantumCircuit`` with the *IR's* meaning of
every gate (``and`` / ``and_dg`` are the controlled-X permutation of :mod:`qcpp.ir.gates`, not their
relative-phase lowering), qubits from ``num_plain`` on in an ``AncillaRegister`` (QCEC's *ancillary* qubits:
they start in |0>, and with ``check_partial_equivalence`` off their final state is compared too, so a lowering
that leaves an ancilla dirty is caught). :func:`check_equivalence` asks QCEC whether the two are equal on every
input whose ancillas are |0>; equal up to a global phase counts as equivalent only if ``global_phase_ok``.

Whole QAOA circuits can be checked at once (:func:`check_equivalence`) or section by section
(:func:`check_sections`): the lowering never moves a gate across a section boundary and every section returns
the ancillas to |0>, so equal sections compose into an equal circuit; QCEC's alternating checker stays fast on
each section, where a whole wide circuit can be slow.

Requires ``qiskit`` and ``mqt.qcec`` (the ``test`` extra).

Example:
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import mcx
    >>> from qcpp.lowering.passes import lower
    >>> high = Circuit([("data", 5)], [Section("s", [mcx([0, 1, 2, 3], 4, "1011")])])
    >>> check_equivalence(high, lower(high), num_plain=5).equivalent
    True
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from qcpp.io.capture import capture_native_output
from qcpp.io.children import die_with_parent
from qcpp.ir.circuit import Circuit

__all__ = ["EquivalenceResult", "check_equivalence", "check_sections", "check_sections_interruptibly", "to_qiskit"]

_EQUIVALENT = frozenset({"equivalent", "equivalent_up_to_global_phase"})


@dataclass(frozen=True)
class EquivalenceResult:
    """QCEC's verdict on two circuits.

    Attributes:
        criterion: QCEC's ``EquivalenceCriterion`` name (``equivalent``, ``equivalent_up_to_global_phase``,
            ``not_equivalent``, ``probably_equivalent``, ``no_information``, ...).
        equivalent: The criterion proves equality (a global phase only if it was allowed).
        seconds: Wall time of the check (conversion included).
        sections: Sections checked (1 for a whole-circuit check).
        messages: What QCEC printed itself (its ``[QCEC] Warning: ...`` lines, prefix removed), captured
            instead of leaking to the terminal, once each.
    """

    criterion: str
    equivalent: bool
    seconds: float
    sections: int = 1
    messages: tuple[str, ...] = ()


def _qiskit() -> Any:
    try:
        import qiskit
        from mqt import qcec  # noqa: F401
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("equivalence checking needs qiskit and mqt.qcec (pip install 'qcpp[test]')") from exc
    return qiskit


def _parity(qc: Any, qs: tuple[int, ...], core: Callable[[], None]) -> None:
    a, b, c, d = qs
    for q in qs:
        qc.h(q)
    qc.cx(a, b)
    qc.cx(b, c)
    qc.cx(c, d)
    core()
    qc.cx(c, d)
    qc.cx(b, c)
    qc.cx(a, b)
    for q in qs:
        qc.h(q)


def to_qiskit(circuit: Circuit, num_plain: int | None = None, num_qubits: int | None = None) -> Any:
    """A Qiskit circuit with the IR's meaning of every gate; qubits ``>= num_plain`` are ancillary.

    Args:
        circuit: A bound circuit (any level).
        num_plain: Qubits ``0 .. num_plain-1`` are plain (data) qubits, the rest go into an ``AncillaRegister``;
            default all plain.
        num_qubits: Pad with idle ancillary qubits up to this many (e.g. the lowered circuit's ``work``).

    Returns:
        ``qiskit.QuantumCircuit``.

    Raises:
        ValueError: an unbound symbol or a gate name this converter does not know.
    """
    qiskit = _qiskit()
    from qiskit.circuit.library import MCXGate

    if circuit.symbols:
        raise ValueError(f"bind the symbols first: {', '.join(circuit.symbols)}")
    n = circuit.num_qubits if num_qubits is None else max(num_qubits, circuit.num_qubits)
    plain = n if num_plain is None else min(num_plain, n)
    regs = [qiskit.QuantumRegister(plain, "q")] if plain else []
    if n > plain:
        regs.append(qiskit.AncillaRegister(n - plain, "anc"))
    qc = qiskit.QuantumCircuit(*regs)
    simple = {"x", "h", "t", "tdg", "s", "sdg", "cx", "cz", "ccx"}
    angled = {"rz", "rx", "ry", "crz", "cry", "crx", "rzz"}
    for name, qubits, params, state in circuit.gates:
        if name in simple:
            getattr(qc, name)(*qubits)
        elif name in angled:
            getattr(qc, name)(float(params[0]), *qubits)
        elif name in ("mcx", "and", "and_dg"):  # the IR's permutation: X on the target if the controls match
            k = len(qubits) - 1
            bits = state or "1" * k
            qc.append(MCXGate(k, ctrl_state=int(bits[::-1], 2)), list(qubits))
        elif name == "sbf":
            theta = float(params[0])
            _parity(qc, qubits, lambda q=qubits, th=theta: qc.rz(th, q[3]))
        elif name == "csbf":
            theta, ctrl, data = float(params[0]), qubits[0], qubits[1:]
            _parity(qc, data, lambda c=ctrl, q=data, th=theta: qc.crz(th, c, q[3]))
        else:
            raise ValueError(f"to_qiskit: no Qiskit form for gate {name!r}")
    return qc


def check_equivalence(
    high: Circuit,
    low: Circuit,
    num_plain: int,
    *,
    global_phase_ok: bool = False,
    timeout: float | None = None,
    **options: Any,
) -> EquivalenceResult:
    """Ask QCEC whether ``low`` equals ``high`` on every input whose ancillas (qubits ``>= num_plain``) are |0>.

    Args:
        high: The reference circuit (bound).
        low: The circuit to check (bound; may have more qubits, e.g. ``work``, which are ancillary).
        num_plain: Number of leading plain qubits (the data); every later qubit is an ancilla.
        global_phase_ok: Accept ``equivalent_up_to_global_phase`` (our lowering is exact, so default no).
        timeout: QCEC's timeout in seconds (``no_information`` when hit).
        **options: Further QCEC configuration options.
    """
    from mqt import qcec

    t0 = time.perf_counter()
    n = max(high.num_qubits, low.num_qubits)
    a = to_qiskit(high, num_plain, n)
    b = to_qiskit(low, num_plain, n)
    if timeout is not None:
        options["timeout"] = timeout
    with capture_native_output() as printed:  # QCEC writes "[QCEC] Warning: ..." straight to the terminal
        result = qcec.verify(a, b, **options)
    name = str(result.equivalence).rsplit(".", 1)[-1]
    ok = name == "equivalent" or (global_phase_ok and name in _EQUIVALENT)
    messages = tuple(dict.fromkeys(line.removeprefix("[QCEC]").strip() for line in printed.lines))
    return EquivalenceResult(name, ok, time.perf_counter() - t0, messages=messages)


def check_sections(
    high: Circuit, low: Circuit, num_plain: int, *, global_phase_ok: bool = False, **options: Any
) -> EquivalenceResult:
    """:func:`check_equivalence` of each pair of corresponding sections (same names, same order), a run of sections
    checked as one where an AND stays computed across their boundaries (the pieces of fused partial mixers).

    Returns:
        The first failing section's result, or an equivalent result covering every section.

    Raises:
        ValueError: the two circuits do not have the same section names in the same order.
    """
    t0 = time.perf_counter()
    names_h = [s.name for s in high.sections]
    names_l = [s.name for s in low.sections]
    if names_h != names_l:
        raise ValueError(f"section mismatch: {names_h[:5]}... vs {names_l[:5]}...")
    messages: dict[str, None] = {}
    for lo, hi in _clean_blocks(high):
        a = Circuit(high.registers, list(high.sections[lo:hi]))
        b = Circuit(low.registers, list(low.sections[lo:hi]))
        r = check_equivalence(a, b, num_plain, global_phase_ok=global_phase_ok, **options)
        messages.update(dict.fromkeys(r.messages))
        if not r.equivalent:
            return EquivalenceResult(r.criterion, False, time.perf_counter() - t0, len(high.sections), tuple(messages))
    return EquivalenceResult("equivalent", True, time.perf_counter() - t0, len(high.sections), tuple(messages))


def _clean_blocks(high: Circuit) -> list[tuple[int, int]]:
    """Runs ``[lo, hi)`` of sections that start and end with every AND undone: a section boundary where some
    ``and`` is not yet undone by its ``and_dg`` (inside a fused run of partial mixers,
    :mod:`qcpp.gadgets.junction`) is no clean point, so the sections on both sides are checked together."""
    out = []
    lo = 0
    open_ands = 0
    for i, sec in enumerate(high.sections):
        for g in sec.gates:
            if g[0] == "and":
                open_ands += 1
            elif g[0] == "and_dg":
                open_ands -= 1
        if open_ands == 0:
            out.append((lo, i + 1))
            lo = i + 1
    if lo < len(high.sections):
        out.append((lo, len(high.sections)))
    return out


def check_sections_interruptibly(
    high: Circuit,
    low: Circuit,
    num_plain: int,
    *,
    global_phase_ok: bool = False,
    started: Callable[[], None] | None = None,
    **options: Any,
) -> EquivalenceResult:
    """:func:`check_sections` in a child process, so that Ctrl-C and SIGTERM stop it at once.

    QCEC's native check holds the interpreter lock for as long as it runs (minutes on a large section), so a
    signal handler in the same process runs only when it returns. Here the parent waits on a pipe in short
    polls, where its handlers run; when a signal's exception (or any other) leaves the wait, the child is
    terminated. The child starts by ``spawn`` (no copy of the parent's threads or locks), which costs its imports
    (about a second).

    A signal may arrive at any moment, so the start is arranged to leave nothing behind wherever it lands: the
    child is started with two small arguments while SIGINT and SIGTERM are held (:func:`_signals_held`: a
    ``spawn`` start interrupted between launching the interpreter and writing its arguments left a child that
    printed a traceback about truncated pickle data); the circuits follow over the pipe once the child is known
    to the parent, which terminates it if the sending is interrupted, and a child that receives no whole job
    ends silently.

    Args:
        high, low, num_plain, global_phase_ok, options: as for :func:`check_sections`.
        started: Called once the child holds the circuits and QCEC is about to run (a readiness signal for
            progress and for tests that interrupt the check).

    Returns:
        The :class:`EquivalenceResult` of :func:`check_sections`.

    Raises:
        Whatever :func:`check_sections` raised in the child; ``RuntimeError`` if the child died without an answer.
    """
    import multiprocessing

    ctx = multiprocessing.get_context("spawn")
    conn, child_end = ctx.Pipe(duplex=True)
    child = ctx.Process(target=_sections_in_child, args=(child_end, os.getpid()), daemon=True)
    launched = False
    try:
        with _signals_held():
            child.start()
            launched = True
        child_end.close()
        conn.send((high, low, num_plain, {"global_phase_ok": global_phase_ok, **options}))
        while True:
            while not conn.poll(0.1):
                if not child.is_alive() and not conn.poll(0):
                    raise RuntimeError(f"the QCEC process ended without an answer (exit code {child.exitcode})")
            kind, value = conn.recv()
            if kind != "started":
                break
            if started is not None:
                started()
    finally:
        if launched:
            if child.is_alive():
                child.terminate()
            child.join(5)
            if child.is_alive():  # pragma: no cover - a child that ignores SIGTERM
                child.kill()
                child.join()
        conn.close()
        child_end.close()
    if kind == "error":
        raise value
    return value


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM inside the block and deliver the first one that arrived when it ends.

    In the main thread only (elsewhere Python runs no signal handler anyway). The handlers in place are put back
    first, then the held signal is raised again, so it is handled exactly as it would have been, one block later.
    SIGINT is also blocked in the calling thread, so a process started inside the block inherits it blocked: a
    terminal's Ctrl-C reaches the whole process group, and the parent, not the child, must handle it (it
    terminates the child with SIGTERM, which stays open).

    Example:
        >>> with _signals_held():
        ...     pass
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held: list[int] = []
    previous = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    for s in previous:
        signal.signal(s, lambda signum, frame: held.append(signum))
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT}) if hasattr(signal, "pthread_sigmask") else None
    try:
        yield
    finally:
        if mask is not None:
            signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        for s, handler in previous.items():
            signal.signal(s, handler)
        if held:
            signal.raise_signal(held[0])


def _sections_in_child(conn: Any, parent: int) -> None:
    """The child of :func:`check_sections_interruptibly`: receive the job, say ``started``, send ``("result",
    result)`` or ``("error", exception)``.

    It dies with its parent: a parent killed outright (``kill -9``) cannot terminate it, and QCEC would otherwise
    run on alone for minutes (Linux ``PR_SET_PDEATHSIG``; elsewhere the parent's ``terminate`` only). A job that
    never arrives whole (the parent was interrupted while sending it) ends the child silently."""
    die_with_parent(parent)
    try:
        high, low, num_plain, kwargs = conn.recv()
    except Exception:  # EOF or truncated data: the parent stopped while sending
        os._exit(1)
    try:
        conn.send(("started", None))
        conn.send(("result", check_sections(high, low, num_plain, **kwargs)))
    except Exception as exc:  # handed to the parent, which raises it
        with contextlib.suppress(Exception):
            conn.send(("error", exc))
    finally:
        conn.close()
