"""Steps 2–4 of a smooth law's construction (:mod:`fpucore.law.smooth`'s module doc): the class
check on the law's own convex interval (f(0) = 0, f′(0) > 0, the ends α, β polished to 30
digits and told apart from singularities, one inflection w*, the computable range), the
represented interval [α − W/2, β + W/2] shrunk to the expression's domain, and the piecewise
Chebyshev representation of the kernels.  Every refusal is a
:class:`~fpucore.law.smooth_class.ClassFailure` naming the reason."""

from __future__ import annotations

import math

import numpy as np

from fpucore.law import chebyshev as cheb
from fpucore.law.scale import require_computable
from fpucore.law.smooth_class import GRID, ClassFailure, convex_end, inflection

MARGIN = 0.5  # represented interval: W/2 beyond each end of the convex interval


def check_and_represent(law, fl, lg, mp, diag_df, diag_f) -> None:
    """The class check of ``law`` (a SmoothLaw being built) from its compiled evaluators (float64
    ``fl``, longdouble ``lg``, 30-digit ``mp``: f, f′, f″) and its representation: sets alpha,
    beta, w_star with their error bars, ``interval`` and ``_rep`` on it (ClassFailure if it is
    not a hardening–softening law)."""
    import mpmath

    set_ = object.__setattr__
    f, df, ddf = fl
    with np.errstate(all="ignore"):
        d0 = float(df(np.float64(0.0)))
    if not math.isfinite(d0):
        raise ClassFailure(f"f' is not finite at w = 0: {diag_df(0.0)}")
    with mpmath.workdps(40):
        try:
            f0 = mp[0](mpmath.mpf(0))
            f0 = abs(complex(f0))
        except (ValueError, ZeroDivisionError, TypeError):
            raise ClassFailure(f"f(0) is not defined: {diag_f(0.0)}") from None
    if not f0 <= 1e-25 * max(1.0, abs(d0)):
        raise ClassFailure(f"f(0) = {f0:.6g} is not 0 (the unstrained spring carries no force)")
    if not d0 > 0:
        raise ClassFailure(
            f"f'(0) = {d0:.6g} must be positive: the unstrained chain must be "
            "stable (0 inside the convex interval (alpha, beta))"
        )
    # the class is decided on float64 roots; only a law that passes pays for the 30-digit
    # polish and the representation (a refusal stays within ~10 ms of float64 scans)
    beta_root = convex_end(df, 1.0, diag_df)
    alpha_root = convex_end(df, -1.0, diag_df)
    assert beta_root is not None  # no upper end is refused inside convex_end
    for r, side in ((beta_root, 1.0), (alpha_root, -1.0)):
        not_a_pole(r, side, f, df, diag_f, diag_df)
    beta = beta_root.x
    alpha = alpha_root.x if alpha_root is not None else -math.inf
    if not beta > GRID[0]:  # f' vanishes before the first point of the class check's grid
        raise ClassFailure(
            f"the convex interval ends at beta = {beta:.3g}, within {GRID[0]:.0e} of w = 0: "
            "f'(w) vanishes below the resolution of the class check (a coefficient too large?)"
        )
    # a lower end that overflows/leaves the domain close to 0 is a domain error in (α, β)
    lo_probe = -np.logspace(-30, math.log10(4 * beta), 400)
    with np.errstate(all="ignore"):
        pv = np.asarray(df(lo_probe), dtype=float)
    pv_bad = ~np.isfinite(pv) & (lo_probe > alpha)
    if np.any(pv_bad):
        x = float(lo_probe[pv_bad][0])
        raise ClassFailure(
            f"f' is not finite at w = {x:.6g} inside the convex interval: {diag_df(x)}"
        )
    lo, hi = domain(fl, *margins(alpha, beta), alpha, beta, diag_f)
    n_grid = 8 * cheb.MAX_PANELS
    w_star_root = inflection(ddf, alpha if math.isfinite(alpha) else lo, beta, n_grid)
    try:  # too steep: refused before any longdouble or 30-digit work
        start = cheb.first_level(fl[2], lo, hi)
    except ValueError as exc:
        raise ClassFailure(
            f"the law cannot be represented on [{lo:.6g}, {hi:.6g}]: {exc}"
        ) from None
    # in the class: the 30-digit roots, and the represented interval from them
    beta, beta_err = beta_root.polished(mp[1])
    alpha, alpha_err = alpha_root.polished(mp[1]) if alpha_root else (-math.inf, 0.0)
    w_star, w_star_err = w_star_root.polished(mp[2])
    lo, hi = domain(fl, *margins(alpha, beta), alpha, beta, diag_f)
    set_(law, "alpha", alpha)
    set_(law, "beta", beta)
    set_(law, "alpha_error", alpha_err)
    set_(law, "beta_error", beta_err)
    set_(law, "w_star", w_star)
    set_(law, "w_star_error", w_star_err)
    c2 = float(df(np.float64(w_star)))
    require_computable("expression", law.text, alpha, beta, w_star, c2, "f'(w*)")
    try:
        rep = cheb.build(lg, mp, lo, hi, start)
    except ValueError as exc:
        raise ClassFailure(
            f"the law cannot be represented on [{lo:.6g}, {hi:.6g}]: {exc}"
        ) from None
    set_(law, "interval", (float(lo), float(hi)))
    set_(law, "_rep", rep)


def not_a_pole(r, side, f, df, diag_f, diag_df) -> None:
    """A sign change of f′ through a singularity (|f′| → ∞ at the float root, e.g. the
    1/(w + 1/2) of log(w + 1/2)) is no end of the convex interval: refused as the domain
    error it is (f beyond it), or as the singularity."""
    if r is None or r.a == r.b:
        return
    with np.errstate(all="ignore"):
        at = abs(float(df(np.float64(r.x))))
        ends = max(abs(float(df(np.float64(r.a)))), abs(float(df(np.float64(r.b)))))
    if at <= ends:
        return
    xb = r.x + side * 1e-6 * max(1.0, abs(r.x))
    with np.errstate(all="ignore"):
        if not math.isfinite(float(f(np.float64(xb)))):
            raise ClassFailure(
                f"f is not a finite real number at w = {xb:.6g} inside the "
                f"convex interval: {diag_f(xb)}"
            )
    raise ClassFailure(
        f"f' changes sign through a singularity at w = {r.x:.6g} (|f'| is "
        f"unbounded there), not through a zero: {diag_df(r.x)}"
    )


def margins(alpha: float, beta: float) -> tuple[float, float]:
    """[α − W/2, β + W/2], W = β − α (α = −∞: −β in its place)."""
    w_ref = alpha if math.isfinite(alpha) else -beta
    W = beta - w_ref
    return w_ref - MARGIN * W, beta + MARGIN * W


def domain(fl, lo, hi, alpha, beta, diag_f):
    """[lo, hi] shrunk to where f, f′, f″ are finite (a gap kept to the first bad point);
    a bad point inside [α, β] is a domain error."""
    for _ in range(4):
        x = np.linspace(lo, hi, 8193)
        with np.errstate(all="ignore"):
            ok = np.ones(x.size, bool)
            for g in fl[:3]:
                ok &= np.isfinite(np.asarray(g(x), dtype=float))
        if np.all(ok):
            return float(lo), float(hi)
        bad = x[~ok]
        inside = bad[(bad >= alpha) & (bad <= beta)]
        if inside.size:
            xb = float(inside[0])
            raise ClassFailure(
                f"f is not a finite real number at w = {xb:.6g} inside the "
                f"convex interval: {diag_f(xb)}"
            )
        above, below = bad[bad > beta], bad[bad < alpha]
        if above.size:
            hi = beta + 0.5 * (above[0] - beta)
        if below.size:
            lo = alpha - 0.5 * (alpha - below[-1])
    return float(lo), float(hi)
