"""Integrator and exact tangent of the one-period map (fpucore.wave.period_map, tableaux.rk).

References: tableau identities, scipy's adaptive DOP853 on the same ODE, a measured convergence
slope against a fine-step reference, and central finite differences of the map itself.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.tableaux.rk import DOP853, RK4, TABLEAUX
from fpucore.wave import period_map as pm

LAW = CubicLaw(-1.0, 10.0)
V = 5.2
T = 1.0 / V
WL, WR = 17 / 3, 1.0  # superkink-like boundary strains


def _kink_state(N):
    n = np.arange(N) - N // 2
    p = 0.8
    w = 10 / 3 - (7 / 3) * np.tanh(p * n)
    wd = V * (7 / 3) * p / np.cosh(p * n) ** 2  # ẇ = −V w′
    return w, wd


def _rhs(N, wl, wr, periodic):
    def f(t, y):
        fw = LAW.f(y[:N])
        ext = np.concatenate(
            [[fw[-1] if periodic else LAW.f(wl)], fw, [fw[0] if periodic else LAW.f(wr)]]
        )
        return np.concatenate([y[N:], ext[2:] - 2 * ext[1:-1] + ext[:-2]])

    return f


@pytest.mark.parametrize("tab", list(TABLEAUX.values()), ids=list(TABLEAUX))
def test_tableau_invariants(tab):
    s = tab.stages
    assert tab.A.shape == (s, s) and tab.B.shape == (s,) and tab.C.shape == (s,)
    assert abs(tab.B.sum() - 1.0) < 1e-14
    assert np.max(np.abs(tab.A.sum(axis=1) - tab.C)) < 1e-14
    assert np.all(np.triu(tab.A) == 0.0)  # explicit
    # order conditions up to 3 (bushy trees) as an independent check of the data
    assert abs(tab.B @ tab.C - 1 / 2) < 1e-14
    assert abs(tab.B @ tab.C**2 - 1 / 3) < 1e-14
    assert abs(tab.B @ (tab.A @ tab.C) - 1 / 6) < 1e-14


def test_dop853_order_conditions_high():
    # a few order-8 conditions: Σ b c^k = 1/(k+1) for k ≤ 7
    for k in range(8):
        assert abs(DOP853.B @ DOP853.C**k - 1 / (k + 1)) < 1e-13


@pytest.mark.parametrize("periodic", [False, True])
def test_matches_solve_ivp(periodic):
    N = 40
    w0, wd0 = _kink_state(N)
    r = pm.integrate(LAW, w0, wd0, T, 12, WL, WR, periodic=periodic)
    ref = solve_ivp(
        _rhs(N, WL, WR, periodic),
        (0, T),
        np.concatenate([w0, wd0]),
        method="DOP853",
        rtol=1e-13,
        atol=1e-13,
    )
    assert np.max(np.abs(ref.y[:, -1] - np.concatenate([r.w, r.wd]))) < 1e-11


@pytest.mark.parametrize("tab,ms", [(DOP853, [2, 3, 4, 6]), (RK4, [4, 8, 16, 32])])
def test_measured_order_on_period_map(tab, ms):
    N = 40
    w0, wd0 = _kink_state(N)
    ref = pm.integrate(LAW, w0, wd0, T, 400, WL, WR, tableau=tab)
    errs = []
    for m in ms:
        r = pm.integrate(LAW, w0, wd0, T, m, WL, WR, tableau=tab)
        errs.append(max(np.abs(r.w - ref.w).max(), np.abs(r.wd - ref.wd).max()))
    slope = -np.polyfit(np.log(ms), np.log(errs), 1)[0]
    assert abs(slope - tab.order) < 0.6, (slope, errs)


def test_step_doubling_tracks_true_error():
    N = 40
    w0, wd0 = _kink_state(N)
    ref = pm.integrate(LAW, w0, wd0, T, 400, WL, WR)
    for m in (3, 5, 8):
        r = pm.integrate(LAW, w0, wd0, T, m, WL, WR)
        true = max(np.abs(r.w - ref.w).max(), np.abs(r.wd - ref.wd).max())
        est = pm.step_doubling_error(LAW, w0, wd0, T, m, WL, WR)
        assert 0.9 * true < est < 1.1 * true + 1e-14  # 2^-8 of the error is left in Φ_2m


def _fd_jacobian(x0, periodic, eps=1e-6):
    n2 = x0.size
    J = np.empty((n2, n2))
    for c in range(n2):
        e = np.zeros(n2)
        e[c] = eps
        J[:, c] = (
            pm.period_map(LAW, x0 + e, V, 10, WL, WR, periodic)
            - pm.period_map(LAW, x0 - e, V, 10, WL, WR, periodic)
        ) / (2 * eps)
    return J


@pytest.mark.parametrize("periodic", [False, True])
def test_tangent_matches_finite_differences(periodic):
    N = 30
    w0, wd0 = _kink_state(N)
    x0 = np.concatenate([w0, wd0])
    r = pm.integrate(LAW, w0, wd0, T, 10, WL, WR, periodic=periodic, store_df=True)
    J = pm.fundamental_matrix(r, periodic=periodic)
    # central differences: truncation error ~ eps² |Φ'''| (round-off ~ 1e-14/eps is smaller here)
    e4 = np.max(np.abs(J - _fd_jacobian(x0, periodic, eps=1e-4)))
    e3 = np.max(np.abs(J - _fd_jacobian(x0, periodic, eps=1e-3)))
    assert e4 < 1e-7
    # the difference shrinks like eps²: it is the FD truncation, not an error of J
    assert 30 < e3 / e4 < 300, (e3, e4)


def test_window_truncation_is_below_roundoff():
    N = 120
    w0, wd0 = _kink_state(N)
    r = pm.integrate(LAW, w0, wd0, T, 10, WL, WR, store_df=True)
    K = pm.spread_radius(r, level=1e-17)
    assert 3 <= K <= 40
    cols = np.arange(2 * N)
    out_w, edge = pm.tangent_columns(r, cols, K)
    out_f, _ = pm.tangent_columns(r, cols, N)
    Jw = pm.scatter_dense(out_w, N, K, False)
    Jf = pm.scatter_dense(out_f, N, N, False)
    assert np.max(np.abs(Jw - Jf)) < 1e-15
    assert edge.max() < 1e-16


def test_bad_input():
    w0, wd0 = _kink_state(10)
    with pytest.raises(ParameterError, match="T"):
        pm.integrate(LAW, w0, wd0, -1.0, 4)
    with pytest.raises(ParameterError, match="m"):
        pm.integrate(LAW, w0, wd0, T, 0)
    bad = w0.copy()
    bad[3] = np.nan
    with pytest.raises(ParameterError, match="finite"):
        pm.integrate(LAW, bad, wd0, T, 4)
    r = pm.integrate(LAW, w0, wd0, T, 4)
    with pytest.raises(ParameterError, match="store_df"):
        pm.tangent_columns(r, [0], 3)
