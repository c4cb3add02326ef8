"""``qcpp.simulate_noisy``: P(optimum) of a circuit compiled for a device, under that device's noise.

The check the hardware guide runs on the ESP model (``benchmarks/noisy_verdict.py``), for a user's own scenario and
angles: the routed native circuit :func:`qcpp.compile` wrote for a device is simulated by qiskit-aer with a
noise model built from the same device file (:mod:`qcpp.simulate.noisy`: gate errors, thermal relaxation over the
gates and the idle waits where the file has T1/T2 and durations, read-out errors), on the qubits it touches, and the
probability that the measured data register is an optimal assignment is returned beside the ESP model's figure.

Needs the extra ``noise`` (``pip install 'qcpp[noise]'``, qiskit-aer). Like the other simulations it predicts its
peak memory and run time first (:func:`qcpp.simulate.noisy.noisy_need`) and refuses, in one line naming the
prediction, what would not fit or would run for more than an hour, unless called in a ``qcpp.allow_large()`` block.

Example:
    >>> import qcpp
    >>> s = qcpp.grid_scenario(2, 2, robots=1)
    >>> c = qcpp.compile(s, device="ibm_fez", bind={"gamma_0": 0.0, "beta_0": 0.0})
    >>> r = qcpp.simulate_noisy(c, noise=False)
    >>> round(r.p_optimum, 6), r.method
    (1.0, 'density_matrix')
    >>> qcpp.simulate_noisy(qcpp.compile(s))
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: compiled: no device: compile with device=NAME to simulate the device's noise
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from qcpp.api.compiling import Compiled
from qcpp.api.progress import ProgressArg, check_progress_arg, reporting
from qcpp.errors import OptionError, check_count
from qcpp.problem.limits import API_OVERRIDE, check_need

if TYPE_CHECKING:
    from qcpp.simulate.noisy import NoisyResult

__all__ = ["simulate_noisy"]


def simulate_noisy(
    compiled: Compiled,
    *,
    noise: bool = True,
    idle: bool = True,
    shots: int = 2000,
    seed: int = 0,
    method: str | None = None,
    progress: ProgressArg = None,
) -> NoisyResult:
    """P(optimum) of ``compiled`` under the noise of the device it was compiled for.

    Up to 10 active qubits the density matrix gives P(optimum) exactly; above, ``shots`` sampled trajectories (state
    vectors up to 24 active qubits, matrix product states beyond) give it with a binomial standard error. Without
    noise the final state's P(optimum) is exact on every method (no shots). A noisy trajectory is a whole
    state-vector run: the time grows as shots x gates x 2^(active qubits) (the hardware guide lists measured times:
    minutes for 15 active qubits and 2,000 shots, hours for 21). The run is predicted first and refused over the
    limits of :func:`qcpp.allow_large`.

    Args:
        compiled: A circuit of :func:`qcpp.compile` with a ``device=`` (a named device's calibration snapshot, or
            an abstract family's default errors), not ``lowered`` (the device's native gates, whose errors the
            device gives), every symbol bound (``bind=``).
        noise: Apply the device's noise (``False``: the same circuit without noise; its P(optimum) is the ideal
            state's, a check of the routing).
        idle: With ``noise``, also relaxation while qubits wait (``False``: gate and read-out errors only, what the
            ESP model charges).
        shots: Trajectories, for the sampled methods.
        seed: qiskit-aer's seed.
        method: ``density_matrix``, ``statevector`` or ``matrix_product_state`` (default: by the active qubit
            count, as above).
        progress: ``True`` for progress lines on stderr, or a function (:mod:`qcpp.api.progress`) called as
            ``progress(done, shots)`` after each run of up to
            :data:`qcpp.simulate.noisy.SHOT_BATCH` sampled shots, fewer where shots take seconds (about every
            30 s: :func:`qcpp.simulate.noisy.shot_batch`); the exact methods report nothing.

    Returns:
        A :class:`qcpp.NoisyResult`: ``p_optimum``, its ``stderr`` (0 when exact), the ``method``,
        the active ``qubits`` and the ``shots`` (0 when exact).

    Raises:
        qcpp.errors.OptionError: ``compiled`` is not a compiled circuit, has no device or is lowered; a bad
            ``shots``, ``seed``, ``method`` or flag.
        qcpp.ir.angles.UnboundParameterError: unbound symbols (naming them).
        qcpp.SizeError: predicted to need more memory than is available or to run for more than an hour
            (naming the prediction; lifted inside :func:`qcpp.allow_large`).
        qcpp.simulate.noisy.NoisyBackendMissing: qiskit-aer is not installed (naming the extra).
    """
    from qcpp.ir.angles import UnboundParameterError
    from qcpp.simulate.noisy import METHODS, noisy_need, require_aer
    from qcpp.simulate.noisy import simulate_noisy as simulate
    from qcpp.training.evaluate import feasible_assignments

    if not isinstance(compiled, Compiled):
        raise OptionError("compiled", f"expected the result of qcpp.compile, got {type(compiled).__name__}")
    if compiled._routed is None:
        raise OptionError("compiled", "no device: compile with device=NAME to simulate the device's noise")
    if compiled.lowered:
        raise OptionError(
            "compiled", "lowered to cx: compile without lowered=True (the device's native gates carry its errors)"
        )
    for name, flag in (("noise", noise), ("idle", idle)):
        if not isinstance(flag, bool):
            raise OptionError(name, f"expected True or False, got {flag!r}")
    count = check_count(shots, "shots")
    chosen_seed = check_count(seed, "seed", 0)
    if method is not None and method not in METHODS:
        raise OptionError("method", f"unknown method {method!r} (expected one of {', '.join(METHODS)})")
    if compiled.symbols:
        raise UnboundParameterError(compiled.symbols, "a noisy simulation needs numbers")
    check_progress_arg(progress)
    check_need(noisy_need(compiled._routed, noise=noise, shots=count, method=method), field="compiled",
               override=API_OVERRIDE)  # fmt: skip
    require_aer()
    indices, optimal = feasible_assignments(compiled.scenario)
    with reporting(progress, f"simulate_noisy on {compiled._routed.device.name}", unit="shots", total=count) as bar:
        return simulate(
            compiled._routed, indices[optimal].tolist(), noise=noise, idle=idle, shots=count, seed=chosen_seed,
            method=method, progress=bar and bar.update,
        )  # fmt: skip
