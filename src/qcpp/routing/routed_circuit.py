"""A circuit routed onto a device's physical qubits, and the device's couplings as Qiskit sees them.

:class:`RoutedCircuit` is what every router of :mod:`qcpp.routing` returns: IR qubit ``i`` is physical qubit ``i``
(so OpenQASM's ``q[i]`` is physical ``i``), with the layouts the routing started and ended with and the SWAPs it
inserted. Routing never reorders the gates of one logical qubit, so the routed circuit equals the original up to
the layouts: ``routed = P_final . original . P_initial^-1`` on inputs whose unused physical qubits are |0>.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> sorted(coupling_map(get_device("grid:1x3")).get_edges())
    [(0, 1), (1, 0), (1, 2), (2, 1)]
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from qcpp.hardware.device import Device
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate

__all__ = ["RoutedCircuit", "coupling_map", "embed_routed", "sabre_target"]


@dataclass(frozen=True)
class RoutedCircuit:
    """A circuit on a device's physical qubits.

    Attributes:
        circuit: IR qubit ``i`` = physical qubit ``i`` (one register ``q`` of ``device.num_qubits``).
        device: The device.
        initial_layout: Logical qubit ``i`` of the input circuit -> physical qubit at the start.
        final_layout: Logical qubit ``i`` -> physical qubit at the end.
        swaps: SWAPs inserted (each three ``cx`` in :attr:`circuit`, or two with the ``cx`` it is fused with).
        measured: Logical qubits measured at the end (the data qubits), for :func:`qcpp.routing.native.esp`.
        fused: Per section name, how many of its SWAPs are fused with a ``cx`` of that section on the same pair
            of qubits (:func:`qcpp.routing.sabre.assemble`: ``cx`` + SWAP is two ``cx``, not four): :attr:`circuit` has
            ``3 swaps - 2 fused`` more ``cx`` than the logical circuit.
    """

    circuit: Circuit
    device: Device
    initial_layout: tuple[int, ...]
    final_layout: tuple[int, ...]
    swaps: int
    measured: tuple[int, ...]
    fused: tuple[tuple[str, int], ...] = ()

    @property
    def active_qubits(self) -> tuple[int, ...]:
        """The physical qubits the circuit acts on or measures, ascending (relay and local-ancilla qubits included,
        so there can be more than the logical circuit's)."""
        used = {q for g in self.circuit.gates for q in g[1]}
        used.update(self.final_layout[lq] for lq in self.measured)
        return tuple(sorted(used))

    @property
    def num_fused(self) -> int:
        """SWAPs fused with a ``cx`` (each saves two ``cx``)."""
        return sum(k for _, k in self.fused)


def embed_routed(routed: RoutedCircuit, device: Device, sites: Sequence[int]) -> RoutedCircuit:
    """``routed`` (on a device whose coupling graph is the subgraph of ``device`` induced by ``sites``, its
    qubit ``i`` on ``sites[i]``) written on ``device``'s qubits: the same gates, SWAPs and layouts, relabelled.

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> from qcpp.ir.gates import cx
        >>> from qcpp.routing.sabre import route
        >>> small = route(Circuit([("data", 2)], [Section("s", [cx(0, 1)])]), get_device("grid:1x2"), (0, 1))
        >>> big = embed_routed(small, get_device("grid:3x3"), [4, 5])
        >>> [g[1] for g in big.circuit.gates], big.initial_layout
        ([(4, 5)], (4, 5))
    """
    to = tuple(sites)
    sections = [Section(sec.name, [Gate(g[0], tuple(to[q] for q in g[1]), g[2], g[3]) for g in sec.gates])
                for sec in routed.circuit.sections]  # fmt: skip
    return RoutedCircuit(Circuit([Register("q", device.num_qubits)], sections), device,
                         tuple(to[p] for p in routed.initial_layout), tuple(to[p] for p in routed.final_layout),
                         routed.swaps, routed.measured, routed.fused)  # fmt: skip


def coupling_map(device: Device) -> Any:
    """The device's couplings as a Qiskit ``CouplingMap`` (both directions)."""
    from qiskit.transpiler import CouplingMap

    edges = [list(e) for e in device.coupling] + [[b, a] for a, b in device.coupling]
    return CouplingMap(edges)


def sabre_target(cmap: Any) -> Any:
    """``Target.from_configuration(basis_gates=["u", "cx"], coupling_map=cmap)``, the target ``SabreSwap(cmap)``
    and (``cmap`` symmetric) ``SabreLayout(cmap)`` build, for a caller that hands one target to many passes or runs:
    the same instructions on the same qubits and couplings, added in the same order (so the same coupling graph,
    whose neighbour order SABRE's choice of SWAP follows), without ``from_configuration``'s table of every standard
    gate, which takes longer to build than a window takes to route.

    >>> from qiskit.transpiler import CouplingMap, Target
    >>> cmap = CouplingMap([[0, 1], [1, 2], [1, 0], [2, 1]])
    >>> reference = Target.from_configuration(basis_gates=["u", "cx"], coupling_map=cmap)
    >>> ours = sabre_target(cmap)
    >>> [(name, list(ours[name])) for name in ours] == [(name, list(reference[name])) for name in reference]
    True
    """
    from qiskit.circuit import Parameter
    from qiskit.circuit.library import CXGate, UGate
    from qiskit.transpiler import Target

    target = Target(num_qubits=len(cmap.graph))
    target.add_instruction(UGate(Parameter("θ"), Parameter("φ"), Parameter("λ")),
                           properties=dict.fromkeys((q,) for q in range(target.num_qubits)), name="u")  # fmt: skip
    target.add_instruction(CXGate(), properties=dict.fromkeys(cmap.get_edges()), name="cx")
    return target
