"""A geometry-preserving placement on heavy-hex devices: one heavy-hex cell per plaquette.

The heavy-hex lattice (:func:`qcpp.hardware.device.heavy_hex_coordinates`) is a honeycomb with a qubit on every
vertex (degree 3) and on every side's midpoint (degree 2): row lines of qubits, joined by *bridge* qubits every
four columns, shifted by two columns from one gap between row lines to the next. Its cells are 12-qubit
hexagons; two cells side by side share a bridge, a cell shares a row-line side with each of the two cells above
and below it.

**Placement** (:func:`hex_placement`). Plaquette ``(i, j)`` of robot ``r``'s copy of the problem grid takes the
cell of gap ``Y + i`` whose bridges are at columns ``X + L + 4 j`` and ``X + L + 4 j + 4`` (``L = 3`` in even gaps
and ``1`` in odd ones, where the device's bridges are; ``(Y, X)`` the robot's offset, ``X`` a multiple of 4). So
grid node row ``i`` is row line ``Y + i``, and every edge qubit sits on a row line:

* the horizontal edge ``(i, j)-(i, j+1)`` on a vertex of the row-line side shared by the cells of plaquettes
  ``(i-1, j)`` and ``(i, j)``: qubit ``(2 (Y + i), X + 4 j + H)`` with ``H = 3`` on even row lines (the side's
  left end) and ``5`` on odd ones (its right end);
* the vertical edge ``(i, j)-(i+1, j)`` on the lower end of the bridge shared by the cells of plaquettes
  ``(i, j-1)`` and ``(i, j)``: qubit ``(2 (Y + i + 1), X + L + 4 j)``.

A plaquette's four edges are then four of its cell's twelve qubits, all on its degree-3 vertices: in an even gap
the top-left vertex and, on the bottom row line, the bottom-left, bottom-middle and bottom-right vertices (two
steps apart along the row line, the top edge two steps from the left one over the left bridge); an odd gap is
its mirror image. Both bridges and all six degree-2 qubits of a cell hold no data: they are free for its partial
mixer's ancillas.

Each robot's patch spans ``R`` row lines and ``4 C`` columns; the ``k`` patches are stacked ``down x across``
(offsets ``Y = R * row``, ``X = 4 C * column``), choosing the stacking that needs the smallest lattice. The rest
of the pipeline is the square grid's (:func:`qcpp.pipeline.device_compile.medial_compile`): local ancillas with search
(:func:`qcpp.layout.medial.allocate_ancillas`), relays (:mod:`qcpp.routing.bridge`) and windows routed home
(:func:`qcpp.routing.windows.route_windows`).

The geometry costs more than on a square grid: a cell is a 12-qubit cycle with no qubit at its centre, so a
plaquette's four edges are 2 to 6 steps apart (2, 2 and 2 around the cell from the top edge, 4, 4 and 6 across
it; all 2 on the square grid's medial layout, around the plaquette's centre site), and the partial mixer's parity
network joins pairs of them: :mod:`qcpp.pipeline.cellmixer` picks, per partial mixer, the equally short parity network
that routes cheapest on its cell.

Example:
    >>> from qcpp.problem.presets import default_scenario
    >>> from qcpp.hardware.device import get_device, heavy_hex_coordinates
    >>> s = default_scenario(3, 3, 1)
    >>> hex_distance(s)
    7
    >>> homes = hex_placement(s, get_device("heavy-hex:7"))
    >>> xy = heavy_hex_coordinates(7)
    >>> [xy[homes[v]] for v in range(3)]  # edges (0,0)-(0,1), (0,0)-(1,0), (0,1)-(0,2)
    [(0, 3), (2, 3), (0, 7)]
    >>> hex_placement(s, get_device("heavy-hex:5")) is None  # too small: the caller falls back
    True
"""

from __future__ import annotations

from functools import cache

from qcpp.hardware.device import Device, heavy_hex_coordinates, heavy_hex_distance
from qcpp.problem.scenario import Scenario

__all__ = [
    "CELL_PHASE_LAYOUT", "hex_distance",
    "hex_placement", "hex_sites", "is_hex_lattice",
]  # fmt: skip

CELL_PHASE_LAYOUT = "medial"
"""The phase separator's layout that ``phase_layout="auto"`` settles on for a heavy-hex lattice (the cell layout):
the balance sums drift to sinks where the robots' patches meet (:func:`qcpp.plan.phase_layout.balance_sinks`),
as on square grids; same gates and counts as ``spatial``."""


def is_hex_lattice(spec: str | Device) -> bool:
    """Whether ``spec`` is a heavy-hex lattice the cell layout may use: the unsized ``heavy-hex``, ``heavy-hex:D``,
    or such a :class:`Device` (not a named IBM device, whose qubit numbering is another).

    >>> [is_hex_lattice(s) for s in ("heavy-hex", "heavy-hex:5", "ibm_fez", "grid")]
    [True, True, False, False]
    """
    if isinstance(spec, Device):
        return heavy_hex_distance(spec) is not None
    return spec == "heavy-hex" or spec.startswith("heavy-hex:")


def _gap_offset(gap: int) -> int:
    """Column of the first interior bridge of ``gap`` (bridges every four columns from there)."""
    return 3 if gap % 2 == 0 else 1


def _row_offset(line: int) -> int:
    """Column of the horizontal edge ``(i, 0)-(i, 1)`` on row line ``line``: the left end of the side the cells
    above and below share in even lines, its right end in odd ones (never a bridge's end that holds a vertical
    edge)."""
    return 3 if line % 2 == 0 else 5


def hex_sites(rows: int, cols: int, edge_sites: tuple[tuple[int, int], ...], y0: int, x0: int) -> list[tuple[int, int]]:
    """Device ``(y, x)`` of every grid edge (in :attr:`qcpp.problem.grid.Grid.edge_sites` order) of a patch at row line
    ``y0``, column ``x0`` (a multiple of 4): see the module docs.

    >>> hex_sites(2, 2, ((0, 1), (1, 0), (1, 2), (2, 1)), 0, 0)
    [(0, 3), (2, 3), (2, 7), (2, 5)]
    """
    out = []
    for a, b in edge_sites:
        i, j = a // 2, b // 2
        if a % 2 == 0:  # (i, j)-(i, j+1): a vertex of the row-line side two cells share
            out.append((2 * (y0 + i), x0 + 4 * j + _row_offset(y0 + i)))
        else:  # (i, j)-(i+1, j): the lower end of the bridge of gap y0 + i
            out.append((2 * (y0 + i) + 2, x0 + _gap_offset(y0 + i) + 4 * j))
    return out


def _needed(scenario: Scenario, down: int, across: int) -> int:
    """The smallest odd distance with ``down x across`` patches' row lines and columns (bridges may still miss)."""
    g = scenario.grid
    d = max(3, down * g.rows, -(-(across * 4 * g.cols + 1) // 2))
    return d + 1 - d % 2


def _arrangements(scenario: Scenario) -> list[tuple[int, int]]:
    """The ``down x across`` stackings of the robots' patches, smallest lattice first (then fewest across)."""
    k = scenario.num_robots
    shapes = [(-(-k // across), across) for across in range(1, k + 1)]
    return sorted(shapes, key=lambda a: (_needed(scenario, *a), a[1]))


def _fits(scenario: Scenario, d: int, down: int, across: int) -> bool:
    return _needed(scenario, down, across) <= d


def hex_distance(scenario: Scenario) -> int:
    """The smallest odd distance whose heavy-hex lattice holds the layout of ``scenario``."""
    d = min(_needed(scenario, *a) for a in _arrangements(scenario))
    while not any(_fits(scenario, d, *a) and _placed(scenario, d, a) is not None for a in _arrangements(scenario)):
        d += 2
    return d


@cache
def _index(d: int) -> dict[tuple[int, int], int]:
    """Qubit index of each coordinate of the distance-``d`` lattice (pure memo of a value callers only read;
    ``_index.cache_clear()`` empties it)."""
    return {xy: q for q, xy in enumerate(heavy_hex_coordinates(d))}


def _placed(scenario: Scenario, d: int, arrangement: tuple[int, int]) -> tuple[int, ...] | None:
    g = scenario.grid
    across = arrangement[1]
    index = _index(d)
    homes = []
    sites = {r: hex_sites(g.rows, g.cols, g.edge_sites, g.rows * (r // across), 4 * g.cols * (r % across))
             for r in range(scenario.num_robots)}  # fmt: skip
    for v in range(scenario.num_variables):
        robot, e = scenario.variable_of(v)
        q = index.get(sites[robot][e])
        if q is None:
            return None
        homes.append(q)
    return tuple(homes)


def hex_placement(scenario: Scenario, device: Device) -> tuple[int, ...] | None:
    """Home of every data qubit (variable index -> physical qubit) on a heavy-hex lattice device, or ``None`` if
    the device is not one (:func:`qcpp.hardware.device.heavy_hex_distance`) or the layout does not fit. Of the
    ``down x across`` stackings of the robots' patches that fit, the one that needs the smallest lattice (the
    lattice is about twice as tall as wide in cells, so robots are stacked down first).

    Args:
        scenario: The scenario.
        device: The device.
    """
    d = heavy_hex_distance(device)
    if d is None:
        return None
    for arrangement in _arrangements(scenario):
        if _fits(scenario, d, *arrangement):
            homes = _placed(scenario, d, arrangement)
            if homes is not None:
                return homes
    return None
