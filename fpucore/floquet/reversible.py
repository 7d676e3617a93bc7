"""Quarter-size Floquet spectrum of a reversible traveling wave (the first choice of
``spectrum(r, method="structured")``).

A wave whose profile has a centre of reflection — every solitary wave (w even about its peak),
the cubic law's superkinks (f′(w) even about the inflection point w* = −b/3a, and w₋ + w₊ = 2w*)
— is carried into itself by ρ: site i → c − i together with t → −t.  For its shifted monodromy
this is a *reversor*: ρ 𝓜 ρ = 𝓜⁻¹, with ρ an involution, in canonical coordinates
(u, p) → (−P u, P p), (P u)_i = u_{c+1−i} (the displacements' reflection; strains y = D u map as
y_i → y_{c−i}).  ρ is anti-symplectic, so its two eigenspaces E₊, E₋ = J E₊ are Lagrangian and

    Qᵀ W Q = [[A, G], [F, Aᵀ]],   A = S₁₁ + S₂₂ᵀ,   G = S₁₂ − S₁₂ᵀ,   F = S₂₁ − S₂₁ᵀ,

for W = S − J Sᵀ J (= S + S⁻¹, the structured route's skew-Hamiltonian matrix, module
:mod:`fpucore.floquet.structured`), Q = [Q₊, J Q₊] and Ŝ = Qᵀ S Q in blocks S_ij.  For an exactly
reversible 𝓜, W commutes with ρ and G = F = 0: every λ = μ + 1/μ is an eigenvalue of the
(N−1)×(N−1) matrix A (once) — one dense eigenvalue call of half the half size, ~1/8 of the
flops of ``dgeev`` on the deflated (2N−2)² block.

Why A and not just S₁₁.  The computed 𝓜 is symplectic to round-off (η ~ 1e-14) but reversible
only to the base wave's accuracy (measured ‖ρ𝓜ρ − 𝓜⁻¹‖ ~ 3e-11 at N = 500); S₁₁ alone would be
the compression of 𝓜 + ρ𝓜ρ and carry that error at first order.  A uses Sᵀ, i.e. the symplectic
inverse; G and F are skew, so xᵀGx = 0 for every eigenvector and their effect on λ is second order:
|δλ_k| ≲ ‖G‖‖F‖ / d_k, d_k the distance to the nearest other λ.

Error bar per λ_k:  δλ_k = (64ε + η) ‖A‖_F + ‖G‖_F ‖F‖_F / max(d_k, ‖G‖_F + ‖F‖_F), with η the
measured non-symplecticity of Ŝ (random probes); per multiplier δλ_k / max(|μ − 1/μ|, √δλ_k) as
in the structured route.  A wave that is not reversible about the proposed centre (‖G‖ + ‖F‖
above 1e-8 ‖A‖) is refused here (None) and goes to the isotropic Arnoldi route.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING

import numpy as np
import scipy.linalg

from fpucore.floquet.reversible_kernels import m_times_rq, qt_times, rpinv_rows

if TYPE_CHECKING:
    from fpucore.law.base import HardeningSofteningLaw

_REVERSIBLE_TOL = 1e-8  # (‖G‖_F + ‖F‖_F) / ‖A‖_F above this: not reversible about c
_PROFILE_TOL = 1e-7  # relative asymmetry of the base profile accepted as a candidate centre


def reversor_of(law: HardeningSofteningLaw, w: np.ndarray, wd: np.ndarray) -> int | None:
    """The centre c of a reflection i → c − i (mod N) that, with time reversed, carries the
    linearized chain into itself; None if there is none.  The linearization sees the base state
    only through g = f′(w) and its rate h = f″(w) ẇ, so the test is g_i = g_{c−i} and
    h_i = −h_{c−i} to 1e-7 relative (a solitary wave: w even, ẇ odd; a cubic superkink: w odd
    about w*, ẇ even, f″ odd about w*).  Found by circular autocorrelation (FFT), then checked
    entry by entry; the matrix route re-checks it on 𝓜 itself (‖G‖ + ‖F‖).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w) (f′ and f″ are evaluated).
    w : array_like, shape (N,)
        Strains of the base wave at t = 0.
    wd : array_like, shape (N,)
        Strain rates ẇ of the base wave at t = 0, per unit time.

    Returns
    -------
    int or None
        The centre c (a site index in [0, N)), or None when the base state has no reversor.
    """
    w = np.asarray(w, dtype=float)
    g = np.asarray(law.df(w), dtype=float)
    h = np.asarray(law.ddf(w), dtype=float) * np.asarray(wd, dtype=float)
    n = g.size
    g0 = g - g.mean()
    sg, sh = float(g0 @ g0), float(h @ h)
    score = np.zeros(n)
    if sg > 0:
        f = np.fft.rfft(g0)
        score += np.fft.irfft(f * f, n) / sg  # Σ_i g_i g_{c−i} / Σ g², 1 when symmetric
    if sh > 0:
        f = np.fft.rfft(h)
        score -= np.fft.irfft(f * f, n) / sh  # h odd: Σ h_i h_{c−i} = −Σ h²
    c = int(np.argmax(score))
    idx = (c - np.arange(n)) % n
    if np.abs(g - g[idx]).max() > _PROFILE_TOL * max(float(np.abs(g).max()), 1e-300):
        return None
    if sh > 0 and np.abs(h + h[idx]).max() > _PROFILE_TOL * float(np.abs(h).max()):
        return None
    return c


def pairing_basis(n: int, c: int):
    """Q = [Q₊, J Q₊] (module doc) as signed pairs: (blk, ia, ib, ca, cb) of length 2N, and v (N,)
    the unit constant-p direction in Q₊ coordinates (= the constant-u direction in J Q₊'s).
    Q₊: u odd under P (pairs (e_i − e_{Pi})/√2), then p even under P (pairs (e_i + e_{Pi})/√2 and
    the fixed points e_i); P i = (c + 1 − i) mod N."""
    i = np.arange(n)
    pi = (c + 1 - i) % n
    lo = i < pi
    pa, pb = i[lo], pi[lo]
    fx = i[i == pi]
    h = 1.0 / math.sqrt(2.0)
    n_pair, n_fix = pa.size, fx.size
    # Q₊: u odd (block 0), p even (block 1)
    blk_p = np.concatenate([np.zeros(n_pair), np.ones(n_pair + n_fix)]).astype(np.int64)
    ia_p = np.concatenate([pa, pa, fx]).astype(np.int64)
    ib_p = np.concatenate([pb, pb, fx]).astype(np.int64)
    ca_p = np.concatenate([np.full(n_pair, h), np.full(n_pair, h), np.ones(n_fix)])
    cb_p = np.concatenate([np.full(n_pair, -h), np.full(n_pair, h), np.zeros(n_fix)])
    # J Q₊ with J(u, p) = (p, −u): u odd → p block with signs flipped; p even → u block
    blk = np.concatenate([blk_p, 1 - blk_p])
    ia = np.concatenate([ia_p, ia_p])
    ib = np.concatenate([ib_p, ib_p])
    flip = np.where(blk_p == 0, -1.0, 1.0)
    ca = np.concatenate([ca_p, flip * ca_p])
    cb = np.concatenate([cb_p, flip * cb_p])
    v = np.where(blk_p == 1, ca_p + cb_p, 0.0)
    return blk, ia, ib, ca, cb, v / np.linalg.norm(v)


def _householder_drop(a: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, float]:
    """(H a H)[:-1, :-1] with H the reflection mapping v onto ±e_last (A v = 0 = vᵀA: an exact
    zero eigenvalue dropped), and the largest entry of the dropped row and column."""
    u = v.copy()
    u[-1] += math.copysign(1.0, v[-1]) if v[-1] != 0 else 1.0
    u /= np.linalg.norm(u)
    a = a - 2.0 * np.outer(u, u @ a)
    a -= 2.0 * np.outer(a @ u, u)
    dropped = max(float(np.abs(a[-1]).max()), float(np.abs(a[:, -1]).max()))
    return np.asfortranarray(a[:-1, :-1]), dropped


def _symplectic_defect(s_hat: np.ndarray, v: np.ndarray, probes: int = 4, seed: int = 7) -> float:
    """η = max over random probes x (mean directions removed) of ‖x + Ŝ J₂ Ŝᵀ J₂ x‖/‖x‖,
    J₂(a, b) = (−b, a) (= Qᵀ J Q)."""
    n = v.size
    rng = np.random.default_rng(seed)
    worst = 0.0
    j2 = lambda x: np.concatenate([-x[n:], x[:n]])  # noqa: E731
    for _ in range(probes):
        x = rng.standard_normal(2 * n)
        x[:n] -= (v @ x[:n]) * v
        x[n:] -= (v @ x[n:]) * v
        y = x + s_hat @ j2(s_hat.T @ j2(x))
        worst = max(worst, float(np.linalg.norm(y) / np.linalg.norm(x)))
    return worst


def reversible_lambdas(
    mat: np.ndarray, n: int, c: int
) -> tuple[np.ndarray, np.ndarray, dict] | None:
    """λ = μ + 1/μ (N−1,) and their bounds δλ (N−1,) from the (N−1)² matrix A (module doc), and
    info (irreversibility ‖G‖_F + ‖F‖_F, symplectic_defect η, A_norm, wall times); None when 𝓜
    is not reversible about c.  mat : the full (2N, 2N) shifted monodromy."""
    t0 = time.perf_counter()
    N = int(n)
    blk, ia, ib, ca, cb, v = pairing_basis(N, int(c))
    mat = np.ascontiguousarray(mat, dtype=np.float64)
    y = np.empty((2 * N, 2 * N))
    m_times_rq(mat, N, blk, ia, ib, ca, cb, y)
    rpinv_rows(y, N, np.empty(2 * N), np.empty(2 * N))
    s_hat = np.empty((2 * N, 2 * N))
    qt_times(y, N, blk, ia, ib, ca, cb, s_hat)
    s11, s12, s21, s22 = s_hat[:N, :N], s_hat[:N, N:], s_hat[N:, :N], s_hat[N:, N:]
    g = float(np.linalg.norm(s12 - s12.T))
    f = float(np.linalg.norm(s21 - s21.T))
    a_full = s11 + s22.T
    a_norm = float(np.linalg.norm(a_full))
    if not (g + f <= _REVERSIBLE_TOL * a_norm):
        return None
    a, dropped = _householder_drop(a_full, v)
    t1 = time.perf_counter()
    lam = scipy.linalg.eigvals(a, overwrite_a=True, check_finite=False)
    t2 = time.perf_counter()
    eta = _symplectic_defect(s_hat, v)
    # distance of each λ to the nearest other one (second-order effect of G, F)
    d = np.abs(lam[:, None] - lam[None, :])
    np.fill_diagonal(d, np.inf)
    dk = d.min(axis=1) if lam.size > 1 else np.full(lam.size, np.inf)
    lam_err = np.full(lam.size, (64.0 * np.finfo(float).eps + eta) * a_norm + dropped)
    if g * f > 0:
        lam_err += g * f / np.maximum(dk, g + f)
    info = {
        "irreversibility": g + f,
        "symplectic_defect": eta,
        "A_norm": a_norm,
        "reduce_s": t1 - t0,
        "eig_s": t2 - t1,
    }
    return lam, lam_err, info
