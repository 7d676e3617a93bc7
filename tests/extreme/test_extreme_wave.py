"""Discrete waves (fpucore.wave, paper §5) at the edges of parameter space.

Each case is checked twice: by the result's own error budget (residual, dropped equation,
step-doubling integrator error, tail error — :func:`_own_budget`) and by an independent check:
the QC limit (eqs. SKsoln_cubic, SWsoln_cubic, Eren_QC), the mirror symmetry w ↦ 2w* − w of the
cubic law (paper §4: f(w) + f(2w* − w) = const maps waves to waves, w₊ ↦ 2w* − w₊), an exact
rescaling between two laws, or a second chain length N.  Cases the solver cannot do must be
refused with the reason (ParameterError naming the argument and, for wide waves, the N needed)
or returned with converged=False and a message — never NaN, never a hang (the solver's own
iteration/time budgets bound every call; no wall-clock asserts here).

The paper's flat-top waves at V = 5.21749194749 and 5.2174919476 (w₊ = 6, |V − V_SK| ≈ 1e-11,
1e-10) are solved by continuation in plateau mass (fpucore.wave.plateau, ~1–2 s each) and checked
at the end of this file; timings are in ``benchmarks/bench_extreme_wave.py``.
"""

import math
import re

import numpy as np
import pytest

from fpucore import qc, wave
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.wave import tails as wt

LAW = CubicLaw(-1.0, 10.0)
STIFF = CubicLaw(-1.0, 100.0)  # f' up to c_max² ≈ 3334, periods T = 1/V ≈ 0.02
TINY = CubicLaw(-0.01, 10.0)  # strains up to ~667
CP1, V_SK1, CM1 = qc.sound_speeds(LAW, 1.0)
CP6, V_SK6, CM6 = qc.sound_speeds(LAW, 6.0)


def _scale(r) -> float:
    return max(1.0, abs(r.w_left), abs(r.w_right))


def _own_budget(r, rel=1e-10):
    """The result's own error estimates, relative to the strain scale (brief: residual ≤ 1e-10)."""
    assert r.converged, r.message
    s = _scale(r)
    assert np.all(np.isfinite(r.w)) and np.all(np.isfinite(r.wdot))
    assert r.residual <= rel * s
    assert r.dropped_residual <= 10 * rel * s
    assert math.isfinite(r.integrator_error) and r.integrator_error <= rel * s
    assert r.tail_error <= 1e-5 * r.amplitude + 1e3 * 1e-12 * s
    assert r.jacobian_truncation <= 1e-12
    assert r.elapsed_s > 0 and len(r.residual_history) == r.iterations + 1


def _common(a, b):
    """max |w_a − w_b| over the sites the two chains share (both centred on n = 0)."""
    lo, hi = max(a.n[0], b.n[0]), min(a.n[-1], b.n[-1])
    ia, ib = (a.n >= lo) & (a.n <= hi), (b.n >= lo) & (b.n <= hi)
    return float(np.max(np.abs(a.w[ia] - b.w[ib])))


def _second_N(r, solve, factor=1.5):
    """Same wave on a longer chain: the profile agrees on the shared sites."""
    N2 = 2 * int(math.ceil(factor * r.N / 2))
    r2 = solve(N2)
    _own_budget(r2)
    return _common(r, r2)


# ============================================================================ near-sonic limits
@pytest.mark.parametrize("eps", [1e-3, 1e-5])
@pytest.mark.parametrize("side", ["c+", "c-"])
def test_near_sonic_solitary_waves_grow_N_and_approach_qc(side, eps):
    V = CP1 * (1 + eps) if side == "c+" else CM1 * (1 - eps)
    r = wave.solve_solitary(LAW, 1.0, V)
    _own_budget(r)
    # automatic N follows the discrete decay rate λ → 0 (width ~ 1/λ ~ 1/√eps)
    lam = wt.decay_rate(LAW, r.w_left, V)
    assert r.N >= 2 * math.log(r.amplitude / 1e-12) / lam * 0.5
    # independent: the QC wave (exact in the sonic limit, paper §5) and its energy
    sw = qc.solitary(LAW, 1.0, V)
    assert r.qc_max_deviation <= 0.05 * r.amplitude
    assert abs(r.energy - sw.energy) <= 0.05 * abs(sw.energy)
    # absolute, not relative to the tiny amplitude: tol is relative to the strain scale and the
    # system's conditioning worsens like 1/λ² (measured: 2.5e-11 at eps = 1e-3; 8e-9 at 1e-5,
    # where the two solutions' profile_error bounds are 6e-8 and 1.6e-7)
    r2 = wave.solve_solitary(LAW, 1.0, V, N=2 * int(math.ceil(0.75 * r.N)))
    _own_budget(r2)
    assert _common(r, r2) <= r.profile_error + r2.profile_error
    if eps >= 1e-3:
        assert _common(r, r2) <= 1e-9 * _scale(r)


def test_near_sonic_N_grows_monotonically():
    Ns = [wave.solve_solitary(LAW, 1.0, CP1 * (1 + e)).N for e in (1e-2, 1e-3, 1e-4)]
    assert Ns[0] < Ns[1] < Ns[2]


@pytest.mark.parametrize("V", [CP1 * (1 + 1e-8), CM1 * (1 - 1e-14)])
def test_too_close_to_sonic_is_refused_with_needed_N(V):
    with pytest.raises(ParameterError) as ei:
        wave.solve_solitary(LAW, 1.0, V)
    msg = str(ei.value)
    assert ei.value.name == "V"
    m = re.search(r"need N = (\d+|unbounded)", msg)
    assert m, msg
    assert m.group(1) == "unbounded" or int(m.group(1)) > wt.N_MAX
    assert f"N_MAX = {wt.N_MAX}" in msg


@pytest.mark.parametrize("V", [CP1, CM1, V_SK1])
def test_exact_sonic_and_superkink_velocities_refused(V):
    with pytest.raises(ParameterError) as ei:
        wave.solve_solitary(LAW, 1.0, V)
    assert ei.value.name == "V" and "valid" in str(ei.value)


# ============================================================================ near V_SK (w₊ = 6)
@pytest.mark.parametrize("sgn", [-1.0, 1.0])
def test_flat_top_bundles_near_V_SK(sgn):
    """Kink–antikink bundles: the plateau tends to the superkink's other state (w₋ below V_SK,
    w₊ above; paper §4) as |V − V_SK| shrinks — measured convergence, plus the mirror wave."""
    w_minus = 2 * LAW.w_star - 6.0
    plateau = w_minus if sgn < 0 else 6.0
    gaps = []
    for d in (1e-4, 1e-5):
        r = wave.solve_solitary(LAW, 6.0, V_SK6 + sgn * d)
        _own_budget(r)
        gaps.append(abs(r.w[r.N // 2] - plateau))
    assert gaps[1] < 0.5 * gaps[0] and gaps[1] < 0.05, gaps
    w_B_lim = 6.0 if sgn < 0 else w_minus  # background w_B → w₊ (below) or w_S(V) → w₋ (above)
    assert abs(r.amplitude - abs(w_minus - 6.0)) <= gaps[1] + abs(r.w_left - w_B_lim) + 1e-12
    # mirror symmetry, w₊ ↦ 2w* − w₊ at the same V and N (a different solve: different guess,
    # different boundary states)
    mr = wave.solve_solitary(LAW, w_minus, r.V, N=r.N)
    assert mr.converged, mr.message
    assert np.max(np.abs(mr.w - (2 * LAW.w_star - r.w))) <= 1e-8 * _scale(r)


def test_very_close_to_V_SK_returns_or_refuses_within_budget():
    """|V − V_SK| = 1e-8: either a correct wave or converged=False with the reason."""
    r = wave.solve_solitary(LAW, 6.0, V_SK6 - 1e-8, time_budget_s=4.0)
    if r.converged:
        _own_budget(r)
    else:
        # the reason: what to try, where it stalled, or (budget spent in the plateau route on a
        # loaded machine) the nearest solvable V
        reason = ("try", "stalled", "nearest solvable V")
        assert "NOT converged" in r.message and any(k in r.message for k in reason), r.message
        assert np.all(np.isfinite(r.w))


# ============================================================================ w₊ → w*, V → V_hi
@pytest.mark.parametrize("dw", [0.1, 0.03])
def test_vanishing_family_near_w_star(dw):
    w_plus = LAW.w_star - dw
    (a, b), (c, d) = qc.solitary_intervals(LAW, w_plus)
    for V in (0.5 * (a + b), 0.5 * (c + d)):
        r = wave.solve_solitary(LAW, w_plus, V)
        _own_budget(r)
        sw = qc.solitary(LAW, w_plus, V)
        assert r.qc_max_deviation <= 0.02 * r.amplitude  # small, wide: QC is accurate
        m = wave.solve_solitary(LAW, 2 * LAW.w_star - w_plus, V, N=r.N)
        # within both error bounds (measured 1.7e-8 against bounds 6e-8 + 2.4e-7 at dw = 0.03:
        # these wide, weak waves are ill-conditioned; the old stopping rule returned the QC
        # guess itself, residual 1.3e-12 ≤ tol, whose mirror image is exact by construction)
        mirror = np.max(np.abs(m.w - (2 * LAW.w_star - r.w)))
        assert mirror <= r.profile_error + m.profile_error
        assert mirror <= 1e-7 * max(1.0, sw.amplitude)


def test_vanishing_family_refused_with_needed_N():
    w_plus = LAW.w_star - 1e-3
    (a, b), _ = qc.solitary_intervals(LAW, w_plus)
    with pytest.raises(ParameterError, match=r"need N = \d+ sites"):
        wave.solve_solitary(LAW, w_plus, 0.5 * (a + b))
    with pytest.raises(ParameterError) as ei:
        wave.solve_solitary(LAW, LAW.w_star, 5.8)
    assert ei.value.name == "w_plus"


# ============================================================================ superkink range ends
LO, HI = qc.superkink_velocity_bounds(LAW)


@pytest.mark.parametrize("V", [LO * (1 + 1e-6), LO * (1 + 1e-3), HI * (1 - 1e-3), HI * (1 - 1e-4)])
def test_superkinks_near_both_velocity_bounds(V):
    r = wave.solve_superkink(LAW, V)
    _own_budget(r)
    sk = qc.superkink_from_V(LAW, V)
    # w± at the convex interval's edges (f′ → 0) near V_lo; w± → w* near V_hi
    assert (r.w_left, r.w_right) == (sk.w_minus, sk.w_plus)
    up = wave.solve_superkink(LAW, V, "upper", N=r.N)
    assert up.converged, up.message
    assert np.max(np.abs(up.w - (2 * LAW.w_star - r.w))) <= 1e-9 * _scale(r)
    assert _second_N(r, lambda N: wave.solve_superkink(LAW, V, N=N)) <= 1e-9 * _scale(r)
    if V > 0.5 * (LO + HI):  # QC limit near V_hi (paper §5: discrete → QC for wide fronts)
        assert r.qc_max_deviation <= 0.05 * r.amplitude


# ============================================================================ stiff laws
def _stiff_cases():
    lo, hi = qc.superkink_velocity_bounds(STIFF)  # same bounds for TINY (c_max is shared)
    wp = STIFF.alpha + 0.25 * (STIFF.beta - STIFF.alpha)
    (a, b), (c, d) = qc.solitary_intervals(STIFF, wp)
    return [
        ("superkink", None, lo + 0.02 * (hi - lo)),
        ("superkink", None, lo + 0.6 * (hi - lo)),
        ("solitary", wp, a + 0.9 * (b - a)),
        ("solitary", wp, c + 0.3 * (d - c)),
    ]


def _solve(law, kind, wp, V, **kw):
    if kind == "superkink":
        return wave.solve_superkink(law, V, **kw)
    return wave.solve_solitary(law, wp, V, **kw)


@pytest.mark.parametrize("kind,wp,V", _stiff_cases())
def test_stiff_and_huge_strain_laws(kind, wp, V):
    """(a, b) = (−0.01, 10) is (−1, 100) with strains × 10: f_tiny(10u) = 10 f_stiff(u), so
    w_tiny = 10 w_stiff solves eq. FPUstrain at the same V — an exact independent check."""
    r = _solve(STIFF, kind, wp, V)
    _own_budget(r)
    t = _solve(TINY, kind, None if wp is None else 10 * wp, V, N=r.N)
    _own_budget(t)
    assert np.max(np.abs(t.w - 10 * r.w)) <= 1e-9 * _scale(t)
    assert abs(t.amplitude - 10 * r.amplitude) <= 1e-9 * _scale(t)
    if kind == "superkink":
        up = wave.solve_superkink(STIFF, V, "upper", N=r.N)
        assert np.max(np.abs(up.w - (2 * STIFF.w_star - r.w))) <= 1e-9 * _scale(r)
    else:
        assert math.isfinite(r.energy)
        assert _second_N(r, lambda N: _solve(STIFF, kind, wp, V, N=N)) <= 1e-9 * _scale(r)


# ======================================================================= absurd inputs, budgets
@pytest.mark.parametrize(
    "call,name",
    [
        (lambda: wave.solve_superkink(LAW, 5.2, N=10**9), "N"),
        (lambda: wave.solve_superkink(LAW, 5.2, N=2**62), "N"),
        (lambda: wave.solve_superkink(LAW, 5.2, N=64.0), "N"),
        (lambda: wave.solve_superkink(LAW, 5.2, N=True), "N"),
        (lambda: wave.solve_superkink(LAW, 5.2, N=-64), "N"),
        (lambda: wave.solve_superkink(LAW, 5.2, tol=0.0), "tol"),
        (lambda: wave.solve_superkink(LAW, 5.2, tol=-1e-12), "tol"),
        (lambda: wave.solve_superkink(LAW, 5.2, tol=float("nan")), "tol"),
        (lambda: wave.solve_superkink(LAW, 5.2, tol=1.0), "tol"),
        (lambda: wave.solve_superkink(LAW, 5.2, max_iter=0), "max_iter"),
        (lambda: wave.solve_superkink(LAW, 5.2, time_budget_s=0.0), "time_budget_s"),
        (lambda: wave.solve_superkink(LAW, 5.2, time_budget_s=float("inf")), "time_budget_s"),
        (lambda: wave.solve_superkink(LAW, 5.2, jacobian="guess"), "jacobian"),
        (lambda: wave.solve_superkink(LAW, LO), "V"),
        (lambda: wave.solve_superkink(LAW, HI), "V"),
        (lambda: wave.solve_superkink(LAW, -5.2), "V"),
        (lambda: wave.solve_superkink(LAW, float("inf")), "V"),
        (lambda: wave.solve_solitary(LAW, 1.0, -5.0), "V"),
        (lambda: wave.solve_solitary(LAW, float("nan"), 5.0), "w_plus"),
        (lambda: wave.solve_solitary(LAW, LAW.beta + 1, 5.0), "w_plus"),
    ],
)
def test_absurd_inputs_refused(call, name):
    with pytest.raises(ParameterError) as ei:
        call()
    assert ei.value.name == name and "valid" in str(ei.value)


def test_budgets_report_non_convergence():
    r = wave.solve_solitary(LAW, 6.0, V_SK6 - 1e-5, max_iter=2, time_budget_s=0.5)
    assert not r.converged and "NOT converged" in r.message
    assert math.isfinite(r.residual) and np.all(np.isfinite(r.w))


# ============================================================ flat tops at the paper's velocities
# Paper Fig. stabSW: V = 5.21749194749 (compressive, δ = |V − V_SK| ≈ 9.5e-12) and 5.2174919476
# (tensile, δ ≈ 1.0e-10).  Solved by continuation in plateau mass (fpucore.wave.plateau).
PAPER_V = [5.21749194749, 5.2174919476]
W_MINUS6 = 2 * LAW.w_star - 6.0


def _flat_top_checks(r):
    assert r.converged, r.message
    s = _scale(r)
    assert r.residual <= 1e-11 * s and r.dropped_residual <= 1e-11 * s
    assert r.integrator_error <= 1e-10 * s
    assert r.tail_error <= 1e-9 * s  # tails at the boundary state w_B
    assert 0 < r.front_uncertainty < 1.0 and "plateau-length uncertainty" in r.message


@pytest.mark.parametrize("V", PAPER_V)
def test_paper_flat_top_waves_converge_with_front_error_bar(V):
    r = wave.solve_solitary(LAW, 6.0, V)
    _flat_top_checks(r)
    assert "plateau route" in r.route
    # amplitude → |w₋ − w₊| = 16/3 (paper §4); the plateau sits at the superkink's other state
    jump = abs(W_MINUS6 - 6.0)
    r8 = wave.solve_solitary(LAW, 6.0, V_SK6 + math.copysign(1e-8, V - V_SK6))
    assert abs(r.amplitude - jump) < abs(r8.amplitude - jump) < 1e-2
    assert abs(r.amplitude - jump) <= 1e-4
    # mirror w₊ ↦ 2w* − w₊ (an independent solve): same plateau within both error bars
    m = wave.solve_solitary(LAW, W_MINUS6, V, N=r.N)
    _flat_top_checks(m)
    from fpucore.wave import plateau as wp

    hr, hm = wp.half_plateau(r.w, r.w_left), wp.half_plateau(m.w, m.w_left)
    assert abs(hr - hm) <= 2 * (r.front_uncertainty + m.front_uncertainty) + 1e-6
    assert abs(r.amplitude - m.amplitude) <= 1e-6


@pytest.mark.parametrize("sgn", [-1.0, 1.0])
def test_front_moves_ln10_over_2lambda_per_decade(sgn):
    """Fronts interact like e^{−2λ d}: each moves ln(10)/(2λ) sites per decade of δ, λ the
    discrete tail rate at the plateau state (closed form, wave_tails.decay_rate) — not QC's γ."""
    from fpucore.wave import plateau as wp

    plateau = W_MINUS6 if sgn < 0 else 6.0
    h = []
    for d in (1e-5, 1e-7, 1e-9, 1e-11):
        r = wave.solve_solitary(LAW, 6.0, V_SK6 + sgn * d)
        assert r.converged, r.message
        h.append(wp.half_plateau(r.w, r.w_left))
    lam = wt.decay_rate(LAW, plateau, V_SK6)
    per_decade = np.diff(h) / 2.0
    pred = math.log(10) / (2 * lam)
    assert np.all(np.abs(per_decade - pred) <= 0.03 * pred), (per_decade, pred)
    sw = qc.solitary(LAW, 6.0, V_SK6 + sgn * 1e-11)
    assert abs(per_decade[-1] - math.log(10) / (2 * sw.gamma)) > 0.1 * pred  # QC rate differs


@pytest.mark.parametrize("sgn", [-1.0, 1.0])
def test_V_SK_pm_1e8_converges(sgn):
    _flat_top_checks(wave.solve_solitary(LAW, 6.0, V_SK6 + sgn * 1e-8))


def test_plateau_too_close_is_refused_with_nearest_V():
    """δ = 1e-14: the residual cannot fix the plateau (error bar > 1 site): refused, with the
    reason and a solvable V."""
    r = wave.solve_solitary(LAW, 6.0, V_SK6 - 1e-14, time_budget_s=20.0)
    assert not r.converged
    assert "exponentially weakly tied to V" in r.message and "nearest solvable V" in r.message
    v_ok = float(re.search(r"nearest solvable V is about ([0-9.e+-]+)", r.message).group(1))
    assert V_SK6 - 1e-9 < v_ok < V_SK6 - 1e-14
