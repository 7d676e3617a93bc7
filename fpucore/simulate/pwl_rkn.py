"""RKN stepper of the chain with event location at the breakpoints of a piecewise-linear law.

For a PL law the right-hand side of eq. FPUstrain, ẅ_n = Δf(w)_n, is only Lipschitz: d³w/dt³
jumps when a bond's strain crosses a breakpoint, and a step that contains the crossing loses the
method's order (the period map's measurement: DOP853 8 → 2.5, fpucore.wave.period_events).  This
stepper keeps the order (state, tableaux, error control and observer as :func:`fpucore.simulate.
rkn.rkn_chunk`):

* **frozen regimes**: within every (sub-)step each bond's force is its piece's linear formula,
  the piece frozen to the one at the step's start (a bond exactly on a breakpoint — a located
  crossing — takes the piece its ẇ moves into).  Between crossings the chain is then one linear
  system, integrated at the method's order even where an inner stage overshoots a breakpoint.
* **location**: a trial step of the size the controller proposes is taken; if some bond's strain
  changes side of a breakpoint in it (a sign change of w − b between the step's ends), the
  earliest such crossing (linear estimate over all bonds) is located by the Illinois method on
  the step fraction θ, each trial value being one RKN sub-step of θh from the step's start; the
  sub-step up to it is accepted (observer, guard), the bond's strain is set to the breakpoint,
  and stepping restarts there with the controller's step.  If the located sub-step shows another
  bond crossing before it, the sub-step is cut short of that one (as in period_events).
* **cost**: an RKN sub-step's value at bond n depends only on bonds n ± (stages + 1) (each stage
  widens the stencil of Δ by one), so the Illinois iterations integrate a window of 2R + 1 bonds,
  R = s + 2, copied from the chain (bit-identical values at the located bond: the same operations
  per element); each crossing then costs about two whole-chain steps (the trial that saw it and
  the accepted sub-step), whatever its iteration count.  Locating every crossing is what keeps
  the order, and the number of crossings — not the step the smooth dynamics would allow — then
  sets the cost: a chain whose waves make K crossings per unit time takes ≳ K steps per unit
  time.  Measured (benchmarks/bench_pwl_simulate.py): the degenerate trilinear Riemann run at the
  paper's size (L = 3600, t = 300) locates 90 681 crossings in 104 597 steps — 30× the cubic
  run's steps, 130–160× its CPU time (87.7 s against 0.68 s), with the energy drift at 5e-14.
  Splitting one trial step at all its crossings in order instead would save the repeated trials
  but not the sub-steps (each crossing changes the linear system for the whole rest of the step,
  so every later piece must be re-integrated from it), i.e. at most the factor ~2 of the trials;
  a per-step bound on the crossings would give up exactness.
* **missed crossings**: a bond that leaves its frozen piece at an inner stage and is back at the
  step's end (in and out within the step) is caught by the stage values (the step is retried up
  to that stage node); a bond set on a breakpoint that goes back across it is bracketed from an
  inside point (halving the fraction), and one that leaves at once (ẇ ≈ 0 on b) takes the other
  piece; if that one leaves at once too (a bond at rest on b, e.g. Riemann data on a breakpoint,
  pushed out of either regime by its neighbours), the step is taken without location and counted
  (``evs[2]``, details["unlocated_tangencies"]): the order is not kept across that step.
* ``locate=False`` evaluates the true law at every stage and takes the steps whole (the plain
  RKN stepper), for the tests that show what location buys.

Crossings are counted (``evs[0]``) with the largest |w − b| at a located crossing before it is
set (``evs[1]``).  A crossing that no stage value shows (an excursion beyond b shorter than the
spacing of the stage nodes) is not seen, and keeps the reduced order.

The frozen pieces, their force and the crossing tests: :mod:`fpucore.simulate.pwl_pieces`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from fpucore.simulate.kernels import combo, step_factor
from fpucore.simulate.layout import (
    BC_LOAD,
    ST_BUDGET,
    ST_LEFT_CONVEX,
    ST_NONFINITE,
    ST_STEP_UNDERFLOW,
)
from fpucore.simulate.observer import check_convex, observe
from fpucore.simulate.pwl_pieces import (
    accel_frozen,
    cut_fraction,
    double_crossing,
    earliest,
    flip_piece,
    freeze,
    mark_outside,
    snap_crossings,
)
from fpucore.simulate.rkn import accel, rkn_err, sumsq2


@njit(cache=True, nogil=True)
def _F(q, L, law_id, p, pc, frozen, bc, fL, fR, g, out):
    if frozen:
        accel_frozen(q, L, p, pc, bc, fL, fR, g, out)
    else:
        accel(q, L, law_id, p, bc, fL, fR, g, out)


@njit(cache=True, nogil=True)
def _trial(cur, hh, pair, pat, K, rows, L, law_id, p, pc, pb, cfirst, frozen, bc, fL, fR, g, Y,
           nxt, e, ed, zero, want_err):  # fmt: skip
    """One RKN step of size hh from (cur, K[iqd]) with F(cur) in K[f0]: q₁ into nxt, q̇₁ into
    K[iqd1], F(q₁) into K[fn] for an FSAL pair, the error vectors into (e, ed) if want_err; then
    (frozen) also cfirst[n] = the first stage node c_i at which bond n's stage value left its
    frozen piece pb[:, n] (2.0 if none; reset here).
    rows = (f0, fn, iqd, iqd1); pat = (stg, cnt, wix, wcnt, rws, cf) the sparse patterns."""
    C, A, B, BP, E, EP, fsal = pair.C, pair.A, pair.B, pair.BP, pair.E, pair.EP, pair.fsal
    stg, cnt, wix, wcnt, rws, cf = pat
    f0, fn, iqd, iqd1 = rows[0], rows[1], rows[2], rows[3]
    s = B.size
    nst = s - 1 if fsal else s
    h2 = hh * hh
    if want_err and frozen:
        cfirst[:L] = 2.0
    for i in range(1, nst):
        rws[0] = iqd
        cf[0] = C[i] * hh
        for k in range(cnt[i]):
            j = stg[i, k]
            rws[k + 1] = f0 if j == 0 else j
            cf[k + 1] = h2 * A[i, j]
        combo(cur, K, rws, cf, cnt[i] + 1, Y)
        if want_err and frozen:
            mark_outside(Y, L, pb, C[i], cfirst)
        _F(Y, L, law_id, p, pc, frozen, bc, fL, fR, g, K[i])
    rws[0] = iqd
    cf[0] = hh
    for k in range(wcnt[0]):
        j = wix[0, k]
        rws[k + 1] = f0 if j == 0 else j
        cf[k + 1] = h2 * B[j]
    combo(cur, K, rws, cf, wcnt[0] + 1, nxt)
    if fsal:
        _F(nxt, L, law_id, p, pc, frozen, bc, fL, fR, g, K[fn])
    for k in range(wcnt[1]):
        j = wix[1, k]
        rws[k] = f0 if j == 0 else (fn if (fsal and j == s - 1) else j)
        cf[k] = hh * BP[j]
    combo(K[iqd], K, rws, cf, wcnt[1], K[iqd1])
    if want_err:
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


@njit(cache=True, nogil=True)
def patterns(pair):
    """The sparse patterns (stg, cnt, wix, wcnt, rws, cf) of an RKN pair (as in rkn_chunk)."""
    A, B = pair.A, pair.B
    s = B.size
    stg = np.zeros((s, s), np.int64)
    cnt = np.zeros(s, np.int64)
    for i in range(s):
        for j in range(i):
            if A[i, j] != 0.0:
                stg[i, cnt[i]] = j
                cnt[i] += 1
    wts = np.zeros((4, s))
    wts[0, :] = B
    wts[1, :] = pair.BP
    wts[2, :] = pair.E
    wts[3, :] = pair.EP
    wix = np.zeros((4, s), np.int64)
    wcnt = np.zeros(4, np.int64)
    for k in range(4):
        for j in range(s):
            if wts[k, j] != 0.0:
                wix[k, wcnt[k]] = j
                wcnt[k] += 1
    return stg, cnt, wix, wcnt, np.zeros(s + 8, np.int64), np.zeros(s + 8)


@njit(cache=True, nogil=True)
def _probe(hh, at):
    """w_bn − b after a frozen sub-step of hh: on the window of bonds w0 … w0 + Lw − 1 (copied
    into WW[0], KW by the caller) if ``win``, else on the whole chain.  ``at``: the located
    crossing's arguments (win, cur, bn, b, w0, R, Lw, pair, pat, K, KW, WW, rows, L, law_id, p,
    pc, pb, cfirst, bc, fL, fR, g, gw, Y, nxt, e, ed, zero), one tuple for every trial θ."""
    (win, cur, bn, b, w0, R, Lw, pair, pat, K, KW, WW, rows, L, law_id, p, pc, pb, cfirst, bc, fL,
     fR, g, gw, Y, nxt, e, ed, zero) = at  # fmt: skip
    if win:
        _trial(WW[0], hh, pair, pat, KW, rows, Lw, law_id, p, pc[w0 : w0 + Lw], pb[:, w0 : w0 + Lw],
               cfirst, True, BC_LOAD, 0.0, 0.0, gw, WW[1], WW[2], WW[3], WW[3], WW[4],
               False)  # fmt: skip
        return WW[2, R] - b
    _trial(cur, hh, pair, pat, K, rows, L, law_id, p, pc, pb, cfirst, True, bc, fL, fR, g, Y, nxt,
           e, ed, zero, False)  # fmt: skip
    return nxt[bn] - b


@njit(cache=True, nogil=True)
def pwl_rkn_chunk(q, t, t_stop, h, step_limit, pair, ctl, chain, work, obs, pc, pb, cfirst,
                  KW, WW, evs, locate):  # fmt: skip
    """Advance (q, q̇) from t to t_stop as :func:`fpucore.simulate.rkn.rkn_chunk` (same arguments,
    work layout and return value), with frozen regimes and event location at the breakpoints
    the law's breakpoints (module docstring) if ``locate``.  pc (L,) int64, pb (2, L), cfirst
    (L,) work; KW (s+3, 2R+2), WW (5, 2R+2)
    the Illinois window's work (R = s + 2); evs (3,) = [crossings located, largest |w − b| at
    one, steps taken unlocated at a tangency], accumulated over calls."""
    rtol, atol, alpha, beta = ctl.rtol, ctl.atol, ctl.lo, ctl.hi
    L, law_id, p, bc, fL, fR = chain.L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR
    K, W, g, stats, bad = work.K, work.W, work.g, work.stats, work.bad
    s = pair.B.size
    fsal, err_exp = pair.fsal, pair.err_exp
    nn = q.size
    f0 = 0
    fn = s - 1 if fsal else s
    iqd = s + 1
    iqd1 = s + 2
    pat = patterns(pair)
    rows = np.zeros(4, np.int64)
    R = s + 2
    Lw = 2 * R + 1
    gw = np.zeros(Lw + 2)
    Y = W[0]
    cur = q
    nxt = W[1]
    in_q = True
    e = W[2]
    ed = W[3]
    zero = W[4]
    status = 0
    if locate:
        freeze(cur, K[iqd], L, p, pc, pb)
    hforce = 0.0  # the controller's step, kept over a retry up to a double crossing
    retried = False
    nflip = 0  # pieces flipped for bonds on their breakpoint in this step, the last one's bond
    lastflip = -1
    skiploc = False  # the step after an unresolved tangency is taken without location
    while t < t_stop:
        if stats[0] >= step_limit:
            status = ST_BUDGET
            break
        rem = t_stop - t
        clamped = h >= rem
        hh = rem if clamped else h
        rows[0], rows[1], rows[2], rows[3] = f0, fn, iqd, iqd1
        _trial(cur, hh, pair, pat, K, rows, L, law_id, p, pc, pb, cfirst, locate, bc, fL, fR, g, Y,
               nxt, e, ed, zero, True)  # fmt: skip
        stats[2] += s - 1
        e2 = rkn_err(cur, nxt, K[iqd], K[iqd1], e, ed, W[5], W[6], rtol, atol)
        err = math.sqrt(e2 / (2 * nn))
        if not math.isfinite(err):
            h = 0.2 * hh
            stats[1] += 1
            if h < 1e-14 * max(1.0, abs(t)):
                status = ST_NONFINITE
                break
            continue
        if err >= 1.0:
            h = hh * step_factor(err, err_exp)
            stats[1] += 1
            if h < 1e-14 * max(1.0, abs(t)):
                status = ST_STEP_UNDERFLOW
                break
            continue
        h_next = hh * step_factor(err, err_exp)
        th, bn, bb = earliest(cur, nxt, L, pb) if locate and not skiploc else (2.0, -1, 0.0)
        if locate and not retried and not skiploc:
            cs = double_crossing(nxt, L, pb, cfirst)
            if cs < th:  # in and out inside the step: retry up to the stage node beyond it
                h = cs * hh
                hforce = h_next if hforce == 0.0 else hforce
                retried = True
                continue
        snap = -1
        if bn >= 0:  # a crossing inside the step: locate it, take the sub-step up to it
            b = bb
            lo, flo, hi, fhi = 0.0, cur[bn] - b, 1.0, nxt[bn] - b
            win = bn - R >= 0 and bn + R + 1 <= L
            w0 = bn - R
            if win:
                for r in range(Lw):
                    WW[0, r] = cur[w0 + r]
                    KW[f0, r] = K[f0, w0 + r]
                    KW[iqd, r] = K[iqd, w0 + r]
                WW[0, Lw] = 0.0
                KW[f0, Lw] = 0.0
                KW[iqd, Lw] = 0.0
            at = (win, cur, bn, b, w0, R, Lw, pair, pat, K, KW, WW, rows, L, law_id, p, pc, pb,
                  cfirst, bc, fL, fR, g, gw, Y, nxt, e, ed, zero)  # fmt: skip
            if flo == 0.0:  # started on b (a located crossing) and went back: an inside point
                th = 0.5
                for _h in range(60):
                    ft = _probe(th * hh, at)
                    if ft != 0.0 and (ft < 0.0) != (fhi < 0.0):
                        lo, flo = th, ft
                        break
                    if ft != 0.0:
                        hi, fhi = th, ft
                    th *= 0.5
                if flo == 0.0:  # it leaves at once (ẇ ≈ 0 on b): the other piece, retried
                    if bn != lastflip and nflip <= 2 * L:  # each bond flips once in turn
                        flip_piece(bn, b, p, pc, pb)
                        nflip += 1
                        lastflip = bn
                    else:  # both pieces leave at once (a bond on b at rest, pushed both ways
                        # by its neighbours' regimes): this step is taken unlocated, and counted
                        skiploc = True
                        evs[2] += 1
                    continue
                th = lo - flo * (hi - lo) / (fhi - flo)
            side = 0
            for _it in range(100):  # Illinois on θ
                ft = _probe(th * hh, at)
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
            # another bond crossing inside [0, θ] (checked on the located sub-step): simultaneous
            # (ending on its breakpoint to pwl_pieces.SNAP_TOL) it is set with bn; earlier, the
            # step is retried up to it (a fresh trial, so that crossing is located in turn)
            _trial(cur, th * hh, pair, pat, K, rows, L, law_id, p, pc, pb, cfirst, True, bc, fL, fR,
                   g, Y, nxt, e, ed, zero, True)  # fmt: skip
            stats[2] += s - 1
            cut = cut_fraction(cur, nxt, L, pb, bn)
            if cut < 2.0:
                h = th * cut * hh
                hforce = h_next if hforce == 0.0 else hforce
                continue
            snap = bn
            hh = th * hh
            clamped = False
        if hforce > 0.0:
            h_next = hforce
            hforce = 0.0
        retried = False
        nflip = 0
        lastflip = -1
        skipped = skiploc
        skiploc = False
        if not fsal:
            _F(nxt, L, law_id, p, pc, locate, bc, fL, fR, g, K[fn])
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
        h = h_next
        stats[0] += 1
        stats[3] += math.sqrt(sumsq2(e, ed) / (2 * nn))
        if err > stats[4]:
            stats[4] = err
        if snap >= 0:  # on the breakpoint: the next step starts in the piece it moves into
            snap_crossings(cur, L, pb, snap, bb, evs)
        if locate and (bn >= 0 or skipped):
            freeze(cur, K[iqd], L, p, pc, pb)
            accel_frozen(cur, L, p, pc, bc, fL, fR, g, K[f0])
            stats[2] += 1
        if check_convex(cur, L, alpha, beta, bad):
            status = ST_LEFT_CONVEX
            break
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
