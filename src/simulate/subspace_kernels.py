"""Compiled (numba) kernels of the feasible-subspace simulator: partial mixers and the tabulated phase.

A robot's mixer in one QAOA layer is an ordered list of disjoint 2x2 rotations per plaquette, applied along the
robot's axis of the state array viewed as ``(pre, n, post)``. The BLAS path of :mod:`simulate.subspace` calls
``zrot`` once per pair, which streams the whole array through memory once per plaquette. These kernels walk
the array once per layer instead: they cut it into tiles ``x[a, :, c0:c1]`` (every basis path of the robot,
``TILE`` trailing columns), copy a tile into a buffer with the robot's axis contiguous (a row per column, a
few hundred KiB that stay in cache), apply every plaquette's rotations to each row, and copy back (when the
robot's axis is the last one, rows are used in place); tiles are independent, so they run in parallel
(numba's threading layer, ``prange``). The backward
kernel un-applies the rotations to two arrays at once and accumulates ``sum Im <y|G|x>`` on the way. The
phase separator multiplies each amplitude by its cost level's entry of a table, in parallel blocks.

Rotation of a pair ``(i, j)``: ``x_i <- c x_i + s x_j``, ``x_j <- s x_i + c x_j`` with ``c`` real and ``s``
imaginary (``s = -i sin(beta / 2)`` forward, ``+i sin(beta / 2)`` backward), as ``zrot(c, s)``; the kernels
work on the arrays' float64 views with the real and imaginary parts spelled out (numba then vectorises).

``AVAILABLE`` is False when numba cannot be imported; :mod:`simulate.subspace` then uses its BLAS path.

Example:
    >>> import numpy as np
    >>> x = np.array([1.0 + 0j, 0.0, 0.0, 0.0]).reshape(1, 2, 2)   # pre 1, n 2, post 2
    >>> mixer(x, np.array([0]), np.array([1]), 0.0, -1j, 8) if AVAILABLE else None
    >>> np.round(x.reshape(-1), 12).tolist() if AVAILABLE else [0j, 0j, -1j, 0j]
    [0j, 0j, -1j, 0j]
"""

from __future__ import annotations

import numpy as np

try:
    import numba
except ImportError:  # pragma: no cover - numba comes with quimb, a core dependency
    numba = None

__all__ = ["AVAILABLE", "TILE", "mixer", "mixer_adjoint", "phase", "phase_weights"]

AVAILABLE = numba is not None
TILE = 8
"""Trailing columns per tile, gathered into a buffer of ``TILE`` contiguous rows (one per column) so that each
pair touches two nearby amplitudes: 8 columns of a 10,000-path robot are 1.3 MiB."""


def _rotate_row(row: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float) -> None:
    """Every pair in order on one contiguous float64 row ``[re_0, im_0, re_1, ...]`` (``s = -1j * sg``)."""
    for k in range(ii.shape[0]):
        i = 2 * ii[k]
        j = 2 * jj[k]
        ur, ui, vr, vi = row[i], row[i + 1], row[j], row[j + 1]
        row[i] = c * ur + sg * vi
        row[i + 1] = c * ui - sg * vr
        row[j] = c * vr + sg * ui
        row[j + 1] = c * vi - sg * ur


def _unrotate_rows(xrow: np.ndarray, yrow: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float) -> float:
    """The pairs in reverse order on two rows; returns ``sum Im(conj(y_i) x_j + conj(y_j) x_i)`` taken before
    each pair is undone."""
    z = 0.0
    for k in range(ii.shape[0] - 1, -1, -1):
        i = 2 * ii[k]
        j = 2 * jj[k]
        ur, ui, vr, vi = xrow[i], xrow[i + 1], xrow[j], xrow[j + 1]
        pr, pi, qr, qi = yrow[i], yrow[i + 1], yrow[j], yrow[j + 1]
        z += pr * vi - pi * vr + qr * ui - qi * ur
        xrow[i] = c * ur + sg * vi
        xrow[i + 1] = c * ui - sg * vr
        xrow[j] = c * vr + sg * ui
        xrow[j + 1] = c * vi - sg * ur
        yrow[i] = c * pr + sg * qi
        yrow[i + 1] = c * pi - sg * qr
        yrow[j] = c * qr + sg * pi
        yrow[j + 1] = c * qi - sg * pr
    return z


def _gather(xr: np.ndarray, a: int, c0: int, c1: int, buf: np.ndarray) -> None:
    """``buf[col - c0]`` = the robot-axis row ``x[a, :, col]`` as ``[re, im, ...]``, for ``col`` in ``[c0, c1)``."""
    for r in range(xr.shape[1]):
        for col in range(c0, c1):
            buf[col - c0, 2 * r] = xr[a, r, 2 * col]
            buf[col - c0, 2 * r + 1] = xr[a, r, 2 * col + 1]


def _scatter(buf: np.ndarray, xr: np.ndarray, a: int, c0: int, c1: int) -> None:
    for r in range(xr.shape[1]):
        for col in range(c0, c1):
            xr[a, r, 2 * col] = buf[col - c0, 2 * r]
            xr[a, r, 2 * col + 1] = buf[col - c0, 2 * r + 1]


def _mixer_impl(xr: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float, tile: int) -> None:
    """``xr``: the float64 view ``(pre, n, 2 post)``; rotation ``c`` and ``s = -1j * sg``."""
    pre, n, post2 = xr.shape
    post = post2 // 2
    if post == 1:  # the robot's axis is contiguous already
        for a in numba.prange(pre):
            _rotate_row(xr[a].reshape(2 * n), ii, jj, c, sg)
        return
    ntiles = (post + tile - 1) // tile
    for t in numba.prange(pre * ntiles):
        a = t // ntiles
        c0 = (t % ntiles) * tile
        c1 = min(c0 + tile, post)
        buf = np.empty((c1 - c0, 2 * n))
        _gather(xr, a, c0, c1, buf)
        for col in range(c1 - c0):
            _rotate_row(buf[col], ii, jj, c, sg)
        _scatter(buf, xr, a, c0, c1)


def _mixer_adjoint_impl(
    xr: np.ndarray, yr: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float, tile: int
) -> float:
    """Float64 views as in :func:`_mixer_impl`; ``s = -1j * sg`` is the inverse rotation here."""
    pre, n, post2 = xr.shape
    post = post2 // 2
    if post == 1:
        acc1 = np.zeros(pre)
        for a in numba.prange(pre):
            acc1[a] = _unrotate_rows(xr[a].reshape(2 * n), yr[a].reshape(2 * n), ii, jj, c, sg)
        return acc1.sum()
    ntiles = (post + tile - 1) // tile
    acc = np.zeros(pre * ntiles)
    for t in numba.prange(pre * ntiles):
        a = t // ntiles
        c0 = (t % ntiles) * tile
        c1 = min(c0 + tile, post)
        bx = np.empty((c1 - c0, 2 * n))
        by = np.empty((c1 - c0, 2 * n))
        _gather(xr, a, c0, c1, bx)
        _gather(yr, a, c0, c1, by)
        z = 0.0
        for col in range(c1 - c0):
            z += _unrotate_rows(bx[col], by[col], ii, jj, c, sg)
        _scatter(bx, xr, a, c0, c1)
        _scatter(by, yr, a, c0, c1)
        acc[t] = z
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


if AVAILABLE:
    _inline = numba.njit(cache=True, nogil=True)
    _rotate_row = _inline(_rotate_row)
    _unrotate_rows = _inline(_unrotate_rows)
    _gather = _inline(_gather)
    _scatter = _inline(_scatter)
    _jit = numba.njit(parallel=True, cache=True, nogil=True)
    _serial = numba.njit(cache=True, nogil=True)  # prange runs as range: no thread start-up and barrier
    _kernels = {
        name: (_serial(fn), _jit(fn))
        for name, fn in (("mixer", _mixer_impl), ("mixer_adjoint", _mixer_adjoint_impl), ("phase", _phase_impl),
                         ("phase_weights", _phase_weights_impl))
    }

PARALLEL_MIN = 1 << 16
"""Arrays smaller than this many amplitudes run single-threaded: on a busy machine a parallel region's barrier
can wait a whole scheduler time slice for its second thread, which costs more than the work."""


def _pick(name: str, size: int):  # type: ignore[no-untyped-def]
    return _kernels[name][size >= PARALLEL_MIN]


def mixer(x: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, s: complex, tile: int | None = None) -> None:
    """Apply the rotations ``(ii[k], jj[k])`` in order along axis 1 of ``x`` (shape ``(pre, n, post)``), in place.

    Args:
        x: complex128 C-contiguous array.
        ii, jj: The pairs, every plaquette's in turn (``intp``).
        c: ``cos(beta / 2)``.
        s: ``-1j * sin(beta / 2)`` (forward) or its conjugate (undo): a purely imaginary number.
        tile: Trailing columns per tile (default :data:`TILE`).
    """
    width = TILE if tile is None else int(tile)
    _pick("mixer", x.size)(_real_view(x), ii, jj, float(c), float(-complex(s).imag), width)


def mixer_adjoint(
    x: np.ndarray, y: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, s: complex, tile: int | None = None
) -> float:
    """Undo the rotations on ``x`` and ``y`` in reverse order; return ``sum_k Im <y|G_k|x>`` taken before each
    pair is undone (``G_k`` the pair's ``X``).

    Args:
        x, y: complex128 C-contiguous arrays of the same shape ``(pre, n, post)``.
        ii, jj, tile: As in :func:`mixer`.
        c: ``cos(beta / 2)``.
        s: ``+1j * sin(beta / 2)`` (the inverse rotation).
    """
    width = TILE if tile is None else int(tile)
    kernel = _pick("mixer_adjoint", x.size)
    return float(kernel(_real_view(x), _real_view(y), ii, jj, float(c), float(-complex(s).imag), width))


def phase(x: np.ndarray, levels: np.ndarray, table: np.ndarray) -> None:
    """``x *= table[levels]`` in place (``x`` complex128 and ``levels`` uint8/uint16, both C-contiguous, same
    number of elements)."""
    _pick("phase", x.size)(_real_view(x).reshape(-1), levels.reshape(-1), np.ascontiguousarray(table.real),
           np.ascontiguousarray(table.imag))


def phase_weights(x: np.ndarray, y: np.ndarray, levels: np.ndarray, num_levels: int) -> np.ndarray:
    """Per level ``l``: ``sum_{k: levels[k] = l} Im(conj(y_k) x_k)`` (float64, length ``num_levels``)."""
    kernel = _pick("phase_weights", x.size)
    return kernel(_real_view(x).reshape(-1), _real_view(y).reshape(-1), levels.reshape(-1), int(num_levels))


def _real_view(x: np.ndarray) -> np.ndarray:
    """The float64 view ``(pre, n, 2 post)`` of a C-contiguous complex128 ``(pre, n, post)`` array."""
    if x.dtype != np.complex128 or not x.flags.c_contiguous:
        raise ValueError("the kernels need a C-contiguous complex128 array")
    return x.view(np.float64)
