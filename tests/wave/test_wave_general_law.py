"""Discrete waves, Floquet spectra and seeded simulations for a law that is not the cubic:
f = w + 10w² − w³ − 0.01w⁴.  References: the period map's own definition checked
with an independent integrator (scipy DOP853 on the chain written from ``law.f``), the paper's
traveling-wave check (a seeded run keeps velocity and shape for 50+ periods, eq. period), the
Hamiltonian quartet symmetry of the monodromy (μ, μ̄, 1/μ, 1/μ̄), and — for the cubic — the
closed-form route: the same wave whichever object (CubicLaw or PolynomialLaw) built the law."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fpucore import CubicLaw, floquet, law_from_expression, qc, simulate, wave

QUARTIC = law_from_expression("w + 10*w**2 - w**3 - 0.01*w**4")
CUBIC, CUBIC_POLY = CubicLaw(-1.0, 10.0), law_from_expression("w + 10*w**2 - w**3")


def _flow_residual(law, r):
    """max over sites of |w(T) shifted − w(0)| with the true flow (DOP853, rtol 1e-13)."""
    N = r.N

    def rhs(t, y):
        ext = np.concatenate([[law.f(r.w_left)], law.f(y[:N]), [law.f(r.w_right)]])
        return np.concatenate([y[N:], ext[2:] - 2 * ext[1:-1] + ext[:-2]])

    y0 = np.concatenate([r.w, r.wdot])
    sol = solve_ivp(rhs, (0, 1 / r.V), y0, method="DOP853", rtol=1e-13, atol=1e-13)
    wT, wdT = sol.y[:N, -1], sol.y[N:, -1]
    return max(np.max(np.abs(wT[1:] - r.w[:-1])), np.max(np.abs(wdT[1:] - r.wdot[:-1]))), wT


@pytest.mark.parametrize(
    "make",
    [
        lambda L: wave.solve_superkink(L, 5.2),
        lambda L: wave.solve_superkink(L, 5.2, "upper"),
        lambda L: wave.solve_solitary(L, 1.0, 5.0),
        lambda L: wave.solve_solitary(L, 6.0, 5.3),
    ],
    ids=["sk-lower", "sk-upper", "tensile", "compressive"],
)
def test_cubic_wave_is_the_same_whichever_route_built_the_law(make):
    """CubicLaw (closed-form QC guess, LAW_CUBIC kernel) vs PolynomialLaw (numerical QC guess,
    LAW_POLY kernel, bit-identical arithmetic for degree 3): the QC guesses differ at ~1e-13, so
    the two Newton solves agree to their residual tolerance, not bit for bit."""
    a, b = make(CUBIC), make(CUBIC_POLY)
    assert a.converged and b.converged
    assert (a.N, a.m, a.K) == (b.N, b.m, b.K)
    scale = max(1.0, abs(a.w_left), abs(a.w_right))
    assert np.max(np.abs(a.w - b.w)) <= 1e-11 * scale
    assert np.max(np.abs(a.wdot - b.wdot)) <= 1e-11 * scale * a.V
    if a.kind != "superkink":
        assert abs(a.energy - b.energy) <= 1e-11 * abs(a.energy)


@pytest.fixture(scope="module")
def quartic_waves():
    return {
        "lower": wave.solve_superkink(QUARTIC, 5.2),
        "upper": wave.solve_superkink(QUARTIC, 5.2, "upper"),
        "tensile": wave.solve_solitary(QUARTIC, 1.0, 5.0),
        "compressive": wave.solve_solitary(QUARTIC, 1.0, 5.35),
    }


@pytest.mark.parametrize("which", ["lower", "upper", "tensile", "compressive"])
def test_quartic_waves_are_fixed_points_of_the_true_flow(quartic_waves, which):
    r = quartic_waves[which]
    assert r.converged, r.message
    scale = max(1.0, abs(r.w_left), abs(r.w_right))
    assert r.residual <= 1e-12 * scale and r.dropped_residual <= 1e-12 * scale
    res, wT = _flow_residual(QUARTIC, r)
    assert res < 1e-10
    if r.kind == "superkink":
        sk = qc.superkink_from_V(QUARTIC, 5.2, which)
        # boundary states from the numerical §3 theory; no cubic symmetry: w₊ + w₋ ≠ 2w*
        assert (r.w_left, r.w_right) == (sk.w_minus, sk.w_plus)
        assert abs(sk.w_plus + sk.w_minus - 2 * QUARTIC.w_star) > 0.03
        assert abs(wT[r.N // 2 + 1] - sk.w_center) < 1e-10  # pinning w_1(T) = w(0) of the QC
    else:
        assert r.w_left == r.w_right == qc.solitary(QUARTIC, 1.0, r.V).w_B
        assert r.kind == which


def test_quartic_superkink_branches_are_not_mirror_images(quartic_waves):
    """Same V, swapped states (the equal-area and Rayleigh conditions are symmetric in w₊ ↔ w₋),
    but the profile of the upper branch is not the lower one reflected about w* (the cubic's
    w ↦ 2w* − w symmetry is gone)."""
    lo, up = quartic_waves["lower"], quartic_waves["upper"]
    assert up.w_left == pytest.approx(lo.w_right, abs=1e-12)
    assert up.w_right == pytest.approx(lo.w_left, abs=1e-12)
    mirror = 2 * QUARTIC.w_star - lo.w
    assert np.max(np.abs(np.sort(mirror) - np.sort(up.w))) > 1e-2


@pytest.mark.parametrize("which", ["lower", "tensile"])
def test_quartic_seeded_simulation_keeps_velocity_and_shape(quartic_waves, which):
    r = quartic_waves[which]
    s = simulate.seeded(r, t_end=55.0 / r.V)
    assert s.success, s.message
    d = s.details
    assert d["periods"] >= 50 and d["n_sites_timed"] >= 50
    assert d["velocity_error"] < 1e-8 and d["shape_error"] < 1e-8
    assert s.energy_drift < 1e-10
    assert len(s.waves) == 1 and s.waves[0].velocity == pytest.approx(r.V, abs=1e-6)


@pytest.mark.parametrize("which", ["superkink", "tensile"])
def test_quartic_floquet_spectrum_has_quartet_symmetry(which):
    if which == "superkink":
        r = wave.solve_superkink(QUARTIC, 5.2, N=120)
    else:
        r = wave.solve_solitary(QUARTIC, 1.0, 5.0, N=80)
    fr = floquet.spectrum(r)
    assert fr.symmetry_error <= 1e-11 and fr.error >= fr.symmetry_error
    assert fr.n_trivial == (2 if which == "superkink" else 4)
    for g in fr.quartets():
        mu = g[0]
        assert np.allclose(g[1:], [np.conj(mu), 1 / np.conj(mu), 1 / mu], atol=1e-9)


def test_quartic_flat_top_wave_next_to_V_SK_by_the_plateau_route():
    """1e-9 above V_SK the compressive wave is a kink–antikink bundle whose plateau sits at the
    superkink's other state w₊ = 1 (paper §4–5): the mass-continuation route converges and its
    amplitude approaches the superkink jump |w₋ − w₊| of the numerical §3 theory."""
    sk = qc.superkink_from_w_plus(QUARTIC, 1.0)
    r = wave.solve_solitary(QUARTIC, 1.0, sk.V + 1e-9)
    assert r.converged, r.message
    assert "plateau" in r.route and r.front_uncertainty < 1.0
    assert r.residual <= 1e-12 * max(1.0, abs(r.w_left))
    assert r.w_left == pytest.approx(sk.w_minus, abs=1e-6)  # w_S(V) → w₋ as V → V_SK
    # the discrete plateau sits 1.6e-4 from the QC saddle at this δ (lattice correction)
    assert r.amplitude == pytest.approx(sk.amplitude, abs=1e-3)
