"""Per-step observer of the chain simulations: event times, probes, guard (Numba).

Called by every stepper (:mod:`fpucore.simulate.kernels`, :mod:`fpucore.simulate.rkn`) after each
accepted step with w, ẇ, ẅ at both step ends.  :func:`observe` records per site the extrema in
time of w_n(t) (hysteresis "zigzag" with prominence ``thr``) and the crossings of a level (w*),
located inside the step with the degree-7 Hermite interpolant through w, ẇ, ẅ and d³w/dt³ at both
ends (the third derivative Δ(f′(w) ẇ) is evaluated for the sites concerned only), plus probe time
series at chosen sites on a fixed time grid (same interpolant).  :func:`check_convex` then checks
the strains against the guard interval (leaving it stops the run, status ``ST_LEFT_CONVEX``).
"""

from __future__ import annotations

from numba import njit

from fpucore import law as _law
from fpucore.simulate.layout import BC_FIXED_PARTICLES


# --------------------------------------------------------------------------- Hermite helpers
@njit(cache=True, nogil=True)
def _jerk(y, k, n, L, law_id, p, bc):
    """d³w_n/dt³ = Δ(f′(w) ẇ)_n at site n (0-based) from strains y[:L] and rates k[:L]: the time
    derivative of ẅ_n = Δ f(w)_n, with the ghosts of the end condition (held end particles:
    g_0 = f(w_1), g_{L+1} = f(w_L); load: constant ghosts, zero derivative)."""
    gc = _law.dforce(law_id, p, y[n]) * k[n]
    if n > 0:
        gl = _law.dforce(law_id, p, y[n - 1]) * k[n - 1]
    else:
        gl = gc if bc == BC_FIXED_PARTICLES else 0.0
    if n < L - 1:
        gr = _law.dforce(law_id, p, y[n + 1]) * k[n + 1]
    else:
        gr = gc if bc == BC_FIXED_PARTICLES else 0.0
    return (gr - gc) - (gc - gl)


@njit(cache=True, nogil=True)
def _h7coef(w0, w1, d0, d1, a0, a1, j0, j1, h, c):
    """Coefficients c[0..7] (in s = (t−t0)/h) of the degree-7 Hermite interpolant matching w, ẇ,
    ẅ and d³w/dt³ at both step ends (error O(h⁸): a quintic from w, ẇ, ẅ alone limited the event
    times to ~1e-8 at the long steps of the order-12 RKN pair)."""
    m0 = h * d0
    m1 = h * d1
    q0 = h * h * a0
    q1 = h * h * a1
    r0 = h * h * h * j0
    r1 = h * h * h * j1
    c[0] = w0
    c[1] = m0
    c[2] = 0.5 * q0
    c[3] = r0 / 6.0
    # the remaining four from P, P′, P″, P‴ at s = 1 (inverse of the 4×4 Hermite block)
    R0 = w1 - (c[0] + c[1] + c[2] + c[3])
    R1 = m1 - (c[1] + 2.0 * c[2] + 3.0 * c[3])
    R2 = q1 - (2.0 * c[2] + 6.0 * c[3])
    R3 = r1 - 6.0 * c[3]
    c[4] = 35.0 * R0 - 15.0 * R1 + 2.5 * R2 - R3 / 6.0
    c[5] = -84.0 * R0 + 39.0 * R1 - 7.0 * R2 + 0.5 * R3
    c[6] = 70.0 * R0 - 34.0 * R1 + 6.5 * R2 - 0.5 * R3
    c[7] = -20.0 * R0 + 10.0 * R1 - 2.0 * R2 + R3 / 6.0


@njit(cache=True, nogil=True)
def _poly(c, s):
    r = c[7]
    for k in range(6, -1, -1):
        r = c[k] + s * r
    return r


@njit(cache=True, nogil=True)
def _dpoly(c, s):
    r = 7.0 * c[7]
    for k in range(6, 0, -1):
        r = k * c[k] + s * r
    return r


@njit(cache=True, nogil=True)
def _d2poly(c, s):
    r = 42.0 * c[7]
    for k in range(6, 1, -1):
        r = k * (k - 1) * c[k] + s * r
    return r


@njit(cache=True, nogil=True)
def _root(c, deriv, level):
    """Root in [0, 1] of P(s) − level (deriv=False) or P′(s) (deriv=True), given a sign change:
    Newton from the secant guess, safeguarded by bisection of the bracket (≤ 60 iterations)."""
    lo = 0.0
    hi = 1.0
    if deriv:
        flo = _dpoly(c, lo)
        fhi = _dpoly(c, hi)
    else:
        flo = _poly(c, lo) - level
        fhi = _poly(c, hi) - level
    x = flo / (flo - fhi) if flo != fhi else 0.5
    for _ in range(60):
        if deriv:
            fx = _dpoly(c, x)
            dfx = _d2poly(c, x)
        else:
            fx = _poly(c, x) - level
            dfx = _dpoly(c, x)
        if fx == 0.0:
            return x
        if (fx > 0.0) == (flo > 0.0):
            lo = x
            flo = fx
        else:
            hi = x
        xn = x - fx / dfx if dfx != 0.0 else 0.5 * (lo + hi)
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
        if abs(xn - x) < 1e-15 or hi - lo < 1e-15:
            return xn
        x = xn
    return x


# --------------------------------------------------------------------------- observer
@njit(cache=True, nogil=True)
def _record(n, sgn, t, w, ev_t, ev_w, ev_s, ev_n):
    k = ev_n[n]
    if k < ev_t.shape[1]:
        ev_t[n, k] = t
        ev_w[n, k] = w
        ev_s[n, k] = sgn
        ev_n[n] = k + 1


_OBS_BLOCK = 64


@njit(cache=True, nogil=True)
def observe(t0, h, y0, k0, a0, y1, k1, a1, chain, obs):
    """Record extrema / level crossings of every w_n inside [t0, t0+h] and probe samples.

    y0/y1 : strains w_n at both step ends, k0/k1 : ẇ_n, a0/a1 : ẅ_n (first L entries are read);
    chain (:class:`~fpucore.simulate.layout.Chain`) gives d³w/dt³ (:func:`_jerk`) for the
    degree-7 Hermite interpolant; obs (:class:`~fpucore.simulate.layout.Observer`) holds the
    arrays filled here (zz rows 1 and 2 are also the run's strain range).

    Most sites see nothing in a step, so each block of sites is first screened by a branch-free
    (vectorised) test for a sign change of ẇ or a crossing of ``level``; only blocks with a hit
    are walked site by site.
    """
    L, law_id, p, bc = chain.L, chain.law_id, chain.p, chain.bc
    thr, level, zz, zt, zdir = obs.thr, obs.level, obs.zz, obs.zt, obs.zdir
    ev_t, ev_w, ev_s, ev_n = obs.ev_t, obs.ev_w, obs.ev_s, obs.ev_n
    cr_t, cr_s, cr_n = obs.cr_t, obs.cr_s, obs.cr_n
    probe_idx, probe_t, probe_out, pcount, c = (
        obs.probe_idx,
        obs.probe_t,
        obs.probe_out,
        obs.pcount,
        obs.c,
    )
    for n0 in range(0, L, _OBS_BLOCK):
        n1 = min(n0 + _OBS_BLOCK, L)
        hit = 0
        for n in range(n0, n1):
            d0 = k0[n]
            d1 = k1[n]
            x = (y0[n] - level) * (y1[n] - level)
            hit |= ((d0 > 0.0) & (d1 <= 0.0)) | ((d0 < 0.0) & (d1 >= 0.0)) | (x < 0.0)
        if hit:
            # (written out here: as a separate per-site function, inlined or not, it ran 2x slower)
            for n in range(n0, n1):
                w0 = y0[n]
                w1 = y1[n]
                d0 = k0[n]
                d1 = k1[n]
                ext = 0
                if ev_n[n] < ev_t.shape[1]:  # a full event list needs no more extrema
                    if d0 > 0.0 and d1 <= 0.0:
                        ext = 1
                    elif d0 < 0.0 and d1 >= 0.0:
                        ext = -1
                crossed = (w0 - level) * (w1 - level) < 0.0 and cr_n[n] < cr_t.shape[1]
                if ext != 0 or crossed:
                    j0 = _jerk(y0, k0, n, L, law_id, p, bc)
                    j1 = _jerk(y1, k1, n, L, law_id, p, bc)
                    _h7coef(w0, w1, d0, d1, a0[n], a1[n], j0, j1, h, c)
                    if crossed:
                        s = _root(c, False, level)
                        k = cr_n[n]
                        cr_t[n, k] = t0 + s * h
                        cr_s[n, k] = 1 if w1 > w0 else -1
                        cr_n[n] = k + 1
                    if ext != 0:
                        s = _root(c, True, 0.0)
                        te = t0 + s * h
                        we = _poly(c, s)
                        dirn = zdir[n]
                        if ext == 1:
                            if dirn == 1:
                                if we > zz[0, n]:
                                    zz[0, n] = we
                                    zt[n] = te
                            elif dirn == -1:
                                if we - zz[0, n] > thr:
                                    _record(n, -1, zt[n], zz[0, n], ev_t, ev_w, ev_s, ev_n)
                                    zdir[n] = 1
                                    zz[0, n] = we
                                    zt[n] = te
                            elif we - zz[1, n] > thr:
                                zdir[n] = 1
                                zz[0, n] = we
                                zt[n] = te
                        else:
                            if dirn == -1:
                                if we < zz[0, n]:
                                    zz[0, n] = we
                                    zt[n] = te
                            elif dirn == 1:
                                if zz[0, n] - we > thr:
                                    _record(n, 1, zt[n], zz[0, n], ev_t, ev_w, ev_s, ev_n)
                                    zdir[n] = -1
                                    zz[0, n] = we
                                    zt[n] = te
                            elif zz[2, n] - we > thr:
                                zdir[n] = -1
                                zz[0, n] = we
                                zt[n] = te
        for n in range(n0, n1):  # running extremes, after the events (their start test reads them)
            w1 = y1[n]
            lo = zz[1, n]
            hi = zz[2, n]
            zz[1, n] = w1 if w1 < lo else lo
            zz[2, n] = w1 if w1 > hi else hi
    # probes on the fixed time grid
    M = probe_t.size
    k = pcount[0]
    t1 = t0 + h
    while k < M and probe_t[k] <= t1 * (1.0 + 1e-15):
        s = (probe_t[k] - t0) / h
        for i in range(probe_idx.size):
            n = probe_idx[i]
            j0 = _jerk(y0, k0, n, L, law_id, p, bc)
            j1 = _jerk(y1, k1, n, L, law_id, p, bc)
            _h7coef(y0[n], y1[n], k0[n], k1[n], a0[n], a1[n], j0, j1, h, c)
            probe_out[i, k] = _poly(c, s)
        k += 1
    pcount[0] = k


@njit(cache=True, nogil=True)
def strain_accel(k, L, out):
    """ẅ_n = v̇_n − v̇_{n−1} read off a first-order derivative vector k = dy/dt; out: (≥ L,)."""
    for n in range(L):
        out[n] = k[L + n + 1] - k[L + n]


@njit(cache=True, nogil=True)
def check_convex(y, L, alpha, beta, bad):
    """True if a strain is outside (α, β) or non-finite; bad[0], bad[1] = the first one's value
    and site index.  A branch-free count first (vectorised): a run stays inside almost always."""
    nout = 0
    for n in range(L):
        x = y[n]
        nout += 0 if ((x > alpha) & (x < beta)) else 1  # NaN counts as outside
    if nout == 0:
        return False
    for n in range(L):
        x = y[n]
        if not (alpha < x < beta):
            bad[0] = x
            bad[1] = n
            break
    return True
