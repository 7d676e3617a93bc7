"""QC superkinks and solitary waves for ANY hardening–softening law, numerically (paper §3).

Built on :mod:`~fpucore.qc.general_roots` (the integrals and roots below),
:mod:`~fpucore.qc.general_speeds` (speeds and ranges, re-exported here) and
:mod:`~fpucore.qc.general_map` (the profile map ξ(s)).

The cubic closed forms of :mod:`fpucore.qc` (§4) are replaced by root finding and quadrature on
``law.f / df / ddf`` and the constants ``alpha, beta, w_star`` — so any
:class:`~fpucore.law.HardeningSofteningLaw` works (e.g. :class:`fpucore.law.PolynomialLaw`).

Cancellation-free forms (Taylor with integral remainder; inner integrals over t ∈ [0, 1] by
Gauss–Legendre, exact for polynomial laws)::

    Rayleigh slope   S(a, w) = (f(w) − f(a))/(w − a)       = ∫₀¹ f′(a + t d) dt          (eq. Rline)
    driving force    G = Φ(w₊) − Φ(w₋) − ½(w₊ − w₋)(f₊ + f₋) = ½ Δ³ ∫₀¹ t(1−t) f″(w₊ + tΔ) dt
                                                                                        (eq. zero_G)
    tangency         S(w₊, w) − f′(w) = −d ∫₀¹ t f″(w₊ + t d) dt                   (eq. cminus)
    first integral   G_B(w) = d² J,  J = ∫₀¹ (1−t)(f′(w_B + t d) − V²) dt          (eq. TW_QC_gen3)

with d = w − a (or w − w₊, w − w_B), Δ = w₋ − w₊.  The trivial roots d = 0 are divided out, so
every root below is simple and bracketed (scipy brentq), with an error bar = max(width of the
sign-change bracket actually found around the root, |F(x)|/|F′(x)|).

Profiles come from ξ(w) = ∫ dw / w′(w) (eq. TW_QC_gen3) by QUADRATURE after a substitution that
removes both endpoint singularities:

* superkink: w = w_mid − (Δ/2) tanh s gives dξ/ds = 2/(k|Δ|√Q(w)), k = √24/|V|,
  −G = (w−w₊)²(w₋−w)² Q(w) with Q > 0 smooth (for the cubic Q = |a|/4 and s = pξ exactly);
* solitary wave: w = w_B + (w_M − w_B) sech²u gives dξ/du = 2/(k √|w_M − w_B| √|R̃(w)|),
  −G_B = (w − w_B)²(w_M − w) R̃(w) with R̃ smooth and non-zero (the log singularity at w_B and
  the square-root singularity at the turning point w_M are both absorbed).

ξ(s) is tabulated by composite Gauss–Legendre (24 and 16 nodes per panel: their difference is the
error bar) and inverted by safeguarded Newton; E_ren^QC (eq. Eren_QC) uses the first integral to
reduce the integrand to (V² w_B + f(w_B)) (w − w_B) + V² (w − w_B)² (as in fpucore.qc) and the same
substitution.  The results subclass :class:`fpucore.qc.QCSuperkink` / :class:`fpucore.qc.QCSolitary`
(same fields, the result protocol, plus error bars), so every caller takes either.

With the tanh substitution the superkink is centred at w(0) = (w₊ + w₋)/2 (``w_center``, where
the discrete superkink is pinned), which equals w* only for the cubic (eq. cubic_cond1).

Accuracy (tests/law/test_law_general.py): for the cubic written as a polynomial every quantity
agrees with the closed forms to ≤ 1e-12, except solitary waves whose V lies within a relative
~1e-4 of c₊, V_SK or c₋ (or in a narrow band, w₊ near w*): there w_M, the profile and E_ren are
determined by a level set of nearly cancelling terms only to ≈ 64·eps·κ, κ = V²/|V² − c²|
(seen: 2e-11 relative), and ``energy_error`` grows with κ so that it covers the difference.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np

from fpucore.errors import ParameterError, fmt_interval, require_finite
from fpucore.law import HardeningSofteningLaw
from fpucore.qc.closed_forms import (
    QC_CHECK,
    QCSolitary,
    QCSuperkink,
    first_integral,
    first_integral_residual,
    require_V,
)
from fpucore.qc.general_map import (
    ProfileMap,
    sech_squared,
)
from fpucore.qc.general_roots import (
    EPS,
    GL_HI,
    GL_LO,
    SECH2_HALF,
    U_MAX,
    bracket_to_end,
    bracketed_root,
    df_at,
    first_integral_J,
    gauss_legendre01,
    inner_rule,
    march_outward,
    rayleigh_slope,
    scalar_J,
    scalar_slope,
)
from fpucore.qc.general_speeds import (  # re-exported: the public names of §3
    QCSpeeds,
    solitary_intervals,
    sound_speeds,
    speeds,
    superkink_velocity_bounds,
    superkink_w_plus_range,
    v_sk_of,
    w_minus_from_w_plus,
    w_minus_sonic,
)

__all__ = [
    "QCSpeeds", "QCSuperkinkGeneral", "QCSolitaryGeneral", "speeds", "sound_speeds",
    "w_minus_from_w_plus", "w_minus_sonic", "rayleigh_roots", "w_S", "solitary_intervals",
    "superkink_w_plus_range", "superkink_velocity_bounds", "superkink_from_w_plus",
    "superkink_from_V", "solitary", "first_integral",
]  # fmt: skip


# =============================================================================== superkinks
@dataclass(frozen=True)
class QCSuperkinkGeneral(QCSuperkink):
    """QC superkink of any law: the fields of :class:`fpucore.qc.QCSuperkink` plus error bars;
    the profile comes from the first integral by quadrature (module docstring).

    ``p`` = half the decay rate ahead, √(12(V² − f′(w₊)))/(2V) (the p of eq. SKsoln_cubic);
    ``p_minus`` the same behind (equal to p for the cubic only).  ``xi_error`` bounds the error
    of the tabulated ξ(s); ``rayleigh_residual``/``driving_force`` as in fpucore.qc.
    """

    p_minus: float = math.nan
    V_error: float = math.nan
    w_plus_error: float = math.nan
    w_minus_error: float = math.nan
    xi_error: float = math.nan
    tables: tuple = field(default=(), repr=False, compare=False)  # (ξ ≥ 0, ξ < 0) ξ(s) tables

    ERROR_FIELDS: ClassVar = QCSuperkink.ERROR_FIELDS + (
        "V_error", "w_plus_error", "w_minus_error", "xi_error",
    )  # fmt: skip
    DERIVED: ClassVar = QCSuperkink.DERIVED + ("symmetry_defect", "w_center")
    EXCLUDE: ClassVar = ("law", "tables")

    @property
    def w_center(self) -> float:
        """w(0) = (w₊ + w₋)/2 (= w* only for the cubic, eq. cubic_cond1)."""
        return 0.5 * (self.w_plus + self.w_minus)

    @property
    def amplitude_error(self) -> float:
        return self.w_plus_error + self.w_minus_error

    @property
    def symmetry_defect(self) -> float:
        """w₊ + w₋ − 2w* (zero for the cubic, eq. cubic_cond1; not for a general law)."""
        return self.w_plus + self.w_minus - 2.0 * self.law.w_star

    def _w_of_s(self, s):
        """w = w_mid − (Δ/2) tanh s written from the nearer end (no loss in the tails)."""
        D = self.w_minus - self.w_plus
        if np.ndim(s) == 0:
            E = math.exp(-2.0 * abs(s))
            tail = 2.0 * E / (1.0 + E)
            return np.float64(
                self.w_plus + 0.5 * D * tail if s >= 0 else self.w_minus - 0.5 * D * tail
            )
        E = np.exp(-2.0 * np.abs(s))
        tail = 2.0 * E / (1.0 + E)  # 1 − tanh|s|
        return np.where(s >= 0, self.w_plus + 0.5 * D * tail, self.w_minus - 0.5 * D * tail)

    def _s_of_xi(self, xi):
        xi = np.asarray(xi, float)
        pos, neg = self.tables  # neg tabulates g(−s): s = −s_neg for ξ < 0
        if xi.ndim == 0:
            x = float(xi)
            return np.float64(pos.s_of_scalar(x) if x >= 0 else -neg.s_of_scalar(-x))
        out = np.empty_like(xi)
        right = xi >= 0
        if right.all() or not right.any():  # one side only (scalar calls): one table
            return pos.s_of(xi) if xi.size == 0 or right.flat[0] else -neg.s_of(-xi)
        out[right] = pos.s_of(xi[right])
        out[~right] = -neg.s_of(-xi[~right])
        return out

    def profile(self, xi):
        """w(ξ), w(0) = (w₊ + w₋)/2 (= w* only for the cubic)."""
        return self._w_of_s(self._s_of_xi(xi))

    def dprofile(self, xi):
        """w′(ξ) = −(Δ/2) sech²s · ds/dξ."""
        s = self._s_of_xi(xi)
        D = self.w_minus - self.w_plus
        g = _sk_g(self.law, self.w_plus, self.w_minus, self.V * self.V)
        return -0.5 * D * sech_squared(s) / (self.tables[0].scale * g(s))

    @property
    def converged(self) -> bool:
        """Residuals at round-off and the ξ(s) table accurate (relative 1e-9 of the width)."""
        return bool(super().converged and self.xi_error * self.p <= QC_CHECK)


def _sk_g(law, wp: float, wm: float, V2: float):
    """g(s) = Q(w(s))^(−1/2), −G = (w−w₊)²(w₋−w)² Q; Q from the expansion about the nearer end
    (−J about w₊ for s ≥ 0, about w₋ for s < 0) so nothing cancels."""
    D = wm - wp

    def g(s):
        s = np.asarray(s, float)
        E = np.exp(-2.0 * np.abs(s))
        near = 0.5 * D * 2.0 * E / (1.0 + E)  # distance to the nearer end (signed like D)
        far = D - near
        dp = np.where(s >= 0, near, far)  # w − w₊
        dm = np.where(s >= 0, -far, -near)  # w − w₋
        with np.errstate(divide="ignore", invalid="ignore"):  # the branch not taken may be 0/0
            Q = np.where(
                s >= 0,
                -first_integral_J(law, wp, dp, V2) / (dm * dm),
                -first_integral_J(law, wm, dm, V2) / (dp * dp),
            )
        return 1.0 / np.sqrt(Q)

    return g


def _build_superkink(law, V, wp, wm, branch, t0, wp_err, wm_err, V_err):
    V2 = V * V
    D = wm - wp
    g = _sk_g(law, wp, wm, V2)
    scale = 2.0 * abs(V) / (math.sqrt(24.0) * abs(D))  # 2/(k|Δ|)
    edges = np.arange(0.0, U_MAX + 0.25, 0.5)
    pos, neg = ProfileMap(g, scale, edges), ProfileMap(lambda s: g(-s), scale, edges)
    fp, fm = float(law.f(wp)), float(law.f(wm))
    rscale = abs(fp) + abs(fm) + V2 * abs(D)
    ray = abs(fp - fm - V2 * (wp - wm)) / rscale
    G = float(law.phi(wp) - law.phi(wm)) - 0.5 * (wp - wm) * (fp + fm)
    G_scale = abs(float(law.phi(wp))) + abs(float(law.phi(wm))) + rscale * abs(wp)
    lam = lambda w: math.sqrt(max(12.0 * (V2 - float(law.df(w))), 0.0)) / V  # noqa: E731
    return QCSuperkinkGeneral(
        law, V, wp, wm, 0.5 * lam(wp), branch, ray, abs(G) / G_scale, time.perf_counter() - t0,
        0.5 * lam(wm), V_err, wp_err, wm_err, max(pos.table_err(), neg.table_err()), (pos, neg),
    )  # fmt: skip


def superkink_from_w_plus(law: HardeningSofteningLaw, w_plus: float) -> QCSuperkinkGeneral:
    """Superkink with state w₊ ahead: w₋ from eq. zero_G, V_SK² = S(w₊, w₋) (eq. Rline)."""
    t0 = time.perf_counter()
    sp = speeds(law, w_plus)
    branch = "lower" if sp.w_plus < law.w_star else "upper"
    return _build_superkink(
        law, sp.V_SK, sp.w_plus, sp.w_minus, branch, t0, 4 * EPS * abs(sp.w_plus),
        sp.w_minus_error, sp.V_SK_error,
    )  # fmt: skip


def superkink_from_V(
    law: HardeningSofteningLaw, V: float, branch: str = "lower"
) -> QCSuperkinkGeneral:
    """Superkink with velocity V: w₊ solves V_SK(w₊) = V on the branch ("lower": w₊ < w* < w₋,
    a front with w′ < 0; "upper": w₊ > w* > w₋), w₋ its equal-area partner."""
    t0 = time.perf_counter()
    V = require_V(V)
    if branch not in ("lower", "upper"):
        raise ParameterError("branch", branch, "'lower' (w_plus < w*) or 'upper' (w_plus > w*)")
    lo, hi = superkink_velocity_bounds(law, branch)
    if not lo < V < hi:
        raise ParameterError(
            "V", V, fmt_interval(lo, hi), f"superkink velocities on the {branch} branch"
        )
    wlo, whi = superkink_w_plus_range(law, branch)
    F = lambda wp: v_sk_of(law, wp) ** 2 - V * V  # noqa: E731
    a, b = (wlo, law.w_star) if branch == "lower" else (law.w_star, whi)
    wp, wp_err = bracketed_root(F, a, b)
    wm, wm_err = w_minus_from_w_plus(law, wp)
    V2 = float(rayleigh_slope(law, wp, wm - wp))
    dwm = abs(V2 - float(law.df(wp))) / abs(V2 - float(law.df(wm)))  # |dw₋/dw₊| (implicit fn.)
    return _build_superkink(
        law, math.sqrt(V2), wp, wm, branch, t0, wp_err, wm_err + dwm * wp_err,
        abs(math.sqrt(V2) - V) + 8 * EPS * V,
    )  # fmt: skip


# =============================================================================== Rayleigh roots
def _rayleigh_roots_one(law, w_plus: float, V: float):
    """(w_near, w_far, err_near, err_far) for one V."""
    V2 = V * V
    nan = math.nan
    if not V2 < law.c_max**2:
        return nan, nan, nan, nan
    ws = law.w_star
    fdv = lambda w: df_at(law, w) - V2  # noqa: E731
    h = lambda w: (w - w_plus) * (scalar_slope(law, w_plus, w - w_plus) - V2)  # noqa: E731
    step = max(abs(ws - w_plus), abs(ws) * 1e-3, 1e-3)
    p1 = bracketed_root(fdv, *bracket_to_end(fdv, ws, law.alpha, -1.0, step))[
        0
    ]  # f′ = V², left of w*
    p2 = bracketed_root(fdv, *bracket_to_end(fdv, ws, law.beta, 1.0, step))[0]  # … and right of w*
    piece = 0 if w_plus < p1 else (2 if w_plus > p2 else 1)
    roots = [(nan, nan)] * 3  # one per monotone piece of h: (−∞, p1), (p1, p2), (p2, ∞)
    if piece != 1 and (h(p1) < 0) != (h(p2) < 0):
        roots[1] = bracketed_root(h, p1, p2)
    if piece != 0:
        br = bracket_to_end(h, p1, law.alpha, -1.0, step)
        roots[0] = bracketed_root(h, *br) if br else (nan, nan)
    if piece != 2:
        br = bracket_to_end(h, p2, law.beta, 1.0, step)
        roots[2] = bracketed_root(h, *br) if br else (nan, nan)
    (r0, e0), (r1, e1) = [r for k, r in enumerate(roots) if k != piece]
    if w_plus <= ws:  # far = the root beyond the partner side, as in fpucore.qc.rayleigh_roots
        return r0, r1, e0, e1
    return r1, r0, e1, e0


def rayleigh_roots(law: HardeningSofteningLaw, w_plus: float, V):
    """(w_near, w_far): the other intersections of f with R(w) = f(w₊) + V²(w − w₊), labelled as
    in :func:`fpucore.qc.rayleigh_roots` (w_far is the saddle w_S for c₊ < V < c₋, w_near the
    center w_C); NaN where they do not exist (V ≥ c₋).  V may be an array.

    h = f − R is monotone on (−∞, p₁), (p₁, p₂), (p₂, ∞) with f′(p_i) = V² (within the hardening–
    softening shape), so each piece not holding w₊ has at most one root: bracketed, then brentq.
    Beyond (α, β) the bracket is searched by outward marching.
    """
    w_plus = require_finite("w_plus", w_plus)
    Va = np.asarray(V, dtype=float)
    out = [_rayleigh_roots_one(law, w_plus, float(v))[:2] for v in Va.ravel()]
    near = np.array([o[0] for o in out]).reshape(Va.shape)
    far = np.array([o[1] for o in out]).reshape(Va.shape)
    if Va.ndim == 0:
        return float(near), float(far)
    return near, far


def w_S(law: HardeningSofteningLaw, w_plus: float, V):
    """Saddle w_S(V) ≠ w₊ of eq. wS (the far Rayleigh root)."""
    return rayleigh_roots(law, w_plus, V)[1]


# =============================================================================== solitary waves
@dataclass(frozen=True)
class QCSolitaryGeneral(QCSolitary):
    """QC solitary wave of any law: the fields of :class:`fpucore.qc.QCSolitary` plus error bars.

    ``w_M`` the turning point (w(0) = w_M), ``w_T`` the next zero of G_B beyond the other saddle
    (the w_T of eq. w_T_M for the cubic; NaN if none), ``gamma`` = √(12(V² − f′(w_B)))/V the
    decay rate (the γ of eq. SWsoln_cubic).  ``energy`` is E_ren^QC (eq. Eren_QC) by quadrature,
    ``energy_error`` its bound (quadrature order difference + tail + propagated root errors +
    round-off amplified near the ends of the velocity interval).
    """

    w_B_error: float = math.nan
    w_M_error: float = math.nan
    V_SK_error: float = math.nan
    xi_error: float = math.nan
    table: object = field(default=None, repr=False, compare=False)  # ξ(u) table

    ERROR_FIELDS: ClassVar = QCSolitary.ERROR_FIELDS + (
        "w_B_error", "w_M_error", "V_SK_error", "xi_error",
    )  # fmt: skip
    EXCLUDE: ClassVar = QCSolitary.EXCLUDE + ("table",)

    @property
    def amplitude_error(self) -> float:
        return self.w_B_error + self.w_M_error

    def profile(self, xi):
        xi = np.asarray(xi, float)
        u = self.table.s_of_scalar(abs(float(xi))) if xi.ndim == 0 else self.table.s_of(np.abs(xi))
        return self.w_B + (self.w_M - self.w_B) * sech_squared(u)

    def dprofile(self, xi):
        """w′(ξ) = sign(ξ) (dw/du)/(dξ/du), dw/du = −2 dM sech²u tanh u."""
        xi = np.asarray(xi, float)
        u = self.table.s_of(np.abs(xi))
        dw = -2.0 * (self.w_M - self.w_B) * sech_squared(u) * np.tanh(u)
        return np.sign(xi) * dw / (self.table.scale * self.table.g(u))


def _sw_g(law, wB: float, wM: float, V2: float):
    """g(u) = |R̃(w(u))|^(−1/2), w = w_B + dM sech²u, −G_B = (w−w_B)²(w_M−w) R̃:
    near w_B (sech²u < ½) R̃ = −J(w_B, d)/(dM − d); near w_M R̃ = ∫₀¹ h_B(w_M + τ(w − w_M)) dτ/d²
    (G_B(w_M) = 0, h_B = G_B′ = f − f(w_B) − V²(· − w_B))."""
    dM = wM - wB
    fB = float(law.f(wB))
    t, wt = inner_rule(law)

    def g(u):
        u = np.asarray(u, float)
        sech2 = sech_squared(u)
        d = dM * sech2
        gap = dM * np.tanh(u) ** 2  # dM − d
        s = wM - gap[..., None] * t  # w_M + τ (w − w_M)
        hB = law.f(s) - fB - V2 * (s - wB)  # |s − w_B| ≥ |dM|/2 here: mild cancellation
        with np.errstate(invalid="ignore", divide="ignore"):  # each form is used where it is finite
            R_far = -first_integral_J(law, wB, d, V2) / gap
            R_near = np.sum(hB * wt, axis=-1) / (d * d)
            R = np.where(np.abs(u) > SECH2_HALF, R_far, R_near)
        return 1.0 / np.sqrt(np.abs(R))

    return g


def solitary(
    law: HardeningSofteningLaw, w_plus: float, V: float, check: bool = True
) -> QCSolitaryGeneral:
    """QC solitary wave for the state w₊ ahead of the associated superkink, velocity V (eq. wB):
    V ∈ (c₊, V_SK) → w_B = w₊; V ∈ (V_SK, c₋) → w_B = w_S(V).  ``check=False`` skips the
    first-integral check on the profile (a third of the cost; families need only E and w_M):
    ``first_integral_residual`` is then NaN."""
    t0 = time.perf_counter()
    V = require_V(V)
    sp = speeds(law, w_plus)
    w_plus, cp, vsk, cm = sp.w_plus, sp.c_plus, sp.V_SK, sp.c_minus
    valid = f"{fmt_interval(cp, vsk)} or {fmt_interval(vsk, cm)}"
    if V == vsk:
        raise ParameterError("V", V, valid, "V = V_SK is the superkink itself")
    V2 = V * V
    w_near, w_far, _, far_err = _rayleigh_roots_one(law, w_plus, V)
    if cp < V < vsk:
        interval, wB, other, wB_err = "below", w_plus, w_far, 0.0
    elif vsk < V < cm:
        interval, wB, other, wB_err = "above", w_far, w_plus, far_err
    else:
        raise ParameterError("V", V, valid, f"solitary-wave velocities for w_plus={w_plus:.10g}")
    if not (math.isfinite(w_near) and math.isfinite(other)):
        raise ParameterError("V", V, valid, "too close to an end of the interval to resolve")
    Jw = lambda w: scalar_J(law, wB, w - wB, V2)  # noqa: E731
    if not (Jw(w_near) < 0 < Jw(other)):
        raise ParameterError("V", V, valid, "too close to an end of the interval to resolve")
    wM, wM_err = bracketed_root(Jw, w_near, other)
    sgn = 1.0 if other > wB else -1.0
    br = march_outward(Jw, other, sgn, 0.125 * abs(other - wB), n=80)
    wT = bracketed_root(Jw, *br)[0] if br else math.nan
    dM = wM - wB
    gamma = math.sqrt(12.0 * (V2 - float(law.df(wB)))) / V

    g = _sw_g(law, wB, wM, V2)
    scale = 2.0 * V / (math.sqrt(24.0) * math.sqrt(abs(dM)))
    # grade the panels toward u = 0 when the orbit grazes the other saddle (flat top near V_SK):
    # there R̃ ≈ ε + c u², so panels must resolve u ~ √ε
    eps_rel = max(abs(wM - other) / abs(dM), 1e-300)
    J_lev = int(min(60, max(0, math.ceil(-math.log2(0.05 * math.sqrt(eps_rel))))))
    edges = np.unique(np.concatenate([[0.0], 2.0 ** -np.arange(J_lev, 0, -1.0),
                                      np.arange(0.5, U_MAX + 0.25, 0.5)]))  # fmt: skip
    m = ProfileMap(g, scale, edges)

    # E_ren^QC = (V² w_B + f_B) ∫d dξ + V² ∫d² dξ over the whole line (even profile)
    fB = float(law.f(wB))
    c1, c2 = V2 * wB + fB, V2
    a, b = edges[:-1], edges[1:]
    hh = (b - a)[:, None]
    vals = []
    for n in (GL_HI, GL_LO):
        x, wq = gauss_legendre01(n)
        u = a[:, None] + hh * x
        d = dM * sech_squared(u)
        jac = scale * g(u) * wq * hh
        vals.append((2.0 * np.sum(d * jac), 2.0 * np.sum(d * d * jac)))
    (I1, I2), (I1l, I2l) = vals
    t1, t2 = c1 * I1, c2 * I2
    tail = 2.0 * abs(c1 * dM) * 4.0 * math.exp(-2.0 * U_MAX) * m.slope_end
    energy = float(t1 + t2)
    # propagated root errors: near V_SK the plateau length ~ (1/λ_o) log(1/ε), ε = |w_M − other|
    # (R̃ ≈ ε + c u²), so δE ≈ |c1 dM + c2 dM²| (2/λ_o) δε/ε to first order
    lam_o = math.sqrt(max(12.0 * (V2 - float(law.df(other))), EPS)) / V
    d_eps = wM_err + (far_err if interval == "below" else 0.0) + wB_err
    prop = abs(c1 * dM + c2 * dM * dM) * 2.0 / lam_o * d_eps / max(abs(wM - other), EPS)
    # … and the level G_B(other) ≈ ½κ ε² itself is a difference of O(V² d²) terms
    d_o = other - wB
    G_o = abs(d_o * d_o * float(first_integral_J(law, wB, d_o, V2)))
    prop += abs(c1 * dM + c2 * dM * dM) / lam_o * 8 * EPS * V2 * d_o * d_o / max(G_o, 1e-300)
    energy_err = float(
        abs(c1 * (I1 - I1l))
        + abs(c2 * (I2 - I2l))
        + tail
        + prop
        + 128 * EPS * (1.0 + V2 / (V2 - float(law.df(wB)))) * (abs(t1) + abs(t2))
    )  # round-off of J ∝ f′ − V² is amplified by κ_B = V²/(V² − f′(w_B)) (near-sonic waves)

    kind = "tensile" if dM > 0 else "compressive"
    sw = QCSolitaryGeneral(
        law, V, w_plus, wB, wT, wM, gamma, kind, interval, vsk, cp, cm, energy, energy_err,
        math.nan, 0.0, wB_err, wM_err, sp.V_SK_error, m.err, m,
    )  # fmt: skip
    xi = np.linspace(0.0, 12.0, 32) / gamma
    fi = first_integral_residual(law, sw.profile(xi), sw.dprofile(xi), wB, V) if check else math.nan
    # xi_error includes the inverse tables' error once a profile has been evaluated (check=True)
    return replace(
        sw, first_integral_residual=fi, xi_error=m.err, elapsed_s=time.perf_counter() - t0
    )
