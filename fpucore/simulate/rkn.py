"""Numba Runge–Kutta–Nyström stepper for the chain in second-order strain form.

Eq. FPUstrain, ẅ_n = f(w_{n+1}) − 2 f(w_n) + f(w_{n−1}), is a special second-order system
q̈ = F(q) (no ẇ on the right), so an RKN pair (:mod:`fpucore.tableaux.rkn`) integrates it with one
force evaluation per stage and stage combinations over q alone — L + 1 numbers instead of the
2L + 2 of the first-order state (w, v) of :mod:`fpucore.simulate.kernels`.

State (length L + 1 each):

    q  = (w_1 … w_L, u_0)        strains and the displacement of particle 0
    q̇ = (ẇ_1 … ẇ_L, v_0)        ẇ_n = v_n − v_{n−1}; v_j = v_0 + Σ_{n ≤ j} ẇ_n

with the ghost forces g_0, g_{L+1} of the end conditions (:mod:`fpucore.simulate.layout`):
``BC_LOAD`` g_0 = fL, g_{L+1} = fR and ü_0 = f(w_1) − fL; ``BC_FIXED_PARTICLES`` g_0 = f(w_1),
g_{L+1} = f(w_L) (v_0 = v_L = 0) and ü_0 = 0.

:func:`rkn_chunk` advances (q, q̇) from t to t_stop with error control in Hairer's RMS norm over
all 2(L + 1) components (scale atol + rtol·max(|x|, |x₁|) per component), calls the shared
observer of :mod:`fpucore.simulate.observer` (Hermite interpolation from w, ẇ, ẅ = F and d³w/dt³ at
both step ends)
after every accepted step, and checks the strains against the guard interval.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from fpucore import law as _law
from fpucore.simulate.kernels import combo, step_factor
from fpucore.simulate.layout import (
    BC_FIXED_PARTICLES,
    ST_BUDGET,
    ST_LEFT_CONVEX,
    ST_NONFINITE,
    ST_STEP_UNDERFLOW,
)
from fpucore.simulate.observer import check_convex, observe


@njit(cache=True, nogil=True)
def accel(q, L, law_id, p, bc, fL, fR, g, out):
    """out = F(q): out[n] = ẅ_{n+1} = (g_{n+2} − g_{n+1}) − (g_{n+1} − g_n), out[L] = ü_0.
    g : (L+2,) work, left holding the forces (ghosts included)."""
    _law.forces_into(law_id, p, q[:L], g[1 : L + 1])
    accel_from_forces(L, bc, fL, fR, g, out)


@njit(cache=True, nogil=True)
def accel_from_forces(L, bc, fL, fR, g, out):
    """out = F(q) from the bond forces g[1 … L] (:func:`accel`'s second half, shared with the
    frozen-piece force of the PL stepper): the ghosts g[0], g[L+1] by the boundary condition,
    then the second differences."""
    if bc == BC_FIXED_PARTICLES:
        g[0] = g[1]
        g[L + 1] = g[L]
        out[L] = 0.0
    else:
        g[0] = fL
        g[L + 1] = fR
        out[L] = g[1] - g[0]
    for n in range(L):
        out[n] = (g[n + 2] - g[n + 1]) - (g[n + 1] - g[n])


@njit(cache=True, nogil=True)
def y_to_rkn(y, L, q, qd):
    """First-order state y = (w, v_0…v_L, u_0) → (q, q̇)."""
    for n in range(L):
        q[n] = y[n]
        qd[n] = y[L + n + 1] - y[L + n]
    q[L] = y[2 * L + 1]
    qd[L] = y[L]


@njit(cache=True, nogil=True)
def rkn_to_y(q, qd, L, y):
    """(q, q̇) → y = (w, v, u_0), with v_j = v_0 + Σ_{n ≤ j} ẇ_n."""
    v = qd[L]
    y[L] = v
    for n in range(L):
        y[n] = q[n]
        v += qd[n]
        y[L + n + 1] = v
    y[2 * L + 1] = q[L]


@njit(cache=True, nogil=True, error_model="numpy")
def rkn_err(q, q1, qd, qd1, e, ed, r, rd, rtol, atol):
    """Σ (e/sc)² + (ė/sċ)² with sc = atol + rtol·max(|q|, |q₁|), likewise sċ; r, rd : work.

    Two passes so that both vectorise: the element-wise ratios (error_model="numpy" drops the
    zero-division branch; sc > 0), then the sum with four independent accumulators (no
    reassociation needed, hence no fastmath)."""
    nn = q.size
    for m in range(nn):
        a = abs(q[m])
        b = abs(q1[m])
        r[m] = e[m] / (atol + rtol * (a if a >= b else b))
        a = abs(qd[m])
        b = abs(qd1[m])
        rd[m] = ed[m] / (atol + rtol * (a if a >= b else b))
    return sumsq2(r, rd)


@njit(cache=True, nogil=True)
def sumsq2(a, b):
    """Σ a² + b² with four independent accumulators."""
    nn = a.size
    s0 = s1 = s2 = s3 = 0.0
    n4 = nn - nn % 4
    for m in range(0, n4, 4):
        s0 += a[m] * a[m] + b[m] * b[m]
        s1 += a[m + 1] * a[m + 1] + b[m + 1] * b[m + 1]
        s2 += a[m + 2] * a[m + 2] + b[m + 2] * b[m + 2]
        s3 += a[m + 3] * a[m + 3] + b[m + 3] * b[m + 3]
    for m in range(n4, nn):
        s0 += a[m] * a[m] + b[m] * b[m]
    return (s0 + s1) + (s2 + s3)


@njit(cache=True, nogil=True)
def rkn_chunk(q, t, t_stop, h, step_limit, pair, ctl, chain, work, obs):
    """Advance (q, q̇) from t to t_stop with an embedded RKN pair and error control.

    q : (L+1,) positions, updated in place.  pair : :class:`~fpucore.simulate.layout.RknPair`.
    work : :class:`~.layout.Work` with K (s+3, L+1): K[0] = F(q) and K[s+1] = q̇ on entry and on
    exit; rows 1…s are stage work, K[s+2] the new q̇; W (7, L+1) work (W[4] must be 0).
    ctl, chain, obs, ``step_limit`` and the return value (t, h_next, status) as for
    :func:`fpucore.simulate.kernels.erk_chunk`, except that stats[3] accumulates the RMS of the
    local error vector (e, ė) of each accepted step.
    """
    C, A, B, BP, E, EP = pair.C, pair.A, pair.B, pair.BP, pair.E, pair.EP
    fsal, err_exp = pair.fsal, pair.err_exp
    rtol, atol, alpha, beta = ctl.rtol, ctl.atol, ctl.lo, ctl.hi
    L, law_id, p, bc, fL, fR = chain.L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR
    K, W, g, stats, bad = work.K, work.W, work.g, work.stats, work.bad
    s = B.size
    nn = q.size
    # row of stage j in K: stage 0 in f0, the FSAL stage (or F(q₁)) in fn; the two swap on accept
    f0 = 0
    fn = s - 1 if fsal else s
    iqd = s + 1
    iqd1 = s + 2
    nst = s - 1 if fsal else s  # stages computed from stage combinations
    # sparse patterns (tableau column indices) of the stage rows and of the four weight vectors
    stg = np.zeros((s, s), np.int64)
    cnt = np.zeros(s, np.int64)
    for i in range(s):
        for j in range(i):
            if A[i, j] != 0.0:
                stg[i, cnt[i]] = j
                cnt[i] += 1
    wts = np.zeros((4, s))
    wts[0, :] = B
    wts[1, :] = BP
    wts[2, :] = E
    wts[3, :] = EP
    wix = np.zeros((4, s), np.int64)
    wcnt = np.zeros(4, np.int64)
    for k in range(4):
        for j in range(s):
            if wts[k, j] != 0.0:
                wix[k, wcnt[k]] = j
                wcnt[k] += 1
    rws = np.zeros(s + 8, np.int64)  # room for the q̇ term and padding to a multiple of 4
    cf = np.zeros(s + 8)
    Y = W[0]
    cur = q
    nxt = W[1]
    in_q = True
    e = W[2]
    ed = W[3]
    zero = W[4]
    status = 0
    while t < t_stop:
        if stats[0] >= step_limit:
            status = ST_BUDGET
            break
        rem = t_stop - t
        clamped = h >= rem
        hh = rem if clamped else h
        h2 = hh * hh
        for i in range(1, nst):
            rws[0] = iqd
            cf[0] = C[i] * hh
            for k in range(cnt[i]):
                j = stg[i, k]
                rws[k + 1] = f0 if j == 0 else j
                cf[k + 1] = h2 * A[i, j]
            combo(cur, K, rws, cf, cnt[i] + 1, Y)
            accel(Y, L, law_id, p, bc, fL, fR, g, K[i])
        # q₁ = q + h q̇ + h² Σ b̄ F
        rws[0] = iqd
        cf[0] = hh
        for k in range(wcnt[0]):
            j = wix[0, k]
            rws[k + 1] = f0 if j == 0 else j
            cf[k + 1] = h2 * B[j]
        combo(cur, K, rws, cf, wcnt[0] + 1, nxt)
        if fsal:
            accel(nxt, L, law_id, p, bc, fL, fR, g, K[fn])
        # q̇₁ = q̇ + h Σ b′ F, and the error vectors
        for k in range(wcnt[1]):
            j = wix[1, k]
            rws[k] = f0 if j == 0 else (fn if (fsal and j == s - 1) else j)
            cf[k] = hh * BP[j]
        combo(K[iqd], K, rws, cf, wcnt[1], K[iqd1])
        for k in range(wcnt[2]):
            j = wix[2, k]
            rws[k] = f0 if j == 0 else (fn if (fsal and j == s - 1) else j)
            cf[k] = h2 * E[j]
        combo(zero, K, rws, cf, wcnt[2], e)
        for k in range(wcnt[3]):
            j = wix[3, k]
            rws[k] = f0 if j == 0 else (fn if (fsal and j == s - 1) else j)
            cf[k] = hh * EP[j]
        combo(zero, K, rws, cf, wcnt[3], ed)
        stats[2] += nst - 1 + (1 if fsal else 0)
        e2 = rkn_err(cur, nxt, K[iqd], K[iqd1], e, ed, W[5], W[6], rtol, atol)
        err = math.sqrt(e2 / (2 * nn))
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
            if not fsal:
                accel(nxt, L, law_id, p, bc, fL, fR, g, K[fn])
                stats[2] += 1
            observe(t, hh, cur, K[iqd], K[f0], nxt, K[iqd1], K[fn], chain, obs)
            tmp = cur
            cur = nxt
            nxt = tmp
            in_q = not in_q
            k = f0
            f0 = fn
            fn = k
            k = iqd
            iqd = iqd1
            iqd1 = k
            t = t_stop if clamped else t + hh
            stats[0] += 1
            stats[3] += math.sqrt(sumsq2(e, ed) / (2 * nn))  # RMS of the local error
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
    # hand back q in q, F(q) in K[0] and q̇ in K[s+1]
    if not in_q:
        for m in range(nn):
            q[m] = cur[m]
    if f0 != 0:
        for m in range(nn):
            K[0, m] = K[f0, m]
    if iqd != s + 1:
        for m in range(nn):
            K[s + 1, m] = K[iqd, m]
    return t, h, status
