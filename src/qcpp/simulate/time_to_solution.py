"""Time to solution: the time to reach an optimal assignment with probability ``target`` (99%), per method.

One criterion for every method:

* a **deterministic** method (DFS, CP-SAT with one worker) reaches the optimum once, at a measured time;
* a **stochastic** method (SA, GA) is run ``R`` times independently; with ``k`` successes, a run reaches the
  optimum with probability ``k / R`` and ``tries_for(k / R)`` runs (:func:`qcpp.simulate.success.tries_for`) reach it
  with probability ``target``, so ``TTS = mean run time x runs`` (:func:`repeated_runs`); the Wilson interval of
  ``k / R`` gives the range;
* **QAOA** on a device: training costs ``estimates x shots per estimate`` circuit runs, then
  ``shots_for(P(optimum) x ESP)`` shots of the trained circuit reach the optimum with probability ``target``;
  every shot takes the circuit's time plus readout (:func:`shot_seconds` on an ideal device, the routed
  circuit's schedule on a real one), so ``TTS = (training shots + shots) x shot time`` (:func:`qaoa_on_device`).

The noise model of a device is the estimated success probability ``ESP`` (:func:`qcpp.routing.native.esp`: the
product of ``1 - error`` over every gate and readout of the routed circuit): **a shot succeeds with probability
``P(optimum) x ESP``**, i.e. an error anywhere ruins the shot and an error-free shot samples the ideal state.
This is optimistic (no idle decoherence, crosstalk or leakage; training is counted at its noiseless number of
estimates) and simple enough to state in one line; its one pessimistic part is that a faulty shot counts as a
miss (under global depolarisation it would still hit an optimum with probability ``optima / 2^n``).
An ideal device has ``ESP = 1``.

Example:
    >>> r = repeated_runs(run_seconds=0.5, successes=3, runs=10)
    >>> r.tries, r.seconds
    (13, 6.5)
    >>> round(shot_seconds(depth=100, two_qubit_depth=40), 9)
    1.6e-05
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from qcpp.simulate.success import tries_for, wilson_interval

__all__ = ["GATE_MODEL", "QaoaTime", "RepeatedRuns", "qaoa_on_device", "repeated_runs", "shot_seconds"]

GATE_MODEL = {"t_1q_ns": 50.0, "t_2q_ns": 300.0, "readout_ns": 1000.0}
"""An ideal all-to-all device: two-qubit layers (two-qubit depth) at ``t_2q``, the remaining layers at
``t_1q``, one readout and reset per shot; no routing, no noise, no error correction."""


def shot_seconds(depth: int, two_qubit_depth: int, model: dict[str, float] | None = None) -> float:
    """Seconds per shot: ``two_qubit_depth * t_2q + (depth - two_qubit_depth) * t_1q + readout``.

    Example:
        >>> shot_seconds(10, 10, {"t_1q_ns": 1.0, "t_2q_ns": 2.0, "readout_ns": 0.0})
        2e-08
    """
    m = GATE_MODEL if model is None else model
    if not 0 <= two_qubit_depth <= depth:
        raise ValueError(f"need 0 <= two_qubit_depth <= depth, got {two_qubit_depth}, {depth}")
    return (two_qubit_depth * m["t_2q_ns"] + (depth - two_qubit_depth) * m["t_1q_ns"] + m["readout_ns"]) * 1e-9


@dataclass(frozen=True)
class RepeatedRuns:
    """Time to solution of a stochastic method from ``runs`` independent runs.

    Attributes:
        successes, runs: Runs that reached the optimum, of all runs.
        run_seconds: Mean wall time of a run.
        tries: Runs needed for ``target`` at the observed rate (``inf`` with no success).
        seconds: ``run_seconds * tries``.
        seconds_range: The same at the ends of the rate's 95% Wilson interval (best, worst).
    """

    successes: int
    runs: int
    run_seconds: float
    tries: float
    seconds: float
    seconds_range: tuple[float, float]


def repeated_runs(run_seconds: float, successes: int, runs: int, target: float = 0.99) -> RepeatedRuns:
    """:class:`RepeatedRuns` of a method whose runs take ``run_seconds`` and succeed ``successes / runs``."""
    lo, hi = wilson_interval(successes, runs)
    tries = tries_for(successes / runs, target)
    return RepeatedRuns(successes, runs, run_seconds, tries, run_seconds * tries,
                        (run_seconds * tries_for(hi, target), run_seconds * tries_for(lo, target)))


@dataclass(frozen=True)
class QaoaTime:
    """Device time of QAOA to reach the optimum with probability ``target``.

    Attributes:
        shot_seconds: Time of one shot.
        p_shot: Probability that one shot returns an optimum: ``P(optimum) x ESP``.
        training_shots: ``estimates * shots_per_estimate``.
        shots: Shots of the trained circuit for ``target`` (``inf`` if ``p_shot = 0``).
        training_seconds, sampling_seconds: The two parts; ``seconds`` their sum.
    """

    shot_seconds: float
    p_shot: float
    training_shots: int
    shots: float
    training_seconds: float
    sampling_seconds: float

    @property
    def seconds(self) -> float:
        return self.training_seconds + self.sampling_seconds


def qaoa_on_device(
    p_optimum: float,
    estimates: int,
    shots_per_estimate: int,
    shot_time: float,
    target: float = 0.99,
    esp: float = 1.0,
) -> QaoaTime:
    """:class:`QaoaTime` from the trained state's ``P(optimum)``, the training's objective estimates, the shots
    per estimate, the time per shot (training shots counted at that shot time) and the device's estimated
    success probability (a shot succeeds with ``P(optimum) x esp``; model in the module docs).

    Args:
        p_optimum: Probability of an optimal assignment in the noiseless trained state.
        estimates: Objective estimates of the training.
        shots_per_estimate: Shots per estimate.
        shot_time: Seconds per shot.
        target: Success probability to reach.
        esp: Estimated success probability of one shot on the device (1: ideal).

    Example:
        >>> t = qaoa_on_device(0.5, estimates=10, shots_per_estimate=100, shot_time=1e-6)
        >>> t.shots, t.training_shots, round(t.seconds, 9)
        (7, 1000, 0.001007)
        >>> qaoa_on_device(0.5, 10, 100, 1e-6, esp=0.5).shots  # P(opt) x ESP = 0.25 per shot
        17
    """
    if not 0 <= esp <= 1:
        raise ValueError(f"esp must be in [0, 1], got {esp}")
    p_shot = min(1.0, max(0.0, p_optimum)) * esp  # a norm rounded past 1 is 1
    shots = tries_for(p_shot, target)
    training = estimates * shots_per_estimate
    sampling = shots * shot_time if math.isfinite(shots) else math.inf
    return QaoaTime(shot_time, p_shot, training, shots, training * shot_time, sampling)
