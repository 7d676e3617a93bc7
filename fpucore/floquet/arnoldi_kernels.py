"""Numba kernels of the isotropic Arnoldi process of the half-size route
(:mod:`fpucore.floquet.structured`): Gram–Schmidt with delayed reorthogonalisation (DCGS2).

Why this shape.  At N = 500 the Krylov basis V (up to 499 × 1000 doubles, 4 MB) no longer fits
in one core's L2 cache, so each sweep over V is bound by memory bandwidth: classical Gram–Schmidt
twice (CGS2) reads V four times per step (coefficients, update, twice).  DCGS2 (Bielich,
Langou, Thomas, Świrydowicz, Yamazaki & Boman, Parallel Computing 112, 2022) reads it twice:
one sweep computes the coefficients of the new vector w = W u *and* the reorthogonalisation
coefficients of u (the previous step's once-projected vector), one sweep updates both.  The
second-pass corrections of H's previous column and the change of basis u → v_k in H's new
column are recovered from those coefficients with the Arnoldi relation (O(k) per step, one read
of H).  For the isotropic (skew-Hamiltonian) process every vector is projected against V *and*
J V, so each sweep carries four inner products (V·x, (JV)·x for x = u, w).

Layout: vectors of length 2N = [u block (N), p block (N)], J (u, p) = (p, −u); V (m, 2N) one
basis vector per row; H and G are stored transposed, HT[j, i] = H[i, j] (column j of H is row j
of HT, contiguous), so HT.T is H in Fortran order for LAPACK without a copy.

``fastmath`` is limited to {"reassoc", "contract"} on the inner-product sweeps (reassociation
lets LLVM vectorise the sums: 1.3× faster per sweep) and to {"contract"} (fused multiply-add) on
the updates (measured 1.2× faster); no "nnan"/"ninf", so non-finite values still propagate and
are caught by the callers' isfinite checks.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from fpucore.floquet.structured_kernels import j_apply, remove_means, w_apply

_SUM = {"reassoc", "contract"}
_FMA = {"contract"}


@njit(fastmath=_SUM, cache=True, nogil=True)
def coefficients(V: np.ndarray, k: int, x0: np.ndarray, x1: np.ndarray, n: int, c: np.ndarray):
    """c[i] = (V_i·x0, (J V_i)·x0, V_i·x1, (J V_i)·x1) for i < k; one read of V[:k] (two rows
    per pass share the loads of x0, x1).  c : (≥k, 4) out.
    Rows are visited from the last down: the update sweep (:func:`project_out`) runs upwards, so
    each sweep starts on the rows the previous one left in cache (measured 8–10 % faster when V
    outgrows L2)."""
    i = k - 2
    while i >= 0:
        vi = V[i]
        wi = V[i + 1]
        s0 = s1 = s2 = s3 = 0.0
        t0 = t1 = t2 = t3 = 0.0
        for j in range(n):
            a, b, e, f = vi[j], vi[n + j], wi[j], wi[n + j]
            u0, u1, y0, y1 = x0[j], x0[n + j], x1[j], x1[n + j]
            s0 += a * u0 + b * u1
            s1 += b * u0 - a * u1
            s2 += a * y0 + b * y1
            s3 += b * y0 - a * y1
            t0 += e * u0 + f * u1
            t1 += f * u0 - e * u1
            t2 += e * y0 + f * y1
            t3 += f * y0 - e * y1
        c[i, 0], c[i, 1], c[i, 2], c[i, 3] = s0, s1, s2, s3
        c[i + 1, 0], c[i + 1, 1], c[i + 1, 2], c[i + 1, 3] = t0, t1, t2, t3
        i -= 2
    if k % 2 == 1:
        i = 0
        vi = V[i]
        s0 = s1 = s2 = s3 = 0.0
        for j in range(n):
            a, b = vi[j], vi[n + j]
            s0 += a * x0[j] + b * x0[n + j]
            s1 += b * x0[j] - a * x0[n + j]
            s2 += a * x1[j] + b * x1[n + j]
            s3 += b * x1[j] - a * x1[n + j]
        c[i, 0], c[i, 1], c[i, 2], c[i, 3] = s0, s1, s2, s3


@njit(fastmath=_SUM, cache=True, nogil=True)
def step_sums(u: np.ndarray, w: np.ndarray, n: int) -> tuple[float, float, float, float]:
    """(w·w, u·u, u·w, (J u)·w) in one vectorised pass."""
    ww = uu = uw = juw = 0.0
    for j in range(n):
        a, b, x, y = u[j], u[n + j], w[j], w[n + j]
        ww += x * x + y * y
        uu += a * a + b * b
        uw += a * x + b * y
        juw += b * x - a * y
    return ww, uu, uw, juw


@njit(fastmath=_FMA, cache=True, nogil=True)
def project_out(V: np.ndarray, k: int, c: np.ndarray, n: int, x0: np.ndarray, x1: np.ndarray):
    """x0 −= Σ_i c[i,0] V_i + c[i,1] J V_i ;  x1 −= Σ_i c[i,2] V_i + c[i,3] J V_i  (i < k);
    one read of V[:k], two rows per pass (halves the traffic on x0, x1)."""
    i = 0
    while i + 1 < k:
        vi = V[i]
        wi = V[i + 1]
        p0, q0, p1, q1 = c[i, 0], c[i, 1], c[i, 2], c[i, 3]
        r0, s0, r1, s1 = c[i + 1, 0], c[i + 1, 1], c[i + 1, 2], c[i + 1, 3]
        for j in range(n):
            a, b, e, f = vi[j], vi[n + j], wi[j], wi[n + j]
            x0[j] -= (a * p0 + b * q0) + (e * r0 + f * s0)
            x0[n + j] -= (b * p0 - a * q0) + (f * r0 - e * s0)
            x1[j] -= (a * p1 + b * q1) + (e * r1 + f * s1)
            x1[n + j] -= (b * p1 - a * q1) + (f * r1 - e * s1)
        i += 2
    if i < k:
        vi = V[i]
        p0, q0, p1, q1 = c[i, 0], c[i, 1], c[i, 2], c[i, 3]
        for j in range(n):
            a, b = vi[j], vi[n + j]
            x0[j] -= a * p0 + b * q0
            x0[n + j] -= b * p0 - a * q0
            x1[j] -= a * p1 + b * q1
            x1[n + j] -= b * p1 - a * q1


@njit(fastmath=_FMA, cache=True, nogil=True)
def project_out_z(V, k, c, n, x0, x1, z):
    """:func:`project_out` and, in the same read of V[:k], z = Σ_i c[i,1] V_i.  A copy on
    purpose: one kernel with a ``with_z`` flag gave the same H bit for bit but measured 3–5 %
    slower per Arnoldi run (the flag is not hoisted out of the inner loop)."""
    for j in range(2 * n):
        z[j] = 0.0
    i = 0
    while i + 1 < k:
        vi = V[i]
        wi = V[i + 1]
        p0, q0, p1, q1 = c[i, 0], c[i, 1], c[i, 2], c[i, 3]
        r0, s0, r1, s1 = c[i + 1, 0], c[i + 1, 1], c[i + 1, 2], c[i + 1, 3]
        for j in range(n):
            a, b, e, f = vi[j], vi[n + j], wi[j], wi[n + j]
            x0[j] -= (a * p0 + b * q0) + (e * r0 + f * s0)
            x0[n + j] -= (b * p0 - a * q0) + (f * r0 - e * s0)
            x1[j] -= (a * p1 + b * q1) + (e * r1 + f * s1)
            x1[n + j] -= (b * p1 - a * q1) + (f * r1 - e * s1)
            z[j] += a * q0 + e * s0
            z[n + j] += b * q0 + f * s0
        i += 2
    if i < k:
        vi = V[i]
        p0, q0, p1, q1 = c[i, 0], c[i, 1], c[i, 2], c[i, 3]
        for j in range(n):
            a, b = vi[j], vi[n + j]
            x0[j] -= a * p0 + b * q0
            x0[n + j] -= b * p0 - a * q0
            x1[j] -= a * p1 + b * q1
            x1[n + j] -= b * p1 - a * q1
            z[j] += a * q0
            z[n + j] += b * q0


@njit(fastmath=_FMA, cache=True, nogil=True)
def hessenberg_times(HT: np.ndarray, k: int, c: np.ndarray, src: int, out: np.ndarray):
    """out[:k+1] = H[:k+1, :k] c[:k, src], H upper Hessenberg stored as HT = Hᵀ (a separate out
    array, so the axpys over rows of HT vectorise: no aliasing with HT)."""
    for i in range(k + 1):
        out[i] = 0.0
    for jj in range(k):
        a = c[jj, src]
        hj = HT[jj]
        for i in range(jj + 2):
            out[i] += hj[i] * a


@njit(fastmath=_SUM, cache=True, nogil=True)
def hessenberg_t_times(HT: np.ndarray, k: int, a: np.ndarray, c: np.ndarray, dst: int):
    """c[i, dst] −= (H[:k, :k]ᵀ a[:k])_i for i < k, H upper Hessenberg stored as HT = Hᵀ
    (row i of HT is column i of H: entries 0 … i+1).  a contiguous (a strided column of c
    would not vectorise: measured 4× slower)."""
    for i in range(k):
        s = 0.0
        hi = HT[i]
        for ll in range(min(i + 2, k)):
            s += hi[ll] * a[ll]
        c[i, dst] -= s


@njit(cache=True, nogil=True)
def dcgs2_steps(bands, d0, n, V, HT, GT, C, u, w, z, wz, t1, t2, t3, t4, k0, tol, tol_j, scal):
    """Steps k0, k0+1, … of the isotropic Arnoldi process on W (structured_kernels.w_apply).

    State on entry: V[:k0] final (orthonormal, isotropic); u the tentative k0-th vector (the
    previous step's once-projected residual, unit length, or a fresh exact vector after a
    breakdown with HT[k0−1, k0] = 0); HT[k0−1, k0] its tentative norm h.
    Per step k: w = W u; one sweep → C[i] = (V_i·u, JV_i·u, V_i·w, JV_i·w); reorthogonalise u
    (coefficients a = C[:, :2], β² = u·u − |a|², Pythagoras); correct column k−1 (H += h a_V,
    G += h a_J, H[k, k−1] = h β); one sweep removes a from u and b = C[:, 2:] from w; v_k = u/β.
    W v_k = (w − W V a_V − W J V a_J)/β.  W V a_V lies in span(V_0 … V_k) with coefficients H a_V
    (the Arnoldi relation), so column k = raw coefficients of w/β on (V_0 … V_k) minus H a_V/β,
    and the projection removes that term from the residual anyway.  W J V a_J = J Wᵀ V a_J does
    not lie in the span: when |a_J| > tol_j it is formed (z = V a_J in the update sweep, then one
    W product) and subtracted from the residual, unprojected — its components along V and J V are
    removed by the next step's delayed pass, which books them into column k.  Below tol_j it is
    dropped and (|a_J|/β)² is added to scal[0] (the caller bounds it by ‖W‖·√scal[0]); likewise
    the H a_V term when |a_V| ≤ tol_j (most steps: |a_V| ~ ε).  The residual,
    block means removed, is the next tentative vector.
    Returns the step at which the residual fell below tol·‖W u‖ (a breakdown: the caller puts a
    fresh vector there and calls again) or m = V.shape[0] when done (then the last column has had
    its second pass too).  scal : (1,) in/out, the sum above.
    z, wz : (2N,) work.
    """
    m = V.shape[0]
    for k in range(k0, m):
        w_apply(bands, d0, n, u, w, t1, t2, t3, t4)
        wn0, uu, uw, juw = step_sums(u, w, n)
        wn0 = math.sqrt(wn0)
        coefficients(V, k, u, w, n, C)
        aa = 0.0
        aj = 0.0
        for i in range(k):
            aa += C[i, 0] * C[i, 0] + C[i, 1] * C[i, 1]
            aj += C[i, 1] * C[i, 1]
        beta = math.sqrt(max(uu - aa, 0.0))
        fix_j = k > 0 and aj > tol_j * tol_j
        # coefficients of the raw w on the finished v_k (from the same sweep's numbers)
        ab = 0.0
        jab = 0.0
        for i in range(k):
            ab += C[i, 0] * C[i, 2] + C[i, 1] * C[i, 3]
            jab += C[i, 0] * C[i, 3] - C[i, 1] * C[i, 2]
        if k > 0:
            h = HT[k - 1, k]
            for i in range(k):
                HT[k - 1, i] += h * C[i, 0]
                GT[k - 1, i] += h * C[i, 1]
            HT[k - 1, k] = h * beta
        if fix_j:
            # W J V a_J has J V-coefficients Hᵀ a_J (W J = J Wᵀ; H[:, :k] is final): booked
            # into b_J so that the sweep below removes them with w's own
            for i in range(k):
                z[i] = C[i, 1]
            hessenberg_t_times(HT, k, z, C, 3)
        elif k > 0:
            scal[0] += aj / (beta * beta)
        if fix_j:  # and wz = W J z, z = V a_J from the same sweep
            project_out_z(V, k, C, n, u, w, wz)
            j_apply(wz, n, z)
            w_apply(bands, d0, n, z, wz, t1, t2, t3, t4)
        elif k > 0:
            project_out(V, k, C, n, u, w)
        vw = (uw - ab) / beta
        jvw = (juw - jab) / beta
        for j in range(2 * n):
            u[j] /= beta
            V[k, j] = u[j]
        ck = vw / beta
        cj = jvw / beta
        if fix_j:  # wz's own components along v_k and J v_k, exactly (O(N))
            dv = 0.0
            dj = 0.0
            for j in range(n):
                dv += u[j] * wz[j] + u[n + j] * wz[n + j]
                dj += u[n + j] * wz[j] - u[j] * wz[n + j]
            ck -= dv / beta
            cj -= dj / beta
            for j in range(2 * n):
                w[j] -= wz[j]
        for j in range(n):
            w[j] = w[j] / beta - ck * u[j] - cj * u[n + j]
            w[n + j] = w[n + j] / beta - ck * u[n + j] + cj * u[j]
        for i in range(k):
            HT[k, i] = C[i, 2] / beta
            GT[k, i] = C[i, 3] / beta
        HT[k, k] = ck
        GT[k, k] = cj
        if aa - aj > tol_j * tol_j:  # − H a_V / β over rows 0..k
            hessenberg_times(HT, k, C, 0, t1)
            for i in range(k + 1):
                HT[k, i] -= t1[i] / beta
        elif k > 0:  # ‖H a_V‖/β ≤ ‖W‖·tol_j/β: round-off, bounded instead (as for a_J)
            scal[0] += (aa - aj) / (beta * beta)
        remove_means(w, n)
        if k + 1 < m:
            nr = math.sqrt(step_sums(w, w, n)[0])
            if nr <= tol * max(wn0, 1.0):
                HT[k, k + 1] = 0.0
                return k + 1
            HT[k, k + 1] = nr
            for j in range(2 * n):
                u[j] = w[j] / nr
        else:  # the last column's second pass (no next step to delay it to)
            coefficients(V, m, w, w, n, C)
            for i in range(m):
                HT[k, i] += C[i, 0]
                GT[k, i] += C[i, 1]
    return m
