"""The computable range of a cubic law and the refusals of out-of-range input: each input that
once gave an overflow, NaN or crash is refused by a ParameterError naming the argument (or
computed right), checked against closed forms evaluated independently (exact
rational arithmetic / mpmath), never against the code's own output."""

from fractions import Fraction

import mpmath as mp
import numpy as np
import pytest

from fpucore import CubicLaw, ParameterError, atlas, floquet, qc, wave
from fpucore.qc import phase

LAW = CubicLaw(-1.0, 10.0)


def refused(name, fn, *args, **kw):
    with pytest.raises(ParameterError) as exc:
        fn(*args, **kw)
    assert exc.value.name == name, str(exc.value)
    return exc.value


# ----------------------------------------------------------------------------- extreme laws
@pytest.mark.parametrize("a,b", [(-1.0, 1.4e154), (-1e-300, 1.0), (-1.0, 1e80), (-1e300, 1e-300)])
def test_laws_beyond_double_precision_are_refused_with_the_range(a, b):
    e = refused("(a, b)", CubicLaw, a, b)
    assert "strain scale" in str(e) and "c_max^2" in str(e)


def test_extreme_but_computable_law_scales_exactly():
    """The cubic's exact scaling w = λu: (a, b) -> (aλ², bλ) leaves every velocity unchanged and
    maps strains w -> w/λ.  With b = 1e20 the old c+ = sqrt(c_max² − 3|a|e) returned 0; the
    reference is √f′(1) in exact rational arithmetic."""
    big, lam = CubicLaw(-1.0, 1e20), 10.0
    small = CubicLaw(-1.0 * lam**2, 1e20 * lam)
    cp = qc.sound_speeds(big, 1.0)[0]
    exact = float(1 + 2 * Fraction(1e20) + 3 * Fraction(-1.0))
    assert cp == pytest.approx(np.sqrt(exact), rel=1e-15)
    for x, y in zip(qc.sound_speeds(big, 1.0), qc.sound_speeds(small, 1.0 / lam), strict=True):
        assert x == pytest.approx(y, rel=1e-14)
    sk, sk2 = qc.superkink_from_w_plus(big, 1.0), qc.superkink_from_w_plus(small, 0.1)
    assert sk.w_minus == pytest.approx(lam * sk2.w_minus, rel=1e-14)


def test_c_plus_near_alpha_to_an_ulp():
    """Near α, c+ once lost a relative 7.5e-5.  Reference: √f′(w+) in 60-digit arithmetic."""
    mp.mp.dps = 60
    for law in (LAW, CubicLaw(-1.0, 100.0), CubicLaw(-0.01, 10.0)):
        for t in (1e-6, 1e-9, 1e-12):
            for w in (
                law.alpha + t * (law.beta - law.alpha),
                law.beta - t * (law.beta - law.alpha),
            ):
                ref = mp.sqrt(1 + 2 * mp.mpf(law.b) * w + 3 * mp.mpf(law.a) * mp.mpf(w) ** 2)
                cp = qc.sound_speeds(law, w)[0]
                assert abs(cp - ref) / ref < 4e-16, (law, t)


def test_qc_numbers_with_large_b_match_the_jump_conditions():
    """b = 1e10 (c_max ~ 6e9): superkink and solitary wave satisfy the Rayleigh relation of
    eq. Rline in exact rational arithmetic, and c+ is √f′(w+)."""
    law = CubicLaw(-1.0, 1e10)
    w_plus = 1.0
    sk = qc.superkink_from_w_plus(law, w_plus)
    a, b = Fraction(law.a), Fraction(law.b)
    f = lambda x: a * x**3 + b * x**2 + x  # noqa: E731
    wp, wm, V2 = Fraction(sk.w_plus), Fraction(sk.w_minus), Fraction(sk.V) ** 2
    lhs = f(wm) - f(wp)
    assert abs(float((lhs - V2 * (wm - wp)) / lhs)) < 1e-13
    cp, vsk, cm = qc.sound_speeds(law, w_plus)
    assert cp == pytest.approx(float(1 + 2 * b + 3 * a) ** 0.5, rel=1e-15)
    sw = qc.solitary(law, w_plus, 0.5 * (cp + vsk))
    assert np.isfinite([sw.energy, sw.energy_error, sw.first_integral_residual]).all()
    assert sw.converged


# ----------------------------------------------------------------------------- input gaps
@pytest.mark.parametrize(
    "kw,name",
    [({"tol": 0.0}, "tol"), ({"N": 10**6}, "N"), ({"time_budget_s": -1.0}, "time_budget_s")],
)
def test_floquet_sweep_refuses_up_front(kw, name):
    refused(name, atlas.sweep, LAW, "superkink", [5.2], use_cache=False, **kw)


@pytest.mark.parametrize("V", [1e300, 1e-300, float("nan"), -1.0])
def test_phase_plane_refuses_extreme_V(V):
    refused("V", phase.phase_plane, LAW, 1.0, V)


def test_phase_plane_refuses_huge_grids():
    refused("n_grid", phase.phase_plane, LAW, 1.0, 5.0, n_grid=100_000)


@pytest.mark.parametrize("fn", [qc.rayleigh_roots, qc.w_S])
@pytest.mark.parametrize("V", [float("nan"), float("inf"), 100.0, -1.0, "5"])
def test_rayleigh_roots_and_w_S_refuse_bad_V(fn, V):
    refused("V", fn, LAW, 1.0, V)


def test_w_minus_sonic_refuses_bad_w_plus():
    refused("w_plus", qc.w_minus_sonic, LAW, float("nan"))
    refused("w_plus", qc.w_minus_sonic, LAW, 100.0)


def test_rayleigh_roots_solve_the_rayleigh_line():
    """Where V is valid: f(w) − f(w+) = V²(w − w+) at both roots, in exact arithmetic."""
    w_plus, V = 1.0, 5.3
    a, b = Fraction(LAW.a), Fraction(LAW.b)
    f = lambda x: a * x**3 + b * x**2 + x  # noqa: E731
    for r in qc.rayleigh_roots(LAW, w_plus, V):
        R = f(Fraction(r)) - f(Fraction(w_plus)) - Fraction(V) ** 2 * (Fraction(r) - 1)
        assert abs(float(R)) < 1e-13 * float(abs(f(Fraction(r))) + 1)


class _State:
    def __init__(self, w):
        self.law, self.V, self.N = LAW, 5.0, 16
        self.w, self.wdot = np.full(16, w), np.zeros(16)
        self.w_left = self.w_right = w


def test_spectrum_refuses_strains_whose_perturbations_overflow():
    refused("r.w", floquet.spectrum, _State(1e6))


@pytest.mark.parametrize("a,b,name", [("-1", 10.0, "a"), (-1.0, True, "b"), (-1.0, "10", "b")])
def test_cubic_law_refuses_non_numbers(a, b, name):
    refused(name, CubicLaw, a, b)


def test_wave_solvers_name_a_missing_law():
    refused("law", wave.solve_superkink, None, 5.2)
    refused("law", wave.solve_solitary, None, 1.0, 5.0)
