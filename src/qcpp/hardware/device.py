"""Device models: a compile target's coupling graph, native gates, error rates, durations and readout error.

A :class:`Device` is a frozen value. Two kinds exist:

* **families** of any size, named ``grid[:RxC]``, ``heavy-hex[:D]`` (IBM's lattice, distance ``D`` odd) and
  ``all-to-all[:N]``. Without a size, :func:`get_device` picks the smallest member that has ``min_qubits``
  qubits: the smallest square ``k x k`` grid, the smallest odd distance ``D``, ``N = min_qubits``. A family's
  error rates and durations are those of a named device of the same architecture (grid: Google Willow's
  published means; heavy-hex: the medians of the IBM Fez snapshot; all-to-all: Quantinuum Helios's published
  means), so a family member is "that device, grown or shrunk to size";
* **named devices** read from ``qcpp/hardware/data/<name>.json``, each file naming its source and date:
  ``ibm_fez`` and ``ibm_torino`` (IBM Heron calibration snapshots, converted once from qiskit-ibm-runtime's fake
  backends by ``scripts/convert_ibm_backends.py``; couplers the snapshot marks faulty, error 1, are dropped),
  ``google_willow`` (square grid, published spec-sheet means) and ``quantinuum_helios`` (all-to-all trapped
  ions, published means).

Couplings are undirected (every device here has a symmetric two-qubit gate). Per-qubit and per-coupling values
are tuples aligned with ``range(num_qubits)`` and :attr:`Device.coupling`; a duration is ``None`` where the
source publishes none (then :func:`qcpp.routing.native.duration_s` is ``None`` too). Coherence times ``t1_s`` /
``t2_s`` (seconds, per qubit, an entry ``None`` where the snapshot has none) exist for the IBM snapshots and the
heavy-hex family (their medians); devices whose sources publish none (Willow, Helios, the grid and all-to-all
families) have ``None``.

Example:
    >>> d = get_device("grid:2x3")
    >>> d.name, d.num_qubits, d.coupling[:3], d.two_qubit_gate
    ('grid:2x3', 6, ((0, 1), (0, 3), (1, 2)), 'cz')
    >>> get_device("heavy-hex", min_qubits=20).name
    'heavy-hex:5'
    >>> get_device("ibm_fez").num_qubits
    156
    >>> get_device("ibm_fez").t1_s[0] > 0, get_device("google_willow").t1_s
    (True, None)
"""

from __future__ import annotations

import json
import math
import os
import re
import statistics
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

from qcpp.errors import QcppError

__all__ = [
    "FAMILIES", "IBM_DEVICES", "Device", "DeviceError", "device_arg", "device_file", "device_from_json",
    "device_label", "device_names", "distances", "get_device", "heavy_hex_coordinates", "heavy_hex_distance",
    "is_device_path", "is_named", "named_device",
]

FAMILIES = ("grid", "heavy-hex", "all-to-all")
"""Device families of any size (``NAME[:SIZE]``)."""

_DATA_PACKAGE = "qcpp.hardware.data"


class DeviceError(QcppError):
    """A device name or size that does not exist or cannot hold the circuit (one line, for the CLI)."""


@dataclass(frozen=True)
class Device:
    """A device: coupling graph, native gates, error rates, durations, readout.

    Attributes:
        name: ``grid:3x4``, ``heavy-hex:5``, ``all-to-all:20``, or a named device (``ibm_fez``).
        num_qubits: Physical qubits ``0 .. num_qubits-1``.
        coupling: Undirected couplings ``(a, b)``, ``a < b``, sorted.
        native_gates: The device's gate names in the IR (``cz``, ``rz``, ``sx``, ``x``; ``rzz``, ``rx``).
        two_qubit_gate: The native entangling gate (``cz`` or ``rzz``).
        error_1q: Error per gate name, per qubit (``rz`` is virtual on superconducting devices: 0).
        error_2q: Error of the native two-qubit gate per coupling.
        readout_error: Per qubit.
        duration_1q_s: Seconds per gate name, per qubit; ``None``: not published.
        duration_2q_s: Seconds per coupling; ``None``: not published.
        readout_duration_s: Seconds per qubit; ``None``: not published.
        source: Where the figures come from.
        date: Date of the figures (calibration snapshot or publication).
        family: ``grid``, ``heavy-hex``, ``all-to-all`` (the architecture, also for named devices).
        t1_s: Energy-relaxation time T1 per qubit in seconds (an entry ``None``: unknown); ``None``: no data.
        t2_s: Dephasing time T2 (Hahn echo, as the snapshots report it) per qubit in seconds; as ``t1_s``.
    """

    name: str
    num_qubits: int
    coupling: tuple[tuple[int, int], ...]
    native_gates: tuple[str, ...]
    two_qubit_gate: str
    error_1q: tuple[tuple[str, tuple[float, ...]], ...]
    error_2q: tuple[float, ...]
    readout_error: tuple[float, ...]
    duration_1q_s: tuple[tuple[str, tuple[float, ...]], ...] | None
    duration_2q_s: tuple[float, ...] | None
    readout_duration_s: tuple[float, ...] | None
    source: str
    date: str
    family: str
    t1_s: tuple[float | None, ...] | None = None
    t2_s: tuple[float | None, ...] | None = None

    def __post_init__(self) -> None:
        n = self.num_qubits
        if any(not (0 <= a < b < n) for a, b in self.coupling):
            raise ValueError(f"{self.name}: a coupling is not (a, b) with 0 <= a < b < {n}")
        if len(self.error_2q) != len(self.coupling) or len(self.readout_error) != n:
            raise ValueError(f"{self.name}: per-coupling or per-qubit data of the wrong length")
        if any(t is not None and len(t) != n for t in (self.t1_s, self.t2_s)):
            raise ValueError(f"{self.name}: T1 or T2 data of the wrong length")

    @property
    def is_all_to_all(self) -> bool:
        """Every pair of qubits is coupled."""
        return len(self.coupling) == self.num_qubits * (self.num_qubits - 1) // 2

    def edge_index(self) -> dict[tuple[int, int], int]:
        """``(a, b)`` (either order) -> index into :attr:`coupling`."""
        return _edge_index(self)

    def graph(self) -> Any:
        """The coupling graph as a ``scipy.sparse.csr_matrix``: one unit entry per coupler (read it as undirected).

        >>> import qcpp
        >>> qcpp.device("grid:2x2").graph().nnz
        4
        """
        import numpy as np
        from scipy.sparse import csr_matrix

        a, b = np.array(self.coupling, dtype=int).reshape(-1, 2).T
        return csr_matrix((np.ones(len(a)), (a, b)), shape=(self.num_qubits, self.num_qubits))

    def summary(self) -> dict:
        """JSON-ready ``{name, qubits, coupling: [[a, b], ...]}`` (what ``qcpp compile --json`` prints)."""
        return {"name": self.name, "qubits": self.num_qubits, "coupling": [list(e) for e in self.coupling]}


@cache
def _edge_index(device: Device) -> dict[tuple[int, int], int]:
    """Pure memo: ``_edge_index.cache_clear()`` empties it."""
    out: dict[tuple[int, int], int] = {}
    for i, (a, b) in enumerate(device.coupling):
        out[(a, b)] = out[(b, a)] = i
    return out


# --- families ----------------------------------------------------------------------------------------------
def grid_coupling(rows: int, cols: int) -> tuple[tuple[int, int], ...]:
    """Square-lattice couplings, qubit ``r * cols + c``.

    >>> grid_coupling(2, 2)
    ((0, 1), (0, 2), (1, 3), (2, 3))
    """
    edges = []
    for r in range(rows):
        for c in range(cols):
            q = r * cols + c
            if c + 1 < cols:
                edges.append((q, q + 1))
            if r + 1 < rows:
                edges.append((q, q + cols))
    return tuple(sorted(edges))


@cache
def heavy_hex_coupling(distance: int) -> tuple[int, tuple[tuple[int, int], ...]]:
    """IBM's heavy-hex lattice of code distance ``distance`` (odd): ``(5 d^2 - 2 d - 1) / 2`` qubits.

    Built by Qiskit's ``CouplingMap.from_heavy_hex`` (the lattice of IBM's devices).
    Pure memo: ``heavy_hex_coupling.cache_clear()`` empties it."""
    from qiskit.transpiler import CouplingMap

    cm = CouplingMap.from_heavy_hex(distance, bidirectional=False)
    return cm.size(), tuple(sorted({(min(a, b), max(a, b)) for a, b in cm.get_edges()}))


def heavy_hex_qubits(distance: int) -> int:
    """Qubits of the distance-``distance`` heavy-hex lattice.

    >>> [heavy_hex_qubits(d) for d in (3, 5, 7)]
    [19, 57, 115]
    """
    return (5 * distance * distance - 2 * distance - 1) // 2


@cache
def heavy_hex_coordinates(distance: int) -> tuple[tuple[int, int], ...]:
    """``(y, x)`` of every qubit of :func:`heavy_hex_coupling`'s lattice (index order of Qiskit's
    ``CouplingMap.from_heavy_hex``, i.e. rustworkx's ``heavy_hex_graph``).

    The lattice has ``distance`` horizontal *row lines* ``y = 0, 2, .., 2 (distance - 1)`` of ``2 distance - 1``
    qubits each (``x = 0 .. 2 distance - 2``, neighbours along the line), and *bridge* qubits at odd ``y`` joining
    the qubits ``(y - 1, x)`` and ``(y + 1, x)``: below row line ``2 g`` with ``g`` even at ``x = 0, 3, 7, 11, ..``,
    with ``g`` odd at ``x = 1, 5, 9, .., 2 distance - 2``. So the interior cells are hexagons of 12 qubits spanning
    ``x .. x + 4`` between two row lines, their bridges four columns apart and shifted by two from gap to gap.

    >>> heavy_hex_coordinates(3)[:5], heavy_hex_coordinates(3)[9:13]
    (((0, 0), (0, 2), (0, 4), (2, 0), (2, 2)), ((1, 0), (1, 3), (3, 1), (3, 4)))

    Pure memo: ``heavy_hex_coordinates.cache_clear()`` empties it."""
    d = distance
    coords: list[tuple[int, int]] = [(2 * i, 2 * j) for i in range(d) for j in range(d)]  # data qubits
    for g in range(d - 1):  # syndrome (bridge) qubits, (d + 1) / 2 per gap
        if g % 2 == 0:
            coords += [(2 * g + 1, 0)] + [(2 * g + 1, 4 * j - 1) for j in range(1, (d + 1) // 2)]
        else:
            coords += [(2 * g + 1, 4 * j + 1) for j in range((d - 1) // 2)] + [(2 * g + 1, 2 * d - 2)]
    coords += [(2 * i, 2 * j + 1) for i in range(d) for j in range(d - 1)]  # flag qubits
    return tuple(coords)


def heavy_hex_distance(device: Device) -> int | None:
    """``d`` if the device's coupling is :func:`heavy_hex_coupling` ``(d)`` (the unsized family's lattice, qubit
    indices as there), else ``None`` (named Heron devices have another layout).

    >>> [heavy_hex_distance(get_device(s)) for s in ("heavy-hex:5", "ibm_fez", "grid:3x3")]
    [5, None, None]
    """
    if device.is_all_to_all or device.family != "heavy-hex":
        return None
    d = 3
    while heavy_hex_qubits(d) < device.num_qubits:
        d += 2
    if heavy_hex_qubits(d) != device.num_qubits or device.coupling != heavy_hex_coupling(d)[1]:
        return None
    return d


def distances(device: Device) -> Any:
    """All-pairs shortest-path lengths of the coupling graph, a ``numpy`` array (``inf`` between components).

    >>> distances(get_device("grid:2x2"))[0].tolist()
    [0.0, 1.0, 1.0, 2.0]
    """
    from scipy.sparse.csgraph import shortest_path

    return shortest_path(device.graph(), directed=False, unweighted=True)


def _uniform(template: Device, name: str, n: int, coupling: tuple[tuple[int, int], ...], family: str) -> Device:
    """A family member with the template's (median) figures on every qubit and coupling."""

    def med(values: Sequence[float]) -> float:
        return statistics.median(values) if values else 0.0

    e1 = tuple((g, (med(v),) * n) for g, v in template.error_1q)
    d1 = None if template.duration_1q_s is None else tuple((g, (med(v),) * n) for g, v in template.duration_1q_s)
    d2 = None if template.duration_2q_s is None else (med(template.duration_2q_s),) * len(coupling)
    ro = None if template.readout_duration_s is None else (med(template.readout_duration_s),) * n

    def med_times(values: tuple[float | None, ...] | None) -> tuple[float | None, ...] | None:
        known = [v for v in values or () if v is not None]
        return (statistics.median(known),) * n if known else None

    return Device(
        name=name,
        num_qubits=n,
        coupling=coupling,
        native_gates=template.native_gates,
        two_qubit_gate=template.two_qubit_gate,
        error_1q=e1,
        error_2q=(med(template.error_2q),) * len(coupling),
        readout_error=(med(template.readout_error),) * n,
        duration_1q_s=d1,
        duration_2q_s=d2,
        readout_duration_s=ro,
        source=f"{family} lattice; figures: medians of {template.name} ({template.source})",
        date=template.date,
        family=family,
        t1_s=med_times(template.t1_s),
        t2_s=med_times(template.t2_s),
    )


_FAMILY_TEMPLATE = {"grid": "google_willow", "heavy-hex": "ibm_fez", "all-to-all": "quantinuum_helios"}
_SIZE_RE = {
    "grid": re.compile(r"^(\d+)x(\d+)$"),
    "heavy-hex": re.compile(r"^(\d+)$"),
    "all-to-all": re.compile(r"^(\d+)$"),
}


def _family_device(family: str, size: str | None, min_qubits: int) -> Device:
    template = named_device(_FAMILY_TEMPLATE[family])
    if size is not None:
        m = _SIZE_RE[family].match(size)
        if m is None:
            form = {"grid": "RxC", "heavy-hex": "D (odd)", "all-to-all": "N"}[family]
            raise DeviceError(f"device {family}:{size}: expected {family}:{form}")
    if family == "grid":
        if size is None:
            k = max(1, math.isqrt(max(min_qubits, 1) - 1) + 1) if min_qubits > 1 else 1
            rows = cols = k
        else:
            rows, cols = int(m.group(1)), int(m.group(2))  # type: ignore[union-attr]
        if rows < 1 or cols < 1:
            raise DeviceError(f"device grid:{size}: rows and columns must be at least 1")
        return _uniform(template, f"grid:{rows}x{cols}", rows * cols, grid_coupling(rows, cols), family)
    if family == "heavy-hex":
        if size is None:
            d = 3
            while heavy_hex_qubits(d) < min_qubits:
                d += 2
        else:
            d = int(m.group(1))  # type: ignore[union-attr]
        if d < 3 or d % 2 == 0:
            raise DeviceError(f"device heavy-hex:{d}: the distance must be odd and at least 3")
        n, coupling = heavy_hex_coupling(d)
        return _uniform(template, f"heavy-hex:{d}", n, coupling, family)
    n = max(min_qubits, 2) if size is None else int(m.group(1))  # type: ignore[union-attr]
    if n < 2:
        raise DeviceError(f"device all-to-all:{n}: needs at least 2 qubits")
    coupling = tuple((a, b) for a in range(n) for b in range(a + 1, n))
    return _uniform(template, f"all-to-all:{n}", n, coupling, family)


# --- named devices and device files -----------------------------------------------------------------------
def device_names() -> tuple[str, ...]:
    """Names of the devices shipped as data files.

    >>> {"google_willow", "ibm_fez", "ibm_torino", "quantinuum_helios"} <= set(device_names())
    True
    """
    files = resources.files(_DATA_PACKAGE).iterdir()
    return tuple(sorted(f.name[: -len(".json")] for f in files if f.name.endswith(".json")))


IBM_DEVICES = ("ibm_fez", "ibm_torino")
"""The shipped IBM Heron snapshots (heavy-hex with defects): the hosts of ``--optimize-for twoq``'s searches on
the other IBM device, a fixed list so that a device file added elsewhere changes no other device's results."""

DEVICE_FILE_MAX_BYTES = 64 << 20
"""The largest device file read (a 10,000-qubit device with every per-qubit field is a few megabytes)."""

_REQUIRED = ("family", "source", "date", "num_qubits", "native_gates", "two_qubit_gate", "coupling", "gate_error",
             "readout_error")  # fmt: skip
_OPTIONAL = ("name", "gate_duration_s", "readout_duration_s", "t1_s", "t2_s")


def _is_number(v: object) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _fail(where: str, field: str, reason: str) -> DeviceError:
    return DeviceError(f"{where}: {field}: {reason}")


def _per(value: object, n: int, where: str, field: str, unit: str, *, unit_range: bool = False,
         optional: bool = False) -> tuple[float, ...] | None:  # fmt: skip
    """One number for all, or a list of ``n`` numbers (``unit``: ``qubit`` or ``coupler``); errors in [0, 1],
    durations at least 0."""
    if value is None and optional:
        return None
    if _is_number(value):
        values: list = [value] * n
    elif isinstance(value, list):
        if len(value) != n:
            raise _fail(where, field, f"expected {n} values (one per {unit}), got {len(value)}")
        values = value
    else:
        raise _fail(where, field, f"expected a number or a list of {n} numbers (one per {unit}), got "
                    f"{type(value).__name__}")  # fmt: skip
    for i, v in enumerate(values):
        top = 1.0 if unit_range else math.inf
        if not _is_number(v) or not 0 <= v <= top:
            span = "between 0 and 1" if unit_range else "a number at least 0"
            raise _fail(where, f"{field}[{i}]" if isinstance(value, list) else field, f"expected {span}, got {v!r}")
    return tuple(float(v) for v in values)


def _times(value: object, n: int, where: str, field: str) -> tuple[float | None, ...] | None:
    if value is None:
        return None
    if not isinstance(value, list) or len(value) != n:
        got = f"{len(value)} values" if isinstance(value, list) else type(value).__name__
        raise _fail(where, field, f"expected a list of {n} values (one per qubit, null where unknown), got {got}")
    for i, v in enumerate(value):
        if v is not None and (not _is_number(v) or v <= 0):
            raise _fail(where, f"{field}[{i}]", f"expected seconds (a number over 0) or null, got {v!r}")
    return tuple(None if v is None else float(v) for v in value)


def _coupling(raw: object, n: int, where: str) -> tuple[tuple[int, int], ...]:
    """The couplers in file order, each ``(min, max)``."""
    if raw == "all":
        return tuple((a, b) for a in range(n) for b in range(a + 1, n))
    if not isinstance(raw, list):
        raise _fail(where, "coupling", f"expected \"all\" or a list of [a, b] qubit pairs, got {type(raw).__name__}")
    out: list[tuple[int, int]] = []
    seen: set[tuple[int, int]] = set()
    for i, pair in enumerate(raw):
        ok = isinstance(pair, list) and len(pair) == 2 and all(type(q) is int and 0 <= q < n for q in pair)
        if not ok or pair[0] == pair[1]:
            raise _fail(where, f"coupling[{i}]", f"expected [a, b], two different qubits 0..{n - 1}, got {pair!r}")
        edge = (min(pair), max(pair))
        if edge in seen:
            raise _fail(where, f"coupling[{i}]", f"the coupler {list(edge)} is listed twice")
        seen.add(edge)
        out.append(edge)
    return tuple(out)


def device_from_json(raw: object, name: str, where: str) -> Device:
    """The :class:`Device` of a device file's JSON value ``raw`` (format: ``docs/guide/hardware.md``), validated.

    Couplers may be listed in any order and either way round: each is sorted together with its own CZ error and
    duration (:attr:`Device.coupling` is sorted; the per-coupler values follow their coupler).

    Args:
        raw: The parsed JSON.
        name: The device's name.
        where: What names the file in a message (its path).

    Raises:
        DeviceError: a missing, unknown or malformed field, one line ``<where>: <field>: <reason>``.

    Example:
        >>> d = device_from_json({"family": "grid", "source": "example", "date": "2026-01-01", "num_qubits": 3,
        ...     "native_gates": ["cz", "rz", "sx", "x"], "two_qubit_gate": "cz", "coupling": [[1, 2], [0, 1]],
        ...     "gate_error": {"cz": [0.5, 0.01], "rz": 0, "sx": 1e-4, "x": 1e-4}, "readout_error": 0.01},
        ...     "mine", "mine.json")
        >>> d.coupling, d.error_2q
        (((0, 1), (1, 2)), (0.01, 0.5))
    """
    if not isinstance(raw, dict):
        raise DeviceError(f"{where}: expected a JSON object of device fields, got {type(raw).__name__}")
    missing = [k for k in _REQUIRED if k not in raw]
    if missing:
        raise DeviceError(f"{where}: missing field{'s' if len(missing) > 1 else ''} {', '.join(missing)}")
    unknown = sorted(set(raw) - set(_REQUIRED) - set(_OPTIONAL))
    if unknown:
        raise DeviceError(f"{where}: unknown field {unknown[0]!r} (fields: {', '.join(_REQUIRED + _OPTIONAL)})")
    for key in ("source", "date"):
        if not isinstance(raw[key], str) or not raw[key].strip():
            raise _fail(where, key, f"expected a non-empty string, got {raw[key]!r}")
    if raw["family"] not in FAMILIES:
        raise _fail(where, "family", f"expected one of {', '.join(FAMILIES)}, got {raw['family']!r}")
    n = raw["num_qubits"]
    if type(n) is not int or n < 1:
        raise _fail(where, "num_qubits", f"expected a whole number at least 1, got {n!r}")
    gates = raw["native_gates"]
    if not isinstance(gates, list) or not gates or not all(isinstance(g, str) and g for g in gates):
        raise _fail(where, "native_gates", f"expected a list of gate names, got {gates!r}")
    twoq = raw["two_qubit_gate"]
    if twoq not in ("cz", "rzz") or twoq not in gates:
        raise _fail(where, "two_qubit_gate", f"expected cz or rzz, one of native_gates, got {twoq!r}")
    edges = _coupling(raw["coupling"], n, where)
    m = len(edges)
    errors = raw["gate_error"]
    if not isinstance(errors, dict):
        raise _fail(where, "gate_error", f"expected an object {{gate: error}}, got {type(errors).__name__}")
    for g in gates:
        if g not in errors:
            raise _fail(where, f"gate_error.{g}", "missing (every native gate needs an error; rz: 0 if virtual)")
    durations = raw.get("gate_duration_s") or {}
    if not isinstance(durations, dict):
        raise _fail(where, "gate_duration_s", f"expected null or an object {{gate: seconds}}, got "
                    f"{type(durations).__name__}")  # fmt: skip
    one = tuple(g for g in gates if g != twoq)
    e1 = tuple((g, _per(errors[g], n, where, f"gate_error.{g}", "qubit", unit_range=True)) for g in one)
    e2 = _per(errors[twoq], m, where, f"gate_error.{twoq}", "coupler", unit_range=True)
    d1 = tuple((g, _per(durations.get(g), n, where, f"gate_duration_s.{g}", "qubit", optional=True)) for g in one)
    d2 = _per(durations.get(twoq), m, where, f"gate_duration_s.{twoq}", "coupler", optional=True)
    readout = _per(raw["readout_error"], n, where, "readout_error", "qubit", unit_range=True)
    readout_s = _per(raw.get("readout_duration_s"), n, where, "readout_duration_s", "qubit", optional=True)
    order = sorted(range(m), key=edges.__getitem__)  # each coupler keeps its own error and duration
    assert e2 is not None and readout is not None
    return Device(
        name=name,
        num_qubits=n,
        coupling=tuple(edges[i] for i in order),
        native_gates=tuple(gates),
        two_qubit_gate=twoq,
        error_1q=e1,  # type: ignore[arg-type]
        error_2q=tuple(e2[i] for i in order),
        readout_error=readout,
        duration_1q_s=d1 if all(v is not None for _, v in d1) else None,  # type: ignore[arg-type]
        duration_2q_s=None if d2 is None else tuple(d2[i] for i in order),
        readout_duration_s=readout_s,
        source=raw["source"],
        date=raw["date"],
        family=raw["family"],
        t1_s=_times(raw.get("t1_s"), n, where, "t1_s"),
        t2_s=_times(raw.get("t2_s"), n, where, "t2_s"),
    )


@cache
def named_device(name: str) -> Device:
    """The device of ``data/<name>.json``.

    Raises:
        DeviceError: no such file.

    Pure memo: ``named_device.cache_clear()`` empties it."""
    if name not in device_names():
        raise DeviceError(f"unknown device {name!r} (known: {', '.join(device_names())}; families: {_family_list()}; "
                          "or a device file's path)")  # fmt: skip
    raw = json.loads(resources.files(_DATA_PACKAGE).joinpath(f"{name}.json").read_text())
    return device_from_json(raw, name, f"{name}.json")


def is_device_path(spec: str) -> bool:
    """Whether ``--device SPEC`` names a device file: it ends in ``.json`` or contains a path separator.

    >>> is_device_path("./mine.json"), is_device_path("cal/heron"), is_device_path("ibm_fez")
    (True, True, False)
    """
    return spec.endswith(".json") or "/" in spec or (os.altsep or "/") in spec or os.sep in spec


def device_file(path: str | os.PathLike[str]) -> Device:
    """The device described by the JSON file ``path`` (format: ``docs/guide/hardware.md``), validated.

    Its name is the file's ``name`` field, or else the file name without ``.json``; it must not be a family's
    (``grid:3x3``) or a shipped device's name, so that a name in a report means one device.

    Raises:
        DeviceError: the file cannot be read, is not JSON, or a field is missing, unknown or malformed (one line
            naming the file and the field).
    """
    from qcpp.io.inputs import read_bounded

    where = os.fspath(path)
    try:
        data = read_bounded(where, DEVICE_FILE_MAX_BYTES)
    except OSError as exc:
        raise DeviceError(f"{where}: cannot read the device file ({exc.strerror or exc})") from None
    if len(data) > DEVICE_FILE_MAX_BYTES:
        raise DeviceError(f"{where}: over {DEVICE_FILE_MAX_BYTES >> 20} MB, too large for a device file")
    try:
        raw = json.loads(data)
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        at = f" (line {exc.lineno}, column {exc.colno})" if isinstance(exc, json.JSONDecodeError) else ""
        raise DeviceError(f"{where}: not a JSON device file{at}") from None
    stem = os.path.basename(where).removesuffix(".json")
    name = raw.get("name", stem) if isinstance(raw, dict) else stem
    device = device_from_json(raw, str(name), where)  # the fields first: a copied file's name is the last step
    if not isinstance(name, str) or not name or any(c.isspace() for c in name):
        raise _fail(where, "name", f"expected a name without spaces, got {name!r}")
    if name.partition(":")[0] in FAMILIES or name in device_names():
        taken = "a family's" if name.partition(":")[0] in FAMILIES else "a shipped device's"
        raise _fail(where, "name", f"{name!r} is {taken} name; give the device a name of its own")
    return device


def is_named(device: Device) -> bool:
    """A named device (shipped, or from a device file: its own figures), not a family member.

    >>> is_named(get_device("ibm_fez")), is_named(get_device("grid:3x3"))
    (True, False)
    """
    return device.name.partition(":")[0] not in FAMILIES


def _family_list() -> str:
    return "grid[:RxC], heavy-hex[:D], all-to-all[:N]"


def get_device(spec: str | Device, min_qubits: int = 1) -> Device:
    """A device: a family member ``grid[:RxC]``, ``heavy-hex[:D]``, ``all-to-all[:N]``, a named device, a device
    file's path (:func:`is_device_path`, read by :func:`device_file`) or a :class:`Device` (returned as it is).

    Args:
        spec: The name, path or device.
        min_qubits: For a family without a size: the smallest member with at least this many qubits.

    Returns:
        The :class:`Device`.

    Raises:
        DeviceError: an unknown name or a malformed size (one line naming both); a device file that cannot be read
            or is malformed (naming the file and the field).

    >>> get_device("grid", min_qubits=10).name
    'grid:4x4'
    >>> get_device("all-to-all", min_qubits=7).num_qubits
    7
    """
    if isinstance(spec, Device):
        return spec
    if not isinstance(spec, str):
        raise DeviceError(f"expected a device name, a device file's path or a Device, got {type(spec).__name__}")
    if is_device_path(spec):
        return device_file(spec)
    family, sep, size = spec.strip().partition(":")
    if family in FAMILIES:
        return _family_device(family, size if sep else None, min_qubits)
    if sep:
        raise DeviceError(f"unknown device {spec!r} (families: {_family_list()}; named: {', '.join(device_names())}; "
                          "or a device file's path)")  # fmt: skip
    return named_device(family)


def device_arg(spec: str | Device) -> str | Device:
    """A ``device`` argument checked before any work: a device file's path becomes its :class:`Device` (read once,
    validated); a name stays a name (checked: a family without a size is sized by the circuit later); a
    :class:`Device` stays itself.

    Raises:
        DeviceError: as :func:`get_device`; any other type (named by its type, never its value).

    >>> device_arg("grid"), device_arg(get_device("grid:2x2")).name
    ('grid', 'grid:2x2')
    """
    dev = get_device(spec)
    return spec if isinstance(spec, str) and not is_device_path(spec) else dev


def device_label(spec: str | Device) -> str:
    """How messages and progress lines name a device argument: the name, never a device's whole value.

    >>> device_label("heavy-hex"), device_label(get_device("grid:2x2"))
    ('heavy-hex', 'grid:2x2')
    """
    return spec.name if isinstance(spec, Device) else spec
