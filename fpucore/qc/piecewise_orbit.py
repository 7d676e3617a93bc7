"""QC profiles of piecewise-linear laws in closed form: solitary waves and superkinks as chains
of exponential / trigonometric arcs, one per linear regime (paper eqs. TW_QC_gen2, TW_QC_gen3,
SWQC_amp, Eren_QC).

**Per regime.**  On a piece f = f(b) + s_j (w − b), eq. TW_QC_gen2 with background w_B (Rayleigh
line R(w) = f(w_B) + V²(w − w_B), g = f − R) is linear:

    w″ = −12 g(w)/V² = λ_j (w − e_j),   λ_j = 12 (V² − s_j)/V²,   e_j = b − g(b)/(s_j − V²),

e_j the piece's Rayleigh intersection (extended).  λ_j > 0 (supersonic piece): u = w − e_j is a
combination of e^{±√λ ξ}; λ_j < 0 (s_j > V², the hard regime): u = ρ cos(ν(ξ − ξ₀)),
ν = √−λ_j; λ_j = 0: a parabola.  The first integral (eq. TW_QC_gen3) is piecewise quadratic:

    w′² = Q(w) = (24/V²) P(w),  P(w) = −∫_{w_B}^w g  (exact trapezoids between breakpoints),
    Q = λ_j u² + K_j on piece j,  K_j = Q(b) − λ_j (b − e_j)²   (K = 0 on the background piece).

**Turning point** w_M (eq. SWQC_amp): the first zero of Q from w_B toward the hard regime;
on its piece u = ±√(−K_j/λ_j) (closed form).  **Arc lengths**: u′ + √λ u ∝ e^{√λ ξ} and
u′ − √λ u ∝ e^{−√λ ξ}, so Δξ = ln(p_b/p_a)/√λ with p = u′ + √λ u (or −ln(q_b/q_a)/√λ with
q = u′ − √λ u; the one without cancellation is evaluated, the other is K/it);
trigonometric: u′ + iνu ∝ e^{iνξ}, Δξ = Δarg/ν; parabola: Δξ = 2Δw/(w′_a + w′_b).
**Integrals** (for E_ren^QC): ∫u dξ = [u′]/λ, ∫u² dξ = ([u u′] − K Δξ)/(2λ) (from u″ = λu and
u′² = λu² + K); on the background tail u = u_a e^{−√λ s}: ∫u = u_a/√λ, ∫u² = u_a²/(2√λ).  With
them E_ren^QC = (V² w_B + f(w_B)) ∫(w − w_B) + V² ∫(w − w_B)² (eq. Eren_QC reduced by the first
integral, as in fpucore.qc).

Superkinks: background w₊, Q with double zeros at w₊ and w₋, pinned at w(0) = (w₊ + w₋)/2 (as
the general route); each half is walked to its limit, the last arc exponential.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from fpucore.errors import ParameterError, fmt_interval, require_finite
from fpucore.qc.piecewise import (
    EPS,
    EqualAreaChecked,
    require_state,
    speeds,
    w_S,
)
from fpucore.result import Result, status_of


def _P(law, wB: float, V2: float, w: float) -> float:
    """P(w) = −∫_{w_B}^w (f − R): trapezoids between the breakpoints (exact for a PL law)."""
    fB = float(law.f(wB))
    g = lambda x: float(law.f(x)) - fB - V2 * (x - wB)  # noqa: E731
    lo, hi = min(wB, w), max(wB, w)
    pts = [lo, *[x for x in law._b if lo < x < hi], hi]
    tot = sum(0.5 * (g(a) + g(c)) * (c - a) for a, c in zip(pts[:-1], pts[1:]))
    return -tot if w >= wB else tot


@dataclass(frozen=True)
class Arc:
    """One regime's arc: entry at ξ_a (level w_a, slope dw_a), exit at ξ_b (∞ for a tail)."""

    j: int
    lam: float
    e: float
    K: float
    xi_a: float
    xi_b: float
    w_a: float
    dw_a: float
    w_b: float
    dw_b: float
    c: float = 0.0  # w″ on a λ = 0 arc

    def w(self, s):
        """w at ξ = ξ_a + s (s ≥ 0 within the arc)."""
        u_a = self.w_a - self.e
        if self.lam > 0:
            r = math.sqrt(self.lam)
            if math.isinf(self.xi_b):  # tail: pure decay
                return self.e + u_a * np.exp(-r * s)
            p, q = _pq(u_a, self.dw_a, r, self.K)
            return self.e + (p * np.exp(r * s) - q * np.exp(-r * s)) / (2.0 * r)
        if self.lam < 0:
            nu = math.sqrt(-self.lam)
            return self.e + u_a * np.cos(nu * s) + self.dw_a / nu * np.sin(nu * s)
        return self.w_a + self.dw_a * s + 0.5 * self.c * s * s

    def dw(self, s):
        """w′ at ξ = ξ_a + s."""
        u_a = self.w_a - self.e
        if self.lam > 0:
            r = math.sqrt(self.lam)
            if math.isinf(self.xi_b):
                return -r * u_a * np.exp(-r * s)
            p, q = _pq(u_a, self.dw_a, r, self.K)
            return 0.5 * (p * np.exp(r * s) + q * np.exp(-r * s))
        if self.lam < 0:
            nu = math.sqrt(-self.lam)
            return -u_a * nu * np.sin(nu * s) + self.dw_a * np.cos(nu * s)
        return self.dw_a + self.c * s


def _pq(u: float, du: float, r: float, K: float) -> tuple[float, float]:
    """(u′ + r u, u′ − r u), the one with equal signs evaluated, the other as K/it."""
    if (du >= 0) == (u >= 0):
        p = du + r * u
        return p, (K / p if p != 0 else du - r * u)
    q = du - r * u
    return (K / q if q != 0 else du + r * u), q


def _half_orbit(law, wB: float, V2: float, w0: float, target: float, turning=False) -> list[Arc]:
    """Arcs from ξ = 0 at level w0 (w′ from Q, sign toward the target; exactly 0 at a turning
    point, where Q(w0) is zero only to rounding and √Q would start the arc with a spurious
    slope ~1e-8) to the limit ``target`` (a double zero of Q, approached exponentially)."""
    d = 1.0 if target > w0 else -1.0
    b = law._b
    arcs: list[Arc] = []
    xi, w_a = 0.0, w0
    dw_a = 0.0 if turning else d * math.sqrt(max(24.0 * _P(law, wB, V2, w0) / V2, 0.0))
    j = int(law.piece(w0)) - int(d < 0 and bool(np.any(b == w0)))  # a corner: the piece ahead
    jt = int(law.piece(target))
    fB = float(law.f(wB))
    while True:
        s = float(law._s[j])
        lam = 12.0 * (V2 - s) / V2
        if j == jt:  # the tail: e = target, K = 0 exactly
            arcs.append(Arc(j, lam, target, 0.0, xi, math.inf, w_a, dw_a, target, 0.0))
            return arcs
        w_b = float(b[j] if d > 0 else b[j - 1])
        Qb = 24.0 * _P(law, wB, V2, w_b) / V2
        dw_b = d * math.sqrt(max(Qb, 0.0))
        if s != V2:
            g_b = float(law.f(w_b)) - fB - V2 * (w_b - wB)
            e = w_b - g_b / (s - V2)
            K = Qb - lam * (w_b - e) ** 2
            if lam > 0:
                r = math.sqrt(lam)
                pa, qa = _pq(w_a - e, dw_a, r, K)
                pb, qb = _pq(w_b - e, dw_b, r, K)
                # u′ + r u ∝ e^{rξ}, u′ − r u ∝ e^{−rξ}: the larger pair decides
                if min(abs(pa), abs(pb)) >= min(abs(qa), abs(qb)):
                    dxi = math.log(pb / pa) / r
                else:
                    dxi = -math.log(qb / qa) / r
            else:
                nu = math.sqrt(-lam)
                th_a = math.atan2(nu * (w_a - e), dw_a)
                th_b = math.atan2(nu * (w_b - e), dw_b)
                dxi = ((th_b - th_a) % (2 * math.pi)) / nu  # u′ + iνu ∝ e^{iνξ}
            arcs.append(Arc(j, lam, e, K, xi, xi + dxi, w_a, dw_a, w_b, dw_b))
        else:
            dxi = 2.0 * (w_b - w_a) / (dw_a + dw_b)
            c = (dw_b - dw_a) / dxi
            arcs.append(Arc(j, 0.0, math.nan, 0.0, xi, xi + dxi, w_a, dw_a, w_b, dw_b, c))
        xi, w_a, dw_a = xi + dxi, w_b, dw_b
        j += 1 if d > 0 else -1


def _moments(arcs: list[Arc], wB: float) -> tuple[float, float]:
    """(∫(w − w_B) dξ, ∫(w − w_B)² dξ) over a half orbit, in closed form (module docstring)."""
    m1 = m2 = 0.0
    for a in arcs:
        if math.isinf(a.xi_b):
            r = math.sqrt(a.lam)
            u = a.w_a - a.e
            dl = a.e - wB
            m1 += u / r + (0.0 if dl == 0 else math.inf)
            m2 += u * u / (2 * r)
            continue
        L = a.xi_b - a.xi_a
        if a.lam == 0.0:  # polynomial arc: 3-point Gauss–Legendre is exact to degree 5
            x, wt = np.polynomial.legendre.leggauss(3)
            y = np.array([a.w(0.5 * L * (1 + t)) for t in x]) - wB
            m1 += 0.5 * L * float(np.dot(wt, y))
            m2 += 0.5 * L * float(np.dot(wt, y * y))
            continue
        ua, ub = a.w_a - a.e, a.w_b - a.e
        I1 = (a.dw_b - a.dw_a) / a.lam
        I2 = (ub * a.dw_b - ua * a.dw_a - a.K * L) / (2 * a.lam)
        dl = a.e - wB
        m1 += dl * L + I1
        m2 += dl * dl * L + 2 * dl * I1 + I2
    return m1, m2


def _evaluate(arcs: list[Arc], xi: np.ndarray, derivative: bool = False) -> np.ndarray:
    out = np.empty_like(xi)
    for a in arcs:
        m = (xi >= a.xi_a) & (xi <= a.xi_b)
        out[m] = (a.dw if derivative else a.w)(xi[m] - a.xi_a)
    return out


@dataclass(frozen=True)
class PLSolitary(Result):
    """QC solitary wave of a PL law: background w_B (eq. wB), turning point w_M = w(0), the
    arcs of the ξ ≥ 0 half, E_ren^QC (eq. Eren_QC).  ``first_integral_residual``: the largest
    |w′² − Q(w)|/max Q at the arc ends (round-off check of the arc chain)."""

    law: object
    V: float
    w_plus: float
    w_B: float
    w_M: float
    kind: str
    interval: str
    V_SK: float
    c_plus: float
    c_minus: float
    energy: float
    mass: float
    first_integral_residual: float
    elapsed_s: float
    w_T: float = math.nan  # the next zero of Q beyond w_M (the cubic's w_T), NaN if none
    gamma: float = math.nan  # decay rate of the tails, w − w_B ∝ e^{−γ|ξ|}
    energy_error: float = math.nan  # rounding bound of E_ren
    arcs: tuple = field(default=(), repr=False, compare=False)

    ERROR_FIELDS: ClassVar = ("first_integral_residual", "energy_error")
    DERIVED: ClassVar = ("amplitude", "width", "converged", "status", "message")
    EXCLUDE: ClassVar = ("law", "arcs")

    @property
    def amplitude(self) -> float:
        return abs(self.w_M - self.w_B)

    @property
    def width(self) -> float:
        """1/γ, the tails' decay length (lattice units), as the cubic's (the phase plane and
        the explorer's profiles size their windows by it)."""
        return 1.0 / self.gamma

    def profile(self, xi):
        """w(ξ) (even in ξ), vectorised."""
        xi = np.asarray(xi, dtype=float)
        return _evaluate(list(self.arcs), np.abs(xi))

    def dprofile(self, xi):
        """w′(ξ) (odd in ξ)."""
        xi = np.asarray(xi, dtype=float)
        return np.sign(xi) * _evaluate(list(self.arcs), np.abs(xi), derivative=True)

    @property
    def converged(self) -> bool:
        return bool(self.first_integral_residual <= 1e-9)

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def message(self) -> str:
        return "" if self.converged else "first-integral residual above 1e-9"


def _turning_point(law, wB: float, V2: float, d: float, count: int = 1):
    """First zero of Q beyond w_B in direction d (the first ``count`` zeros, in order, when
    count > 1; NaN where there are fewer): on piece j, λ u² + K = 0 (closed form)."""
    found: list[float] = []
    b = law._b
    j = int(law.piece(wB))
    fB = float(law.f(wB))
    while True:
        j += 1 if d > 0 else -1
        if not 0 <= j <= b.size:
            break
        lo = b[j - 1] if j > 0 else -math.inf
        hi = b[j] if j < b.size else math.inf
        a = lo if d > 0 else hi
        Qa = 24.0 * _P(law, wB, V2, a) / V2
        s = float(law._s[j])
        ga = float(law.f(a)) - fB - V2 * (a - wB)
        if s == V2:  # Q linear: Q(a) − (24/V²) g (w − a)
            x = a + Qa * V2 / (24.0 * ga) if ga != 0 else math.nan
            roots = [x]
        else:
            lam = 12.0 * (V2 - s) / V2
            e = a - ga / (s - V2)
            K = Qa - lam * (a - e) ** 2
            rr = -K / lam
            roots = [e - math.sqrt(rr), e + math.sqrt(rr)] if rr >= 0 else []
        found += sorted((x for x in roots if lo <= x <= hi), reverse=d < 0)
        if len(found) >= count:
            return found[0] if count == 1 else found[:count]
    if count > 1 and found:
        return found + [math.nan] * (count - len(found))
    raise ParameterError("V", math.sqrt(V2), "a velocity of a solitary wave", "no turning point")


def solitary(law, w_plus: float, V: float) -> PLSolitary:
    """QC solitary wave for the state w₊ ahead and velocity V in (c₊, V_SK) ∪ (V_SK, c₋)."""
    t0 = time.perf_counter()
    w_plus = require_state(law, w_plus)
    V = abs(require_finite("V", V))
    sp = speeds(law, w_plus)
    if not (sp.c_plus < V < sp.c_minus) or V == sp.V_SK:
        raise ParameterError(
            "V",
            V,
            f"{fmt_interval(sp.c_plus, sp.V_SK)} or {fmt_interval(sp.V_SK, sp.c_minus)}",
            "solitary waves exist between the sonic limits, V != V_SK",
        )
    below = V < sp.V_SK
    wB = w_plus if below else w_S(law, w_plus, V)
    V2 = V * V
    d = 1.0 if wB < law.w_star else -1.0
    wM, wT = _turning_point(law, wB, V2, d, count=2)
    arcs = _half_orbit(law, wB, V2, wM, wB, turning=True)
    m1, m2 = _moments(arcs, wB)
    fB = float(law.f(wB))
    energy = 2.0 * ((V2 * wB + fB) * m1 + V2 * m2)
    energy_error = 64 * EPS * 2.0 * (abs((V2 * wB + fB) * m1) + V2 * m2)
    gamma = math.sqrt(12.0 * (V2 - float(law.df(wB))) / V2)
    qs = max(24.0 * _P(law, wB, V2, a.w_a) / V2 for a in arcs) or 1.0
    res = (
        max((abs(a.dw_a**2 - 24.0 * _P(law, wB, V2, a.w_a) / V2) for a in arcs[1:]), default=0.0)
        / qs
    )
    res = max(res, abs(_P(law, wB, V2, wM)) * 24.0 / V2 / qs)
    return PLSolitary(
        law,
        V,
        w_plus,
        wB,
        wM,
        "tensile" if wM > wB else "compressive",
        "below" if below else "above",
        sp.V_SK,
        sp.c_plus,
        sp.c_minus,
        energy,
        2.0 * m1,
        res,
        time.perf_counter() - t0,
        wT,
        gamma,
        energy_error,
        tuple(arcs),
    )


@dataclass(frozen=True)
class PLSuperkink(EqualAreaChecked):
    """QC superkink of a PL law: w₊ ahead, w₋ behind, V = V_SK, w(0) = (w₊ + w₋)/2; the arcs
    toward w₊ (ξ > 0) and toward w₋ (ξ < 0)."""

    law: object
    V: float
    w_plus: float
    w_minus: float
    branch: str
    driving_force: float
    elapsed_s: float
    p: float = math.nan  # half the decay rate ahead, √(12(V² − f′(w₊)))/(2V) (as fpucore.qc)
    p_minus: float = math.nan  # the same behind
    rayleigh_residual: float = math.nan  # |f₊ − f₋ − V²(w₊ − w₋)| / (|f₊| + |f₋|)
    arcs_plus: tuple = field(default=(), repr=False, compare=False)
    arcs_minus: tuple = field(default=(), repr=False, compare=False)

    ERROR_FIELDS: ClassVar = ("driving_force", "rayleigh_residual")
    DERIVED: ClassVar = ("amplitude", "width", "w_center", "converged", "status", "message")
    EXCLUDE: ClassVar = ("law", "arcs_plus", "arcs_minus")

    @property
    def amplitude(self) -> float:
        return abs(self.w_minus - self.w_plus)

    @property
    def width(self) -> float:
        """1/p, the decay length ahead (lattice units), as the cubic's."""
        return 1.0 / self.p

    @property
    def w_center(self) -> float:
        return 0.5 * (self.w_plus + self.w_minus)

    def profile(self, xi):
        xi = np.asarray(xi, dtype=float)
        out = np.empty_like(xi)
        pos = xi >= 0
        out[pos] = _evaluate(list(self.arcs_plus), xi[pos])
        out[~pos] = _evaluate(list(self.arcs_minus), -xi[~pos])
        return out

    def dprofile(self, xi):
        """w′(ξ)."""
        xi = np.asarray(xi, dtype=float)
        out = np.empty_like(xi)
        pos = xi >= 0
        out[pos] = _evaluate(list(self.arcs_plus), xi[pos], derivative=True)
        out[~pos] = -_evaluate(list(self.arcs_minus), -xi[~pos], derivative=True)
        return out


def superkink(law, w_plus: float) -> PLSuperkink:
    """QC superkink with the state w₊ ahead (eqs. Rline, zero_G, TW_QC_gen3)."""
    t0 = time.perf_counter()
    sp = speeds(law, w_plus)
    V2 = sp.V_SK**2
    wc = 0.5 * (sp.w_plus + sp.w_minus)
    ap = _half_orbit(law, sp.w_plus, V2, wc, sp.w_plus)
    am = _half_orbit(law, sp.w_plus, V2, wc, sp.w_minus)
    half = lambda w: math.sqrt(12.0 * (V2 - float(law.df(w)))) / (2.0 * sp.V_SK)  # noqa: E731
    fp, fm = float(law.f(sp.w_plus)), float(law.f(sp.w_minus))
    rr = abs(fp - fm - V2 * (sp.w_plus - sp.w_minus)) / max(abs(fp) + abs(fm), EPS)
    return PLSuperkink(
        law,
        sp.V_SK,
        sp.w_plus,
        sp.w_minus,
        sp.branch,
        sp.driving_force,
        time.perf_counter() - t0,
        half(sp.w_plus),
        half(sp.w_minus),
        rr,
        tuple(ap),
        tuple(am),
    )


__all__ = ["Arc", "PLSolitary", "PLSuperkink", "solitary", "superkink", "EPS"]
