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
phase separator multiplies each amplitude by its cost level's entry of a table, in parallel blocks, or inside a
mixer pass (``levels=``, ``table=``): the forward layer then applies the phase to each gathered tile before its
rotations, and the backward sweep takes the phase separator's per-level gradient weights and undoes it after
robot 0's un-rotations, so a layer costs one pass over memory less each way. Parallel work is cut into
``CHUNKS_PER_THREAD`` items per thread, each allocating its tile buffers once.

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


def _gather_levels(lev: np.ndarray, a: int, c0: int, c1: int, out: np.ndarray) -> None:
    """``out[col - c0, r]`` = ``lev[a, r, col]``: the cost levels of the gathered rows."""
    for r in range(lev.shape[1]):
        for col in range(c0, c1):
            out[col - c0, r] = lev[a, r, col]


def _phase_row(row: np.ndarray, lev: np.ndarray, tr: np.ndarray, ti: np.ndarray) -> None:
    """``row[k] *= t[lev[k]]`` on a float64 row ``[re_0, im_0, ...]`` (``t = tr + 1j ti``)."""
    for k in range(lev.shape[0]):
        a, d = tr[lev[k]], ti[lev[k]]
        u, v = row[2 * k], row[2 * k + 1]
        row[2 * k] = a * u - d * v
        row[2 * k + 1] = a * v + d * u


def _unphase_rows(
    xrow: np.ndarray, yrow: np.ndarray, lev: np.ndarray, tr: np.ndarray, ti: np.ndarray, weights: np.ndarray
) -> None:
    """Add ``Im(conj(y_k) x_k)`` to ``weights[lev[k]]``, then ``x_k, y_k *= t[lev[k]]`` (the adjoint phase step)."""
    for k in range(lev.shape[0]):
        lv = lev[k]
        u, v = xrow[2 * k], xrow[2 * k + 1]
        p, q = yrow[2 * k], yrow[2 * k + 1]
        weights[lv] += p * v - q * u
        a, d = tr[lv], ti[lv]
        xrow[2 * k] = a * u - d * v
        xrow[2 * k + 1] = a * v + d * u
        yrow[2 * k] = a * p - d * q
        yrow[2 * k + 1] = a * q + d * p


def _chunk_bounds(total: int, chunks: int, k: int) -> tuple[int, int]:
    return k * total // chunks, (k + 1) * total // chunks


def _mixer_impl(
    xr: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float, tile: int, chunks: int,
    lev: np.ndarray, tr: np.ndarray, ti: np.ndarray,
) -> None:
    """``xr``: the float64 view ``(pre, n, 2 post)``; rotation ``c`` and ``s = -1j * sg``. With a non-empty
    ``lev`` (same ``(pre, n, post)`` shape as the state) every amplitude is first multiplied by
    ``(tr + 1j ti)[lev]``: the phase separator, fused into the pass. ``chunks`` parallel work items each
    allocate their buffers once."""
    pre, n, post2 = xr.shape
    post = post2 // 2
    fuse = lev.size > 0
    if post == 1:  # the robot's axis is contiguous already
        for ch in numba.prange(chunks):
            a0, a1 = _chunk_bounds(pre, chunks, ch)
            for a in range(a0, a1):
                row = xr[a].reshape(2 * n)
                if fuse:
                    _phase_row(row, lev[a].reshape(n), tr, ti)
                _rotate_row(row, ii, jj, c, sg)
        return
    ntiles = (post + tile - 1) // tile
    for ch in numba.prange(chunks):
        t0, t1 = _chunk_bounds(pre * ntiles, chunks, ch)
        buf = np.empty((tile, 2 * n))
        lbuf = np.empty((tile if fuse else 0, n), dtype=lev.dtype)
        for t in range(t0, t1):
            a = t // ntiles
            c0 = (t % ntiles) * tile
            c1 = min(c0 + tile, post)
            _gather(xr, a, c0, c1, buf)
            if fuse:
                _gather_levels(lev, a, c0, c1, lbuf)
            for col in range(c1 - c0):
                if fuse:
                    _phase_row(buf[col], lbuf[col], tr, ti)
                _rotate_row(buf[col], ii, jj, c, sg)
            _scatter(buf, xr, a, c0, c1)


def _mixer_adjoint_impl(
    xr: np.ndarray, yr: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, sg: float, tile: int, chunks: int,
    lev: np.ndarray, tr: np.ndarray, ti: np.ndarray, nlev: int,
) -> tuple[float, np.ndarray]:
    """Float64 views as in :func:`_mixer_impl`; ``s = -1j * sg`` is the inverse rotation here. With a non-empty
    ``lev``, after the rotations each amplitude pair's ``Im(conj(y) x)`` is added to its level's weight and
    both are multiplied by ``(tr + 1j ti)[lev]`` (the phase separator's adjoint step, fused). Returns the
    rotations' ``sum Im <y|G|x>`` and the ``nlev`` level weights (zeros without ``lev``)."""
    pre, n, post2 = xr.shape
    post = post2 // 2
    fuse = lev.size > 0
    acc = np.zeros(chunks)
    part = np.zeros((chunks, nlev))
    if post == 1:
        for ch in numba.prange(chunks):
            a0, a1 = _chunk_bounds(pre, chunks, ch)
            z = 0.0
            for a in range(a0, a1):
                xrow, yrow = xr[a].reshape(2 * n), yr[a].reshape(2 * n)
                z += _unrotate_rows(xrow, yrow, ii, jj, c, sg)
                if fuse:
                    _unphase_rows(xrow, yrow, lev[a].reshape(n), tr, ti, part[ch])
            acc[ch] = z
        return acc.sum(), part.sum(axis=0)
    ntiles = (post + tile - 1) // tile
    for ch in numba.prange(chunks):
        t0, t1 = _chunk_bounds(pre * ntiles, chunks, ch)
        bx = np.empty((tile, 2 * n))
        by = np.empty((tile, 2 * n))
        lbuf = np.empty((tile if fuse else 0, n), dtype=lev.dtype)
        z = 0.0
        for t in range(t0, t1):
            a = t // ntiles
            c0 = (t % ntiles) * tile
            c1 = min(c0 + tile, post)
            _gather(xr, a, c0, c1, bx)
            _gather(yr, a, c0, c1, by)
            if fuse:
                _gather_levels(lev, a, c0, c1, lbuf)
            for col in range(c1 - c0):
                z += _unrotate_rows(bx[col], by[col], ii, jj, c, sg)
                if fuse:
                    _unphase_rows(bx[col], by[col], lbuf[col], tr, ti, part[ch])
            _scatter(bx, xr, a, c0, c1)
            _scatter(by, yr, a, c0, c1)
        acc[ch] = z
    return acc.sum(), part.sum(axis=0)


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
    _gather_levels = _inline(_gather_levels)
    _phase_row = _inline(_phase_row)
    _unphase_rows = _inline(_unphase_rows)
    _chunk_bounds = _inline(_chunk_bounds)
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

CHUNKS_PER_THREAD = 4
"""Parallel work items per thread in the mixer kernels (each allocates its tile buffers once); more than one
per thread so that a thread slowed by other load on the machine does not hold up the rest."""

_NO_LEVELS = np.zeros((0, 0, 0), dtype=np.uint8)
_NO_TABLE = np.zeros(0)


def _pick(name: str, size: int):  # type: ignore[no-untyped-def]
    return _kernels[name][size >= PARALLEL_MIN]


def _chunks_for(size: int) -> int:
    return CHUNKS_PER_THREAD * numba.get_num_threads() if size >= PARALLEL_MIN else 1


def _fused(
    x: np.ndarray, levels: np.ndarray | None, table: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Levels reshaped like ``x`` and the table's real and imaginary parts (empty when nothing is fused)."""
    if levels is None or table is None:
        return _NO_LEVELS, _NO_TABLE, _NO_TABLE
    if levels.size != x.size or not levels.flags.c_contiguous:
        raise ValueError("the fused levels must be C-contiguous with one level per amplitude")
    return levels.reshape(x.shape), np.ascontiguousarray(table.real), np.ascontiguousarray(table.imag)


def mixer(
    x: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, s: complex, tile: int | None = None,
    levels: np.ndarray | None = None, table: np.ndarray | None = None,
) -> None:
    """Apply the rotations ``(ii[k], jj[k])`` in order along axis 1 of ``x`` (shape ``(pre, n, post)``), in place.

    Args:
        x: complex128 C-contiguous array.
        ii, jj: The pairs, every plaquette's in turn (``intp``).
        c: ``cos(beta / 2)``.
        s: ``-1j * sin(beta / 2)`` (forward) or its conjugate (undo): a purely imaginary number.
        tile: Trailing columns per tile (default :data:`TILE`).
        levels, table: Optional phase separator fused into the same pass: before its rotations every
            amplitude is multiplied by ``table[levels]`` (``levels`` uint8/uint16, one per amplitude).
    """
    width = TILE if tile is None else int(tile)
    lev, tr, ti = _fused(x, levels, table)
    _pick("mixer", x.size)(_real_view(x), ii, jj, float(c), float(-complex(s).imag), width, _chunks_for(x.size),
                           lev, tr, ti)


def mixer_adjoint(
    x: np.ndarray, y: np.ndarray, ii: np.ndarray, jj: np.ndarray, c: float, s: complex, tile: int | None = None,
    levels: np.ndarray | None = None, table: np.ndarray | None = None, num_levels: int = 0,
) -> tuple[float, np.ndarray]:
    """Undo the rotations on ``x`` and ``y`` in reverse order, accumulating ``sum_k Im <y|G_k|x>`` taken before
    each pair is undone (``G_k`` the pair's ``X``); optionally then the adjoint phase step, fused.

    Args:
        x, y: complex128 C-contiguous arrays of the same shape ``(pre, n, post)``.
        ii, jj, tile: As in :func:`mixer`.
        c: ``cos(beta / 2)``.
        s: ``+1j * sin(beta / 2)`` (the inverse rotation).
        levels, table, num_levels: Optional fused phase step: after the rotations, every amplitude's
            ``Im(conj(y) x)`` is added to its level's weight, then ``x`` and ``y`` are multiplied by
            ``table[levels]`` (the inverse phase separator).

    Returns:
        ``(sum_k Im <y|G_k|x>, weights)``; ``weights`` has ``num_levels`` entries (all zero when nothing is
        fused), as :func:`phase_weights` of the arrays between the rotations and the phase step.
    """
    width = TILE if tile is None else int(tile)
    lev, tr, ti = _fused(x, levels, table)
    kernel = _pick("mixer_adjoint", x.size)
    z, weights = kernel(_real_view(x), _real_view(y), ii, jj, float(c), float(-complex(s).imag), width,
                        _chunks_for(x.size), lev, tr, ti, int(num_levels) if lev.size else 0)
    return float(z), weights


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
