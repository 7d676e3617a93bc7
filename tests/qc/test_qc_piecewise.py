"""Closed-form QC theory of piecewise-linear laws against an independent 40-digit reference:
mpmath quadrature of the paper's general formulas (eqs. Rline, zero_G, cminus, TW_QC_gen3,
Eren_QC) over the pieces, and mpmath root finding — never through fpucore.qc.piecewise."""

# the closures over loop variables below are called within the same iteration
# ruff: noqa: B023

import math

import mpmath as mp
import numpy as np
import pytest

from fpucore import ParameterError
from fpucore.law import PiecewiseLinearLaw, TrilinearLaw
from fpucore.qc import piecewise as P
from fpucore.qc import piecewise_orbit as O

mp.mp.dps = 34  # the reference carries >= 30 digits


class Ref:
    """f as a sum of ramps, f = s₀w + Σ J_k (max(w − b_k, 0) − max(−b_k, 0)), and Φ = ∫₀ʷ f as
    the sum of their antiderivatives (checked against mpmath quadrature of f in a test)."""

    def __init__(self, b, s):
        self.b = [mp.mpf(x) for x in b]
        self.s = [mp.mpf(x) for x in s]
        self.J = [self.s[k + 1] - self.s[k] for k in range(len(b))]

    def f(self, w):
        w = mp.mpf(w)
        return self.s[0] * w + sum(
            J * (max(w - bk, 0) - max(-bk, 0)) for J, bk in zip(self.J, self.b)
        )

    def cuts(self, a, c):
        lo, hi = min(a, c), max(a, c)
        return [lo, *[x for x in self.b if lo < x < hi], hi]

    def integral(self, g, a, c):
        pts = self.cuts(mp.mpf(a), mp.mpf(c))
        val = mp.quad(g, pts)
        return val if c >= a else -val

    def phi(self, w):
        w = mp.mpf(w)
        r2 = lambda x: max(x, 0) ** 2 / 2  # noqa: E731
        return self.s[0] * w * w / 2 + sum(
            J * (r2(w - bk) - r2(-bk) - max(-bk, 0) * w) for J, bk in zip(self.J, self.b)
        )

    def G(self, wp, wm):  # eq. zero_G
        return self.phi(wp) - self.phi(wm) - (wp - wm) * (self.f(wp) + self.f(wm)) / 2

    def chord(self, a, c):
        return (self.f(c) - self.f(a)) / (c - a)

    def Q(self, wB, V2, w):  # w′² from eq. TW_QC_gen3 with background w_B
        fB = self.f(wB)
        g = lambda x: self.f(x) - fB - V2 * (x - wB)  # noqa: E731
        del g
        w = mp.mpf(w)
        return -24 / V2 * (self.phi(w) - self.phi(wB) - fB * (w - wB) - V2 * (w - wB) ** 2 / 2)


def golden_max(F, a, c, tol=None):
    """Maximum of a unimodal F on [a, c] (golden section: needs no derivative at a corner)."""
    tol = mp.mpf(10) ** -32 if tol is None else tol
    g = (mp.sqrt(5) - 1) / 2
    x1, x2 = c - g * (c - a), a + g * (c - a)
    f1, f2 = F(x1), F(x2)
    while c - a > tol:
        if f1 < f2:
            a, x1, f1 = x1, x2, f2
            x2 = a + g * (c - a)
            f2 = F(x2)
        else:
            c, x2, f2 = x2, x1, f1
            x1 = c - g * (c - a)
            f1 = F(x1)
    return (a + c) / 2, F((a + c) / 2)


def bracket(F, x0, step, n=200, grow=1.0):
    """First sign change of F from x0 in steps (multiplied by ``grow`` each time)."""
    f0, x = F(x0), x0
    for _ in range(n):
        y = x + step
        if (F(y) < 0) != (f0 < 0):
            return (x, y)
        x, step = y, step * grow
    raise AssertionError("no sign change")


def test_reference_potential_is_the_quadrature_of_f():
    ref = Ref((-1.0, 0.5, 1.5, 3.0), (0.5, 1.0, 4.0, 0.5, 0.1))
    for w in (-2.5, -0.3, 0.7, 2.0, 4.0):
        assert abs(ref.phi(w) - ref.integral(ref.f, 0, w)) < mp.mpf(10) ** -35


LAWS = [
    ((0.5, 1.5), (1.0, 4.0, 0.2)),
    ((0.5, 1.5), (0.2, 4.0, 1.0)),  # asymmetric, E3 > E1: a finite lower superkink range
    ((0.5, 1.5), (1.0, 4.0, 0.0)),  # degenerate E3 = 0
    ((-1.0, 0.5, 1.5, 3.0), (0.5, 1.0, 4.0, 0.5, 0.1)),  # a general PL law, five regimes
]


@pytest.mark.parametrize("b, s", LAWS)
@pytest.mark.parametrize("which", ["lower", "upper"])
def test_superkink_states_and_speeds_against_quadrature(b, s, which):
    law = PiecewiseLinearLaw(b, s)
    ref = Ref(b, s)
    w1, w2 = law.hard_regime
    lo, hi = P.superkink_w_plus_range(law, which)
    end = lo if which == "lower" else hi
    inner = w1 if which == "lower" else w2
    span = abs(end - inner) if math.isfinite(end) else 3.0
    sgn = -1 if which == "lower" else 1
    for frac in (0.1, 0.5, 0.9):
        wp = inner + sgn * frac * span
        if np.any(np.isclose(law._b, wp)):
            continue
        sp = P.speeds(law, wp)
        # w₋: root of eq. zero_G (Φ by quadrature) beyond the hard regime, found by bracketing
        far = w2 if which == "lower" else w1
        step = mp.mpf("0.01") * (1 if which == "lower" else -1)
        a_, c_ = bracket(lambda x: ref.G(wp, x), mp.mpf(far) + step / 100, step, grow=1.3)
        wm = mp.findroot(lambda x: ref.G(wp, x), (a_, c_), solver="anderson")
        assert sp.w_minus == pytest.approx(float(wm), rel=2e-14, abs=2e-14)
        V2 = ref.chord(mp.mpf(wp), wm)  # eq. Rline
        assert sp.V_SK == pytest.approx(float(mp.sqrt(V2)), rel=2e-14)
        # supersonic with respect to both states (paper §2)
        assert V2 > law.df(wp) and V2 > law.df(float(wm))
        # c₋: the largest chord slope from w₊ (eq. cminus: the saddle–centre collision)
        ends = (mp.mpf(w1), mp.mpf(w2) + 10) if which == "lower" else (mp.mpf(w1) - 10, w2)
        x, S = golden_max(lambda x: ref.chord(mp.mpf(wp), x), *ends)
        assert sp.c_minus == pytest.approx(float(mp.sqrt(S)), rel=1e-14)
        assert sp.w_minus_sonic == pytest.approx(float(x), abs=1e-12)
        assert sp.c_plus < sp.V_SK < sp.c_minus and sp.converged


def test_superkink_range_end_against_divergence():
    # E3 > E1: beyond the closed-form end of the lower range the equal-area root runs away
    law = TrilinearLaw(0.5, 1.5, 0.2, 4.0, 1.0)
    lo, hi = P.superkink_w_plus_range(law, "lower")
    assert lo == pytest.approx(0.5 - 3.0 * 1.0 / 0.8, rel=1e-15)
    ref = Ref((0.5, 1.5), (0.2, 4.0, 1.0))
    for wp, exists in ((lo + 0.01, True), (lo - 0.01, False)):
        G = [ref.G(mp.mpf(wp), mp.mpf(x)) for x in np.linspace(1.6, 1e4, 400)]
        assert G[0] > 0 and (min(G) < 0) == exists  # G changes sign only inside the range
    with pytest.raises(ParameterError) as e:
        P.w_minus(law, lo - 0.01)
    assert e.value.name == "w_plus"
    with pytest.raises(ParameterError) as e:
        P.speeds(law, 1.0)  # inside the hard regime
    assert "hard regime" in str(e.value)


@pytest.mark.parametrize(
    "b, s, wp",
    [(*LAWS[0], 0.3), (*LAWS[0], 2.2), (*LAWS[1], -0.7), (*LAWS[2], 2.2), (*LAWS[3], 0.2)],
)
def test_solitary_turning_point_profile_energy_against_quadrature(b, s, wp):
    law = PiecewiseLinearLaw(b, s)
    ref = Ref(b, s)
    sp = P.speeds(law, wp)
    for t in (0.6, 1.4):  # t < 1: (c₊, V_SK); t > 1: (V_SK, c₋)
        V = (
            sp.c_plus + t * (sp.V_SK - sp.c_plus)
            if t < 1
            else sp.V_SK + (t - 1) * (sp.c_minus - sp.V_SK) * 1.6
        )
        sw = O.solitary(law, wp, V)
        V2 = mp.mpf(V) ** 2
        # background: w₊ below V_SK, else the saddle root of f = R beyond the hard regime
        if t < 1:
            wB = mp.mpf(wp)
        else:
            fp = ref.f(wp)
            R = lambda x: ref.f(x) - fp - V2 * (x - wp)  # noqa: E731
            w1, w2 = law.hard_regime
            start, step = (mp.mpf(w2), mp.mpf("0.01")) if wp < w1 else (mp.mpf(w1), -mp.mpf("0.01"))
            wB = mp.findroot(R, bracket(R, start + step / 10, step, grow=1.3), solver="anderson")
            assert sw.w_B == pytest.approx(float(wB), rel=1e-14, abs=1e-14)
        d = 1 if wB < law.w_star else -1
        Qf = lambda x: ref.Q(wB, V2, x)  # noqa: E731
        a_, c_ = bracket(Qf, wB + d * mp.mpf("1e-6"), d * mp.mpf("0.002"), n=4000)
        wM = mp.findroot(Qf, (a_, c_), solver="anderson")
        assert sw.w_M == pytest.approx(float(wM), rel=1e-13, abs=1e-13)
        assert sw.amplitude == pytest.approx(float(abs(wM - wB)), rel=1e-12)
        # profile: ξ(w) = ∫_w^{w_M} dx/√Q(x) by quadrature, at levels in every piece crossed
        for lev in (0.999, 0.7, 0.3, 0.05):
            w = wB + lev * (wM - wB)
            xi = ref.integral(lambda x: 1 / mp.sqrt(Qf(x)), w, wM)
            assert float(sw.profile(float(abs(xi)))) == pytest.approx(float(w), abs=1e-12)
        # E_ren^QC, eq. Eren_QC: 2∫ integrand dw/|w′| over (w_B, w_M)
        fB = ref.f(wB)
        PB = ref.phi(wB)

        def dens(x):
            q = Qf(x)
            if q <= 0:  # within ~1e-20 of w_B the 40-digit Q is rounding: a negligible stretch
                return mp.mpf(0)
            return (V2 * (x * x - wB * wB) / 2 + V2 * q / 24 + ref.phi(x) - PB) / mp.sqrt(q)

        E = 2 * ref.integral(dens, min(wB, wM), max(wB, wM))
        assert sw.energy == pytest.approx(float(E), rel=1e-11, abs=1e-12)
        del fB
        assert sw.converged


def test_superkink_profile_against_quadrature():
    b, s = (0.5, 1.5), (1.0, 4.0, 0.2)
    law, ref = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2), Ref(b, s)
    sk = O.superkink(law, 0.3)
    wp, wm = mp.mpf(0.3), mp.mpf(sk.w_minus)
    V2 = ref.chord(wp, wm)
    wc = (wp + wm) / 2
    for w in (mp.mpf("0.31"), mp.mpf("0.45"), mp.mpf("1.0"), mp.mpf("1.55"), mp.mpf("1.65")):
        Qf = lambda x: ref.Q(wp, V2, x)  # noqa: E731
        xi = ref.integral(lambda x: 1 / mp.sqrt(Qf(x)), w, wc)  # ξ(w) − ξ(w_c), w′ < 0
        assert float(sk.profile(float(xi))) == pytest.approx(float(w), abs=1e-12)
    assert sk.profile(np.array([60.0]))[0] == pytest.approx(0.3, abs=1e-12)
    assert sk.profile(np.array([-60.0]))[0] == pytest.approx(sk.w_minus, abs=1e-12)


def test_general_route_cannot_take_a_piecewise_law():
    """The general quadrature route of fpucore.qc works on f″, zero between breakpoints:
    its equal-area function vanishes identically, so it must not be used for these laws."""
    from fpucore.qc.general_roots import driving_force_g

    law = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2)
    assert driving_force_g(law, 0.3, 1.4) == 0.0  # G ≠ 0 there: H(1.7) = 3·0.2·1.2 − 3.8·1.2·0.2
