"""Exact QAOA simulation restricted to the paths the SBF mixer can reach.

The simulated operator is the compiled circuit's (:mod:`qcpp.plan.qaoa`) on its data register:

* **Basis.** Data qubit ``i`` is decision variable ``i``, so a basis state is an *assignment* (one edge mask per
  robot). The mixer never leaves the paths reachable from the initial support by allowed SBF moves, so robot ``r``
  gets the basis ``bases[r]`` of those paths (:func:`qcpp.problem.sbf.reachable_paths`, BFS order) and the state
  is a complex array of shape ``(n_0, ..., n_{R-1})``.
* **Initial state.** ``initial_path`` (default): every robot on :func:`~qcpp.problem.paths.initial_path`;
  ``representatives``: the uniform superposition of :func:`~qcpp.problem.sbf.representatives` (one path per
  move-graph component; the bases then hold every component); ``local_search``: the path of the classical warm
  start :func:`qcpp.problem.solvers.descent.local_search`; ``local_search_mix``: ``(|initial> + |descent>)/sqrt 2``
  per robot. Each is a product over robots.
* **Layer k** (angles ``[gamma_0, beta_0, gamma_1, ...]``): the phase separator multiplies the amplitude of ``x``
  by ``exp(-i gamma_k (C(x) - phase_offset))``, ``C`` the cost and ``phase_offset`` the constant the compiled
  circuit leaves out as a global phase (``"feasible"``: the reference constant of
  :func:`qcpp.plan.phase.phase_plan`; ``"whole-space"``: the Ising constant; or a number). Then for robot ``r``
  and plaquette ``q`` (row-major), where ``sbf_logic(scenario, r, q, rule)`` allows the flip, the pair
  ``(x, x')`` is rotated by ``exp(-i beta_k X / 2)``.

Each partial mixer is a set of disjoint 2x2 rotations along one robot's axis, applied by compiled numba kernels
(:mod:`qcpp.simulate.subspace_kernels`, ``kernels="auto"``) or by BLAS ``zrot`` (``kernels="blas"``; the tests
compare the two). The cost diagonal is stored as a small integer level per amplitude plus a table of the distinct
cost values, so a phase separator is a table look-up. Gradients are exact (adjoint differentiation).

**The paper rule.** A partial mixer is unitary on the data register only if the rule's relation is symmetric
(``allowed(x)`` iff ``allowed(x')``). The ``paper`` rule can leave the feasible set and reach a plaquette whose
flip is allowed while the flip back is not; there the compiled circuit leaves its logic ancillas entangled with
the data, and :class:`SubspaceQAOA` raises :class:`NonUnitaryMixerError`. Where the relation is symmetric the
paper rule is simulated exactly, infeasible edge sets included (flagged in :attr:`SubspaceQAOA.feasible` and
excluded from the optimum of :meth:`SubspaceQAOA.p_optimum`).

Example:
    >>> from qcpp.problem.scenario import scenario_from_dict
    >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
    >>> q = SubspaceQAOA(s)
    >>> q.dims, q.dimension
    ((12,), 12)
    >>> angles = [0.3, 1.1]
    >>> round(float(abs(q.state(angles)).max()), 6) < 1.0, round(float(q.probabilities(angles).sum()), 12)
    (True, 1.0)
    >>> q.expectation(angles) < q.expectation([0.0, 0.0])   # p=1 already moves weight to cheaper paths
    True
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from typing import Literal

import numpy as np
from scipy.linalg.blas import zdotc
from scipy.linalg.lapack import zrot

from qcpp.errors import QcppError
from qcpp.gadgets.initial_state import start_paths
from qcpp.plan.options import INITIAL_STATES, Initial
from qcpp.plan.phase import phase_plan
from qcpp.problem.cost import assignment_costs
from qcpp.problem.hamiltonian import ising_hamiltonian
from qcpp.problem.paths import enumerate_paths, is_feasible, path_bits
from qcpp.problem.sbf import RULES, Rule, SbfLogic, sbf_logic
from qcpp.problem.scenario import Scenario
from qcpp.simulate import subspace_kernels

__all__ = [
    "INITIAL_STATES",
    "InitialState",
    "NonUnitaryMixerError",
    "RobotBasis",
    "SubspaceQAOA",
    "angle_bindings",
    "evaluate_logic",
    "robot_basis",
    "split_angles",
]

InitialState = Initial  # the compiler's initial states: the simulator prepares exactly what compile emits
Kernels = Literal["auto", "numba", "blas"]

_CHUNK = 1 << 18  # elements per chunk of the element-wise loops
_DEFAULT_BUFFER = 1 << 22  # complex amplitudes (64 MiB) in the transposed buffer of a short-stride axis
_DIRECT_MIN = 64  # rotate rows in place when the axis' contiguous run (post) is at least this long
MAX_LEVELS = 1 << 16
"""Most distinct cost values a level table holds (a ``uint16`` level per amplitude)."""


class NonUnitaryMixerError(QcppError):
    """The SBF rule allows a flip whose reverse it forbids, on a path the mixer reaches.

    The compiled partial mixer is then not a unitary on the data register (its logic ancillas end entangled
    with the data), so no feasible-subspace state vector exists.
    """


@dataclass(frozen=True, eq=False)
class RobotBasis:
    """One robot's reachable paths and the rotations of each partial mixer on them.

    Attributes:
        paths: The basis: edge masks in BFS order (the initial support first; with one initial path exactly
            :func:`qcpp.problem.sbf.reachable_paths`).
        feasible: ``(n,)`` bool, whether each path is a feasible start-goal path.
        initial: ``(n,)`` float, the robot's initial amplitudes (real, non-negative, unit norm).
        pairs: One ``(plaquette, i, j)`` per plaquette whose flip is allowed somewhere, plaquettes ascending:
            index arrays with ``paths[i[k]] ^ plaquette mask == paths[j[k]]`` and ``i[k] < j[k]`` ascending.
    """

    robot: int
    paths: tuple[int, ...]
    feasible: np.ndarray
    initial: np.ndarray
    pairs: tuple[tuple[int, np.ndarray, np.ndarray], ...]

    @property
    def size(self) -> int:
        return len(self.paths)

    def index(self, mask: int) -> int:
        """Position of ``mask`` in :attr:`paths`.

        Raises:
            KeyError: if the mask is not reachable.
        """
        lookup = self.__dict__.get("_lookup")
        if lookup is None:
            lookup = {m: i for i, m in enumerate(self.paths)}
            object.__setattr__(self, "_lookup", lookup)
        return lookup[mask]


def evaluate_logic(logic: SbfLogic, masks: np.ndarray) -> np.ndarray:
    """:meth:`qcpp.problem.sbf.SbfLogic.evaluate` on many masks at once.

    Args:
        logic: The compiled logic function.
        masks: ``(N,)`` edge masks, ``int64`` (grids with at most 63 edges) or ``object`` (Python ints).

    Returns:
        ``(N,)`` bool.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> from qcpp.problem.sbf import enumerate_paths
        >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
        >>> lg = sbf_logic(s, 0, s.grid.plaquettes[0])
        >>> paths = enumerate_paths(s, 0)
        >>> evaluate_logic(lg, np.array(paths)).tolist() == [lg.evaluate(m) for m in paths]
        True
    """
    n = len(masks)
    temps = [np.zeros(n, dtype=bool) for _ in range(logic.num_temps)]
    bits: dict[int, np.ndarray] = {}
    for step in logic.steps:
        acc = np.ones(n, dtype=bool)
        for lit in step.literals:
            if lit.signal < 0:
                v = temps[~lit.signal]
            else:
                v = bits.get(lit.signal)
                if v is None:
                    v = bits[lit.signal] = ((masks >> lit.signal) & 1).astype(bool)
                if lit.xor is not None:
                    w = bits.get(lit.xor)
                    if w is None:
                        w = bits[lit.xor] = ((masks >> lit.xor) & 1).astype(bool)
                    v = v ^ w
            acc &= v if lit.value else ~v
        temps[step.target] ^= acc
    return temps[logic.output]


def _mask_array(masks: Sequence[int], num_edges: int) -> np.ndarray:
    return np.array(masks, dtype=np.int64 if num_edges <= 62 else object)


def robot_basis(
    scenario: Scenario, robot: int, rule: Rule = "exact", initial: InitialState = "initial_path"
) -> RobotBasis:
    """Build a robot's reachable basis and its partial mixers' rotation pairs.

    The basis is the breadth-first closure of the initial support under allowed SBF moves, in the order of
    :func:`qcpp.problem.sbf.reachable_paths` started from each initial path in turn (unioned); the logic is
    evaluated on whole BFS levels at once with :func:`evaluate_logic`.

    Args:
        rule: SBF rule, ``exact`` or ``paper``.
        initial: One of :data:`~qcpp.gadgets.initial_state.INITIAL_STATES` (see the module docstring).

    Raises:
        ValueError: for an unknown rule or initial state.
        NonUnitaryMixerError: if the rule's relation is not symmetric on the reachable paths.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]})
        >>> b = robot_basis(s, 0)
        >>> b.size, [(q, i.tolist(), j.tolist()) for q, i, j in b.pairs]
        (2, [(0, [0], [1])])
    """
    if rule not in RULES:
        raise ValueError(f"unknown SBF rule {rule!r} (expected one of {', '.join(RULES)})")
    if initial not in INITIAL_STATES:
        raise ValueError(f"unknown initial state {initial!r} (expected one of {', '.join(INITIAL_STATES)})")
    grid = scenario.grid
    starts = start_paths(scenario, robot, initial, rule)
    moves = [
        (q.index, q.edge_mask, lg) for q in grid.plaquettes if not (lg := sbf_logic(scenario, robot, q, rule)).never
    ]
    paths: list[int] = []
    lookup: dict[int, int] = {}
    for st in starts:
        if st in lookup:
            continue
        lookup[st] = len(paths)
        paths.append(st)
        frontier = [st]
        while frontier:
            arr = _mask_array(frontier, grid.num_edges)
            allowed = np.stack([evaluate_logic(lg, arr) for _, _, lg in moves], axis=1) if moves else None
            nxt: list[int] = []
            if allowed is not None:
                for f, k in zip(*np.nonzero(allowed)):  # row-major: node by node, plaquettes ascending
                    m = frontier[f] ^ moves[k][1]
                    if m not in lookup:
                        lookup[m] = len(paths)
                        paths.append(m)
                        nxt.append(m)
            frontier = nxt
    arr = _mask_array(paths, grid.num_edges)
    pairs: list[tuple[int, np.ndarray, np.ndarray]] = []
    for qi, qmask, lg in moves:
        ok = evaluate_logic(lg, arr)
        ii = np.flatnonzero(ok)
        if ii.size == 0:
            continue
        jj = np.array([lookup[paths[i] ^ qmask] for i in ii.tolist()], dtype=np.intp)  # closed under moves
        bad = ~ok[jj]
        if bad.any():
            i, j = int(ii[bad][0]), int(jj[bad][0])
            raise NonUnitaryMixerError(
                f"rule {rule!r}, robot {robot}, plaquette {qi}: the flip of path {paths[i]:#x} is allowed but "
                f"the flip back from {paths[j]:#x} is not (feasible: {is_feasible(scenario, robot, paths[i])} -> "
                f"{is_feasible(scenario, robot, paths[j])}); the partial mixer is not unitary on the data "
                "register. Use rule='exact', or a gate-level simulator to see what the compiled circuit does"
            )
        keep = ii < jj
        pairs.append((qi, ii[keep].astype(np.intp), jj[keep]))
    amp = np.zeros(len(paths))
    amp[[lookup[st] for st in starts]] = 1.0
    amp /= np.sqrt(amp.sum())
    if rule == "exact":
        # the exact rule only allows flips whose result is feasible (qcpp.problem.sbf, checked exhaustively in
        # its tests), and every start is a feasible path
        feasible = np.ones(len(paths), dtype=bool)
    else:
        feasible = np.array([is_feasible(scenario, robot, m) for m in paths], dtype=bool)
    basis = RobotBasis(robot, tuple(paths), feasible, amp, tuple(pairs))
    object.__setattr__(basis, "_lookup", lookup)
    return basis


def split_angles(angles: Sequence[float] | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Split ``[gamma_0, beta_0, gamma_1, beta_1, ...]`` into ``(gammas, betas)`` (empty for ``p = 0``).

    Raises:
        ValueError: if the vector has odd length or a value that is not finite.

    Example:
        >>> [g.tolist() for g in split_angles([0.1, 0.2, 0.3, 0.4])]
        [[0.1, 0.3], [0.2, 0.4]]
    """
    a = np.asarray(angles, dtype=float).reshape(-1)
    if a.size % 2:
        raise ValueError(f"angles must be [gamma_0, beta_0, ...] of even length, got {a.size} values")
    if not np.all(np.isfinite(a)):
        raise ValueError("angles must be finite")
    return a[0::2].copy(), a[1::2].copy()


def angle_bindings(angles: Sequence[float] | np.ndarray) -> dict[str, float]:
    """The compiled circuit's symbol values ``gamma_k``, ``beta_k`` for ``[gamma_0, beta_0, ...]``.

    Example:
        >>> angle_bindings([0.1, 0.2])
        {'gamma_0': 0.1, 'beta_0': 0.2}
    """
    gammas, betas = split_angles(angles)
    return {f"gamma_{k}": float(g) for k, g in enumerate(gammas)} | {f"beta_{k}": float(b) for k, b in enumerate(betas)}


@cache
def _check_lapack_in_place() -> None:
    """The kernels rely on f2py handing ``zrot`` the caller's buffer (``overwrite_x=1`` on a contiguous
    complex128 array); make sure this build of scipy does, once per process
    (``_check_lapack_in_place.cache_clear()`` checks again)."""
    x = np.array([1.0, 0.0], dtype=np.complex128)
    zrot(x, x, 0.0, 1.0 + 0j, 1, 0, 1, 1, 1, 1, 1)
    if not np.allclose(x, [0.0, -1.0]):
        raise RuntimeError("scipy's LAPACK zrot did not work in place; the subspace simulator cannot run here")


def _phase_offset(scenario: Scenario, offset: float | str | None) -> float:
    """Resolve ``phase_offset`` (see :class:`SubspaceQAOA`)."""
    if offset is None or offset == "feasible":
        return float(phase_plan(scenario).reference_constant)
    if offset == "whole-space":
        return float(ising_hamiltonian(scenario).c0)
    if isinstance(offset, str):
        raise ValueError(f"unknown phase_offset {offset!r}; expected a number, 'feasible' or 'whole-space'")
    return float(offset)


class SubspaceQAOA:
    """The constrained-mixer QAOA on the product of the robots' reachable path sets.

    Args:
        rule: SBF rule of the mixer, ``exact`` (default) or ``paper`` (see the module docstring).
        initial: ``initial_path`` (default), ``representatives``, ``local_search`` or ``local_search_mix``.
        phase_offset: The phase separator is ``exp(-i gamma (C - phase_offset))``: a number, ``"feasible"``
            (default; ``None`` means the same) for the reference constant of the default
            :func:`qcpp.plan.phase.phase_plan`, or ``"whole-space"`` for the Ising constant ``c0``. Use the
            constant of the representation the compared circuit was compiled with.
        buffer: Amplitudes in the scratch buffer used for axes with short contiguous runs (memory
            ``16 * buffer`` bytes, twice during a gradient; BLAS kernels only).
        kernels: How the partial mixers run: ``numba`` (lane-blocked, vectorised, parallel;
            :mod:`qcpp.simulate.subspace_kernels`),
            ``blas`` (one ``zrot`` call per pair and run) or ``auto`` (default: numba when importable).
        max_levels: Most distinct costs kept as a level table (:meth:`cost_levels`; at most :data:`MAX_LEVELS`);
            more are kept as a float64 diagonal, with the same results.

    Raises:
        ValueError: for an unknown rule or initial state, or ``max_levels`` outside ``1 .. MAX_LEVELS``.
        NonUnitaryMixerError: see :func:`robot_basis`.

    Attributes:
        scenario, rule, initial, phase_offset: As given (``phase_offset`` resolved).
        robot_bases: One :class:`RobotBasis` per robot.

    Example:
        >>> from qcpp.problem.scenario import scenario_from_dict
        >>> s = scenario_from_dict({"grid": {"rows": 2, "cols": 3},
        ...                         "robots": [{"start": [0, 0], "goal": [1, 2]}, {"start": [1, 0], "goal": [0, 2]}]})
        >>> q = SubspaceQAOA(s)
        >>> q.dims, len(q.gradient([0.2, 0.4, 0.1, 0.3]))
        ((4, 4), 4)
    """

    def __init__(
        self,
        scenario: Scenario,
        rule: Rule = "exact",
        initial: InitialState = "initial_path",
        phase_offset: float | Literal["feasible", "whole-space"] | None = None,
        buffer: int = _DEFAULT_BUFFER,
        kernels: Kernels = "auto",
        max_levels: int = MAX_LEVELS,
    ) -> None:
        if not 1 <= max_levels <= MAX_LEVELS:
            raise ValueError(f"max_levels must be 1 .. {MAX_LEVELS}, got {max_levels}")
        if kernels not in ("auto", "numba", "blas"):
            raise ValueError(f"unknown kernels {kernels!r} (expected auto, numba or blas)")
        if kernels == "numba" and not subspace_kernels.AVAILABLE:
            raise ValueError("kernels='numba' needs numba, which is not importable here")
        self.kernels: Kernels = "numba" if kernels == "auto" and subspace_kernels.AVAILABLE else kernels
        if self.kernels == "blas":
            _check_lapack_in_place()
        self.scenario = scenario
        self.rule: Rule = rule
        self.initial: InitialState = initial
        self.robot_bases: tuple[RobotBasis, ...] = tuple(
            robot_basis(scenario, r, rule, initial) for r in range(scenario.num_robots)
        )
        self.phase_offset = _phase_offset(scenario, phase_offset)
        self.buffer = max(1, int(buffer))
        self.max_levels = max_levels
        self._pair_lists = tuple(tuple((i.tolist(), j.tolist()) for _, i, j in b.pairs) for b in self.robot_bases)
        self._pair_arrays = tuple(
            (np.concatenate([i for _, i, _ in b.pairs]).astype(np.intp),
             np.concatenate([j for _, _, j in b.pairs]).astype(np.intp)) if b.pairs else None
            for b in self.robot_bases
        )
        self._levels: np.ndarray | None = None  # compact diagonal: values[levels]
        self._values: np.ndarray | None = None
        self._diag: np.ndarray | None = None  # float64 diagonal when there are too many distinct values
        self._optimum: tuple[float, np.ndarray] | None = None
        self._unique: tuple[np.ndarray, np.ndarray] | None = None  # cost table when there are no levels

    # ------------------------------------------------------------------ basis

    @property
    def bases(self) -> tuple[tuple[int, ...], ...]:
        """Per robot, its basis paths (edge masks) in array order."""
        return tuple(b.paths for b in self.robot_bases)

    @property
    def dims(self) -> tuple[int, ...]:
        """Shape of the state array: the robots' basis sizes."""
        return tuple(b.size for b in self.robot_bases)

    @property
    def dimension(self) -> int:
        """Number of amplitudes (product of :attr:`dims`)."""
        return int(np.prod(self.dims, dtype=np.int64))

    @property
    def num_qubits(self) -> int:
        """Data qubits of the circuit (``scenario.num_variables``)."""
        return self.scenario.num_variables

    @property
    def feasible(self) -> tuple[np.ndarray, ...]:
        """Per robot, whether each basis path is feasible (all True except under a symmetric ``paper`` rule
        that reaches infeasible edge sets)."""
        return tuple(b.feasible for b in self.robot_bases)

    def index_of(self, masks: Sequence[int]) -> tuple[int, ...]:
        """Array index of an assignment (one mask per robot).

        Raises:
            KeyError: if some robot's path is not in its basis (its amplitude is always zero).
        """
        if len(masks) != len(self.robot_bases):
            raise ValueError(f"expected {len(self.robot_bases)} paths, got {len(masks)}")
        return tuple(b.index(m) for b, m in zip(self.robot_bases, masks))

    def assignment(self, index: Sequence[int]) -> tuple[int, ...]:
        """The assignment (one edge mask per robot) at an array index."""
        return tuple(b.paths[int(i)] for b, i in zip(self.robot_bases, index, strict=True))

    def data_index(self, masks: Sequence[int]) -> int:
        """Computational-basis index of an assignment on the data register: ``sum_i x_i 2^i`` with ``x_i``
        variable ``i`` (qubit ``i`` is the least significant bit, as in qiskit's ``Statevector``)."""
        idx = 0
        v = self.scenario.edges_per_robot
        for r, m in enumerate(masks):
            for k, b in enumerate(path_bits(self.scenario, m)):
                if b:
                    idx |= 1 << (r * v + k)
        return idx

    # ------------------------------------------------------------------ cost

    def cost_diagonal(self) -> np.ndarray:
        """The cost ``C`` of every basis assignment, shape :attr:`dims`, float64, read-only.

        Built once by :func:`qcpp.problem.cost.assignment_costs` (one full-size float array) and then kept as
        :meth:`cost_levels` when a table of at most 65,536 values covers it (it typically takes a few hundred
        distinct values); this method then expands the levels again (bit-identical values, a new array per call).
        """
        self._build_cost()
        if self._diag is not None:
            return self._diag
        assert self._values is not None and self._levels is not None
        out = self._values[self._levels]
        out.flags.writeable = False
        return out

    def cost_levels(self) -> tuple[np.ndarray, np.ndarray] | None:
        """``(values, levels)`` with ``cost_diagonal() == values[levels]``: a sorted table of costs (the distinct
        values, or for integer costs every integer from the minimum to the maximum) and a ``uint8``/``uint16``
        array of shape :attr:`dims`; ``None`` when the table would exceed :attr:`max_levels` values."""
        self._build_cost()
        if self._levels is None:
            return None
        assert self._values is not None
        return self._values, self._levels

    def _build_cost(self) -> None:
        if self._levels is not None or self._diag is not None:
            return
        diag = assignment_costs(self.scenario, self.bases)
        dims = self.dims
        compact = _compress(diag.reshape(-1), self.max_levels)
        if compact is None:
            diag.flags.writeable = False
            self._diag = diag
        else:
            self._values, levels = compact
            self._levels = levels.reshape(dims)

    def _cost_chunk(self, sl: slice) -> np.ndarray:
        """The float cost of a flat slice of the state."""
        if self._diag is not None:
            return self._diag.reshape(-1)[sl]
        assert self._values is not None and self._levels is not None
        return self._values[self._levels.reshape(-1)[sl]]

    def optimum(self) -> tuple[float, np.ndarray]:
        """The minimum cost over every feasible assignment of the scenario, and the flat indices of the basis
        assignments that reach it (cached): the assignments :meth:`p_optimum` counts.

        Ties are within ``1e-9 * max(1, |min|)``. Where the basis holds every feasible path
        (:meth:`reaches_every_path`) the minimum is the basis's own. Where it does not (hard obstacles split a
        robot's move graph and the start misses a component), the minimum is the one over every assignment of
        enumerated paths (:func:`~qcpp.problem.paths.enumerate_paths`, whatever the rule here) and the indices are
        the basis assignments of that cost: none where the optimum lies in a component the state never reaches, so
        P(optimum) is 0 there rather than the probability of the best reachable assignment.
        """
        if self._optimum is None:
            best, flat = self._basis_optimum()
            every = self._every_path()
            if every is not None:
                whole = float(assignment_costs(self.scenario, every).min())
                if best > whole + 1e-9 * max(1.0, abs(whole)):
                    best, flat = whole, np.empty(0, dtype=np.intp)
            self._optimum = (best, flat)
        return self._optimum

    def _basis_optimum(self) -> tuple[float, np.ndarray]:
        """The minimum cost over the feasible basis assignments and their flat indices."""
        diag = self.cost_diagonal()
        if all(f.all() for f in self.feasible):
            masked = diag
        else:
            ok = np.ones(self.dims, dtype=bool)
            for r, f in enumerate(self.feasible):
                shape = [1] * len(self.dims)
                shape[r] = len(f)
                ok = ok & f.reshape(shape)
            masked = np.where(ok, diag, np.inf)
        best = float(masked.min())
        tol = 1e-9 * max(1.0, abs(best))
        return best, np.flatnonzero(masked.reshape(-1) <= best + tol)

    def reaches_every_path(self) -> bool:
        """Whether the basis holds every feasible path of every robot. Hard obstacles can split a robot's move
        graph into components SBF moves do not join; on free grids the exact rule reaches every path from the
        initial one wherever ``tests/problem/explorability_test.py`` sweeps them. So the paths are counted (about as
        long as building the basis) only with hard obstacles and a start other than ``representatives`` (one path
        per component); elsewhere this is ``True``."""
        return self._every_path() is None

    def _every_path(self) -> tuple[list[int], ...] | None:
        """Every feasible path of each robot (:func:`~qcpp.problem.paths.enumerate_paths`) where the basis misses
        one of them (counted only where it can: :meth:`reaches_every_path`), else ``None``."""
        if self.scenario.objective.obstacles != "hard" or self.initial == "representatives":
            return None
        every = tuple(enumerate_paths(self.scenario, r) for r in range(self.scenario.num_robots))
        return None if all(int(f.sum()) == len(e) for f, e in zip(self.feasible, every)) else every

    def optimal_assignments(self) -> list[tuple[int, ...]]:
        """All optimal feasible assignments (edge-mask tuples), see :meth:`optimum`."""
        _, flat = self.optimum()
        return [self.assignment(np.unravel_index(k, self.dims)) for k in flat]

    # ------------------------------------------------------------------ states

    def initial_state(self) -> np.ndarray:
        """The initial state: the outer product of the robots' initial amplitudes (complex128)."""
        psi = np.ones((), dtype=np.complex128)
        for b in self.robot_bases:
            psi = np.multiply.outer(psi, b.initial)
        return np.ascontiguousarray(psi, dtype=np.complex128)

    def state(self, angles: Sequence[float] | np.ndarray) -> np.ndarray:
        """The QAOA state ``prod_k U_M(beta_k) exp(-i gamma_k (C - offset)) |psi_0>``, shape :attr:`dims`.

        Args:
            angles: ``[gamma_0, beta_0, gamma_1, beta_1, ...]`` (``p`` layers, ``2p`` values; empty for the
                initial state).
        """
        gammas, betas = split_angles(angles)
        psi = self.initial_state()
        for g, b in zip(gammas, betas):
            self._phase(psi, g)
            for r in range(len(self.robot_bases)):
                self._mixer(psi, r, b)
        return psi

    def expectation(self, angles: Sequence[float] | np.ndarray) -> float:
        """``<psi(angles)| C |psi(angles)>`` (the cost itself, not ``C - offset``)."""
        return self.expectation_from_state(self.state(angles))

    def expectation_from_state(self, psi: np.ndarray) -> float:
        """``<psi| C |psi>`` of a state array of shape :attr:`dims`."""
        self._build_cost()
        flat = psi.reshape(-1)
        if self._levels is not None:
            assert self._values is not None
            lev = self._levels.reshape(-1)
            weight = np.zeros(self._values.size)
            for sl in _chunks(flat.size):
                weight += np.bincount(lev[sl], weights=_abs2(flat[sl]), minlength=self._values.size)
            return float(np.dot(weight, self._values))
        total = 0.0
        for sl in _chunks(flat.size):
            total += float(np.dot(self._cost_chunk(sl), _abs2(flat[sl])))
        return total

    def probabilities(self, angles: Sequence[float] | np.ndarray) -> np.ndarray:
        """``|amplitude|^2`` of every basis assignment, shape :attr:`dims`."""
        psi = self.state(angles)
        return psi.real * psi.real + psi.imag * psi.imag

    def p_optimum(self, angles: Sequence[float] | np.ndarray) -> float:
        """Total probability of the optimal feasible assignments (see :meth:`optimum`)."""
        return self.p_optimum_from_state(self.state(angles))

    def p_optimum_from_state(self, psi: np.ndarray) -> float:
        """:meth:`p_optimum` of a given state array."""
        _, flat = self.optimum()
        a = psi.reshape(-1)[flat]
        return float(np.sum(a.real * a.real + a.imag * a.imag))

    def amplitude(self, angles: Sequence[float] | np.ndarray, masks: Sequence[int]) -> complex:
        """The amplitude of one assignment (one edge mask per robot); exactly 0 outside the reachable basis."""
        try:
            idx = self.index_of(masks)
        except KeyError:
            return 0j
        return complex(self.state(angles)[idx])

    def sample(
        self, angles: Sequence[float] | np.ndarray, shots: int, seed: int | None = None
    ) -> list[tuple[int, ...]]:
        """Measure the state ``shots`` times in the computational basis.

        Args:
            shots: Number of samples (>= 0).
            seed: Seed of ``numpy.random.default_rng``; the same seed gives the same list.

        Returns:
            One assignment (tuple of edge masks, robot order) per shot.
        """
        return self.sample_from_state(self.state(angles), shots, seed)

    def sample_from_state(self, psi: np.ndarray, shots: int, seed: int | None = None) -> list[tuple[int, ...]]:
        """:meth:`sample` from a given state array."""
        if shots < 0:
            raise ValueError(f"shots must be >= 0, got {shots}")
        flat = psi.reshape(-1)
        cdf = np.cumsum(flat.real * flat.real + flat.imag * flat.imag)
        u = np.random.default_rng(seed).random(shots) * cdf[-1]
        picks = np.minimum(np.searchsorted(cdf, u, side="right"), flat.size - 1)
        return [self.assignment(np.unravel_index(int(k), self.dims)) for k in picks]

    def state_dict(
        self,
        angles: Sequence[float] | np.ndarray,
        key: Literal["index", "bits", "masks"] = "index",
        tol: float = 0.0,
    ) -> dict[object, complex]:
        """The state as ``{basis state: amplitude}`` for comparison with a gate-level simulator.

        Args:
            key: ``index`` = data-register basis index ``sum_i x_i 2^i`` (qubit ``i`` least significant, as
                qiskit's ``Statevector`` of the data register; with ancillas above the data qubits and back in
                |0> the index is the same); ``bits`` = a string whose character ``i`` is variable ``i``;
                ``masks`` = the assignment's tuple of edge masks.
            tol: Leave out amplitudes with ``abs(a) <= tol``.
        """
        psi = self.state(angles)
        n = self.num_qubits
        out: dict[object, complex] = {}
        for idx in zip(*np.nonzero(np.abs(psi) > tol)):
            masks = self.assignment(idx)
            amp = complex(psi[idx])
            if key == "masks":
                out[masks] = amp
            elif key == "index":
                out[self.data_index(masks)] = amp
            elif key == "bits":
                out[format(self.data_index(masks), f"0{n}b")[::-1]] = amp
            else:
                raise ValueError(f"unknown key {key!r} (expected index, bits or masks)")
        return out

    def dense_state(self, angles: Sequence[float] | np.ndarray, max_qubits: int = 24) -> np.ndarray:
        """The full ``2^n`` data-register state vector (index as in :meth:`state_dict`), for small ``n``.

        Raises:
            ValueError: if ``n > max_qubits``.
        """
        n = self.num_qubits
        if n > max_qubits:
            raise ValueError(f"{n} data qubits exceed max_qubits={max_qubits}")
        psi = self.state(angles)
        v = self.scenario.edges_per_robot
        weights = 1 << np.arange(v, dtype=np.int64)
        index = np.zeros((), dtype=np.int64)
        for r, b in enumerate(self.robot_bases):
            local = (np.array([path_bits(self.scenario, m) for m in b.paths], dtype=np.int64) @ weights) << (r * v)
            index = np.add.outer(index, local)
        out = np.zeros(1 << n, dtype=np.complex128)
        out[index.reshape(-1)] = psi.reshape(-1)
        return out

    # ------------------------------------------------------------------ gradient

    def gradient(self, angles: Sequence[float] | np.ndarray) -> np.ndarray:
        """Exact ``dE/dangles`` (same layout as ``angles``) by adjoint differentiation."""
        return self.value_and_gradient(angles)[1]

    def value_and_gradient(self, angles: Sequence[float] | np.ndarray) -> tuple[float, np.ndarray]:
        """``(E, dE/dangles)`` with one forward and one backward sweep.

        Every operator is ``exp(-i theta G)`` (``G = diag(C - offset)`` with ``theta = gamma``, or a pair
        generator with ``theta = beta / 2``), so with ``phi_k`` the state after operator ``k`` and
        ``lambda_k = U_{k+1}^+ ... U_M^+ C psi``, ``dE/dtheta_k = 2 Im <lambda_k| G_k |phi_k>``; the backward
        sweep un-applies the operators to both vectors. Memory: two state arrays plus the cost diagonal.
        """
        gammas, betas = split_angles(angles)
        self._build_cost()
        psi = self.state(angles)
        lam = np.empty_like(psi)
        pflat, lflat = psi.reshape(-1), lam.reshape(-1)
        energy = 0.0
        for sl in _chunks(pflat.size):
            np.multiply(pflat[sl], self._cost_chunk(sl), out=lflat[sl])
            energy += float(np.vdot(pflat[sl], lflat[sl]).real)
        return energy, self._backward(psi, lam, gammas, betas)

    def p_optimum_and_gradient(self, angles: Sequence[float] | np.ndarray) -> tuple[float, np.ndarray]:
        """``(P(optimum), dP(optimum)/dangles)`` by one adjoint sweep: the observable is the projector onto
        :meth:`optimum`'s assignments (``lambda = P psi``), so this needs the optimum and is a reference for
        studies of what angles can reach, not a training objective.

        Example:
            >>> from qcpp.problem.scenario import scenario_from_dict
            >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
            >>> q = SubspaceQAOA(s)
            >>> x, h = np.array([0.2, 0.9]), 1e-6
            >>> v, g = q.p_optimum_and_gradient(x)
            >>> numeric = (q.p_optimum(x + [0, h]) - q.p_optimum(x - [0, h])) / (2 * h)
            >>> round(v - q.p_optimum(x), 12), bool(abs(g[1] - numeric) < 1e-6)
            (0.0, True)
        """
        gammas, betas = split_angles(angles)
        self._build_cost()
        psi = self.state(angles)
        _, flat = self.optimum()
        lam = np.zeros_like(psi)
        lam.reshape(-1)[flat] = psi.reshape(-1)[flat]
        value = self.p_optimum_from_state(psi)
        return value, self._backward(psi, lam, gammas, betas)

    def cost_distribution_index(self) -> tuple[np.ndarray, np.ndarray]:
        """``(values, index)``: the sorted distinct costs (or, for integer costs, every integer between the
        extremes) and, per amplitude (shape :attr:`dims`), the position of its cost in ``values``.

        This is :meth:`cost_levels` when it exists; otherwise the table is built once with ``np.unique``.
        """
        compact = self.cost_levels()
        if compact is not None:
            return compact
        if self._unique is None:
            assert self._diag is not None
            values, index = np.unique(self._diag.reshape(-1), return_inverse=True)
            self._unique = (values, index.reshape(self.dims))
        return self._unique

    def level_probabilities(self, psi: np.ndarray) -> np.ndarray:
        """The probability of each cost in :meth:`cost_distribution_index`'s table for the state ``psi``."""
        values, index = self.cost_distribution_index()
        if (self.kernels == "numba" and index.dtype in (np.uint8, np.uint16) and psi.dtype == np.complex128
                and psi.flags.c_contiguous):
            return subspace_kernels.level_weights(psi, index, values.size)
        flat, lev = psi.reshape(-1), index.reshape(-1)
        weight = np.zeros(values.size)
        for sl in _chunks(flat.size):
            weight += np.bincount(lev[sl], weights=_abs2(flat[sl]), minlength=values.size)
        return weight

    def objective_and_gradient(
        self,
        angles: Sequence[float] | np.ndarray,
        objective: Callable[[np.ndarray, np.ndarray], tuple[float, np.ndarray]],
    ) -> tuple[float, np.ndarray]:
        """``(F, dF/dangles)`` for any differentiable function ``F`` of the measured cost's distribution.

        ``objective(values, probabilities)`` gets the cost table of :meth:`cost_distribution_index` and the
        probability of each entry, and returns ``F`` and ``dF/dprobabilities``. Since ``F`` depends on the
        angles only through the probabilities, ``dF/dtheta = d<psi|O|psi>/dtheta`` for the fixed diagonal
        observable ``O = dF/dprobabilities[cost(x)]``, which the adjoint sweep of :meth:`value_and_gradient`
        gives with ``lambda = O psi`` (one forward and one backward sweep, two state arrays).

        Example:
            >>> from qcpp.problem.scenario import scenario_from_dict
            >>> s = scenario_from_dict({"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]})
            >>> q = SubspaceQAOA(s)
            >>> mean = lambda v, w: (float(np.dot(v, w)), v)
            >>> f, g = q.objective_and_gradient([0.2, 0.9], mean)
            >>> bool(np.allclose(g, q.gradient([0.2, 0.9]))), round(f - q.expectation([0.2, 0.9]), 9)
            (True, 0.0)
        """
        gammas, betas = split_angles(angles)
        self._build_cost()
        psi = self.state(angles)
        values, index = self.cost_distribution_index()
        value, weights = objective(values, self.level_probabilities(psi))
        weights = np.asarray(weights, dtype=np.float64)
        if self.kernels == "numba" and index.dtype in (np.uint8, np.uint16):
            lam = psi.copy()
            subspace_kernels.phase(lam, index, weights.astype(np.complex128))  # lam = weights[cost(x)] psi
            return float(value), self._backward(psi, lam, gammas, betas)
        lam = np.empty_like(psi)
        pflat, lflat, lev = psi.reshape(-1), lam.reshape(-1), index.reshape(-1)
        for sl in _chunks(pflat.size):
            np.multiply(pflat[sl], weights[lev[sl]], out=lflat[sl])
        return float(value), self._backward(psi, lam, gammas, betas)

    def _backward(self, psi: np.ndarray, lam: np.ndarray, gammas: np.ndarray, betas: np.ndarray) -> np.ndarray:
        """The adjoint sweep: ``2 Im <lambda_k|G_k|phi_k>`` per angle (destroys ``psi`` and ``lam``)."""
        p = len(gammas)
        grad = np.zeros(2 * p)
        for k in range(p - 1, -1, -1):
            for r in range(len(self.robot_bases) - 1, -1, -1):
                grad[2 * k + 1] += self._mixer_adjoint(psi, lam, r, betas[k])
            grad[2 * k] = self._phase_adjoint(psi, lam, gammas[k])
        return grad

    # ------------------------------------------------------------------ kernels

    def _phase(self, psi: np.ndarray, gamma: float) -> None:
        """``psi *= exp(-i gamma (C - offset))`` in place."""
        self._build_cost()
        flat = psi.reshape(-1)
        if self._levels is not None:
            assert self._values is not None
            table = np.exp(-1j * gamma * (self._values - self.phase_offset))
            if self.kernels == "numba":
                subspace_kernels.phase(psi, self._levels, table)
                return
            lev = self._levels.reshape(-1)
            for sl in _chunks(flat.size):
                flat[sl] *= table[lev[sl]]
        else:
            for sl in _chunks(flat.size):
                flat[sl] *= np.exp(-1j * gamma * (self._cost_chunk(sl) - self.phase_offset))

    def _phase_adjoint(self, psi: np.ndarray, lam: np.ndarray, gamma: float) -> float:
        """``2 Im <lam|(C - offset)|psi>``, then un-apply the phase separator to both arrays."""
        pf, lf = psi.reshape(-1), lam.reshape(-1)
        if self._levels is not None:
            assert self._values is not None
            shifted = self._values - self.phase_offset
            table = np.exp(1j * gamma * shifted)
            if self.kernels == "numba":
                weight = subspace_kernels.phase_weights(psi, lam, self._levels, shifted.size)
                subspace_kernels.phase(psi, self._levels, table)
                subspace_kernels.phase(lam, self._levels, table)
                return 2.0 * float(np.dot(weight, shifted))
            lev = self._levels.reshape(-1)
            weight = np.zeros(shifted.size)
            for sl in _chunks(pf.size):
                w = np.conj(lf[sl])
                w *= pf[sl]
                weight += np.bincount(lev[sl], weights=w.imag, minlength=shifted.size)
                ph = table[lev[sl]]
                pf[sl] *= ph
                lf[sl] *= ph
            return 2.0 * float(np.dot(weight, shifted))
        total = 0.0
        for sl in _chunks(pf.size):
            dd = self._cost_chunk(sl) - self.phase_offset
            total += np.vdot(lf[sl], dd * pf[sl]).imag
            ph = np.exp(1j * gamma * dd)
            pf[sl] *= ph
            lf[sl] *= ph
        return 2.0 * total

    def _layout(self, r: int) -> tuple[int, int, int]:
        dims = self.dims
        return int(np.prod(dims[:r], dtype=np.int64)), dims[r], int(np.prod(dims[r + 1 :], dtype=np.int64))

    def _with_runs(
        self, r: int, arrays: Sequence[np.ndarray], fn: Callable[[list[np.ndarray], int, int], None]
    ) -> None:
        """Call ``fn(flats, base, width)`` over contiguous runs of robot ``r``'s axis of every array in
        ``arrays`` (same shape). Long trailing runs are used in place; short ones go through a transposed
        scratch buffer of about :attr:`buffer` amplitudes per array."""
        pre, n, post = self._layout(r)
        if post >= _DIRECT_MIN or pre == 1:
            flats = [a.reshape(-1) for a in arrays]
            for p in range(pre):
                fn(flats, p * n * post, post)
            return
        rows = max(1, min(pre, self.buffer // (n * post)))
        views = [a.reshape(pre, n, post) for a in arrays]
        bufs = [np.empty(n * rows * post, dtype=np.complex128) for _ in arrays]
        for a0 in range(0, pre, rows):
            a1 = min(pre, a0 + rows)
            w = (a1 - a0) * post
            blocks = []
            for v, b in zip(views, bufs):
                blk = b[: n * w].reshape(n, a1 - a0, post)
                np.copyto(blk, v[a0:a1].transpose(1, 0, 2))
                blocks.append(blk)
            fn([b[: n * w] for b in bufs], 0, w)
            for v, blk in zip(views, blocks):
                v[a0:a1] = blk.transpose(1, 0, 2)

    def _mixer(self, psi: np.ndarray, r: int, beta: float) -> None:
        """Apply robot ``r``'s partial mixers (plaquettes ascending) in place."""
        plist = self._pair_lists[r]
        if not plist:
            return
        c, s = float(np.cos(beta / 2)), complex(-1j * np.sin(beta / 2))
        pairs = self._pair_arrays[r]
        if self.kernels == "numba" and pairs is not None:
            subspace_kernels.mixer(psi.reshape(self._layout(r)), pairs[0], pairs[1], c, s)
            return

        def rotate(flats: list[np.ndarray], base: int, w: int) -> None:
            (x,) = flats
            for ii, jj in plist:
                for i, j in zip(ii, jj):
                    zrot(x, x, c, s, w, base + i * w, 1, base + j * w, 1, 1, 1)  # in place

        self._with_runs(r, [psi], rotate)

    def _mixer_adjoint(self, psi: np.ndarray, lam: np.ndarray, r: int, beta: float) -> float:
        """Backward sweep over robot ``r``'s partial mixers (plaquettes descending): return
        ``sum_q Im <lam|G_q|psi>`` (robot ``r``'s share of ``dE/dbeta``) and un-apply every rotation to both
        arrays."""
        plist = self._pair_lists[r]
        if not plist:
            return 0.0
        c, s = float(np.cos(beta / 2)), complex(1j * np.sin(beta / 2))
        pairs = self._pair_arrays[r]
        if self.kernels == "numba" and pairs is not None:
            shape = self._layout(r)
            return subspace_kernels.mixer_adjoint(psi.reshape(shape), lam.reshape(shape), pairs[0], pairs[1], c, s)
        acc = [0j]

        def rotate_back(flats: list[np.ndarray], base: int, w: int) -> None:
            x, y = flats
            z = 0j
            for ii, jj in reversed(plist):
                for i, j in zip(ii, jj):
                    oi, oj = base + i * w, base + j * w
                    z += zdotc(y, x, w, oi, 1, oj, 1) + zdotc(y, x, w, oj, 1, oi, 1)
                    zrot(x, x, c, s, w, oi, 1, oj, 1, 1, 1)
                    zrot(y, y, c, s, w, oi, 1, oj, 1, 1, 1)
            acc[0] += z

        self._with_runs(r, [psi, lam], rotate_back)
        return acc[0].imag


def _chunks(n: int) -> list[slice]:
    return [slice(a, min(a + _CHUNK, n)) for a in range(0, n, _CHUNK)]


def _abs2(a: np.ndarray) -> np.ndarray:
    """``|a|^2`` of a contiguous complex array, via its float view."""
    f = a.view(np.float64)
    sq = f * f
    out = sq[0::2]
    out += sq[1::2]
    return out


def _compress(flat: np.ndarray, max_levels: int = MAX_LEVELS) -> tuple[np.ndarray, np.ndarray] | None:
    """A sorted value table and a uint8/uint16 level per element (``table[levels] == flat`` exactly), or
    ``None`` when more than ``max_levels`` values are needed.

    Integer-valued costs (the default objective's) take a fast path: the table is every integer from the
    minimum to the maximum and a level is ``cost - minimum``. Otherwise the table is the distinct values."""
    lo, hi = float(flat.min()), float(flat.max())
    if hi - lo < max_levels and lo == np.rint(lo):
        size = int(hi - lo) + 1
        levels = np.empty(flat.size, dtype=np.uint8 if size <= 256 else np.uint16)
        for sl in _chunks(flat.size):
            shifted = flat[sl] - lo
            levels[sl] = shifted
            if not np.array_equal(levels[sl], shifted):  # a non-integer cost: use the general path
                break
        else:
            return lo + np.arange(size, dtype=np.float64), levels
    values = np.empty(0)
    for sl in _chunks(flat.size):
        ch = flat[sl]
        if values.size:
            pos = np.minimum(np.searchsorted(values, ch), values.size - 1)
            ch = ch[values[pos] != ch]
        if ch.size:
            values = np.union1d(values, ch)
            if values.size > max_levels:
                return None
    levels = np.empty(flat.size, dtype=np.uint8 if values.size <= 256 else np.uint16)
    for sl in _chunks(flat.size):
        levels[sl] = np.searchsorted(values, flat[sl])
    return values, levels
