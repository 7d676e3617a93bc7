"""Phase plane (Fig. pplane) and existence diagram (Fig. SWvelocities_cubic)."""

import math

import numpy as np
import pytest

from fpucore import CubicLaw, ParameterError, qc
from fpucore.qc.diagram import classify, existence_diagram, solitary_family
from fpucore.qc.phase import critical_points, phase_plane

LAW = CubicLaw(-1.0, 10.0)
VSK1 = 2 * math.sqrt(65) / 3


@pytest.mark.parametrize(
    "V,regime", [(VSK1 - 0.001, "tensile"), (VSK1, "superkink"), (VSK1 + 0.005, "compressive")]
)
def test_pplane_regimes_of_the_paper_figure(V, regime):
    pp = phase_plane(LAW, 1.0, V)
    assert pp.regime == regime
    kinds = [c.kind for c in pp.critical_points]
    assert kinds == ["saddle", "center", "saddle"]  # (w+, 0), (w_C, 0), (w_S, 0)
    assert pp.critical_points[0].w == 1.0
    assert pp.orbit_residual < 1e-12
    if regime == "superkink":
        assert [o.name for o in pp.orbits] == ["kink", "antikink"]
        assert pp.critical_points[2].w == pytest.approx(17 / 3, rel=1e-12)


def test_critical_points_are_rayleigh_intersections():
    for V in (4.5, 5.0, 5.45):
        for c in critical_points(LAW, 1.0, V):
            r = float(LAW.f(c.w)) - float(LAW.f(1.0)) - V**2 * (c.w - 1.0)
            assert abs(r) < 1e-11 * V**2 * max(1.0, abs(c.w))
            assert (c.kind == "saddle") == (V**2 > float(LAW.df(c.w)))


@pytest.mark.parametrize("V", [4.3, 5.0, VSK1, 5.3, 5.37])
def test_window_holds_every_critical_point(V):
    """For c+^2 < V^2 < c-^2 the paper counts three critical points (two saddles and a centre);
    the plotted window holds all three, the second saddle w_S too when it lies beyond beta
    (w+ = 1, V = 5: w_S = 6.79 > beta = 6.72).  w_S is checked against the largest real root of
    the Rayleigh condition f(w) - f(w+) = V^2 (w - w+) found by numpy's companion matrix."""
    cp, _, cm = qc.sound_speeds(LAW, 1.0)
    assert cp < V < cm
    pp = phase_plane(LAW, 1.0, V)
    assert [c.kind for c in pp.critical_points] == ["saddle", "center", "saddle"]
    for c in pp.critical_points:
        assert pp.w[0] <= c.w <= pp.w[-1]
    # the roots of the cubic f(w) - f(w+) - V^2 (w - w+) by numpy's companion matrix
    roots = np.roots([-1.0, 10.0, 1.0 - V**2, V**2 - float(LAW.f(1.0))])
    w_S = max(r.real for r in roots if abs(r.imag) < 1e-9)
    assert pp.critical_points[2].w == pytest.approx(w_S, rel=1e-10)


def test_level_set_through_saddle_contains_orbit():
    """The homoclinic orbit lies on the H = 0 level of the gridded first integral: linear
    interpolation of H at the orbit points is bounded by the grid's interpolation error."""
    pp = phase_plane(LAW, 1.0, 5.0, n_grid=401)
    o = pp.orbits[0]
    from scipy.interpolate import RegularGridInterpolator

    H = RegularGridInterpolator((pp.wp, pp.w), pp.H)(np.c_[o.wp, o.w])
    dw, dwp = pp.w[1] - pp.w[0], pp.wp[1] - pp.wp[0]
    curv = np.max(np.abs(np.diff(pp.H, 2, axis=1))) + np.max(np.abs(np.diff(pp.H, 2, axis=0)))
    assert np.max(np.abs(H)) <= curv  # bilinear error <= max second difference
    assert dw > 0 and dwp > 0


def test_existence_diagram_orders_and_meets_at_w_star():
    d = existence_diagram(LAW, n=401)
    away = np.abs(d.w_plus - LAW.w_star) > 1e-9
    assert np.all(d.c_plus[away] < d.V_SK[away]) and np.all(d.V_SK[away] < d.c_minus[away])
    i = np.argmin(np.abs(d.w_plus - LAW.w_star))  # odd n: a grid point sits on w*
    assert d.c_plus[i] == pytest.approx(d.c_minus[i], rel=1e-14)
    assert d.alpha < d.w_plus.min() and d.w_plus.max() < d.beta
    # the edges of the admissible w+ reproduce the superkink velocity bounds
    lo, hi = qc.superkink_velocity_bounds(LAW)
    assert lo < d.V_SK.min() and d.V_SK.max() <= hi
    for edge in (LAW.alpha + 1e-12, LAW.beta - 1e-12):
        assert qc.sound_speeds(LAW, edge)[1] == pytest.approx(lo, rel=1e-10)


def test_classify_regions():
    assert classify(LAW, 1.0, 5.0) == "tensile"
    assert classify(LAW, 1.0, 5.45) == "compressive"
    assert classify(LAW, 6.0, 5.0) == "compressive"
    assert classify(LAW, 6.0, -5.3) == "tensile"  # mirror V -> -V
    assert classify(LAW, 1.0, VSK1) == "superkink"
    with pytest.raises(ParameterError):
        classify(LAW, 1.0, 3.0)


def test_solitary_family_reaches_the_superkink_amplitude():
    fam = solitary_family(LAW, 1.0, n=200)
    assert fam.kind_below == "tensile" and fam.kind_above == "compressive"
    assert fam.amp_below[-1] == pytest.approx(fam.sk_amplitude, rel=2e-2)
    assert fam.amp_above[0] == pytest.approx(fam.sk_amplitude, rel=2e-2)
    assert np.all(np.diff(fam.amp_below) > 0)  # amplitude grows toward V_SK (Fig. SWamp...)
    assert np.all(np.diff(fam.amp_above) < 0)


def test_vectorised_family_matches_single_waves():
    fam = solitary_family(LAW, 6.0, n=40)
    for Vs, amps, ens in ((fam.V_below, fam.amp_below, fam.energy_below),
                          (fam.V_above, fam.amp_above, fam.energy_above)):  # fmt: skip
        for V, amp, en in zip(Vs[::7], amps[::7], ens[::7]):
            sw = qc.solitary(LAW, 6.0, float(V))
            assert amp == pytest.approx(sw.amplitude, rel=1e-13)
            assert en == pytest.approx(sw.energy, rel=1e-12)
    assert fam.max_energy_error < 1e-9 * np.max(np.abs(fam.energy_above))


@pytest.mark.parametrize("w0,wp0", [(2.0, 0.0), (2.5, 0.1), (1.6, -0.3), (3.0, 0.5)])
def test_orbit_through_a_point_matches_a_numerical_integration(w0, wp0):
    """The level-set orbit through (w0, w0') against an independent integration of eq.
    TW_QC_gen2, V^2/12 w'' = -(f(w) - f(w+) - V^2 (w - w+)), by scipy's DOP853: the integrated
    trajectory stays on the level (H constant) and reaches exactly the turning points the
    closed form gives (inside the centre's loop: a closed orbit with two turning points;
    outside it: an open orbit that turns once and leaves the window)."""
    from scipy.integrate import solve_ivp

    from fpucore.qc.phase import orbit_through

    V, wp_ = 5.0, 1.0
    pp = phase_plane(LAW, wp_, V)
    window = (pp.w[0], pp.w[-1])
    o = orbit_through(LAW, wp_, V, w0, wp0, window)
    assert o.residual < 1e-13
    fplus = float(LAW.f(wp_))

    def rhs(_, y):
        w, p = y
        return [p, -12.0 / V**2 * (float(LAW.f(w)) - fplus - V**2 * (w - wp_))]

    def leaves(_, y):  # stop where the orbit leaves the window
        return min(y[0] - window[0], window[1] - y[0])

    leaves.terminal = True
    sol = solve_ivp(rhs, (0.0, 40.0), [w0, wp0], method="DOP853", rtol=1e-12, atol=1e-12,
                    events=leaves, dense_output=True)  # fmt: skip
    t = np.linspace(0.0, sol.t[-1], 20001)
    w, p = sol.sol(t)
    if o.closed:
        assert len(o.turning_points) == 2
        assert w.min() == pytest.approx(o.turning_points[0], abs=1e-8)
        assert w.max() == pytest.approx(o.turning_points[1], abs=1e-8)
    else:
        assert len(o.turning_points) == 1
        # the integration (forward or backward in ξ) reaches the one turning point
        back = solve_ivp(rhs, (0.0, -40.0), [w0, wp0], method="DOP853", rtol=1e-12,
                         atol=1e-12, events=leaves, dense_output=True)  # fmt: skip
        wb, pb = back.sol(np.linspace(0.0, back.t[-1], 20001))
        ext = [w.max(), wb.max()] if o.turning_points[0] > w0 - 1e-12 else [w.min(), wb.min()]
        assert min(abs(e - o.turning_points[0]) for e in ext) < 1e-8
        w, p = np.concatenate([w, wb]), np.concatenate([p, pb])
    # the closed form's upper branch lies on the integrated trajectory where both are
    up = p > 0
    ws, ps = w[up][np.argsort(w[up])], p[up][np.argsort(w[up])]
    k = np.isfinite(o.w) & (o.wp > 0.05) & (o.w > ws[0]) & (o.w < ws[-1])
    assert k.sum() > 100
    assert np.max(np.abs(np.interp(o.w[k], ws, ps) - o.wp[k])) < 1e-5


def test_orbit_through_refuses_a_point_outside_its_window():
    from fpucore.qc.phase import orbit_through

    with pytest.raises(ParameterError, match="w0"):
        orbit_through(LAW, 1.0, 5.0, 9.0, 0.0, (0.0, 7.0))
    with pytest.raises(ParameterError, match="w_window"):
        orbit_through(LAW, 1.0, 5.0, 1.0, 0.0, (7.0, 0.0))
