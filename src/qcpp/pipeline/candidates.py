"""Routed candidates on a named device, and the choice among them by the figure the user asks for.

On a named device (a calibration snapshot or a published spec sheet: per-qubit and per-coupler errors), compile
does not stop at its own routing. :func:`calibrated_candidates` collects:

* ``qcpp``: the routing of compile's own path, and, on circuits small enough for the placement search, the next
  cheapest routings of that search (``qcpp #2`` ...: a few more two-qubit gates on other qubits may run with fewer
  errors), written gate by gate in native gates (:func:`qcpp.routing.native.to_native`);
* ``qcpp + O3 passes`` (``qcpp #2 + O3 passes`` ...): each of those after Qiskit's O3 optimisation at its own
  layout (:func:`qcpp.routing.qiskit_o3.qiskit_optimized`: one-qubit runs merged, two-qubit blocks resynthesised;
  fewer and shorter gates, so fewer errors and less idle time), its SWAPs first written the way round whose ``cx``
  cancel by commutation with the circuit's (:func:`qcpp.routing.swap_orientation.orient_swaps`: the same operator,
  fewer CZ after the passes), where Qiskit candidates are asked for;
* ``qcpp + from |0> + O3 passes`` (``qcpp #2 + from |0> + O3 passes`` ...): the same, with every ``cx`` whose
  control is in a known basis state on the device's all-|0> start removed or written as ``x`` before the passes
  (:func:`qcpp.routing.known_state.from_zero`: the robots' start is a basis state, so the first partial mixers and
  the SWAPs into qubits still in |0> have many; at p = 1 the whole first phase separator acts on that basis state,
  a global phase); these equal the logical circuit on the all-|0> input the device runs from, not as a unitary on
  every input (no gates may run before them), so compile offers them only when asked, ``--zero-start``
  (``from_zero_start``), with either figure;
* ``cells on heavy-hex:D + our placement`` (``#2``; ``+ O3 passes``): on IBM's heavy-hex devices, the cell layout
  routed on the abstract lattice ``heavy-hex:D`` (where it is laid out by construction) and placed on the best
  embeddings of its coupling subgraph in the device, where it has one (the cells of a one-robot 3x3 or 3x4 grid
  fit; larger routings use more qubits than the search takes, reach the lattice's edges, whose 10-cycles IBM's
  lattice lacks, or need room around their cells that the device's shape and defects do not give);
* ``search on heavy-hex:D + our placement`` (``#2``; ``+ O3 passes``): on the same devices, for circuits the
  placement search takes, the greedy path's routing on each abstract lattice ``heavy-hex:D`` that holds the circuit
  (its own placement search and partial-mixer choice there), placed the same way where it embeds (these and the
  cells' placements also ``+ from |0> + O3 passes``);
* ``qiskit O3 seed s``: Qiskit's own ``transpile(optimization_level=3)`` onto the calibrated target, seeds
  ``0 .. QISKIT_SEEDS - 1`` (:func:`qcpp.routing.qiskit_o3.qiskit_o3`), so the result is never worse than
  Qiskit's by the chosen figure;
* ``... + our placement`` (``#2`` ...): each of those moved onto the best embeddings of its coupling subgraph by
  our ESP model (:func:`qcpp.routing.noise_aware.embedding_sites`: the same gates on better qubits and couplers).

:func:`choose` keeps the best by ``optimize_for`` (:data:`OPTIMIZE_FOR`): ``esp`` the highest ESP (with idle
decoherence, :func:`qcpp.routing.native.esp_idle`, where the device has T1 / T2; else the gate-only
:func:`~qcpp.routing.native.esp`), ties to fewer two-qubit gates; ``twoq`` the fewest two-qubit gates, ties to the
higher ESP; remaining ties to the first candidate in the order above. :func:`default_objective` is ``esp`` on named
devices and ``twoq`` on the families (``grid``, ``heavy-hex``, ``all-to-all``: uniform figures, where the count
decides), where compile keeps its single routing.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> default_objective(get_device("ibm_fez")), default_objective(get_device("heavy-hex:5"))
    ('esp', 'twoq')
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

from qcpp.hardware.device import Device, device_label, device_names, get_device, is_named
from qcpp.ir.circuit import Circuit
from qcpp.routing.known_state import from_zero
from qcpp.routing.native import esp, esp_idle, to_native
from qcpp.routing.noise_aware import embedding_sites
from qcpp.routing.qiskit_o3 import qiskit_o3_seeds, qiskit_optimized
from qcpp.routing.routed_circuit import RoutedCircuit, embed_routed
from qcpp.routing.swap_orientation import orient_swaps

__all__ = [
    "FROM_ZERO", "OPTIMIZE_FOR", "QISKIT_SEEDS", "RoutedCandidate", "calibrated_candidates", "choose",
    "default_objective", "figure_key", "is_calibrated", "zero_start_refusal",
]

OPTIMIZE_FOR = ("esp", "twoq")
"""Figures compile can optimise for: ``esp`` (success probability) or ``twoq`` (two-qubit gates)."""

QISKIT_SEEDS = 3
"""Qiskit O3 runs per compile on a named device (``seed_transpiler`` 0, 1, 2)."""

FROM_ZERO = "from |0>"
"""The part of a candidate's name that marks it simplified for the all-|0> start (equal to the logical circuit on
that input only)."""


@dataclass(frozen=True)
class RoutedCandidate:
    """One routed circuit compile may return.

    Attributes:
        name: Where it comes from (``qcpp``, ``qcpp #2 + our placement``, ``qiskit O3 seed 1``).
        native: The routed circuit in the device's native gates.
        lowered: The same routing in CX + one-qubit gates (``None``: the candidate exists only in native gates:
            Qiskit's routing, or ours after Qiskit's optimisation).
        logical: The logical circuit its layouts index, where that is not the one compile's own routings route
            (``None``): Qiskit's routings index the lowered compiled circuit, the cells' routing its circuit with
            local ancillas.
    """

    name: str
    native: RoutedCircuit
    lowered: RoutedCircuit | None = None
    logical: Circuit | None = None

    @cached_property
    def twoq(self) -> int:
        """Native two-qubit gates."""
        return sum(1 for g in self.native.circuit.gates if len(g[1]) == 2)

    @cached_property
    def esp(self) -> float:
        """Gate-only ESP (:func:`qcpp.routing.native.esp`)."""
        return esp(self.native)

    @cached_property
    def esp_idle(self) -> float | None:
        """ESP with idle decoherence (:func:`qcpp.routing.native.esp_idle`; ``None``: no T1 / T2)."""
        return esp_idle(self.native, gate_esp=self.esp)

    def summary(self) -> dict[str, object]:
        """JSON-ready ``{name, two_qubit, esp, esp_idle}``."""
        return {"name": self.name, "two_qubit": self.twoq, "esp": self.esp, "esp_idle": self.esp_idle}


def is_calibrated(device: Device) -> bool:
    """A named device (shipped or from a device file: its own figures per qubit and coupler), not a family
    member, not all-to-all (nothing to place: every pair is coupled)."""
    return is_named(device) and not device.is_all_to_all


def zero_start_refusal(device: str | Device | None, lowered: bool, lowered_field: str = "lowered") -> str | None:
    """Why compile's ``zero_start`` (the ``+ from |0>`` candidates) does not apply to a compile onto ``device``, in
    one line after the option's name; ``None`` where it applies: on a named device with couplers
    (:func:`is_calibrated`: where compile chooses among candidates), for the native-gate circuit (those candidates
    exist after Qiskit's passes only, so not ``lowered``, which ``lowered_field`` names).

    Example:
        >>> zero_start_refusal("ibm_fez", False) is None
        True
        >>> zero_start_refusal("grid", False)
        'applies with a named device with couplers only (google_willow, ibm_fez, ibm_torino, a device file), not grid'
    """
    if device is None:
        return "applies with a named device only (no device given)"
    if not is_calibrated(get_device(device)):
        named = [n for n in sorted(device_names()) if is_calibrated(get_device(n))]
        return (f"applies with a named device with couplers only ({', '.join(named)}, a device file), not "
                f"{device_label(device)}")  # fmt: skip
    if lowered:
        return (f"applies to the native-gate circuit only, not with {lowered_field} (its candidates are after "
                "Qiskit's passes)")  # fmt: skip
    return None


def default_objective(device: Device) -> str:
    """``esp`` on named devices, ``twoq`` on the families (module docs)."""
    return "esp" if is_named(device) else "twoq"


def figure_key(two_qubit: int, esp: float, esp_idle: float | None, optimize_for: str) -> tuple[float, float]:
    """The sort key :func:`choose` maximises: by ``optimize_for``, the ESP (with idle decoherence where known) then
    fewer two-qubit gates, or fewer two-qubit gates then the ESP. Also for a candidate read from ``--json``."""
    figure = esp if esp_idle is None else esp_idle
    log = math.log(figure) if figure > 0 else -math.inf
    return (log, -two_qubit) if optimize_for == "esp" else (-two_qubit, log)


def _key(c: RoutedCandidate, optimize_for: str) -> tuple[float, float]:
    return figure_key(c.twoq, c.esp, c.esp_idle, optimize_for)


def choose(candidates: Sequence[RoutedCandidate], optimize_for: str) -> RoutedCandidate:
    """The best candidate by ``optimize_for`` (module docs; ties: the first).

    Raises:
        ValueError: no candidates, or an unknown figure.

    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx
    >>> from qcpp.routing.sabre import route
    >>> dev = get_device("ibm_fez")
    >>> c = Circuit([("data", 2)], [Section("s", [cx(0, 1)])])
    >>> bad, good = (RoutedCandidate(n, to_native(route(c, dev, lay))) for n, lay in (("a", (0, 2)), ("b", (0, 1))))
    >>> choose([bad, good], "esp").name, choose([bad, good], "twoq").name
    ('b', 'b')
    """
    if optimize_for not in OPTIMIZE_FOR:
        raise ValueError(f"optimize for one of {', '.join(OPTIMIZE_FOR)}, not {optimize_for!r}")
    if not candidates:
        raise ValueError("choose: no candidates")
    return max(enumerate(candidates), key=lambda ic: (_key(ic[1], optimize_for), -ic[0]))[1]


def calibrated_candidates(
    ours: Sequence[RoutedCircuit],
    device: Device,
    qiskit_circuit: Circuit | None = None,
    measured: Sequence[int] | None = None,
    qiskit_seeds: int = QISKIT_SEEDS,
    elsewhere: Sequence[tuple[str, Circuit, RoutedCircuit]] = (),
    from_zero_start: bool = False,
) -> list[RoutedCandidate]:
    """The candidates of the module docs.

    Args:
        ours: Compile's own routings on ``device``, its choice first (CX + one-qubit gates, or native).
        device: The named device.
        qiskit_circuit: The lowered logical circuit for Qiskit's O3 (``None``: no Qiskit candidates, neither
            Qiskit's routings nor ours after Qiskit's optimisation: those exist in native gates only).
        measured: Logical qubits measured at the end.
        qiskit_seeds: Qiskit O3 seeds.
        elsewhere: ``(name, logical circuit, routing)`` of routings on another device (CX + one-qubit gates: the
            cell layout on a ``heavy-hex:D`` lattice), each placed on ``device`` where its couplers embed.
        from_zero_start: Also the ``+ from |0> + O3 passes`` candidates (with ``qiskit_circuit``; compile asks for
            them with ``--zero-start``: equal to the logical circuit on the all-|0> input only).

    Returns:
        The candidates, in the order of the module docs.
    """
    found: dict[object, list[tuple[int, ...]]] = {}  # VF2's embeddings per coupling subgraph, shared by this call

    def placements(name: str, native: RoutedCircuit, lowered: RoutedCircuit | None = None,
                   logical: Circuit | None = None) -> list[RoutedCandidate]:  # fmt: skip
        """The same gates on each of the best embeddings of ``native``'s couplers in ``device`` (``name + our
        placement``, ``#2``); ``native`` may be routed on another lattice."""
        placed = []
        for j, sites in enumerate(embedding_sites(native, device, found_memo=found)):
            label = f"{name} + our placement" + (f" #{j + 1}" if j else "")
            moved = None if lowered is None else embed_routed(lowered, device, sites)
            placed.append(RoutedCandidate(label, embed_routed(native, device, sites), moved, logical))
        return placed

    def with_placements(name: str, native: RoutedCircuit, lowered: RoutedCircuit | None = None,
                        logical: Circuit | None = None) -> list[RoutedCandidate]:  # fmt: skip
        """The candidate ``name`` (on ``device``) and its :func:`placements`."""
        return [RoutedCandidate(name, native, lowered, logical), *placements(name, native, lowered, logical)]

    names = ["qcpp" if i == 0 else f"qcpp #{i + 1}" for i in range(len(ours))]
    out: list[RoutedCandidate] = []
    for name, routed in zip(names, ours, strict=True):
        out += with_placements(name, to_native(routed), routed)
    if qiskit_circuit is not None:
        for name, routed in zip(names, ours, strict=True):
            oriented = orient_swaps(routed)
            out += with_placements(f"{name} + O3 passes", qiskit_optimized(oriented))
            if from_zero_start:
                out += with_placements(f"{name} + from |0> + O3 passes", qiskit_optimized(from_zero(oriented)))
    for name, logical, routed in elsewhere:
        for placed in placements(name, to_native(routed), routed, logical):
            out.append(placed)
            if qiskit_circuit is not None and placed.lowered is not None:
                oriented = orient_swaps(placed.lowered)
                out.append(RoutedCandidate(f"{placed.name} + O3 passes", qiskit_optimized(oriented), None, logical))
                if from_zero_start:
                    out.append(RoutedCandidate(f"{placed.name} + from |0> + O3 passes",
                                               qiskit_optimized(from_zero(oriented)), None, logical))  # fmt: skip
    if qiskit_circuit is not None:
        for seed, theirs in enumerate(qiskit_o3_seeds(qiskit_circuit, device, range(qiskit_seeds), measured)):
            out += with_placements(f"qiskit O3 seed {seed}", theirs, logical=qiskit_circuit)
    return out
