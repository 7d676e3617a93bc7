"""QC quantities (paper §3) of the smooth presets against 30-digit references computed here with
mpmath from the paper's formulas (quadrature of the exact f for Φ, bracketing root finders),
not through fpucore: w₋ (eq. zero_G), V_SK (eq. Rline), c₊ (eq. cplus), w₋ˢ and c₋ (eq. cminus),
w_C and w_S (intersections of the Rayleigh line), the solitary wave's turning point w_M
(eq. TW_QC_gen3) — each within the error bar the route reports (plus 8 ulp)."""

from __future__ import annotations

import mpmath
import pytest
from smooth_reference import force as exact  # the presets' exact f in mpmath

from fpucore import qc
from fpucore.law.presets import preset_law
from fpucore.qc import general

SMOOTH = ("exponential", "tanh", "rational")


def close(x, ref, err):
    return abs(x - float(ref)) <= err + 8 * 2.2e-16 * max(1.0, abs(float(ref)))


@pytest.mark.parametrize("name", SMOOTH)
@pytest.mark.parametrize("frac", [0.3, 0.7])
def test_speeds_against_30_digit_quadrature(name, frac):
    law = preset_law(name)
    lo, hi = qc.superkink_w_plus_range(law, "lower")
    w_plus = hi - frac * (hi - lo) if lo > -1e300 else law.w_star - frac
    sp = general.speeds(law, w_plus)
    with mpmath.workdps(30):
        f = exact(name)
        df = lambda w: mpmath.diff(f, w)  # noqa: E731
        wp = mpmath.mpf(w_plus)
        fp = f(wp)
        G = lambda w: -mpmath.quad(f, [wp, w]) + (w - wp) * (fp + f(w)) / 2  # noqa: E731
        w_star, beta = mpmath.mpf(law.w_star), mpmath.mpf(law.beta)
        w_minus = mpmath.findroot(G, (w_star, beta), solver="anderson")
        V2 = (f(w_minus) - fp) / (w_minus - wp)
        tang = lambda w: df(w) * (w - wp) - (f(w) - fp)  # noqa: E731
        w_ms = mpmath.findroot(tang, (w_star, beta), solver="anderson")
        assert close(sp.w_minus, w_minus, sp.w_minus_error)
        assert close(sp.V_SK, mpmath.sqrt(V2), sp.V_SK_error)
        assert close(sp.c_plus, mpmath.sqrt(df(wp)), sp.c_plus_error)
        assert close(sp.w_minus_sonic, w_ms, sp.w_minus_sonic_error)
        assert close(sp.c_minus, mpmath.sqrt(df(w_ms)), sp.c_minus_error)
        assert sp.converged


@pytest.mark.parametrize("name", SMOOTH)
def test_rayleigh_roots_and_solitary_turning_point(name):
    law = preset_law(name)
    lo, hi = qc.superkink_w_plus_range(law, "lower")
    w_plus = 0.5 * (max(lo, law.alpha) + hi)
    cp, vsk, cm = qc.sound_speeds(law, w_plus)
    V = cp + 0.5 * (vsk - cp)
    w_c, w_s = qc.rayleigh_roots(law, w_plus, V)
    sw = qc.solitary(law, w_plus, V)
    with mpmath.workdps(30):
        f = exact(name)
        wp, V2 = mpmath.mpf(w_plus), mpmath.mpf(V) ** 2
        h = lambda w: f(w) - f(wp) - V2 * (w - wp)  # noqa: E731
        # brackets from the shape (paper §3): w₊ < w_C < w_S < β for w₊ < w*
        ref_c = mpmath.findroot(h, (wp + (w_c - w_plus) / 2, (w_c + w_s) / 2), solver="anderson")
        ref_s = mpmath.findroot(h, ((w_c + w_s) / 2, mpmath.mpf(law.beta)), solver="anderson")
        assert abs(w_c - float(ref_c)) <= 1e-12 * max(1, abs(w_c))
        assert abs(w_s - float(ref_s)) <= 1e-12 * max(1, abs(w_s))
        # turning point of the tensile wave: G_B(w_M) = 0 between w_C and w_S (eq. TW_QC_gen3)
        GB = lambda w: (mpmath.quad(f, [wp, w]) - f(wp) * (w - wp)  # noqa: E731
                        - V2 / 2 * (w - wp) ** 2)  # fmt: skip
        ref_m = mpmath.findroot(GB, (ref_c, ref_s), solver="anderson")
        assert close(sw.w_M, ref_m, sw.w_M_error)


STIFF = [
    ("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 0.3}),  # steep exponential
    ("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3",
     {"c": 0.1, "k": 1, "m": 0.05, "s": 0.01}),  # narrow tanh transition
    ("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 0.02}),  # w* near beta
]  # fmt: skip


def _mp_law(text, c):
    c = {k: mpmath.mpf(repr(float(v))) for k, v in c.items()}
    if "tanh" in text:
        k, m, s = c["k"], c["m"], c["s"]
        return lambda w: w + k * (mpmath.tanh((w - m) / s) + mpmath.tanh(m / s)) - c["c"] * w**3
    return lambda w: w + c["b"] * w**2 - c["c"] * w**3 * mpmath.exp(w / c["d"])


@pytest.mark.parametrize("text, consts", STIFF)
def test_stiff_laws_partner_state_and_speed_within_error_bars(text, consts):
    from fpucore.law import law_from_expression

    law = law_from_expression(text, consts)
    lo, hi = qc.superkink_w_plus_range(law, "lower")
    w_plus = 0.5 * (max(lo, law.alpha) + hi)
    sp = general.speeds(law, w_plus)
    with mpmath.workdps(30):
        f = _mp_law(text, consts)
        wp = mpmath.mpf(w_plus)
        fp = f(wp)
        G = lambda w: -mpmath.quad(f, [wp, law.w_star, w]) + (w - wp) * (fp + f(w)) / 2  # noqa: E731
        w_minus = mpmath.findroot(G, (mpmath.mpf(law.w_star), mpmath.mpf(law.beta)),
                                  solver="anderson")  # fmt: skip
        V = mpmath.sqrt((f(w_minus) - fp) / (w_minus - wp))
        assert close(sp.w_minus, w_minus, sp.w_minus_error)
        assert close(sp.V_SK, V, sp.V_SK_error)
