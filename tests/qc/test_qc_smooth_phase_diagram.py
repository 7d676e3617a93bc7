"""The phase plane and the existence diagram (API) for the smooth presets, against references
computed here at 40 digits with mpmath from the exact expression (Φ in closed form from
tests/support/smooth_reference.py): the highlighted orbits lie on the level set of the first
integral of eq. TW_QC_gen3 within the residual the route reports, the critical points are the
roots of the Rayleigh line with the eigenvalues 12(V² − f′)/V², and the diagram's c₊ = √f′(w₊)
and V_SK (equal areas, eq. zero_G + Rline) at sampled w₊."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from smooth_reference import antiderivative, force

from fpucore import qc
from fpucore.law.presets import preset_law
from fpucore.qc.diagram import existence_diagram
from fpucore.qc.phase import phase_plane

SMOOTH = ("exponential", "tanh", "rational")


def state(law, frac_V):
    lo, hi = qc.superkink_w_plus_range(law, "lower")
    w_plus = 0.5 * (max(lo, law.alpha) + hi)
    cp, vsk, _ = qc.sound_speeds(law, w_plus)
    return w_plus, cp + frac_V * (vsk - cp), vsk


@pytest.mark.parametrize("name", SMOOTH)
@pytest.mark.parametrize("regime", ["solitary", "superkink"])
def test_phase_plane_orbits_and_critical_points(name, regime):
    law = preset_law(name)
    w_plus, V, vsk = state(law, 0.5)
    if regime == "superkink":
        V = vsk
    pp = phase_plane(law, w_plus, V, n_grid=41, n_orbit=201)
    assert pp.regime == ("superkink" if regime == "superkink" else "tensile")
    assert pp.orbits and pp.orbit_residual <= 1e-10
    with mpmath.workdps(40):
        Phi, f = antiderivative(name), force(name)
        df = lambda w: mpmath.diff(f, w)  # noqa: E731
        wp, V2 = mpmath.mpf(w_plus), mpmath.mpf(V) ** 2
        fp = f(wp)

        def H(w, wdot):  # eq. TW_QC_gen3's first integral, 0 on the orbits through w₊
            w = mpmath.mpf(float(w))
            return (V2 / 24 * mpmath.mpf(float(wdot)) ** 2 + Phi(w) - Phi(wp) - fp * (w - wp)
                    - V2 / 2 * (w - wp) ** 2)  # fmt: skip

        span = float(np.ptp(pp.H))
        for o in pp.orbits:
            idx = np.linspace(0, o.w.size - 1, 25).astype(int)
            worst = max(abs(float(H(o.w[i], o.wp[i]))) for i in idx) / span
            assert worst <= pp.orbit_residual + 1e-12, (o.name, worst, pp.orbit_residual)
        # critical points: w₊ and the other roots of the Rayleigh line inside the window
        ray = lambda w: f(w) - fp - V2 * (w - wp)  # noqa: E731
        for c in pp.critical_points:
            ref = mpmath.findroot(ray, mpmath.mpf(c.w))
            assert abs(c.w - float(ref)) <= 1e-12 * max(1.0, abs(c.w)), (c, ref)
            lam2 = 12 * (V2 - df(ref)) / V2
            assert abs(c.eigenvalue - float(lam2)) <= 1e-9 * max(1.0, abs(float(lam2)))
            assert c.kind == ("saddle" if lam2 > 0 else "center")
        assert any(abs(c.w - w_plus) <= 1e-12 for c in pp.critical_points)


@pytest.mark.parametrize("name", SMOOTH)
def test_existence_diagram_against_equal_areas(name):
    law = preset_law(name)
    d = existence_diagram(law, n=40)
    assert d.w_plus.size >= 39 and np.all(np.isfinite(d.V_SK))
    assert np.all(d.c_plus < d.V_SK) and np.all(d.V_SK < d.c_minus)
    with mpmath.workdps(40):
        Phi, f = antiderivative(name), force(name)
        for wp_f, cp in zip(d.w_plus, d.c_plus):
            ref = mpmath.sqrt(mpmath.diff(f, mpmath.mpf(float(wp_f))))
            assert abs(cp - float(ref)) <= 1e-12 * float(ref)
        for i in (3, d.w_plus.size // 3, d.w_plus.size - 4):
            wp = mpmath.mpf(float(d.w_plus[i]))
            fp = f(wp)

            def G(w, wp=wp, fp=fp):  # equal areas (eq. zero_G)
                return -(Phi(w) - Phi(wp)) + (w - wp) * (fp + f(w)) / 2

            other = law.beta if wp < law.w_star else max(law.alpha, law.interval[0])
            wm = mpmath.findroot(G, (mpmath.mpf(law.w_star), mpmath.mpf(other)),
                                 solver="anderson")  # fmt: skip
            V_SK = mpmath.sqrt((f(wm) - fp) / (wm - wp))
            assert abs(d.V_SK[i] - float(V_SK)) <= 1e-11 * float(V_SK), (i, d.V_SK[i], V_SK)
