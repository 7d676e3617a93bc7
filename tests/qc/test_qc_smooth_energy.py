"""E_ren^QC (eq. Eren_QC) and the QC solitary-wave profile w(ξ) of the smooth presets against
references computed here at 40 digits with mpmath from the exact expression, not through fpucore:
Φ from antiderivatives written from the formulas, the turning point from G_B (eq. TW_QC_gen3), the
energy as 2∫_{w_B}^{w_M} (½V²(w² − w_B²) + Φ(w) − Φ(w_B) + V²w′²/24)/|w′| dw with
V²w′²/24 = −G_B(w) (the first integral), by tanh-sinh quadrature, and ξ(w) = ∫_w^{w_M} dw/|w′|.
Each value must lie within the error bar the route reports."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from smooth_reference import antiderivative, force

from fpucore import qc
from fpucore.law.presets import preset_law

SMOOTH = ("exponential", "tanh", "rational")
DPS = 40


def reference(name, sw, V):
    """(w_B, w_M, E_ren, ξ(w) function) at DPS digits."""
    Phi, f = antiderivative(name), force(name)
    V2 = mpmath.mpf(V) ** 2
    wp = mpmath.mpf(sw.w_plus)
    if sw.w_B == sw.w_plus:
        wB = wp
    else:  # above V_SK: w_B = w_S, the far root of the Rayleigh line through w₊
        wB = mpmath.findroot(lambda w: f(w) - f(wp) - V2 * (w - wp), mpmath.mpf(sw.w_B))
    fB = f(wB)

    def GB(w):
        return Phi(w) - Phi(wB) - fB * (w - wB) - V2 / 2 * (w - wB) ** 2

    wM = mpmath.findroot(GB, mpmath.mpf(sw.w_M))
    # |w′| (abs: within ~1e-40 of w_M the rounding of G_B may give it either sign)
    speed = lambda w: mpmath.sqrt(abs(24 * GB(w))) / mpmath.sqrt(V2)  # noqa: E731

    def density(w):  # energy density / |w′|, with V²w′²/24 = −G_B
        return (V2 / 2 * (w**2 - wB**2) + Phi(w) - Phi(wB) - GB(w)) / speed(w)

    # ξ runs over the measure dw/|w′| on the increasing w axis (a compressive wave: w_M < w_B)
    lo, hi = sorted((wB, wM))
    E = 2 * mpmath.quad(density, [lo, (lo + hi) / 2, hi])
    # (a node within ~1e-40 of w_M where G_B rounds to 0 has a weight ~1e-40: dropped)
    inv = lambda s: (lambda v: 1 / v if v else mpmath.mpf(0))(speed(s))  # noqa: E731
    xi = lambda w: mpmath.quad(inv, sorted((w, wM)))  # noqa: E731
    return wB, wM, E, xi


def cases():
    for name in SMOOTH:
        for side in ("below", "above"):
            yield name, side


@pytest.mark.parametrize("name, side", list(cases()))
def test_energy_and_profile_against_40_digit_quadrature(name, side):
    law = preset_law(name)
    lo, hi = qc.superkink_w_plus_range(law, "lower")
    w_plus = 0.5 * (max(lo, law.alpha) + hi)
    cp, vsk, cm = qc.sound_speeds(law, w_plus)
    V = cp + 0.5 * (vsk - cp) if side == "below" else vsk + 0.5 * (cm - vsk)
    sw = qc.solitary(law, w_plus, V)
    with mpmath.workdps(DPS):
        wB, wM, E, xi = reference(name, sw, V)
        eps = 8 * 2.2e-16
        assert abs(sw.w_B - float(wB)) <= sw.w_B_error + eps * max(1, abs(float(wB)))
        assert abs(sw.w_M - float(wM)) <= sw.w_M_error + eps * max(1, abs(float(wM)))
        assert abs(sw.energy - float(E)) <= sw.energy_error + eps * abs(float(E)), (
            sw.energy,
            float(E),
            sw.energy_error,
        )
        assert sw.energy_error <= 1e-8 * abs(float(E))  # and the bar is not vacuous
        # the profile at the ξ where the exact wave has strain w (from the crest to the tail)
        for t in (0.02, 0.3, 0.7, 0.98):
            w = wB + mpmath.mpf(t) * (wM - wB)
            x = float(xi(w))
            got = float(sw.profile(np.float64(x)))
            slope = abs(float(sw.dprofile(np.array([x]))[0]))
            bound = slope * sw.xi_error + sw.w_M_error + sw.w_B_error
            err = abs(got - float(w))
            assert err <= bound + eps * max(1, abs(float(w))), (t, got, float(w), bound)
