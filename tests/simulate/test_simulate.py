"""Chain simulator: independent-integrator agreement, conserved energies per end condition,
symplectic behaviour, end conditions, interpolated outputs and refusals (small, fast runs)."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fpucore import simulate
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def numpy_rhs(law, L, boundary, fL=0.0, fR=0.0):
    """Independent vectorised RHS of eq. FPUsystem in the same state layout (w, v, u_0)."""

    def f(t, y):
        w, v = y[:L], y[L : 2 * L + 1]
        g = np.concatenate(([fL], law.f(w), [fR]))
        dv = np.diff(g)
        if boundary == "fixed_particles":
            dv[0] = dv[-1] = 0.0
        return np.concatenate((np.diff(v), dv, [v[0]]))

    return f


@pytest.mark.parametrize("method", ["rkn12", "rkn8", "dop853"])
@pytest.mark.parametrize("boundary", ["fixed_particles", "fixed_strain", "free"])
def test_agrees_with_scipy_dop853(boundary, method):
    L, T = 120, 12.0
    # released (free) ends overshoot below zero strain: gentler data there, and the bounded guard
    wl, wr = (0.5, 0.2) if boundary == "free" else (3.0, 0.5)
    kw = dict(rtol=1e-12, boundary=boundary, track=False, method=method, guard="bounded")
    s = simulate.riemann(LAW, wl, wr, L, T, **kw)
    assert s.success, s.message
    fL, fR = (float(LAW.f(wl)), float(LAW.f(wr))) if boundary == "fixed_strain" else (0, 0)
    y0 = np.zeros(2 * L + 2)
    y0[: L // 2], y0[L // 2 : L] = wl, wr
    ref = solve_ivp(
        numpy_rhs(LAW, L, boundary, fL, fR), (0, T), y0, method="DOP853", rtol=1e-12, atol=1e-12
    )
    # waves reach the ends by t = 12, so the end condition matters here
    assert np.max(np.abs(s.final_w - ref.y[:L, -1])) < 1e-8
    # the RKN pairs integrate (w, u_0) and (ẇ, v_0); the velocities are rebuilt from them
    ev = simulate.riemann(LAW, wl, wr, L, T, n_snapshots=2, **kw)
    assert ev.energy_drift < 1e-11


def test_dopri5_agrees_with_dop853():
    a = simulate.riemann(LAW, 4.6, 0.0, 200, 10.0, rtol=1e-11, track=False)
    b = simulate.riemann(LAW, 4.6, 0.0, 200, 10.0, rtol=1e-11, method="dopri5", track=False)
    assert a.success and b.success and b.n_steps > 3 * a.n_steps
    assert np.max(np.abs(a.final_w - b.final_w)) < 1e-7


@pytest.mark.parametrize("method", ["rkn12", "rkn8", "dop853", "dopri5"])
def test_energy_drift_follows_tolerance(method):
    # two snapshots only: with 200 the snapshot spacing, not the tolerance, caps the step
    d = [
        simulate.riemann(LAW, 4.6, 0, 400, 20.0, rtol=r, track=False, method=method, n_snapshots=2)
        for r in (1e-6, 1e-10)
    ]
    assert d[1].n_steps > d[0].n_steps
    assert d[1].energy_drift < 1e-2 * d[0].energy_drift
    assert d[1].energy_drift < 100 * 1e-10
    assert d[1].error_estimate < 1e-2 * d[0].error_estimate


def test_dead_load_energy_conserved_after_waves_hit_the_ends():
    """fixed_strain with unequal end loads f(0.5) ≠ f(0.8): the loads do work once the waves reach
    the end particles (t ≈ 10 here); H including the load potential (u_0 term) stays conserved."""
    s = simulate.riemann(LAW, 0.5, 0.8, 100, 30.0, boundary="fixed_strain", rtol=1e-12)
    assert s.success, s.message
    assert s.energy_drift < 1e-10
    assert "u_0" in s.energy_name


def test_symplectic_energy_bounded_and_fourth_order():
    kw = dict(n_snapshots=1001, track=False, estimate_error=False)
    runs = {
        dt: simulate.gaussian(LAW, 1.0, 2.0, 256, 3000.0, method="symplectic", dt=dt, **kw)
        for dt in (0.05, 0.025)
    }
    for s in runs.values():
        assert s.success
        E = np.abs(s.energy - s.energy[0])
        # no secular growth: the error over the whole run is of the size reached in its first tenth
        assert E.max() < 4 * E[:101].max()
    ratio = runs[0.05].energy_drift / runs[0.025].energy_drift
    assert 8 < ratio < 32  # 4th order: 2^4 = 16
    # a loose adaptive run drifts secularly on the same problem
    d = simulate.gaussian(LAW, 1.0, 2.0, 256, 3000.0, rtol=1e-6, **kw)
    Ed = np.abs(d.energy - d.energy[0])
    assert Ed.max() > 4 * Ed[:101].max()


def test_symplectic_step_doubling_estimate():
    s = simulate.riemann(LAW, 2.0, 0.0, 200, 10.0, method="symplectic", dt=0.01)
    ref = simulate.riemann(LAW, 2.0, 0.0, 200, 10.0, rtol=1e-12, track=False)
    err = np.max(np.abs(s.snapshots - ref.snapshots))
    assert np.isfinite(s.error_estimate)
    assert err < 3 * s.error_estimate + 1e-12
    assert s.error_estimate < 30 * err


def test_free_ends_leave_convex_interval_cleanly():
    s = simulate.riemann(LAW, 4.6, 0.0, 3600, 300.0, boundary="free")
    assert s.stop_reason == "left_convex" and s.t_final < 1.0
    assert "w_1 " in s.message and "convex interval" in s.message
    assert np.all(np.isfinite(s.final_w)) and np.all(np.isfinite(s.snapshots[0]))
    b = simulate.riemann(LAW, 4.6, 0.0, 3600, 300.0, boundary="free", guard="bounded")
    assert b.stop_reason == "left_convex" and "zeros of f" in b.message


def test_fixed_particles_and_fixed_strain_agree_before_waves_reach_ends():
    a = simulate.riemann(LAW, 4.6, 0.0, 800, 40.0)
    b = simulate.riemann(LAW, 4.6, 0.0, 800, 40.0, boundary="fixed_strain")
    assert np.max(np.abs(a.final_w - b.final_w)) < 1e-12
    assert [w.velocity for w in a.waves] == pytest.approx([w.velocity for w in b.waves], abs=1e-9)


def test_restoring_interval_closed_form():
    lo, hi = simulate.restoring_interval(LAW)
    assert lo == pytest.approx(5 - math.sqrt(26), abs=1e-12)
    assert hi == pytest.approx(5 + math.sqrt(26), abs=1e-12)


def test_probes_match_snapshots_and_decimation():
    s = simulate.riemann(
        LAW, 4.6, 0.0, 400, 20.0, n_snapshots=201, max_sites_out=37, probes=(150, 201, 260)
    )
    assert s.sites.size == 37 and s.sites[0] == 1 and s.sites[-1] == 400
    assert np.array_equal(s.snapshots[-1], s.final_w[s.sites - 1])
    # the probe grid (4001 points) contains the snapshot times; probes are Hermite-interpolated
    idx = np.rint(s.t / (s.probe_t[1] - s.probe_t[0])).astype(int)
    assert np.allclose(s.probe_t[idx], s.t, atol=1e-12)
    ref = simulate.riemann(LAW, 4.6, 0.0, 400, 20.0, n_snapshots=201, track=False)
    for i, site in enumerate(s.probe_sites):
        assert np.max(np.abs(s.probe_series[i, idx] - ref.snapshots[:, site - 1])) < 1e-7


def test_progress_callback_reaches_one():
    seen = []
    simulate.riemann(LAW, 1.0, 0.0, 64, 2.0, progress=seen.append, track=False)
    assert seen[-1] == pytest.approx(1.0) and all(np.diff(seen) >= 0)


def test_budget_is_reported():
    s = simulate.riemann(LAW, 4.6, 0.0, 200, 50.0, max_steps=50, track=False)
    assert s.stop_reason == "budget" and "max_steps" in s.message and not s.success


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(L=401), "L"),
        (dict(L=8), "L"),
        (dict(L=float("inf")), "L"),
        (dict(L=float("nan")), "L"),
        (dict(w_left=7.0), "w_left"),
        (dict(boundary="periodic"), "boundary"),
        (dict(method="euler"), "method"),
        (dict(t_end=-1.0), "t_end"),
        (dict(rtol=1.0), "rtol"),
        (dict(method="symplectic", dt=1.0), "dt"),
        (dict(guard="none"), "guard"),
        (dict(probes=(0,)), "probes"),
    ],
)
def test_bad_input(kwargs, name):
    args = dict(w_left=4.6, w_right=0.0, L=400, t_end=1.0)
    args.update(kwargs)
    with pytest.raises(ParameterError) as e:
        simulate.riemann(LAW, **args)
    assert e.value.name == name


def test_gaussian_bad_amplitude():
    with pytest.raises(ParameterError) as e:
        simulate.gaussian(LAW, 1.0, 20.0, 400, 1.0, guard="bounded")
    assert e.value.name == "A"


def test_embedded_tableaux_fit_the_fused_error_pass():
    """chain_kernels fuses the error estimate into one pass over at most eight stage rows."""
    from fpucore.tableaux.embedded import EMBEDDED

    for tab in EMBEDDED.values():
        assert np.count_nonzero((tab.E5 != 0) | (tab.E3 != 0)) <= 8
        assert tab.E5.size == tab.stages + 1
        assert np.allclose(tab.A.sum(axis=1), tab.C) and tab.B.sum() == pytest.approx(1.0)
