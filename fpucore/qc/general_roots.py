"""Numerical building blocks of the general-law QC (paper §3, :mod:`fpucore.qc.general`):
Gauss–Legendre rules, the cancellation-free Rayleigh slope, driving force, tangency and first
integral, and bracketed root finding with error bars (see that module's docstring for the forms)."""

from __future__ import annotations

import functools
import math
from collections.abc import Callable

import numpy as np
from scipy.optimize import brentq

from fpucore.law import CubicLaw, HardeningSofteningLaw, PolynomialLaw

EPS = float(np.finfo(float).eps)
GL_HI, GL_LO = 24, 16  # outer quadrature (ξ tables, energy): value and error-bar orders
U_MAX = 22.0  # sech²(22) ≈ 3e-19: beyond it the substituted integrands are at their limit
K_INV = 17  # Chebyshev–Lobatto points per panel for the inverse map s(ξ)
SECH2_HALF = math.asinh(1.0)  # sech²u = 1/2 here: switch between the two expansions of R̃


@functools.cache
def gauss_legendre01(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [0, 1] (cached, read-only: computing them dominated
    the cost of a solitary wave)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x, w = 0.5 * (x + 1.0), 0.5 * w
    x.flags.writeable = w.flags.writeable = False
    return x, w


@functools.cache
def composite01(panels: int, n: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss–Legendre on [0, 1]: ``panels`` equal panels of n nodes (read-only)."""
    if panels == 1:
        return gauss_legendre01(n)
    x0, w0 = gauss_legendre01(n)
    x = ((np.arange(panels)[:, None] + x0[None, :]) / panels).ravel()
    w = np.tile(w0, panels) / panels
    x.flags.writeable = w.flags.writeable = False
    return x, w


def inner_rule(law: HardeningSofteningLaw) -> tuple[np.ndarray, np.ndarray]:
    """Nodes for the t-integrals: exact for a polynomial law (integrands have degree ≤ n),
    ``law.quadrature_panels`` panels of 32 nodes for a smooth law (converged on its convex
    interval, see :attr:`fpucore.law.SmoothLaw.quadrature_error`), 32 nodes otherwise."""
    if isinstance(law, PolynomialLaw):
        return gauss_legendre01(law.degree // 2 + 2)
    if isinstance(law, CubicLaw):
        return gauss_legendre01(3)
    return composite01(int(getattr(law, "quadrature_panels", 1)))


# =============================================================================== integrals
def rayleigh_slope(law, a, d):
    """S = ∫₀¹ f′(a + t d) dt = (f(a+d) − f(a))/d (eq. Rline chord slope; f′(a) at d = 0)."""
    t, wt = inner_rule(law)
    a, d = np.asarray(a, float), np.asarray(d, float)
    return np.sum(law.df(a[..., None] + t * d[..., None]) * wt, axis=-1)


def first_integral_J(law, a, d, V2):
    """J = G_a(a + d)/d² = ∫₀¹ (1−t)(f′(a + t d) − V²) dt (eq. TW_QC_gen3 without its double
    zero at w = a; = (f′(a) − V²)/2 at d = 0)."""
    t, wt = inner_rule(law)
    a, d = np.asarray(a, float), np.asarray(d, float)
    return np.sum((1.0 - t) * (law.df(a[..., None] + t * d[..., None]) - V2) * wt, axis=-1)


@functools.cache
def inner_rule_py(law: HardeningSofteningLaw) -> tuple[tuple[float, float], ...]:
    """:func:`inner_rule` as (node, weight) pairs of Python floats (scalar integrands)."""
    t, wt = inner_rule(law)
    return tuple(zip(t.tolist(), wt.tolist()))


def scalar_slope(law, a: float, d: float) -> float:
    """:func:`rayleigh_slope` for one (a, d): pure Python for a polynomial law (root finding)."""
    if not isinstance(law, PolynomialLaw):
        return float(rayleigh_slope(law, a, d))
    return sum(wk * law.df_scalar(a + tk * d) for tk, wk in inner_rule_py(law))


def df_at(law, w: float) -> float:
    """f′(w) for one float (pure Python for a polynomial law)."""
    return law.df_scalar(w) if isinstance(law, PolynomialLaw) else float(law.df(w))


def scalar_J(law, a: float, d: float, V2: float) -> float:
    """:func:`first_integral_J` for one (a, d)."""
    if not isinstance(law, PolynomialLaw):
        return float(first_integral_J(law, a, d, V2))
    return sum(wk * (1.0 - tk) * (law.df_scalar(a + tk * d) - V2) for tk, wk in inner_rule_py(law))


def driving_force_g(law, a, d):
    """∫₀¹ t(1−t) f″(a + t d) dt: the driving force of eq. zero_G is G = ½ d³ × this."""
    if isinstance(law, PolynomialLaw):  # scalar path: called thousands of times by the roots
        return sum(
            wk * tk * (1.0 - tk) * law.ddf_scalar(a + tk * d) for tk, wk in inner_rule_py(law)
        )
    t, wt = inner_rule(law)
    return float(np.sum(t * (1.0 - t) * law.ddf(a + t * d) * wt))


def tangency_defect(law, a, d):
    """∫₀¹ t f″(a + t d) dt = (f′(a+d) − S)/d: zero where the line from (a, f(a)) touches f."""
    if isinstance(law, PolynomialLaw):
        return sum(wk * tk * law.ddf_scalar(a + tk * d) for tk, wk in inner_rule_py(law))
    t, wt = inner_rule(law)
    return float(np.sum(t * law.ddf(a + t * d) * wt))


# =============================================================================== roots
def bracketed_root(
    F: Callable[[float], float], a: float, b: float, noisy: bool | float = False
) -> tuple[float, float]:
    """Root of F in [a, b] (F(a), F(b) of opposite signs) and its error bar: the larger of the
    half-width of the smallest sign-change bracket found around it and |F(x)|/|F′(x)|.
    ``noisy`` (a smooth law, whose f is an expression evaluated in float64 with rounding that
    does not vanish at the root): plus (2 × the scatter of F about its secant at 9 points
    within ±16 ulp of x + 64 eps max(|F(a)|, |F(b)|)) / |F′(x)|."""
    fa, fb = F(a), F(b)
    if fa == 0.0:
        return a, 0.0
    if fb == 0.0:
        return b, 0.0
    scale = max(abs(a), abs(b))
    x = brentq(F, a, b, xtol=EPS * scale, rtol=4 * EPS, maxiter=400)
    lo, hi = min(a, b), max(a, b)
    d = 2 * EPS * max(abs(x), EPS * scale)
    fx = F(x)
    for _ in range(80):
        fl, fr = F(max(lo, x - d)), F(min(hi, x + d))
        if fl == 0 or fr == 0 or (fl < 0) != (fr < 0):
            break
        d *= 2.0
    slope = (fr - fl) / (min(hi, x + d) - max(lo, x - d))
    resid = abs(fx / slope) if slope != 0 else d
    err = max(d, resid)
    if noisy and slope != 0:
        h = 4 * EPS * max(abs(x), EPS * scale)
        pts = [x + k * h for k in range(-4, 5)]
        scatter = max(abs(F(p) - fx - slope * (p - x)) for p in pts)
        # systematic rounding of the expression (not seen as scatter): 64 eps of F's scale
        rel = 64 * EPS + (0.0 if noisy is True else float(noisy))  # + the quadrature's error
        err += (2.0 * scatter + rel * max(abs(fa), abs(fb))) / abs(slope)
    return x, err


def march_outward(F, x0: float, direction: float, h0: float, n: int = 120):
    """March x0 + direction·h0·(1.6^k − 1)/0.6 until F changes sign w.r.t. F(x0); the bracket
    or None.  Used beyond (α, β) and when α = −∞ (no finite end to bracket against)."""
    f0, x_prev, h, x = F(x0), x0, h0, x0
    for _ in range(n):
        x = x + direction * h
        fx = F(x)
        if not math.isfinite(fx):
            return None
        if (fx < 0) != (f0 < 0) or fx == 0:
            return (x_prev, x)
        x_prev, h = x, h * 1.6
    return None


def bracket_to_end(F, x0: float, end: float, direction: float, h0: float):
    """Sign-change bracket of F from x0 toward ``end`` (α or β, possibly infinite), then beyond."""
    f0 = F(x0)
    if math.isfinite(end):
        fe = F(end)
        if (fe < 0) != (f0 < 0) or fe == 0:
            return (x0, end)
        return march_outward(F, end, direction, h0)
    return march_outward(F, x0, direction, h0)


# =============================================================================== validation
def is_smooth(law) -> bool | float:
    """A law evaluated from an expression (:class:`fpucore.law.SmoothLaw`): its roots carry the
    rounding scatter of the expression and the error left in its quadrature
    (``bracketed_root(..., noisy=is_smooth(law))``: True, or that relative error if nonzero)."""
    if getattr(law, "representation_error", None) is None:
        return False
    return law.quadrature_error or True


def search_direction(law, w_plus: float) -> float:
    """+1 on the lower branch (w₊ < w*, partner w₋ > w*), −1 on the upper branch."""
    return 1.0 if w_plus < law.w_star else -1.0


def far_end(law, s: float) -> float:
    return law.beta if s > 0 else law.alpha
