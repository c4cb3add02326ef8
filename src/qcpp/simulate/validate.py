"""Validate a compiled QAOA circuit against the exact feasible-subspace simulator (behind ``qcpp validate``).

:func:`validate` compiles the **lowered** circuit of a scenario (:func:`qcpp.plan.compile.compile_scenario`), binds
angles (given, or seeded random in ``[0.1, pi - 0.1]``; ``[gamma_0, beta_0, gamma_1, ...]``), runs it from
``|0...0>`` with one gate-level simulator and checks:

1. **ancilla probability**: the probability that every ancilla (all qubits after the data) is measured in |0> is 1
   to ``tolerance``;
2. **amplitudes**: for every feasible assignment (and every basis state of the subspace simulator, which under the
   ``paper`` rule may hold infeasible edge sets) the amplitude of "data qubits = the assignment's bits, ancillas
   0" equals :class:`qcpp.simulate.subspace.SubspaceQAOA`'s to ``tolerance``.

Backends:

``statevector`` / ``sparse``
    The dense state (up to 26 qubits) or the sparse state (any width while the support stays small): both checks
    exactly, every assignment.
``tensor``
    Two independent tensor-network methods (:mod:`qcpp.simulate.tensor`): exact contraction of ``<y|U|0>`` on the
    data qubits alone, each partial mixer first contracted into one operator proven unitary
    (:func:`qcpp.simulate.tensor.collapse_ancilla_blocks`, which needs the unfused circuit, ``fuse=False``), for
    every assignment or a seeded sample of ``max_amplitudes``; and the matrix product state of the whole circuit
    (:class:`~qcpp.simulate.tensor.MPSCircuit`) for the ancilla probability and every amplitude. With ``mps=False``
    the ancilla probability comes from an exact contraction (skipped beyond
    :data:`qcpp.simulate.tensor.DEFAULT_MAX_WIDTH`) or the bound ``sum |amplitude|^2 <= P(ancillas 0) <= 1``.
``qcec``
    Not a simulation: MQT QCEC (:mod:`qcpp.simulate.equivalence`) proves the lowered circuit equal to the
    high-level one at the same angles on every input with clean ancillas, section by section.
``auto`` (the default of ``qcpp validate``)
    :func:`choose_backend`: ``statevector`` up to :data:`AUTO_STATEVECTOR_QUBITS` qubits, else ``sparse``. The
    tensor path search can be slow, so it runs only when asked.

Size: the reference is the exact feasible-subspace state (the product of the robots' path counts).
:func:`validate_size` predicts it without planning a circuit, and :func:`validate` refuses
(:class:`ValidationTooLargeError`) more than ``max_assignments`` (:data:`MAX_VALIDATE_ASSIGNMENTS`) or a predicted
peak over the memory budget rather than running out of memory. :attr:`ValidationReport.verdict` is ``passed``
when every check ran and passed, ``failed`` when one failed, else ``incomplete`` (a check skipped, or none ran);
:attr:`ValidationReport.passed` is true only for ``passed``.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> r = validate(default_scenario(2, 2, 1), p=1, backend="statevector", seed=3)
    >>> r.passed, r.amplitudes_checked, r.max_amplitude_error < 1e-10
    (True, 2, True)
"""

from __future__ import annotations

import contextlib
import dataclasses
import itertools
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np

from qcpp.errors import OptionError, QcppError
from qcpp.io.html import html_table
from qcpp.plan.options import DEFAULT_PLAN, PlanOptions
from qcpp.problem.paths import enumerate_paths
from qcpp.problem.sbf import RULES, Rule
from qcpp.problem.scenario import Scenario
from qcpp.simulate.statevector import MAX_STATEVECTOR_QUBITS

__all__ = [
    "AUTO_STATEVECTOR_QUBITS",
    "BACKENDS",
    "COUNT_CAP_GROWTH",
    "FIRST_COUNT_CAP",
    "MAX_VALIDATE_ASSIGNMENTS",
    "Backend",
    "Check",
    "ValidationReport",
    "ValidationSize",
    "ValidationTooLargeError",
    "check_validatable",
    "choose_backend",
    "random_angles",
    "validate",
    "validate_size",
]

Backend = Literal["tensor", "statevector", "sparse", "qcec", "auto"]
BACKENDS: tuple[Backend, ...] = ("tensor", "statevector", "sparse", "qcec", "auto")
DEFAULT_TOLERANCE = 1e-8
AUTO_STATEVECTOR_QUBITS = 20
"""``auto`` uses the dense statevector up to this many qubits (2^20 amplitudes, 16 MB), else ``sparse``."""
MAX_VALIDATE_ASSIGNMENTS = 2_000_000
"""Most feasible assignments :func:`validate` compares against without ``max_assignments=None``
(``--allow-large``): about 1 GB for the reference state and its index."""
BYTES_PER_ASSIGNMENT = 500
"""Peak memory per feasible assignment, roughly: the subspace state and Hamiltonian, the assignment tuples, their
basis-state indices and reference amplitudes, the sparse state."""
MPS_BOND_LIMIT = 32
"""The ``tensor`` backend's MPS stops beyond this bond (the check notes it): its run time grows with the bond's cube."""


@dataclass(frozen=True)
class Check:
    """One check of a validation.

    Attributes:
        name: ``ancilla_probability`` or ``amplitudes``.
        method: How it was computed (e.g. ``statevector``, ``tensor contraction``, ``tensor MPS``).
        value: The ancilla probability, or the largest ``|amplitude - subspace amplitude|``.
        error: ``|1 - value|`` for the probability, ``value`` for amplitudes.
        count: Amplitudes compared (1 for the probability).
        status: ``pass``, ``fail`` or ``skipped``.
        seconds: Wall time of this check (simulation included).
        note: What was compared, or why it was skipped.
    """

    name: str
    method: str
    value: float
    error: float
    count: int
    status: Literal["pass", "fail", "skipped"]
    seconds: float
    note: str = ""


@dataclass(frozen=True)
class ValidationReport:
    """Result of :func:`validate`.

    Attributes:
        scenario: Scenario name.
        backend: Simulator used.
        p: QAOA layers of the circuit checked.
        rule: The SBF rule its mixer was compiled with (``exact`` or ``paper``).
        seed: Seed of the random angles and of the amplitude sample (``None``: angles given, no sample).
        angles: ``[gamma_0, beta_0, ...]``.
        qubits: Qubits of the lowered circuit.
        gates: Gates of the lowered circuit.
        feasible_assignments: Number of assignments whose amplitudes the checks are about.
        tolerance: Allowed deviation (the ``qcec`` backend compares no amplitudes: :meth:`to_dict` gives ``None``).
        checks: The checks, in order.
        seconds: Total wall time.
        plan: The plan options of the circuit checked that differ from the default (field -> value; ``rule`` is
            its own field).
    """

    scenario: str
    backend: str
    p: int
    rule: str
    seed: int | None
    angles: tuple[float, ...]
    qubits: int
    gates: int
    feasible_assignments: int
    tolerance: float
    checks: tuple[Check, ...] = field(default_factory=tuple)
    seconds: float = 0.0
    plan: dict[str, Any] = field(default_factory=dict)

    @property
    def verdict(self) -> Literal["passed", "failed", "incomplete"]:
        """``failed`` when a check failed, else ``incomplete`` when one was skipped or none ran, else ``passed``."""
        if any(c.status == "fail" for c in self.checks):
            return "failed"
        if not self.checks or any(c.status == "skipped" for c in self.checks):
            return "incomplete"
        return "passed"

    @property
    def passed(self) -> bool:
        """True when every check ran and passed (:attr:`verdict` is ``passed``; a skipped check never passes)."""
        return self.verdict == "passed"

    @property
    def ancilla_probability(self) -> float:
        """The first computed ancilla probability (NaN if skipped)."""
        for c in self.checks:
            if c.name == "ancilla_probability" and c.status != "skipped":
                return c.value
        return math.nan

    @property
    def max_amplitude_error(self) -> float:
        """Largest amplitude error over the amplitude checks (NaN if none ran)."""
        errs = [c.value for c in self.checks if c.name == "amplitudes" and c.status != "skipped"]
        return max(errs) if errs else math.nan

    @property
    def amplitudes_checked(self) -> int:
        """Distinct assignments compared by at least one amplitude check (the largest count)."""
        counts = [c.count for c in self.checks if c.name == "amplitudes" and c.status != "skipped"]
        return max(counts) if counts else 0

    def _repr_html_(self) -> str:
        """In a notebook: the verdict as the caption and one table row per check."""
        verdict = self.verdict if self.passed else self.verdict.upper()
        caption = (
            f"validation {verdict}: {self.scenario}, p = {self.p}, backend {self.backend}, {self.qubits} qubits, "
            f"{self.gates} gates, {self.feasible_assignments} feasible assignments"
        )
        rows = [(c.name, c.method, f"{c.value:.3g}", f"{c.error:.3g}", str(c.count), c.status, c.note)
                for c in self.checks]  # fmt: skip
        headers = ("check", "method", "value", "error", "count", "status", "")
        return html_table(caption, headers, rows, align=(None, None, "right", "right", "right"))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (the object ``qcpp validate --json`` prints): every field, the summary properties,
        ``passed`` and ``verdict``; ``tolerance`` is ``None`` for the ``qcec`` backend (an exact decision)."""
        d = asdict(self)
        d["angles"] = list(self.angles)
        d["checks"] = [asdict(c) for c in self.checks]
        d.update(
            passed=self.passed,
            verdict=self.verdict,
            ancilla_probability=_json_float(self.ancilla_probability),
            max_amplitude_error=_json_float(self.max_amplitude_error),
            amplitudes_checked=self.amplitudes_checked,
        )
        for c in d["checks"]:
            c["value"], c["error"] = _json_float(c["value"]), _json_float(c["error"])
        if self.backend == "qcec":
            d["tolerance"] = None  # QCEC decides equality exactly; it compares no amplitudes
        return d


def _json_float(x: float) -> float | None:
    return None if math.isnan(x) else float(x)


FIRST_COUNT_CAP = 1024
"""Paths counted per robot in :func:`validate_size`'s first round."""

COUNT_CAP_GROWTH = 16
"""How much :func:`validate_size` raises its per-robot cap each round (so the rounds before the last cost about a
fifteenth of it)."""


@dataclass(frozen=True)
class ValidationSize:
    """What a validation will hold, predicted before it starts: the feasible subspace it compares against.

    Attributes:
        paths_per_robot: Each robot's path count (a lower bound where counting stopped: ``exact`` false).
        exact: Whether every count is exact.
    """

    paths_per_robot: tuple[int, ...]
    exact: bool

    @property
    def assignments(self) -> int:
        """Feasible assignments: the size of the reference state (the product of the path counts)."""
        return math.prod(self.paths_per_robot)

    @property
    def bytes(self) -> int:
        """Predicted peak memory of the reference and the comparison (:data:`BYTES_PER_ASSIGNMENT` each)."""
        return self.assignments * BYTES_PER_ASSIGNMENT

    def describe(self) -> str:
        """One phrase, e.g. ``8,590 x 8,590 paths = 73,788,100 feasible assignments (about 36.9 GB)``."""
        paths = " x ".join(f"{n:,}" for n in self.paths_per_robot)
        gb = self.bytes / 1e9
        if self.exact:
            return f"{paths} paths = {self.assignments:,} feasible assignments (about {gb:.1f} GB)"
        return f"at least {self.assignments:,} feasible assignments (at least {gb:.1f} GB; paths counted: {paths})"


class ValidationTooLargeError(QcppError):
    """A validation over the limits of :func:`validate` (one line naming the size and the limit)."""


def validate_size(scenario: Scenario, *, max_assignments: int | None = None) -> ValidationSize:
    """Predict a validation's size without building anything (counting paths no further than needed).

    With ``max_assignments``, the robots' paths are counted together, every robot up to a cap that grows
    :data:`COUNT_CAP_GROWTH`-fold from :data:`FIRST_COUNT_CAP` per round, until the product of the counts exceeds
    ``max_assignments`` (the counts are then lower bounds) or every count is exact. Counting is as slow as
    enumerating (tens of thousands of paths a second), so a scenario of several robots with millions of paths each
    is known to be too large after about ``max_assignments ** (1 / robots)`` paths per robot, not after counting
    the first robot's paths up to ``max_assignments``.

    Args:
        max_assignments: Stop counting once the assignments are known to exceed this (``None``: count all).

    Returns:
        The counts; ``exact`` false where counting stopped early (then ``assignments > max_assignments``).

    Example:
        >>> from qcpp.problem.presets import default_scenario
        >>> size = validate_size(default_scenario(4, 4, 2))
        >>> size.paths_per_robot, size.assignments, size.exact
        ((184, 184), 33856, True)
        >>> small = validate_size(default_scenario(5, 5, 2), max_assignments=1000)
        >>> small.paths_per_robot, small.exact
        ((1024, 1024), False)
    """
    from qcpp.problem.paths import count_paths

    robots = range(scenario.num_robots)
    if max_assignments is None:
        return ValidationSize(tuple(count_paths(scenario, r) for r in robots), True)
    counts = [0 for _ in robots]
    exact = [False for _ in robots]
    cap = FIRST_COUNT_CAP
    while True:
        for r in robots:
            if not exact[r]:
                counts[r] = count_paths(scenario, r, cap)
                exact[r] = counts[r] < cap
        if all(exact) or math.prod(counts) > max_assignments:
            return ValidationSize(tuple(counts), all(exact))
        cap *= COUNT_CAP_GROWTH


def choose_backend(qubits: int) -> Backend:
    """What ``auto`` runs on a lowered circuit of ``qubits`` qubits: ``statevector`` up to
    :data:`AUTO_STATEVECTOR_QUBITS`, else ``sparse``.

    Example:
        >>> choose_backend(15), choose_backend(80)
        ('statevector', 'sparse')
    """
    return "statevector" if qubits <= AUTO_STATEVECTOR_QUBITS else "sparse"


def random_angles(p: int, seed: int | None) -> np.ndarray:
    """Seeded random angles ``[gamma_0, beta_0, ...]`` uniform in ``[0.1, pi - 0.1]`` (away from 0 and pi).

    Example:
        >>> a = random_angles(2, seed=1)
        >>> a.shape, bool(np.all((a > 0.1) & (a < math.pi - 0.1)))
        ((4,), True)
    """
    return np.random.default_rng(seed).uniform(0.1, math.pi - 0.1, 2 * p)


def _assignments(scenario: Scenario, bases: Sequence[Sequence[int]]) -> list[tuple[int, ...]]:
    per_robot = []
    for r in range(scenario.num_robots):
        per_robot.append(list(dict.fromkeys([*enumerate_paths(scenario, r), *bases[r]])))
    return list(itertools.product(*per_robot))


def _amplitude_check(method: str, got: np.ndarray, ref: np.ndarray, tol: float, t0: float, note: str) -> Check:
    err = float(np.max(np.abs(got - ref))) if len(ref) else 0.0
    status: Literal["pass", "fail"] = "pass" if err <= tol else "fail"
    return Check("amplitudes", method, err, err, len(ref), status, time.perf_counter() - t0, note)


def _probability_check(method: str, prob: float, tol: float, t0: float, note: str) -> Check:
    err = abs(1.0 - prob)
    status: Literal["pass", "fail"] = "pass" if err <= tol else "fail"
    return Check("ancilla_probability", method, prob, err, 1, status, time.perf_counter() - t0, note)


def _skipped(name: str, t0: float | None, note: str) -> Check:
    """A ``tensor contraction`` check that could not run (``t0``: when it started; ``None``: it never did)."""
    return Check(name, "tensor contraction", math.nan, math.nan, 0, "skipped",
                 0.0 if t0 is None else time.perf_counter() - t0, note)


def _mps_layout(scenario: Scenario, num_qubits: int) -> list[int]:
    """Site order with the ancillas between the first half of the robots and the rest (or mid-data for one)."""
    n = scenario.num_variables
    cut = (scenario.num_robots // 2) * scenario.edges_per_robot if scenario.num_robots > 1 else n // 2
    return [*range(cut), *range(n, num_qubits), *range(cut, n)]


def validate(
    scenario: Scenario,
    p: int,
    backend: Backend = "tensor",
    angles: Sequence[float] | None = None,
    seed: int | None = 0,
    rule: Rule = "exact",
    *,
    tolerance: float = DEFAULT_TOLERANCE,
    max_amplitudes: int | None = 256,
    mps: bool = True,
    cache_dir: str | Path | None = None,
    dask: str | None = None,
    max_assignments: int | None = MAX_VALIDATE_ASSIGNMENTS,
    max_bytes: int | None = None,
    stage: Callable[[str], None] | None = None,
    options: PlanOptions | None = None,
) -> ValidationReport:
    """Check a compiled circuit's ancillas and amplitudes against the feasible-subspace simulator.

    Args:
        p: QAOA layers (>= 1).
        backend: ``tensor``, ``statevector`` or ``sparse`` (see the module docstring).
        angles: ``[gamma_0, beta_0, ...]`` (``2p`` values); default :func:`random_angles` of ``seed``.
        seed: Seed of the random angles and of the ``tensor`` backend's amplitude sample.
        rule: SBF rule, ``exact`` or ``paper``.
        tolerance: Allowed deviation of each check.
        max_amplitudes: ``tensor``: contract at most this many assignments exactly (a seeded random sample when
            there are more; ``None``: all; 0: none). A contraction wider than
            :data:`qcpp.simulate.tensor.DEFAULT_MAX_WIDTH` is reported as skipped (the MPS checks still run).
        mps: ``tensor``: also run the matrix product state (ancilla probability, every amplitude); it is dropped
            (with a note on the contraction check) once its bond exceeds :data:`MPS_BOND_LIMIT`, and the ancilla
            probability then comes from the contracted, verified-unitary ancilla blocks.
        cache_dir: ``tensor``: contraction-path cache (default
            :func:`qcpp.simulate.contraction_paths.default_cache_dir`).
        dask: ``tensor``: a dask scheduler address, or ``'local'`` for a LocalCluster
            (:func:`qcpp.simulate.cluster.dask_client`): contractions wider than ``DEFAULT_MAX_WIDTH`` are sliced by
            cotengra and the slices run on the cluster instead of being skipped. ``None``: in-process.
        max_assignments: Refuse more feasible assignments than this (``None``: no limit).
        max_bytes: Refuse a predicted peak (:attr:`ValidationSize.bytes`) over this (``None``: no limit).
        stage: Called with a few words as each stage starts (``compiling the lowered circuit``), for progress.
        options: How the circuit is built (:class:`~qcpp.plan.options.PlanOptions`; default
            ``PlanOptions(rule=rule)``); its rule replaces ``rule``. The reference is simulated with the same rule,
            initial state and phase constant (:attr:`qcpp.plan.qaoa.QaoaPlan.reference_constant`); with
            ``first_phase=False`` the reference has ``gamma_0 = 0`` (the circuit has no first phase separator).
            :func:`check_validatable` says which options the simulator cannot check.

    Returns:
        The :class:`ValidationReport` (its ``backend`` is the one that ran: ``auto`` resolved).

    Raises:
        ValidationTooLargeError: over ``max_assignments`` or ``max_bytes``.
        ValueError: bad backend, rule, ``p`` or angles; the statevector backend beyond 26 qubits; a ``paper``-rule
            mixer that is not unitary on the data (:class:`qcpp.simulate.subspace.NonUnitaryMixerError`).
        qcpp.errors.OptionError: a plan option the simulator cannot check (:func:`check_validatable`).
    """
    from qcpp.plan.compile import compile_scenario
    from qcpp.simulate.subspace import angle_bindings

    t_start = time.perf_counter()
    options, x = _checked_request(p, backend, angles, seed, rule, tolerance, options)
    bindings = angle_bindings(x)
    at = stage if stage is not None else _no_stage

    at("predicting the size")
    _check_size(scenario, max_assignments, max_bytes)

    # the tensor backend contracts each partial mixer into one operator on its data qubits, which needs clean
    # ancillas at both ends of it: it gets the partial mixers unfused (the same high-level gates; the fused lowering
    # differs by cancelled inverse pairs only, tests/compiler/junction_test.py)
    built = dataclasses.replace(options, fuse=False) if backend == "tensor" else options
    at("compiling the lowered circuit")
    compiled = compile_scenario(scenario, p, built, lowered=True, bindings=bindings)
    circuit = compiled.circuit

    at("simulating the feasible subspace")
    reference = _reference(scenario, options, compiled.plan.reference_constant, x)
    if backend == "auto":  # compiled fused, as every backend but tensor (which auto never picks)
        backend = choose_backend(circuit.num_qubits)
    at(f"simulating the circuit ({backend})")
    n = scenario.num_variables
    if backend == "statevector":
        checks = _statevector_checks(circuit, n, reference, tolerance)
    elif backend == "sparse":
        checks = _sparse_checks(circuit, n, reference, tolerance)
    elif backend == "qcec":
        checks = [_qcec_check(scenario, p, options, bindings, circuit, at)]
    else:
        from qcpp.simulate.cluster import dask_client

        ancillas = list(range(n, circuit.num_qubits))
        with dask_client(dask) if dask is not None else contextlib.nullcontext(None) as client:
            checks = _tensor_checks(scenario, circuit, ancillas, reference.index, reference.amplitudes, seed,
                                    tolerance, max_amplitudes, mps, cache_dir, client)  # fmt: skip

    return ValidationReport(
        scenario=scenario.name,
        backend=backend,
        p=p,
        rule=options.rule,
        seed=seed if angles is None or backend == "tensor" else None,
        angles=tuple(float(v) for v in x),
        qubits=circuit.num_qubits,
        gates=len(circuit),
        feasible_assignments=len(reference.assignments),
        tolerance=tolerance,
        checks=tuple(checks),
        seconds=time.perf_counter() - t_start,
        plan=_changed_options(options),
    )


def _no_stage(_text: str) -> None:
    """The stage callback of a validation nobody watches."""


def _checked_request(
    p: int, backend: str, angles: Sequence[float] | None, seed: int | None, rule: Rule, tolerance: float,
    options: PlanOptions | None,
) -> tuple[PlanOptions, np.ndarray]:  # fmt: skip
    """The plan options and angles of a validation, its arguments checked in the order :func:`validate` documents.

    Returns:
        ``(options, angles)``: ``options`` default ``PlanOptions(rule=rule)`` (their rule wins over ``rule``), the
        ``2p`` angles given or :func:`random_angles` of ``seed``.

    Raises:
        ValueError: an unknown backend or rule, ``p`` not a positive integer, a tolerance not positive, or not
            ``2p`` finite angles.
        qcpp.errors.OptionError: a plan option the simulator cannot check (:func:`check_validatable`).
    """
    if backend not in BACKENDS:
        raise ValueError(f"unknown backend {backend!r} (expected one of {', '.join(BACKENDS)})")
    if rule not in RULES:
        raise ValueError(f"unknown SBF rule {rule!r} (expected one of {', '.join(RULES)})")
    options = PlanOptions(rule=rule) if options is None else options
    check_validatable(options)
    if not isinstance(p, int) or p < 1:
        raise ValueError(f"p must be a positive integer, got {p!r}")
    if not tolerance > 0:
        raise ValueError(f"tolerance must be positive, got {tolerance}")
    x = random_angles(p, seed) if angles is None else np.asarray(angles, dtype=float).reshape(-1)
    if x.size != 2 * p or not np.all(np.isfinite(x)):
        raise ValueError(f"expected {2 * p} finite angles [gamma_0, beta_0, ...], got {x.tolist()}")
    return options, x


def _check_size(scenario: Scenario, max_assignments: int | None, max_bytes: int | None) -> None:
    """Refuse a validation over ``max_assignments`` feasible assignments or a predicted peak over ``max_bytes``
    (``None``: no limit), predicted by :func:`validate_size` before anything is built.

    Raises:
        ValidationTooLargeError: one line naming the size and the limit it exceeds.
    """
    size = validate_size(scenario, max_assignments=max_assignments)
    if max_assignments is not None and size.assignments > max_assignments:
        raise ValidationTooLargeError(
            f"validating {size.describe()}: over the limit of {max_assignments:,} feasible assignments"
        )
    if max_bytes is not None and size.bytes > max_bytes:
        raise ValidationTooLargeError(
            f"validating {size.describe()}: over the memory budget of {max_bytes / 1e9:.1f} GB"
        )


@dataclass(frozen=True)
class _Reference:
    """What the circuit is compared with: every feasible assignment (and every basis state of the subspace
    simulator) as per-robot edge masks, its amplitude in the subspace state (0 outside its basis), and its basis
    state of the circuit (data bits set, ancillas 0; Python ints in an object array: any width).

    Invariant: the three are aligned, one entry per assignment.
    """

    assignments: list[tuple[int, ...]]
    amplitudes: np.ndarray
    index: np.ndarray


def _reference(scenario: Scenario, options: PlanOptions, constant: float, x: np.ndarray) -> _Reference:
    """The exact feasible-subspace state at angles ``x`` with the circuit's rule, initial state and phase constant
    (``gamma_0 = 0`` without the first phase separator: the circuit has no gate for it)."""
    from qcpp.simulate.subspace import SubspaceQAOA

    sub = SubspaceQAOA(scenario, options.rule, options.initial, phase_offset=constant)
    psi_sub = sub.state(x if options.first_phase else np.concatenate([[0.0], x[1:]]))  # no gate: gamma_0 = 0
    assignments = _assignments(scenario, sub.bases)
    ref = np.zeros(len(assignments), dtype=np.complex128)
    for k, masks in enumerate(assignments):
        with contextlib.suppress(KeyError):  # outside the subspace basis: amplitude 0
            ref[k] = psi_sub[sub.index_of(masks)]
    index = np.array([sub.data_index(m) for m in assignments], dtype=object)  # ancillas (above the data) are 0
    return _Reference(assignments, ref, index)


def _statevector_checks(circuit: Any, n: int, reference: _Reference, tol: float) -> list[Check]:
    """The ancilla probability and every amplitude from the dense state of ``circuit`` (``n`` data qubits).

    Raises:
        ValueError: more than :data:`~qcpp.simulate.statevector.MAX_STATEVECTOR_QUBITS` qubits.
    """
    nq = circuit.num_qubits
    if nq > MAX_STATEVECTOR_QUBITS:
        raise ValueError(
            f"statevector: {nq} qubits exceed {MAX_STATEVECTOR_QUBITS} (2^{nq} amplitudes); use --backend tensor"
        )
    from qcpp.simulate.statevector import simulate_statevector

    t0 = time.perf_counter()
    sv = simulate_statevector(circuit)
    clean = sv[: 1 << n]  # ancilla bits (above the data bits) all 0
    checks = [_probability_check("statevector", float(np.vdot(clean, clean).real), tol, t0, "sum over 2^n")]
    t0 = time.perf_counter()
    got = sv[np.array(reference.index, dtype=np.int64)]
    note = f"all {len(reference.assignments)} feasible assignments"
    checks.append(_amplitude_check("statevector", got, reference.amplitudes, tol, t0, note))
    return checks


def _sparse_checks(circuit: Any, n: int, reference: _Reference, tol: float) -> list[Check]:
    """The ancilla probability and every amplitude from the sparse state of ``circuit`` (``n`` data qubits)."""
    from qcpp.simulate.sparse import simulate_sparse

    t0 = time.perf_counter()
    state = simulate_sparse(circuit)
    prob = float(sum(abs(a) ** 2 for k, a in state.items() if k >> n == 0))
    checks = [_probability_check("sparse", prob, tol, t0, f"{len(state)} stored amplitudes")]
    t0 = time.perf_counter()
    got = np.array([state.get(int(k), 0j) for k in reference.index], dtype=np.complex128)
    note = f"all {len(reference.assignments)} feasible assignments"
    checks.append(_amplitude_check("sparse", got, reference.amplitudes, tol, t0, note))
    return checks


def _changed_options(options: PlanOptions) -> dict[str, Any]:
    """The plan options that differ from the default (field -> value), but ``rule`` (the report's own field) and
    ``fuse`` (a backend's choice, not the user's)."""
    return {
        f.name: getattr(options, f.name)
        for f in dataclasses.fields(options)
        if f.name not in ("rule", "fuse") and getattr(options, f.name) != getattr(DEFAULT_PLAN, f.name)
    }


def check_validatable(options: PlanOptions) -> None:
    """Refuse plan options whose circuit :func:`validate` cannot compare with the subspace simulator.

    Every option but one is checked: the simulator prepares every initial state, takes the phase constant of any
    phase separator (``target``, ``phase``, ``optimize``, ``ancilla_budget``, ``phase_layout`` change gates, not the
    state) and, without the first phase separator, runs with ``gamma_0 = 0``. ``angles="multi"`` is refused: the
    simulator has one beta per layer, the multi-angle circuit one per partial mixer.

    Raises:
        qcpp.errors.OptionError: one line naming the option.

    Example:
        >>> check_validatable(PlanOptions(target="ft", first_phase=False))
        >>> check_validatable(PlanOptions(angles="multi"))
        Traceback (most recent call last):
        ...
        qcpp.errors.OptionError: angles: the subspace simulator has one beta per layer, not multi
    """
    if options.angles != "layer":
        raise OptionError("angles", f"the subspace simulator has one beta per layer, not {options.angles}")


def _open_qubits(scenario: Scenario) -> list[int]:
    """Data qubits left open in each exact contraction: the last robot's (one contraction per assignment of the
    other robots), or every data qubit of a small single-robot scenario."""
    n, per = scenario.num_variables, scenario.edges_per_robot
    if scenario.num_robots > 1:
        return list(range(n - per, n))
    return list(range(n)) if n <= 20 else []


QCEC_STAGE = "checking the sections with QCEC"
"""The stage :func:`validate` names once the QCEC child process holds the circuits (``qcec`` backend)."""


def _qcec_check(
    scenario: Scenario, p: int, options: PlanOptions, bindings: dict[str, float], low: Any,
    stage: Callable[[str], None],
) -> Check:
    from qcpp.plan.compile import compile_scenario
    from qcpp.simulate.equivalence import check_sections_interruptibly

    t0 = time.perf_counter()
    high = compile_scenario(scenario, p, options, bindings=bindings).circuit
    # QCEC holds the GIL: Ctrl-C needs a child; the stage is named once the child holds the circuits
    r = check_sections_interruptibly(high, low, scenario.num_variables, started=lambda: stage(QCEC_STAGE))
    note = f"QCEC: lowered == high-level on clean ancillas, {r.sections} sections ({r.criterion})"
    for message in r.messages:  # QCEC's own warnings, captured instead of leaking, in our words where known
        if "alternating checker cannot handle" in message:
            note += "; decided by QCEC's construction checker (its alternating checker does not take ancillas)"
        else:
            note += f"; QCEC: {message}"
    if r.equivalent:
        return Check("equivalence", "qcec", 0.0, 0.0, r.sections, "pass", time.perf_counter() - t0, note)
    status: Literal["fail", "skipped"] = "fail" if r.criterion == "not_equivalent" else "skipped"
    return Check("equivalence", "qcec", 1.0, 1.0, r.sections, status, time.perf_counter() - t0, note)


def _tensor_checks(
    scenario: Scenario,
    circuit: Any,
    ancillas: list[int],
    index: np.ndarray,
    ref: np.ndarray,
    seed: int | None,
    tol: float,
    max_amplitudes: int | None,
    mps: bool,
    cache_dir: str | Path | None,
    client: Any = None,
) -> list[Check]:
    from qcpp.simulate.tensor import ContractionTooWideError, MPSCircuit, TensorCircuit

    checks: list[Check] = []
    total = len(index)
    mps_ok = False
    mps_note = ""
    if mps:
        t0 = time.perf_counter()
        try:
            m = MPSCircuit(circuit, layout=_mps_layout(scenario, circuit.num_qubits), bond_limit=MPS_BOND_LIMIT)
        except ContractionTooWideError as exc:
            # the MPS is the optional second method: not a check that failed to run, a note on the ones that did
            mps_note = f"; MPS not used: {exc}"
        else:
            mps_ok = True
            note = f"max bond {m.max_bond}, simulated in {m.seconds:.1f} s"
            checks.append(_probability_check("tensor MPS", m.zero_probability(ancillas), tol, t0, note))
            t0 = time.perf_counter()
            got = m.amplitudes(int(k) for k in index)
            checks.append(_amplitude_check("tensor MPS", got, ref, tol, t0, f"all {total} feasible assignments"))

    t0 = time.perf_counter()
    tc = TensorCircuit(circuit, cache_dir=cache_dir, client=client, ancillas=ancillas)
    if max_amplitudes == 0:
        checks.append(_skipped("amplitudes", None, "max_amplitudes=0"))
        return checks
    if max_amplitudes is None or max_amplitudes >= total:
        pick = np.arange(total)
        note = f"all {total} feasible assignments; partial mixers unfused"
    else:
        pick = np.sort(np.random.default_rng(seed).choice(total, size=max_amplitudes, replace=False))
        held = float(np.sum(np.abs(ref[pick]) ** 2))
        note = f"seeded sample of {len(pick)} of {total} assignments, holding probability {held:.6f}"
        note += "; partial mixers unfused"
    try:
        got = tc.amplitudes((int(index[k]) for k in pick), open_qubits=_open_qubits(scenario))
    except ContractionTooWideError as exc:
        checks.append(_skipped("amplitudes", t0, str(exc)))
        return checks
    if client is not None:  # say that Dask ran, and what it did
        workers = len(client.nthreads())
        sent = tc.dask_contractions
        note += (f"; Dask ({workers} worker(s)): {sent} contraction(s) sliced on the cluster" if sent else
                 f"; Dask ({workers} worker(s)) ready, not needed: every contraction fit in-process")
    checks.append(_amplitude_check("tensor contraction", got, ref[pick], tol, t0, note + mps_note))

    if not mps_ok and tc.block_leak is not None:
        note = "every ancilla block contracted to a unitary on the data: 1 - (sum of ||T^dagger T - I||) bounds it"
        checks.append(_probability_check("tensor blocks", 1.0 - tc.block_leak, tol, t0, note))
    elif not mps_ok:
        t0 = time.perf_counter()
        try:
            prob = tc.zero_probability(ancillas)
            checks.append(_probability_check("tensor contraction", prob, tol, t0, "<psi|P_0|psi> contracted"))
        except ContractionTooWideError as exc:
            if len(pick) == total:
                bound = float(np.sum(np.abs(got) ** 2))
                note = f"lower bound sum |amplitude|^2 over every feasible assignment ({exc})"
                checks.append(_probability_check("tensor contraction", bound, tol, t0, note))
            else:
                checks.append(_skipped("ancilla_probability", t0, str(exc)))
    return checks
