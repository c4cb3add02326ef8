"""``qcpp.compile``: the QAOA circuit of a scenario, optionally lowered, bound and routed onto a device.

The circuit is built by the code ``qcpp compile`` runs (:func:`qcpp.plan.compile.compile_scenario`, and with a
device :func:`qcpp.pipeline.device_compile.compile_for_device`), so :meth:`Compiled.counts` and
:meth:`Compiled.to_dict` equal that command's ``--json`` for the same scenario and options (timing aside), and
:meth:`Compiled.to_qasm` its ``--qasm`` file.

Example:
    >>> from qcpp.api.scenarios import grid_scenario
    >>> c = compile(grid_scenario(3, 3, robots=1), lowered=True, bind={"gamma_0": 0.3})
    >>> c.qubits, c.counts()["cx"], c.symbols
    (15, 106, ('beta_0',))
    >>> c.to_qasm(version=2)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    qcpp.ir.angles.UnboundParameterError: unbound symbols (...): beta_0; bind them first
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from qcpp.api.checks import check_context_arg, check_layers_arg, check_scenario_arg, plan_options_arg
from qcpp.api.progress import ProgressArg, check_progress_arg, reporting
from qcpp.api.scenarios import Scenario
from qcpp.errors import OptionError, check_choice, check_count
from qcpp.problem.limits import API_OVERRIDE

if TYPE_CHECKING:
    from qcpp.api.decoding import DecodedCounts
    from qcpp.hardware.device import Device
    from qcpp.ir.circuit import Circuit
    from qcpp.routing.context import RoutingContext
    from qcpp.routing.routed_circuit import RoutedCircuit

__all__ = ["Compiled", "compile"]

QASM_VERSIONS = (3, 2)


@dataclass(frozen=True)
class Compiled:
    """A compiled QAOA circuit.

    Attributes:
        scenario: The scenario compiled.
        p: QAOA layers.
        circuit: The circuit (:class:`qcpp.ir.circuit.Circuit`): high level, lowered to
            ``{cx, x, h, rz, t, tdg, s, sdg}``, or routed (qubit ``i`` = the device's physical qubit ``i``; the
            device's native gates unless ``lowered``).
        lowered: Whether the circuit was lowered.
        device: The device routed onto, or ``None``.
        initial_layout: With a device: logical qubit ``i`` -> physical qubit at the start (else ``None``).
        final_layout: With a device: logical qubit ``i`` -> physical qubit at the end (else ``None``).

    With ``zero_start=True`` the circuit may equal the logical one on the all-|0> input only
    (:attr:`equal_on_every_input`): run it as it is, with no gates before it.
    """

    scenario: Scenario
    p: int
    circuit: Circuit
    lowered: bool
    device: Device | None = None
    initial_layout: list[int] | None = None
    final_layout: list[int] | None = None
    _summary: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)
    _routed: RoutedCircuit | None = field(default=None, repr=False, compare=False)

    @property
    def qubits(self) -> int:
        """Qubits of the circuit (with a device: the device's)."""
        return self.circuit.num_qubits

    @property
    def symbols(self) -> tuple[str, ...]:
        """The unbound angle symbols (``gamma_0``, ``beta_0``, ...), in layer order."""
        return self.circuit.symbols

    @property
    def esp(self) -> float | None:
        """With a device: the estimated success probability of the routed circuit, the product of (1 - error) over
        its native gates and the read-outs of the data qubits (``qcpp compile --json``'s ``routed.esp``); else
        ``None``."""
        return self._summary["routed"]["esp"] if self.device is not None else None

    @property
    def esp_idle(self) -> float | None:
        """With a device that publishes T1 / T2: :attr:`esp` times the idle decoherence of the scheduled circuit
        (``routed.esp_idle``); else ``None``."""
        return self._summary["routed"]["esp_idle"] if self.device is not None else None

    @property
    def zero_start(self) -> bool:
        """Whether it was compiled with ``zero_start=True`` (routings simplified for the all-|0> start offered)."""
        return bool(self._summary["routed"]["zero_start"]) if self.device is not None else False

    @property
    def equal_on_every_input(self) -> bool:
        """Whether the circuit equals the logical circuit on every input (as a unitary, up to the layouts): false
        where ``zero_start`` chose a routing simplified for the all-|0> start (``routed.equal_on_every_input``),
        which equals it on that input only, so no gates may run before it."""
        return bool(self._summary["routed"]["equal_on_every_input"]) if self.device is not None else True

    def counts(self) -> dict[str, int]:
        """Gate name -> count, sorted by name: ``qcpp compile --json``'s ``gates``."""
        return dict(sorted(self.circuit.count_ops().items()))

    def to_dict(self) -> dict[str, Any]:
        """What ``qcpp compile --json`` prints for the same scenario and options, without ``seconds``."""
        return {k: v for k, v in self._summary.items() if k != "seconds"}

    @property
    def measured_qubits(self) -> tuple[int, ...]:
        """The circuit qubit each data qubit is read from at the end: data qubit ``i`` (variable ``i``) is measured
        on ``measured_qubits[i]`` into classical bit ``i`` by ``measure=True`` (with a device: its physical qubit
        at the end, ``final_layout[i]``; else circuit qubit ``i``)."""
        n = self.scenario.num_variables
        return tuple(self.final_layout[:n]) if self.final_layout is not None else tuple(range(n))

    def to_qasm(self, version: int = 3, profile: str = "default", measure: bool = False) -> str:
        """OpenQASM text: ``3`` (unbound symbols become ``input float[64]``) or ``2`` (every symbol bound).

        Args:
            version: 3 or 2.
            profile: The OpenQASM 3 export profile (:mod:`qcpp.lowering.qasm_profiles`): ``default`` (the most
                faithful: ``include "stdgates.inc"``, qcpp's gate definitions; Qiskit, Cirq, the QDK), ``portable``
                (no include, no gate definitions: Amazon Braket's local simulator and PennyLane's ``from_qasm3``)
                or ``braket`` (Braket's native gate names). Every profile is the same unitary.
            measure: Also declare a classical register ``meas`` of one bit per data qubit and measure data qubit
                ``i`` into ``meas[i]`` at the end, on :attr:`measured_qubits` ``[i]`` (OpenQASM 3:
                ``meas[i] = measure q[j];``, every profile; 2: ``measure q[j] -> meas[i];``). Without it the text
                has no measurement (and is what it was before the option existed, byte for byte).

        Raises:
            qcpp.errors.OptionError: a version other than 2 or 3, an unknown profile, or a profile other than
                ``default`` with version 2.
            qcpp.ir.angles.UnboundParameterError: ``version=2`` with unbound symbols (naming them).

        Example:
            >>> import qcpp
            >>> text = qcpp.compile(qcpp.grid_scenario(2, 2, robots=1)).to_qasm(profile="portable")
            >>> for line in text.splitlines()[:3]:
            ...     print(line)
            OPENQASM 3.0;
            input float[64] beta_0;
            qubit[4] q;
        """
        from qcpp.lowering.qasm_measure import with_measurements
        from qcpp.lowering.qasm_profiles import ZERO_START_NOTE, check_profile, iter_qasm_profile, with_note

        check_choice(version, QASM_VERSIONS, "version")
        check_profile(profile, version)
        _check_flag(measure, "measure")
        chunks = iter_qasm_profile(self.circuit, int(version), profile)  # type: ignore[arg-type]
        if measure:
            chunks = with_measurements(chunks, self.measured_qubits, int(version))
        return "".join(with_note(chunks, None if self.equal_on_every_input else ZERO_START_NOTE))

    def write_qasm(
        self, path: str | os.PathLike[str], version: int = 3, profile: str = "default", measure: bool = False
    ) -> None:
        """Write :meth:`to_qasm` to ``path``, whole or not at all (an error leaves no partial file).

        Raises:
            As :meth:`to_qasm`; :class:`qcpp.io.atomic.OutputError` for a destination that cannot be written.
        """
        from qcpp.lowering.qasm_profiles import ZERO_START_NOTE, check_profile, write_qasm_profile

        check_choice(version, QASM_VERSIONS, "version")
        check_profile(profile, version)
        _check_flag(measure, "measure")
        write_qasm_profile(self.circuit, path, int(version), profile,  # type: ignore[arg-type]
                           self.measured_qubits if measure else None,
                           None if self.equal_on_every_input else ZERO_START_NOTE)  # fmt: skip

    def to_qiskit(self, measure: bool = False) -> Any:
        """The circuit as a ``qiskit.QuantumCircuit``, through Qiskit's own OpenQASM 3 loader (unbound symbols
        become Qiskit ``Parameter`` objects of the same names).

        Compiled for a device whose native one-qubit gates include ``sx`` (IBM's: ``rz sx x``), not ``lowered``: each
        ``rx(pi/2)`` of the native circuit (the IR's way of writing ``sx``, :mod:`qcpp.routing.native`) is Qiskit's
        ``sx``, with the circuit's global phase lowered by ``pi/4`` per gate (``rx(pi/2) = e^{-i pi/4} sx``: the
        unitary is exactly the same), so the circuit is in the device's basis as it is and its ``cz sx rz x`` counts
        are those :attr:`esp` charges. With a device, ``qc.layout`` (a Qiskit ``TranspileLayout``) records the
        routing: ``qc.layout.initial_index_layout(filter_ancillas=True)`` is :attr:`initial_layout`,
        ``qc.layout.final_index_layout()`` is :attr:`final_layout`.

        Args:
            measure: Also measure every data qubit: a classical register ``meas`` with data qubit ``i`` (variable
                ``i``) measured into ``meas[i]`` from :attr:`measured_qubits` ``[i]`` (with a device its physical
                qubit at the end, ``final_layout[i]``), so a sampler's counts (``result[0].data.meas.get_counts()``)
                read as the data register, clbit 0 rightmost: :meth:`decode` takes them as they are.
        """
        import qiskit.qasm3

        qc = qiskit.qasm3.loads(self.to_qasm(3, measure=measure))
        if self.device is None:
            return qc
        from qcpp.routing.qiskit_export import attach_layout, native_sx

        if not self.lowered and "sx" in self.device.native_gates:
            qc, _ = native_sx(qc)
        assert self.initial_layout is not None and self.final_layout is not None
        return attach_layout(qc, self.initial_layout, self.final_layout)

    def decode(self, counts: Any, *, optimum: Any = None) -> DecodedCounts:
        """Measured counts of this circuit's data register (``to_qiskit(measure=True)``, ``to_qasm(...,
        measure=True)``) decoded into robot paths, feasibility and cost: :func:`qcpp.decode_counts` on
        :attr:`scenario`.

        Example:
            >>> import qcpp
            >>> c = qcpp.compile(qcpp.grid_scenario(2, 2, robots=1))
            >>> d = c.decode({"0101": 3, "1111": 1})
            >>> d.feasible_share, d.best.nodes
            (0.75, (((0, 0), (0, 1), (1, 1)),))
        """
        from qcpp.api.decoding import decode_counts

        return decode_counts(self.scenario, counts, optimum=optimum)

    def to_cirq(self) -> Any:
        """The circuit as a ``cirq.Circuit``: qubit ``i`` is ``cirq.LineQubit(i)``, unbound symbols are sympy symbols
        of the same names (resolve them with ``cirq.ParamResolver``), the same unitary as :meth:`to_qiskit`'s
        (:mod:`qcpp.lowering.toolchains`: gate for gate, or a gate's exact decomposition where Cirq has no such
        gate).

        Raises:
            qcpp.errors.MissingExtraError: Cirq is not installed (``pip install 'qcpp[cirq]'``); a
                ``qcpp.QcppError`` and an ``ImportError``.
        """
        from qcpp.lowering.toolchains import to_cirq

        return to_cirq(self.circuit)

    def to_pytket(self) -> Any:
        """The circuit as a ``pytket.Circuit`` on :attr:`qubits` qubits: unbound symbols are sympy symbols of the same
        names (``symbol_substitution`` binds them), the same unitary as :meth:`to_qiskit`'s
        (:mod:`qcpp.lowering.toolchains`).

        Raises:
            qcpp.errors.MissingExtraError: pytket is not installed (``pip install 'qcpp[pytket]'``); a
                ``qcpp.QcppError`` and an ``ImportError``.
        """
        from qcpp.lowering.toolchains import to_pytket

        return to_pytket(self.circuit)

    def __repr__(self) -> str:
        where = f" on {self.device.name}" if self.device is not None else ""
        form = "lowered" if self.lowered else "native gates" if self.device is not None else "high level"
        total = sum(self.circuit.count_ops().values())
        g = self.scenario.grid
        return (
            f"<Compiled {g.rows}x{g.cols}, {self.scenario.num_robots} robot(s), p={self.p}, {form}{where}: "
            f"{self.qubits} qubits, {total} gates>"
        )


def _check_flag(flag: object, name: str) -> None:
    if not isinstance(flag, bool):
        raise OptionError(name, f"expected True or False, got {flag!r}")


def compile(
    scenario: Scenario,
    p: int = 1,
    *,
    device: str | Device | None = None,
    lowered: bool = False,
    bind: Mapping[str, float] | None = None,
    layout: str = "auto",
    local_ancillas: bool = False,
    optimize_for: str | None = None,
    zero_start: bool = False,
    effort: str = "full",
    max_gates: int | None = None,
    progress: ProgressArg = None,
    context: RoutingContext | None = None,
    **plan_options: Any,
) -> Compiled:
    """Compile the constrained-mixer QAOA circuit of ``scenario`` (what ``qcpp compile`` does).

    Args:
        p: QAOA layers (at least 1).
        device: Route onto this device (``qcpp.devices()``, or ``grid[:RxC]``, ``heavy-hex[:D]``,
            ``all-to-all[:N]``, a device file's path such as ``"mine.json"``, or a :class:`~qcpp.Device`); the
            circuit is then in the device's qubits and native gates.
        lowered: Lower to CX and one-qubit gates (with a device: keep CX + one-qubit gates).
        bind: Values of some or all symbols (``{"gamma_0": 0.3, "beta_0": 0.7}``).
        layout: With a device: ``auto``, ``medial`` or ``greedy``.
        local_ancillas: With a device: region-local ancillas.
        optimize_for: With a named device: choose the routed candidate by ``esp`` (success probability with idle
            decoherence; the default there) or ``twoq`` (fewest two-qubit gates); ``qcpp compile --optimize-for``.
        zero_start: With a named device (not ``lowered``): also offer routings simplified for the all-|0> start
            the device runs from, by either figure; the circuit then equals the logical one on that input only
            (:attr:`Compiled.equal_on_every_input`): put no gates before it. ``qcpp compile --zero-start``.
        effort: With a device: ``full`` (the default: every search) or ``quick`` (no choice of partial-mixer
            plans for the routing, :data:`~qcpp.routing.options.QUICK_ROUTING`: a few times faster on a named
            device, for more two-qubit gates; ``benchmarks/compile_effort.py``). ``qcpp compile --effort``;
            ``qcpp.estimate(..., effort=)`` routes its exact rows the same way.
        max_gates: Refuse circuits predicted to exceed this many lowered gates (default: as ``qcpp compile``, refuse
            only what would not fit in the available memory or would run for hours).
        progress: ``True`` for progress lines on stderr, or a function ``progress(done, total)``
            (:mod:`qcpp.api.progress`). Without a device: the gates built so far, of ``total`` the predicted
            lowered gates with ``lowered=True`` (``None`` for the high-level circuit, whose count is known only once
            built); the circuit is then built section by section, the same circuit. With a device: each stage of
            the routing as it starts (``progress(1, None)``, ``progress(2, None)``, ...; ``True`` names them).
        context: With a device: a :class:`~qcpp.RoutingContext` to keep the routing's searches in, shared by
            calls that route the same circuits (``estimate`` of what was just compiled, the same compile again):
            they are then answered from it, with the same result (default: a fresh one per call).
        **plan_options: How the circuit is built (``rule``, ``initial``, ``target``, ...;
            :class:`~qcpp.plan.options.PlanOptions`).

    Returns:
        The :class:`Compiled` circuit.

    Raises:
        qcpp.errors.OptionError: a bad ``p``, option or binding value, an unknown plan option, or a symbol in
            ``bind`` the circuit does not have (naming them).
        qcpp.hardware.device.DeviceError: an unknown device, or a device file that cannot be read or is malformed.
        qcpp.problem.limits.SizeError: a circuit predicted over ``max_gates``, or (without it) one that would not fit
            in the available memory or would run for hours (lifted inside :func:`qcpp.allow_large`).
        qcpp.problem.errors.ScenarioError: weights the circuit cannot represent exactly.
    """
    from qcpp.estimators.guard import check_size
    from qcpp.hardware.device import device_arg, device_label
    from qcpp.pipeline.candidates import OPTIMIZE_FOR, zero_start_refusal
    from qcpp.plan.compile import check_binding_values, compile_scenario
    from qcpp.plan.options import LAYOUT_METHODS
    from qcpp.problem.cost_range import check_cost_range
    from qcpp.routing.options import EFFORTS, effort_routing

    s = check_scenario_arg(scenario)
    layers = check_layers_arg(p)
    options = plan_options_arg(plan_options)
    bindings = check_binding_values(bind if bind is not None else {}, "bind")
    check_choice(layout, LAYOUT_METHODS, "layout")
    if optimize_for is not None:
        check_choice(optimize_for, OPTIMIZE_FOR, "optimize_for")
    check_choice(effort, EFFORTS, "effort")
    for name, flag in (("lowered", lowered), ("local_ancillas", local_ancillas), ("zero_start", zero_start)):
        if not isinstance(flag, bool):
            raise OptionError(name, f"expected True or False, got {flag!r}")
    if device is None:
        if layout != "auto":
            raise OptionError("layout", f"{layout!r} applies with a device only (no device given)")
        if local_ancillas:
            raise OptionError("local_ancillas", "applies with a device only (no device given)")
        if optimize_for is not None:
            raise OptionError("optimize_for", "applies with a device only (no device given)")
        if effort != "full":
            raise OptionError("effort", f"{effort!r} applies with a device only (no device given)")
    else:
        device = device_arg(device)  # an unknown name or a bad file fails before any work; a file is read once
    refusal = zero_start_refusal(device, lowered) if zero_start else None
    if refusal is not None:
        raise OptionError("zero_start", refusal)
    limit = None if max_gates is None else check_count(max_gates, "max_gates", 0)
    check_progress_arg(progress)
    check_context_arg(context, device)
    check_cost_range(s)  # what the command line checks when it loads a file
    size = check_size(s, layers, options, limit, "raise it with max_gates=N", allow_large_hint=API_OVERRIDE)
    task = f"compile {s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s), p={layers}"
    if device is None:
        # sections differ in cost per gate (a mixer section builds slower than a phase section): no time left
        with reporting(progress, task, unit="gates", total=size.gates if lowered else None, time_left=False) as bar:
            result = compile_scenario(s, layers, options, lowered=lowered, bindings=bindings,
                                      progress=bar and bar.update, stage=bar and bar.stage)  # fmt: skip
        return Compiled(s, layers, result.circuit, lowered, _summary=result.summary())
    from qcpp.pipeline.device_compile import compile_for_device

    with reporting(progress, f"{task}, device {device_label(device)}", unit="stages", stages=True) as bar:
        routed = compile_for_device(
            s, layers, device, options, lowered=lowered, bindings=bindings, local_ancillas=local_ancillas,
            layout_method=layout, optimize_for=optimize_for, stage=bar and bar.stage, zero_start=zero_start,
            routing=effort_routing(effort), context=context,
        )  # fmt: skip
    r = routed.routed
    return Compiled(
        s, layers, r.circuit, lowered, r.device, list(r.initial_layout), list(r.final_layout),
        _summary=routed.compile_summary(), _routed=r,
    )  # fmt: skip

