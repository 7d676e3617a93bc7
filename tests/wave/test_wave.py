"""Discrete superkinks and solitary waves (fpucore.wave, paper §5).

References: the paper's system (eq. nonlin_system) and its stated accuracy (dropped equation
≈ 1e-13 at N = 500); an independent integrator (scipy's adaptive DOP853) applied to the
computed fixed point; the paper's own finite-difference-Jacobian Newton as a second method;
QC closed forms (eqs. SKsoln_cubic, SWsoln_cubic, Eren_QC) in the limits where the paper says the
QC model is accurate; and measured convergence (FD truncation ∝ h², N-independence of E_ren^D).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fpucore import qc, wave
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.wave.system import WaveSystem

LAW = CubicLaw(-1.0, 10.0)
V_SK1, CP1, CM1 = 2 * math.sqrt(65) / 3, 3 * math.sqrt(2), 5.5  # w+ = 1 (paper, Fig. SWs_cubic)
V_SK6, CP6, CM6 = 7 * math.sqrt(5) / 3, math.sqrt(13), math.sqrt(29)  # w+ = 6


def _check_wave(r, tol=1e-11):
    assert r.converged, r.message
    assert r.residual <= tol and r.dropped_residual <= tol
    # tails equal the boundary states (to the far-field conditioning of an N = 500 chain)
    assert r.tail_error <= 1e-10
    assert np.max(np.abs(r.w[:3] - r.w_left)) <= 1e-10
    assert np.max(np.abs(r.w[-3:] - r.w_right)) <= 1e-10
    assert r.integrator_error <= 1e-10 and r.jacobian_truncation <= 1e-16
    assert r.elapsed_s > 0 and len(r.residual_history) == r.iterations + 1


def test_paper_velocities_match_qc_module():
    assert np.allclose(qc.sound_speeds(LAW, 1.0), (CP1, V_SK1, CM1), rtol=1e-14)
    assert np.allclose(qc.sound_speeds(LAW, 6.0), (CP6, V_SK6, CM6), rtol=1e-14)


@pytest.mark.parametrize("V", [4.9, 5.2, 5.5, 5.8])
def test_superkinks_N500(V):
    r = wave.solve_superkink(LAW, V, N=500)
    _check_wave(r)
    sk = qc.superkink_from_V(LAW, V)
    assert r.kind == "superkink" and r.N == 500 and r.n[0] == -250 and r.n[-1] == 249
    assert (r.w_left, r.w_right) == (sk.w_minus, sk.w_plus)
    assert np.all(np.diff(r.w) <= 1e-10)  # monotone front up to the tail error (paper §3)
    assert abs(r.w[r.N // 2] - LAW.w_star) < 0.1 * sk.amplitude  # pinned near w(0) = w*


def test_superkink_upper_branch_is_mirror_image():
    lo = wave.solve_superkink(LAW, 5.2, "lower")
    up = wave.solve_superkink(LAW, 5.2, "upper", N=lo.N)
    assert up.converged
    # symmetry f(w) + f(2w* − w) = const maps waves to waves (paper §4): w ↦ 2w* − w
    assert np.max(np.abs(up.w - (2 * LAW.w_star - lo.w))) < 1e-10


@pytest.mark.parametrize(
    "w_plus,V",
    [
        (1.0, 4.6),
        (1.0, 5.2),
        (1.0, 5.42),
        (1.0, 5.48),
        (6.0, 4.2),
        (6.0, 5.0),
        (6.0, 5.25),
        (6.0, 5.35),
    ],
)
def test_solitary_waves_N500(w_plus, V):
    r = wave.solve_solitary(LAW, w_plus, V, N=500)
    _check_wave(r)
    sw = qc.solitary(LAW, w_plus, V)
    assert r.kind == sw.kind and r.w_left == r.w_right == sw.w_B
    # extremum at n = 0 (pinning ẇ_1(T) = 0) and the wave's sign matches its kind
    k = int(np.argmax(np.abs(r.w - sw.w_B)))
    assert r.n[k] == 0
    assert (r.w[k] > sw.w_B) == (sw.kind == "tensile")
    assert abs(r.amplitude - abs(r.w[k] - sw.w_B)) < 1e-15


def test_fixed_point_of_independent_integrator():
    """The solution is a fixed point of the true flow, not only of the fixed-step RK map."""
    r = wave.solve_superkink(LAW, 5.2)
    N, V = r.N, r.V

    def rhs(t, y):
        fw = LAW.f(y[:N])
        ext = np.concatenate([[LAW.f(r.w_left)], fw, [LAW.f(r.w_right)]])
        return np.concatenate([y[N:], ext[2:] - 2 * ext[1:-1] + ext[:-2]])

    sol = solve_ivp(
        rhs, (0, 1 / V), np.concatenate([r.w, r.wdot]), method="DOP853", rtol=1e-13, atol=1e-13
    )
    wT, wdT = sol.y[:N, -1], sol.y[N:, -1]
    assert np.max(np.abs(wT[1:] - r.w[:-1])) < 1e-10
    assert np.max(np.abs(wdT[1:] - r.wdot[:-1])) < 1e-10
    assert abs(wT[N // 2 + 1] - LAW.w_star) < 1e-10  # pinning w_1(T) = w*


def _system_at(r):
    sp = wave.superkink_spec(LAW, r.V, "lower")
    x = np.empty(2 * r.N)
    x[0::2], x[1::2] = r.w, r.wdot
    return sp.system(r.N, r.m, r.K), x


def test_exact_jacobian_matches_finite_differences():
    r = wave.solve_superkink(LAW, 5.2, N=64)
    S, x = _system_at(r)
    ab, kl, ku, trunc, F, _ = S.jacobian_banded(x)
    J = S.dense_from_banded(ab, kl, ku)

    def central(h):
        Jc = np.empty_like(J)
        for j in range(x.size):
            e = np.zeros_like(x)
            e[j] = h
            Jc[:, j] = (S.residual(x + e)[0] - S.residual(x - e)[0]) / (2 * h)
        return Jc

    e3, e4 = np.max(np.abs(J - central(1e-3))), np.max(np.abs(J - central(1e-4)))
    assert e4 < 1e-6
    assert 30 < e3 / e4 < 300  # the gap shrinks like h²: the FD truncation, not J's error
    # the paper's forward differences agree to their own truncation level √ε
    assert np.max(np.abs(J - S.jacobian_fd(x))) < 1e-5
    assert trunc < 1e-16


def test_paper_fd_jacobian_route_gives_same_wave():
    ex = wave.solve_solitary(LAW, 1.0, 5.0, N=64)
    fd = wave.solve_solitary(LAW, 1.0, 5.0, N=64, jacobian="fd")
    assert ex.converged and fd.converged and fd.jacobian == "fd"
    assert np.max(np.abs(ex.w - fd.w)) < 1e-10 and np.max(np.abs(ex.wdot - fd.wdot)) < 1e-10


def test_superkink_approaches_qc_near_upper_velocity_limit():
    lo, hi = qc.superkink_velocity_bounds(LAW)
    Vs = [5.5, 5.7, 5.8, 5.85]
    rel = []
    for V in Vs:
        r = wave.solve_superkink(LAW, V)
        assert r.converged
        rel.append(r.qc_max_deviation / r.amplitude)
    assert all(b < a for a, b in zip(rel, rel[1:])), rel
    assert rel[-1] < 0.2 * rel[0]


@pytest.mark.parametrize(
    "w_plus,Vs",
    [(1.0, [4.5, 4.3, 4.25]), (1.0, [5.45, 5.49, 5.499]), (6.0, [3.8, 3.65, 3.62])],
)
def test_solitary_approaches_qc_near_sonic_limits(w_plus, Vs):
    rel_dev, rel_E = [], []
    for V in Vs:
        r = wave.solve_solitary(LAW, w_plus, V)
        assert r.converged, r.message
        sw = qc.solitary(LAW, w_plus, V)
        rel_dev.append(r.qc_max_deviation / r.amplitude)
        rel_E.append(abs(r.energy - sw.energy) / abs(sw.energy))
    assert all(b < a for a, b in zip(rel_dev, rel_dev[1:])), rel_dev
    assert all(b < a for a, b in zip(rel_E, rel_E[1:])), rel_E
    assert rel_dev[-1] < 0.01 and rel_E[-1] < 0.01


def test_solitary_amplitude_tends_to_superkink_jump_near_V_SK():
    """Paper §4–5: at V → V_SK the amplitude → |w₋ − w₊| = 14/3 (kink–antikink bundle), from
    both sides; the approach is slow (measured: gap ∝ √|V − V_SK|), so Newton needs the
    continuation in log|V − V_SK| that solve_solitary falls back on."""
    jump = abs(2 * LAW.w_star - 2 * 1.0)  # w₋ = 2w* − w₊ = 17/3, w₊ = 1
    for sgn in (-1.0, 1.0):
        gaps = []
        for d in (1e-2, 1e-3, 1e-5):
            r = wave.solve_solitary(LAW, 1.0, V_SK1 + sgn * d)
            assert r.converged, r.message
            gaps.append(jump - r.amplitude)
        assert all(0 < b < a for a, b in zip(gaps, gaps[1:])), gaps
        assert gaps[-1] < 0.03


def test_energy_independent_of_N_and_velocity_convention():
    a = wave.solve_solitary(LAW, 1.0, 5.0)
    b = wave.solve_solitary(LAW, 1.0, 5.0, N=500)
    assert a.N < 100
    # the E_ren^D summand vanishes in the tails only with v_± = −V w_B (module docstring)
    assert abs(a.energy - b.energy) < 1e-8 * abs(a.energy)
    assert abs(b.v[-1] + b.V * b.w_right) < 1e-10
    assert abs(b.v[0] + b.V * b.w_left) == 0.0


def test_particle_velocities_are_a_traveling_wave():
    """v_n from ẇ_n = v_n − v_{n−1} satisfies the (w, v) system of eq. FPUsystem with
    v_{n+1}(T) = v_n(0): integrate that system independently for one period."""
    r = wave.solve_solitary(LAW, 6.0, 5.3)
    N, V = r.N, r.V
    v0 = r.v  # particles −N/2−1 … N/2−1

    def rhs(t, y):
        w, v = y[:N], y[N:]
        wd = v[1:] - v[:-1]
        ws = np.concatenate([[r.w_left], w, [r.w_right]])
        vd = LAW.f(ws[1:]) - LAW.f(ws[:-1])
        return np.concatenate([wd, vd])

    sol = solve_ivp(
        rhs, (0, 1 / V), np.concatenate([r.w, v0]), method="DOP853", rtol=1e-13, atol=1e-13
    )
    vT = sol.y[N:, -1]
    assert np.max(np.abs(vT[1:] - v0[:-1])) < 1e-9


def test_family_continuation_converges_everywhere():
    from fpucore.wave import solitary_family, superkink_family

    fam = solitary_family(LAW, 6.0, [4.8, 4.9, 5.0, 5.1, 5.2, 5.25, 5.3])
    assert fam.converged and np.all(fam.residual <= 1e-11)
    assert list(fam.results[0].route.split()[:1]) == ["qc-guess"]
    assert all(r.route.startswith("predictor") for r in fam.results[1:5])
    sk = superkink_family(LAW, np.linspace(4.85, 5.8, 6), N=200)
    assert sk.converged and np.all(np.diff(sk.amplitude) < 0)


def test_non_convergence_is_reported_not_hidden():
    r = wave.solve_solitary(LAW, 6.0, 5.0, N=500, max_iter=1, time_budget_s=5.0)
    assert not r.converged and r.status == "not_converged"
    assert "NOT converged" in r.message and ("try" in r.message or "use" in r.message)
    assert r.residual > 1e-12


@pytest.mark.parametrize(
    "call,name",
    [
        (lambda: wave.solve_superkink(LAW, 4.0), "V"),
        (lambda: wave.solve_superkink(LAW, 6.5), "V"),
        (lambda: wave.solve_superkink(LAW, float("nan")), "V"),
        (lambda: wave.solve_superkink(LAW, 5.2, branch="middle"), "branch"),
        (lambda: wave.solve_superkink(LAW, 5.2, N=501), "N"),
        (lambda: wave.solve_superkink(LAW, 5.2, N=40), "N"),  # below N_MIN
        (lambda: wave.solve_superkink(LAW, 5.85, N=64), "N"),  # wide wave, short chain
        (lambda: wave.solve_superkink(LAW, 5.2, tol=0.0), "tol"),
        (lambda: wave.solve_solitary(LAW, 1.0, 5.6), "V"),
        (lambda: wave.solve_solitary(LAW, 1.0, 4.0), "V"),
        (lambda: wave.solve_solitary(LAW, 1.0, V_SK1), "V"),
        (lambda: wave.solve_solitary(LAW, float("inf"), 5.0), "w_plus"),
        (lambda: wave.solve_solitary(LAW, 1.0, CP1 * (1 + 1e-12)), "V"),  # needs N > N_MAX
        (lambda: wave.solve_solitary(LAW, 1.0, 4.26, N=100), "N"),  # near-sonic: wide
    ],
)
def test_bad_input_refused(call, name):
    with pytest.raises(ParameterError) as ei:
        call()
    assert ei.value.name == name
    assert "valid" in str(ei.value)


def test_short_chain_message_names_the_width():
    with pytest.raises(ParameterError, match="too small for the wave width"):
        wave.solve_superkink(LAW, 5.85, N=64)


def test_system_rows_are_the_papers_equations():
    """Row bookkeeping: F at the QC guess equals eq. nonlin_system written out directly."""
    sp = wave.solitary_spec(LAW, 1.0, 5.0)
    N = 40
    S = WaveSystem(LAW, 5.0, N, sp.w_left, sp.w_right, "wd", 0.0, 10, 12)
    x = sp.qc_guess(N)
    F, dropped = S.residual(x)
    r = S.integrate(x)
    w, wd = x[0::2], x[1::2]
    expect = np.concatenate(
        [r.w[1:] - w[:-1], [sp.w_right - w[-1]], r.wd[1:] - wd[:-1], [r.wd[N // 2 + 1]]]
    )
    assert np.array_equal(np.sort(F), np.sort(expect))
    assert F[S.row_pin] == r.wd[N // 2 + 1] and dropped == -wd[-1]
