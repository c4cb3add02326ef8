"""``qcpp.validate``: the compiled circuit checked against the exact feasible-subspace simulator (``qcpp validate``).

Where :func:`qcpp.verify` shows that the mixer never leaves the feasible space, this shows that the lowered circuit
computes the state the algorithm defines: at the given (or seeded random) angles its ancillas end in |0> and its
amplitudes on the feasible assignments equal those of :class:`qcpp.simulate.subspace.SubspaceQAOA`, an
independent simulator that never builds a circuit. The checks and backends are those of the command
(:mod:`qcpp.simulate.validate`), and :meth:`ValidationReport.to_dict` is its ``--json`` object (timings aside),
``verdict`` and ``passed`` included: ``passed`` is true only when every check ran and passed, as the command's exit
code 0.

Example:
    >>> import qcpp
    >>> report = qcpp.validate(qcpp.grid_scenario(2, 3, robots=1), p=1, angles=[0.4, 0.9])
    >>> report.passed, report.backend, report.feasible_assignments
    (True, 'statevector', 4)
    >>> qcpp.validate(qcpp.grid_scenario(2, 3, robots=1), backend="fast")
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: backend: expected tensor or statevector or sparse or qcec or auto, got 'fast'
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from qcpp.api.checks import check_angles_arg, check_layers_arg, check_scenario_arg, plan_options_arg
from qcpp.api.progress import ProgressArg, check_progress_arg, reporting
from qcpp.api.scenarios import Scenario
from qcpp.errors import OptionError, check_choice, check_count
from qcpp.problem.limits import API_OVERRIDE

if TYPE_CHECKING:
    from qcpp.simulate.validate import ValidationReport

__all__ = ["validate"]


def validate(
    scenario: Scenario,
    p: int = 1,
    *,
    backend: str = "auto",
    angles: Sequence[float] | None = None,
    seed: int = 0,
    max_amplitudes: int = 256,
    dask: str | None = None,
    progress: ProgressArg = None,
    **plan_options: Any,
) -> ValidationReport:
    """Check the compiled circuit of ``scenario`` against the feasible-subspace simulator (``qcpp validate``).

    Args:
        p: QAOA layers.
        backend: ``auto`` (a state vector up to 26 qubits, else the sparse state), ``statevector``, ``sparse``,
            ``tensor`` (a tensor network: contracted amplitudes of a sample and a matrix product state) or ``qcec``
            (MQT QCEC proves the lowered circuit equal to the high-level one; needs the ``test`` extra).
        angles: ``2p`` angles ``[gamma_0, beta_0, ...]``; ``None``: seeded random ones.
        seed: Seed of the random angles and of the tensor backend's amplitude sample.
        max_amplitudes: ``tensor``: contract at most this many amplitudes exactly (a seeded sample of them).
        dask: ``tensor``: a dask scheduler address (``tcp://host:8786``) or ``local`` (a cluster on this machine);
            contractions too wide for one process are sliced and run there. Giving it with ``auto`` picks
            ``tensor``.
        progress: ``True`` for progress lines on stderr naming each stage (``compiling the lowered circuit``,
            ``simulating the circuit (tensor)``, ...), or a function ``progress(done, total)``
            (:mod:`qcpp.api.progress`) called as each stage starts: ``progress(1, None)``, ``progress(2, None)``, ...
        **plan_options: How the circuit is built, as for :func:`qcpp.compile`: ``rule``, ``initial``, ``target``,
            ``phase``, ``optimize``, ``ancilla_budget``, ``phase_layout``, ``first_phase``, ``fuse``
            (:class:`~qcpp.plan.options.PlanOptions`); the reference simulation follows them. Not ``angles``
            (here the angle values): the simulator has one beta per layer.

    Returns:
        The :class:`~qcpp.simulate.validate.ValidationReport`: ``verdict`` (``passed``, ``failed`` or
        ``incomplete``: a check skipped), ``passed`` (every check ran and passed), ``checks`` (each
        with its value, error, status and seconds), ``backend`` (the one that ran), ``to_dict()``.

    Raises:
        qcpp.errors.OptionError: a bad option (naming it), an unknown plan option; ``first_phase=False`` with a
            start that is a superposition; ``dask`` with a backend other than ``tensor``; the ``qcec`` backend
            without mqt.qcec.
        qcpp.problem.limits.SizeError: a feasible subspace whose reference state would not fit in the available
            memory or would take hours (lifted inside :func:`qcpp.allow_large`).
        qcpp.problem.errors.ScenarioError: weights the QAOA phases cannot represent exactly.
    """
    from qcpp.problem.cost_range import check_phase_range
    from qcpp.problem.limits import check_need
    from qcpp.simulate.footprint import validate_need
    from qcpp.simulate.validate import BACKENDS
    from qcpp.simulate.validate import validate as run

    s = check_scenario_arg(scenario)
    layers = check_layers_arg(p)
    check_choice(backend, BACKENDS, "backend")
    options = plan_options_arg(plan_options)
    check_count(seed, "seed", 0)
    check_count(max_amplitudes, "max_amplitudes", 1)
    values = check_angles_arg(angles, layers)
    if dask is not None:
        from qcpp.simulate.cluster import check_dask_address

        check_dask_address(dask, "dask")
        if backend == "auto":
            backend = "tensor"  # only the tensor backend contracts on a cluster: asking for one picks it
        if backend != "tensor":
            raise OptionError("dask", f"only the tensor backend uses a dask cluster, got backend={backend!r}")
    if backend == "qcec":
        try:
            import mqt.qcec  # noqa: F401
        except ImportError as exc:
            raise OptionError("backend", f"qcec needs mqt.qcec (pip install 'qcpp[test]'): {exc}") from None
    check_progress_arg(progress)
    check_phase_range(s)
    if not options.first_phase:
        from qcpp.plan.qaoa import qaoa_plan

        qaoa_plan(s, 0, options)  # refuses a start that is a superposition, before any work
    task = f"validate p={layers} on {s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s)"
    with reporting(progress, task, unit="stages", stages=True) as bar:
        if bar is not None:
            bar.stage("predicting the size")
        check_need(validate_need(s), field="scenario", override=API_OVERRIDE)
        return run(
            s, layers, backend=backend, angles=values, seed=seed, options=options,  # type: ignore[arg-type]
            max_amplitudes=max_amplitudes, dask=dask, max_assignments=None, max_bytes=None, stage=bar and bar.stage,
        )  # fmt: skip
