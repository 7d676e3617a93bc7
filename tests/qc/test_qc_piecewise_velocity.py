"""Superkinks of a PL law by velocity: qc.superkink_from_V inverts the exact V_SK(w₊) (the
chord to the closed-form equal-area partner), and its velocity bounds are the limits of V_SK at
the ends of the w₊ range, written out by hand for the trilinear law."""

import math

import numpy as np
import pytest

from fpucore import ParameterError, qc
from fpucore.law import PiecewiseLinearLaw, TrilinearLaw

LAWS = [
    TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2),  # E1 > E3: lower range infinite, upper finite
    TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2),  # degenerate E1 = 0
    TrilinearLaw(0.5, 1.5, 0.2, 4.0, 1.0),  # E3 > E1
    PiecewiseLinearLaw([0.5, 1.5, 3.0], [1.0, 4.0, 0.5, 0.1]),
]


def trilinear_bounds(E1, E2, E3, branch):
    """Next to the hard regime V → √E2; at the far end the chord runs to the outer regime of
    larger modulus (the partner escapes to infinity, or w₊ does)."""
    return math.sqrt(max(E1, E3)), math.sqrt(E2)


@pytest.mark.parametrize("branch", ["lower", "upper"])
@pytest.mark.parametrize("law", LAWS[:3])
def test_velocity_bounds_of_the_trilinear_law(law, branch):
    E1, E2, E3 = law.slopes
    assert qc.superkink_velocity_bounds(law, branch) == pytest.approx(
        trilinear_bounds(E1, E2, E3, branch), rel=1e-15
    )


@pytest.mark.parametrize("branch", ["lower", "upper"])
@pytest.mark.parametrize("law", LAWS)
def test_superkink_from_V_inverts_V_SK_of_w_plus(law, branch):
    lo, hi = qc.superkink_velocity_bounds(law, branch)
    for t in (1e-6, 0.1, 0.5, 0.9, 1 - 1e-6):
        V = lo + (hi - lo) * t
        sk = qc.superkink_from_V(law, V, branch)
        assert sk.V == pytest.approx(V, rel=4e-16)
        back = qc.superkink_from_w_plus(law, sk.w_plus)  # the closed form, by state
        assert back.V == sk.V and back.w_minus == sk.w_minus
        assert (sk.w_plus < law.hard_regime[0]) == (branch == "lower")


@pytest.mark.parametrize("branch", ["lower", "upper"])
@pytest.mark.parametrize("law", LAWS)
def test_V_SK_is_monotone_on_a_branch(law, branch):
    lo, hi = qc.superkink_w_plus_range(law, branch)
    ws = np.linspace(max(lo, -40.0), min(hi, 40.0), 801)[1:-1]
    ws = ws[~np.isin(ws, law.breakpoints)]
    V = np.array([qc.sound_speeds(law, w)[1] for w in ws])
    d = np.diff(V)
    assert np.all(d > 0) or np.all(d < 0)


def test_velocity_outside_the_bounds_is_refused():
    law = LAWS[0]
    lo, hi = qc.superkink_velocity_bounds(law)
    for V in (0.5 * lo, hi, 1.1 * hi):
        with pytest.raises(ParameterError) as e:
            qc.superkink_from_V(law, V)
        assert e.value.name == "V"
    with pytest.raises(ParameterError) as e:
        qc.superkink_from_V(law, 1.5, "middle")
    assert e.value.name == "branch"
