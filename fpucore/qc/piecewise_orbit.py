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
from fpucore.qc.piecewise_arcs import (
    Arc,
    evaluate_arcs,
    half_orbit,
    orbit_moments,
    orbit_potential,
)
from fpucore.result import Result, status_of


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
        return evaluate_arcs(list(self.arcs), np.abs(xi))

    def dprofile(self, xi):
        """w′(ξ) (odd in ξ)."""
        xi = np.asarray(xi, dtype=float)
        return np.sign(xi) * evaluate_arcs(list(self.arcs), np.abs(xi), derivative=True)

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
        Qa = 24.0 * orbit_potential(law, wB, V2, a) / V2
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
    arcs = half_orbit(law, wB, V2, wM, wB, turning=True)
    m1, m2 = orbit_moments(arcs, wB)
    fB = float(law.f(wB))
    energy = 2.0 * ((V2 * wB + fB) * m1 + V2 * m2)
    energy_error = 64 * EPS * 2.0 * (abs((V2 * wB + fB) * m1) + V2 * m2)
    gamma = math.sqrt(12.0 * (V2 - float(law.df(wB))) / V2)
    qs = max(24.0 * orbit_potential(law, wB, V2, a.w_a) / V2 for a in arcs) or 1.0
    res = (
        max(
            (abs(a.dw_a**2 - 24.0 * orbit_potential(law, wB, V2, a.w_a) / V2) for a in arcs[1:]),
            default=0.0,
        )
        / qs
    )
    res = max(res, abs(orbit_potential(law, wB, V2, wM)) * 24.0 / V2 / qs)
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
        out[pos] = evaluate_arcs(list(self.arcs_plus), xi[pos])
        out[~pos] = evaluate_arcs(list(self.arcs_minus), -xi[~pos])
        return out

    def dprofile(self, xi):
        """w′(ξ)."""
        xi = np.asarray(xi, dtype=float)
        out = np.empty_like(xi)
        pos = xi >= 0
        out[pos] = evaluate_arcs(list(self.arcs_plus), xi[pos], derivative=True)
        out[~pos] = -evaluate_arcs(list(self.arcs_minus), -xi[~pos], derivative=True)
        return out


def superkink(law, w_plus: float) -> PLSuperkink:
    """QC superkink with the state w₊ ahead (eqs. Rline, zero_G, TW_QC_gen3)."""
    t0 = time.perf_counter()
    sp = speeds(law, w_plus)
    V2 = sp.V_SK**2
    wc = 0.5 * (sp.w_plus + sp.w_minus)
    ap = half_orbit(law, sp.w_plus, V2, wc, sp.w_plus)
    am = half_orbit(law, sp.w_plus, V2, wc, sp.w_minus)
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
