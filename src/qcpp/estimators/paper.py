"""The paper's own resource estimates, exactly as its section "Resource estimates" states them.

The paper (arXiv:2407.08767) estimates one QAOA layer for ``r`` robots on an ``m x n`` grid with
``e = m(n-1) + n(m-1)`` edges:

* qubits: ``N_Q ~ r e`` data qubits plus "eight ancillary qubits per robot" (:attr:`PaperEstimate.data_qubits`,
  :attr:`PaperEstimate.qubits` = ``r e + 8 r``);
* phase separator: ``r e`` single-qubit gates and, per quadratic term, 2 CNOT + 1 RZ: "a total of ``re(re+1)``
  CNOT gates and ``re(re+1)/2`` single-qubit gates";
* mixer: ``r(m-1)(n-1)`` partial mixers of 44 three-qubit Toffolis (an ``(l+1)``-qubit Toffoli is ``4(l-2)`` of
  them, Barenco et al.), each 6 CNOT + 9 single-qubit gates, plus the controlled SBF rotation (8 CNOT, 10
  single-qubit gates); "twice of the controlled partial mixer" doubles the whole partial mixer by default (544 CNOT,
  812 single-qubit gates) or only its logic with ``doubling="logic"`` (536, 802).

For ``p`` layers the layer is multiplied by ``p`` and the initial state added (one X per edge of each robot's
initial path, ``r (m + n - 2)`` gates). Each reading is discussed in ``docs/paper-notes.md``.

Example (3x3 grid, one robot: e = 12):
    >>> est = paper_estimate(3, 3, 1)
    >>> est.data_qubits, est.qubits, est.phase_cx, est.phase_single_qubit
    (12, 20, 156, 90)
    >>> est.partial_mixers, est.partial_mixer_cx, est.partial_mixer_single_qubit
    (4, 544, 812)
    >>> est.cx, est.single_qubit
    (2332, 3342)
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any, Literal

__all__ = [
    "ANCILLAS_PER_ROBOT",
    "Doubling",
    "PaperEstimate",
    "paper_estimate",
    "paper_partial_mixer",
    "toffoli_decomposition",
]

ANCILLAS_PER_ROBOT = 8
TOFFOLI_CX = 6
TOFFOLI_SINGLE = 9
SBF_H, SBF_CX, SBF_RZ = 8, 6, 1
CONTROLLED_RZ_RZ, CONTROLLED_RZ_CX = 2, 2
Doubling = Literal["partial-mixer", "logic"]
DOUBLINGS: tuple[Doubling, ...] = ("partial-mixer", "logic")


def toffoli_decomposition(qubits: int) -> int:
    """Number of 3-qubit Toffolis the paper uses for one ``qubits``-qubit Toffoli.

    Args:
        qubits: ``l + 1`` (``l`` controls and one target), at least 3.

    Returns:
        ``1`` for a 3-qubit Toffoli, ``4(l - 2)`` for ``l >= 3`` (Barenco et al. 1995, Lemma 7.2).

    >>> toffoli_decomposition(3), toffoli_decomposition(5), toffoli_decomposition(7)
    (1, 8, 16)
    """
    if qubits < 3:
        raise ValueError(f"a Toffoli gate has at least 3 qubits, got {qubits}")
    controls = qubits - 1
    return 1 if controls == 2 else 4 * (controls - 2)


@dataclass(frozen=True)
class PaperPartialMixer:
    """The paper's cost of one partial mixer.

    Attributes:
        toffolis: 3-qubit Toffolis of the logic (f1, f2, f3, f), computed once.
        logic_cx: CNOTs of the logic, computed once.
        logic_single_qubit: single-qubit gates of the logic, computed once.
        sbf_cx: CNOTs of the controlled SBF rotation.
        sbf_single_qubit: single-qubit gates of the controlled SBF rotation.
        cx: CNOTs after doubling.
        single_qubit: single-qubit gates after doubling.
    """

    toffolis: int
    logic_cx: int
    logic_single_qubit: int
    sbf_cx: int
    sbf_single_qubit: int
    cx: int
    single_qubit: int


def paper_partial_mixer(doubling: Doubling = "partial-mixer") -> PaperPartialMixer:
    """Cost of one partial mixer as the paper states it.

    Args:
        doubling: what "twice of the controlled partial mixer" doubles: ``partial-mixer`` (everything,
            default) or ``logic`` (only the Toffoli logic; the controlled SBF rotation once).

    >>> pm = paper_partial_mixer()
    >>> pm.toffolis, pm.logic_cx, pm.logic_single_qubit, pm.sbf_cx, pm.sbf_single_qubit
    (44, 264, 396, 8, 10)
    >>> paper_partial_mixer("logic").cx
    536
    """
    if doubling not in DOUBLINGS:
        raise ValueError(f"doubling must be one of {DOUBLINGS}, got {doubling!r}")
    f1 = 1 * toffoli_decomposition(5)
    f2 = 2 * toffoli_decomposition(5)
    f3 = 4 * toffoli_decomposition(3)
    f = 1 * toffoli_decomposition(7)
    toffolis = f1 + f2 + f3 + f
    logic_cx, logic_1q = TOFFOLI_CX * toffolis, TOFFOLI_SINGLE * toffolis
    sbf_cx = SBF_CX + CONTROLLED_RZ_CX
    sbf_1q = SBF_H + (SBF_RZ - 1) + CONTROLLED_RZ_RZ  # the RZ of the figure becomes the controlled RZ
    if doubling == "partial-mixer":
        cx, single = 2 * (logic_cx + sbf_cx), 2 * (logic_1q + sbf_1q)
    else:
        cx, single = 2 * logic_cx + sbf_cx, 2 * logic_1q + sbf_1q
    return PaperPartialMixer(toffolis, logic_cx, logic_1q, sbf_cx, sbf_1q, cx, single)


@dataclass(frozen=True)
class PaperEstimate:
    """The paper's estimate for one grid, robot count and number of layers.

    Attributes:
        rows, cols, robots, p: the point.
        doubling: the reading of "twice of the controlled partial mixer" (see :func:`paper_partial_mixer`).
        edges: ``e = m(n-1) + n(m-1)``.
        data_qubits: ``N_Q ~ r e``.
        ancillas: ``8 r``.
        qubits: ``r e + 8 r``.
        initial_single_qubit: X gates of the initial state, ``r (m + n - 2)``.
        phase_cx, phase_single_qubit: one phase separator.
        partial_mixers: ``r (m-1)(n-1)``.
        partial_mixer_cx, partial_mixer_single_qubit: one partial mixer (after doubling).
        mixer_cx, mixer_single_qubit: one full mixer.
        toffolis: 3-qubit Toffolis in all layers (counting the doubling).
        cx, single_qubit: the whole circuit, ``initial + p (phase + mixer)``.
    """

    rows: int
    cols: int
    robots: int
    p: int
    doubling: Doubling
    edges: int
    data_qubits: int
    ancillas: int
    qubits: int
    initial_single_qubit: int
    phase_cx: int
    phase_single_qubit: int
    partial_mixers: int
    partial_mixer_cx: int
    partial_mixer_single_qubit: int
    mixer_cx: int
    mixer_single_qubit: int
    toffolis: int
    cx: int
    single_qubit: int

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return asdict(self)


def paper_estimate(
    rows: int, cols: int, robots: int, p: int = 1, doubling: Doubling = "partial-mixer"
) -> PaperEstimate:
    """The paper's estimate (see the module docstring for each term and reading).

    Args:
        rows: grid rows (the paper's ``m`` or ``n``; its formulas are symmetric).
        cols: grid columns.
        robots: number of robots ``r``.
        p: number of QAOA layers.
        doubling: see :func:`paper_partial_mixer`.

    >>> paper_estimate(2, 2, 1).cx   # re = 4: phase 4*5 = 20 CNOT, one partial mixer 544
    564
    """
    for name, value, low in (("rows", rows, 2), ("cols", cols, 2), ("robots", robots, 1), ("p", p, 0)):
        if not isinstance(value, int) or isinstance(value, bool) or value < low:
            raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    e = rows * (cols - 1) + cols * (rows - 1)
    re = robots * e
    phase_cx = re * (re + 1)
    phase_1q = re + re * (re + 1) // 2
    pm = paper_partial_mixer(doubling)
    n_pm = robots * (rows - 1) * (cols - 1)
    init_1q = robots * (rows + cols - 2)
    mixer_cx, mixer_1q = n_pm * pm.cx, n_pm * pm.single_qubit
    per_pm_toffolis = 2 * pm.toffolis
    return PaperEstimate(
        rows=rows,
        cols=cols,
        robots=robots,
        p=p,
        doubling=doubling,
        edges=e,
        data_qubits=re,
        ancillas=ANCILLAS_PER_ROBOT * robots,
        qubits=re + ANCILLAS_PER_ROBOT * robots,
        initial_single_qubit=init_1q,
        phase_cx=phase_cx,
        phase_single_qubit=phase_1q,
        partial_mixers=n_pm,
        partial_mixer_cx=pm.cx,
        partial_mixer_single_qubit=pm.single_qubit,
        mixer_cx=mixer_cx,
        mixer_single_qubit=mixer_1q,
        toffolis=p * n_pm * per_pm_toffolis,
        cx=p * (phase_cx + mixer_cx),
        single_qubit=init_1q + p * (phase_1q + mixer_1q),
    )
