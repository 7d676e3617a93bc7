"""Simulation layer at the edges of parameter space: long runs (t = 1e4) and stiff laws.

Independent checks: step halving (the symplectic energy error must fall like dt^4 and stay
bounded, not grow), the closed-form superkink velocity (eqs. cubic_cond1/2: a Riemann state w^l
behind the front selects w_+ = 2w* − w^l), and an exact rescaling of the equations.
"""

import numpy as np
import pytest

from fpucore import CubicLaw, qc, simulate

PAPER = CubicLaw(-1.0, 10.0)


def test_long_symplectic_run_energy_bounded_and_fourth_order():
    kw = dict(L=128, t_end=1.0e4, method="symplectic", n_snapshots=101, estimate_error=False)
    coarse = simulate.gaussian(PAPER, 1.0, 0.5, dt=0.04, **kw)
    fine = simulate.gaussian(PAPER, 1.0, 0.5, dt=0.02, **kw)
    assert coarse.success and fine.success, coarse.message
    assert coarse.t[-1] == pytest.approx(1.0e4)
    # bounded: the error over the last tenth is no larger than over the whole run (no drift)
    e = np.abs(coarse.energy - coarse.energy[0])
    assert e[-10:].max() <= 1.5 * e[:91].max()
    # fourth order: halving dt divides the energy error by ~16
    ratio = coarse.energy_drift / fine.energy_drift
    assert 10 < ratio < 24, ratio
    assert coarse.energy_drift < 1e-6


def test_long_adaptive_run_energy_drift_tracks_tolerance():
    kw = dict(L=128, t_end=1.0e4, n_snapshots=11)
    loose = simulate.gaussian(PAPER, 1.0, 0.5, rtol=1e-8, **kw)
    tight = simulate.gaussian(PAPER, 1.0, 0.5, rtol=1e-11, **kw)
    assert loose.success and tight.success
    assert tight.energy_drift < loose.energy_drift  # the tolerance controls the drift
    assert tight.energy_drift < 1e-8
    assert np.isfinite(tight.error_estimate) and tight.error_estimate > 0


STIFF = CubicLaw(-1.0, 100.0)  # f' up to ~3334: sound speeds ~ 58, ten times the paper's
TINY_A = CubicLaw(-0.01, 10.0)  # = STIFF with strains x 10: f_tiny(10u) = 10 f_stiff(u)


def _riemann_superkink(law, frac, L, t_end):
    wl = law.w_star + frac * (law.beta - law.w_star)
    s = simulate.riemann(law, wl, 0.0, L=L, t_end=t_end)
    assert s.success, s.message
    sks = [w for w in s.waves if w.kind == "superkink"]
    assert sks, [w.as_dict() for w in s.waves]
    sk_qc = qc.superkink_from_w_plus(law, 2 * law.w_star - wl)
    return s, sks[0], sk_qc


def test_stiff_law_riemann_superkink_velocity_matches_closed_form():
    s, sk, ref = _riemann_superkink(STIFF, 0.4, L=1600, t_end=10.0)
    assert sk.velocity == pytest.approx(-ref.V, rel=1e-6)
    assert s.energy_drift < 1e-7


def test_tiny_a_is_an_exact_rescaling_of_the_stiff_law():
    """Same Riemann data (in units of each law's w*): the fields must agree as w_tiny = 10 w_stiff
    to the integrators' tolerance, and the closed-form superkink speeds coincide."""
    runs = []
    for law in (STIFF, TINY_A):
        wl = law.w_star + 0.4 * (law.beta - law.w_star)
        runs.append(simulate.riemann(law, wl, 0.0, L=800, t_end=4.0, track=False))
        assert runs[-1].success, runs[-1].message
    s1, s2 = runs
    scale = np.max(np.abs(s2.final_w))
    assert np.max(np.abs(s2.final_w - 10.0 * s1.final_w)) < 1e-7 * scale
    assert abs(s2.energy_drift - s1.energy_drift) < 1e-8
    v1 = qc.superkink_from_w_plus(
        STIFF, 2 * STIFF.w_star - (STIFF.w_star + 0.4 * (STIFF.beta - STIFF.w_star))
    )
    v2 = qc.superkink_from_w_plus(
        TINY_A, 2 * TINY_A.w_star - (TINY_A.w_star + 0.4 * (TINY_A.beta - TINY_A.w_star))
    )
    assert v2.V == pytest.approx(v1.V, rel=1e-12)


def test_leaving_the_convex_interval_stops_with_a_message():
    s = simulate.riemann(PAPER, 4.6, 0.0, L=200, t_end=5.0, boundary="free")
    assert s.stop_reason == "left_convex" and not s.success
    assert "alpha" in s.message or "convex" in s.message
    # only the times it reached are returned: nothing non-finite to plot
    assert s.t[-1] <= s.t_final + 1e-12 and s.snapshots.shape[0] == s.t.size
    assert np.all(np.isfinite(s.snapshots)) and np.all(np.isfinite(s.energy))
