"""Discrete traveling waves of piecewise-linear laws by the period-and-shift Newton (event-located
map and tangent).  References: the explicit compact waves of the degenerate law (eq.
TW_discrete solved in closed form, fpucore.wave.compact), measured convergence in the step and
in N away from it, and the same law typed as text."""

import numpy as np
import pytest

import fpucore as F
from fpucore.law import TrilinearLaw, law_from_expression
from fpucore.wave import period_map
from fpucore.wave.compact import compact_wave
from fpucore.wave.setup import resize, superkink_spec
from fpucore.wave.system import newton

DEGENERATE = TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2)
GENERAL = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2)
WB = 0.2


def state(w, wd):
    x = np.empty(2 * w.size)
    x[0::2], x[1::2] = w, wd
    return x


@pytest.mark.parametrize("V", [0.09, 0.15, 0.3, 0.5, 0.7])
def test_degenerate_solitary_waves_are_the_explicit_compact_waves(V):
    r = F.wave.solve_solitary(DEGENERATE, WB, V)
    cw = compact_wave(DEGENERATE, V, WB)
    assert r.converged and "compact-guess" in r.route
    xi = r.n.astype(float)
    err = np.max(np.abs(r.w - cw.profile(xi)))
    assert err <= r.profile_error <= 1e-9  # the bar covers the true error, and is not vacuous
    assert abs(r.amplitude - cw.amplitude) <= r.amplitude_error
    # mass Σ(w_n − w_B) is the same at every phase of a traveling wave, hence ∫(w − w_B) dξ
    assert abs(np.sum(r.w - WB) - cw.mass) <= r.N * r.profile_error
    # the compact support: sites beyond 1 + a are exactly the background
    far = np.abs(xi) > 1 + cw.a + 1e-9
    assert np.max(np.abs(r.w[far] - WB)) <= r.profile_error


def test_the_step_count_is_not_fooled_by_a_step_as_long_as_the_core():
    """At V = 0.15 a period of 6 steps lasts 1.11 ≈ π/√(2E₂), one bond's passage through the hard
    regime, and the step-doubling estimate at m = 6 agrees by accident (5e-15): the chosen m must
    give the exact compact wave's period-and-shift (w_n(T) = w_{n−1}(0)) to the tolerance."""
    V, N, tol = 0.15, 64, 1e-12
    cw = compact_wave(DEGENERATE, V, WB)
    w, wd = cw.lattice(np.arange(N) - N // 2)
    spec = F.wave.solitary_spec(DEGENERATE, WB, V)
    m = spec.choose_m_floor(state(w, wd), tol)
    r = period_map.integrate(DEGENERATE, w, wd, 1.0 / V, m, WB, WB)
    assert np.max(np.abs(r.w[1:] - w[:-1])) <= 1e3 * tol


def test_newton_reaches_the_compact_wave_from_another_velocitys_wave():
    V = 0.5
    start = compact_wave(DEGENERATE, 0.95 * V, WB)  # measured: 0.93 V is outside the basin

    def predictor(N):
        return state(*start.lattice(np.arange(N) - N // 2))

    r = F.wave.solve_solitary(DEGENERATE, WB, V, predictor=predictor)
    cw = compact_wave(DEGENERATE, V, WB)
    assert r.converged and r.iterations >= 3  # Newton had work to do (start 5% off in V)
    assert np.max(np.abs(r.w - cw.profile(r.n.astype(float)))) <= r.profile_error


def fixed_point(law, V, N, m, x0):
    sp = superkink_spec(law, V, "lower")
    sys_ = sp.system(N, m, 16)
    out = newton(sys_, resize(x0, x0.size // 2, N, sp.w_left, sp.w_right), 1e-13, step_tol=1e-14)
    assert out.converged
    return out.x


def test_trilinear_superkink_converges_at_the_methods_order_in_the_step():
    """Fixed points of the m-step map against m = 64: the log–log slope is DOP853's order (8)
    with event location (a crossing inside a step would cost it: ~2.5, period_events)."""
    V = 1.6
    r = F.wave.solve_superkink(GENERAL, V, N=64)
    x0 = state(r.w, r.wdot)
    ref = fixed_point(GENERAL, V, 64, 64, x0)
    ms = np.array([4, 5, 6, 7])  # measured local slopes 7.6, 8.3, 8.0; round-off from m = 8
    err = np.array([np.max(np.abs(fixed_point(GENERAL, V, 64, m, x0) - ref)[0::2]) for m in ms])
    assert np.all(err > 4e-13)  # above the Newton/round-off floor (~1.3e-13)
    slope = -np.polyfit(np.log(ms), np.log(err), 1)[0]
    assert slope >= 7.0


def test_trilinear_superkink_error_bars_cover_the_change_with_N_and_tol():
    V = 1.6
    a = F.wave.solve_superkink(GENERAL, V, N=64, tol=1e-8)
    b = F.wave.solve_superkink(GENERAL, V, N=128, tol=1e-12)
    assert a.converged and b.converged
    i = np.searchsorted(b.n, a.n)  # the same sites
    diff = np.max(np.abs(a.w - b.w[i]))
    assert diff <= a.profile_error + b.profile_error
    assert a.integrator_error <= 1e-8 * 10 and b.integrator_error <= 1e-11


def test_non_degenerate_solitary_wave_by_continuation_in_the_soft_modulus():
    """From the compact wave of E1 = 0 to E1 = 0.1 (the QC profile is too far for Newton);
    then N = 64 against N = 128: the bars cover the change."""
    V, prev = 0.6, F.wave.solve_solitary(DEGENERATE, WB, 0.6)
    for E1 in (0.03, 0.1):
        law = TrilinearLaw(0.5, 1.5, E1, 4.0, 0.2)
        x_prev, N_prev = state(prev.w, prev.wdot), prev.N
        prev = F.wave.solve_solitary(
            law, WB, V, N=64, predictor=lambda N, x=x_prev, n=N_prev: resize(x, n, N, WB, WB)
        )
        assert prev.converged, prev.message
    x = state(prev.w, prev.wdot)
    big = F.wave.solve_solitary(law, WB, V, N=128, predictor=lambda N: resize(x, 64, N, WB, WB))
    assert big.converged
    i = np.searchsorted(big.n, prev.n)
    assert np.max(np.abs(prev.w - big.w[i])) <= prev.profile_error + big.profile_error
    assert prev.profile_error <= 1e-9
    assert abs(prev.energy - big.energy) <= prev.energy_error + big.energy_error


def test_a_law_typed_as_text_gives_the_same_superkink():
    text = law_from_expression("trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)")
    a = F.wave.solve_superkink(GENERAL, 1.6, N=64)
    b = F.wave.solve_superkink(text, 1.6, N=64)
    assert np.array_equal(a.w, b.w) and np.array_equal(a.wdot, b.wdot)
    assert a.profile_error == b.profile_error


def test_trilinear_solitary_wave_by_continuation_from_the_superkink_limit():
    """The QC guess converges only near V_SK (the kink–antikink limit); the solver continues from
    there (Spec.easy_end of a PL law).  Then N = 64 against N = 128: the bars cover the change,
    and the energy of both agrees within its bars."""
    V = 1.4
    a = F.wave.solve_solitary(GENERAL, 0.3, V, N=64)
    assert a.converged and "continuation from V=1.6" in a.route, a.message
    x = state(a.w, a.wdot)
    b = F.wave.solve_solitary(
        GENERAL, 0.3, V, N=128, predictor=lambda N: resize(x, 64, N, a.w_left, a.w_right)
    )
    assert b.converged
    i = np.searchsorted(b.n, a.n)
    assert np.max(np.abs(a.w - b.w[i])) <= a.profile_error + b.profile_error
    assert abs(a.amplitude - b.amplitude) <= a.amplitude_error + b.amplitude_error
    assert abs(a.energy - b.energy) <= a.energy_error + b.energy_error
    assert a.profile_error <= 1e-10


@pytest.mark.parametrize("d", [-1e-6, 1e-6])
def test_trilinear_flat_tops_next_to_V_SK(d):
    """Flat tops 1e-6 from V_SK on both sides (kink–antikink bundles): converged with finite
    bars, and the same wave on N = 128 within them (measured: V_SK ∓ 1e-10 is refused with the
    reason, NOT converged, by the plateau route)."""
    vsk = F.qc.sound_speeds(GENERAL, 0.3)[1]
    a = F.wave.solve_solitary(GENERAL, 0.3, vsk + d, N=64)
    assert a.converged, a.message
    assert a.profile_error <= 1e-6
    x = state(a.w, a.wdot)
    b = F.wave.solve_solitary(
        GENERAL, 0.3, vsk + d, N=128, predictor=lambda N: resize(x, 64, N, a.w_left, a.w_right)
    )
    assert b.converged
    i = np.searchsorted(b.n, a.n)
    assert np.max(np.abs(a.w - b.w[i])) <= a.profile_error + b.profile_error


def test_the_result_says_how_transversal_its_crossings_are():
    V = 0.5
    r = F.wave.solve_solitary(DEGENERATE, WB, V)
    cw = compact_wave(DEGENERATE, V, WB)
    assert "2 breakpoint crossings located per period" in r.message
    assert f"crossing {V * abs(cw.C) * cw.omega:.3g} (transversal)" in r.message
    assert "crossing" not in F.wave.solve_superkink(F.CubicLaw(), 5.2, N=64).message
