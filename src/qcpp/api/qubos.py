"""``qcpp.qubo_model`` and ``qcpp.write_qubo``: a scenario's cost as a binary quadratic model (``qcpp export``).

The model is :class:`qcpp.qubo.model.Bqm` (labels, linear and quadratic coefficients, offset; ``energy(bits)``,
``to_ising()``, ``to_dimod()``); :func:`write_qubo` writes it in the command's formats, so
``write_qubo(qubo_model(s, ...), path, fmt)`` writes the file ``qcpp export --format FMT --out PATH`` writes. The
forms (``per-robot`` with its degree penalty, or the paper's) are described in the QUBO docs page.

Example:
    >>> import qcpp
    >>> model = qcpp.qubo_model(qcpp.grid_scenario(2, 2, robots=1), form="paper")
    >>> model.num_variables, model.form, model.energy([1, 1, 0, 0]) == model.energy([0, 0, 1, 1])
    (4, 'paper', True)
    >>> qcpp.qubo_model(qcpp.grid_scenario(2, 2, robots=1), form="paper", penalty=3.0)
    Traceback (most recent call last):
    ...
    qcpp.errors.OptionError: penalty: applies to form='per-robot' only (got form='paper')
"""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING

from qcpp.api.checks import check_scenario_arg
from qcpp.api.scenarios import Scenario
from qcpp.errors import OptionError, check_choice

if TYPE_CHECKING:
    from qcpp.qubo.model import Bqm

__all__ = ["qubo_model", "write_qubo"]


def qubo_model(scenario: Scenario, *, form: str = "per-robot", penalty: float | None = None) -> Bqm:
    """The cost of ``scenario`` as a binary quadratic model (``qcpp export``'s model).

    Args:
        form: ``per-robot`` (edge and visit variables, degree penalties that vanish on feasible paths, so every
            feasible assignment's energy is its cost) or ``paper`` (the paper's cost exactly, over the edge
            variables). At the rule's penalty every minimum of ``per-robot`` has right degrees: each robot's edges
            are a start-goal path plus zero or more separate cycles, and the minimum energy is at most the feasible
            optimum. The minima are exactly the optimal feasible assignments when no such cycle lowers the energy;
            where one does (a cycle covers nodes or balances lengths), the minima lie below the optimum and are
            not feasible. Dropping the cycles (:func:`qcpp.qubo.solve.drop_cycles`) then leaves feasible paths,
            not necessarily optimal ones (docs/qubo.md, "What degree penalties cannot see: cycles").
        penalty: ``per-robot``: the degree-penalty weight ``P`` (default: the documented rule, large enough that
            no assignment with a wrong degree has an energy at or below the feasible optimum).

    Returns:
        The :class:`~qcpp.qubo.model.Bqm`; its first ``num_edge_variables`` variables are the circuit's data
        qubits, in order.

    Raises:
        qcpp.errors.OptionError: an unknown form, or a penalty that is not a positive finite number or is given
            with ``paper``.
    """
    from qcpp.qubo.model import FORMS, bqm_for

    s = check_scenario_arg(scenario)
    check_choice(form, FORMS, "form")
    if penalty is not None:
        if form != "per-robot":
            raise OptionError("penalty", f"applies to form='per-robot' only (got form={form!r})")
        if isinstance(penalty, bool) or not isinstance(penalty, (int, float)) or not (
            math.isfinite(penalty) and penalty > 0
        ):
            raise OptionError("penalty", f"expected a positive finite number, got {penalty!r}")
    return bqm_for(s, form, None if penalty is None else float(penalty))


def write_qubo(model: Bqm, path: str | os.PathLike[str], format: str) -> None:
    """Write ``model`` to ``path`` in ``format`` (``qcpp export --format``), whole or not at all.

    Args:
        model: A model of :func:`qubo_model`.
        path: The file.
        format: ``qubo`` or ``ising`` (JSON), ``bqm`` (dimod's serialisable JSON; needs dimod), ``lp`` or ``mps``
            (a MIP of the same minimum, for OR-Tools, SCIP, Gurobi, ...).

    Raises:
        qcpp.errors.OptionError: an unknown format, ``bqm`` without dimod, or not a model.
        qcpp.io.atomic.OutputError: a destination that cannot be written.
    """
    from qcpp.io.atomic import check_output, write_text_atomic
    from qcpp.qubo.export import EXPORT_FORMATS, export_text
    from qcpp.qubo.model import Bqm
    from qcpp.qubo.solve import INSTALL_HINT

    if not isinstance(model, Bqm):
        raise OptionError("model", f"expected the result of qcpp.qubo_model, got {type(model).__name__}")
    check_choice(format, EXPORT_FORMATS, "format")
    if format == "bqm":
        try:
            import dimod  # noqa: F401
        except ImportError:
            reason = f"bqm needs dimod: {INSTALL_HINT} (ising, qubo, lp, mps need nothing)"
            raise OptionError("format", reason) from None
    target = os.fspath(path)
    check_output(target)
    write_text_atomic(target, export_text(model, format))
