"""Compiled (numba) kernels of the feasible-subspace simulator: partial mixers and the tabulated phase.

A robot's mixer in one layer is a list of disjoint 2x2 rotations per plaquette, applied to every *line*
``x[a, :, col]`` of the state viewed as ``(pre, n, post)``. The BLAS path streams the whole array once per
plaquette; these kernels walk it once per layer: :data:`LANES` lines at a time are copied into a cache-sized block
(one ``[re_0..re_3, im_0..im_3]`` row per basis path), every plaquette's rotations applied, and copied back.
Lanes are written out so LLVM's SLP vectoriser makes each rotation one vector operation; blocks run in parallel
(``prange``). The backward kernel un-applies the rotations to two arrays at once and accumulates
``sum Im <y|G|x>``. The phase separator multiplies each amplitude by its cost level's table entry.

Rotation of a pair ``(i, j)``: ``x_i <- c x_i + s x_j``, ``x_j <- s x_i + c x_j``, ``c`` real, ``s`` imaginary
(``-i sin(beta / 2)`` forward, ``+i sin(beta / 2)`` backward), as BLAS ``zrot(c, s)``.

``AVAILABLE`` is False when numba cannot be imported; :mod:`qcpp.simulate.subspace` then uses its BLAS path.

Example:
    >>> import numpy as np
    >>> x = np.array([1.0 + 0j, 0.0, 0.0, 0.0]).reshape(1, 2, 2)   # pre 1, n 2, post 2
    >>> mixer(x, np.array([0]), np.array([1]), 0.0, -1j) if AVAILABLE else None
    >>> np.round(x.reshape(-1), 12).tolist() if AVAILABLE else [0j, 0j, -1j, 0j]
    [0j, 0j, -1j, 0j]
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from qcpp.io.caches import use_writable_numba_cache

use_writable_numba_cache()  # before numba decorates cache=True kernels: a read-only install still gets a cache
try:
    import numba
except ImportError:  # pragma: no cover - numba comes with quimb, a core dependency
    numba = None

__all__ = [
    "AVAILABLE", "LANES", "level_weights", "mixer", "mixer_adjoint", "pair_level_weights", "pair_weight_gradients",
    "phase", "phase_weights",
]

AVAILABLE = numba is not None
LANES = 4
"""Lines (robot-axis rows ``x[a, :, col]``) rotated together: a block of ``n`` basis paths by 4 lines is one
64-byte row ``[re_0..re_3, im_0..im_3]`` per path (small enough to stay in a core's L2 cache), and every rotation is
4-wide arithmetic."""


def _rotate_pair(b: np.ndarray, i: int, j: int, c: float, sg: float) -> None:
    """The rotation of pair ``(i, j)`` on a lane block ``b`` of shape ``(n, 8)``: row ``r`` holds basis path ``r``
    of four lines as ``[re_0..re_3, im_0..im_3]`` (``s = -1j * sg``). Written out lane by lane, loads before
    stores, so that LLVM's SLP vectoriser turns each line into one 4-wide operation."""
    ur0, ur1, ur2, ur3 = b[i, 0], b[i, 1], b[i, 2], b[i, 3]
    ui0, ui1, ui2, ui3 = b[i, 4], b[i, 5], b[i, 6], b[i, 7]
    vr0, vr1, vr2, vr3 = b[j, 0], b[j, 1], b[j, 2], b[j, 3]
    vi0, vi1, vi2, vi3 = b[j, 4], b[j, 5], b[j, 6], b[j, 7]
    b[i, 0], b[i, 1], b[i, 2], b[i, 3] = c * ur0 + sg * vi0, c * ur1 + sg * vi1, c * ur2 + sg * vi2, c * ur3 + sg * vi3
    b[i, 4], b[i, 5], b[i, 6], b[i, 7] = c * ui0 - sg * vr0, c * ui1 - sg * vr1, c * ui2 - sg * vr2, c * ui3 - sg * vr3
    b[j, 0], b[j, 1], b[j, 2], b[j, 3] = c * vr0 + sg * ui0, c * vr1 + sg * ui1, c * vr2 + sg * ui2, c * vr3 + sg * ui3
    b[j, 4], b[j, 5], b[j, 6], b[j, 7] = c * vi0 - sg * ur0, c * vi1 - sg * ur1, c * vi2 - sg * ur2, c * vi3 - sg * ur3


def _rotate_lanes(b: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float) -> None:
    """Every pair in order on a lane block (:func:`_rotate_pair`)."""
    for k in range(ii.shape[0]):
        _rotate_pair(b, ii[k], jj[k], c, sg)


def _unrotate_lanes(bx: np.ndarray, by: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float) -> float:
    """The pairs in reverse order on two lane blocks (:func:`_rotate_pair`); returns the sum over lanes and pairs
    of ``Im(conj(y_i) x_j + conj(y_j) x_i)`` taken before each pair is undone."""
    z0 = z1 = z2 = z3 = 0.0
    for k in range(ii.shape[0] - 1, -1, -1):
        i = ii[k]
        j = jj[k]
        z0 += by[i, 0] * bx[j, 4] - by[i, 4] * bx[j, 0] + by[j, 0] * bx[i, 4] - by[j, 4] * bx[i, 0]
        z1 += by[i, 1] * bx[j, 5] - by[i, 5] * bx[j, 1] + by[j, 1] * bx[i, 5] - by[j, 5] * bx[i, 1]
        z2 += by[i, 2] * bx[j, 6] - by[i, 6] * bx[j, 2] + by[j, 2] * bx[i, 6] - by[j, 6] * bx[i, 2]
        z3 += by[i, 3] * bx[j, 7] - by[i, 7] * bx[j, 3] + by[j, 3] * bx[i, 7] - by[j, 7] * bx[i, 3]
        _rotate_pair(bx, i, j, c, sg)
        _rotate_pair(by, i, j, c, sg)
    return (z0 + z1) + (z2 + z3)


def _lane_lines(l0: int, nl: int, post: int, aa: np.ndarray, cc: np.ndarray) -> None:
    """Lines ``l0 .. l0 + nl - 1`` (line ``L`` = the robot-axis row ``x[L // post, :, L % post]``) as ``(a, col)``."""
    for t in range(nl):
        aa[t] = (l0 + t) // post
        cc[t] = (l0 + t) % post


def _gather_lanes(xr: np.ndarray, aa: np.ndarray, cc: np.ndarray, nl: int, b: np.ndarray) -> None:
    """Copy ``nl`` lines into the lane block ``b`` (unused lanes zero)."""
    for r in range(xr.shape[1]):
        for t in range(nl):
            b[r, t] = xr[aa[t], r, 2 * cc[t]]
            b[r, LANES + t] = xr[aa[t], r, 2 * cc[t] + 1]
        for t in range(nl, LANES):
            b[r, t] = 0.0
            b[r, LANES + t] = 0.0


def _scatter_lanes(b: np.ndarray, xr: np.ndarray, aa: np.ndarray, cc: np.ndarray, nl: int) -> None:
    for r in range(xr.shape[1]):
        for t in range(nl):
            xr[aa[t], r, 2 * cc[t]] = b[r, t]
            xr[aa[t], r, 2 * cc[t] + 1] = b[r, LANES + t]


def _chunk_bounds(total: int, chunks: int, k: int) -> tuple[int, int]:
    return k * total // chunks, (k + 1) * total // chunks


def _mixer_impl(xr: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float, chunks: int) -> None:
    """``xr``: the float64 view ``(pre, n, 2 post)``; rotation ``c`` and ``s = -1j * sg``. The ``pre * post``
    lines are cut into blocks of :data:`LANES`, and the blocks into ``chunks`` parallel work items."""
    pre, n, post2 = xr.shape
    post = post2 // 2
    nblocks = (pre * post + LANES - 1) // LANES
    for ch in numba.prange(chunks):
        k0, k1 = _chunk_bounds(nblocks, chunks, ch)
        b = np.empty((n, 2 * LANES))
        aa = np.empty(LANES, dtype=np.int64)
        cc = np.empty(LANES, dtype=np.int64)
        for blk in range(k0, k1):
            l0 = blk * LANES
            nl = min(LANES, pre * post - l0)
            _lane_lines(l0, nl, post, aa, cc)
            _gather_lanes(xr, aa, cc, nl, b)
            _rotate_lanes(b, ii, jj, c, sg)
            _scatter_lanes(b, xr, aa, cc, nl)


def _mixer_adjoint_impl(
    xr: np.ndarray, yr: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float, chunks: int
) -> float:
    """Float64 views as in :func:`_mixer_impl`; ``s = -1j * sg`` is the inverse rotation here. Returns the
    rotations' ``sum Im <y|G|x>``."""
    pre, n, post2 = xr.shape
    post = post2 // 2
    nblocks = (pre * post + LANES - 1) // LANES
    acc = np.zeros(chunks)
    for ch in numba.prange(chunks):
        k0, k1 = _chunk_bounds(nblocks, chunks, ch)
        bx = np.empty((n, 2 * LANES))
        by = np.empty((n, 2 * LANES))
        aa = np.empty(LANES, dtype=np.int64)
        cc = np.empty(LANES, dtype=np.int64)
        z = 0.0
        for blk in range(k0, k1):
            l0 = blk * LANES
            nl = min(LANES, pre * post - l0)
            _lane_lines(l0, nl, post, aa, cc)
            _gather_lanes(xr, aa, cc, nl, bx)
            _gather_lanes(yr, aa, cc, nl, by)
            z += _unrotate_lanes(bx, by, ii, jj, c, sg)
            _scatter_lanes(bx, xr, aa, cc, nl)
            _scatter_lanes(by, yr, aa, cc, nl)
        acc[ch] = z
    return acc.sum()


_BLOCK = 1 << 16  # amplitudes per parallel block of the phase kernels


def _phase_impl(xr: np.ndarray, lev: np.ndarray, tr: np.ndarray, ti: np.ndarray) -> None:
    """``x *= t[lev]`` on the float64 view (``t = tr + 1j ti``)."""
    n = lev.shape[0]
    for b in numba.prange((n + _BLOCK - 1) // _BLOCK):
        for k in range(b * _BLOCK, min(n, (b + 1) * _BLOCK)):
            a, d = tr[lev[k]], ti[lev[k]]
            u, v = xr[2 * k], xr[2 * k + 1]
            xr[2 * k] = a * u - d * v
            xr[2 * k + 1] = a * v + d * u


def _phase_weights_impl(xr: np.ndarray, yr: np.ndarray, lev: np.ndarray, nlev: int) -> np.ndarray:
    """``sum over amplitudes of level l of Im(conj(y) x)`` for every level ``l``."""
    n = lev.shape[0]
    nb = (n + _BLOCK - 1) // _BLOCK
    part = np.zeros((nb, nlev))
    for b in numba.prange(nb):
        for k in range(b * _BLOCK, min(n, (b + 1) * _BLOCK)):
            part[b, lev[k]] += yr[2 * k] * xr[2 * k + 1] - yr[2 * k + 1] * xr[2 * k]
    return part.sum(axis=0)


def _level_weights_impl(xr: np.ndarray, lev: np.ndarray, nlev: int) -> np.ndarray:
    """``sum over amplitudes of level l of |x|^2`` for every level ``l``."""
    n = lev.shape[0]
    nb = (n + _BLOCK - 1) // _BLOCK
    part = np.zeros((nb, nlev))
    for b in numba.prange(nb):
        for k in range(b * _BLOCK, min(n, (b + 1) * _BLOCK)):
            part[b, lev[k]] += xr[2 * k] * xr[2 * k] + xr[2 * k + 1] * xr[2 * k + 1]
    return part.sum(axis=0)


def _pair_level_weights_impl(lev: np.ndarray, p0: np.ndarray, p1: np.ndarray, nlev: int) -> np.ndarray:
    """``sum_{a, b: lev[a, b] = l} p0[a] p1[b]`` for every level ``l``."""
    n0 = lev.shape[0]
    nb = (n0 + 63) // 64
    part = np.zeros((nb, nlev))
    for blk in numba.prange(nb):
        for a in range(blk * 64, min(n0, (blk + 1) * 64)):
            pa = p0[a]
            for b in range(lev.shape[1]):
                part[blk, lev[a, b]] += pa * p1[b]
    return part.sum(axis=0)


def _pair_weight_gradients_impl(
    lev: np.ndarray, dw: np.ndarray, p0: np.ndarray, p1: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """``g0[a] = sum_b dw[lev[a, b]] p1[b]`` and ``g1[b] = sum_a p0[a] dw[lev[a, b]]``."""
    n0, n1 = lev.shape
    nb = (n0 + 63) // 64
    g0 = np.zeros(n0)
    part = np.zeros((nb, n1))
    for blk in numba.prange(nb):
        for a in range(blk * 64, min(n0, (blk + 1) * 64)):
            pa = p0[a]
            acc = 0.0
            for b in range(n1):
                d = dw[lev[a, b]]
                acc += d * p1[b]
                part[blk, b] += pa * d
            g0[a] = acc
    return g0, part.sum(axis=0)


if AVAILABLE:
    _inline = numba.njit(cache=True, nogil=True)
    _rotate_pair = _inline(_rotate_pair)
    _rotate_lanes = _inline(_rotate_lanes)
    _unrotate_lanes = _inline(_unrotate_lanes)
    _lane_lines = _inline(_lane_lines)
    _gather_lanes = _inline(_gather_lanes)
    _scatter_lanes = _inline(_scatter_lanes)
    _chunk_bounds = _inline(_chunk_bounds)
    _jit = numba.njit(parallel=True, cache=True, nogil=True)
    _serial = numba.njit(cache=True, nogil=True)  # prange runs as range: no thread start-up and barrier
    _kernels = {
        name: (_serial(fn), _jit(fn))
        for name, fn in (("mixer", _mixer_impl), ("mixer_adjoint", _mixer_adjoint_impl), ("phase", _phase_impl),
                         ("phase_weights", _phase_weights_impl),
                         ("level_weights", _level_weights_impl),
                         ("pair_level_weights", _pair_level_weights_impl),
                         ("pair_weight_gradients", _pair_weight_gradients_impl))
    }


@contextmanager
def _slp_vectorize() -> Iterator[None]:
    """Compile with LLVM's SLP vectoriser on (numba leaves it off by default): it packs the four written-out
    lanes of :func:`_rotate_lanes` into vector instructions (without it they stay scalar). Scoped to our
    kernels' calls (where numba compiles them on first use) so that other numba code keeps numba's default."""
    before = numba.config.SLP_VECTORIZE
    numba.config.SLP_VECTORIZE = 1
    try:
        yield
    finally:
        numba.config.SLP_VECTORIZE = before


PARALLEL_MIN = 1 << 16
"""Arrays smaller than this many amplitudes run single-threaded: on a busy machine a parallel region's barrier
can wait a whole scheduler time slice for its second thread, which costs more than the work."""

CHUNKS_PER_THREAD = 4
"""Parallel work items per thread in the mixer kernels (each allocates its lane blocks once); more than one
per thread so that a thread slowed by other load on the machine does not hold up the rest."""


def _pick(name: str, size: int):  # type: ignore[no-untyped-def]
    return _kernels[name][size >= PARALLEL_MIN]


def _chunks_for(size: int) -> int:
    return CHUNKS_PER_THREAD * numba.get_num_threads() if size >= PARALLEL_MIN else 1


def mixer(x: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, s: complex) -> None:
    """Apply the rotations ``(ii[k], jj[k])`` in order along axis 1 of ``x`` (shape ``(pre, n, post)``), in place.

    Args:
        x: complex128 C-contiguous array.
        ii, jj: The pairs, every plaquette's in turn (``intp``).
        c: ``cos(beta / 2)``.
        s: ``-1j * sin(beta / 2)`` (forward) or its conjugate (undo): a purely imaginary number.
    """
    with _slp_vectorize():
        _pick("mixer", x.size)(_real_view(x), ii, jj, float(c), float(-complex(s).imag), _chunks_for(x.size))


def mixer_adjoint(x: np.ndarray, y: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, s: complex) -> float:
    """Undo the rotations on ``x`` and ``y`` in reverse order; return ``sum_k Im <y|G_k|x>`` taken before each
    pair is undone (``G_k`` the pair's ``X``).

    Args:
        x, y: complex128 C-contiguous arrays of the same shape ``(pre, n, post)``.
        ii, jj: As in :func:`mixer`.
        c: ``cos(beta / 2)``.
        s: ``+1j * sin(beta / 2)`` (the inverse rotation).
    """
    kernel = _pick("mixer_adjoint", x.size)
    with _slp_vectorize():
        return float(kernel(_real_view(x), _real_view(y), ii, jj, float(c), float(-complex(s).imag),
                            _chunks_for(x.size)))


def phase(x: np.ndarray, levels: np.ndarray, table: np.ndarray) -> None:
    """``x *= table[levels]`` in place (``x`` complex128 and ``levels`` uint8/uint16, both C-contiguous, same
    number of elements)."""
    _pick("phase", x.size)(_real_view(x).reshape(-1), levels.reshape(-1), np.ascontiguousarray(table.real),
           np.ascontiguousarray(table.imag))


def phase_weights(x: np.ndarray, y: np.ndarray, levels: np.ndarray, num_levels: int) -> np.ndarray:
    """Per level ``l``: ``sum_{k: levels[k] = l} Im(conj(y_k) x_k)`` (float64, length ``num_levels``)."""
    kernel = _pick("phase_weights", x.size)
    return kernel(_real_view(x).reshape(-1), _real_view(y).reshape(-1), levels.reshape(-1), int(num_levels))


def level_weights(x: np.ndarray, levels: np.ndarray, num_levels: int) -> np.ndarray:
    """Per level ``l``: ``sum_{k: levels[k] = l} |x_k|^2`` (float64, length ``num_levels``): the measured cost's
    distribution of the state ``x`` over a cost table.

    Example:
        >>> import numpy as np
        >>> level_weights(np.array([0.6, 0.8j, 0.0]), np.array([1, 0, 1], dtype=np.uint8), 2).round(12).tolist()
        [0.64, 0.36]
    """
    return _pick("level_weights", x.size)(_real_view(x).reshape(-1), levels.reshape(-1), int(num_levels))


def pair_level_weights(levels: np.ndarray, p0: np.ndarray, p1: np.ndarray, num_levels: int) -> np.ndarray:
    """The measured cost's distribution of a two-robot product state: per level ``l``,
    ``sum_{a, b: levels[a, b] = l} p0[a] p1[b]`` (one pass over the ``(n0, n1)`` uint8/uint16 levels, no state).

    Example:
        >>> import numpy as np
        >>> lev = np.array([[0, 1], [1, 1]], dtype=np.uint8)
        >>> pair_level_weights(lev, np.array([0.5, 0.5]), np.array([0.25, 0.75]), 2).tolist()
        [0.125, 0.875]
    """
    return _pick("pair_level_weights", levels.size)(levels, np.ascontiguousarray(p0, dtype=np.float64),
                                                    np.ascontiguousarray(p1, dtype=np.float64), int(num_levels))


def pair_weight_gradients(
    levels: np.ndarray, dw: np.ndarray, p0: np.ndarray, p1: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The derivatives of ``F(pair_level_weights(levels, p0, p1))`` in ``p0`` and ``p1`` given ``dw = dF/dweights``:
    ``(sum_b dw[levels[a, b]] p1[b], sum_a p0[a] dw[levels[a, b]])``."""
    return _pick("pair_weight_gradients", levels.size)(levels, np.ascontiguousarray(dw, dtype=np.float64),
                                                       np.ascontiguousarray(p0, dtype=np.float64),
                                                       np.ascontiguousarray(p1, dtype=np.float64))


def _real_view(x: np.ndarray) -> np.ndarray:
    """The float64 view ``(pre, n, 2 post)`` of a C-contiguous complex128 ``(pre, n, post)`` array."""
    if x.dtype != np.complex128 or not x.flags.c_contiguous:
        raise ValueError("the kernels need a C-contiguous complex128 array")
    return x.view(np.float64)
