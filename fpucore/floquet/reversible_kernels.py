"""Numba kernels of the reversible half-size spectrum (:mod:`fpucore.floquet.reversible`).

The basis Q = [Q₊, J Q₊] of the two eigenspaces of the reversor is a signed pairing: column k is
``ca[k]·e[blk[k]·N + ia[k]] + cb[k]·e[blk[k]·N + ib[k]]`` (cb = 0 for a fixed point), so
Qᵀ S Q = Qᵀ R⁺ 𝓜 R Q costs three streaming passes over (2N)² arrays instead of a dense product.
"""

from __future__ import annotations

from numba import njit
from numba.extending import register_jitable


@njit(cache=True, nogil=True)
def m_times_rq(mat, n, blk, ia, ib, ca, cb, out) -> None:
    """out = 𝓜 R Q, (2N, 2N): R Q's column k is ca (e_{ia−1} − e_{ia}) + cb (e_{ib−1} − e_{ib})
    in block blk (R = diag(D, D), (Du)_i = u_{i+1} − u_i), so out[:, k] combines four columns of
    𝓜; done row by row, as each row of 𝓜 is contiguous."""
    m2 = 2 * n
    for r in range(m2):
        row = mat[r]
        o = out[r]
        for k in range(m2):
            b = blk[k] * n
            i, j = ia[k], ib[k]
            i1 = i - 1 if i > 0 else n - 1
            j1 = j - 1 if j > 0 else n - 1
            o[k] = ca[k] * (row[b + i1] - row[b + i]) + cb[k] * (row[b + j1] - row[b + j])


@register_jitable
def block_column_means(y, o, n, mean) -> None:
    """mean[k] = the mean of y[o : o + n, k] (one N-block of every column), row by row; a helper
    compiled into the kernels that call it (register_jitable: no dispatcher of its own)."""
    m2 = y.shape[1]
    for k in range(m2):
        mean[k] = 0.0
    for r in range(n):
        yr = y[o + r]
        for k in range(m2):
            mean[k] += yr[k]
    for k in range(m2):
        mean[k] /= n


@njit(cache=True, nogil=True)
def rpinv_rows(y, n, mean, run) -> None:
    """y ← R⁺ y column-wise, in place (R⁺: block mean removed, exclusive cumulative sum, block
    mean removed; :func:`fpucore.floquet.structured_kernels.rpinv_apply` on every column), row by
    row so that every access is contiguous.  mean, run : (2N,) work."""
    m2 = y.shape[1]
    for blk in range(2):
        o = blk * n
        block_column_means(y, o, n, mean)
        for k in range(m2):
            run[k] = 0.0
        for r in range(n):  # out_r = Σ_{l<r} (y_l − mean)
            yr = y[o + r]
            for k in range(m2):
                v = yr[k] - mean[k]
                yr[k] = run[k]
                run[k] += v
        block_column_means(y, o, n, mean)
        for r in range(n):
            yr = y[o + r]
            for k in range(m2):
                yr[k] -= mean[k]


@njit(cache=True, nogil=True)
def qt_times(y, n, blk, ia, ib, ca, cb, out) -> None:
    """out = Qᵀ y, (2N, 2N): row k is ca·y[blk·N + ia] + cb·y[blk·N + ib]."""
    m2 = 2 * n
    for k in range(m2):
        b = blk[k] * n
        ri = y[b + ia[k]]
        rj = y[b + ib[k]]
        a, c = ca[k], cb[k]
        o = out[k]
        for col in range(m2):
            o[col] = a * ri[col] + c * rj[col]
