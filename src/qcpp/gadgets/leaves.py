"""Leaf gadgets: the gates a construction is built from, each with its lowered cost in closed form.

Every construction of :mod:`qcpp.gadgets` is a sequence of these leaves (with a mirror image for the
uncompute), so its cost is a sum of the closed forms below (each equal to the count of the leaf's own lowered
gates).

===========  ===========================================  =====================================
leaf         what                                         lowered cost
===========  ===========================================  =====================================
``cx``       CNOT                                         1 cx
``x``        NOT                                          1 x
``and``      AND of two positive controls into clean t    3 cx, 2 h, 2 t, 2 tdg, 1 sdg
``and_dg``   its uncompute                                3 cx, 2 h, 2 t, 2 tdg, 1 s
``ccx``      full Toffoli (target may hold data)          6 cx, 2 h, 4 t, 3 tdg
``mcx(k)``   k >= 3 positive controls, clean work         (k - 2) ANDs + their mirrors + 1 ccx
``crx``      controlled RX(theta)                         2 cx, 2 h, 2 rz
``ccrx``     doubly controlled RX(theta) (phase poly.)    4 cx, 2 h, 4 rz
``csbf``     RX(theta) on X⊗4 controlled (paper rule)     8 cx, 8 h, 2 rz
===========  ===========================================  =====================================

``ccrx`` is ``H_t exp(-i theta/2 a b Z_t) H_t`` with ``a b Z_t = (Z_t - Z_a Z_t - Z_b Z_t + Z_a Z_b Z_t) / 4``:
four RZ(±theta/4) on the target between four CNOTs that walk the parities ``t, t^a, t^a^b, t^b`` (no ancilla, but
four arbitrary rotations instead of two: a NISQ choice).

Example:
    >>> leaf_cost("and").to_dict()
    {'cx': 3, 'h': 2, 'sdg': 1, 't': 2, 'tdg': 2}
    >>> leaf_cost("mcx", 4).cx
    18
"""

from __future__ import annotations

from functools import cache

from qcpp.ir.angles import Param
from qcpp.ir.cost import Cost
from qcpp.ir.gates import Gate, cx, h, rz

__all__ = ["LEAF_NAMES", "ccrx_gates", "leaf_cost", "leaf_logical_cost"]

_AND = Cost.of(cx=3, h=2, t=2, tdg=2, sdg=1)
_AND_DG = Cost.of(cx=3, h=2, t=2, tdg=2, s=1)
_CCX = Cost.of(cx=6, h=2, t=4, tdg=3)

_FIXED = {
    "cx": Cost.of(cx=1),
    "x": Cost.of(x=1),
    "and": _AND,
    "and_dg": _AND_DG,
    "ccx": _CCX,
    "crx": Cost.of(cx=2, h=2, rz=2),
    "ccrx": Cost.of(cx=4, h=2, rz=4),
    "csbf": Cost.of(cx=8, h=8, rz=2),
}
_LOGICAL = {**_FIXED, "and": Cost.of({"and": 1}), "and_dg": Cost.of(and_dg=1), "ccx": Cost.of(ccx=1)}

LEAF_NAMES: tuple[str, ...] = (*_FIXED, "mcx")
"""Every leaf kind."""


@cache
def leaf_cost(name: str, k: int = 0) -> Cost:
    """Lowered cost of one leaf (``k``: controls of an ``mcx``, all positive).

    Args:
        name: a name of :data:`LEAF_NAMES`.
        k: number of controls (``mcx`` only; ``k >= 3``).

    Returns:
        The cost in the default basis.

    Pure memo: ``leaf_cost.cache_clear()`` empties it."""
    return _cost(name, k, _FIXED)


@cache
def leaf_logical_cost(name: str, k: int = 0) -> Cost:
    """Like :func:`leaf_cost` with ANDs, their uncomputes and Toffolis kept whole (the fault-tolerant view).
    Pure memo: ``leaf_logical_cost.cache_clear()`` empties it."""
    return _cost(name, k, _LOGICAL)


def _cost(name: str, k: int, table: dict[str, Cost]) -> Cost:
    if name == "mcx":
        if k < 3:
            raise ValueError(f"mcx leaves have k >= 3 controls, got {k}")
        return (k - 2) * (table["and"] + table["and_dg"]) + table["ccx"]
    try:
        return table[name]
    except KeyError:
        raise ValueError(f"unknown leaf {name!r}") from None


def ccrx_gates(theta: Param, a: int, b: int, target: int) -> list[Gate]:
    """RX(theta) on ``target`` controlled by ``a`` AND ``b`` (both on |1>), as a phase polynomial, no ancilla.

    >>> [g.name for g in ccrx_gates(0.4, 0, 1, 2)]
    ['h', 'rz', 'cx', 'rz', 'cx', 'rz', 'cx', 'rz', 'cx', 'h']
    """
    q = theta / 4
    return [
        h(target), rz(q, target), cx(a, target), rz(-q, target), cx(b, target),
        rz(q, target), cx(a, target), rz(-q, target), cx(b, target), h(target),
    ]  # fmt: skip
