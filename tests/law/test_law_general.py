"""Any hardening–softening law: PolynomialLaw, the LAW_POLY kernels and the numerical QC theory
of paper §3 (fpucore.qc.general) — against the cubic closed forms of §4
(fpucore.qc.closed_forms) and against an independent 30-digit mpmath computation for a quartic
law."""

import math

import mpmath as mp
import numpy as np
import pytest

from fpucore import CubicLaw, ParameterError
from fpucore.law import (
    LAW_CUBIC,
    LAW_POLY,
    POLY_IDS,
    PolynomialLaw,
    ddforce,
    dforce,
    force,
    law_from_expression,
)
from fpucore.qc import closed_forms as qc
from fpucore.qc import general as G

CUBICS = [CubicLaw(-1.0, 10.0), CubicLaw(-6.0, 4.0), CubicLaw(-0.3, 25.0)]  # paper, stiff, soft
QUARTIC = "w + 10*w**2 - w**3 - 0.01*w**4"


def close(x, y, tol=1e-12):
    """|x − y| ≤ tol·max(1, |y|) (relative for |y| > 1, absolute below)."""
    return abs(x - y) <= tol * max(1.0, abs(y))


# =============================================================================== (a) the cubic
def _points(law):
    """w₊ on both branches and V at fractions of (c₊, V_SK) and (V_SK, c₋)."""
    out = []
    for frac in (0.15, 0.5, 0.9):
        for wp in (law.alpha + frac * (law.w_star - law.alpha),
                   law.w_star + frac * (law.beta - law.w_star)):  # fmt: skip
            cp, vsk, cm = qc.sound_speeds(law, wp)
            out += [(wp, cp + t * (vsk - cp)) for t in (0.1, 0.6, 0.999)]
            out += [(wp, vsk + t * (cm - vsk)) for t in (0.001, 0.5, 0.95)]
    return out


@pytest.mark.parametrize("law", CUBICS, ids=["a-1b10", "a-6b4", "a-0.3b25"])
@pytest.mark.parametrize("as_poly", [False, True], ids=["CubicLaw", "PolynomialLaw"])
def test_cubic_speeds_and_roots_match_closed_forms(law, as_poly):
    gen = law.as_polynomial() if as_poly else law
    for wp in {p[0] for p in _points(law)}:
        sp = G.speeds(gen, wp)
        for x, y in zip((sp.c_plus, sp.V_SK, sp.c_minus), qc.sound_speeds(law, wp)):
            assert close(x, y)
        assert close(sp.w_minus, 2 * law.w_star - wp)  # eq. cubic_cond1
        assert close(sp.w_minus_sonic, qc.w_minus_sonic(law, wp))
        assert sp.V_SK_error < 1e-12 * sp.V_SK and sp.w_minus_error < 1e-12 * max(1, sp.w_minus)
    lo, hi = G.superkink_velocity_bounds(gen, "lower")
    assert close(lo, qc.superkink_velocity_bounds(law)[0]) and close(hi, law.c_max)
    for wp, V in _points(law):
        near, far = G.rayleigh_roots(gen, wp, V)
        n0, f0 = qc.rayleigh_roots(law, wp, V)
        assert close(near, float(n0)) and close(far, float(f0))
        assert close(G.w_S(gen, wp, V), float(qc.w_S(law, wp, V)))


@pytest.mark.parametrize("law", CUBICS, ids=["a-1b10", "a-6b4", "a-0.3b25"])
@pytest.mark.parametrize("branch", ["lower", "upper"])
def test_cubic_superkinks_match_closed_forms(law, branch):
    lo, hi = qc.superkink_velocity_bounds(law)
    for t in (0.02, 0.5, 0.97):
        V = lo + t * (hi - lo)
        a, b = (
            G.superkink_from_V(law.as_polynomial(), V, branch),
            qc.superkink_from_V(law, V, branch),
        )
        for x, y in ((a.V, b.V), (a.w_plus, b.w_plus), (a.w_minus, b.w_minus), (a.p, b.p)):
            assert close(x, y)
        assert close(a.p_minus, b.p) and close(a.amplitude, b.amplitude)
        assert a.rayleigh_residual < 1e-14 and a.driving_force < 1e-13
        xi = np.linspace(-12, 12, 49) / b.p
        scale = b.amplitude
        assert np.max(np.abs(a.profile(xi) - b.profile(xi))) <= 1e-12 * max(1, scale)
        assert np.max(np.abs(a.dprofile(xi) - b.dprofile(xi))) <= 1e-12 * max(1, scale * b.p)
        assert a.xi_error < 1e-10 / b.p and a.elapsed_s > 0
        c = G.superkink_from_w_plus(law, b.w_plus)
        assert close(c.V, b.V) and close(c.w_minus, b.w_minus)


@pytest.mark.parametrize("law", CUBICS, ids=["a-1b10", "a-6b4", "a-0.3b25"])
def test_cubic_solitary_waves_match_closed_forms(law):
    gen = law.as_polynomial()
    for wp, V in _points(law):
        a, b = G.solitary(gen, wp, V), qc.solitary(law, wp, V)
        assert (a.kind, a.interval) == (b.kind, b.interval)
        cp, vsk, cm = qc.sound_speeds(law, wp)
        # where the velocity interval is narrow (w₊ near w*) or V is near one of its ends, w_M
        # and E_ren are determined only to ~eps·κ, κ = V²/(distance of V² to the nearest of c₊²,
        # V_SK², c₋²) (a level set of near-cancelling terms): the tolerance says so, and the
        # error bars of both routes still cover the difference
        kap = V * V / min(V * V - cp * cp, abs(V * V - vsk * vsk), cm * cm - V * V)
        tol = 1e-12 + 64 * kap * 2.2e-16
        assert close(a.w_T, b.w_T, 1e-10)  # auxiliary far root of G_B (beyond the other saddle)
        for x, y in ((a.w_B, b.w_B), (a.w_M, b.w_M), (a.gamma, b.gamma),
                     (a.amplitude, b.amplitude), (a.V_SK, b.V_SK), (a.c_plus, b.c_plus),
                     (a.c_minus, b.c_minus)):  # fmt: skip
            assert close(x, y, tol), (wp, V, x, y)
        # near a sonic limit J ∝ f′ − V² is known only to eps·κ_B, κ_B = V²/(V² − f′(w_B))
        kappa = V * V / (V * V - float(law.df(b.w_B)))
        assert abs(a.energy - b.energy) <= (tol + 32 * kappa * 2.2e-16) * abs(b.energy)
        assert abs(a.energy - b.energy) <= a.energy_error + b.energy_error
        xi = np.linspace(-10, 10, 41) / b.gamma
        amp = max(1.0, b.amplitude)
        assert np.max(np.abs(a.profile(xi) - b.profile(xi))) <= tol * amp
        assert np.max(np.abs(a.dprofile(xi) - b.dprofile(xi))) <= tol * amp * max(1, b.gamma)
        assert a.first_integral_residual < 1e-12


def test_cubic_solitary_family_near_the_superkink_limit():
    """Flat-top waves (|V − V_SK| = 1e-8): the graded panels keep profile and E_ren to 1e-12."""
    law = CUBICS[0]
    for wp in (1.0, 6.0):
        vsk = qc.sound_speeds(law, wp)[1]
        for V in (vsk - 1e-8, vsk + 1e-8):
            a, b = G.solitary(law, wp, V), qc.solitary(law, wp, V)
            # E_ren ~ log(1/ε) with ε² ∝ V² − V_SK²: a level set known only to eps·V²/|V² − V_SK²|
            kappa = V * V / abs(V * V - vsk * vsk)
            assert abs(a.energy - b.energy) <= (1e-12 + 4 * kappa * 2.2e-16) * abs(b.energy)
            assert abs(a.energy - b.energy) <= a.energy_error + b.energy_error
            xi = np.linspace(-40, 40, 81) / b.gamma
            # front positions shift by ~κ eps (the plateau length is log-sensitive to ε)
            tol = (1e-11 + 4 * kappa * 2.2e-16) * b.amplitude
            assert np.max(np.abs(a.profile(xi) - b.profile(xi))) <= tol


# =============================================================================== (b) a quartic
mp.mp.dps = 30
_c = [mp.mpf(0), mp.mpf(1), mp.mpf(10), mp.mpf(-1), mp.mpf("-0.01")]  # exact decimal 0.01


def mf(w):
    return sum(_c[k] * w**k for k in range(1, 5))


def mdf(w):
    return sum(k * _c[k] * w ** (k - 1) for k in range(1, 5))


def mddf(w):
    return sum(k * (k - 1) * _c[k] * w ** (k - 2) for k in range(2, 5))


def mphi(w):
    return sum(_c[k] * w ** (k + 1) / (k + 1) for k in range(1, 5))


def _bisect(F, a, b):
    """mpmath root with a bracket (anderson; independent of the float64 code)."""
    return mp.findroot(F, (mp.mpf(a), mp.mpf(b)), solver="anderson", tol=mp.mpf(10) ** -28)


@pytest.fixture(scope="module")
def quartic_ref():
    """Everything for w₊ = 1 at 30 digits from the paper's raw formulas (no cancellation-free
    rewriting): eqs. Rline, zero_G, cplus, cminus, wB/wS, TW_QC_gen3, SWQC_amp, Eren_QC."""
    wp = mp.mpf(1)
    w_star = _bisect(mddf, 0.1, 6)
    beta = _bisect(mdf, 1, 10)
    alpha = _bisect(mdf, -1, -1e-6)

    def D(w):  # driving force with w₋ = w (eq. zero_G)
        return mphi(wp) - mphi(w) - (wp - w) * (mf(wp) + mf(w)) / 2

    wm = _bisect(D, w_star, beta)
    V2 = (mf(wm) - mf(wp)) / (wm - wp)
    wms = _bisect(lambda w: mf(w) - mf(wp) - mdf(w) * (w - wp), w_star, beta)
    ref = dict(wp=wp, w_star=w_star, beta=beta, alpha=alpha, w_minus=wm, V_SK=mp.sqrt(V2),
               c_plus=mp.sqrt(mdf(wp)), w_ms=wms, c_minus=mp.sqrt(mdf(wms)))  # fmt: skip
    waves = {}
    for tag, t in (("below", 0.4), ("above", 0.6)):
        cp, vsk, cm = ref["c_plus"], ref["V_SK"], ref["c_minus"]
        V = cp + t * (vsk - cp) if tag == "below" else vsk + t * (cm - vsk)
        V2 = V * V
        h = lambda w, V2=V2: mf(w) - mf(wp) - V2 * (w - wp)  # noqa: E731
        if tag == "below":
            wB = wp
            wC = _bisect(h, wp + mp.mpf("1e-6"), wms)
            other = wm
        else:
            wB = _bisect(h, wms, wm)  # w_S(V) between the tangency point and w₋
            wC = _bisect(h, wp + mp.mpf("1e-6"), wms)
            other = wp
        GB = lambda w, wB=wB, V2=V2: (  # noqa: E731
            mphi(w) - mphi(wB) - mf(wB) * (w - wB) - V2 / 2 * (w - wB) ** 2
        )
        wM = _bisect(GB, wC, other)
        wpr = lambda w, GB=GB, V=V: mp.sqrt(abs(24 * GB(w))) / V  # noqa: E731  |w′|, TW_QC_gen3

        def integrand(w, wB=wB, V=V, GB=GB, wpr=wpr):
            return (  # noqa: E731  eq. Eren_QC / |w′|
                V**2 / 2 * (w**2 - wB**2) + V**2 / 24 * (-24 * GB(w) / V**2) + mphi(w) - mphi(wB)
            ) / wpr(w)

        E = 2 * mp.sign(wM - wB) * mp.quad(integrand, [wB, (wB + wM) / 2, wM])
        # three points of the profile: ξ(w) = ∫_w^{w_M} dw/|w′|
        ws = [wB + (wM - wB) * q for q in (mp.mpf("0.9"), mp.mpf("0.5"), mp.mpf("0.01"))]
        xis = [abs(mp.quad(lambda s, wpr=wpr: 1 / wpr(s), [w, wM])) for w in ws]
        waves[tag] = dict(V=V, w_B=wB, w_M=wM, energy=E, ws=ws, xis=xis)
    # superkink profile: ξ(w) = ∫_{w_mid}^{w} dw/w′, w′ = −√(−24 G)/V_SK (lower branch)
    V = ref["V_SK"]
    Gsk = lambda w: mphi(w) - mphi(wp) - mf(wp) * (w - wp) - V**2 / 2 * (w - wp) ** 2  # noqa: E731
    mid = (wp + wm) / 2
    sk_ws = [wp + (wm - wp) * q for q in (mp.mpf("0.02"), mp.mpf("0.3"), mp.mpf("0.8"))]
    sk_xis = [mp.quad(lambda s: -V / mp.sqrt(abs(24 * Gsk(s))), [mid, w]) for w in sk_ws]
    ref.update(waves=waves, sk_ws=sk_ws, sk_xis=sk_xis)
    return ref


def test_quartic_law_constants(quartic_ref):
    law = law_from_expression(QUARTIC)
    assert law.coeffs == (1.0, 10.0, -1.0, -0.01)
    r = quartic_ref
    for name in ("alpha", "beta", "w_star"):
        assert close(getattr(law, name), float(r[name]), 1e-14)
        assert abs(getattr(law, name) - float(r[name])) <= 4 * getattr(law, name + "_error")
    assert close(law.c_max, float(mp.sqrt(mdf(r["w_star"]))), 1e-14)


def test_quartic_superkink_and_speeds_vs_mpmath(quartic_ref):
    law, r = law_from_expression(QUARTIC), quartic_ref
    sp = G.speeds(law, 1.0)
    for x, key in ((sp.c_plus, "c_plus"), (sp.V_SK, "V_SK"), (sp.c_minus, "c_minus"),
                   (sp.w_minus, "w_minus"), (sp.w_minus_sonic, "w_ms")):  # fmt: skip
        assert close(x, float(r[key])), key
    assert abs(sp.V_SK - float(r["V_SK"])) <= sp.V_SK_error + 1e-15
    assert abs(sp.w_minus - float(r["w_minus"])) <= sp.w_minus_error + 1e-15
    sk = G.superkink_from_w_plus(law, 1.0)
    # no cubic symmetry: the states do not average to the inflection (eq. cubic_cond1 fails)
    defect = float(r["wp"] + r["w_minus"] - 2 * r["w_star"])
    assert abs(defect) > 0.03 and close(sk.symmetry_defect, defect)
    assert sk.p != pytest.approx(sk.p_minus, rel=1e-3)  # asymmetric kink: different tail rates
    xi = sk.profile(np.array([float(x) for x in r["sk_xis"]]))
    assert np.max(np.abs(xi - np.array([float(w) for w in r["sk_ws"]]))) < 1e-12
    back = G.superkink_from_V(law, float(r["V_SK"]), "lower")
    assert close(back.w_plus, 1.0, 1e-11) and close(back.w_minus, float(r["w_minus"]), 1e-11)


@pytest.mark.parametrize("tag", ["below", "above"])
def test_quartic_solitary_vs_mpmath(quartic_ref, tag):
    law, ref = law_from_expression(QUARTIC), quartic_ref["waves"][tag]
    sw = G.solitary(law, 1.0, float(ref["V"]))
    assert sw.interval == tag
    assert sw.kind == ("tensile" if tag == "below" else "compressive")
    assert close(sw.w_B, float(ref["w_B"])) and close(sw.w_M, float(ref["w_M"]))
    assert close(sw.amplitude, float(abs(ref["w_M"] - ref["w_B"])))
    assert abs(sw.energy - float(ref["energy"])) <= 1e-12 * abs(float(ref["energy"]))
    assert abs(sw.energy - float(ref["energy"])) <= sw.energy_error
    w = sw.profile(np.array([float(x) for x in ref["xis"]]))
    assert np.max(np.abs(w - np.array([float(x) for x in ref["ws"]]))) < 1e-12
    assert sw.first_integral_residual < 1e-12 and sw.elapsed_s > 0


def test_quartic_branch_ranges_are_not_mirror_images():
    """The two superkink branches cover the same velocities (the equal-area and Rayleigh
    conditions are symmetric in w₊ ↔ w₋, so the upper branch is the lower one with its states
    swapped), but their w₊-ranges are not mirror images about w* as for the cubic: the lower
    branch ends where w₋ reaches β (not at α), the upper one at w₊ = β."""
    law = law_from_expression(QUARTIC)
    lo_l, hi_l = G.superkink_velocity_bounds(law, "lower")
    lo_u, hi_u = G.superkink_velocity_bounds(law, "upper")
    assert hi_l == hi_u == law.c_max and abs(lo_l - lo_u) < 1e-9
    wl, _ = G.superkink_w_plus_range(law, "lower")
    _, wu = G.superkink_w_plus_range(law, "upper")
    assert law.alpha < wl < 0 and wu == law.beta
    assert abs((law.w_star - wl) - (wu - law.w_star)) > 0.05  # 3.139 vs 3.070; cubic: equal


# =============================================================================== (c) refusals
@pytest.mark.parametrize(
    "make,name,words",
    [
        (
            lambda: law_from_expression("w + 3*w**2 - 11*w**3/6 + w**4/2 - w**5/20"),
            "coeffs",
            "inflections",
        ),
        (lambda: PolynomialLaw((1.0, 3.0, -11 / 6, 0.5, -0.05)), "coeffs", "two or more"),
        (lambda: law_from_expression("-w + w**2 - w**3"), "c_1", "f'(0) must be positive"),
        (lambda: law_from_expression("w**2 - w**3"), "c_1", "f'(0) must be positive"),
        (lambda: law_from_expression("w + * 2"), "expression", "could not parse"),
        (lambda: law_from_expression("w + (w**2"), "expression", "could not parse"),
        # not polynomials: the smooth-law route answers (tests/law/test_law_smooth.py)
        (lambda: law_from_expression("w + sin(w)"), "expression", "'sin' is not allowed"),
        (lambda: law_from_expression("w + 1/w - w**3"), "expression", "division by zero"),
        (lambda: law_from_expression("w**2.5 + w"), "expression", "no softening"),
        (lambda: law_from_expression("w + x**2"), "expression", "unknown name 'x'"),
        (lambda: law_from_expression("__import__('os')"), "expression", "unknown name"),
        (lambda: law_from_expression("1 + w - w**3"), "expression", "f(0) must be 0"),
        (lambda: law_from_expression("w + 1e400*w**2 - w**3"), "expression", "non-finite"),
        (lambda: law_from_expression("w + w/0"), "expression", "non-finite"),
        (lambda: PolynomialLaw((1.0, math.inf, -1.0)), "c_2", "finite"),
        (lambda: PolynomialLaw((1.0, 10.0, math.nan)), "c_3", "finite"),
        (lambda: PolynomialLaw((1.0,)), "coeffs", "degree >= 2"),
        (lambda: law_from_expression("w + w**2"), "coeffs", "no softening"),
        (lambda: law_from_expression("w - w**2 - w**3"), "w_star", "positive strain"),
        (lambda: law_from_expression("w - w**2"), "coeffs", "softening only"),
        (lambda: PolynomialLaw((1.0, 0.0, 0.0, -1.0)), "coeffs", "without changing sign"),
    ],
)
def test_refusals_name_the_problem(make, name, words):
    with pytest.raises(ParameterError) as e:
        make()
    assert e.value.name == name and words in str(e.value), str(e.value)


def test_qc_general_refusals():
    law = law_from_expression(QUARTIC)
    lo, _ = G.superkink_w_plus_range(law, "lower")
    for call, name in [
        (lambda: G.speeds(law, law.w_star), "w_plus"),
        (lambda: G.speeds(law, 0.5 * (law.alpha + lo)), "w_plus"),  # partner beyond β
        (lambda: G.solitary(law, 1.0, 7.0), "V"),
        (lambda: G.solitary(law, 1.0, G.sound_speeds(law, 1.0)[1]), "V"),
        (lambda: G.superkink_from_V(law, 6.0), "V"),
        (lambda: G.superkink_from_V(law, 5.0, "middle"), "branch"),
    ]:
        with pytest.raises(ParameterError) as e:
            call()
        assert e.value.name == name


# =============================================================================== (d) kernels
def test_poly_kernels_match_polyval():
    """Every polynomial kernel (generic loop and the unrolled ones of degree 3–8) against
    numpy.polyval, and each unrolled kernel bit-identical to the loop (same operations in the
    same order); PolynomialLaw picks the unrolled id by degree, the loop beyond degree 8."""
    rng = np.random.default_rng(7)
    cases = [tuple(rng.normal(size=n)) for n in (3, 4, 5, 6, 7, 8, 9)]
    cases += [(1.0, 10.0, -1.0, -0.01)]
    for coeffs in cases:
        p = np.array(coeffs)
        ids = (LAW_POLY,) + ((p.size,) if p.size in POLY_IDS else ())
        c = np.concatenate([[0.0], p])[::-1]  # numpy.polyval order, zero constant term
        dc, ddc = np.polyder(c), np.polyder(c, 2)
        for law_id in ids:
            for w in rng.uniform(-3, 8, 30):
                s = np.polyval(np.abs(c), abs(w))
                assert abs(force(law_id, p, w) - np.polyval(c, w)) <= 1e-14 * s
                assert abs(dforce(law_id, p, w) - np.polyval(dc, w)) <= 1e-14 * (1 + abs(w)) * s
                assert abs(ddforce(law_id, p, w) - np.polyval(ddc, w)) <= 1e-13 * (1 + w * w) * s
                for k in (force, dforce, ddforce):
                    assert k(law_id, p, w) == k(LAW_POLY, p, w)
    # the generic kernel (degree > 8) is the plain Horner loop in this order, bit for bit
    for n in (9, 12):
        p = rng.normal(size=n)
        for w in rng.uniform(-3, 8, 10):
            f = df = ddf = 0.0
            for k in range(n - 1, -1, -1):
                f = f * w + p[k]
                df = df * w + (k + 1) * p[k]
                ddf = ddf * w + (k + 1) * k * p[k] if k else ddf
            assert (force(LAW_POLY, p, w), dforce(LAW_POLY, p, w)) == (f * w, df)
            assert ddforce(LAW_POLY, p, w) == ddf
    deg7 = PolynomialLaw((1.0, 10.0, -1.0, -0.01, 1e-4, -1e-5, 1e-7))
    assert law_from_expression(QUARTIC).law_id == 4 and deg7.law_id == 7
    deg9 = PolynomialLaw((1.0, 10.0, -1.0, -0.01, 1e-4, -1e-5, 1e-7, 0.0, -1e-9))
    assert deg9.law_id == LAW_POLY


def test_cubic_as_polynomial_kernels_agree():
    rng = np.random.default_rng(3)
    for law in CUBICS:
        poly = law.as_polynomial()
        assert poly.law_id in POLY_IDS and law.law_id == LAW_CUBIC
        for name in ("alpha", "beta", "w_star"):
            assert close(getattr(poly, name), getattr(law, name), 1e-14)
        for w in rng.uniform(law.alpha, law.beta, 40):
            for k in (force, dforce, ddforce):
                a, b = k(poly.law_id, poly.params, w), k(LAW_CUBIC, law.params, w)
                assert a == k(LAW_POLY, poly.params, w)  # unrolled = loop, same order
                assert abs(a - b) <= 1e-14 * max(1.0, abs(b), abs(law.b) * w * w)
            for m in ("f", "df", "ddf", "phi"):
                assert close(float(getattr(poly, m)(w)), float(getattr(law, m)(w)), 1e-13)
