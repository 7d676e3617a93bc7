"""QC superkinks and solitary waves for ANY hardening–softening law, numerically (paper §3).

The public names of §3 for any law, gathered from :mod:`~fpucore.qc.general_roots` (the
integrals and roots below), :mod:`~fpucore.qc.general_speeds` (speeds and ranges),
:mod:`~fpucore.qc.general_map` (the profile map ξ(s)), :mod:`~fpucore.qc.general_superkink`,
:mod:`~fpucore.qc.general_rayleigh` (the other intersections of the Rayleigh line) and
:mod:`~fpucore.qc.general_solitary`.

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

from fpucore.qc.closed_forms import first_integral
from fpucore.qc.general_rayleigh import rayleigh_roots, w_S
from fpucore.qc.general_solitary import QCSolitaryGeneral, solitary, solitary_kind
from fpucore.qc.general_speeds import (
    QCSpeeds,
    solitary_intervals,
    sound_speeds,
    speeds,
    superkink_velocity_bounds,
    superkink_w_plus_range,
    w_minus_from_w_plus,
    w_minus_sonic,
)
from fpucore.qc.general_superkink import QCSuperkinkGeneral, superkink_from_V, superkink_from_w_plus

__all__ = [
    "QCSpeeds",
    "QCSuperkinkGeneral",
    "QCSolitaryGeneral",
    "speeds",
    "sound_speeds",
    "w_minus_from_w_plus",
    "w_minus_sonic",
    "rayleigh_roots",
    "w_S",
    "solitary_intervals",
    "superkink_w_plus_range",
    "superkink_velocity_bounds",
    "superkink_from_w_plus",
    "superkink_from_V",
    "solitary",
    "solitary_kind",
    "first_integral",
]
