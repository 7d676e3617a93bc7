"""Numba kernels of the monodromy construction (eq. linear_map) and the exact deflation of the
conservation block at μ = 1 (see :mod:`fpucore.floquet.monodromy`)."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def shift_rows(psi: np.ndarray, n: int, out: np.ndarray) -> None:
    """𝓜 from Ψ(T) (eq. linear_map): in each N-block of rows, row i ← row i+1, last ← first.

    psi, out : (2N, 2N) float64, rows/columns ordered [y_{−N/2} … y_{N/2−1}, ẏ_{−N/2} … ].
    """
    m = psi.shape[1]
    for blk in range(2):
        o = blk * n
        for i in range(n):
            src = o + (i + 1 if i + 1 < n else 0)
            for j in range(m):
                out[o + i, j] = psi[src, j]


@njit(cache=True, nogil=True)
def deflate_sums(a: np.ndarray, n: int, u: np.ndarray, beta: float) -> None:
    """In place a ← P a P with P = diag(H, H), H = I − β u uᵀ (Householder, symmetric, H² = I).

    H maps the normalised constant vector of an N-block onto that block's last coordinate, so
    after the transform index N−1 carries Σ y_n/√N and index 2N−1 carries Σ ẏ_n/√N.
    a : (2N, 2N) float64;  u : (N,) float64;  β = 2 / uᵀu.
    """
    m = 2 * n
    tmp = np.empty(m)
    # left: each row block B ← H B  (B − β u (uᵀ B))
    for blk in range(2):
        o = blk * n
        for j in range(m):
            tmp[j] = 0.0
        for i in range(n):
            ui = u[i]
            if ui != 0.0:
                for j in range(m):
                    tmp[j] += ui * a[o + i, j]
        for i in range(n):
            c = beta * u[i]
            if c != 0.0:
                for j in range(m):
                    a[o + i, j] -= c * tmp[j]
    # right: each column block C ← C H  (C − β (C u) uᵀ)
    for blk in range(2):
        o = blk * n
        for i in range(m):
            s = 0.0
            for j in range(n):
                s += a[i, o + j] * u[j]
            s *= beta
            for j in range(n):
                a[i, o + j] -= s * u[j]


@njit(cache=True, nogil=True)
def scatter_shifted(out: np.ndarray, cols: np.ndarray, n: int, k_half: int, mat: np.ndarray):
    """Place tangent window columns into 𝓜 with the index shift of eq. linear_map.

    out : (nc, 2, W) window columns from period_map.tangent_columns (periodic=True), window row k
    is site (c mod N) − K + k (mod N).  Ψ row s lands in 𝓜 row s − 1 (mod N) of its block, which
    is "rows up by one, last row replaced by the first".  mat : (2N, 2N), zero outside windows.
    """
    nc, _, w = out.shape
    for ci in range(nc):
        c = cols[ci]
        s0 = c % n - k_half
        for k in range(w):
            r = (s0 + k - 1) % n
            mat[r, c] = out[ci, 0, k]
            mat[n + r, c] = out[ci, 1, k]


@njit(cache=True, nogil=True)
def extract_deflated(a: np.ndarray, n: int, out: np.ndarray) -> float:
    """Copy the (2N−2) block of the deflated 𝓜 without rows/cols N−1, 2N−1 into out (F-order
    is fine) and return the largest |entry| of the two sum rows outside the 2×2 quotient block
    (exactly 0 for the ring: the conservation defect of the integration)."""
    m = 2 * n
    defect = 0.0
    for j in range(m):
        if j != n - 1 and j != m - 1:
            defect = max(defect, abs(a[n - 1, j]), abs(a[m - 1, j]))
    ii = 0
    for i in range(m):
        if i == n - 1 or i == m - 1:
            continue
        jj = 0
        for j in range(m):
            if j == n - 1 or j == m - 1:
                continue
            out[ii, jj] = a[i, j]
            jj += 1
        ii += 1
    return defect
