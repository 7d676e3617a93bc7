"""Piecewise Chebyshev representation of a smooth law's f, f′, f″: the data of ``LAW_CHEB``.

One compiled kernel serves every smooth law (:mod:`.kernels`): the law's ``params`` hold the
interval [lo, hi] cut into ``npan`` uniform panels (the panel of w is ⌊(w − lo)·npan/(hi − lo)⌋,
arithmetic, no search) and on each panel the Chebyshev coefficients of degree ``NCOEF − 1`` of
f, f′ and f″, each fitted separately to the exact expression and its exact SymPy derivatives
(values in NumPy longdouble at the panel's Chebyshev points of the first kind), evaluated by
Clenshaw's recurrence.  Fitting f′ and f″ from their own expressions keeps the Jacobian of the
Newton solvers and the Floquet tangent flow as accurate as f itself (differentiating the series
of f loses a factor ~ NCOEF²·npan/(hi − lo) per derivative).

Layout of ``params`` (float64): ``[lo, hi, npan, NCOEF, npan/(hi − lo), 0, 0, 0]`` then the
coefficients of f (npan × NCOEF, row per panel), of f′ and of f″.  Outside [lo, hi] the kernels
return NaN: a state that leaves the represented interval is never extrapolated.

The number of panels doubles from 16 (from the first level whose float64 fit of f″ is within
:data:`SKIP`, :func:`first_level`: the same result) until the measured error of each of f, f′,
f″ — the largest difference between the Clenshaw evaluation in float64 (the kernel's own
operations) and the longdouble exact expression at 3 points per Chebyshev node interval,
relative to the function's largest magnitude on [lo, hi] — is below :data:`TARGET` (at most
:data:`MAX_PANELS`).
The longdouble reference is itself checked against mpmath at 30 digits at :data:`N_MP` points;
its own error is added; the stored error is that measurement × :data:`SAFETY` + 8 eps × scale
(sampled, not a bound: the rounding of Clenshaw between the check points).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import cast

import numpy as np

NCOEF = 10
HEADER = 8
MIN_PANELS, MAX_PANELS = 16, 4096
TARGET = 4e-14  # relative error of f, f′, f″ at which panel doubling stops
ACCEPT = 1e-9  # relative error above which a law is refused (cannot be represented)
N_MP = 24  # points of the 30-digit check
MP_DIGITS = 30
SAFETY = 2.0
# still unresolved here (error > 1 %) means the law varies on a scale the 4096 panels will not
# reach either (convergence is ~ (h/scale)^NCOEF once resolved): refused at once, not after 4 s
UNRESOLVED_PANELS, UNRESOLVED = 256, 1e-2
SKIP = 1e-6  # float64 fit of f″ still this far off: a level the longdouble doubling skips
EPS = float(np.finfo(float).eps)


@dataclass(frozen=True)
class RepresentationError:
    """Measured error of the kernel's f, f′, f″ on ``interval`` = [lo, hi] (absolute, and
    relative to ``scale`` = the largest |f|, |f′|, |f″| there), ``panels``, ``points`` checked
    against the longdouble expression and ``mp_points`` against mpmath at ``mp_digits``."""

    f: float
    df: float
    ddf: float
    interval: tuple[float, float]
    scale: tuple[float, float, float]
    panels: int
    points: int
    mp_points: int
    mp_digits: int

    @property
    def relative(self) -> tuple[float, float, float]:
        rel = tuple(e / s if s > 0 else e for e, s in zip((self.f, self.df, self.ddf), self.scale))
        return cast("tuple[float, float, float]", rel)

    def __str__(self) -> str:
        lo, hi = self.interval
        return (
            f"|f - f_rep| <= {self.f:.2g}, |f' - f'_rep| <= {self.df:.2g}, "
            f"|f'' - f''_rep| <= {self.ddf:.2g} on [{lo:.6g}, {hi:.6g}] ({self.panels} "
            f"panels of degree {NCOEF - 1})"
        )


@functools.cache
def _tables():
    import mpmath

    m = NCOEF
    k = np.arange(m, dtype=np.longdouble)
    pi = np.longdouble(mpmath.nstr(mpmath.pi, 25))
    x = np.cos(pi * (2 * k + 1) / (2 * m))  # first-kind points on [−1, 1]
    T = np.cos(np.outer(np.arccos(x), k))  # T[i, j] = T_j(x_i)
    fit = (2.0 / m) * T  # c_j = (2/m) Σ_i v_i T_j(x_i), c_0 halved
    fit[:, 0] *= 0.5
    return x, fit


def nodes(lo: float, hi: float, npan: int) -> np.ndarray:
    """(npan, NCOEF) longdouble Chebyshev points of every panel."""
    x, _ = _tables()
    L = np.longdouble(lo)
    h = (np.longdouble(hi) - L) / npan
    a = L + h * np.arange(npan, dtype=np.longdouble)
    return a[:, None] + 0.5 * h * (x[None, :] + 1)


def fit(values: np.ndarray) -> np.ndarray:
    """Chebyshev coefficients (npan, NCOEF) float64 of panel values at :func:`nodes`."""
    _, F = _tables()
    return (values @ F).astype(np.float64)


def clenshaw(coef: np.ndarray, lo: float, hi: float, w: np.ndarray, start=None) -> np.ndarray:
    """The kernel's evaluation (same operations, vectorised): NaN outside [lo, hi]; ``start``
    (npan,) is added per panel (the potential's cumulative integral)."""
    npan = coef.shape[0]
    w = np.asarray(w, dtype=np.float64)
    inv_h = npan / (hi - lo)
    x = (w - lo) * inv_h
    ok = (x >= 0.0) & (x <= npan)
    k = np.minimum(np.where(ok, x, 0.0).astype(np.int64), npan - 1)
    t = 2.0 * (np.where(ok, x, 0.0) - k) - 1.0
    cT = np.ascontiguousarray(coef.T)  # gather one coefficient row at a time (contiguous)
    b1 = np.zeros_like(t)
    b2 = np.zeros_like(t)
    for j in range(coef.shape[1] - 1, 0, -1):
        b1, b2 = cT[j][k] + 2.0 * t * b1 - b2, b1
    out = cT[0][k] + t * b1 - b2
    if start is not None:
        out = out + start[k]
    return np.where(ok, out, np.nan)


def _check_points(lo: float, hi: float, npan: int) -> np.ndarray:
    """Points between and beside the nodes: 3 per node interval (float64)."""
    n = npan * NCOEF * 3
    return np.linspace(lo, hi, n + 1)


@dataclass(frozen=True)
class Representation:
    params: np.ndarray
    coef: tuple[np.ndarray, np.ndarray, np.ndarray]
    error: RepresentationError

    def value(self, k: int, w):
        """f (k = 0), f′ (1), f″ (2) of the representation at w (NaN outside)."""
        lo, hi = self.error.interval
        return clenshaw(self.coef[k], lo, hi, w)


def _f64_error(ddf, lo: float, hi: float, npan: int) -> float:
    """Relative error of f″ fitted in float64 on ``npan`` panels (NaN if not finite there)."""
    X = np.asarray(nodes(lo, hi, npan), dtype=np.float64)
    P = _check_points(lo, hi, npan)
    with np.errstate(all="ignore"):
        v = np.asarray(ddf(X), dtype=np.float64)
        ref = np.asarray(ddf(P), dtype=np.float64)
    if not (np.all(np.isfinite(v)) and np.all(np.isfinite(ref))):
        return float("nan")
    _, F = _tables()
    c = v @ F.astype(np.float64)
    scale = float(max(np.max(np.abs(v)), np.max(np.abs(ref))))
    return float(np.max(np.abs(clenshaw(c, lo, hi, P) - ref))) / scale if scale > 0 else 0.0


def first_level(ddf, lo: float, hi: float) -> int:
    """The panel count at which :func:`build` starts, from a float64 scan of f″ (the hardest
    of the three to represent): panels double from :data:`MIN_PANELS` while the float64 fit
    misses by more than :data:`SKIP` relative — levels where the longdouble fit would miss by
    as much (≫ the float64 rounding), so :func:`build` would not stop there: skipping them
    leaves its result bit for bit the same and saves their longdouble work.  Raises
    ValueError at once (a few ms of float64) where :func:`build` would refuse the law as
    unresolved: still above :data:`UNRESOLVED` at :data:`UNRESOLVED_PANELS`."""
    npan = MIN_PANELS
    while npan < MAX_PANELS:
        rel = _f64_error(ddf, lo, hi, npan)
        if not rel > SKIP:  # resolved to SKIP, or not finite (build names the point)
            break
        if npan >= UNRESOLVED_PANELS and rel > UNRESOLVED:
            raise ValueError(unresolved_reason(npan, lo, hi, rel))
        npan *= 2
    return npan


def unresolved_reason(npan: int, lo: float, hi: float, rel: float) -> str:
    return (
        f"the law varies on a scale below 1/{npan * NCOEF} of [{lo:.6g}, {hi:.6g}] "
        f"(relative error {rel:.2g} with {npan} panels): too steep to represent"
    )


def build(long_fns, mp_fns, lo: float, hi: float, start: int = MIN_PANELS) -> Representation:
    """The representation of (f, f′, f″) on [lo, hi]; ``long_fns`` evaluate the exact
    expressions on longdouble arrays, ``mp_fns`` on one mpmath number; panels double from
    ``start`` (:func:`first_level`).  Raises ValueError with the reason when the values are not
    finite or the error stays above :data:`ACCEPT`."""
    npan = start
    while True:
        X = nodes(lo, hi, npan)
        vals = [np.asarray(g(X), dtype=np.longdouble) for g in long_fns]
        for v in vals:
            if not np.all(np.isfinite(v)):
                bad = X[~np.isfinite(v)].ravel()[0]
                raise ValueError(f"not finite at w = {float(bad):.10g}")
        coef = [fit(v) for v in vals]
        P = _check_points(lo, hi, npan)
        Pl = P.astype(np.longdouble)
        errs, scales = [], []
        for g, c, v in zip(long_fns, coef, vals):
            ref = np.asarray(g(Pl), dtype=np.longdouble)
            scale = float(max(np.max(np.abs(v)), np.max(np.abs(ref))))
            errs.append(float(np.max(np.abs(clenshaw(c, lo, hi, P) - ref))))
            scales.append(scale)
        rel = [e / s if s > 0 else e for e, s in zip(errs, scales)]
        if max(rel) <= TARGET or npan >= MAX_PANELS:
            break
        if npan >= UNRESOLVED_PANELS and max(rel) > UNRESOLVED:  # refuse fast (≤ 50 ms)
            raise ValueError(unresolved_reason(npan, lo, hi, max(rel)))
        npan *= 2
    if max(rel) > ACCEPT:
        which = ("f", "f'", "f''")[int(np.argmax(rel))]
        raise ValueError(
            f"{which} cannot be represented to a relative {ACCEPT:g} with {MAX_PANELS} panels "
            f"(error {max(rel):.2g}): the law varies too steeply on [{lo:.6g}, {hi:.6g}]"
        )
    # the longdouble reference against mpmath at 30 digits, and the representation directly
    import mpmath

    mp_err = [0.0, 0.0, 0.0]
    pts = lo + (hi - lo) * 0.5 * (1 - np.cos(np.pi * (np.arange(N_MP) + 0.5) / N_MP))
    with mpmath.workdps(MP_DIGITS):
        for k, (g, gm, c) in enumerate(zip(long_fns, mp_fns, coef)):
            ref = np.array([float(gm(mpmath.mpf(float(x)))) for x in pts])
            lv = np.asarray(g(pts.astype(np.longdouble)), dtype=np.float64)
            rv = clenshaw(c, lo, hi, pts)
            mp_err[k] = max(float(np.max(np.abs(lv - ref))), 0.0)
            errs[k] = max(errs[k] + mp_err[k], float(np.max(np.abs(rv - ref))))
    # a measurement on sample points, not a bound: x SAFETY, plus the rounding of one Clenshaw
    # evaluation anywhere (8 eps of the function's scale)
    errs = [SAFETY * e + 8 * EPS * sc for e, sc in zip(errs, scales)]
    params = np.concatenate(
        [np.array([lo, hi, npan, NCOEF, npan / (hi - lo), 0.0, 0.0, 0.0])]
        + [c.ravel() for c in coef]
    )
    err = RepresentationError(
        errs[0],
        errs[1],
        errs[2],
        (float(lo), float(hi)),
        cast("tuple[float, float, float]", tuple(scales)),
        npan,
        int(P.size),
        N_MP,
        MP_DIGITS,
    )
    return Representation(
        params, cast("tuple[np.ndarray, np.ndarray, np.ndarray]", tuple(coef)), err
    )
