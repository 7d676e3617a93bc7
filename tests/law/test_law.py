"""Force law: derivatives, potential, constants of eq. cubic_more, symmetry, Numba kernels."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fpucore import CubicLaw, ParameterError
from fpucore.law import ddforce, dforce, force

laws = st.builds(
    CubicLaw,
    a=st.floats(-50.0, -0.01),
    b=st.floats(0.05, 120.0),
)


def test_paper_constants():
    law = CubicLaw(-1.0, 10.0)
    assert law.w_star == pytest.approx(10 / 3, rel=1e-15)
    assert law.alpha == pytest.approx(-(math.sqrt(103) - 10) / 3, rel=1e-14)
    assert law.beta == pytest.approx((10 + math.sqrt(103)) / 3, rel=1e-15)


@settings(max_examples=60, deadline=None)
@given(laws)
def test_constants_are_roots(law):
    # f'(alpha) = f'(beta) = 0 and f''(w*) = 0, to round-off relative to the terms involved
    for w in (law.alpha, law.beta):
        scale = 1 + 3 * law.abs_a * w * w + 2 * law.b * abs(w)
        assert abs(float(law.df(w))) <= 1e-12 * scale
    assert abs(float(law.ddf(law.w_star))) <= 1e-12 * law.b
    assert law.alpha < 0 < law.w_star < law.beta


@settings(max_examples=60, deadline=None)
@given(laws, st.floats(-1.0, 1.0))
def test_symmetry_identity(law, t):
    w = law.w_star + t * (law.beta - law.w_star)
    lhs = float(law.f(w)) + float(law.f(law.mirror(w)))
    scale = abs(float(law.f(w))) + abs(float(law.f(law.mirror(w)))) + 1
    assert abs(lhs - law.symmetry_constant) <= 1e-12 * scale


def test_derivatives_against_finite_differences():
    law = CubicLaw(-1.3, 7.0)
    w = np.linspace(law.alpha, law.beta, 17)
    h = 1e-5
    assert np.allclose((law.phi(w + h) - law.phi(w - h)) / (2 * h), law.f(w), rtol=1e-8, atol=1e-8)
    assert np.allclose((law.f(w + h) - law.f(w - h)) / (2 * h), law.df(w), rtol=1e-8, atol=1e-7)
    assert np.allclose((law.df(w + h) - law.df(w - h)) / (2 * h), law.ddf(w), rtol=1e-8, atol=1e-6)


def test_numba_kernels_match_vectorised():
    law = CubicLaw(-0.7, 3.0)
    for w in np.linspace(-0.2, 5.0, 11):
        assert force(law.law_id, law.params, w) == pytest.approx(float(law.f(w)), rel=1e-15)
        assert dforce(law.law_id, law.params, w) == pytest.approx(float(law.df(w)), rel=1e-14)
        assert ddforce(law.law_id, law.params, w) == pytest.approx(float(law.ddf(w)), rel=1e-14)


@pytest.mark.parametrize(
    "a,b,name",
    [(1.0, 10.0, "a"), (0.0, 10.0, "a"), (-1.0, 0.0, "b"), (-1.0, -2.0, "b"),
     (math.nan, 1.0, "a"), (-1.0, math.inf, "b"), ("x", 1.0, "a")],
)  # fmt: skip
def test_bad_law_parameters(a, b, name):
    with pytest.raises(ParameterError) as e:
        CubicLaw(a, b)
    assert e.value.name == name and name + "=" in str(e.value)
