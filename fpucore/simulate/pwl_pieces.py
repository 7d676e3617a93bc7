"""A piecewise-linear law's frozen pieces and the crossings of their ends, for the RKN stepper
with event location (:mod:`fpucore.simulate.pwl_rkn`, whose docstring gives the method).

Each bond n of the chain has a frozen piece pc[n] of the law for the coming step, with its ends
pb[:, n] (the breakpoints around it, ±inf beyond the outer ones); p is the law's parameter
array (m = p[0] breakpoints p[1 … m], then the moduli and the forces at the breakpoints).
Here: the pieces frozen and flipped, the force of the frozen pieces, and the crossings of
their ends in a step — found, dated by a linear estimate, and set onto the breakpoint.
"""

from __future__ import annotations

import math

from numba import njit

from fpucore.simulate.rkn import accel_from_forces


@njit(cache=True, nogil=True)
def freeze(q, qd, L, p, pc, pb):
    """pc[n] = the piece of bond n for the coming step: the piece of w_n = q[n]; a strain exactly
    on a breakpoint takes the piece that ẇ_n = qd[n] moves it into.  pb (2, L): its ends."""
    m = int(p[0])
    for n in range(L):
        x = q[n]
        j = 0
        while j < m and x >= p[1 + j]:
            j += 1
        if j > 0 and x == p[j] and qd[n] < 0.0:
            j -= 1
        pc[n] = j
        pb[0, n] = p[j] if j > 0 else -math.inf
        pb[1, n] = p[1 + j] if j < m else math.inf


@njit(cache=True, nogil=True)
def accel_frozen(q, L, p, pc, bc, fL, fR, g, out):
    """F(q) as :func:`fpucore.simulate.rkn.accel`, each bond's force by the linear formula of its
    frozen piece pc[n] (also beyond the piece)."""
    m = int(p[0])
    for n in range(L):
        j = pc[n]
        k = j - 1 if j > 0 else 0
        g[n + 1] = p[2 + 2 * m + k] + p[1 + m + j] * (q[n] - p[1 + k])
    accel_from_forces(L, bc, fL, fR, g, out)


@njit(cache=True, nogil=True)
def flip_piece(n, b, p, pc, pb):
    """Bond n, on breakpoint b, into the piece on b's other side."""
    m = int(p[0])
    j = pc[n] + 1 if pb[1, n] == b else pc[n] - 1
    pc[n] = j
    pb[0, n] = p[j] if j > 0 else -math.inf
    pb[1, n] = p[1 + j] if j < m else math.inf


@njit(cache=True, nogil=True)
def exit_bound(x, n, pb):
    """The end of bond n's frozen piece that the strain x lies beyond (NaN if x is inside)."""
    if x < pb[0, n]:
        return pb[0, n]
    if x >= pb[1, n]:
        return pb[1, n]
    return math.nan


@njit(cache=True, nogil=True)
def earliest(w, w1, L, pb):
    """(fraction, bond, breakpoint) of the earliest crossing in the step w → w1: a bond whose end
    strain lies outside its frozen piece pb has crossed the end it lies beyond, at the fraction
    (w − b)/(w − w1) (linear estimate; 0.5 for a bond that started on b, set there by a located
    crossing, and went back); bond −1 if none."""
    best, bn, bb = 2.0, -1, 0.0
    for n in range(L):
        x = w1[n]
        if pb[0, n] <= x < pb[1, n]:
            continue
        b = exit_bound(x, n, pb)
        d0 = w[n] - b
        fr = d0 / (d0 - (x - b)) if d0 != 0.0 else 0.5
        if fr < best:
            best, bn, bb = fr, n, b
    return best, bn, bb


@njit(cache=True, nogil=True)
def mark_outside(Y, L, pb, c, cfirst):
    """cfirst[n] = min(cfirst[n], c) for the bonds whose stage value Y[n] left the frozen piece
    (a branch-free count first: almost always none)."""
    nout = 0
    for n in range(L):
        x = Y[n]
        nout += 0 if ((x >= pb[0, n]) & (x < pb[1, n])) else 1
    if nout:
        for n in range(L):
            x = Y[n]
            if not (pb[0, n] <= x < pb[1, n]) and c < cfirst[n]:
                cfirst[n] = c


@njit(cache=True, nogil=True)
def double_crossing(w1, L, pb, cfirst):
    """Smallest stage node c_i at which a bond was outside its frozen piece although it is back
    inside at the step's end w1 — in and out within the step, which :func:`earliest` cannot see
    (2.0 if none): a step to c_i then ends beyond the breakpoint and the crossing is located."""
    best = 2.0
    for n in range(L):
        c = cfirst[n]
        if c < best and pb[0, n] <= w1[n] < pb[1, n]:
            best = c
    return best


#: |w − b| (relative to max(1, |b|)) of a crossing simultaneous with the located one
SNAP_TOL = 1e-12


@njit(cache=True, nogil=True)
def cut_fraction(w, w1, L, pb, bn):
    """Fraction (as :func:`earliest`) of the earliest crossing in w → w1 by a bond other than bn
    that does not end on its breakpoint (to SNAP_TOL); 2.0 if none."""
    best = 2.0
    for n in range(L):
        x = w1[n]
        if n == bn or pb[0, n] <= x < pb[1, n]:
            continue
        b = exit_bound(x, n, pb)
        if abs(x - b) > SNAP_TOL * max(1.0, abs(b)):
            d0 = w[n] - b
            fr = d0 / (d0 - (x - b)) if d0 != 0.0 else 0.5
            if fr < best:
                best = fr
    return best


@njit(cache=True, nogil=True)
def snap_crossings(w1, L, pb, bn, bb, evs):
    """Set bond bn to its located breakpoint bb, and every other bond that ended outside its
    frozen piece to the end it crossed, in w1; count them in evs[0], their largest |w1 − b| in
    evs[1]."""
    for n in range(L):
        x = w1[n]
        if n == bn:
            b = bb
        elif pb[0, n] <= x < pb[1, n]:
            continue
        else:
            b = exit_bound(x, n, pb)
        if abs(x - b) > evs[1]:
            evs[1] = abs(x - b)
        evs[0] += 1
        w1[n] = b
