"""Numba kernels for direct simulation of the FPU chain in the first-order strain–velocity form
(paper eq. FPUsystem; state layout and end conditions in :mod:`fpucore.simulate.layout`).

Two steppers, both advancing ``y`` in place from t to t_stop (a chunk between two output times) and
calling the observer of :mod:`fpucore.simulate.observer` after every accepted step:
  * :func:`erk_chunk` — adaptive embedded RK (DOP853 or DOPRI5 tableau from
    fpucore.tableaux.embedded),
    scipy/Hairer step-size control, RMS error norm with scale atol + rtol·max(|y|, |y_new|);
  * :func:`yoshida_chunk` — 4th-order symplectic Yoshida composition of velocity Verlet with a
    fixed step (kick-drift-kick in (w, v); the map is symplectic because w = D u is linear).
The default integrator, RKN12 on the second-order form, lives in :mod:`fpucore.simulate.rkn`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from fpucore import law as _law
from fpucore.simulate.layout import (  # noqa: F401  (re-exported: ck.BC_LOAD, ck.ST_OK, …)
    BC_FIXED_PARTICLES,
    BC_LOAD,
    ST_BUDGET,
    ST_LEFT_CONVEX,
    ST_NONFINITE,
    ST_OK,
    ST_STEP_UNDERFLOW,
)
from fpucore.simulate.observer import check_convex, observe, strain_accel


# --------------------------------------------------------------------------- right-hand side
@njit(cache=True, nogil=True)
def forces(y, L, law_id, p, fL, fR, g):
    """g[0] = fL, g[1..L] = f(w_1..w_L), g[L+1] = fR.  g: (L+2,)."""
    g[0] = fL
    g[L + 1] = fR
    _law.forces_into(law_id, p, y[:L], g[1 : L + 1])


@njit(cache=True, nogil=True)
def assemble(y, L, bc, g, out):
    """out = dy/dt from the state y and the forces g (see :func:`forces`)."""
    # explicit views: the loops then vectorise (with raw offsets into y/out they did not)
    v = y[L : 2 * L + 1]
    ow = out[:L]
    ov = out[L : 2 * L + 1]
    for n in range(L):
        ow[n] = v[n + 1] - v[n]
    for j in range(L + 1):
        ov[j] = g[j + 1] - g[j]
    if bc == BC_FIXED_PARTICLES:
        ov[0] = 0.0
        ov[L] = 0.0
    out[2 * L + 1] = y[L]


@njit(cache=True, nogil=True)
def rhs(y, L, law_id, p, bc, fL, fR, g, out):
    """Right-hand side of eq. FPUsystem with the boundary closure; g is (L+2,) work."""
    forces(y, L, law_id, p, fL, fR, g)
    assemble(y, L, bc, g, out)


# --------------------------------------------------------------------------- adaptive RK
@njit(cache=True, nogil=True)
def step_factor(err, err_exp):
    """Hairer's step-size controller: h_new / h = 0.9 err^err_exp, err_exp = −1/(q + 1) for an
    error estimator of order q, clipped to [0.2, 10] (err: the scaled RMS error norm)."""
    if err == 0.0:
        return 10.0
    return min(10.0, max(0.2, 0.9 * err**err_exp))


@njit(cache=True, nogil=True)
def combo(y, K, rows, cf, nc, out):
    """out = y + Σ_q cf[q] K[rows[q]], up to eight stages per memory pass, y folded into the
    first pass.  ``rows``/``cf`` must have room for nc rounded up to a multiple of 4: the padding
    entries get weight 0 (the passes, not the flops, dominate the cost of a DOP853 step)."""
    nn = out.size
    ncp = (nc + 3) // 4 * 4
    for q in range(nc, ncp):
        cf[q] = 0.0
        rows[q] = rows[0]
    q = 0
    while q < ncp:
        first = q == 0
        if q + 8 <= ncp:
            a0, a1, a2, a3 = cf[q], cf[q + 1], cf[q + 2], cf[q + 3]
            a4, a5, a6, a7 = cf[q + 4], cf[q + 5], cf[q + 6], cf[q + 7]
            k0, k1, k2, k3 = K[rows[q]], K[rows[q + 1]], K[rows[q + 2]], K[rows[q + 3]]
            k4, k5, k6, k7 = K[rows[q + 4]], K[rows[q + 5]], K[rows[q + 6]], K[rows[q + 7]]
            if first:
                for m in range(nn):
                    out[m] = y[m] + (
                        (a0 * k0[m] + a1 * k1[m] + a2 * k2[m] + a3 * k3[m])
                        + (a4 * k4[m] + a5 * k5[m] + a6 * k6[m] + a7 * k7[m])
                    )
            else:
                for m in range(nn):
                    out[m] += (a0 * k0[m] + a1 * k1[m] + a2 * k2[m] + a3 * k3[m]) + (
                        a4 * k4[m] + a5 * k5[m] + a6 * k6[m] + a7 * k7[m]
                    )
            q += 8
        else:
            a0, a1, a2, a3 = cf[q], cf[q + 1], cf[q + 2], cf[q + 3]
            k0, k1, k2, k3 = K[rows[q]], K[rows[q + 1]], K[rows[q + 2]], K[rows[q + 3]]
            if first:
                for m in range(nn):
                    out[m] = y[m] + (a0 * k0[m] + a1 * k1[m] + a2 * k2[m] + a3 * k3[m])
            else:
                for m in range(nn):
                    out[m] += a0 * k0[m] + a1 * k1[m] + a2 * k2[m] + a3 * k3[m]
            q += 4


@njit(cache=True, nogil=True, error_model="numpy")
def _err_pass(y, ynew, K, rows, c5, c3, rtol, atol, t5, t3):
    """Hairer's error sums Σ (e5/sc)², Σ (e3/sc)², Σ sc², with e5 = Σ_q c5[q] K[rows[q]] (exactly
    eight rows; unused ones padded with zero weights) and sc = atol + rtol·max(|y|, |y_new|) > 0.

    Two passes so that both vectorise: the element-wise ratios (error_model="numpy" drops the
    zero-division branch that otherwise keeps the division scalar; sc > 0 always), then the sums
    with four independent accumulators (no reassociation needed, hence no fastmath)."""
    k0, k1, k2, k3 = K[rows[0]], K[rows[1]], K[rows[2]], K[rows[3]]
    k4, k5, k6, k7 = K[rows[4]], K[rows[5]], K[rows[6]], K[rows[7]]
    a0, a1, a2, a3, a4, a5, a6, a7 = c5[0], c5[1], c5[2], c5[3], c5[4], c5[5], c5[6], c5[7]
    b0, b1, b2, b3, b4, b5, b6, b7 = c3[0], c3[1], c3[2], c3[3], c3[4], c3[5], c3[6], c3[7]
    nn = y.size
    for m in range(nn):
        x5 = (a0 * k0[m] + a1 * k1[m] + a2 * k2[m] + a3 * k3[m]) + (
            a4 * k4[m] + a5 * k5[m] + a6 * k6[m] + a7 * k7[m]
        )
        x3 = (b0 * k0[m] + b1 * k1[m] + b2 * k2[m] + b3 * k3[m]) + (
            b4 * k4[m] + b5 * k5[m] + b6 * k6[m] + b7 * k7[m]
        )
        ya = abs(y[m])
        yb = abs(ynew[m])
        sc = atol + rtol * (ya if ya >= yb else yb)
        t5[m] = x5 / sc
        t3[m] = x3 / sc
    s0 = s1 = s2 = s3 = 0.0
    u0 = u1 = u2 = u3 = 0.0
    n4 = nn - nn % 4
    for m in range(0, n4, 4):
        s0 += t5[m] * t5[m]
        s1 += t5[m + 1] * t5[m + 1]
        s2 += t5[m + 2] * t5[m + 2]
        s3 += t5[m + 3] * t5[m + 3]
        u0 += t3[m] * t3[m]
        u1 += t3[m + 1] * t3[m + 1]
        u2 += t3[m + 2] * t3[m + 2]
        u3 += t3[m + 3] * t3[m + 3]
    for m in range(n4, nn):
        s0 += t5[m] * t5[m]
        u0 += t3[m] * t3[m]
    # Σ sc² only feeds the reported error estimate: the RMS scale of |y|
    q = 0.0
    for m in range(nn):
        ya = abs(y[m])
        yb = abs(ynew[m])
        sc = atol + rtol * (ya if ya >= yb else yb)
        q += sc * sc
    return (s0 + s1) + (s2 + s3), (u0 + u1) + (u2 + u3), q


@njit(cache=True, nogil=True)
def erk_chunk(y, t, t_stop, h, step_limit, pair, ctl, chain, work, obs):
    """Advance y from t to t_stop with an embedded explicit RK pair and error control.

    pair : :class:`~fpucore.simulate.layout.ErkPair`; ctl : :class:`~.layout.Control`;
    chain : :class:`~.layout.Chain`; obs : :class:`~.layout.Observer`.
    work : :class:`~.layout.Work` with K (s+1, 2L+2) stage work — K[0] must hold f(y) on entry and
    holds f(y) on exit (FSAL) — and W (5, 2L+2) work; stats[3] accumulates the local error
    estimates (RMS-norm × RMS scale).  h : proposed step on entry.  Stops with ST_BUDGET once
    stats[0] reaches ``step_limit`` (the caller resumes from the returned (t, h): a resumed run
    takes exactly the steps of an uninterrupted one).  Returns (t, h_next, status).
    """
    A, B, E5, E3, dual, err_exp = pair.A, pair.B, pair.E5, pair.E3, pair.dual, pair.err_exp
    rtol, atol, alpha, beta = ctl.rtol, ctl.atol, ctl.lo, ctl.hi
    L, law_id, p, bc, fL, fR = chain.L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR
    K, W, g, stats, bad = work.K, work.W, work.g, work.stats, work.bad
    s = B.size
    nn = y.size
    # stage j lives in row perm[j] of K; the FSAL swap of rows 0 and s is a swap of perm entries
    perm = np.arange(s + 1)
    # nonzero pattern of the (sparse) tableau: stg[i, :cnt[i]] stages used by stage i,
    # row s: the solution weights B; error weights E5/E3 (s+1 entries, FSAL last): estg
    stg = np.zeros((s + 1, s + 1), np.int64)
    cnt = np.zeros(s + 1, np.int64)
    for i in range(s):
        for j in range(i):
            if A[i, j] != 0.0:
                stg[i, cnt[i]] = j
                cnt[i] += 1
        if B[i] != 0.0:
            stg[s, cnt[s]] = i
            cnt[s] += 1
    estg = np.zeros(s + 1, np.int64)
    ne = 0
    for i in range(s + 1):
        if E5[i] != 0.0 or E3[i] != 0.0:
            estg[ne] = i
            ne += 1
    erow = np.zeros(8, np.int64)
    c5 = np.zeros(8)
    c3 = np.zeros(8)
    for q in range(min(ne, 8)):
        c5[q] = E5[estg[q]]
        c3[q] = E3[estg[q]]
    rws = np.zeros(s + 4, np.int64)  # room for padding to a multiple of 4 (see combo)
    cf = np.zeros(s + 4)
    cur = y  # current state buffer; the other one receives the step
    nxt = W[0]
    in_y = True
    x5 = W[1]
    x3 = W[2]
    acc0 = W[3]  # ẅ at the step start / end for the observer's interpolant
    acc1 = W[4]
    strain_accel(K[perm[0]], L, acc0)
    status = 0
    while t < t_stop:
        if stats[0] >= step_limit:
            status = ST_BUDGET
            break
        rem = t_stop - t
        clamped = h >= rem
        hh = rem if clamped else h
        for i in range(1, s):
            for q in range(cnt[i]):
                cf[q] = hh * A[i, stg[i, q]]
                rws[q] = perm[stg[i, q]]
            combo(cur, K, rws, cf, cnt[i], nxt)
            rhs(nxt, L, law_id, p, bc, fL, fR, g, K[perm[i]])
        for q in range(cnt[s]):
            cf[q] = hh * B[stg[s, q]]
            rws[q] = perm[stg[s, q]]
        combo(cur, K, rws, cf, cnt[s], nxt)
        ynew = nxt
        rhs(ynew, L, law_id, p, bc, fL, fR, g, K[perm[s]])
        stats[2] += s
        for q in range(8):
            erow[q] = perm[estg[q]] if q < ne else perm[0]
        e5, e3, sc2 = _err_pass(cur, ynew, K, erow, c5, c3, rtol, atol, x5, x3)
        e5 *= hh * hh
        e3 *= hh * hh
        if dual:
            den = e5 + 0.01 * e3
            err = 0.0 if den == 0.0 else e5 / math.sqrt(den * nn)
        else:
            err = math.sqrt(e5 / nn)
        if not math.isfinite(err):
            h = 0.2 * hh
            stats[1] += 1
            if h < 1e-14 * max(1.0, abs(t)):
                status = ST_NONFINITE
                break
            continue
        if err < 1.0:
            if not clamped:
                h = hh * step_factor(err, err_exp)
            strain_accel(K[perm[s]], L, acc1)
            observe(t, hh, cur, K[perm[0]], acc0, ynew, K[perm[s]], acc1, chain, obs)
            tmpa = acc0
            acc0 = acc1
            acc1 = tmpa
            nxt = cur
            cur = ynew
            in_y = not in_y
            tmp = perm[0]
            perm[0] = perm[s]
            perm[s] = tmp
            t = t_stop if clamped else t + hh
            stats[0] += 1
            stats[3] += err * math.sqrt(sc2 / nn)
            if err > stats[4]:
                stats[4] = err
            if check_convex(cur, L, alpha, beta, bad):
                status = ST_LEFT_CONVEX
                break
        else:
            h = hh * step_factor(err, err_exp)
            stats[1] += 1
            if h < 1e-14 * max(1.0, abs(t)):
                status = ST_STEP_UNDERFLOW
                break
    # hand back the state in y and f(y) in K[0]
    if not in_y:
        for m in range(nn):
            y[m] = cur[m]
    if perm[0] != 0:
        for m in range(nn):
            K[0, m] = K[perm[0], m]
    return t, h, status


# --------------------------------------------------------------------------- symplectic
@njit(cache=True, nogil=True)
def _kick(y, L, bc, g, dt):
    for j in range(L + 1):
        y[L + j] += dt * (g[j + 1] - g[j])
    if bc == BC_FIXED_PARTICLES:
        y[L] = 0.0
        y[2 * L] = 0.0


@njit(cache=True, nogil=True)
def _drift(y, L, dt):
    for n in range(L):
        y[n] += dt * (y[L + n + 1] - y[L + n])
    y[2 * L + 1] += dt * y[L]


@njit(cache=True, nogil=True)
def yoshida_chunk(y, t, t_stop, h, step_limit, ctl, chain, work, obs):
    """Advance y from t to t_stop with the 4th-order Yoshida composition of velocity Verlet,
    fixed step h (the last step of the chunk is shortened to land on t_stop).

    work : :class:`~fpucore.simulate.layout.Work` with K (2, 2L+2) = [f(y), work] and
    W (3, 2L+2) = [copy of y, ẅ at both step ends]; on entry g must hold the forces at y and
    K[0] = f(y), both hold the values at y on exit.  ctl : only the guard interval is read.
    Stops with ST_BUDGET once stats[0] reaches ``step_limit``.  Returns (t, h, status).
    """
    alpha, beta = ctl.lo, ctl.hi
    L, law_id, p, bc, fL, fR = chain.L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR
    k0, k1, y0, g, stats, bad = work.K[0], work.K[1], work.W[0], work.g, work.stats, work.bad
    cbr = 2.0 ** (1.0 / 3.0)
    c1 = 1.0 / (2.0 - cbr)
    c0 = -cbr * c1
    nn = y.size
    status = 0
    acc0 = work.W[1]
    acc1 = work.W[2]
    strain_accel(k0, L, acc0)
    while t < t_stop:
        if stats[0] >= step_limit:
            status = ST_BUDGET
            break
        rem = t_stop - t
        clamped = h >= rem * (1.0 - 1e-12)
        hh = rem if clamped else h
        for m in range(nn):
            y0[m] = y[m]
        # K(c1/2) D(c1) K((c1+c0)/2) D(c0) K((c0+c1)/2) D(c1) K(c1/2); g is FSAL
        _kick(y, L, bc, g, 0.5 * c1 * hh)
        _drift(y, L, c1 * hh)
        forces(y, L, law_id, p, fL, fR, g)
        _kick(y, L, bc, g, 0.5 * (c1 + c0) * hh)
        _drift(y, L, c0 * hh)
        forces(y, L, law_id, p, fL, fR, g)
        _kick(y, L, bc, g, 0.5 * (c0 + c1) * hh)
        _drift(y, L, c1 * hh)
        forces(y, L, law_id, p, fL, fR, g)
        _kick(y, L, bc, g, 0.5 * c1 * hh)
        assemble(y, L, bc, g, k1)
        stats[2] += 3
        strain_accel(k1, L, acc1)
        observe(t, hh, y0, k0, acc0, y, k1, acc1, chain, obs)
        for m in range(nn):
            k0[m] = k1[m]
        tmpa = acc0
        acc0 = acc1
        acc1 = tmpa
        t = t_stop if clamped else t + hh
        stats[0] += 1
        if check_convex(y, L, alpha, beta, bad):
            status = ST_LEFT_CONVEX
            break
    return t, h, status
