"""The first integral of the QC traveling-wave equation (paper §3, eq. TW_QC_gen3) for any
hardening–softening law: H(w, w′) on the phase plane, zero on every orbit through the saddle,
the spans it is evaluated within, and its scaled residual on a computed orbit (the check of
every QC solitary wave)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from fpucore.errors import ParameterError, fmt_interval, require_finite
from fpucore.law import HardeningSofteningLaw, require_law
from fpucore.qc.cubic_speeds import finite_array, require_V

if TYPE_CHECKING:
    from fpucore.law.base import Strain

V_SPAN = 1e3  # velocities of phase portraits / first integrals: V <= V_SPAN c_max
W_SPAN = 10.0  # strains of a first integral within W_SPAN (β − α) of (α, β)
WP_MAX = 1e100  # |w′| of a first integral (V²w′² stays finite: c_max² <= 1e60, law/cubic.py)


def first_integral(
    law: HardeningSofteningLaw, w: Strain, wp: Strain, w_ref: float, V: float
) -> Strain:
    """H(w, w′) = V²/24 w′² + Φ(w) − Φ(w_ref) − f(w_ref)(w − w_ref) − V²/2 (w − w_ref)².

    Zero on every orbit through the saddle (w_ref, 0) (eq. TW_QC_gen3); its level sets are the
    exact phase portrait of eq. TW_QC_gen2 (with w₊ → w_ref on the right-hand side).
    """
    law = require_law(law)
    w_ref, V = require_finite("w_ref", w_ref), require_V(V)
    w, wp = finite_array("w", w), finite_array("wp", wp)
    span = law.beta - law.alpha
    lo, hi = law.alpha - W_SPAN * span, law.beta + W_SPAN * span
    for name, x in (("w", w), ("w_ref", np.asarray(w_ref))):
        out = (x < lo) | (x > hi)
        if np.any(out):
            raise ParameterError(
                name,
                float(x[out].flat[0]),
                fmt_interval(lo, hi, open_=False),
                f"strains within {W_SPAN:g} (beta - alpha) of the convex interval",
            )
    vmax = V_SPAN * law.c_max
    if V > vmax:
        raise ParameterError("V", V, f"(0, {vmax:.10g}]", f"V <= {V_SPAN:g} c_max")
    if np.any(np.abs(wp) > WP_MAX):
        raise ParameterError("wp", "entries beyond 1e100", f"|wp| <= {WP_MAX:g}")
    d = w - w_ref
    return (
        V * V / 24.0 * wp * wp
        + law.phi(w)
        - law.phi(w_ref)
        - law.f(w_ref) * d
        - 0.5 * V * V * d * d
    )


def first_integral_residual(law, w, wp, w_ref: float, V: float) -> float:
    """max |H| on (w, w′) scaled by the size of the terms that cancel in H (so the ratio is a
    round-off-level number for an exact orbit); H as in :func:`first_integral`."""
    d = w - w_ref
    phi_w, phi_r, f_r = law.phi(w), float(law.phi(w_ref)), float(law.f(w_ref))
    H = V * V / 24.0 * wp * wp + phi_w - phi_r - f_r * d - 0.5 * V * V * d * d
    scale = np.abs(phi_w) + abs(phi_r) + np.abs(f_r * d) + V * V * (d * d + wp * wp / 24.0)
    return float(np.max(np.abs(H) / (scale + 1e-300)))
