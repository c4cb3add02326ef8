"""``qcpp.estimate``: the resource counts of one scenario's QAOA circuit, the row ``qcpp estimate --json`` prints.

The estimate goes through the command's own code (:func:`qcpp.estimators.report.estimate_rows`), so
:meth:`Estimate.to_dict` is that command's JSON row for the same scenario and options. A scenario equal to the
default placement of its grid and robot count (``qcpp.grid_scenario(rows, cols, robots=N)``) is the row of
``qcpp estimate --grid RxC --robots N`` (``scenario: "default"``); any other is the row of ``--scenario FILE``, or of
the inline ``--grid``/``--robots``/``--obstacle`` options that build it (``scenario: "custom"``).

Example:
    >>> from qcpp.api.scenarios import grid_scenario
    >>> est = estimate(grid_scenario(3, 3, robots=1), p=2)
    >>> est.qubits, est.cx, est.depth_kind
    (15, 212, 'exact')
    >>> est.to_dict()["cx"] == est.cx
    True
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any, Generic, TypeVar, overload

from qcpp.api.checks import check_context_arg, check_layers_arg, check_scenario_arg, plan_options_arg
from qcpp.api.progress import ProgressArg, check_progress_arg, reporting
from qcpp.api.scenarios import Scenario, default_scenario
from qcpp.errors import OptionError, check_choice
from qcpp.io.html import html_table

if TYPE_CHECKING:
    import os
    from collections.abc import Iterable

    from matplotlib.figure import Figure

    from qcpp.hardware.device import Device
    from qcpp.routing.context import RoutingContext

__all__ = ["Estimate", "estimate", "plot_estimates"]

T = TypeVar("T")


class _Column(Generic[T]):
    """An attribute of :class:`Estimate` that reads the row's column of its own name."""

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, obj: None, owner: type) -> _Column[T]: ...
    @overload
    def __get__(self, obj: Estimate, owner: type) -> T: ...
    def __get__(self, obj: Estimate | None, owner: type) -> T | _Column[T]:
        if obj is None:
            return self
        return obj._row[self.name]  # type: ignore[no-any-return]


class Estimate:
    """One row of ``qcpp estimate --json``: every column is an attribute (``est.cx``, ``est.ft_total_t``,
    ``est.routed_twoq`` with a device, ``est.physical_qubits`` with ``physical=True``, ``est.paper_cx`` with
    ``compare_paper=True``). What each column counts, and in which unit: the resource-estimates page of the docs
    (docs/resource-estimates.md: "What is counted", "Fault-tolerant view", "Physical estimates", "Figures of
    merit").

    Immutable; ``to_dict()`` gives the row (a fresh copy each call); a notebook shows it as a table.
    """

    __slots__ = ("_row",)

    rows = _Column[int]()
    cols = _Column[int]()
    robots = _Column[int]()
    p = _Column[int]()
    rule = _Column[str]()
    target = _Column[str]()
    scenario = _Column[str]()
    qubits = _Column[int]()
    data_qubits = _Column[int]()
    ancillas = _Column[int]()
    gates = _Column[int]()
    cx = _Column[int]()
    single_qubit = _Column[int]()
    two_qubit = _Column[int]()
    t = _Column[int]()
    rotations = _Column[int]()
    depth = _Column["int | None"]()
    two_qubit_depth = _Column["int | None"]()
    rotation_depth = _Column["int | None"]()
    depth_kind = _Column["str | None"]()
    toffoli = _Column[int]()
    ft_total_t = _Column[int]()
    sections = _Column["dict[str, dict[str, int]]"]()

    def __init__(self, row: dict[str, Any]) -> None:
        object.__setattr__(self, "_row", json.loads(json.dumps(row)))  # the JSON's values, nothing shared

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"an Estimate is immutable (cannot set {name!r})")

    def __getattr__(self, name: str) -> Any:
        try:
            return self._row[name]
        except KeyError:
            raise AttributeError(
                f"an Estimate has no column {name!r} (its columns: {', '.join(self.columns)})"
            ) from None

    def __dir__(self) -> list[str]:
        return sorted({*super().__dir__(), *self._row})

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Estimate) and self._row == other._row

    def __hash__(self) -> int:
        return hash(json.dumps(self._row, sort_keys=True))

    @property
    def columns(self) -> tuple[str, ...]:
        """The row's columns, in the command's order (``sections`` included)."""
        return tuple(self._row)

    def to_dict(self) -> dict[str, Any]:
        """The row: equal to ``qcpp estimate --json``'s for the same scenario and options."""
        return json.loads(json.dumps(self._row))

    def __iter__(self) -> Iterator[tuple[str, Any]]:
        return iter(self.to_dict().items())

    def __repr__(self) -> str:
        g = f"{self.rows}x{self.cols}, {self.robots} robot(s), p={self.p}"
        depth = f"{self.depth} ({self.depth_kind})" if self.depth is not None else "not computed"
        return f"<Estimate {g}: {self.qubits} qubits, {self.cx} CX, {self.t} T, depth {depth}>"

    def _repr_html_(self) -> str:
        """The row as a two-column HTML table (column, value), numbers right-aligned."""
        rows = [(name, "" if value is None else (f"{value:.4g}" if isinstance(value, float) else str(value)))
                for name, value in self._row.items() if name != "sections"]  # fmt: skip
        return html_table(repr(self)[1:-1], ("column", "value"), rows, align=("left", "right"))


def estimate(
    scenario: Scenario,
    p: int = 1,
    *,
    device: str | Device | None = None,
    compare_paper: bool = False,
    paper_doubling: str = "partial-mixer",
    epsilon: float = 1e-3,
    toffoli_t: int = 7,
    depth: str = "auto",
    depth_budget: int = 20_000,
    physical: bool = False,
    qubit_model: str = "qubit_gate_ns_e3",
    qec_scheme: str = "surface_code",
    error_budget: float = 1e-3,
    effort: str = "full",
    progress: ProgressArg = None,
    context: RoutingContext | None = None,
    **plan_options: Any,
) -> Estimate:
    """Resource counts of the lowered QAOA circuit of ``scenario`` with ``p`` layers, without building it.

    The options are those of ``qcpp estimate`` (``--device``, ``--compare paper``, ``--epsilon``, ...), with the
    same defaults and checks.

    Args:
        scenario: The scenario (``qcpp.grid_scenario`` or ``qcpp.load_scenario``).
        p: QAOA layers (at least 1).
        device: Add the routed figures on this device (``qcpp.devices()``, or ``grid[:RxC]``,
            ``heavy-hex[:D]``, ``all-to-all[:N]``, a device file's path, or a :class:`~qcpp.Device`); this compiles
            and routes the circuit.
        compare_paper: Add the paper's estimates and the ratios.
        paper_doubling: Reading of the paper's doubling: ``partial-mixer`` or ``logic``.
        epsilon: The fault-tolerant model's rotation synthesis precision.
        toffoli_t: The fault-tolerant model's T per Toffoli: 7 or 4.
        depth: ``auto``, ``exact``, ``bound`` or ``none``.
        depth_budget: The lowered gates per layer up to which ``auto`` computes the exact depth.
        physical: Add the physical estimates of the QDK resource estimator.
        qubit_model: The QDK qubit model of the physical estimates.
        qec_scheme: The QDK error-correction scheme of the physical estimates.
        error_budget: The QDK error budget of the physical estimates.
        effort: With a device: ``full`` (the default: every search) or ``quick`` (no choice of partial-mixer plans
            for the routing, as ``qcpp.compile(..., effort="quick")``; ``routed_model`` then says so). It changes
            only rows compiled whole: small circuits, where that choice is made. ``qcpp estimate --effort``.
        progress: ``True`` for progress lines on stderr, or a function ``progress(done, total)``
            (:mod:`qcpp.api.progress`) called as each stage of the ``device`` routing starts (``progress(1, None)``,
            ...). The counts alone take milliseconds and report nothing; a sweep is a loop over calls, whose own
            count is the progress.
        context: With a device: a :class:`~qcpp.RoutingContext` shared with the calls that route the same circuits
            (``compile`` of the same scenario on the same device, a sweep over devices): their searches, and a
            whole compile of the same circuit, are answered from it, with the same result (default: a fresh one
            per call).
        **plan_options: How the circuit is built: ``rule``, ``initial``, ``target``, ``phase``, ``optimize``,
            ``ancilla_budget``, ``phase_layout``, ``angles``, ``first_phase`` (``False``: no first phase separator,
            exact from a basis-state start; :class:`~qcpp.plan.options.PlanOptions`).

    Returns:
        The :class:`Estimate`.

    Raises:
        qcpp.errors.OptionError: a bad ``p`` or option (named), or an unknown plan option.
        qcpp.hardware.device.DeviceError: an unknown device, or a device file that cannot be read or is malformed.
        qcpp.problem.errors.ScenarioError: weights the circuit cannot represent exactly.
    """
    from qcpp.estimators.estimate import Point, checked_estimate_options
    from qcpp.estimators.paper import DOUBLINGS
    from qcpp.estimators.report import estimate_rows
    from qcpp.hardware.device import device_arg, device_label
    from qcpp.problem.cost_range import check_cost_range
    from qcpp.routing.options import EFFORTS, effort_routing

    s = check_scenario_arg(scenario)
    layers = check_layers_arg(p)
    plan = plan_options_arg(plan_options)
    settings = checked_estimate_options(
        plan, epsilon=epsilon, toffoli_t=toffoli_t, depth=depth, depth_budget=depth_budget, physical=physical,
        qubit_model=qubit_model, qec_scheme=qec_scheme, error_budget=error_budget,
    )  # fmt: skip
    check_choice(paper_doubling, DOUBLINGS, "paper_doubling")
    if not isinstance(compare_paper, bool):
        raise OptionError("compare_paper", f"expected True or False, got {compare_paper!r}")
    check_choice(effort, EFFORTS, "effort")
    if device is not None:
        device = device_arg(device)  # an unknown name or a bad file fails before any work; a file is read once
    elif effort != "full":
        raise OptionError("effort", f"{effort!r} applies with a device only (no device given)")
    check_progress_arg(progress)
    check_context_arg(context, device)
    check_cost_range(s)  # what the command line checks when it loads a file
    point = _point(s, layers, Point)
    task = f"estimate p={layers} on {s.grid.rows}x{s.grid.cols}, {s.num_robots} robot(s)"
    if device is not None:
        task += f", device {device_label(device)}"
    with reporting(progress, task, unit="stages", stages=True) as bar:

        def stage(text: str) -> None:
            if bar is not None and text:  # "" ends a row: no stage
                bar.stage(text)

        rows = estimate_rows([point], settings, compare_paper, paper_doubling, device, stage,  # type: ignore[arg-type]
                             context, routing=effort_routing(effort))  # fmt: skip
        return Estimate(next(rows))


def plot_estimates(
    estimates: Iterable[Estimate | dict[str, Any]],
    metric: str = "cx",
    *,
    compare_paper: bool = False,
    path: str | os.PathLike[str] | None = None,
    figsize: tuple[float, float] | None = None,
) -> Figure:
    """Plot one column of several estimates: the plot of ``qcpp estimate --plot FILE --metric METRIC``.

    Against the grid's node count with one panel per ``p`` when the estimates cover several grid sizes, else
    against ``p`` (one grid), else against the robot count; one curve per robot count, one point per estimate (a
    curve with several grids of one size, such as ``3x4`` and ``4x3``, is drawn without a line). Style it with
    matplotlib's ``rcParams`` before the call (fonts, sizes), or through the returned figure.

    Args:
        estimates: :class:`Estimate` objects (or their ``to_dict()`` rows), of one SBF rule.
        metric: The column to draw: ``cx``, ``qubits``, ``t``, ``depth``, ``ft_total_t``, ... (every choice:
            :data:`qcpp.estimators.plots.PLOT_METRICS`); ``physical_*`` need estimates made with ``physical=True``,
            the routed columns (``routed_twoq``, ``esp``, ...) a ``device``.
        compare_paper: Also draw the paper's estimate of the metric as dashed curves (qubits, data_qubits, cx and
            single_qubit: the quantities the paper estimates; for any other metric a warning says it has none).
        path: Also save the figure here (PNG, PDF, SVG, ... by the suffix), whole or not at all.
        figsize: The figure's size in inches.

    Returns:
        The ``matplotlib.figure.Figure``.

    Raises:
        qcpp.errors.OptionError: an unknown metric (the message lists the choices).
        ValueError: no estimates, or none with a value for the metric.

    Example:
        >>> import qcpp
        >>> ests = [qcpp.estimate(qcpp.grid_scenario(3, 3, robots=1), p=k, depth="none") for k in (1, 2)]
        >>> fig = qcpp.plot_estimates(ests, "cx")
        >>> fig.axes[0].get_xlabel(), fig.axes[0].get_ylabel()
        ('QAOA layers p', 'CNOT gates: cx [gates]')
    """
    from qcpp.estimators.plots import draw_rows
    from qcpp.io.atomic import save_figure_atomic

    rows = [e.to_dict() if isinstance(e, Estimate) else dict(e) for e in estimates]
    fig = draw_rows(rows, metric, compare_paper=compare_paper, figsize=figsize)
    if path is not None:
        save_figure_atomic(fig, path, dpi=150, bbox_inches="tight")
    return fig


def _point(s: Scenario, p: int, point_type: Any) -> Any:
    """The command line's point for ``s``: ``--grid/--robots`` for a default placement, else ``--scenario``."""
    g = s.grid
    if s.num_robots <= 2 * (g.rows + g.cols) - 4 and s == default_scenario(g.rows, g.cols, s.num_robots):
        return point_type(g.rows, g.cols, s.num_robots, p)
    return point_type.from_scenario(s, p)
