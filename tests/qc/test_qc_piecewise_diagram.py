"""The existence diagram of a piecewise-linear law is its closed forms at every w₊ (the general
quadrature route drew V_SK as a staircase, up to 4 % off: 1.0604 for 1.0314 at w₊ = −10.29)."""

import math

import numpy as np

import fpucore as F
from fpucore import qc
from fpucore.qc.diagram import existence_diagram

LAW = F.TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2)


def v_sk_closed(w_plus: float, w1=0.5, w2=1.5, E1=1.0, E2=4.0, E3=0.2) -> float:
    """V_SK² = (f(w₋) − f(w₊))/(w₋ − w₊) with w₋ from the equal-area condition, evaluated here
    for w₊ in the first soft regime and w₋ in the last: the chord's areas over [w₊, w₋]."""
    f1, f2 = E1 * w1, E1 * w1 + E2 * (w2 - w1)

    def f(w):
        return E1 * w if w <= w1 else (f1 + E2 * (w - w1) if w <= w2 else f2 + E3 * (w - w2))

    def area(a, b):  # ∫ f over [a, b] (exact: trapezoids between the corners)
        pts = [a, *[c for c in (w1, w2) if a < c < b], b]
        return sum((f(x) + f(y)) * (y - x) / 2 for x, y in zip(pts, pts[1:]))

    def g(wm):  # equal areas: ∫ f = chord area
        return area(w_plus, wm) - (f(w_plus) + f(wm)) * (wm - w_plus) / 2

    lo, hi = w2 + 1e-12, w2 + 1e6
    for _ in range(300):  # bisection: g changes sign once on the last regime
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(lo) * g(mid) > 0 else (lo, mid)
    wm = 0.5 * (lo + hi)
    return math.sqrt((f(wm) - f(w_plus)) / (wm - w_plus))


def test_the_diagram_is_the_closed_form_and_has_no_staircase():
    d = existence_diagram(LAW, n=200)
    assert np.all(np.isfinite(d.V_SK))
    for w, v in zip(d.w_plus, d.V_SK):
        assert abs(v - qc.sound_speeds(LAW, float(w))[1]) <= 1e-14 * v
    lower = d.w_plus < 0.5  # the first soft regime's branch: the reference above applies
    for w, v in zip(d.w_plus[lower][::10], d.V_SK[lower][::10]):
        assert abs(v - v_sk_closed(float(w))) <= 1e-9 * v, (w, v, v_sk_closed(float(w)))
    # no plateaus: V_SK changes between neighbouring points of the lower branch
    assert np.all(np.abs(np.diff(d.V_SK[lower])) > 0)
