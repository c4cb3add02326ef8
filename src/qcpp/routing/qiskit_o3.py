"""Qiskit's own preset pipeline as a routing candidate: ``transpile(optimization_level=3)`` onto the device's
calibrated ``Target`` (:func:`qcpp.routing.target.device_target`), read back as a
:class:`~qcpp.routing.routed_circuit.RoutedCircuit` in the device's native gates.

With the calibrated target, Qiskit's O3 lays the circuit out noise-aware (``VF2Layout`` where the circuit embeds
without SWAPs, else ``SabreLayout`` and ``VF2PostLayout``, both scored by the target's errors), routes with SABRE and
optimises (two-qubit block resynthesis, one-qubit merging). Compile keeps it as one candidate beside its own routings
(:mod:`qcpp.pipeline.candidates`), so the routed circuit is never worse than Qiskit's by the figure the user picks.
:func:`qiskit_optimized` runs only that pipeline's optimisation on a routing of ours, at its own layout.

The circuit goes to Qiskit as written (lowered gates; symbols as Qiskit ``Parameter``\\s, read back as the same
affine angles) without measurements, so O3 keeps the whole unitary (a final measurement would let it drop diagonal
gates before it): the result equals the input up to the layouts, as every routed circuit of :mod:`qcpp.routing`.
``sx`` is read back as ``rx(pi/2)`` (the IR's name for it, :mod:`qcpp.routing.native`; equal up to a global
phase). The SWAPs Qiskit inserted are counted from the circuit between its routing and its translation stage.

Example:
    >>> from qcpp.hardware.device import get_device
    >>> from qcpp.ir.circuit import Circuit, Section
    >>> from qcpp.ir.gates import cx, h
    >>> c = Circuit([("data", 3)], [Section("s", [h(0), cx(0, 1), cx(0, 2), cx(1, 2)])])
    >>> r = qiskit_o3(c, get_device("ibm_fez"), seed=0)
    >>> sorted(r.circuit.count_ops()), r.circuit.num_qubits, len(r.initial_layout)
    (['cz', 'rx', 'rz'], 156, 3)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from qcpp.hardware.device import Device
from qcpp.ir.angles import Angle
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import Gate, cz, rx, x
from qcpp.routing.routed_circuit import RoutedCircuit
from qcpp.routing.target import device_target

__all__ = ["from_qiskit_angle", "qiskit_o3", "qiskit_o3_seeds", "qiskit_optimized", "to_qiskit_lowered"]

_SIMPLE = {"x", "h", "t", "tdg", "s", "sdg", "cx", "cz", "sx"}
_ANGLED = {"rz", "rx", "ry", "rzz"}
_STANDARD = {"x": "X", "h": "H", "t": "T", "tdg": "Tdg", "s": "S", "sdg": "Sdg", "cx": "CX", "cz": "CZ", "sx": "SX",
             "rz": "RZ", "rx": "RX", "ry": "RY", "rzz": "RZZ"}  # fmt: skip


def to_qiskit_lowered(circuit: Circuit) -> Any:
    """A Qiskit circuit of a lowered circuit (one- and two-qubit gates of :data:`_SIMPLE` and :data:`_ANGLED`), an
    unbound symbol as the Qiskit ``Parameter`` of the same name.

    The circuit equals the one ``qc.<name>(*angles, *qubits)`` would build gate by gate: each gate is appended as
    the same standard-gate instruction those methods append, without their argument checks where the qubits are
    distinct indices of the circuit (any other gate goes through the method, which reports the error).

    Raises:
        ValueError: a gate this converter does not know.
    """
    from qiskit import QuantumCircuit
    from qiskit._accelerate.circuit import StandardGate
    from qiskit.circuit import CircuitInstruction, Parameter

    params: dict[str, Any] = {}

    def angle(value: Any) -> Any:
        if not isinstance(value, Angle) or not value.terms:
            return float(value)
        out: Any = value.constant
        for name, coeff in value.terms:
            out = out + coeff * params.setdefault(name, Parameter(name))
        return out

    qc = QuantumCircuit(circuit.num_qubits)
    bits = dict(enumerate(qc.qubits))
    standard = {name: getattr(StandardGate, _STANDARD[name]) for name in (*_SIMPLE, *_ANGLED)}
    fixed: dict[tuple[str, tuple[int, ...]], Any] = {}  # an unparametrised instruction, once per qubit tuple
    from_standard, append = CircuitInstruction.from_standard, qc._append
    for name, qubits, params_, _ in circuit.gates:
        if name in _SIMPLE:
            inst = fixed.get((name, qubits))
            if inst is None:
                try:
                    bs = tuple([bits[q] for q in qubits])
                except (KeyError, TypeError):
                    bs = ()
                if len(set(bs)) != len(qubits) or len(qubits) != (2 if name in ("cx", "cz") else 1):
                    getattr(qc, name)(*qubits)  # raises Qiskit's error for these qubits
                    continue
                inst = fixed[name, qubits] = from_standard(standard[name], bs, ())
            append(inst, _standard_gate=True)
        elif name in _ANGLED:
            try:
                bs = tuple([bits[q] for q in qubits])
            except (KeyError, TypeError):
                bs = ()
            if len(set(bs)) != len(qubits) or len(qubits) != (2 if name == "rzz" else 1):
                getattr(qc, name)(angle(params_[0]), *qubits)  # raises Qiskit's error for these qubits
                continue
            append(from_standard(standard[name], bs, [angle(params_[0])]), _standard_gate=True)
        else:
            raise ValueError(f"to_qiskit_lowered: no Qiskit form for gate {name!r} (lower the circuit first)")
    return qc


def from_qiskit_angle(value: Any) -> float | Angle:
    """A Qiskit gate parameter as the IR's angle: a float, or an affine :class:`~qcpp.ir.angles.Angle` of the
    expression's parameters.

    Raises:
        ValueError: the expression is not affine in its parameters.

    >>> from qiskit.circuit import Parameter
    >>> g = Parameter("gamma_0")
    >>> from_qiskit_angle(0.5 - 2 * g)
    Angle('-2.0*gamma_0 + 0.5')
    """
    if type(value) is float:
        return value  # float(value) would return this very object
    from qiskit.circuit import ParameterExpression

    if not isinstance(value, ParameterExpression) or not value.parameters:
        return float(value)
    zero = {p: 0.0 for p in value.parameters}
    constant = float(value.bind(zero))
    terms = []
    for p in value.parameters:
        grad = value.gradient(p)
        if isinstance(grad, ParameterExpression) and grad.parameters:
            raise ValueError(f"from_qiskit_angle: {value} is not affine in {p}")
        terms.append((p.name, float(grad)))
    return Angle(constant, terms)


def _routed_gates(qc: Any) -> list[Gate]:
    """The native gates of a circuit Qiskit translated to the target (``cz rz sx x``, or ``rzz rx``).

    Read by each instruction's name, qubits and parameters (no Qiskit gate object is built), and the unparametrised
    gates (a routed circuit repeats its ``cz`` and ``sx`` on the same qubits) made once for each qubit tuple. The
    gates equal those of :func:`~qcpp.ir.gates.rz`, :func:`~qcpp.ir.gates.rx`, :func:`~qcpp.ir.gates.cz`,
    :func:`~qcpp.ir.gates.x` on the instruction's qubit indices, angles read by :func:`from_qiskit_angle`.
    """
    out: list[Gate] = []
    append = out.append
    index = {q: i for i, q in enumerate(qc.qubits)}
    fixed: dict[tuple[str, tuple[Any, ...]], Gate] = {}  # by name and Qiskit qubits
    new = tuple.__new__
    for inst in qc.data:
        name, qubits = inst.name, inst.qubits
        if name == "rz" or name == "rx":
            theta = inst.params[0]
            if type(theta) is not float:
                theta = from_qiskit_angle(theta)
            append(new(Gate, (name, (index[qubits[0]],), (theta,), None)))  # rz / rx without the input checks
            continue
        if name in ("cz", "sx", "x"):
            g = fixed.get((name, qubits))
            if g is None:
                qs = tuple([index[q] for q in qubits])
                g = cz(*qs) if name == "cz" else rx(math.pi / 2, qs[0]) if name == "sx" else x(qs[0])
                fixed[name, qubits] = g
            append(g)
            continue
        qs = tuple([index[q] for q in qubits])
        if name == "rzz":
            append(Gate("rzz", qs, (from_qiskit_angle(inst.params[0]),), None))
        elif name in ("barrier", "delay"):
            continue
        else:
            raise ValueError(f"qiskit_o3: Qiskit wrote {name!r}, not a native gate of the target")
    return out


def qiskit_o3(
    circuit: Circuit, device: Device, seed: int = 0, measured: Sequence[int] | None = None
) -> RoutedCircuit:
    """``transpile(circuit, target=device_target(device), optimization_level=3, seed_transpiler=seed)`` as a routed
    circuit in native gates (module docs).

    Args:
        circuit: A lowered circuit on at most ``device.num_qubits`` qubits.
        device: The target device.
        seed: Qiskit's ``seed_transpiler``.
        measured: Logical qubits measured at the end (default: the ``data`` register, else all).

    Returns:
        The routed circuit (``initial_layout`` / ``final_layout`` from Qiskit's ``TranspileLayout``).
    """
    return qiskit_o3_seeds(circuit, device, (seed,), measured)[0]


def qiskit_o3_seeds(
    circuit: Circuit, device: Device, seeds: Sequence[int], measured: Sequence[int] | None = None
) -> list[RoutedCircuit]:
    """:func:`qiskit_o3` at each of ``seeds``, in order; the circuit goes to Qiskit once (``transpile`` leaves its
    input as it was), so several seeds cost only their transpiles.

    Args:
        circuit: A lowered circuit on at most ``device.num_qubits`` qubits.
        device: The target device.
        seeds: Qiskit ``seed_transpiler`` values, one routed circuit each.
        measured: Logical qubits measured at the end (default: the ``data`` register, else all).

    Returns:
        The routed circuits, one per seed, in the order of ``seeds``.

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> from qcpp.ir.gates import cx
        >>> c = Circuit([("data", 3)], [Section("s", [cx(0, 1), cx(0, 2), cx(1, 2)])])
        >>> dev = get_device("ibm_fez")
        >>> qiskit_o3_seeds(c, dev, (0, 1)) == [qiskit_o3(c, dev, 0), qiskit_o3(c, dev, 1)]
        True
    """
    from qiskit import transpile

    if measured is None:
        data = next((r.size for r in circuit.registers if r.name == "data"), circuit.num_qubits)
        measured = range(data)
    qc = to_qiskit_lowered(circuit)
    target = device_target(device)
    n = circuit.num_qubits
    out = []
    for seed in seeds:
        swaps: list[int] = []

        def count_swaps(pass_: Any, dag: Any, swaps: list[int] = swaps, **_: Any) -> None:
            k = dag.count_ops().get("swap", 0)
            if k:
                swaps.append(k)

        done = transpile(qc, target=target, optimization_level=3, seed_transpiler=seed, callback=count_swaps)
        initial = tuple(done.layout.initial_index_layout(filter_ancillas=True)[:n]) if done.layout else tuple(range(n))
        final = tuple(done.layout.final_index_layout(filter_ancillas=True)[:n]) if done.layout else initial
        routed = Circuit([Register("q", device.num_qubits)], [Section("qiskit_o3", _routed_gates(done))])
        out.append(RoutedCircuit(routed, device, initial, final, swaps[-1] if swaps else 0, tuple(measured)))
    return out


def qiskit_optimized(routed: RoutedCircuit) -> RoutedCircuit:
    """A routed circuit (CX + one-qubit gates, on the couplings of its device) after Qiskit's O3 optimisation at
    its own layout, in the device's native gates: ``transpile`` onto the calibrated target with the trivial initial
    layout and no routing, so only the optimisation and translation stages change it (two-qubit blocks resynthesised,
    runs of one-qubit gates merged into at most two ``sx``, gates that cancel removed). Every qubit stays where it
    was, so the layouts (and SWAP count) are ``routed``'s, and the result equals ``routed`` up to a global phase.

    Why: gate by gate (:func:`qcpp.routing.native.to_native`), every ``cx`` brings its own Hadamards and every ``h``,
    ``t``, ``s`` its own pulses; merged, a routed circuit has fewer and shorter one-qubit layers, so fewer gate
    errors and less idle time.

    Args:
        routed: A routed circuit in CX and one-qubit gates (:data:`_SIMPLE`, :data:`_ANGLED`).

    Returns:
        The optimised routed circuit.

    Raises:
        RuntimeError: Qiskit moved a qubit (it must not: no layout or routing stage runs).

    Example:
        >>> from qcpp.hardware.device import get_device
        >>> from qcpp.ir.gates import cx, h
        >>> from qcpp.routing.native import to_native
        >>> dev = get_device("ibm_fez")
        >>> c = Circuit([Register("q", dev.num_qubits)], [Section("s", [h(1), cx(0, 1), cx(0, 1), h(1)])])
        >>> r = RoutedCircuit(c, dev, (0, 1), (0, 1), 0, (0, 1))
        >>> sum(to_native(r).circuit.count_ops().values()), sum(qiskit_optimized(r).circuit.count_ops().values())
        (20, 0)
    """
    from qiskit import transpile

    device = routed.device
    qc = to_qiskit_lowered(routed.circuit)
    trivial = list(range(qc.num_qubits))
    done = transpile(qc, target=device_target(device), optimization_level=3, initial_layout=trivial,
                     routing_method="none", seed_transpiler=0)  # fmt: skip
    if done.layout is not None and (list(done.layout.initial_index_layout()) != trivial
                                     or list(done.layout.final_index_layout()) != trivial):  # fmt: skip
        raise RuntimeError("qiskit_optimized: Qiskit moved qubits of a routed circuit")
    circuit = Circuit(routed.circuit.registers, [Section("qiskit_optimized", _routed_gates(done))])
    return RoutedCircuit(circuit, device, routed.initial_layout, routed.final_layout, routed.swaps, routed.measured)
