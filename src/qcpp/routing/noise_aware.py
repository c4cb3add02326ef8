"""Noise-aware placement of a routed circuit on a calibrated device: the same gates on better qubits.

A routed circuit uses a subgraph of a coupling graph (the couplers its two-qubit gates act on). Any embedding of
that subgraph into a device's coupling graph runs the same gates, with the same SWAPs, on other qubits and
couplers; on a calibrated device (per-qubit and per-coupler errors) some embeddings are far better than others.
:func:`embeddings` asks Qiskit's ``VF2PostLayout`` (VF2++ subgraph isomorphism, scored by the calibrated
``Target``'s errors weighted by how often the circuit uses each qubit and coupler,
:func:`qcpp.routing.target.device_target`) for the best embedding it finds within its call limit, for several
seeds. :func:`post_layout` keeps, of those on the circuit's own device, the one of the highest ESP by our own
model (:func:`log_score`: with idle decoherence where the device has T1 / T2), or the circuit as it was if none is
better; :func:`embed_in` moves a circuit routed on another lattice (a geometric layout on ``heavy-hex:D``) onto a
named device's best region. A relabelled circuit is the routed circuit with every physical qubit renamed
(:func:`qcpp.routing.routed_circuit.embed_routed`): gate for gate the same, so equal to the input up to the new
layouts.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx, h
    >>> from qcpp.routing.native import esp, to_native
    >>> from qcpp.routing.sabre import route
    >>> dev = get_device("ibm_fez")
    >>> c = Circuit([("data", 3)], [Section("s", [h(0), cx(0, 1), cx(1, 2)])])
    >>> r = to_native(route(c, dev, (0, 1, 2)))
    >>> better = post_layout(r)
    >>> esp(better) >= esp(r), better.circuit.count_ops() == r.circuit.count_ops()
    (True, True)
"""

from __future__ import annotations

import math

from qcpp.hardware.device import Device
from qcpp.routing.native import esp, esp_idle
from qcpp.routing.routed_circuit import RoutedCircuit, embed_routed
from qcpp.routing.target import device_target

__all__ = ["POST_LAYOUT_SEEDS", "embed_in", "embeddings", "log_score", "post_layout"]

POST_LAYOUT_SEEDS = 3
"""``VF2PostLayout`` seeds tried (each a different search order through the embeddings)."""


def log_score(routed: RoutedCircuit) -> float:
    """Natural log of the ESP :func:`post_layout` maximises: with idle decoherence where the device has T1 / T2."""
    value = esp_idle(routed)
    value = esp(routed) if value is None else value
    return math.log(value) if value > 0 else -math.inf


def embeddings(
    routed: RoutedCircuit, device: Device, seeds: int = POST_LAYOUT_SEEDS, call_limit: int = 3_000_000
) -> list[RoutedCircuit]:
    """``routed`` (native gates) written on ``device`` at each distinct embedding ``VF2PostLayout`` picks, one
    search per seed (module docs); empty if its coupling subgraph does not embed (or ``routed`` has more qubits).

    Args:
        routed: A routed circuit in native gates (its device's two-qubit gate is read as ``device``'s).
        device: The device to embed it in (not all-to-all).
        seeds: ``VF2PostLayout`` seeds tried.
        call_limit: VF2's state-visit limit per seed (bounds its time on large circuits).
    """
    from qiskit import QuantumCircuit
    from qiskit.converters import circuit_to_dag
    from qiskit.transpiler import Layout
    from qiskit.transpiler.passes import VF2PostLayout

    n = device.num_qubits
    if device.is_all_to_all or routed.circuit.num_qubits > n:
        return []
    qc = QuantumCircuit(n)
    for g in routed.circuit.gates:
        qs = g[1]
        if len(qs) == 2:
            qc.cz(*qs)
        elif g[0] != "rz":  # virtual: no error, nothing to place by
            qc.sx(qs[0])
    dag = circuit_to_dag(qc)
    target = device_target(device)
    seen: set[tuple[int, ...]] = set()
    out = []
    for seed in range(seeds):
        vf2 = VF2PostLayout(target=target, seed=seed, strict_direction=False, call_limit=call_limit)
        vf2.property_set["layout"] = Layout.generate_trivial_layout(*qc.qregs)
        vf2.run(dag)
        found = vf2.property_set.get("post_layout")
        if found is None:
            continue
        sites = tuple(found[qc.qubits[i]] for i in range(routed.circuit.num_qubits))
        if sites not in seen:
            seen.add(sites)
            out.append(embed_routed(routed, device, sites))
    return out


def post_layout(routed: RoutedCircuit, seeds: int = POST_LAYOUT_SEEDS, call_limit: int = 3_000_000) -> RoutedCircuit:
    """``routed`` (native gates) moved onto the best-scoring embedding found of its coupling subgraph on its own
    device, or ``routed`` itself where none scores higher (module docs; arguments as :func:`embeddings`)."""
    best, best_score = routed, log_score(routed)
    for moved in embeddings(routed, routed.device, seeds, call_limit):
        score = log_score(moved)
        if score > best_score:
            best, best_score = moved, score
    return best


def embed_in(
    routed: RoutedCircuit, device: Device, seeds: int = POST_LAYOUT_SEEDS, call_limit: int = 3_000_000
) -> RoutedCircuit | None:
    """``routed`` (native gates, routed on another device, e.g. a ``heavy-hex:D`` lattice) on ``device``'s
    best-scoring embedding found of its coupling subgraph, or ``None`` where none was found (arguments as
    :func:`embeddings`)."""
    found = embeddings(routed, device, seeds, call_limit)
    return max(found, key=log_score) if found else None
