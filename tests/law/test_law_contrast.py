"""Laws whose stiffness contrast f'(w*)/f'(0) leaves f' without digits at the chain's strains are
refused before any discrete work (fpucore/law/scale.py: require_discrete); laws inside the range
compute with finite error bars, checked against the exact scaling w = λu of a unit-scale law."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fpucore as F
from fpucore import qc, simulate, wave
from fpucore.law.scale import CONTRAST_MAX

LOST = [  # each once returned a non-converged wave with a NaN error bar instead of a refusal
    lambda: F.PolynomialLaw((1.0, 1e20, -1e20)),
    lambda: F.PolynomialLaw((1.0, 1e10, -1e-10)),
    lambda: F.CubicLaw(-1.0, 1e10),
]


def _calls(law):
    lo, hi = qc.superkink_velocity_bounds(law)
    V = 0.5 * (lo + hi)
    return [
        (wave.solve_superkink, (law, V), {"N": 32}),
        (wave.solve_solitary, (law, 0.5 * law.w_star, V), {"N": 32}),
        (simulate.riemann, (law, 0.5 * law.w_star, 0.0, 20, 1e-3), {}),
        (simulate.gaussian, (law, 0.0, 0.1 * law.w_star, 20, 1e-3), {}),
    ]


@pytest.mark.parametrize("make", LOST, ids=["1e20", "1e10,-1e-10", "cubic b=1e10"])
def test_laws_without_digits_are_refused_before_discrete_work(make):
    law = make()  # the law and its QC closed forms stay available (exact there)
    assert law.c_max**2 / float(law.df(0.0)) > CONTRAST_MAX
    for fn, args, kw in _calls(law):
        with pytest.raises(F.ParameterError) as ei:
            fn(*args, **kw)
        assert ei.value.name == "law" and "stiffness contrast" in str(ei.value)
        assert "2^52" in str(ei.value)  # the valid range is stated


def test_a_far_scaled_law_inside_the_range_matches_its_unit_scale_twin():
    """w + 1e-10 w² − 1e-30 w³ is u + 1e5 u² − u³ with w = 1e15 u (contrast 3.3e9, W = 6.7e19):
    the same superkink at the same V, every strain × 1e15 (an exact scaling of the equations of
    motion), within the two results' own error bars."""
    far = F.law_from_expression("w + 1e-10*w**2 - 1e-30*w**3")
    unit = F.PolynomialLaw((1.0, 1e5, -1.0))
    lo, hi = qc.superkink_velocity_bounds(unit)
    V = lo + 0.3 * (hi - lo)
    r_far = wave.solve_superkink(far, V, N=64)
    r_unit = wave.solve_superkink(unit, V, N=64)
    assert r_far.converged and r_unit.converged
    for r in (r_far, r_unit):
        assert all(math.isfinite(v) for v in r.errors().values()), r.errors()
    bound = r_far.profile_error + 1e15 * r_unit.profile_error
    assert np.max(np.abs(r_far.w - 1e15 * r_unit.w)) <= bound + 1e-12 * 1e15 * unit.beta
    assert r_far.V == pytest.approx(r_unit.V, rel=1e-14)


SWEEP = settings(max_examples=25, deadline=None, derandomize=True, database=None,
                 suppress_health_check=list(HealthCheck))  # fmt: skip


@SWEEP
@given(st.integers(-30, 30), st.integers(-30, 30))
def test_coefficient_magnitudes_give_a_finite_result_or_a_refusal(p, q):
    """f = w + 10^p w² − 10^q w³ over 60 decades of each coefficient: the law, its superkink
    (N = 32) either is refused with a ParameterError or has finite error bars, and a converged
    wave a residual within its own tolerance scale."""
    try:
        law = F.PolynomialLaw((1.0, 10.0**p, -(10.0**q)))
        lo, hi = qc.superkink_velocity_bounds(law)
        r = wave.solve_superkink(law, lo + 0.3 * (hi - lo), N=64, time_budget_s=30)
    except F.ParameterError as exc:
        assert "\n" not in str(exc)
        return
    assert np.isfinite(r.w).all() and np.isfinite(r.wdot).all()
    if r.converged:
        assert all(math.isfinite(v) for v in r.errors().values()), (p, q, r.errors())
