"""Stiff and extreme smooth laws (curvature concentrated near w* or near β) through the discrete
routes: each computes with a passing error check — a superkink converged on two chain lengths
agreeing at the common sites within the sum of their profile bounds (measured convergence in N),
its Floquet spectrum with a converged error bar, a Riemann run that conserves energy — or is
refused with the reason."""

from __future__ import annotations

import numpy as np
import pytest

from fpucore import floquet, simulate, wave
from fpucore.errors import ParameterError
from fpucore.law import SmoothLaw, law_from_expression
from fpucore.qc import superkink_velocity_bounds

EXP = "w + b*w**2 - c*w**3*exp(w/d)"
TANH = "w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3"
STIFF = {
    "steep exponential": (EXP, {"b": 10, "c": 1, "d": 0.3}),
    "narrow tanh transition": (TANH, {"c": 0.1, "k": 1, "m": 0.05, "s": 0.01}),  # 4096 panels
    "w* near beta": (EXP, {"b": 10, "c": 1, "d": 0.02}),  # (β − w*) = 0.22 (β − α)
}


@pytest.mark.parametrize("case", list(STIFF))
def test_stiff_laws_compute_with_passing_error_checks(case):
    text, consts = STIFF[case]
    law = law_from_expression(text, consts)
    assert isinstance(law, SmoothLaw) and max(law.representation_error.relative) <= 1e-12
    lo, hi = superkink_velocity_bounds(law, "lower")
    V = lo + 0.6 * (hi - lo)
    a = wave.solve_superkink(law, V, N=200)
    b = wave.solve_superkink(law, V, N=280)
    assert a.converged and b.converged, (a.message, b.message)
    assert np.all((a.w > law.alpha) & (a.w < law.beta))
    ia = {int(n): k for k, n in enumerate(a.n)}
    common = [(ia[int(n)], k) for k, n in enumerate(b.n) if int(n) in ia and abs(n) <= 60]
    d = max(abs(a.w[i] - b.w[k]) for i, k in common)
    assert d <= a.profile_error + b.profile_error, (d, a.profile_error, b.profile_error)
    s = floquet.spectrum(a, finite_size=False)
    assert s.status == "ok" and s.error <= 1e-9 and s.verdict, s.message
    # Riemann: softening side behind, hardening side ahead, stopped before a wall is reached
    t_end = 0.8 * 100 / float(np.sqrt(law.df(law.w_star)))
    w_left, w_right = law.w_star + 0.5 * (law.beta - law.w_star), 0.5 * law.w_star
    res = simulate.riemann(law, w_left, w_right, L=200, t_end=t_end)
    assert res.status == "ok", res.message
    assert res.energy_drift <= 1e-9


def test_a_transition_too_narrow_to_represent_is_refused_with_the_reason():
    with pytest.raises(ParameterError) as exc:
        law_from_expression(TANH, {"c": 0.1, "k": 1, "m": 0.01, "s": 0.002})
    msg = str(exc.value)
    assert "too steep to represent" in msg and "s=0.002" in msg and "relative error" in msg
