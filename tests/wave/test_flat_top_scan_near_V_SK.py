"""Solitary waves 1e-16 … 1e-12 · V_SK from V_SK, on both sides (paper §4–5: flat tops, plateau
route): every point converges with its error check passed, or says in the user's terms why not.

At |V − V_SK| of a few ulps of V the plateau length is tied to V only through the last bits of V
and V_SK; the mass continuation's secant of ln|V − V_SK| against the plateau mass then leaves
its exact tangent (measured, w₊ = 1: they agree to 2 % down to 2e-13·V_SK, then 35 %, then
opposite signs).  A secant of the wrong sign asked for a front move of −1.07 sites, and the
front translation integrated over a negative time: ``T=-0.01317 is out of range: valid T > 0``
(issue: atlas point 1e-15 below V_SK, w₊ = 1), an argument the user never gave.
The wider scan (1e-16 … 1e-9, N = 64, 128, 250, 500) is in the notes; here a few points per
chain that cover the three outcomes (converged, plateau undetermined, V = V_SK refused).
"""

from __future__ import annotations

import math
import re

import pytest

from fpucore import qc, wave
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.wave import plateau

LAW = CubicLaw(-1.0, 10.0)
# (w₊, N, relative distance (V − V_SK)/V_SK); the first: the atlas point
POINTS = [
    (1.0, 64, -1e-15),
    (1.0, 64, +1e-15),
    (1.0, 64, -1e-12),
    (1.0, 64, +1e-16),  # rounds to V_SK itself: no wave there
    (6.0, 250, -1e-15),
    (6.0, 250, -1e-14),
    (6.0, 250, +1e-12),
]
INTERNAL = re.compile(r"\b(T|delta|ds|dM|s|M|x0|w0/wd0|m|K)=")  # arguments the user never gives


@pytest.mark.slow
@pytest.mark.parametrize(
    "w_plus,N,rel", POINTS, ids=[f"w+={p[0]:g}-N={p[1]}-{p[2]:+g}" for p in POINTS]
)
def test_each_point_near_V_SK_converges_checked_or_says_why_not(w_plus, N, rel):
    v_sk = qc.sound_speeds(LAW, w_plus)[1]
    V = v_sk * (1.0 + rel)
    if V == v_sk:
        with pytest.raises(ParameterError, match=r"V=.* out of range.*V = V_SK is the superkink"):
            wave.solve_solitary(LAW, w_plus, V, N=N)
        return
    r = wave.solve_solitary(LAW, w_plus, V, N=N)  # no exception: an answer or a reason
    assert not INTERNAL.search(r.message), r.message
    if r.converged:  # the error check passed: fronts fixed to < 1 site, finite bounds
        assert r.front_uncertainty <= plateau.FRONT_MAX, r.message
        assert math.isfinite(r.profile_error) and r.profile_error < 0.1 * r.amplitude
    else:  # the reason, in the user's terms, with where a wave can be computed
        assert "plateau length" in r.message and "V_SK" in r.message, r.message
        m = re.search(r"nearest solvable V is about ([0-9.e+-]+)", r.message)
        if m:  # farther from V_SK, on the same side
            V_ok = float(m.group(1))
            assert (V_ok - v_sk) * (V - v_sk) > 0 and abs(V_ok - v_sk) > abs(V - v_sk)
    if abs(rel) >= 1e-12:  # a resolved flat top: the plateau route reaches it
        assert r.converged, r.message
