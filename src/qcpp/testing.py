"""Hypothesis strategies for random angles, gates and circuits of the IR (needs the ``test`` extra).

An optional module for property tests of the IR and of code built on it: no production module imports it. The
plain scenario lists the estimate == compiled checks run on are in :mod:`qcpp.estimators.crosscheck`.

>>> from hypothesis import given, settings
>>> @settings(max_examples=5)
... @given(circuits(max_qubits=3))
... def check(c):
...     assert c.inverse().inverse() == c
>>> check()
"""

from __future__ import annotations

import math
from collections.abc import Collection, Sequence

from hypothesis import strategies as st

from qcpp.ir.angles import Angle, Param
from qcpp.ir.circuit import Circuit, Register, Section
from qcpp.ir.gates import (
    GATE_SPECS,
    Gate,
    ccx,
    crx,
    cry,
    crz,
    csbf,
    cx,
    cz,
    h,
    mcx,
    rx,
    ry,
    rz,
    rzz,
    s,
    sbf,
    sdg,
    t,
    tdg,
    x,
)

__all__ = [
    "ALL_GATE_NAMES",
    "CLEAN_TARGET_NAMES",
    "SYMBOLS",
    "angles",
    "circuits",
    "gates",
]

CLEAN_TARGET_NAMES = frozenset({"and", "and_dg"})
"""Gates whose lowering is exact only on a clean target (drawn only by tests that respect that contract)."""

ALL_GATE_NAMES: tuple[str, ...] = tuple(n for n in GATE_SPECS if n not in CLEAN_TARGET_NAMES)
"""Every gate name of the IR."""

SYMBOLS: tuple[str, ...] = ("gamma_0", "beta_0", "gamma_1")
"""Symbols used by :func:`angles` when ``symbolic=True``."""

_FIXED = {"x": x, "h": h, "t": t, "tdg": tdg, "s": s, "sdg": sdg}
_ONE = {"rz": rz, "rx": rx, "ry": ry}
_TWO = {"cx": cx, "cz": cz}
_TWO_P = {"crz": crz, "cry": cry, "crx": crx, "rzz": rzz}


def angles(symbolic: bool = False) -> st.SearchStrategy[Param]:
    """Floats in [-2π, 2π], or (if ``symbolic``) also affine angles over :data:`SYMBOLS`."""
    number = st.floats(-2 * math.pi, 2 * math.pi, allow_nan=False, allow_infinity=False)
    if not symbolic:
        return number
    coeff = st.floats(-2, 2, allow_nan=False).filter(lambda c: c != 0.0)
    symbolic_angle = st.builds(
        lambda name, c, const: Angle.symbol(name, c) + const,
        st.sampled_from(SYMBOLS),
        coeff,
        number,
    )
    return st.one_of(number, symbolic_angle)


@st.composite
def gates(
    draw: st.DrawFn,
    num_qubits: int,
    names: Collection[str] = ALL_GATE_NAMES,
    max_controls: int = 4,
    symbolic: bool = False,
    qubits: Sequence[int] | None = None,
) -> Gate:
    """One random gate on distinct qubits drawn from ``qubits`` (default ``range(num_qubits)``).

    Args:
        draw: supplied by hypothesis.
        num_qubits: size of the qubit pool when ``qubits`` is None.
        names: gate names to draw from (those needing more qubits than available are skipped).
        max_controls: most controls of an ``mcx``.
        symbolic: allow symbolic angles.
        qubits: explicit qubit pool.

    Returns:
        The gate (``mcx`` goes through the normalising constructor, so it may come out as
        ``x``/``cx``/``ccx``).
    """
    pool = list(range(num_qubits)) if qubits is None else list(qubits)
    size = len(pool)
    usable = [n for n in names if (GATE_SPECS[n].num_qubits or 2) <= size]
    if not usable:
        raise ValueError(f"no gate of {sorted(names)} fits on {size} qubits")
    name = draw(st.sampled_from(sorted(usable)))
    spec = GATE_SPECS[name]
    arity = spec.num_qubits if spec.num_qubits is not None else draw(st.integers(2, min(size, max_controls + 1)))
    qs = draw(st.permutations(pool))[:arity]
    theta = draw(angles(symbolic)) if spec.num_params else 0.0
    if name in _FIXED:
        return _FIXED[name](qs[0])
    if name in _ONE:
        return _ONE[name](theta, qs[0])
    if name in _TWO:
        return _TWO[name](*qs)
    if name in _TWO_P:
        return _TWO_P[name](theta, *qs)
    if name == "ccx":
        return ccx(*qs)
    if name == "sbf":
        return sbf(theta, *qs)
    if name == "csbf":
        return csbf(theta, *qs)
    state = "".join(draw(st.lists(st.sampled_from("01"), min_size=arity - 1, max_size=arity - 1)))
    return mcx(qs[:-1], qs[-1], state)


@st.composite
def circuits(
    draw: st.DrawFn,
    min_qubits: int = 1,
    max_qubits: int = 5,
    max_gates: int = 12,
    names: Collection[str] = ALL_GATE_NAMES,
    max_controls: int = 4,
    symbolic: bool = False,
) -> Circuit:
    """A random circuit: a ``data`` register, sometimes an ``anc`` register, 1-3 sections.

    Args:
        draw: supplied by hypothesis.
        min_qubits: fewest qubits in all.
        max_qubits: most qubits in all.
        max_gates: most gates per section.
        names: gate names to use.
        max_controls: most controls of an ``mcx``.
        symbolic: allow symbolic angles (over :data:`SYMBOLS`).

    Returns:
        The circuit.
    """
    n = draw(st.integers(min_qubits, max_qubits))
    n_anc = draw(st.integers(0, min(2, n - 1)))
    regs = [Register("data", n - n_anc)] + ([Register("anc", n_anc)] if n_anc else [])
    sections = []
    for i in range(draw(st.integers(1, 3))):
        body = draw(st.lists(gates(n, names, max_controls=max_controls, symbolic=symbolic), max_size=max_gates))
        sections.append(Section(draw(st.sampled_from([f"phase_{i}", f"mixer_{i}", "initial_state"])), body))
    return Circuit(regs, sections)
