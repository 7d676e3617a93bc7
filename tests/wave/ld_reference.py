"""A reference traveling wave more accurate than double precision (tests/wave/test_error_bounds).

Route, independent of the solver's stopping rules and error estimates: the same equations
(eq. nonlin_system, :class:`fpucore.wave.system.WaveSystem` row order) on a longer chain N_ref,
with the period map integrated in 80-bit long double (numpy ``longdouble``, eps ≈ 1.1e-19) with
``m_ref`` DOP853 steps, solved by iterative refinement: x ← x − J⁻¹F_ld(x), J the double-precision
exact Jacobian (a chord: it converges linearly with rate ≈ ‖I − J⁻¹J_exact‖ ≈ 1e-12).  Its own
accuracy is established by :func:`reference_spread`: two such references that differ in N_ref
and m_ref agree to the level the tests then require of it.

Only the cubic law is written here (f = a w³ + b w² + w, eq. cubic).
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lapack

from fpucore import wave
from fpucore.tableaux import DOP853
from fpucore.wave.system import newton

LD = np.longdouble
DEBUG = False
_A = DOP853.A.astype(LD)
_B = DOP853.B.astype(LD)


def _f(law, w):
    a, b = LD(law.a), LD(law.b)
    return ((a * w + b) * w + 1) * w


def period_ld(law, w0, wd0, V, m, w_left, w_right):
    """One period T = 1/V of eq. FPUstrain in long double, fixed boundary strains."""
    T = LD(1) / LD(V)
    h = T / m
    w, wd = w0.astype(LD), wd0.astype(LD)
    s = _B.size
    fl, fr = _f(law, LD(w_left)), _f(law, LD(w_right))
    kw = [None] * s
    kwd = [None] * s
    for _ in range(m):
        for i in range(s):
            yw, ywd = w.copy(), wd.copy()
            for j in range(i):
                if _A[i, j] != 0:
                    yw += _A[i, j] * h * kw[j]
                    ywd += _A[i, j] * h * kwd[j]
            g = np.concatenate([[fl], _f(law, yw), [fr]])
            kw[i] = ywd
            kwd[i] = g[2:] - 2 * g[1:-1] + g[:-2]
        for i in range(s):
            w = w + _B[i] * h * kw[i]
            wd = wd + _B[i] * h * kwd[i]
    return w, wd


def residual_ld(S, x, m):
    """F(x) of eq. nonlin_system in long double, rows ordered as in ``S`` (a WaveSystem)."""
    N = S.N
    w, wd = x[0::2], x[1::2]
    rw, rwd = period_ld(S.law, w, wd, S.V, m, S.w_left, S.w_right)
    F = np.empty(2 * N, dtype=LD)
    F[S.row_w[: N - 1]] = rw[1:] - w[:-1]
    F[S.row_w[N - 1]] = LD(S.w_right) - w[N - 1]
    F[S.row_wd] = rwd[1:] - wd[:-1]
    F[S.row_pin] = (rw[S.i_pin] - LD(S.pin_value)) if S.pin == "w" else rwd[S.i_pin]
    return F


def spec_of(law, kind, V, w_plus=None, branch="lower"):
    if kind == "superkink":
        return wave.superkink_spec(law, V, branch)
    return wave.solitary_spec(law, w_plus, V)


def reference(law, spec, N_ref, m_ref, x_start=None, N_start=None, iters=12, refresh=False):
    """(x_ref as long double (2N_ref,), last correction size): the refined reference wave."""
    scale = max(1.0, abs(spec.w_left), abs(spec.w_right))
    if x_start is None:
        x0 = wave.qc_guess(spec, N_ref)
    else:
        x0 = wave.resize(x_start, N_start, N_ref, spec.w_left, spec.w_right)
    m_d = min(m_ref, 128)
    K = wave.choose_K(law, spec, x0, m_d)
    S = wave.build_system(law, spec, N_ref, m_d, K)
    o = newton(S, x0, 1e-13 * scale, 60, "exact", 120.0)
    x = o.x.astype(LD)
    ab, kl, ku, _, _, _ = S.jacobian_banded(o.x)
    lu, piv, info = lapack.dgbtrf(ab, kl, ku)
    assert info == 0
    last = np.inf
    for it in range(iters):
        if it and refresh:  # Newton, not chord: near-singular J (flat tops) needs the current J
            ab, kl, ku, _, _, _ = S.jacobian_banded(x.astype(float))
            lu, piv, info = lapack.dgbtrf(ab, kl, ku)
        F = residual_ld(S, x, m_ref)
        # scale F up so the double solve keeps its relative precision at tiny residuals
        s = float(np.max(np.abs(F))) or 1.0
        dx, _ = lapack.dgbtrs(lu, kl, ku, (F / LD(s)).astype(float).reshape(-1, 1), piv)
        dx = dx[:, 0].astype(LD) * LD(s)
        x = x - dx
        step = float(max(np.max(np.abs(dx[0::2])), np.max(np.abs(dx[1::2])) / S.V))
        if DEBUG:
            print("ref step", step, float(np.max(np.abs(F))))
        if step >= 0.5 * last and step < 1e-15 * scale:
            last = step
            break
        last = step
    return x, last


def on_sites(x_ref, N_ref, N):
    """The reference strains w_n(0) on the N sites −N/2 … N/2−1 of a shorter chain (float64)."""
    w = np.asarray(x_ref[0::2])
    off = N_ref // 2 - N // 2
    return w[off : off + N]
