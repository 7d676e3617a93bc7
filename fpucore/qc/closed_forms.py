"""Quasicontinuum (QC) traveling waves: the closed forms of paper §3–4 for the cubic law.

The QC traveling-wave equation (eq. TW_QC_gen2) is

    −V²/12 w″ + V² w − f(w) = V² w₊ − f(w₊),

with first integral (eq. TW_QC_gen3)  V²/24 (w′)² + G(w) = 0,
G(w) = Φ(w) − Φ(w₊) − f(w₊)(w − w₊) − V²/2 (w − w₊)².

Velocities are taken positive (every wave with V has a mirror wave with −V).  The sound speeds
c₊ < V_SK < c₋, the velocity ranges and the Rayleigh-line roots are in
:mod:`fpucore.qc.cubic_speeds` (re-exported here); this module holds the waves: superkinks
(eq. SKsoln_cubic), solitary waves (eq. SWsoln_cubic) and their renormalized energy (eq. E_ren).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from fpucore.errors import ParameterError, fmt_interval
from fpucore.law import CubicLaw, HardeningSofteningLaw
from fpucore.qc.cubic_speeds import (  # re-exported: the speeds are part of the closed forms
    EPS,
    c_max_squared,
    cubic_law,
    finite_array,
    rayleigh_roots,
    require_V,
    require_w_plus,
    solitary_intervals,
    sound_speed_plus,
    sound_speeds,
    superkink_velocity_bounds,
    w_minus_sonic,
    w_S,
)
from fpucore.qc.first_integrals import (  # re-exported: the checks of the closed forms
    V_SPAN,
    W_SPAN,
    WP_MAX,
    first_integral,
    first_integral_residual,
)
from fpucore.result import Result, status_of

if TYPE_CHECKING:
    from fpucore.law.base import Strain

__all__ = [
    "EPS",
    "QC_CHECK",
    "V_SPAN",
    "W_SPAN",
    "WP_MAX",
    "c_max_squared",
    "cubic_law",
    "require_V",
    "require_w_plus",
    "superkink_velocity_bounds",
    "sound_speeds",
    "sound_speed_plus",
    "solitary_intervals",
    "w_minus_sonic",
    "rayleigh_roots",
    "w_S",
    "QCSuperkink",
    "superkink_from_V",
    "superkink_from_w_plus",
    "solitary_closed_form",
    "QCSolitary",
    "first_integral",
    "finite_array",
    "first_integral_residual",
    "solitary",
]

QC_CHECK = 1e-9  # scaled residual of a closed form above which it is reported as not converged


# =============================================================================== superkinks
@dataclass(frozen=True)
class QCSuperkink(Result):
    """QC superkink (eq. SKsoln_cubic): w(ξ) = w* − (w₋ − w₊)/2 · tanh(p ξ), ξ = x − V t.

    ``branch`` is "lower" when w₊ < w* (a front with w′ < 0) and "upper" when w₊ > w*.
    Error estimates: ``rayleigh_residual`` = |f(w₊) − f(w₋) − V²(w₊ − w₋)| and ``driving_force``
    = |G| of eq. zero_G, both scaled by |f(w₋)| + |f(w₊)| (round-off level for exact forms).
    """

    law: CubicLaw
    V: float
    w_plus: float
    w_minus: float
    p: float
    branch: str
    rayleigh_residual: float
    driving_force: float
    elapsed_s: float

    @property
    def w_star(self) -> float:
        return self.law.w_star

    @property
    def w_center(self) -> float:
        """w(0), the value a discrete superkink is pinned at: w* (eq. cubic_cond1)."""
        return self.law.w_star

    @property
    def amplitude(self) -> float:
        return abs(self.w_minus - self.w_plus)

    @property
    def width(self) -> float:
        """Width 1/p of the transition layer (lattice units)."""
        return 1.0 / self.p

    def profile(self, xi: Strain) -> Strain:
        xi = np.asarray(xi, dtype=float)
        return 0.5 * (self.w_plus + self.w_minus) - 0.5 * (self.w_minus - self.w_plus) * np.tanh(
            self.p * xi
        )

    def dprofile(self, xi: Strain) -> Strain:
        xi = np.asarray(xi, dtype=float)
        E = np.exp(-2.0 * self.p * np.abs(xi))  # sech² = 4E/(1+E)², no overflow at large |ξ|
        return -2.0 * (self.w_minus - self.w_plus) * self.p * E / (1.0 + E) ** 2

    ERROR_FIELDS: ClassVar[tuple[str, ...]] = ("rayleigh_residual", "driving_force")
    DERIVED: ClassVar[tuple[str, ...]] = ("amplitude", "width", "converged", "status", "message")
    EXCLUDE: ClassVar[tuple[str, ...]] = ("law",)

    @property
    def converged(self) -> bool:
        """Closed forms: the scaled residuals sit at round-off (see :data:`QC_CHECK`)."""
        return bool(max(self.rayleigh_residual, self.driving_force) <= QC_CHECK)

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def message(self) -> str:
        return "" if self.converged else "closed-form residuals above round-off"


def _superkink(law: CubicLaw, V: float, w_plus: float, w_minus: float, branch: str, t0: float):
    p = math.sqrt(6.0 * law.abs_a) * abs(w_minus - w_plus) / (2.0 * V)
    fp, fm = float(law.f(w_plus)), float(law.f(w_minus))
    scale = abs(fp) + abs(fm) + V * V * abs(w_minus - w_plus)
    ray = abs(fp - fm - V * V * (w_plus - w_minus)) / scale
    G = float(law.phi(w_plus) - law.phi(w_minus)) - 0.5 * (w_plus - w_minus) * (fp + fm)
    G_scale = abs(float(law.phi(w_plus))) + abs(float(law.phi(w_minus))) + scale * abs(w_plus)
    return QCSuperkink(
        law, V, w_plus, w_minus, p, branch, ray, abs(G) / G_scale, time.perf_counter() - t0
    )


def superkink_from_V(law: HardeningSofteningLaw, V: float, branch: str = "lower") -> QCSuperkink:
    """Superkink with velocity V: w± = w* ∓ √((c_max² − V²)/|a|) (eq. wpm_cubic).

    branch="lower" gives w₊ < w* < w₋; "upper" the mirror image w₊ > w* > w₋.
    """
    t0 = time.perf_counter()
    law = cubic_law(law)
    V = require_V(V)
    lo, hi = superkink_velocity_bounds(law)
    if not lo < V < hi:
        raise ParameterError(
            "V", V, fmt_interval(lo, hi), "superkink velocities, eq. V_bounds_cubic"
        )
    if not isinstance(branch, str) or branch not in ("lower", "upper"):
        raise ParameterError("branch", branch, "'lower' (w_plus < w*) or 'upper' (w_plus > w*)")
    delta = math.sqrt((hi - V) * (hi + V) / law.abs_a)  # no cancellation near V_hi
    s = -1.0 if branch == "lower" else 1.0
    return _superkink(law, V, law.w_star + s * delta, law.w_star - s * delta, branch, t0)


def superkink_from_w_plus(law: HardeningSofteningLaw, w_plus: float) -> QCSuperkink:
    """Superkink with state w₊ ahead: w₋ = 2w* − w₊ (eq. cubic_cond1), V_SK by eq. cubic_cond2."""
    t0 = time.perf_counter()
    law = cubic_law(law)
    w_plus = require_w_plus(law, w_plus)
    V = math.sqrt(c_max_squared(law) - law.abs_a * (w_plus - law.w_star) ** 2)
    branch = "lower" if w_plus < law.w_star else "upper"
    return _superkink(law, V, w_plus, 2.0 * law.w_star - w_plus, branch, t0)


# =============================================================================== solitary waves
def _theta_ratios(theta):
    """(θ/sinh θ, (θ cosh θ − sinh θ)/sinh³ θ) for θ > 0 (arrays or scalars), with the series
    θ cosh θ − sinh θ = Σ_{k≥1} 2k θ^{2k+1}/(2k+1)! where the direct form cancels (θ < 0.5)."""
    th = np.asarray(theta, dtype=float)
    sh, ch = np.sinh(th), np.cosh(th)
    num, term = np.zeros_like(th), th.copy()
    for k in range(1, 14):
        term = term * th * th / ((2 * k) * (2 * k + 1))
        num = num + 2 * k * term
    return th / sh, np.where(th < 0.5, num, th * ch - sh) / sh**3


def solitary_closed_form(law: CubicLaw, w_B: Strain, V: Strain) -> tuple[Strain, ...]:
    """The closed form of a QC solitary wave from its background w_B and velocity V (arrays or
    scalars): returns (dM, dT, gamma, energy, energy_error, ok) with w_M = w_B + dM,
    w_T = w_B + dT (eq. w_T_M), gamma of eq. SWsoln_cubic and E_ren^QC (eq. Eren_QC).

    Turning points: G(w_B + d) = d² [a/4 d² + f″(w_B)/6 d + (f′(w_B) − V²)/2] (eq. TW_QC_gen3
    with w₊ → w_B), solved as a stable quadratic.  Energy: with u = w − w_B the Φ and w′² terms
    cancel through the first integral, E = (V² w_B + f(w_B)) ∫u + V² ∫u², and
    u = (2 dM dT / B)/(s + cosh γξ), s = cosh θ, gives ∫u = (2 dM dT/B)(2/γ) θ/sinh θ and
    ∫u² = (2 dM dT/B)² (2/γ)(θ cosh θ − sinh θ)/sinh³ θ.  ``ok`` is False where the quadratic has
    no real pair of same-sign roots (round-off at an interval end)."""
    law = cubic_law(law)
    w_B, V = finite_array("w_B", w_B), finite_array("V", V)
    if np.any(V <= 0):
        raise ParameterError("V", float(V[V <= 0].flat[0]), "V > 0")
    out = (w_B <= law.alpha) | (w_B >= law.beta)
    if np.any(out):
        raise ParameterError(
            "w_B",
            float(w_B[out].flat[0]),
            fmt_interval(law.alpha, law.beta),
            "backgrounds lie in the convex interval (alpha, beta)",
        )
    A, B, C = law.a / 4.0, law.ddf(w_B) / 6.0, 0.5 * (law.df(w_B) - V * V)
    disc = B * B - 4.0 * A * C
    ok = (disc > 0) & (C < 0)
    disc = np.where(ok, disc, 1.0)
    q = -0.5 * (B + np.copysign(np.sqrt(disc), B))
    r1, r2 = q / A, C / q
    near = np.abs(r1) < np.abs(r2)
    dM, dT = np.where(near, r1, r2), np.where(near, r2, r1)
    gamma = math.sqrt(6.0 * law.abs_a) / V * np.sqrt(np.abs(dM * dT))
    Bc = dT - dM
    s_m1 = 2.0 * dM / Bc  # s − 1 without cancellation
    theta = np.log1p(s_m1 + np.sqrt(np.abs(s_m1 * (s_m1 + 2.0))))
    r_th, k_th = _theta_ratios(np.where(ok, theta, 1.0))
    amp = 2.0 * dM * dT / Bc
    t1 = (V * V * w_B + law.f(w_B)) * amp / gamma * 2.0 * r_th
    t2 = V * V * amp * amp / gamma * 2.0 * k_th
    return dM, dT, gamma, t1 + t2, 64.0 * EPS * (np.abs(t1) + np.abs(t2)), ok


@dataclass(frozen=True)
class QCSolitary(Result):
    """QC solitary wave (eq. SWsoln_cubic) with background w_B (eq. wB) and turning points
    w_T, w_M (eq. w_T_M); w(0) = w_M.

    ``interval`` is "below" for c₊ < V < V_SK (w_B = w₊) and "above" for V_SK < V < c₋
    (w_B = w_S(V)).  ``energy`` is E_ren^QC (eq. Eren_QC) in closed form, with
    ``energy_error`` its round-off bound; ``first_integral_residual`` is max |V²/24 w′² + G(w)|
    over the profile, scaled (a round-off-level check of the closed form).
    """

    law: CubicLaw
    V: float
    w_plus: float
    w_B: float
    w_T: float
    w_M: float
    gamma: float
    kind: str
    interval: str
    V_SK: float
    c_plus: float
    c_minus: float
    energy: float
    energy_error: float
    first_integral_residual: float
    elapsed_s: float

    @property
    def amplitude(self) -> float:
        """w_amp^QC = |w_M − w_B| (eq. SWQC_amp)."""
        return abs(self.w_M - self.w_B)

    @property
    def width(self) -> float:
        return 1.0 / self.gamma

    def _parts(self, xi):
        xi = np.asarray(xi, dtype=float)
        dM, dT = self.w_M - self.w_B, self.w_T - self.w_B
        E = np.exp(-self.gamma * np.abs(xi))  # overflow-free form of cosh
        den = 2.0 * (dM + dT) * E + (dT - dM) * (1.0 + E * E)
        return xi, dM, dT, E, den

    def profile(self, xi: Strain) -> Strain:
        xi, dM, dT, E, den = self._parts(xi)
        return self.w_B + 4.0 * dM * dT * E / den

    def dprofile(self, xi: Strain) -> Strain:
        xi, dM, dT, E, den = self._parts(xi)
        return -4.0 * dM * dT * (dT - dM) * self.gamma * np.sign(xi) * (1.0 - E * E) * E / den**2

    ERROR_FIELDS: ClassVar[tuple[str, ...]] = ("energy_error", "first_integral_residual")
    DERIVED: ClassVar[tuple[str, ...]] = ("amplitude", "converged", "status", "message")
    EXCLUDE: ClassVar[tuple[str, ...]] = ("law", "w_plus", "V_SK", "c_plus", "c_minus")

    @property
    def converged(self) -> bool:
        """Closed forms: the scaled first-integral residual sits at round-off."""
        return bool(self.first_integral_residual <= QC_CHECK)

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def message(self) -> str:
        return "" if self.converged else "first-integral residual above round-off"


_XI_CHECK = np.linspace(0.0, 12.0, 32)


def solitary(law: HardeningSofteningLaw, w_plus: float, V: float) -> QCSolitary:
    """QC solitary wave associated with the superkink whose state ahead is w₊, velocity V.

    V must lie in (c₊, V_SK) (background w_B = w₊) or (V_SK, c₋) (w_B = w_S(V)).
    """
    t0 = time.perf_counter()
    law = cubic_law(law)
    w_plus = require_w_plus(law, w_plus)
    V = require_V(V)
    cp, vsk, cm = sound_speeds(law, w_plus)
    valid = f"{fmt_interval(cp, vsk)} or {fmt_interval(vsk, cm)}"
    if V == vsk:
        raise ParameterError("V", V, valid, "V = V_SK is the superkink itself")
    if cp < V < vsk:
        interval, w_B = "below", w_plus
    elif vsk < V < cm:
        interval, w_B = "above", float(w_S(law, w_plus, V))
    else:
        raise ParameterError("V", V, valid, f"solitary-wave velocities for w_plus={w_plus:.10g}")

    dM, dT, gamma, energy, energy_error, ok = (float(x) for x in solitary_closed_form(law, w_B, V))
    if not ok:  # cannot happen inside the intervals; guards round-off at their ends
        raise ParameterError("V", V, valid, "too close to an end of the interval to resolve")

    kind = "tensile" if dM > 0 else "compressive"
    sw = QCSolitary(
        law,
        V,
        w_plus,
        w_B,
        w_B + dT,
        w_B + dM,
        gamma,
        kind,
        interval,
        vsk,
        cp,
        cm,
        energy,
        energy_error,
        math.nan,
        0.0,
    )
    xi = _XI_CHECK / gamma  # one half of the (even) profile, out to 12 widths
    fi = first_integral_residual(law, sw.profile(xi), sw.dprofile(xi), w_B, V)
    return replace(sw, first_integral_residual=fi, elapsed_s=time.perf_counter() - t0)
