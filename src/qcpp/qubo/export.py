"""Serialise a :class:`qcpp.qubo.model.Bqm` for other tools: dimod JSON, Ising, QUBO list, LP / MPS.

Formats (:data:`EXPORT_FORMATS`):

* ``bqm`` -- dimod's serializable ``BinaryQuadraticModel`` JSON (``dimod.BinaryQuadraticModel.from_serializable
  (json.load(f))`` reads it back); needs dimod.
* ``ising`` -- JSON ``{"h": {label: h}, "J": [[a, b, J], ...], "offset": c0, ...}`` with
  ``E = offset + sum h Z + sum J Z Z`` under qcpp's convention ``x = (1 - Z)/2`` (``Z = +1`` is bit 0). dimod's
  spins are ``s = 2x - 1 = -Z``: pass ``{k: -v for k, v in h.items()}`` to ``dimod.from_ising``.
* ``qubo`` -- JSON ``{"Q": [[a, b, q], ...], "offset": k, ...}``: ``E = offset + sum q b_a b_b`` over 0/1 bits,
  the linear coefficients on the diagonal (``a == b``), every variable listed once on it.
* ``lp`` / ``mps`` -- the same minimisation as a mixed-integer linear program (CPLEX LP text / free MPS, written by
  OR-Tools' exporter): binary variables, and per quadratic term ``q b_a b_b`` a continuous ``p{a}_{b}`` in
  ``[0, 1]`` with ``p <= b_a, p <= b_b`` (``q < 0``) or ``p >= b_a + b_b - 1`` (``q > 0``), so its optimum is the
  QUBO's. LP/MPS names cannot hold ``:``, ``,`` or ``-``: each becomes ``_`` (``x0:0,0-0,1`` is ``x0_0_0_0_1``,
  :func:`mip_name`); ``a``, ``b`` in ``p{a}_{b}`` are variable positions in the JSON formats' order.

The JSON formats also carry ``form``, ``penalty``, ``variables`` (in order), ``num_edge_variables`` and a
``labels`` note saying how to decode them.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.qubo.model import per_robot_bqm
    >>> text = export_text(per_robot_bqm(default_scenario(2, 2, 1), penalty=3.0), "qubo")
    >>> import json; json.loads(text)["Q"][0]
    ['x0:0,0-0,1', 'x0:0,0-0,1', -5.0]
"""

from __future__ import annotations

import json
import re
from typing import Any, Literal

from qcpp.qubo.model import Bqm, to_dimod, to_ising

__all__ = ["EXPORT_FORMATS", "LABELS_NOTE", "export_text", "mip_model", "mip_name"]

ExportFormat = Literal["bqm", "ising", "qubo", "lp", "mps"]
EXPORT_FORMATS: tuple[ExportFormat, ...] = ("bqm", "ising", "qubo", "lp", "mps")

LABELS_NOTE = (
    "x{r}:{r1},{c1}-{r2},{c2} = robot r uses the edge between nodes (r1, c1) and (r2, c2), smaller node first; "
    "y{r}:{row},{col} = robot r visits node (row, col) (per-robot form only)"
)

_MIP_UNSAFE = re.compile(r"[:,\-]")


def mip_name(label: str) -> str:
    """A label as an LP/MPS-safe name (``:``, ``,`` and ``-`` become ``_``).

    Example:
        >>> mip_name("x1:2,3-2,4")
        'x1_2_3_2_4'
    """
    return _MIP_UNSAFE.sub("_", label)


def _header(model: Bqm, fmt: str) -> dict[str, Any]:
    return {
        "format": f"qcpp-{fmt}",
        "form": model.form,
        "penalty": model.penalty,
        "labels": LABELS_NOTE,
        "num_edge_variables": model.num_edge_variables,
        "variables": list(model.labels),
    }


def mip_model(model: Bqm) -> Any:
    """The model as an OR-Tools ``model_builder.Model`` (linearised products, see the module docstring)."""
    from ortools.linear_solver.python import model_builder as mb

    m = mb.Model()
    xs = [m.new_bool_var(mip_name(lab)) for lab in model.labels]
    terms = [c * x for c, x in zip(model.linear.tolist(), xs, strict=True) if c != 0.0]
    for i, j, q in zip(model.quad_i.tolist(), model.quad_j.tolist(), model.quad_val.tolist(), strict=True):
        p = m.new_var(0.0, 1.0, False, f"p{i}_{j}")
        if q < 0:
            m.add(p <= xs[i])
            m.add(p <= xs[j])
        else:
            m.add(p >= xs[i] + xs[j] - 1)
        terms.append(q * p)
    m.minimize(mb.LinearExpr.sum(terms) + model.offset)
    return m


def export_text(model: Bqm, fmt: str) -> str:
    """The model in format ``fmt`` (:data:`EXPORT_FORMATS`) as one text.

    Raises:
        ValueError: on an unknown format.
        ModuleNotFoundError: ``bqm`` without dimod.
    """
    if fmt == "bqm":
        return json.dumps(to_dimod(model).to_serializable()) + "\n"
    if fmt == "ising":
        h, J, offset = to_ising(model)
        out = _header(model, fmt)
        out.update(
            convention="E = offset + sum_i h_i Z_i + sum_ij J_ij Z_i Z_j, x = (1 - Z)/2 (Z = +1 is bit 0); "
            "dimod spins s = 2x - 1 = -Z, so dimod.from_ising needs -h",
            offset=offset,
            h=h,
            J=[[a, b, v] for (a, b), v in J.items()],
        )
        return json.dumps(out) + "\n"
    if fmt == "qubo":
        out = _header(model, fmt)
        q = [[lab, lab, c] for lab, c in model.linear_terms().items()]
        q += [[a, b, v] for a, b, v in model.quadratic_terms()]
        out.update(convention="E = offset + sum Q[a][b] x_a x_b over 0/1 bits (a == b: linear)", offset=model.offset,
                   Q=q)
        return json.dumps(out) + "\n"
    if fmt == "lp":
        return mip_model(model).export_to_lp_string()
    if fmt == "mps":
        return mip_model(model).export_to_mps_string()
    raise ValueError(f"unknown export format {fmt!r} (expected one of {', '.join(EXPORT_FORMATS)})")
