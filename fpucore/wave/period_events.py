"""One period of the FPU chain with event location at the breakpoints of a piecewise-linear law
(paper eq. FPUstrain; the period map of :mod:`fpucore.wave.period_map`, same state and
boundary conventions).

For a PL law the right-hand side Δf(w) is only Lipschitz: the solution's third derivative jumps
when a site crosses a breakpoint, and a fixed-step RK method of order p drops to order ≈ 2–3
across such a crossing (``benchmarks/pwl_period_order.py``).  Here every nominal step of
h = T/m is tried whole; if some site's strain changes side of a breakpoint within it, the
earliest crossing (linear estimate over the sites) is located by the Illinois method on the
step fraction θ, each trial being one RK sub-step of θ·h from the step's start (the solution is
smooth up to the crossing, so the sub-step keeps the method's order), the located strain is set
to the breakpoint, and the step is restarted there for its remainder.  Within every (sub-)step
each site's regime is frozen to the one at its start (f by that regime's linear formula, also
where an inner RK stage overshoots the breakpoint: the stages are only low-order accurate, and
evaluating them on the far side cost DOP853 its order, measured ≈ 5); a site located on a
breakpoint takes the regime it moves into.  Each sub-step then integrates one linear system.
Measured against the exact compact wave (tests/wave/test_wave_period_events.py): log–log slope
8.3 for DOP853 and 4.2 for RK4 with location, 2.5 and 1.8 without.  Crossings are counted
(``crossings``); a tangential crossing (w′ = 0 at the breakpoint) is not located (no sign
change) and keeps the reduced order: ``crossing_speed``, the smallest |ẇ| of a site at its
located crossing, says how far from tangential the located ones are.

:func:`fpucore.wave.period_map.integrate` takes this route for every law with breakpoints
(Newton solver, step doubling, Floquet monodromy); with ``store_df`` the sub-steps and their
frozen f′ are kept for the tangent map (its saltation matrix is the identity: see
:mod:`fpucore.wave.period_map`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from fpucore import law as _law
from fpucore.errors import ParameterError, require_finite
from fpucore.tableaux.rk import DOP853, Tableau
from fpucore.wave.period_checks import check_m, check_state


@njit(cache=True, nogil=True)
def _freeze(w, wd, p, pc):
    """pc[n] = the piece of site n for the coming sub-step: the piece of w[n]; a strain exactly on
    a breakpoint (a located crossing) takes the piece it is moving into."""
    m = int(p[0])
    for n in range(w.size):
        j = 0
        while j < m and w[n] >= p[1 + j]:
            j += 1
        if j > 0 and w[n] == p[j] and wd[n] < 0.0:
            j -= 1
        pc[n] = j


@njit(cache=True, nogil=True)
def _force_in(p, j, x):
    """f of piece j's linear formula at x (also beyond the piece: its linear extension)."""
    m = int(p[0])
    k = j - 1 if j > 0 else 0
    return p[2 + 2 * m + k] + p[1 + m + j] * (x - p[1 + k])


@njit(cache=True, nogil=True)
def _step(w, wd, h, A, B, law_id, p, fl, fr, periodic, kw, kwd, yw, g, wo, wdo, pc, frozen):
    """One explicit RK step of size h from (w, wd) into (wo, wdo) (as in period_map).  frozen:
    every stage evaluates f with the piece pc[n] of the step's start — between located
    crossings the solution stays in it, so the step integrates one linear system at the
    method's order even where an inner stage value overshoots a breakpoint."""
    N = w.size
    s = B.size
    for i in range(s):
        for n in range(N):
            yw[n] = w[n]
            kw[i, n] = wd[n]
        for j in range(i):
            a = A[i, j] * h
            if a != 0.0:
                for n in range(N):
                    yw[n] += a * kw[j, n]
                    kw[i, n] += a * kwd[j, n]
        if frozen:
            for n in range(N):
                g[n + 1] = _force_in(p, pc[n], yw[n])
        else:
            for n in range(N):
                g[n + 1] = _law.force(law_id, p, yw[n])
        if periodic:
            g[0] = g[N]
            g[N + 1] = g[1]
        else:
            g[0] = fl
            g[N + 1] = fr
        for n in range(N):
            kwd[i, n] = g[n + 2] - 2.0 * g[n + 1] + g[n]
    for n in range(N):
        wo[n] = w[n]
        wdo[n] = wd[n]
    for i in range(s):
        b = B[i] * h
        if b != 0.0:
            for n in range(N):
                wo[n] += b * kw[i, n]
                wdo[n] += b * kwd[i, n]


@njit(cache=True, nogil=True)
def _earliest(w, w1, bps):
    """(fraction, site, breakpoint index) of the earliest sign change of w − b over the step
    (linear estimate); site −1 if none.  A strain exactly on b (just located) does not count."""
    best, bn, bk = 2.0, -1, -1
    for n in range(w.size):
        for k in range(bps.size):
            d0 = w[n] - bps[k]
            d1 = w1[n] - bps[k]
            if d0 * d1 < 0.0:
                fr = d0 / (d0 - d1)
                if fr < best:
                    best, bn, bk = fr, n, k
    return best, bn, bk


@njit(cache=True, nogil=True)
def _events_kernel(
    w0,
    wd0,
    T,
    m,
    A,
    B,
    law_id,
    p,
    bps,
    w_left,
    w_right,
    periodic,
    locate,
    w,
    wd,
    work,
    counts,
    store,
    hs,
    sl,
    nsub,
    speed,
):
    """Integrate over [0, T] with m nominal steps, restarting at located breakpoint crossings.
    work : (6, N) scratch rows; counts = [crossings located, largest |w − b| at them, times…].
    store (with locate): every sub-step taken, in order, as hs[k] (its size) and sl[k, n] (the
    frozen f′ of site n in it), up to hs.size of them; nsub[0] = the number taken (> hs.size:
    the caller retries with room for it); speed[0] = the smallest |ẇ| of a site at its located
    crossing (∞ if none: transversality, 0 would be a tangential crossing)."""
    N = w0.size
    s = B.size
    ns = 0
    vmin = np.inf
    kw = np.empty((s, N))
    kwd = np.empty((s, N))
    g = np.empty(N + 2)
    pc = np.zeros(N, np.int64)
    w1, wd1, wt, wdt, yw = work[0], work[1], work[2], work[3], work[4]
    for n in range(N):
        w[n] = w0[n]
        wd[n] = wd0[n]
    fl = _law.force(law_id, p, w_left)
    fr = _law.force(law_id, p, w_right)
    h = T / m
    nev = 0
    resid = 0.0
    t = 0.0
    for _ in range(m):
        rem = h
        while rem > 0.0:
            if locate:
                _freeze(w, wd, p, pc)
            _step(
                w, wd, rem, A, B, law_id, p, fl, fr, periodic, kw, kwd, yw, g, w1, wd1, pc, locate
            )
            th, bn, bk = _earliest(w, w1, bps) if locate else (2.0, -1, -1)
            if bn < 0:
                if store and ns < hs.size:
                    _record(p, pc, rem, hs, sl, ns)
                ns += 1
                for n in range(N):
                    w[n] = w1[n]
                    wd[n] = wd1[n]
                t += rem
                break
            b = bps[bk]
            lo, flo, hi, fhi = 0.0, w[bn] - b, 1.0, w1[bn] - b
            side = 0
            for _it in range(100):  # Illinois on θ
                _step(
                    w,
                    wd,
                    th * rem,
                    A,
                    B,
                    law_id,
                    p,
                    fl,
                    fr,
                    periodic,
                    kw,
                    kwd,
                    yw,
                    g,
                    wt,
                    wdt,
                    pc,
                    True,
                )
                ft = wt[bn] - b
                if ft == 0.0 or hi - lo <= 4e-16:
                    break
                if (ft < 0.0) == (flo < 0.0):
                    lo, flo = th, ft
                    if side == -1:
                        fhi *= 0.5
                    side = -1
                else:
                    hi, fhi = th, ft
                    if side == 1:
                        flo *= 0.5
                    side = 1
                th = lo - flo * (hi - lo) / (fhi - flo)
                if not (lo < th < hi):
                    th = 0.5 * (lo + hi)
            # an earlier crossing by another pair inside [0, θ]: located on the next pass
            th2, bn2, _bk2 = _earliest(w, wt, bps)
            if bn2 >= 0 and (bn2 != bn or th2 < 0.5 * th):
                th = th * th2 * 0.999
                _step(
                    w,
                    wd,
                    th * rem,
                    A,
                    B,
                    law_id,
                    p,
                    fl,
                    fr,
                    periodic,
                    kw,
                    kwd,
                    yw,
                    g,
                    wt,
                    wdt,
                    pc,
                    True,
                )
            else:
                resid = max(resid, abs(wt[bn] - b))
                vmin = min(vmin, abs(wdt[bn]))
                if nev < counts.size - 2:
                    counts[2 + nev] = t + th * rem
                wt[bn] = b  # on the breakpoint: the next step starts on its far side
                nev += 1
            if store and ns < hs.size:
                _record(p, pc, th * rem, hs, sl, ns)
            ns += 1
            for n in range(N):
                w[n] = wt[n]
                wd[n] = wdt[n]
            t += th * rem
            rem -= th * rem
    counts[0] = nev
    counts[1] = resid
    nsub[0] = ns
    speed[0] = vmin


@njit(cache=True, nogil=True)
def _record(p, pc, h, hs, sl, k):
    """Sub-step k: its size and each site's frozen slope s_{pc[n]} (f′ of the frozen piece)."""
    m = int(p[0])
    hs[k] = h
    for n in range(pc.size):
        sl[k, n] = p[1 + m + pc[n]]


@dataclass(frozen=True)
class EventPeriodResult:
    """Final state of one period (w, wd at t = T) and the number of crossings located.

    With ``store_df``: hs (k,) the sizes of the k sub-steps taken (nominal steps cut at located
    crossings; Σ hs = T) and dfs (k, 1, N) each site's frozen f′ in each of them (the same at
    every stage), the input of :func:`fpucore.wave.period_map.tangent_columns`."""

    w: np.ndarray
    wd: np.ndarray
    crossings: int
    T: float
    m: int
    location_residual: float = 0.0  # largest |w − b| at a located crossing (before snapping)
    event_times: np.ndarray | None = None  # the first (up to 8) crossing times
    hs: np.ndarray | None = None
    dfs: np.ndarray | None = None
    crossing_speed: float = float("inf")  # smallest |ẇ| at a located crossing (transversality)


def integrate_events(
    law,
    w0,
    wd0,
    T: float,
    m: int,
    w_left: float = 0.0,
    w_right: float = 0.0,
    periodic: bool = False,
    locate: bool = True,
    tableau: Tableau = DOP853,
    store_df: bool = False,
) -> EventPeriodResult:
    """Eq. FPUstrain over [0, T] with m nominal RK steps and event location at the law's
    breakpoints (``locate=False``: plain fixed steps, for comparison).  ``store_df`` (with
    ``locate``): keep the sub-steps and their frozen f′ for the tangent map."""
    if not hasattr(law, "breakpoints"):
        raise ParameterError("law", type(law).__name__, "a piecewise-linear law")
    w0, wd0 = check_state(w0, wd0)
    T = require_finite("T", T)
    if T <= 0:
        raise ParameterError("T", T, "T > 0")
    m = check_m(m)
    w_left, w_right = require_finite("w_left", w_left), require_finite("w_right", w_right)
    N = w0.size
    store = bool(store_df and locate)
    cap = 2 * m + 16 if store else 1
    while True:
        w, wd, counts, nsub = np.empty(N), np.empty(N), np.zeros(10), np.zeros(1, np.int64)
        speed = np.full(1, np.inf)
        hs, sl = np.empty(cap), np.empty((cap, N) if store else (1, 1))
        _events_kernel(
            w0,
            wd0,
            T,
            m,
            tableau.A,
            tableau.B,
            law.law_id,
            law.params,
            np.asarray(law.breakpoints, dtype=np.float64),
            w_left,
            w_right,
            bool(periodic),
            bool(locate),
            w,
            wd,
            np.empty((6, N)),
            counts,
            store,
            hs,
            sl,
            nsub,
            speed,
        )
        k = int(nsub[0])
        if not store or k <= cap:
            break
        cap = k  # deterministic: the same run again, with room for every sub-step
    return EventPeriodResult(
        w,
        wd,
        int(counts[0]),
        T,
        m,
        float(counts[1]),
        counts[2 : 2 + int(counts[0])].copy(),
        hs[:k].copy() if store else None,
        sl[:k, None, :].copy() if store else None,
        float(speed[0]),
    )
