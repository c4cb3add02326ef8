"""Physical resource estimates (surface-code machine) from logical counts, via Microsoft's QDK resource estimator.

The logical counts (:class:`LogicalCounts`) are what the estimator's ``LogicalCounts`` input takes (Beverland et
al. 2022, "Assessing requirements to scale to practical quantum advantage", arXiv:2211.07629, the PSSPC layout):

* ``numQubits``: the circuit's logical qubits (data, ``logic`` and ``work`` ancillas);
* ``tCount``: explicit ``t``/``tdg`` gates;
* ``rotationCount`` / ``rotationDepth``: arbitrary-angle ``rz`` gates and the number of rotation layers (the
  estimator synthesises them itself, its T per rotation following from its error budget);
* ``cczCount``: full Toffolis (``ccx``: the target holds data);
* ``ccixCount``: logical ANDs computed into clean ancillas (``and``: Gidney's temporary AND is a CCiX);
* ``measurementCount``: AND uncomputes by measurement (``and_dg``) plus the final read-out of every data qubit.

The estimator (``qdk.estimator.LogicalCounts(...).estimate(params)``, local) returns
physical qubits, runtime, code distance and the T-factory layout. The qubit model is one of the estimator's
documented presets (:data:`QUBIT_MODELS`; default ``qubit_gate_ns_e3``: gate-based, 50 ns gates, 1e-3 error
rates), the QEC scheme ``surface_code`` (``floquet_code`` only for the Majorana models) and the total error
budget (default 1e-3, the estimator's own default). Every figure is an **estimate** of the estimator's model.

Example:
    >>> est = physical_estimate(LogicalCounts(num_qubits=20, t_count=100, rotation_count=10, rotation_depth=5,
    ...                                       ccz_count=4, ccix_count=50, measurement_count=70))
    >>> est.physical_qubits > 20 * 2 * est.code_distance ** 2, est.qubit_model, est.runtime_s > 0
    (True, 'qubit_gate_ns_e3', True)
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import MISSING, asdict, dataclass, fields
from typing import Any

from qcpp.errors import QcppError

__all__ = [
    "DEFAULT_ERROR_BUDGET",
    "DEFAULT_QEC_SCHEME",
    "DEFAULT_QUBIT_MODEL",
    "QEC_SCHEMES",
    "QUBIT_MODELS",
    "SCHEME_MODELS",
    "LogicalCounts",
    "PhysicalEstimate",
    "PhysicalEstimateError",
    "estimator_params",
    "model_scheme_error",
    "physical_estimate",
    "physical_from_result",
]

QUBIT_MODELS: tuple[str, ...] = (
    "qubit_gate_ns_e3",
    "qubit_gate_ns_e4",
    "qubit_gate_us_e3",
    "qubit_gate_us_e4",
    "qubit_maj_ns_e4",
    "qubit_maj_ns_e6",
)
"""The estimator's predefined qubit parameters (``qdk.estimator.QubitParams``)."""

QEC_SCHEMES: tuple[str, ...] = ("surface_code", "floquet_code")
"""The estimator's predefined QEC schemes (``qdk.estimator.QECScheme``); ``floquet_code`` needs a Majorana model."""

SCHEME_MODELS: dict[str, tuple[str, ...]] = {
    "surface_code": QUBIT_MODELS,
    "floquet_code": tuple(m for m in QUBIT_MODELS if m.startswith("qubit_maj_")),
}
"""The qubit models each QEC scheme supports (the estimator refuses ``floquet_code`` on a gate-based model:
``InvalidFaultToleranceProtocol``); :func:`model_scheme_error` checks a pair before the estimator is called."""


def model_scheme_error(qubit_model: str, qec_scheme: str, model_flag: str = "qubit_model") -> str | None:
    """Why the estimator cannot use ``qec_scheme`` with ``qubit_model`` (naming both and the compatible models),
    or ``None`` when it can (or when either is not a known name: the choice checks say so).

    >>> model_scheme_error("qubit_gate_ns_e3", "floquet_code", "--qubit-model")
    'floquet_code needs a Majorana qubit model (--qubit-model qubit_maj_ns_e4 or qubit_maj_ns_e6), got qubit_gate_ns_e3'
    >>> model_scheme_error("qubit_maj_ns_e4", "surface_code") is None
    True
    """
    allowed = SCHEME_MODELS.get(qec_scheme)
    if allowed is None or qubit_model not in QUBIT_MODELS or qubit_model in allowed:
        return None
    return f"{qec_scheme} needs a Majorana qubit model ({model_flag} {' or '.join(allowed)}), got {qubit_model}"


DEFAULT_QUBIT_MODEL = "qubit_gate_ns_e3"
DEFAULT_QEC_SCHEME = "surface_code"
DEFAULT_ERROR_BUDGET = 1e-3


class PhysicalEstimateError(QcppError):
    """The estimator refused the input (e.g. the code distance it needs exceeds its maximum)."""


@dataclass(frozen=True)
class LogicalCounts:
    """The estimator's logical-counts input (see the module docstring)."""

    num_qubits: int
    t_count: int = 0
    rotation_count: int = 0
    rotation_depth: int = 0
    ccz_count: int = 0
    ccix_count: int = 0
    measurement_count: int = 0

    def to_qdk(self) -> dict[str, int]:
        """The ``qdk.estimator.LogicalCounts`` dict: the fields, named in camelCase (``numQubits``, ...)."""
        return {_camel(k): v for k, v in asdict(self).items()}

    @classmethod
    def from_qdk(cls, counts: Mapping[str, Any]) -> LogicalCounts:
        """The counts of a QDK ``logicalCounts`` dict, named as :meth:`to_qdk` names them (its inverse).

        A count the dict leaves out is 0, but ``numQubits`` (the one field without a default) must be there
        (``KeyError`` otherwise).

        Example:
            >>> LogicalCounts.from_qdk({"numQubits": 3, "tCount": 4}) == LogicalCounts(num_qubits=3, t_count=4)
            True
            >>> c = LogicalCounts(5, 1, 2, 3, 4, 5, 6)
            >>> LogicalCounts.from_qdk(c.to_qdk()) == c
            True
        """
        values: dict[str, int] = {}
        for f in fields(cls):
            key = _camel(f.name)
            values[f.name] = int(counts[key] if f.default is MISSING else counts.get(key, 0))
        return cls(**values)


def _camel(name: str) -> str:
    """``num_qubits`` -> ``numQubits``: the QDK's spelling of a field name."""
    return re.sub(r"_(\w)", lambda m: m[1].upper(), name)


@dataclass(frozen=True)
class PhysicalEstimate:
    """The estimator's figures for one circuit (estimates of its model, not measurements).

    Attributes:
        physical_qubits: all physical qubits (algorithm + T factories).
        runtime_s: wall-clock runtime in seconds.
        algorithm_qubits: physical qubits of the algorithm's logical qubits (with routing).
        t_factory_qubits: physical qubits of all T factories together.
        t_factories: number of T factories running in parallel.
        t_states: T states consumed.
        code_distance: surface-code distance of the logical qubits.
        logical_depth: logical cycles of the algorithm.
        qubit_model, qec_scheme, error_budget: the inputs that chose the model.
    """

    physical_qubits: int
    runtime_s: float
    algorithm_qubits: int
    t_factory_qubits: int
    t_factories: int
    t_states: int
    code_distance: int
    logical_depth: int
    qubit_model: str
    qec_scheme: str
    error_budget: float


def physical_estimate(
    counts: LogicalCounts,
    qubit_model: str = DEFAULT_QUBIT_MODEL,
    qec_scheme: str = DEFAULT_QEC_SCHEME,
    error_budget: float = DEFAULT_ERROR_BUDGET,
) -> PhysicalEstimate:
    """Run the QDK resource estimator on ``counts``.

    Args:
        counts: the logical counts.
        qubit_model: one of :data:`QUBIT_MODELS`.
        qec_scheme: one of :data:`QEC_SCHEMES`.
        error_budget: total error budget, ``0 < error_budget < 1``.

    Raises:
        ValueError: an unknown model or scheme, a scheme the model does not support (:data:`SCHEME_MODELS`), or a
            budget outside (0, 1).
        PhysicalEstimateError: the estimator cannot meet the budget (its message, one line).
    """
    params = estimator_params(qubit_model, qec_scheme, error_budget)
    from qdk.estimator import EstimatorError
    from qdk.estimator import LogicalCounts as QdkLogicalCounts

    try:
        res = QdkLogicalCounts(counts.to_qdk()).estimate(params)
    except EstimatorError as exc:  # a BaseException subclass in qdk: catch it by name
        message = " ".join(str(exc).split())
        raise PhysicalEstimateError(f"QDK resource estimator ({qubit_model}, {qec_scheme}): {message}") from None
    return physical_from_result(res, qubit_model, qec_scheme, error_budget)


def estimator_params(qubit_model: str, qec_scheme: str, error_budget: float) -> dict[str, Any]:
    """The QDK estimator's parameters for a model, every value checked.

    Raises:
        ValueError: an unknown model or scheme, a scheme the model does not support (:data:`SCHEME_MODELS`), or a
            budget outside (0, 1).

    >>> estimator_params("qubit_gate_ns_e3", "surface_code", 1e-3)["qecScheme"]
    {'name': 'surface_code'}
    """
    if qubit_model not in QUBIT_MODELS:
        raise ValueError(f"unknown qubit model {qubit_model!r} (expected one of {', '.join(QUBIT_MODELS)})")
    if qec_scheme not in QEC_SCHEMES:
        raise ValueError(f"unknown QEC scheme {qec_scheme!r} (expected one of {', '.join(QEC_SCHEMES)})")
    pair = model_scheme_error(qubit_model, qec_scheme)
    if pair is not None:
        raise ValueError(pair)
    if not 0.0 < error_budget < 1.0:
        raise ValueError(f"error budget must be in (0, 1), got {error_budget!r}")
    return {"qubitParams": {"name": qubit_model}, "qecScheme": {"name": qec_scheme}, "errorBudget": error_budget}


def physical_from_result(res: Any, qubit_model: str, qec_scheme: str, error_budget: float) -> PhysicalEstimate:
    """The :class:`PhysicalEstimate` of a QDK estimator result (from logical counts or from a program)."""
    pc = res["physicalCounts"]
    bd = pc["breakdown"]
    return PhysicalEstimate(
        physical_qubits=int(pc["physicalQubits"]),
        runtime_s=float(pc["runtime"]) * 1e-9,
        algorithm_qubits=int(bd["physicalQubitsForAlgorithm"]),
        t_factory_qubits=int(bd["physicalQubitsForTfactories"]),
        t_factories=int(bd["numTfactories"]),
        t_states=int(bd["numTstates"]),
        code_distance=int(res["logicalQubit"]["codeDistance"]),
        logical_depth=int(bd["logicalDepth"]),
        qubit_model=qubit_model,
        qec_scheme=qec_scheme,
        error_budget=error_budget,
    )
