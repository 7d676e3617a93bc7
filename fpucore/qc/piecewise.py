"""QC theory in closed form for continuous piecewise-linear laws (paper §3 for
:class:`fpucore.law.TrilinearLaw` / :class:`fpucore.law.PiecewiseLinearLaw`): speeds, the
equal-area partner, Rayleigh roots and existence ranges.  Profiles, amplitudes and E_ren^QC:
:mod:`fpucore.qc.piecewise_orbit`.

Notation: breakpoints b_k, slope jumps J_k = s_k − s_{k−1} (f″ = Σ J_k δ(w − b_k)), hard regime
[w₁, w₂] (the maximum slope s_h = c_max²).

**Equal area (eq. zero_G) is linear in w₋.**  With Δ = w₋ − w₊ the paper's driving force is
G = ½Δ³∫₀¹ t(1−t) f″(w₊ + tΔ) dt; the Dirac masses of f″ give t_k(1−t_k)Δ² = (b_k − w₊)(w₋ − b_k),
so

    G = ½ sgn(Δ) H(w₋),   H(x) = Σ_{b_k strictly between w₊ and x} J_k (b_k − w₊)(x − b_k),

and on each piece of x, H = a x − c with a = Σ J_k (b_k − w₊), c = Σ J_k (b_k − w₊) b_k: the
partner is w₋ = c/a.  H is symmetric in (w₊, x).  Trilinear (w₊ < w₁, w₋ > w₂; A = E₂ − E₁,
B = E₂ − E₃):

    A (w₁ − w₊)(w₋ − w₁) = B (w₂ − w₊)(w₋ − w₂),
    w₋ = [A w₁(w₁ − w₊) − B w₂(w₂ − w₊)] / [A(w₁ − w₊) − B(w₂ − w₊)].

H has only positive terms until x passes the hard regime, so w₊ and w₋ lie on opposite sides
of the whole hard regime (w₊ inside it: no superkink), and H is concave beyond it: the partner
exists iff the final slope a_∞(w₊) = Σ_{b_k beyond w₊} J_k (b_k − w₊) < 0 — linear in w₊ on each
piece, which gives the superkink range (trilinear, lower branch: w₊ > w₁ − B(w₂ − w₁)/(E₃ − E₁)
when E₃ > E₁, else every w₊ < w₁; upper branch: w₊ < w₂ + A(w₂ − w₁)/(E₁ − E₃) when E₁ > E₃).
As w₊ → w₁ the partner tends to w₂ (H's only root at w₊ = w₁): superkinks bifurcate at the
finite amplitude w₂ − w₁ with V_SK → √E₂ = c_max (the cubic's w₊ = w₋ = w* spread over H).

**Speeds.**  V_SK² = (f(w₋) − f(w₊))/(w₋ − w₊) (eq. Rline), computed as the length-weighted mean
of the slopes between (no cancellation); the equal-area condition forces s(w±) < V_SK² (if
V² ≤ s(w₊), f − R would not change sign on (w₊, w₋)).  c₊ = √s(w₊) (eq. cplus).  c₋ (eq.
cminus): the chord slope from w₊ is largest at a corner, not at a tangency: c₋² = max over
breakpoints b beyond w₊ of (f(b) − f(w₊))/(b − w₊), w₋ˢ = that b — there the centre w_C and
the saddle w_S of eq. TW_QC_gen2 collide as V² → c₋².  **Rayleigh roots**: on each piece f = R is
linear, w = b + (f(b) − R(b))/(V² − s_j); f − R has slopes s_j − V² of sign −, +, − (unimodal
slopes), hence w₊ and at most two more roots, the centre w_C (s_j > V²) and the saddle w_S.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from scipy.optimize import brentq

from fpucore.errors import ParameterError, fmt_interval, require_finite
from fpucore.result import Result, status_of

EPS = float(np.finfo(float).eps)


def require_piecewise(law):
    if not hasattr(law, "hard_regime") or not hasattr(law, "breakpoints"):
        raise ParameterError(
            "law", type(law).__name__, "a piecewise-linear law (TrilinearLaw, PiecewiseLinearLaw)"
        )
    return law


def slope_mean(law, a: float, c: float) -> float:
    """(f(c) − f(a))/(c − a) as the length-weighted mean of the slopes on [a, c] (exact form
    of the chord slope, no cancellation of f values)."""
    lo, hi = min(a, c), max(a, c)
    b = np.concatenate(([-math.inf], law._b, [math.inf]))
    ln = np.clip(np.minimum(hi, b[1:]) - np.maximum(lo, b[:-1]), 0.0, None)
    return float(np.dot(law._s, ln) / (hi - lo))


def jumps(law) -> np.ndarray:
    return np.diff(law._s)


def branch_of(law, w_plus: float) -> str:
    w1, w2 = law.hard_regime
    if w_plus < w1:
        return "lower"
    if w_plus > w2:
        return "upper"
    raise ParameterError(
        "w_plus",
        w_plus,
        f"w_plus < {w1:.10g} or w_plus > {w2:.10g}",
        "a state in the hard regime [w1, w2] has no superkink or solitary wave (the PL analogue "
        "of w+ = w*: c+ = V_SK = c-)",
    )


def require_state(law, w_plus, name: str = "w_plus") -> float:
    """A state ahead: finite, not on a breakpoint (two sound speeds there), outside the hard
    regime."""
    law = require_piecewise(law)
    w = require_finite(name, w_plus)
    if np.any(law._b == w):
        raise ParameterError(
            name, w, "a strain inside a regime", "on a breakpoint f'(w) has two values"
        )
    branch_of(law, w)
    return w


# =============================================================================== equal area
def _piece_bounds(b: np.ndarray, j: int) -> tuple[float, float]:
    return (b[j - 1] if j > 0 else -math.inf), (b[j] if j < b.size else math.inf)


def _partner(law, w_plus: float):
    """w₋ = c/a on the piece where H changes sign (module docstring), or None."""
    b, J, h = law._b, jumps(law), law._h  # hard piece h = (b[h-1], b[h])
    lower = w_plus < b[h - 1]
    for j in range(h + 1, b.size + 1) if lower else range(h - 1, -1, -1):
        lo, hi = _piece_bounds(b, j)
        # breakpoints strictly between w₊ and any point of piece j
        sel = ((b > w_plus) & (b <= lo)) if lower else ((b < w_plus) & (b >= hi))
        a = float(np.dot(J[sel], b[sel] - w_plus))
        c = float(np.dot(J[sel], (b[sel] - w_plus) * b[sel]))
        if a != 0.0 and lo <= c / a <= hi:
            return c / a
    return None


def w_minus(law, w_plus: float) -> float:
    """The equal-area partner w₋ of w₊ (eqs. Rline + zero_G), exact (module docstring)."""
    w_plus = require_state(law, w_plus)
    x = _partner(law, w_plus)
    if x is None:
        lo, hi = superkink_w_plus_range(law, branch_of(law, w_plus))
        raise ParameterError(
            "w_plus",
            w_plus,
            fmt_interval(lo, hi),
            "no equal-area partner: the final slope of H is >= 0 (the partner runs to infinity)",
        )
    return x


def superkink_w_plus_range(law, branch: str = "lower") -> tuple[float, float]:
    """Open w₊-interval of superkinks: (w_lo, w₁) or (w₂, w_hi), ends where a_∞(w₊) = 0
    (a_∞ = C − w₊ D on each piece; negative next to the hard regime)."""
    law = require_piecewise(law)
    if branch not in ("lower", "upper"):
        raise ParameterError("branch", branch, "'lower' (w_plus < w1) or 'upper' (w_plus > w2)")
    b, J, h = law._b, jumps(law), law._h
    w1, w2 = law.hard_regime
    lower = branch == "lower"
    for j in range(h - 1, -1, -1) if lower else range(h + 1, b.size + 1):
        lo, hi = _piece_bounds(b, j)
        sel = (b >= hi) if lower else (b <= lo)  # the breakpoints beyond w₊ (far side)
        D, C = float(J[sel].sum()), float(np.dot(J[sel], b[sel]))
        end = lo if lower else hi
        if math.isfinite(end):
            crosses = C - end * D >= 0.0
        else:  # a_∞ → −end·D: changes sign iff it tends to +∞
            crosses = (D > 0) if lower else (D < 0)
        if crosses and D != 0.0:
            return (C / D, w1) if lower else (w2, C / D)
    return (-math.inf, w1) if lower else (w2, math.inf)


# =============================================================================== speeds
def c_minus_sonic(law, w_plus: float) -> tuple[float, float]:
    """(c₋, w₋ˢ): the largest chord slope from w₊ to a breakpoint beyond the hard regime."""
    b = law._b
    far = b[b > w_plus] if w_plus < law.hard_regime[0] else b[b < w_plus]
    sl = [slope_mean(law, w_plus, x) for x in far]
    k = int(np.argmax(sl))
    return math.sqrt(sl[k]), float(far[k])


class EqualAreaChecked(Result):
    """Status of a result whose check is the equal-area driving force (eq. zero_G), at
    round-off when converged; subclasses carry ``driving_force``."""

    driving_force: float  # a field of each (dataclass) subclass

    @property
    def converged(self) -> bool:
        return bool(self.driving_force <= 1e-11)

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def message(self) -> str:
        return "" if self.converged else "equal-area residual above round-off"


@dataclass(frozen=True)
class PLSpeeds(EqualAreaChecked):
    """c₊ (eq. cplus), V_SK and w₋ (eqs. Rline, zero_G), c₋ and w₋ˢ (eq. cminus) in closed
    form for a PL law.  ``driving_force``: |G(w₊, w₋)|/(f-scale · |Δ|) from the law's Φ, an a
    posteriori round-off check."""

    w_plus: float
    branch: str
    c_plus: float
    V_SK: float
    c_minus: float
    w_minus: float
    w_minus_sonic: float
    driving_force: float
    elapsed_s: float

    ERROR_FIELDS: ClassVar = ("driving_force",)
    DERIVED: ClassVar = ("converged", "status", "message")


def speeds(law, w_plus: float) -> PLSpeeds:
    t0 = time.perf_counter()
    w_plus = require_state(law, w_plus)
    wm = w_minus(law, w_plus)
    V2 = slope_mean(law, w_plus, wm)
    cm, ws = c_minus_sonic(law, w_plus)
    fp, fm = float(law.f(w_plus)), float(law.f(wm))
    G = float(law.phi(w_plus) - law.phi(wm)) - 0.5 * (w_plus - wm) * (fp + fm)
    scale = (abs(fp) + abs(fm) + math.sqrt(V2) ** 2 * abs(wm - w_plus)) * abs(wm - w_plus)
    return PLSpeeds(
        w_plus,
        branch_of(law, w_plus),
        math.sqrt(float(law.df(w_plus))),
        math.sqrt(V2),
        cm,
        wm,
        ws,
        abs(G) / scale,
        time.perf_counter() - t0,
    )


def solitary_intervals(law, w_plus: float):
    """((c₊, V_SK), (V_SK, c₋)): velocity ranges of the solitary waves for w₊ (eq. wB)."""
    sp = speeds(law, w_plus)
    return (sp.c_plus, sp.V_SK), (sp.V_SK, sp.c_minus)


def rayleigh_roots(law, w_B: float, V: float) -> list[float]:
    """Every w ≠ w_B with f(w) = f(w_B) + V²(w − w_B), sorted (piece by piece, exact)."""
    V2 = require_finite("V", V) ** 2
    b = law._b
    fB = float(law.f(w_B))
    out: list[float] = []
    for j in range(b.size + 1):
        s = law._s[j]
        if s == V2:
            continue
        a = b[j - 1] if j > 0 else b[0]
        g = float(law.f(a)) - fB - V2 * (a - w_B)
        x = a - g / (s - V2)
        lo = b[j - 1] if j > 0 else -math.inf
        hi = b[j] if j < b.size else math.inf
        if lo <= x <= hi and abs(x - w_B) > 8 * EPS * max(1.0, abs(w_B)):
            if not out or abs(x - out[-1]) > 8 * EPS * max(1.0, abs(x)):
                out.append(x)
    return sorted(out)


def w_S(law, w_plus: float, V: float) -> float:
    """The saddle w_S(V) ≠ w₊ (background of the waves with V_SK < V < c₋): the Rayleigh root
    beyond the hard regime with s(w_S) < V²."""
    w_plus = require_state(law, w_plus)
    roots = rayleigh_roots(law, w_plus, V)
    w1, w2 = law.hard_regime
    far = [x for x in roots if (x > w2 if w_plus < w1 else x < w1) and law.df(x) < V * V]
    if not far:
        cm = c_minus_sonic(law, w_plus)[0]
        raise ParameterError("V", V, f"(0, {cm:.10g})", "no saddle beyond the hard regime")
    return far[-1] if w_plus < w1 else far[0]


# =============================================================================== V ↦ w₊
def _vsk2(law, w_plus: float) -> float:
    """V_SK² of the state w₊ (chord slope to its equal-area partner), no validation."""
    x = _partner(law, w_plus)
    return math.nan if x is None else slope_mean(law, w_plus, x)


def superkink_velocity_bounds(law, branch: str = "lower") -> tuple[float, float]:
    """(V_lo, V_hi): the superkink velocities of a branch, the limits of V_SK(w₊) at the ends of
    :func:`superkink_w_plus_range`.  Next to the hard regime the partner tends to its far end
    (H's only root at w₊ = w₁ is w₂), so V_SK² → s_h = c_max².  At a finite far end the partner
    runs to infinity (a_∞ = 0): V_SK² → the slope of the last regime beyond (s_m on the lower
    branch, s₀ on the upper); at an infinite far end w₊ runs away from a finite partner:
    V_SK² → the slope of w₊'s own outer regime (s₀ lower, s_m upper)."""
    lo, hi = superkink_w_plus_range(law, branch)  # validates law and branch
    s = law._s
    lower = branch == "lower"
    far = lo if lower else hi
    if math.isfinite(far):
        s_far = s[-1] if lower else s[0]
    else:
        s_far = s[0] if lower else s[-1]
    return math.sqrt(float(s_far)), math.sqrt(float(s[law._h]))


def w_plus_of_V(law, V: float, branch: str = "lower") -> float:
    """The state w₊ ahead of the superkink of velocity V on a branch: the root of
    V_SK(w₊) = V (V_SK² exact on each piece, module docstring; monotone on a branch, checked
    in tests/qc/test_qc_piecewise_velocity.py), bracketed between the hard regime's edge and
    the far end, solved by Brent's method to the last bit of w₊."""
    V = require_finite("V", V)
    vlo, vhi = superkink_velocity_bounds(law, branch)
    if not (vlo < V < vhi):
        raise ParameterError(
            "V", V, fmt_interval(vlo, vhi), f"superkink velocities of the {branch} branch"
        )
    lo, hi = superkink_w_plus_range(law, branch)
    w1, w2 = law.hard_regime
    edge, sgn = (w1, -1.0) if branch == "lower" else (w2, 1.0)
    V2 = V * V

    def g(w: float) -> float:  # V_SK² − V²: > 0 next to the hard regime
        return (float(law._s[law._h]) if w == edge else _vsk2(law, w)) - V2

    far = lo if branch == "lower" else hi
    fail = ParameterError("V", V, fmt_interval(vlo, vhi), "no state w_plus bracketed for this V")
    if math.isfinite(far):  # halve the way toward the far end until V_SK < V
        t = 0.5
        while not g(x := far + (edge - far) * t) < 0.0:
            t *= 0.5
            if t < 1e-18:
                raise fail
    else:  # march outward, doubling
        d = w2 - w1
        while not g(x := edge + sgn * d) < 0.0:
            d *= 2.0
            if d > 1e300:
                raise fail
    a, b = (x, edge) if branch == "lower" else (edge, x)
    return float(brentq(g, a, b, xtol=1e-300, rtol=4 * EPS, maxiter=200))
