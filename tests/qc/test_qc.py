"""QC closed forms (paper §3-4) against the paper's printed numbers and independent checks."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from fpucore import CubicLaw, ParameterError, qc

LAW = CubicLaw(-1.0, 10.0)


def test_superkink_velocity_bounds_paper():
    lo, hi = qc.superkink_velocity_bounds(LAW)
    assert round(lo, 5) == 4.78423 and round(hi, 5) == 5.85947


def test_w_plus_1_paper_values():
    sk = qc.superkink_from_w_plus(LAW, 1.0)
    assert sk.V == pytest.approx(2 * math.sqrt(65) / 3, rel=1e-15)
    assert sk.w_minus == pytest.approx(17 / 3, rel=1e-15)
    cp, vsk, cm = qc.sound_speeds(LAW, 1.0)
    assert cp == pytest.approx(3 * math.sqrt(2), rel=1e-15)
    assert cm == pytest.approx(11 / 2, rel=1e-15)
    assert vsk == pytest.approx(sk.V, rel=1e-15)


def test_w_plus_6_paper_values():
    cp, vsk, cm = qc.sound_speeds(LAW, 6.0)
    assert vsk == pytest.approx(7 * math.sqrt(5) / 3, rel=1e-15)
    assert vsk == pytest.approx(5.21749194749951, abs=1e-14)  # Fig. stabSW caption
    assert cp == pytest.approx(math.sqrt(13), rel=1e-15)
    assert cm == pytest.approx(math.sqrt(29), rel=1e-15)


def test_speeds_meet_at_w_star():
    cp, vsk, cm = qc.sound_speeds(LAW, LAW.w_star)
    c = math.sqrt(1 + LAW.b**2 / (3 * LAW.abs_a))
    assert cp == pytest.approx(c, rel=1e-15) and vsk == cp and cm == cp
    cp, vsk, cm = qc.sound_speeds(LAW, LAW.w_star + 1e-3)
    assert cp < vsk < cm


def test_c_minus_is_tangent_slope():
    # c-^2 is the slope of the line through (w+, f(w+)) tangent to f at w-^s (eq. cminus)
    for wp in (0.3, 1.0, 4.0, 6.0):
        s = qc.w_minus_sonic(LAW, wp)
        slope = (float(LAW.f(s)) - float(LAW.f(wp))) / (s - wp)
        assert slope == pytest.approx(float(LAW.df(s)), rel=1e-13)
        assert qc.sound_speeds(LAW, wp)[2] ** 2 == pytest.approx(slope, rel=1e-13)


@pytest.mark.parametrize("V", [4.8, 5.2, 5.5, 5.85])
@pytest.mark.parametrize("branch", ["lower", "upper"])
def test_superkink_from_V_roundtrip(V, branch):
    sk = qc.superkink_from_V(LAW, V, branch)
    assert sk.rayleigh_residual < 1e-14 and sk.driving_force < 1e-13
    back = qc.superkink_from_w_plus(LAW, sk.w_plus)
    assert back.V == pytest.approx(V, rel=1e-12)
    assert back.w_minus == pytest.approx(sk.w_minus, rel=1e-12)
    assert (sk.w_plus < LAW.w_star) == (branch == "lower")
    # both states are supersonic: V^2 > f'(w+-)
    assert V**2 > float(LAW.df(sk.w_plus)) and V**2 > float(LAW.df(sk.w_minus))


def _qc_ode_residual(wave, w_ref, xi, h=1e-3):
    """Residual of eq. TW_QC_gen2, w'' by a 4th-order difference of the analytic w'."""
    d = wave.dprofile
    w2 = (-d(xi + 2 * h) + 8 * d(xi + h) - 8 * d(xi - h) + d(xi - 2 * h)) / (12 * h)
    V = wave.V
    w = wave.profile(xi)
    r = -(V**2) / 12 * w2 + V**2 * w - LAW.f(w) - (V**2 * w_ref - float(LAW.f(w_ref)))
    return np.max(np.abs(r)) / (V**2 * np.max(np.abs(w - w_ref)))


@pytest.mark.parametrize("V", [4.79, 5.2, 5.85])
def test_superkink_profile_solves_qc_ode(V):
    sk = qc.superkink_from_V(LAW, V)
    xi = np.linspace(-8, 8, 401) / sk.p
    # truncation of the difference is ~h^4 p^5 amp / 30 ~ 1e-11 here
    assert _qc_ode_residual(sk, sk.w_plus, xi) < 1e-9
    H = qc.first_integral(LAW, sk.profile(xi), sk.dprofile(xi), sk.w_plus, V)
    assert np.max(np.abs(H)) < 1e-12 * V**2 * sk.amplitude**2
    assert sk.profile(0.0) == pytest.approx(LAW.w_star, rel=1e-15)
    assert sk.profile(60 / sk.p) == pytest.approx(sk.w_plus, abs=1e-13)
    assert sk.profile(-60 / sk.p) == pytest.approx(sk.w_minus, abs=1e-13)


CASES = [(1.0, 4.3), (1.0, 5.0), (1.0, 5.37), (1.0, 5.38), (1.0, 5.49),
         (6.0, 3.7), (6.0, 5.0), (6.0, 5.3), (6.0, 5.38), (0.2, 3.0)]  # fmt: skip


@pytest.mark.parametrize("wp,V", CASES)
def test_solitary_profile_solves_qc_ode(wp, V):
    sw = qc.solitary(LAW, wp, V)
    xi = np.linspace(-10, 10, 401) / sw.gamma
    assert _qc_ode_residual(sw, sw.w_B, xi) < 1e-8
    assert sw.first_integral_residual < 1e-12
    assert sw.profile(0.0) == pytest.approx(sw.w_M, rel=1e-15)
    assert sw.dprofile(0.0) == 0.0
    assert sw.profile(80 / sw.gamma) == pytest.approx(sw.w_B, abs=1e-12)
    # background is a saddle with the Rayleigh line through w+ (eq. wB, wS)
    assert float(LAW.f(sw.w_B)) - float(LAW.f(wp)) == pytest.approx(
        V**2 * (sw.w_B - wp), abs=1e-11 * V**2
    )
    assert V**2 > float(LAW.df(sw.w_B))


def test_solitary_kinds_follow_fig_SWvelocities():
    assert qc.solitary(LAW, 1.0, 5.0).kind == "tensile"
    assert qc.solitary(LAW, 1.0, 5.4).kind == "compressive"
    assert qc.solitary(LAW, 6.0, 5.0).kind == "compressive"
    assert qc.solitary(LAW, 6.0, 5.3).kind == "tensile"


def test_w_T_M_match_paper_formula():
    # eq. w_T_M as printed (the roots of the quartic's quadratic factor), a second derivation
    A, b = LAW.abs_a, LAW.b
    for wp, V in CASES:
        sw = qc.solitary(LAW, wp, V)
        wB = sw.w_B
        root = math.sqrt(
            4 * (wB - b / (3 * A)) ** 2 - 2 / A * (V**2 - 1) - 6 * wB**2 + 4 * b / A * wB
        )
        pair = sorted([2 * b / (3 * A) - wB + root, 2 * b / (3 * A) - wB - root])
        assert sorted([sw.w_T, sw.w_M]) == pytest.approx(pair, rel=1e-10, abs=1e-10)


@pytest.mark.parametrize("wp,V", CASES)
def test_energy_closed_form_against_quadrature(wp, V):
    """E_ren^QC (eq. Eren_QC) in closed form vs adaptive quadrature of the paper's integrand."""
    sw = qc.solitary(LAW, wp, V)

    def integrand(x):
        w, d = sw.profile(x), sw.dprofile(x)
        return float(
            0.5 * V**2 * (w * w - sw.w_B**2) + V**2 / 24 * d * d + LAW.phi(w) - LAW.phi(sw.w_B)
        )

    L = 60.0 / sw.gamma
    pts = np.linspace(-L, L, 41)
    ref = sum(
        quad(integrand, lo, hi, epsabs=0, epsrel=1e-12, limit=200)[0]
        for lo, hi in zip(pts[:-1], pts[1:])
    )
    assert sw.energy == pytest.approx(ref, rel=1e-9)
    assert sw.energy_error < 1e-10 * abs(sw.energy)


@pytest.mark.parametrize("wp", [1.0, 6.0])
def test_superkink_limit_of_solitary_waves(wp):
    sk = qc.superkink_from_w_plus(LAW, wp)
    for side in (-1, +1):
        errs_amp, errs_gamma, energies = [], [], []
        for k in range(2, 9):
            sw = qc.solitary(LAW, wp, sk.V + side * 10.0**-k)
            errs_amp.append(abs(sw.amplitude - sk.amplitude))
            errs_gamma.append(abs(sw.gamma - 2 * sk.p))
            energies.append(abs(sw.energy))
        assert errs_amp[-1] < 1e-3 and errs_gamma[-1] < 1e-3
        assert all(np.diff(errs_amp) < 0) and all(np.diff(errs_gamma) < 0)
        # E_ren grows without bound (logarithmically in the distance to V_SK)
        assert all(np.diff(energies) > 0) and energies[-1] > 2 * energies[0]


def test_sonic_limits_delocalize_with_the_predicted_rates():
    """Amplitude -> 0 like (V - c+)^1 at c+ (Taylor at w+) and like (c- - V)^(1/2) at c-
    (the saddle w_S(V) folds into w-^s there); the fitted log-log slopes must match."""
    cp, vsk, cm = qc.sound_speeds(LAW, 1.0)
    dist = 10.0 ** -np.arange(4, 10)
    amp_p = [qc.solitary(LAW, 1.0, cp + d).amplitude for d in dist]
    amp_m = [qc.solitary(LAW, 1.0, cm - d).amplitude for d in dist]
    slope_p = np.polyfit(np.log(dist), np.log(amp_p), 1)[0]
    slope_m = np.polyfit(np.log(dist), np.log(amp_m), 1)[0]
    assert slope_p == pytest.approx(1.0, abs=0.01)
    assert slope_m == pytest.approx(0.5, abs=0.01)
    assert math.isfinite(qc.solitary(LAW, 1.0, cm - 1e-12).energy)


@pytest.mark.parametrize(
    "call,name",
    [
        (lambda: qc.solitary(LAW, 1.0, 7.0), "V"),
        (lambda: qc.solitary(LAW, 1.0, 4.0), "V"),
        (lambda: qc.solitary(LAW, 1.0, 2 * math.sqrt(65) / 3), "V"),
        (lambda: qc.solitary(LAW, 1.0, -5.0), "V"),
        (lambda: qc.solitary(LAW, LAW.w_star, 5.0), "w_plus"),
        (lambda: qc.solitary(LAW, 9.0, 5.0), "w_plus"),
        (lambda: qc.solitary(LAW, math.nan, 5.0), "w_plus"),
        (lambda: qc.superkink_from_V(LAW, 6.0), "V"),
        (lambda: qc.superkink_from_V(LAW, 4.7), "V"),
        (lambda: qc.superkink_from_V(LAW, 5.0, branch="middle"), "branch"),
        (lambda: qc.superkink_from_w_plus(LAW, LAW.w_star), "w_plus"),
        (lambda: qc.superkink_from_w_plus(LAW, LAW.beta), "w_plus"),
    ],
)
def test_bad_input_is_refused_with_range(call, name):
    with pytest.raises(ParameterError) as e:
        call()
    msg = str(e.value)
    assert e.value.name == name and msg.startswith(name + "=") and "valid" in msg
