"""Numba kernels of the structure-preserving half-size spectrum (:mod:`fpucore.floquet.structured`).

Vectors of length 2N are ordered [strain or u block (N), velocity or p block (N)].  𝓜 is stored
by its periodic bands (:func:`extract_bands`); S = R⁺𝓜R, Sᵀ and W = S − J Sᵀ J are applied in
O(N·K).  (The Gram–Schmidt passes of the Arnoldi process are BLAS level-2 calls in the
driver: measured faster than any pure-loop kernel here, which cannot use SIMD reductions without
fastmath.)
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def extract_bands(mat: np.ndarray, n: int, d0: int, bands: np.ndarray) -> None:
    """bands[b, c, k] = block_b[(c + d0 + k) mod N, c] for the four N×N blocks of 𝓜
    (b = 0 yy, 1 yv, 2 vy, 3 vv).  mat : (2N, 2N); bands : (4, N, width)."""
    w = bands.shape[2]
    for b in range(4):
        ro = (b // 2) * n
        co = (b % 2) * n
        for c in range(n):
            for k in range(w):
                r = (c + d0 + k) % n
                bands[b, c, k] = mat[ro + r, co + c]


@njit(cache=True, nogil=True)
def band_mv(bands: np.ndarray, d0: int, n: int, x: np.ndarray, out: np.ndarray) -> None:
    """out = 𝓜 x from the periodic bands."""
    w = bands.shape[2]
    for i in range(2 * n):
        out[i] = 0.0
    for b in range(4):
        ro = (b // 2) * n
        co = (b % 2) * n
        for c in range(n):
            xc = x[co + c]
            if xc != 0.0:
                for k in range(w):
                    r = c + d0 + k
                    if r < 0:
                        r += n
                    elif r >= n:
                        r -= n
                    out[ro + r] += bands[b, c, k] * xc


@njit(cache=True, nogil=True)
def band_mtv(bands: np.ndarray, d0: int, n: int, x: np.ndarray, out: np.ndarray) -> None:
    """out = 𝓜ᵀ x from the periodic bands."""
    w = bands.shape[2]
    for i in range(2 * n):
        out[i] = 0.0
    for b in range(4):
        ro = (b // 2) * n
        co = (b % 2) * n
        for c in range(n):
            s = 0.0
            for k in range(w):
                r = c + d0 + k
                if r < 0:
                    r += n
                elif r >= n:
                    r -= n
                s += bands[b, c, k] * x[ro + r]
            out[co + c] += s


@njit(cache=True, nogil=True)
def remove_means(x: np.ndarray, n: int) -> None:
    """Subtract each N-block's mean (project onto the zero-sum subspace the deflation keeps)."""
    for blk in range(2):
        o = blk * n
        s = 0.0
        for i in range(n):
            s += x[o + i]
        s /= n
        for i in range(n):
            x[o + i] -= s


@njit(cache=True, nogil=True)
def r_apply(x: np.ndarray, n: int, out: np.ndarray) -> None:
    """out = R x = (D u, D p), (Du)_i = u_{i+1} − u_i on the ring."""
    for blk in range(2):
        o = blk * n
        for i in range(n):
            j = i + 1 if i + 1 < n else 0
            out[o + i] = x[o + j] - x[o + i]


@njit(cache=True, nogil=True)
def rt_apply(x: np.ndarray, n: int, out: np.ndarray) -> None:
    """out = Rᵀ x, (Dᵀz)_i = z_{i−1} − z_i."""
    for blk in range(2):
        o = blk * n
        for i in range(n):
            j = i - 1 if i > 0 else n - 1
            out[o + i] = x[o + j] - x[o + i]


@njit(cache=True, nogil=True)
def rpinv_apply(x: np.ndarray, n: int, out: np.ndarray) -> None:
    """out = R⁺ x: block mean removed from x, cumulative sum, block mean removed."""
    for blk in range(2):
        o = blk * n
        s = 0.0
        for i in range(n):
            s += x[o + i]
        s /= n
        acc = 0.0
        tot = 0.0
        for i in range(n):
            out[o + i] = acc
            tot += acc
            acc += x[o + i] - s
        tot /= n
        for i in range(n):
            out[o + i] -= tot


@njit(cache=True, nogil=True)
def rtpinv_apply(x: np.ndarray, n: int, out: np.ndarray) -> None:
    """out = (Rᵀ)⁺ x: block mean removed, u_0 = 0, u_i = u_{i−1} − z_i, block mean removed."""
    for blk in range(2):
        o = blk * n
        s = 0.0
        for i in range(n):
            s += x[o + i]
        s /= n
        acc = 0.0
        tot = 0.0
        out[o] = 0.0
        for i in range(1, n):
            acc -= x[o + i] - s
            out[o + i] = acc
            tot += acc
        tot /= n
        for i in range(n):
            out[o + i] -= tot


@njit(cache=True, nogil=True)
def j_apply(x: np.ndarray, n: int, out: np.ndarray) -> None:
    """out = J x, J(u, p) = (p, −u)."""
    for i in range(n):
        out[i] = x[n + i]
        out[n + i] = -x[i]


@njit(cache=True, nogil=True)
def s_apply(bands, d0, n, x, out, t1, t2) -> None:
    """out = S x = R⁺ 𝓜 R x (t1, t2: (2N,) work)."""
    r_apply(x, n, t1)
    band_mv(bands, d0, n, t1, t2)
    rpinv_apply(t2, n, out)


@njit(cache=True, nogil=True)
def st_apply(bands, d0, n, x, out, t1, t2) -> None:
    """out = Sᵀ x = Rᵀ 𝓜ᵀ (Rᵀ)⁺ x."""
    rtpinv_apply(x, n, t1)
    band_mtv(bands, d0, n, t1, t2)
    rt_apply(t2, n, out)


@njit(cache=True, nogil=True)
def w_apply(bands, d0, n, x, out, t1, t2, t3, t4) -> None:
    """out = W x = S x − J Sᵀ J x (= (S + S⁻¹) x for symplectic S), mean-free."""
    s_apply(bands, d0, n, x, out, t1, t2)
    j_apply(x, n, t3)
    st_apply(bands, d0, n, t3, t4, t1, t2)
    j_apply(t4, n, t3)
    for i in range(2 * n):
        out[i] -= t3[i]
    remove_means(out, n)
