"""The computable range of a force law: one set of scale checks for the cubic and any polynomial.

Every closed form of paper §3–4 multiplies at most an energy density (≤ c_max² W², since
0 < f′ ≤ c_max² on (α, β)) by one more strain; the scaling w = λu maps the coefficients c_k to
c_k λ^(k−1) with V unchanged, so the shape of a law is scale-free and W = max(|α|, β) (the finite
ends), c_max² = f′(w*) set its units.  Laws whose units leave the bounds below would overflow or
underflow in some closed form (b = 1.4e154: b² = inf; b = 1e80: energies ~1e318), so they are
refused — for the cubic (:class:`~fpucore.law.CubicLaw`) and the polynomial
(:class:`~fpucore.law.PolynomialLaw`) alike, e.g. ``CubicLaw(-1e200, 1e200)`` and the text
``"w + 1e200*w**2 - 1e200*w**3"``.

A polynomial's coefficients are first bounded by :data:`COEFF_RANGE` (each nonzero |c_k|),
so that its derivative's companion matrix (``numpy.roots``) stays finite: 1e308 or a subnormal
1e-320 otherwise give a ``LinAlgError``.  Every cubic inside the range below has coefficients
well inside it (|a| ∈ [1e-60, 1e60], b ≤ 1e60).
"""

from __future__ import annotations

import math

from fpucore.errors import ParameterError

W_RANGE = (1e-30, 1e30)  # strain scale W = max(|α|, β)
CMAX2_MAX = 1e60  # speed scale c_max² = f′(w*)
ENERGY_W_MAX = 1e120  # c_max² W³: the largest product of an energy density and a strain
W_STAR_MIN = 1e-100  # w* / W: the inflection point stays a representable strain
COEFF_RANGE = (1e-150, 1e150)  # |c_k| of a polynomial law (or c_k = 0)
CONTRAST_MAX = 2.0**52  # stiffness contrast f′(w*)/f′(0) of a chain computed discretely
# strain scale W = max(|α|, β) below which the discrete wave's error bounds are lost: measured
# (superkink, N = 64) a NaN profile bound on converged waves at W = 1.8e-8 (w + w² − 1e15 w³) and
# 3.4e-8 (the paper's cubic scaled), finite bounds from W = 7e-8 up
DISCRETE_W_MIN = 1e-6


def require_coefficient(name: str, c: float) -> float:
    """A polynomial coefficient c_k: 0 or |c_k| within :data:`COEFF_RANGE`."""
    if c != 0.0 and not COEFF_RANGE[0] <= abs(c) <= COEFF_RANGE[1]:
        raise ParameterError(
            name,
            c,
            f"0 or {COEFF_RANGE[0]:g} <= |{name}| <= {COEFF_RANGE[1]:g}",
            "outside this range the roots of f' and f'' (companion-matrix eigenvalues) and the "
            "closed forms overflow or underflow in double precision",
        )
    return c


def require_computable(
    name: str, value: object, alpha: float, beta: float, w_star: float, c_max2: float, what: str
) -> None:
    """Refuse a law whose strain scale W = max(|α|, β) (finite ends only), speed scale
    c_max² = f′(w*) or inflection w* leave the computable range (module docstring).
    ``name``/``value``: what the refusal names (``"(a, b)"``, ``"coeffs"``); ``what``: how
    c_max² is written for this law (``"1 + b^2/(3|a|)"``, ``"f'(w*)"``)."""
    W = max(abs(alpha) if math.isfinite(alpha) else 0.0, beta)
    prod = c_max2 * W**3 if (math.isfinite(c_max2) and W < 1e100) else math.inf
    if (
        not (math.isfinite(W) and math.isfinite(c_max2))
        or not W_RANGE[0] <= W <= W_RANGE[1]
        or c_max2 > CMAX2_MAX
        or prod > ENERGY_W_MAX
        or not w_star >= W_STAR_MIN * W  # w* would underflow (b = 1e-300); NaN refused too
    ):
        raise ParameterError(
            name,
            value,
            f"laws with strain scale W = max(|alpha|, beta) in [{W_RANGE[0]:g}, {W_RANGE[1]:g}], "
            f"c_max^2 = {what} <= {CMAX2_MAX:g}, c_max^2 W^3 <= {ENERGY_W_MAX:g} and "
            f"w* >= {W_STAR_MIN:g} W (here W = {W:.3g}, c_max^2 = {c_max2:.3g}, "
            f"w* = {w_star:.3g})",
            "outside this range the closed forms overflow or underflow in double precision",
        )


def require_discrete(law, name: str = "law"):
    """Refuse, before any discrete work (a traveling wave, a simulation), a law whose strain
    scale is below :data:`DISCRETE_W_MIN` or whose stiffness
    contrast K = f′(w*)/f′(0) = c_max²/c_1 exceeds :data:`CONTRAST_MAX` = 2^52 = 1/eps.

    K is the one shape number the scaling w = λu leaves.  At the strains of a wave or of a
    simulation f′ is a sum of terms of size ~K c_1 whose round-off (eps K c_1) reaches f′(0)
    itself when K ≥ 1/eps: the sound speed near w = 0, the tails and the linearisation have
    lost all their digits.  Measured (superkink and solitary wave at N = 64, the cubic
    w + b w² − w³, K ≈ b²/3): converged with finite error bars up to K = 3e17; at K = 3e19 the
    solitary wave's energy error is lost and ``w + 1e20 w² − 1e20 w³`` (K = 3.3e19) gives no
    converged superkink.  The quasicontinuum closed forms (paper §3–4) stay exact there (they
    evaluate f, Φ at two or three strains, tested in exact arithmetic) and are not refused."""
    W = max(abs(law.alpha) if math.isfinite(law.alpha) else 0.0, law.beta)
    if not W >= DISCRETE_W_MIN:
        what = getattr(law, "expression", None) or law.describe()
        raise ParameterError(
            name,
            what,
            f"a law with strain scale W = max(|alpha|, beta) >= {DISCRETE_W_MIN:g} for discrete "
            f"waves and simulations (here W = {W:.3g}; scale the strain, w = lambda u)",
            "below it the discrete wave's error bounds are lost (the QC closed forms of "
            "fpucore.qc still apply)",
        )
    if getattr(law, "breakpoints", ()):
        # a PL law's f′ is one stored slope, not a sum of large terms: no digits are lost at any
        # contrast, and a zero first modulus (c₁ = 0) is the degenerate case of compact waves
        return law
    c1 = float(law.df(0.0))
    c_max2 = float(law.df(law.w_star))
    contrast = c_max2 / c1 if c1 > 0 else math.inf
    if not contrast <= CONTRAST_MAX:
        what = getattr(law, "expression", None) or law.describe()
        raise ParameterError(
            name,
            what,
            f"a law with stiffness contrast f'(w*)/f'(0) <= 2^52 = {CONTRAST_MAX:.3g} for "
            f"discrete waves and simulations (here {c_max2:.3g}/{c1:.3g} = {contrast:.3g})",
            "above it f' at the chain's strains is a sum of terms whose round-off exceeds "
            "f'(0): sound speeds, tails and the linearisation lose all their digits (the QC "
            "closed forms of fpucore.qc still apply)",
        )
    return law
