"""The range of weights whose costs every solver represents exactly, and the one-line refusal outside it.

Every solver path computes the cost ``alpha0*c1 + alpha1*c2 + alpha2*c3`` (:mod:`qcpp.problem.cost`) in a number
format with a finite exact range:

* ``dfs``, ``anneal``, ``genetic``, ``qaoa`` (and the estimators' phase-separator reductions) in float64: every
  integer up to ``2**53`` is a float, beyond it two costs that differ by 1 can round to the same number, and
  beyond about ``1e308`` they overflow to ``inf``/``nan``;
* the QAOA circuit's simulated phases ``exp(-i gamma C)`` (``solve -m qaoa``, ``simulate``, ``validate``): a
  float error that grows like ``|C| * 2**-53``, exact to the simulators' 1e-8 only up to about ``2**26``
  (:data:`PHASE_COST_LIMIT`, :func:`check_phase_range`);
* ``cpsat`` on integers: the objective times the common denominator of its coefficients (``scale``) must stay
  within ``2**53`` (CP-SAT keeps its objective and bounds as doubles; beyond that it answers ``MODEL_INVALID``),
  and every weight must be a fraction with a denominator up to ``10**6``
  (:data:`qcpp.problem.solvers.cpsat.MAX_DENOMINATOR`).

So one range, the same for every solver, is checked before any work (:func:`check_cost_range`):

* each field on its own is within :func:`field_cap`: a weight at most ``2**53``, a length at most ``2**26.5``
  (about 9.5e7; a balance term squares it), whether or not this scenario's cost uses it;
* the largest cost any assignment of simple paths can have, :func:`cost_bound`, is at most
  :data:`COST_LIMIT` ``= 2**53`` (``cpsat``: ``2**53 / scale``);
* every nonzero weight has a magnitude of at least :data:`MIN_WEIGHT` ``= 1e-6`` (the finest weight CP-SAT
  reads exactly; far above float64's underflow of squared lengths).

Outside it the error names the field, its value and the largest magnitude the field may have with the other
fields as given, in one line (``ScenarioError``, so the CLI prints it with exit code 2).

The bound: a simple path has at most ``nodes - 1`` edges, so ``|c1| <= robots * (sum of the nodes - 1 largest
|w_e|)``, ``|L_r - L_s| <= L_max`` (the sum of the ``nodes - 1`` largest ``d_e``) and each balanced pair adds at
most ``L_max**2``, and a node's summed degree ``D_i`` lies in ``[0, 2 * robots]``, so ``(D_i - t_i)**2 <=
max(t_i, 2 * robots - t_i)**2``.

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> base = {"grid": {"rows": 3, "cols": 3},
    ...         "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}]}
    >>> cost_bound(scenario_from_dict(base))
    136.0
    >>> check_cost_range(scenario_from_dict(base))
    >>> try:
    ...     check_cost_range(scenario_from_dict({**base, "objective": {"edge_length": 1e9}}))
    ... except ScenarioError as exc:
    ...     print(exc.field)
    objective.edge_length
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass, replace

from qcpp.problem.cost import balanced_pairs
from qcpp.problem.errors import ScenarioError
from qcpp.problem.scenario import Objective, Scenario

__all__ = ["COST_LIMIT", "MIN_WEIGHT", "PHASE_COST_LIMIT", "WeightField", "check_cost_range", "check_phase_range",
           "cost_bound", "field_cap", "largest_allowed", "weight_fields"]

COST_LIMIT = float(2**53)
"""Largest cost magnitude every solver represents exactly (float64's exact integer range)."""

PHASE_COST_LIMIT = float(2**26)
"""Largest cost magnitude whose QAOA phases ``exp(-i gamma C)`` stay exact to the simulators' 1e-8: the float
error of a phase grows like ``|C| * 2**-53``; ``benchmarks/cost_range.py`` (``validate --backend sparse``, two robots
on 3x3): largest amplitude error 5.8e-10 at a cost bound of 6.4e7, 4.1e-8 (a failed check) at 6.4e9."""

MIN_WEIGHT = 1e-6
"""Smallest magnitude of a nonzero weight (CP-SAT reads weights as fractions with denominators up to 10**6)."""


@dataclass(frozen=True)
class WeightField:
    """One numeric field of a scenario's objective.

    Attributes:
        name: The field as the file writes it (``objective.alpha[1]``, ``objective.edge_lengths[0]``).
        value: Its value.
        positive: Whether the field must be positive (lengths) rather than any sign.
    """

    name: str
    value: float
    positive: bool = False


def weight_fields(scenario: Scenario) -> tuple[WeightField, ...]:
    """Every numeric field of ``scenario``'s objective, in file order.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> [f.name for f in weight_fields(s)][:4]
        ['objective.alpha[0]', 'objective.alpha[1]', 'objective.alpha[2]', 'objective.obstacle_weight']
    """
    ob = scenario.objective
    out = [WeightField(f"objective.alpha[{i}]", float(a)) for i, a in enumerate(ob.alpha)]
    out.append(WeightField("objective.obstacle_weight", float(ob.obstacle_weight)))
    out.append(WeightField("objective.free_weight", float(ob.free_weight)))
    out.append(WeightField("objective.edge_length", float(ob.edge_length), positive=True))
    out += [
        WeightField(f"objective.edge_lengths[{i}]", float(d), positive=True) for i, (_, d) in enumerate(ob.edge_lengths)
    ]
    return tuple(out)


def _with_value(ob: Objective, name: str, value: float) -> Objective:
    """``ob`` with the field ``name`` set to ``value`` (no validation: bounds only)."""
    if name.startswith("objective.alpha["):
        i = int(name[len("objective.alpha[") : -1])
        alpha = list(ob.alpha)
        alpha[i] = value
        return replace(ob, alpha=tuple(alpha))  # type: ignore[arg-type]
    if name.startswith("objective.edge_lengths["):
        i = int(name[len("objective.edge_lengths[") : -1])
        lengths = list(ob.edge_lengths)
        lengths[i] = (lengths[i][0], value)
        return replace(ob, edge_lengths=tuple(lengths))
    return replace(ob, **{name[len("objective.") :]: value})


def _top_sum(values: list[float], k: int) -> float:
    return sum(sorted(values, reverse=True)[:k])  # not fsum: it raises on overflow, sum gives inf


def cost_bound(scenario: Scenario, ob: Objective | None = None) -> float:
    """An upper bound on ``|cost|`` over every assignment of simple paths (see the module docstring), with the
    objective ``ob`` (default: the scenario's); ``inf`` when the bound itself overflows a float."""
    s, g, ob = scenario, scenario.grid, scenario.objective if ob is None else ob
    k = g.num_nodes - 1  # edges of a simple path, at most
    obstacle_edges = s.obstacle_edges
    lengths = dict.fromkeys(range(g.num_edges), abs(ob.edge_length))
    for (u, v), d in ob.edge_lengths:
        lengths[g.edge_index(u, v)] = abs(d)
    weights = [abs(ob.obstacle_weight) if e in obstacle_edges else abs(ob.free_weight) for e in s.variable_edges]
    c1 = s.num_robots * _top_sum(weights, k)
    l_max = _top_sum([lengths[e] for e in s.variable_edges], k)
    c2 = len(balanced_pairs(s)) * l_max * l_max if len(balanced_pairs(s)) else 0.0
    top = 2 * s.num_robots
    c3 = sum(float(max(t, top - t)) ** 2 for t in s.degree_targets if not math.isnan(t))
    a0, a1, a2 = (abs(a) for a in ob.alpha)
    terms = [a * c for a, c in ((a0, c1), (a1, c2), (a2, c3)) if a and c]
    if any(math.isinf(x) or math.isnan(x) for x in terms):
        return math.inf
    total = sum(terms)
    return math.inf if math.isnan(total) else total


def largest_allowed(scenario: Scenario, name: str, limit: float = COST_LIMIT) -> float:
    """The largest magnitude the field ``name`` may have, the other fields as given, for the bound to stay
    within ``limit`` (``inf``: the field does not matter for this scenario; ``0.0``: the others alone exceed it).

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> largest_allowed(s, "objective.edge_length")   # one robot: no balance term, lengths do not matter
        inf
    """
    ob = scenario.objective
    if cost_bound(scenario, _with_value(ob, name, 0.0)) > limit:
        return 0.0
    if cost_bound(scenario, _with_value(ob, name, 1e308)) <= limit:
        return math.inf
    lo_bits, hi_bits = 0, _bits(1e308)  # bisection on the float's bits (ordered like the floats >= 0)
    while hi_bits - lo_bits > 1:
        mid = (lo_bits + hi_bits) // 2
        if cost_bound(scenario, _with_value(ob, name, _float(mid))) <= limit:
            lo_bits = mid
        else:
            hi_bits = mid
    return _float(lo_bits)


def _bits(x: float) -> int:
    return struct.unpack("<q", struct.pack("<d", x))[0]


def _float(bits: int) -> float:
    return struct.unpack("<d", struct.pack("<q", bits))[0]


def field_cap(field: WeightField, limit: float = COST_LIMIT) -> float:
    """The largest magnitude ``field`` may have on any grid: ``limit`` for a weight (it multiplies a count of at
    least 1), ``sqrt(limit)`` for a length (a balance term squares it). A field the scenario's cost does not use
    (``alpha[1]`` with one robot) is held to this too: such a value is a typo more often than not.

    Example:
        >>> field_cap(WeightField("objective.edge_length", 1.0, positive=True)) == 2 ** 26.5
        True
    """
    return math.sqrt(limit) if field.positive else limit


def check_cost_range(scenario: Scenario, *, limit: float = COST_LIMIT, solver: str = "") -> None:
    """Refuse weights whose costs the solvers cannot represent exactly (see the module docstring).

    Args:
        limit: The largest cost magnitude allowed (:data:`COST_LIMIT`; ``cpsat`` passes ``2**53 / scale``).
        solver: Named in the message when the limit is a solver's own (``"cpsat (objective scaled by 4)"``).

    Raises:
        ScenarioError: naming the field, its value and the allowed range.
    """
    for f in weight_fields(scenario):
        if f.value != 0 and abs(f.value) < MIN_WEIGHT:
            allowed = f"at least {MIN_WEIGHT:g}" if f.positive else f"0 or at least {MIN_WEIGHT:g} in magnitude"
            raise ScenarioError(
                f.name,
                f"{f.value:g} is too small for the solvers to represent exactly: the allowed range is {allowed} "
                f"(CP-SAT reads weights as fractions with denominators up to 10^6; scale all weights up instead)",
            )
    bound = cost_bound(scenario)
    if bound <= limit:
        for f in weight_fields(scenario):  # on its own, whether or not this scenario's cost uses it
            cap = field_cap(f, limit)
            if abs(f.value) > cap:
                short = f.name.split(".")[-1]
                allowed = f"{MIN_WEIGHT:g} <= {short} <= " if f.positive else f"|{short}| <= "
                enters = "a balance term squares it" if f.positive else "it multiplies a count of at least 1"
                raise ScenarioError(
                    f.name,
                    f"{f.value:g} is too large for {solver or 'the solvers'} to represent the cost exactly in any "
                    f"scenario (allowed: {allowed}{_round_down(cap)}: {enters}, and costs are exact up to "
                    f"{limit:.3g}; this scenario's cost does not use it yet)",
                )
        return
    # the field to blame: the one whose reset to its default shrinks the bound the most
    default = Objective()
    defaults = {"objective.obstacle_weight": default.obstacle_weight, "objective.free_weight": default.free_weight}
    fields = weight_fields(scenario)
    worst = min(
        fields,
        key=lambda f: cost_bound(scenario, _with_value(scenario.objective, f.name, defaults.get(f.name, 1.0))),
    )
    worst_max = largest_allowed(scenario, worst.name, limit)
    assert worst is not None
    who = solver or "the solvers"
    reach = "overflows a float" if math.isinf(bound) else f"could reach {bound:.3g}"
    if worst_max == 0:
        allowed = "other weights are out of range too: no value of it fits until they are smaller"
    else:
        short = worst.name.split(".")[-1]
        low = f"{MIN_WEIGHT:g} <= {short} <= " if worst.positive else f"|{short}| <= "
        allowed = f"allowed with the other weights as given: {low}{_round_down(worst_max)}"
    raise ScenarioError(
        worst.name,
        f"{worst.value:g} is too large for {who} to represent the cost exactly ({allowed}; "
        f"the cost {reach}, over the exact range |cost| <= {limit:.3g})",
    )


def check_phase_range(scenario: Scenario) -> None:
    """:func:`check_cost_range` with :data:`PHASE_COST_LIMIT`: what simulating the QAOA circuit (``solve -m qaoa``,
    ``simulate``, ``validate``) needs for its phases to be exact to 1e-8 (``compile`` only writes the angles, and
    takes the general range).

    Raises:
        ScenarioError: naming the field, its value and the allowed range.
    """
    check_cost_range(scenario, limit=PHASE_COST_LIMIT, solver="the QAOA circuit's phases (exact to 1e-8)")


def _round_down(x: float) -> str:
    """``x`` to 3 significant digits, rounded towards zero (so the printed value is allowed)."""
    if x == 0 or math.isinf(x):
        return f"{x:g}"
    exp = math.floor(math.log10(x)) - 2
    return f"{math.floor(x / 10**exp) * 10**exp:.3g}"
