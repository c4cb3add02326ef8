"""Routing a lowered circuit onto a device with Qiskit's SABRE, seeded with our layout.

:func:`route` takes a lowered circuit (``cx`` plus one-qubit gates) and an initial layout (logical qubit ``i``
-> physical qubit) and returns a :class:`~qcpp.routing.routed_circuit.RoutedCircuit` on the device's physical
qubits. Only the two-qubit gates are handed to Qiskit's ``SabreSwap`` (a well-kept router: we do not write our
own); the routed order of two-qubit gates and the SWAPs it inserts are read back and :func:`assemble` puts our
gates in that order: every one-qubit gate of ours goes on its qubit's current physical position just before that
qubit's next two-qubit gate, and every SWAP becomes three ``cx``. Our gates keep their angles (also symbolic ones)
and their section names (a SWAP belongs to the section of the gate before it). A SWAP next to a ``cx`` on the same
two qubits (nothing between them on either) is fused with it into two ``cx`` instead of four where the ops were
routed window by window (:func:`qcpp.routing.windows.route_windows`) and in :func:`route` with ``fuse=True``
(:attr:`RoutedCircuit.fused` counts them); :func:`window_cx` counts the CX of routed ops without assembling them.
Routing never reorders the gates of one logical qubit, so the routed circuit equals the original up to the
layouts (``tests/compiler/routing_test.py`` checks it with a statevector and with QCEC).

Example:
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx, h
    >>> from qcpp.hardware.device import get_device
    >>> c = Circuit([("data", 3)], [Section("s", [h(0), cx(0, 1), cx(0, 2), cx(1, 2)])])
    >>> r = route(c, get_device("grid:1x3"), initial_layout=(0, 1, 2))
    >>> r.circuit.num_qubits, r.swaps, r.initial_layout, r.final_layout
    (3, 1, (0, 1, 2), (0, 2, 1))
    >>> all(g[0] != "cx" or tuple(sorted(g[1])) in {(0, 1), (1, 2)} for g in r.circuit.gates)
    True
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import groupby
from operator import itemgetter
from typing import Any

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate, cx
from qcpp.routing.options import DEFAULT_TRIALS
from qcpp.routing.positions import Positions
from qcpp.routing.routed_circuit import RoutedCircuit, coupling_map, sabre_target

__all__ = ["assemble", "checked_inputs", "cx_dag", "dag_cx", "dag_ops", "route", "window_cx"]


def route(
    circuit: Circuit,
    device: Device,
    initial_layout: Sequence[int],
    seed: int = 0,
    measured: Sequence[int] | None = None,
    trials: int | None = DEFAULT_TRIALS,
    fuse: bool = False,
) -> RoutedCircuit:
    """Route a lowered circuit onto ``device`` from ``initial_layout`` with Qiskit's SABRE.

    Args:
        circuit: One- and two-qubit gates only (e.g. :func:`qcpp.lowering.passes.lower`'s output).
        device: The target; it needs at least ``circuit.num_qubits`` qubits.
        initial_layout: Logical qubit ``i`` -> physical qubit (distinct).
        seed: SABRE's seed.
        measured: Logical qubits measured at the end (default: the ``data`` register, else all).
        trials: SABRE's trials (the best of that many randomised routings; Qiskit's default if ``None``).
        fuse: Write a SWAP next to a ``cx`` on the same two qubits as two ``cx`` (:func:`assemble`, anywhere in
            the circuit); by default every SWAP is three ``cx``.

    Returns:
        The :class:`RoutedCircuit` (lowered gates plus ``cx`` for SWAPs).

    Raises:
        ValueError: the device is too small, the layout is not a placement, or a gate acts on 3+ qubits.
    """
    from qiskit.transpiler.passes import SabreSwap

    gates, section_of, layout, measured_ = checked_inputs(circuit, device, initial_layout, measured)
    big = device.num_qubits
    pairs = [(layout[g[1][0]], layout[g[1][1]]) for g in gates if len(g[1]) == 2]
    if device.is_all_to_all or not pairs:
        routed_ops = [("cx", pair) for pair in pairs]
    else:  # the pass run on the DAG, in the order a pass manager would write its circuit
        sabre = SabreSwap(sabre_target(coupling_map(device)), heuristic="decay", seed=seed, trials=trials)
        routed_ops = dag_ops(sabre.run(cx_dag(big, pairs)))
    # one window for everything: a whole-circuit routing has no per-window sums to keep apart
    windows = ([0] * len(gates), [0] * len(routed_ops)) if fuse else None
    return assemble(gates, section_of, layout, big, routed_ops, device, measured_, None, windows)  # type: ignore[arg-type]


def cx_dag(num_qubits: int, pairs: Sequence[Sequence[int]]) -> Any:
    """A Qiskit DAG of one ``cx`` per pair, in order, on ``num_qubits`` qubits (one register ``q``): what SABRE
    routes (:func:`route`, the placement search)."""
    from qiskit import QuantumCircuit
    from qiskit.circuit import CircuitInstruction
    from qiskit.circuit.library import CXGate
    from qiskit.converters import circuit_to_dag

    qc = QuantumCircuit(num_qubits)
    gate, qubits = CXGate(), qc.qubits
    for a, b in pairs:
        qc._append(CircuitInstruction(gate, (qubits[a], qubits[b])))  # qc.cx's checks cost more than the routing
    return circuit_to_dag(qc, copy_operations=False)


def dag_ops(dag: Any) -> list[tuple[str, tuple[int, ...]]]:
    """The operations of a routed DAG in topological order as ``(name, qubit indices)``: what :func:`assemble`
    and :func:`window_cx` read."""
    index = {q: i for i, q in enumerate(dag.qubits)}
    indices: dict[tuple[Any, ...], tuple[int, ...]] = {}  # per tuple of Qiskit qubits (a routing repeats its pairs)
    out = []
    append = out.append
    for node in dag.topological_op_nodes():
        qargs = node.qargs
        qs = indices.get(qargs)
        if qs is None:
            qs = indices[qargs] = tuple([index[q] for q in qargs])
        append((node.name, qs))  # the node's name is its operation's, without building the operation
    return out


def assemble(
    gates: list[Gate],
    section_of: list[str],
    layout: tuple[int, ...],
    big: int,
    routed_ops: Sequence[tuple[str, tuple[int, int]]],
    device: Device,
    measured: tuple[int, ...],
    op_sections: Sequence[str] | None = None,
    windows: tuple[Sequence[int], Sequence[int]] | None = None,
) -> RoutedCircuit:
    """Our gates in the routed order: ``routed_ops`` lists ``("swap", (p, q))`` and ``("cx", (p, q))`` on physical
    qubits (each ``cx`` is the next two-qubit gate of the logical qubits on ``p`` and ``q``); every one-qubit gate
    goes on its qubit's current position just before that qubit's next two-qubit gate. A SWAP belongs to
    ``op_sections[i]`` if given, else to the section of the gate before it. ``windows``: the window (index) of
    every gate and of every routed op, if the ops were routed window by window
    (:func:`qcpp.routing.windows.route_windows`, or all in one window: :func:`route` with ``fuse=True``); only then
    are SWAPs fused (below), otherwise every SWAP is three ``cx``.

    A SWAP next to a ``cx`` on the same two qubits, with nothing between them on either qubit, is *fused* with it
    (``cx a b`` then ``SWAP = cx a b; cx b a; cx a b``: the two ``cx a b`` cancel, two ``cx`` remain; the same
    the other way round), where both belong to the same section (so a window's routed gates depend on that
    window alone). Before a SWAP whose next operation on both qubits is a ``cx`` between them, the one-qubit
    gates pending on them (the gates before that ``cx``) are put at their positions before the SWAP, where they
    all belong to the SWAP's section, so the SWAP and the ``cx`` meet."""
    out = _Assembly(gates, section_of, layout, big, windows)
    following = _next_ops(routed_ops)
    swaps = 0
    for k, (name, (p1, p2)) in enumerate(routed_ops):
        if name != "swap":
            out.two_qubit(k, p1, p2)
            continue
        swaps += 1
        owner = op_sections[k] if op_sections is not None else out.last_section
        window = out.window_of_op[k] if out.window_of_op is not None else owner
        if not out.fused_with_previous(p1, p2, owner, window):
            nxt = following[k]
            if nxt is None or not out.fused_with_next(p1, p2, owner, window, nxt, routed_ops[nxt]):
                out.three_cx(p1, p2, owner, window)
        out.positions.swap(p1, p2)
    for lq in range(len(layout)):
        out.flush(lq)
    return RoutedCircuit(_sectioned(out.emitted, big), device, layout, tuple(out.positions.where), swaps, measured,
                         tuple(sorted(out.fused.items())))  # fmt: skip


class _Assembly:
    """The state of one :func:`assemble` as it walks the routed ops: our gates emitted so far (with their
    sections and windows), where every logical qubit is, and how far each one's gates are emitted.

    It is the one mutable value of an assembly, made and used up by that call.

    Invariants: ``positions`` holds every logical qubit's physical qubit and back (a free physical qubit is in
    ``|0>``); ``queues[lq][ptr[lq]:]`` are the indices of ``lq``'s gates not yet emitted, in order;
    ``last_on[p]`` is the index in ``emitted`` of the last gate on physical qubit ``p``; ``emitted_window[j]``
    is the window of ``emitted[j]``.
    """

    __slots__ = ("cx_gates", "emitted", "emitted_window", "fuse", "fused", "gates", "last_on", "last_section",
                 "positions", "ptr", "queues", "section_of", "skip", "window_of_gate", "window_of_op")  # fmt: skip

    def __init__(
        self, gates: list[Gate], section_of: list[str], layout: tuple[int, ...], big: int,
        windows: tuple[Sequence[int], Sequence[int]] | None,
    ) -> None:  # fmt: skip
        """Nothing emitted yet, every logical qubit at its ``layout`` position on a device of ``big`` qubits;
        SWAPs are fused only where ``windows`` (each gate's and each routed op's window) is given."""
        n = len(layout)
        queues: list[list[int]] = [[] for _ in range(n)]
        for i, g in enumerate(gates):
            for q in g[1]:
                queues[q].append(i)
        self.gates, self.section_of, self.queues = gates, section_of, queues
        self.positions = Positions(layout, big)
        self.ptr = [0] * n
        self.emitted: list[tuple[str, Gate]] = []
        self.emitted_window: list[Any] = []
        self.last_section = section_of[0] if section_of else "main"
        self.last_on: dict[int, int] = {}  # physical qubit -> index in ``emitted`` of the last gate on it
        self.fused: dict[str, int] = {}  # section -> its SWAPs fused with a cx
        self.skip: set[int] = set()  # ops whose ``cx`` a SWAP before them already emitted (fused)
        self.fuse = windows is not None
        self.window_of_gate: Sequence[Any] = windows[0] if windows is not None else section_of
        self.window_of_op: Sequence[Any] | None = windows[1] if windows is not None else None
        self.cx_gates: dict[tuple[int, int], Gate] = {}  # cx(a, b), made once per pair

    def flush(self, lq: int) -> None:
        """Emit the one-qubit gates pending on logical qubit ``lq`` (those before its next two-qubit gate) at its
        current position."""
        q, k, gates = self.queues[lq], self.ptr[lq], self.gates
        end = len(q)
        if k == end or len(gates[q[k]][1]) != 1:
            return
        p, section_of, window_of_gate = self.positions.where[lq], self.section_of, self.window_of_gate
        emitted, last_on = self.emitted, self.last_on
        emitted_append, window_append = emitted.append, self.emitted_window.append
        new = tuple.__new__  # Gate(...) without the NamedTuple constructor's Python frame: the same value
        while k < end:
            i = q[k]
            g = gates[i]
            if len(g[1]) != 1:
                break
            last_on[p] = len(emitted)
            emitted_append((section_of[i], new(Gate, (g[0], (p,), g[2], g[3]))))
            window_append(window_of_gate[i])
            k += 1
        self.last_section = section_of[q[k - 1]]
        self.ptr[lq] = k

    def two_qubit(self, k: int, p1: int, p2: int) -> None:
        """Routed op ``k``, a ``cx`` on physical ``p1``, ``p2``: the pending one-qubit gates of both logical
        qubits there, then their next two-qubit gate (unless a SWAP before it already emitted it, fused)."""
        who = self.positions.who
        a, b = who[p1], who[p2]
        self.flush(a)
        self.flush(b)
        queues, ptr, gates = self.queues, self.ptr, self.gates
        i = queues[a][ptr[a]]
        if queues[b][ptr[b]] != i or gates[i][1] != (a, b):
            raise AssertionError("the router reordered the gates of a qubit")  # pragma: no cover
        g = gates[i]
        if k not in self.skip:  # emit(section_of[i], Gate(g[0], (p1, p2), g[2], g[3]), window_of_gate[i])
            emitted = self.emitted
            self.last_on[p1] = self.last_on[p2] = len(emitted)
            emitted.append((self.section_of[i], tuple.__new__(Gate, (g[0], (p1, p2), g[2], g[3]))))
            self.emitted_window.append(self.window_of_gate[i])
        self.last_section = self.section_of[i]
        ptr[a] += 1
        ptr[b] += 1

    def emit(self, section: str, g: Gate, window: Any) -> None:
        """Append one gate of ``section`` and ``window``."""
        for q in g[1]:
            self.last_on[q] = len(self.emitted)
        self.emitted.append((section, g))
        self.emitted_window.append(window)

    def fused_with_previous(self, p1: int, p2: int, owner: str, window: Any) -> bool:
        """Fuse a SWAP on ``p1``, ``p2`` with the ``cx`` just before it on both (same window): ``cx a b; SWAP``
        is written ``cx b a; cx a b``. Returns whether it did (else nothing changed)."""
        j = self.last_on.get(p1)
        if not self.fuse or j is None or j != self.last_on.get(p2) or self.emitted_window[j] != window:
            return False
        before = self.emitted[j]
        if before[1][0] != "cx" or set(before[1][1]) != {p1, p2}:
            return False
        a, b = before[1][1]  # cx a b; SWAP (cx a b; cx b a; cx a b) = cx b a; cx a b
        self.emitted[j] = (before[0], cx(b, a))
        self.emit(owner, cx(a, b), window)
        self.fused[owner] = self.fused.get(owner, 0) + 1
        return True

    def fused_with_next(
        self, p1: int, p2: int, owner: str, window: Any, nxt: int, after: tuple[str, tuple[int, int]]
    ) -> bool:
        """Fuse a SWAP on ``p1``, ``p2`` with routed op ``nxt`` (``after``), the next op on either, where it is a
        ``cx`` between them whose gate and pending one-qubit gates all belong to ``window``: the pending gates
        first, then ``SWAP; cx x y`` written ``cx x y; cx y x`` (op ``nxt`` is then skipped). Returns whether it
        did (else nothing changed)."""
        l1, l2 = self.positions.who[p1], self.positions.who[p2]
        if not (self.fuse and after[0] == "cx" and set(after[1]) == {p1, p2} and l1 >= 0 and l2 >= 0):
            return False
        queues, ptr, gates = self.queues, self.ptr, self.gates
        if self.window_of_gate[queues[l1][_next_twoq(queues[l1], ptr[l1], gates)]] != window:
            return False
        if not (self._pending_in(l1, window) and self._pending_in(l2, window)):
            return False
        self.flush(l1)
        self.flush(l2)
        x, y = after[1]  # SWAP (cx x y; cx y x; cx x y); cx x y = cx x y; cx y x
        self.emit(owner, cx(x, y), window)
        self.emit(owner, cx(y, x), window)
        self.skip.add(nxt)
        self.fused[owner] = self.fused.get(owner, 0) + 1
        return True

    def _pending_in(self, lq: int, window: Any) -> bool:
        """Whether every one-qubit gate pending on ``lq`` belongs to ``window``."""
        q, i, gates, window_of_gate = self.queues[lq], self.ptr[lq], self.gates, self.window_of_gate
        while i < len(q) and len(gates[q[i]][1]) == 1:
            if window_of_gate[q[i]] != window:
                return False
            i += 1
        return True

    def three_cx(self, p1: int, p2: int, owner: str, window: Any) -> None:
        """A SWAP fused with nothing: ``cx p1 p2; cx p2 p1; cx p1 p2`` (one ``cx`` value per pair)."""
        forward, backward = self._cx_of(p1, p2), self._cx_of(p2, p1)
        emitted_append, window_append = self.emitted.append, self.emitted_window.append
        emitted_append((owner, forward))
        emitted_append((owner, backward))
        emitted_append((owner, forward))
        window_append(window)
        window_append(window)
        window_append(window)
        self.last_on[p1] = self.last_on[p2] = len(self.emitted) - 1

    def _cx_of(self, a: int, b: int) -> Gate:
        """``cx(a, b)``, made once per pair."""
        g = self.cx_gates.get((a, b))
        if g is None:
            g = self.cx_gates[a, b] = cx(a, b)
        return g


def _next_twoq(queue: Sequence[int], start: int, gates: Sequence[Gate]) -> int:
    """Position in ``queue`` (a qubit's gate indices) of its next two-qubit gate from ``start``."""
    i = start
    while len(gates[queue[i]][1]) == 1:
        i += 1
    return i


def window_cx(ops: Sequence[tuple[str, tuple[int, int]]]) -> int:
    """CX of a window's routed ops (:func:`qcpp.routing.windows.route_window`) as
    :func:`qcpp.routing.windows.route_windows` writes them: 1 per ``cx``, 3 per
    SWAP, 2 fewer per SWAP that :func:`assemble` fuses with a ``cx`` on its pair (the ops alone decide, except
    that one-qubit gates pending from an earlier window keep a SWAP and the ``cx`` after it apart: then this is 2
    below what is written).

    >>> window_cx([("cx", (0, 1)), ("swap", (0, 1)), ("cx", (1, 2))])  # the SWAP fuses with the cx before it
    3
    """
    total = len(ops)
    last: dict[int, int] = {}  # per qubit, its last op so far
    get = last.get
    charged: set[int] = set()  # SWAPs counted 3 so far: no op before them on both qubits
    for k, (name, (p, q)) in enumerate(ops):
        j = get(p)
        both = j is not None and j == get(q)  # the op before this one on both qubits is one op, on this pair
        if name == "swap":
            if not both:
                total += 2
                charged.add(k)
        elif both and name == "cx" and j in charged:  # a cx right after a SWAP on its pair: they fuse
            total -= 2
            charged.discard(j)
        last[p] = last[q] = k
    return total


def dag_cx(dag: Any) -> int:
    """:func:`window_cx` of ``dag_ops(dag)``, read from the runs of operations on one pair instead of every
    operation: a routed DAG of ``cx`` and ``swap`` (one window) counts 1 per operation, plus 2 per SWAP that fuses
    with neither the operation before it on both its qubits nor the ``cx`` after it on both. Qiskit's
    ``collect_2q_runs`` gives the maximal runs of consecutive operations on one pair, in order, so a SWAP has an
    operation before it on both its qubits exactly when it is not the first of its run, and the ``cx`` after it
    on both is the second of its run. The placement search scores thousands of routings by this count alone.

    >>> from qiskit import QuantumCircuit
    >>> from qiskit.converters import circuit_to_dag
    >>> qc = QuantumCircuit(3)
    >>> _ = qc.cx(0, 1), qc.swap(0, 1), qc.swap(1, 2), qc.cx(0, 2)  # the first SWAP fuses, the second not
    >>> dag = circuit_to_dag(qc)
    >>> dag_cx(dag), window_cx(dag_ops(dag))
    (6, 6)
    """
    total = dag.size()
    for run in dag.collect_2q_runs():
        if run[0].name == "swap" and not (len(run) > 1 and run[1].name == "cx"):
            total += 2  # three cx, fused with nothing
    return total


def _next_ops(ops: Sequence[tuple[str, tuple[int, ...]]]) -> list[int | None]:
    """Per op, the index of the next op that touches one of its qubits (``None``: none)."""
    seen: dict[int, int] = {}
    get = seen.get
    out: list[int | None] = [None] * len(ops)
    for k in range(len(ops) - 1, -1, -1):
        qs = ops[k][1]
        if len(qs) == 2:
            p, q = qs
            a, b = get(p), get(q)
            out[k] = b if a is None else a if b is None or not b < a else b  # min of those seen
            seen[p] = seen[q] = k
            continue
        nxt = [seen[q] for q in qs if q in seen]
        out[k] = min(nxt) if nxt else None
        for q in qs:
            seen[q] = k
    return out


def checked_inputs(
    circuit: Circuit, device: Device, initial_layout: Sequence[int], measured: Sequence[int] | None
) -> tuple[list[Gate], list[str], tuple[int, ...], tuple[int, ...]]:
    """Checked inputs of a router: the gates, their section names, the layout, the measured qubits."""
    n, big = circuit.num_qubits, device.num_qubits
    layout = tuple(int(p) for p in initial_layout)
    if n > big:
        raise ValueError(f"the circuit needs {n} qubits; device {device.name} has {big}")
    if len(layout) != n or len(set(layout)) != n or any(not 0 <= p < big for p in layout):
        raise ValueError(f"initial layout must place {n} logical qubits on distinct physical qubits < {big}")
    gates: list[Gate] = []
    section_of: list[str] = []
    for sec in circuit.sections:
        for g in sec.gates:
            if len(g[1]) > 2:
                raise ValueError(f"route needs a lowered circuit; gate {g[0]} acts on {len(g[1])} qubits")
        gates.extend(sec.gates)
        section_of.extend([sec.name] * len(sec.gates))
    if measured is None:
        data = next((r for r in circuit.registers if r.name == "data"), None)
        measured = tuple(range(data.size)) if data is not None and circuit.registers[0] is data else tuple(range(n))
    return gates, section_of, layout, tuple(measured)


def _sectioned(emitted: list[tuple[str, Gate]], num_qubits: int) -> Circuit:
    """The emitted ``(section name, gate)`` pairs as a circuit on one register ``q``, a section per run of a name."""
    sections = [Section(name, [g for _, g in run]) for name, run in groupby(emitted, key=itemgetter(0))]
    return Circuit([Register("q", num_qubits)], sections)
