"""The cubic law's sound speeds, velocity ranges and Rayleigh-line roots in closed form
(paper §4, eqs. cplus, cubic_cond2, cminus_cubic, V_bounds_cubic, Rline, wS).

Written in terms of e = (w₊ − w*)² where that avoids cancellation:

    c₊² = c_max² − 3|a| e,   V_SK² = c_max² − |a| e,   c₋² = c_max² − ¾|a| e,
    c_max² = f′(w*) = 1 + b²/(3|a|)

so c₊ < V_SK < c₋ holds exactly for w₊ ≠ w*, and the three meet at w₊ = w*.  The waves
themselves are in :mod:`fpucore.qc.closed_forms`, which re-exports these names.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np

from fpucore.errors import ParameterError, fmt_interval, require_finite
from fpucore.law import CubicLaw, HardeningSofteningLaw, require_law

if TYPE_CHECKING:
    from fpucore.law.base import Strain

EPS = np.finfo(float).eps


def cubic_law(law: HardeningSofteningLaw) -> CubicLaw:
    """The law as a CubicLaw, or ParameterError (not a law) / NotImplementedError (another law)."""
    require_law(law)
    if not isinstance(law, CubicLaw):
        raise NotImplementedError("QC closed forms (paper §4) exist for the cubic law only")
    return law


def c_max_squared(law: CubicLaw) -> float:
    """c_max² = f′(w*) = 1 + b²/(3|a|)."""
    return 1.0 + law.b**2 / (3.0 * law.abs_a)


def require_w_plus(law: HardeningSofteningLaw, w_plus: float) -> float:
    """w₊ must lie in the convex interval and away from w*, where the family degenerates."""
    w_plus = law.require_convex("w_plus", w_plus)
    if abs(w_plus - law.w_star) <= 1e-12 * max(1.0, law.w_star):
        raise ParameterError(
            "w_plus",
            w_plus,
            f"(alpha, w*) or (w*, beta) = {fmt_interval(law.alpha, law.w_star)} or "
            f"{fmt_interval(law.w_star, law.beta)}",
            "at w_plus = w* the superkink and solitary-wave families degenerate (c+ = V_SK = c-)",
        )
    return w_plus


def require_V(V: float) -> float:
    V = require_finite("V", V)
    if V <= 0:
        raise ParameterError("V", V, "V > 0", "waves with -V are mirror images of those with V")
    return V


def superkink_velocity_bounds(law: HardeningSofteningLaw) -> tuple[float, float]:
    """(V_lo, V_hi) of eq. V_bounds_cubic: 2/3 c_max² < V_SK² < c_max²."""
    law = cubic_law(law)
    c2 = c_max_squared(law)
    return math.sqrt(2.0 * c2 / 3.0), math.sqrt(c2)


def sound_speeds(law: HardeningSofteningLaw, w_plus: float) -> tuple[float, float, float]:
    """(c₊, V_SK, c₋) for the state w₊ ahead (eqs. cplus, cubic_cond2, cminus_cubic)."""
    law = cubic_law(law)
    w_plus = law.require_convex("w_plus", w_plus)
    c2, e = c_max_squared(law), (w_plus - law.w_star) ** 2
    A = law.abs_a
    return sound_speed_plus(law, w_plus), math.sqrt(c2 - A * e), math.sqrt(c2 - 0.75 * A * e)


def finite_array(name: str, x) -> np.ndarray:
    """x as a float array of finite numbers, or ParameterError naming the argument."""
    if isinstance(x, (str, bytes)):
        raise ParameterError(name, x, "finite real numbers")
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(name, type(x).__name__, "finite real numbers") from None
    if not np.all(np.isfinite(a)):
        raise ParameterError(name, "non-finite entries", "finite real numbers")
    return a


def sound_speed_plus(law: CubicLaw, w_plus: Strain) -> Strain:
    """c₊ = √f′(w₊) (eq. cplus; w₊ may be an array), written without cancellation.

    c₊² = c_max² − 3|a|e, e = (w₊ − w*)², cancels near α and β (a relative 7.5e-5 lost near α)
    and entirely when b²/|a| is large (b = 1e80, w₊ = 1 gave c₊ = 0).  Where it would
    lose more than one bit (3|a|e > c_max²/2) a scalar w₊ gets f′(w₊) = 1 + 2bw₊ + 3aw₊² in exact
    rational arithmetic, rounded once (c₊ to an ulp: near α the sum cancels in any fixed
    precision), an array the factored 3|a| (w − α)(β − w) (error ~ε|α|/(w − α), for plots).
    Elsewhere the e-form keeps c₊ ≤ V_SK ≤ c₋ exact (and equal at w*); V_SK² = c_max² − |a|e and
    c₋² = c_max² − ¾|a|e never cancel, since |a|e ≤ c_max²/3 on (α, β)."""
    w = finite_array("w_plus", w_plus)
    c2, A = c_max_squared(law), law.abs_a
    d = 3.0 * A * (w - law.w_star) ** 2
    if w.ndim == 0:
        if d <= 0.5 * c2:
            return math.sqrt(c2 - float(d))
        x, a, b = Fraction(float(w)), Fraction(law.a), Fraction(law.b)
        try:
            return math.sqrt(max(float(1 + x * (2 * b + 3 * a * x)), 0.0))
        except OverflowError:  # |w₊| far outside the convex interval: f′ is no double
            law.require_convex("w_plus", float(w))
            raise
    factored = 3.0 * A * np.maximum(w - law.alpha, 0.0) * np.maximum(law.beta - w, 0.0)
    return np.sqrt(np.where(d > 0.5 * c2, factored, np.maximum(c2 - d, 0.0)))


def solitary_intervals(law: HardeningSofteningLaw, w_plus: float):
    """((c₊, V_SK), (V_SK, c₋)): the two velocity intervals of solitary waves for w₊."""
    law = cubic_law(law)
    w_plus = require_w_plus(law, w_plus)
    cp, vsk, cm = sound_speeds(law, w_plus)
    return (cp, vsk), (vsk, cm)


def w_minus_sonic(law: HardeningSofteningLaw, w_plus: float) -> float:
    """w₋ˢ = (b − |a| w₊)/(2|a|) = (3w* − w₊)/2, tangency point of the c₋ Rayleigh line."""
    law = cubic_law(law)
    w_plus = law.require_convex("w_plus", w_plus)
    return 0.5 * (3.0 * law.w_star - w_plus)


def require_V_upto(law: CubicLaw, w_plus: float, V, lo: float, lo_name: str):
    """V (scalar or array) finite with lo <= V <= c₋ (c₋ rounded up by a few ulps)."""
    cm = sound_speeds(law, w_plus)[2]
    valid = f"[{lo:.10g}, {cm:.10g}] ({lo_name} <= V <= c-)"
    if np.ndim(V) == 0:
        Va = np.asarray(require_finite("V", V))
    else:
        try:
            Va = np.asarray(V, dtype=float)
        except (TypeError, ValueError, OverflowError):
            raise ParameterError("V", V, valid, "not an array of numbers") from None
        if Va.size == 0:
            raise ParameterError("V", V, valid, "empty")
    if not np.all(np.isfinite(Va)):
        bad = Va[~np.isfinite(Va)].flat[0]
        raise ParameterError("V", float(bad), valid, "not a finite number")
    hi = cm * (1.0 + 8.0 * EPS)
    out = (Va < lo) | (Va > hi)
    if np.any(out):
        raise ParameterError(
            "V", float(Va[out].flat[0]), valid, "no intersection with the Rayleigh line beyond c-"
        )
    return Va, cm


def rayleigh_roots(law: HardeningSofteningLaw, w_plus: float, V):
    """The two other intersections of f with the Rayleigh line R(w) = f(w₊) + V²(w − w₊).

    Returns (w_near, w_far) = w₋ˢ ∓ √((c₋² − V²)/|a|) ordered by distance from w* (w_near is
    closer to w*).  V may be an array; every V must lie in (0, c₋] (beyond c₋ only w₊ is a
    critical point: ParameterError).  See :func:`fpucore.qc.phase.critical_points` for the
    saddle/center classification.
    """
    law = cubic_law(law)
    w_plus = law.require_convex("w_plus", w_plus)
    Va, cm = require_V_upto(law, w_plus, V, 0.0, "0")
    if np.any(Va <= 0):
        raise ParameterError("V", float(Va[Va <= 0].flat[0]), f"(0, {cm:.10g}]", "V > 0")
    A = law.abs_a
    disc = np.maximum((cm - Va) * (cm + Va) / A, 0.0)  # c₋² − V² without cancellation
    r = np.sqrt(disc)
    s = w_minus_sonic(law, w_plus)
    # The two roots solve a w² + (a w₊ + b) w + C = 0, C = a w₊² + b w₊ + 1 − V² (f − R divided
    # by w − w₊).  s ± r cancels for the root of small magnitude when |w| << w* (b²/|a| large:
    # a relative error ~ε w*/|w|); it comes from Vieta instead, w_small = C/(a w_big).
    big = s + math.copysign(1.0, s) * r
    C = (1.0 - Va * Va) + w_plus * (law.b + law.a * w_plus)
    with np.errstate(divide="ignore", invalid="ignore"):
        small = np.where(big != 0.0, C / (law.a * big), s - r)
    if (s >= law.w_star) == (s >= 0.0):  # the far root (from w*) is the big one
        far, near = big, small
    else:
        near, far = big, small
    if np.ndim(V) == 0:
        return float(near), float(far)
    return near, far


def w_S(law: HardeningSofteningLaw, w_plus: float, V):
    """Saddle w_S(V) ≠ w₊ of eq. wS: f(w_S) − f(w₊) = V²(w_S − w₊), V² > f′(w_S) — the far
    Rayleigh root, a saddle for c₊ < V < c₋ (V may be an array; V outside (0, c₋]:
    ParameterError, as for :func:`rayleigh_roots`)."""
    return rayleigh_roots(law, w_plus, V)[1]
