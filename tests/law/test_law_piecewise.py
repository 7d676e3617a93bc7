"""Piecewise-linear laws: values, potential, kernels, class checks, text form."""

import math

import numpy as np
import pytest

from fpucore import ParameterError
from fpucore.law import (
    PiecewiseLinearLaw,
    TrilinearLaw,
    ddforce,
    dforce,
    force,
    law_from_expression,
)


def _ref_f(w, b, s):
    """f by direct definition from the piece containing 0 (independent of the tables)."""
    # f(w) = ∫₀ʷ f′: sum of slope × overlap of [0, w] with each piece
    edges = [-math.inf, *b, math.inf]
    lo, hi = (0.0, w) if w >= 0 else (w, 0.0)
    tot = sum(sk * max(0.0, min(hi, edges[k + 1]) - max(lo, edges[k])) for k, sk in enumerate(s))
    return tot if w >= 0 else -tot


def test_trilinear_values_potential_and_kernels():
    law = TrilinearLaw(w1=0.5, w2=1.5, E1=1.0, E2=4.0, E3=0.2)
    w = np.linspace(-2.0, 4.0, 61)
    ref = np.array([_ref_f(x, (0.5, 1.5), (1.0, 4.0, 0.2)) for x in w])
    assert np.allclose(law.f(w), ref, rtol=1e-15, atol=1e-15)
    assert float(law.f(0.0)) == 0.0
    # f' by slope of the piece; Φ' = f by central differences away from the corners
    assert float(law.df(1.0)) == 4.0 and float(law.df(0.2)) == 1.0 and float(law.df(2.0)) == 0.2
    h = 1e-6
    wm = np.array([-1.0, 0.3, 1.0, 2.5])
    assert np.allclose((law.phi(wm + h) - law.phi(wm - h)) / (2 * h), law.f(wm), rtol=1e-9)
    # Φ exact: ∫₀^1.5 f = 0.5·0.25 (first piece) + trapezoid (0.5, 4.5)·1
    assert float(law.phi(1.5)) == pytest.approx(0.125 + 2.5, rel=1e-15)
    assert float(law.phi(-2.0)) == pytest.approx(2.0, rel=1e-15)
    for x in w:
        assert force(law.law_id, law.params, x) == pytest.approx(float(law.f(x)), abs=1e-15)
        assert dforce(law.law_id, law.params, x) == float(law.df(x))
        assert ddforce(law.law_id, law.params, x) == 0.0
    assert law.hard_regime == (0.5, 1.5) and law.w_star == 1.0 and law.c_max == 2.0
    assert law.alpha == -math.inf and law.beta == math.inf and not law.degenerate


def test_general_piecewise_and_degenerate():
    law = PiecewiseLinearLaw((-1.0, 0.5, 1.5, 3.0), (0.5, 1.0, 4.0, 0.5, 0.1))
    w = np.linspace(-3.0, 5.0, 41)
    ref = np.array([_ref_f(x, law.breakpoints, law.slopes) for x in w])
    assert np.allclose(law.f(w), ref, rtol=1e-14, atol=1e-15)
    assert law.hard_regime == (0.5, 1.5)
    deg = TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2)
    assert deg.degenerate and deg.alpha == 0.5 and float(deg.f(-3.0)) == 0.0
    deg3 = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.0)
    assert deg3.beta == 1.5 and float(deg3.f(7.0)) == float(deg3.f(1.5)) == 4.5
    assert TrilinearLaw(0.5, 1.5, 1, 4, 0.2).as_piecewise() == TrilinearLaw(0.5, 1.5, 1, 4, 0.2)


@pytest.mark.parametrize(
    "kwargs, name, words",
    [
        (dict(w1=1.0, w2=0.5), "w2", "increase"),
        (dict(w1=-0.5), "w1", "first (soft) regime"),
        (dict(E1=-1.0), "E1", "negative modulus"),
        (dict(E3=-0.1), "E3", "negative modulus"),
        (dict(E2=0.5), "E2", "hard"),
        (dict(E1=5.0), "E2", "hard"),
        (dict(E2=math.nan), "E2", "finite"),
    ],
)
def test_trilinear_refusals(kwargs, name, words):
    base = dict(w1=0.5, w2=1.5, E1=1.0, E2=4.0, E3=0.2)
    base.update(kwargs)
    with pytest.raises(ParameterError) as e:
        TrilinearLaw(**base)
    assert e.value.name == name and words in str(e.value)


@pytest.mark.parametrize(
    "b, s, name, words",
    [
        ((0.5, 0.4), (1, 4, 0.2), "breakpoints", "increasing"),
        ((0.5, 1.5), (1, 4), "slopes", "one more"),
        ((0.5, 1.5), (1, -4, 0.2), "slopes[1]", "negative modulus"),
        ((0.5, 1.5, 2.0), (1, 4, 0.2, 3.0), "slopes[3]", "strictly increase"),  # concave-convex
        ((0.5, 1.5), (1, 2, 4), "slopes[2]", "no softening"),
        ((0.5, 1.5), (4, 2, 1), "slopes[0]", "no hardening"),
        ((-0.5, 1.5), (1, 4, 0.2), "breakpoints", "soft regime before"),
        ((0.5, 1.5, 2.0), (1, 4, 4, 0.2), "slopes[2]", "strictly"),
    ],
)
def test_piecewise_refusals(b, s, name, words):
    with pytest.raises(ParameterError) as e:
        PiecewiseLinearLaw(b, s)
    assert e.value.name == name and words in str(e.value)


def test_text_form_round_trip_and_refusals():
    law = law_from_expression("trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)")
    assert law == TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2)
    assert law_from_expression(law.expression) == law
    pw = law_from_expression("piecewise(breakpoints=[0.5, 1.5, 3], slopes=[1, 4, 0.5, 0.1])")
    assert pw.slopes == (1.0, 4.0, 0.5, 0.1) and law_from_expression(pw.expression) == pw
    for bad, words in [
        ("trilinear(w1=0.5, w2=1.5, E1=1, E2=4)", "missing E3"),
        ("trilinear(w1=__import__('os'), w2=1.5, E1=1, E2=4, E3=0)", "only numbers"),
        ("trilinear(0.5, 1.5, 1, 4, 0.2)", "keyword"),
        ("piecewise(breakpoints=0.5, slopes=[1, 4, 0.2])", "list"),
        ("trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2", "could not parse"),
    ]:
        with pytest.raises(ParameterError) as e:
            law_from_expression(bad)
        assert e.value.name == "expression" and words in str(e.value)
    with pytest.raises(ParameterError) as e:  # the law's own check names the argument
        law_from_expression("trilinear(w1=0.5, w2=1.5, E1=-1, E2=4, E3=0.2)")
    assert e.value.name == "E1"


def test_cli_takes_piecewise_law():
    import argparse

    from fpucore.cli.common import add_law_args, law_fields, law_from_args

    p = argparse.ArgumentParser()
    add_law_args(p)
    law = law_from_args(p.parse_args(["--law", "trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0)"]))
    assert law == TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.0)
    assert law_fields(law)["slopes"] == [1.0, 4.0, 0.0]
