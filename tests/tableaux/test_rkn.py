"""Runge–Kutta–Nyström pairs (fpucore.tableaux.rkn, fpucore.simulate.rkn): the tableaux against the
RKN order conditions in exact arithmetic, the measured convergence order on the chain against an
independent integrator (scipy DOP853), and the state conversions."""

from fractions import Fraction

import numpy as np
import pytest
import rkn_order
from scipy.integrate import solve_ivp

from fpucore.law import CubicLaw
from fpucore.simulate import kernels as ck
from fpucore.simulate import rkn as crk
from fpucore.simulate.layout import Chain, Control, Observer, RknPair, Work
from fpucore.tableaux.rkn import DPRKN8, DPRKN12, RKN

LAW = CubicLaw(-1.0, 10.0)


@pytest.mark.parametrize("tab", list(RKN.values()), ids=list(RKN))
def test_tableau_invariants(tab):
    e = tab.exact
    s = tab.stages
    for i in range(s):
        assert all(e["A"][i][j] == 0 for j in range(i, s))  # explicit
        assert abs(sum(e["A"][i]) - e["c"][i] ** 2 / 2) < Fraction(1, 10**26)  # Σ_j a_ij = c_i²/2
    for b, target in (("b", Fraction(1, 2)), ("bp", 1), ("bh", Fraction(1, 2)), ("bph", 1)):
        assert abs(sum(e[b]) - target) < Fraction(1, 10**16)
    assert tab.fsal == (tab is DPRKN8)  # RKN8(6)9FM is FSAL, RKN12(10)17M is not
    assert np.array_equal(tab.e, tab.b - tab.bh) and np.array_equal(tab.ep, tab.bp - tab.bph)


def test_order_condition_checker_on_nystrom_rk4():
    """The classical 4th-order Nyström method (from RK4): order 4 exactly, not 5; and breaking one
    coefficient of it is detected."""
    F = Fraction
    c = [F(0), F(1, 2), F(1, 2), F(1)]
    A = [[0] * 4, [F(1, 8), 0, 0, 0], [F(1, 8), 0, 0, 0], [0, 0, F(1, 2), 0]]
    A = [[F(x) for x in r] for r in A]
    b = [F(1, 6), F(1, 6), F(1, 6), F(0)]
    bp = [F(1, 6), F(1, 3), F(1, 3), F(1, 6)]
    rv, rq, n = rkn_order.residuals(c, A, b, bp, 4)
    assert rv == 0 and rq == 0 and n == 7  # 1 + 1 + 2 + 3 trees
    assert max(rkn_order.residuals(c, A, b, bp, 5)[:2]) > 1e-3
    bad = [r[:] for r in A]
    bad[3][2] = F(1, 3)
    assert max(rkn_order.residuals(c, bad, b, bp, 4)[:2]) > 1e-3


@pytest.mark.parametrize("tab", [DPRKN8, DPRKN12], ids=["rkn8", "rkn12"])
def test_order_conditions_hold_exactly_to_the_stated_order(tab):
    """Every velocity condition up to the order p and position condition up to p − 1 holds (to the
    double-precision rounding of DPRKN12's weights); the pairs' embedded formulas to their own
    order; and each formula fails some condition of the next order (so p is the order, not a
    lower bound)."""
    e = tab.exact
    tol = Fraction(0) if tab is DPRKN8 else Fraction(1, 10**15)
    for (b, bp), p in (((e["b"], e["bp"]), tab.order), ((e["bh"], e["bph"]), tab.err_order)):
        rv, rq, _ = rkn_order.residuals(e["c"], e["A"], b, bp, p)
        assert rv <= tol and rq <= tol
        rv, rq, _ = rkn_order.residuals(e["c"], e["A"], b, bp, p + 1)
        assert max(rv, rq) > 1e-9


def _fixed_step(tab, w0, T, n_steps, L):
    """n_steps equal steps of the pair on the chain (held end particles), via rkn_chunk with a stop
    after every step (the proposed step is a little longer, so every step lands on it) and a
    tolerance so loose that no step is rejected."""
    s = tab.stages
    q = np.zeros(L + 1)
    q[:L] = w0
    chain = Chain(L, LAW.law_id, LAW.params, ck.BC_FIXED_PARTICLES, 0.0, 0.0)
    work = Work(np.zeros((s + 3, L + 1)), np.zeros((7, L + 1)), np.zeros(L + 2), np.zeros(6),
                np.zeros(2))  # fmt: skip
    crk.accel(q, L, LAW.law_id, LAW.params, chain.bc, 0.0, 0.0, work.g, work.K[0])
    pair = RknPair(tab.c, tab.A, tab.b, tab.bp, tab.e, tab.ep, tab.fsal, -1.0 / (tab.err_order + 1))
    ctl = Control(1e6, 1e6, -1e9, 1e9)
    e2, e1, z3 = np.zeros((L, 1)), np.zeros((L, 1), np.int8), np.zeros((3, L))
    en = np.zeros(L, np.int64)
    obs = Observer(np.inf, np.nan, z3, np.zeros(L), np.zeros(L, np.int8), e2, e2, e1, en, e2, e1,
                   en, np.zeros(0, np.int64), np.zeros(0), np.zeros((0, 0)),
                   np.zeros(1, np.int64), np.zeros(8))  # fmt: skip
    stats = work.stats
    h = T / n_steps
    t = 0.0
    for k in range(1, n_steps + 1):
        t, _, status = crk.rkn_chunk(q, t, k * h, 1.001 * h, 10**9, pair, ctl, chain, work, obs)
        assert status == ck.ST_OK
    assert stats[0] == n_steps and stats[1] == 0
    return q[:L].copy()


@pytest.mark.parametrize(
    "tab, steps, slope",
    [(DPRKN8, (6, 8, 11, 16), (7.0, 9.5)), (DPRKN12, (4, 5, 6, 8), (10.5, 14.0))],
    ids=["rkn8", "rkn12"],
)
def test_measured_convergence_order_on_the_chain(tab, steps, slope):
    """Fixed steps on a nonlinear chain (smooth strain bump, amplitude 2: f′ ranges over 1…29), the
    error at T = 2 against scipy's DOP853 at rtol 1e-13 on the first-order form; the fitted log–log
    slope of error against h is the order."""
    L, T = 12, 2.0
    n = np.arange(L)
    w0 = 2.0 * np.exp(-(((n - L / 2) / 2.0) ** 2))

    def rhs(t, y):  # (w, v_0..v_L), end particles held
        w, v = y[:L], y[L:]
        g = np.concatenate(([0.0], LAW.f(w), [0.0]))
        dv = np.diff(g)
        dv[0] = dv[-1] = 0.0
        return np.concatenate((np.diff(v), dv))

    y0 = np.concatenate((w0, np.zeros(L + 1)))
    ref = solve_ivp(rhs, (0, T), y0, method="DOP853", rtol=1e-13, atol=1e-13).y[:L, -1]
    hs, errs = [], []
    for m in steps:
        err = np.max(np.abs(_fixed_step(tab, w0, T, m, L) - ref))
        hs.append(T / m)
        errs.append(err)
    assert min(errs) > 1e-11  # still above the reference's own error
    k = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert slope[0] < k < slope[1], (k, errs)


def test_state_conversion_round_trip():
    rng = np.random.default_rng(1)
    L = 9
    y = rng.standard_normal(2 * L + 2)
    q, qd, back = np.zeros(L + 1), np.zeros(L + 1), np.zeros(2 * L + 2)
    crk.y_to_rkn(y, L, q, qd)
    crk.rkn_to_y(q, qd, L, back)
    assert np.allclose(back, y, rtol=0, atol=1e-14)


@pytest.mark.parametrize("bc", [ck.BC_FIXED_PARTICLES, ck.BC_LOAD])
def test_accel_is_the_first_order_rhs_differenced(bc):
    """F(q) of the second-order form equals (d/dt of ẇ_n = v_n − v_{n−1}, d/dt v_0) computed from
    the first-order right-hand side."""
    rng = np.random.default_rng(2)
    L = 11
    y = np.zeros(2 * L + 2)
    y[:L] = rng.uniform(0, 4, L)
    fL, fR = 0.3, -0.7
    out = np.zeros(2 * L + 2)
    ck.rhs(y, L, LAW.law_id, LAW.params, bc, fL, fR, np.zeros(L + 2), out)
    q, qd = np.zeros(L + 1), np.zeros(L + 1)
    crk.y_to_rkn(y, L, q, qd)
    F = np.zeros(L + 1)
    crk.accel(q, L, LAW.law_id, LAW.params, bc, fL, fR, np.zeros(L + 2), F)
    vdot = out[L : 2 * L + 1]
    assert np.allclose(F[:L], np.diff(vdot), atol=1e-13)
    assert F[L] == pytest.approx(vdot[0], abs=1e-14)
