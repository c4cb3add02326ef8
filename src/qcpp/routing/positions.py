"""Where the logical qubits stand on the device while a circuit is routed: :class:`Positions`.

Example:
    >>> pos = Positions((2, 0), 3)
    >>> pos.swap(0, 1)  # logical 1 moves to physical 1; physical 0 is free now
    >>> pos.where, pos.who
    ([2, 1], [-1, 1, 0])
"""

from __future__ import annotations

__all__ = ["Positions"]


class Positions:
    """Where every logical qubit is (``where``: logical -> physical) and who is on every physical qubit (``who``:
    physical -> logical, -1 for a free qubit) while windows are routed; ``swap`` moves both.

    Invariant: ``who[where[lq]] == lq`` for every logical qubit ``lq``.
    """

    def __init__(self, layout: tuple[int, ...], size: int) -> None:
        self.where = list(layout)
        self.who = [-1] * size
        for lq, p in enumerate(layout):
            self.who[p] = lq

    @classmethod
    def identity(cls, size: int) -> Positions:
        """Every physical qubit holding the logical qubit of its own number."""
        pos = cls.__new__(cls)
        pos.where = list(range(size))
        pos.who = list(range(size))
        return pos

    def swap(self, p: int, q: int) -> None:
        """Exchange the logical qubits on physical ``p`` and ``q`` (either may be free)."""
        a, b = self.who[p], self.who[q]
        self.who[p], self.who[q] = b, a
        if a >= 0:
            self.where[a] = q
        if b >= 0:
            self.where[b] = p
