"""The substituted profile map ξ(s) of the general-law QC (paper §3, :mod:`fpucore.qc.general`):
ξ tabulated by composite Gauss–Legendre on Chebyshev panels, inverted by safeguarded Newton."""

from __future__ import annotations

import bisect
import functools
from collections.abc import Callable

import numpy as np

from fpucore.qc.general_roots import (
    EPS,
    GL_HI,
    GL_LO,
    K_INV,
    gauss_legendre01,
)


# =============================================================================== ξ(s) tables
@functools.cache
def _cheb_tables(K: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Chebyshev–Lobatto points t on [0, 1], their barycentric weights, and the matrix S with
    ∫₀^{t_k} p = Σ_m S[k, m] p(t_m) for the interpolant p of degree K − 1 (spectral integration)."""
    k = np.arange(K)
    t = 0.5 * (1.0 - np.cos(np.pi * k / (K - 1)))
    bw = (-1.0) ** k
    bw[0] *= 0.5
    bw[-1] *= 0.5
    S = np.empty((K, K))
    for m in range(K):  # integrate the m-th Lagrange basis polynomial
        c = np.polynomial.chebyshev.chebfit(2 * t - 1, np.eye(K)[m], K - 1)
        ci = np.polynomial.chebyshev.chebint(c, lbnd=-1)
        S[:, m] = 0.5 * np.polynomial.chebyshev.chebval(2 * t - 1, ci)
    for a in (t, bw, S):
        a.flags.writeable = False
    return t, bw, S


class ProfileMap:
    """ξ(s) = scale ∫₀ˢ g for s on the panel edges ``e`` (0 first, increasing |s|), for a smooth
    g > 0 that is constant beyond the last edge; vectorised inversion s(ξ).

    Edges: composite Gauss–Legendre (``GL_HI`` nodes; ``GL_LO`` for the error bar).  Inversion:
    on each panel, g at ``K_INV`` Chebyshev–Lobatto points is integrated spectrally to ξ at those
    points (the end value checked against the Gauss–Legendre edge: the difference enters ``err``),
    and s(ξ) is interpolated through them (barycentric, in ξ).  The inverse-interpolation error is
    measured halfway between the nodes and also enters ``err``; where either exceeds round-off,
    s_of polishes by Newton on the quadrature.  Built on first use (families need only the edges).
    """

    def __init__(self, g: Callable[[np.ndarray], np.ndarray], scale: float, edges: np.ndarray):
        self.g, self.scale, self.e = g, scale, edges
        xh, wh = gauss_legendre01(GL_HI)
        xl, wl = gauss_legendre01(GL_LO)
        a, b = edges[:-1], edges[1:]
        h = (b - a)[:, None]
        hi = np.sum(g(a[:, None] + h * xh) * wh * h, axis=1)
        lo = np.sum(g(a[:, None] + h * xl) * wl * h, axis=1)
        self.C = np.concatenate([[0.0], np.cumsum(hi)]) * scale
        self.quad_err = float(np.sum(np.abs(hi - lo)) * scale + 8 * EPS * abs(self.C[-1]))
        self.slope_end = scale * float(g(np.array([edges[-1]]))[0])
        self._xh, self._wh = xh, wh
        self._inv = None

    @property
    def err(self) -> float:
        """Error bar of ξ(s) (quadrature, plus the inverse tables' error once they are built)."""
        return self.quad_err + (self._inv[4] if self._inv is not None else 0.0)

    def table_err(self) -> float:
        """:attr:`err` with the inverse tables built (profiles are about to be evaluated)."""
        self._tables()
        return self.err

    def _tables(self):
        """(s nodes (P, K), ξ nodes, barycentric weights in ξ, polish?, table error)."""
        if self._inv is not None:
            return self._inv
        t, bw_s, S = _cheb_tables(K_INV)
        a, b = self.e[:-1], self.e[1:]
        h = (b - a)[:, None]
        sn = a[:, None] + h * t
        sn[:, -1] = b
        xn = self.C[:-1, None] + self.scale * h * (self.g(sn) @ S.T)
        end_err = float(np.max(np.abs(xn[:, -1] - self.C[1:])))
        xn[:, 0], xn[:, -1] = self.C[:-1], self.C[1:]
        span = xn[:, -1:] - xn[:, :1]
        u = (xn - xn[:, :1]) / span
        d = u[:, :, None] - u[:, None, :]
        k = np.arange(K_INV)
        d[:, k, k] = 1.0
        bw = 1.0 / np.prod(d, axis=2)
        # halfway points: ξ there from the forward interpolant (Chebyshev in s), s back from the
        # inverse interpolant; |Δs| · slope is the table's error in ξ
        sm = 0.5 * (sn[:, 1:] + sn[:, :-1])
        tm = (sm - a[:, None]) / h
        q = bw_s / (tm[:, :, None] - t)
        xim = np.sum(q * xn[:, None, :], axis=2) / np.sum(q, axis=2)
        self._inv = (sn, xn, bw, False, 0.0)
        jm = np.repeat(np.arange(a.size), K_INV - 1)
        ds = np.abs(self._interp(jm, xim.ravel()) - sm.ravel())
        slope = (np.diff(xn, axis=1) / np.diff(sn, axis=1)).ravel()
        tab_err = float(np.max(ds * slope)) + end_err
        polish = bool(tab_err > 64 * EPS * max(1.0, abs(self.C[-1])))
        self._inv = (sn, xn, bw, polish, tab_err)
        return self._inv

    @functools.cached_property
    def _py(self):
        """The inverse tables as Python lists, for :meth:`s_of_scalar`."""
        sn, xn, bw, _, _ = self._tables()
        u = (xn - xn[:, :1]) / (xn[:, -1:] - xn[:, :1])
        return self.C.tolist(), sn.tolist(), xn.tolist(), u.tolist(), bw.tolist()

    def s_of_scalar(self, x: float) -> float:
        """:meth:`s_of` for one ξ ≥ 0 in pure Python (tails and bisections call it thousands
        of times; NumPy's per-call overhead was 0.1 ms)."""
        if x >= self.C[-1] or self._tables()[3]:  # tail, or tables needing the Newton polish
            return float(self.s_of(np.array([x]))[0])
        Cl, sn, xn, un, bw = self._py
        j = min(max(bisect.bisect_right(Cl, x) - 1, 0), len(Cl) - 2)
        xj, sj, uj, bj = xn[j], sn[j], un[j], bw[j]
        u = (x - xj[0]) / (xj[-1] - xj[0])
        num = den = 0.0
        for uk, sk, bk in zip(uj, sj, bj):
            d = u - uk
            if d == 0.0:
                return sk
            q = bk / d
            num += q * sk
            den += q
        return min(max(num / den, sj[0]), sj[-1])

    def _xi(self, j: np.ndarray, s: np.ndarray) -> np.ndarray:
        """ξ(s) for s in panel j: C[j] + scale ∫_{e[j]}^{s} g (Gauss–Legendre, ``GL_HI`` nodes)."""
        a = self.e[j]
        h = (s - a)[:, None]
        return self.C[j] + self.scale * np.sum(self.g(a[:, None] + h * self._xh) * self._wh * h, 1)

    def _interp(self, j: np.ndarray, x: np.ndarray) -> np.ndarray:
        """Barycentric interpolation of s(ξ) on panel j (second form; exact at the nodes)."""
        sn, xn, bw = self._inv[0][j], self._inv[1][j], self._inv[2][j]  # type: ignore[index]
        span = xn[:, -1] - xn[:, 0]
        d = ((x - xn[:, 0]) / span)[:, None] - (xn - xn[:, :1]) / span[:, None]
        hit = d == 0.0
        q = bw / np.where(hit, 1.0, d)
        s = np.sum(q * sn, axis=1) / np.sum(q, axis=1)
        exact = hit.any(axis=1)
        if exact.any():
            s[exact] = sn[exact][hit[exact]]
        return s

    def s_of(self, xi: np.ndarray) -> np.ndarray:
        """Invert ξ(s) for ξ ≥ 0 (tail beyond the table: linear, g constant there)."""
        C, e = self.C, self.e
        xi = np.asarray(xi, float)
        shape = xi.shape
        xi = xi.ravel()
        out = np.empty_like(xi)
        tail = xi >= C[-1]
        out[tail] = e[-1] + (xi[tail] - C[-1]) / self.slope_end
        if tail.all():
            return out.reshape(shape)
        polish = self._tables()[3]
        x = xi[~tail]
        j = np.clip(np.searchsorted(C, x, side="right") - 1, 0, len(e) - 2)
        a, b = e[j], e[j + 1]
        s = np.clip(self._interp(j, x), a, b)
        for _ in range(40 if polish else 0):  # Newton on ξ(s) − x inside the panel
            F = self._xi(j, s) - x
            s_new = np.clip(s - F / (self.scale * self.g(s)), a, b)
            done = np.abs(s_new - s) <= 4 * EPS * (1.0 + np.abs(s))
            s = s_new
            if np.all(done):
                break
        out[~tail] = s
        return out.reshape(shape)


def sech_squared(x):
    """sech² x = 4e/(1+e)², e = exp(−2|x|) (no overflow)."""
    E = np.exp(-2.0 * np.abs(x))
    return 4.0 * E / (1.0 + E) ** 2
