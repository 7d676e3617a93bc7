"""Smooth hardening–softening laws from text (exp, log, sqrt, tanh, sinh, cosh, atan, quotients,
rational powers, named constants): the class check against independent 30-digit references
(mpmath written here from the formulas, not through fpucore), the Chebyshev kernel against the
exact expression within its stored error, refusals with reason and place, polynomial texts
bit-identical to the polynomial route."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

import fpucore as F
from fpucore.errors import ParameterError
from fpucore.law import (
    LAW_CHEB,
    PolynomialLaw,
    SmoothLaw,
    ddforce,
    dforce,
    force,
    law_from_expression,
)
from fpucore.law.presets import PRESETS, preset_law

SMOOTH = ("exponential", "tanh", "rational")
mpmath.mp.dps = 40


def exact(name: str, **over):
    """f of a preset as an mpmath function written from its formula (independent of fpucore)."""
    c = {**PRESETS[name].constants_dict, **over}
    c = {k: mpmath.mpf(repr(v)) for k, v in c.items()}
    if name == "exponential":
        return lambda w: w + c["b"] * w**2 - c["c"] * w**3 * mpmath.exp(w / c["d"])
    if name == "tanh":
        k, m, s = c["k"], c["m"], c["s"]
        return lambda w: w + k * (mpmath.tanh((w - m) / s) + mpmath.tanh(m / s)) - c["c"] * w**3
    if name == "rational":
        return lambda w: w * (1 + c["b"] * w) / (1 + c["c"] * w**2)
    raise KeyError(name)


def d(f, n):
    return lambda w: mpmath.diff(f, w, n)


def test_smooth_law_is_exported_at_the_top_level():
    law = F.law_from_expression("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 50})
    assert isinstance(law, F.SmoothLaw) and law.law_id == LAW_CHEB
    assert law.constants_dict == {"b": 10.0, "c": 1.0, "d": 50.0}


@pytest.mark.parametrize("name", SMOOTH)
def test_alpha_beta_w_star_against_30_digit_roots(name):
    law = preset_law(name)
    f = exact(name)
    f1, f2 = d(f, 1), d(f, 2)
    beta = mpmath.findroot(f1, law.beta)
    w_star = mpmath.findroot(f2, law.w_star)
    assert abs(law.beta - beta) <= law.beta_error + 4e-16 * abs(beta)
    assert abs(law.w_star - w_star) <= law.w_star_error + 4e-16 * abs(w_star)
    alpha = mpmath.findroot(f1, law.alpha)
    assert abs(law.alpha - alpha) <= law.alpha_error + 4e-16 * abs(alpha)
    assert law.alpha < 0 < law.w_star < law.beta
    # f'' > 0 on (alpha, w*), < 0 on (w*, beta): the class, sampled independently
    for x in np.linspace(float(alpha), float(beta), 41)[1:-1]:
        if abs(x - float(w_star)) > 1e-6:
            assert (f2(x) > 0) == (x < w_star)


@pytest.mark.parametrize("name", SMOOTH)
def test_kernel_within_the_stored_representation_error(name):
    law = preset_law(name)
    err = law.representation_error
    lo, hi = law.interval
    assert err.interval == (lo, hi) and lo < law.alpha and hi > law.beta
    assert max(err.relative) <= 1e-12
    f = exact(name)
    p = law.params
    rng = np.random.default_rng(7)
    for x in np.concatenate([rng.uniform(lo, hi, 60), [lo, hi, law.alpha, law.w_star, law.beta]]):
        xm = mpmath.mpf(float(x))
        assert abs(force(LAW_CHEB, p, x) - float(f(xm))) <= err.f
        assert abs(dforce(LAW_CHEB, p, x) - float(d(f, 1)(xm))) <= err.df
        assert abs(ddforce(LAW_CHEB, p, x) - float(d(f, 2)(xm))) <= err.ddf
    for x in (lo - 1e-9 * (hi - lo), hi + 1e-9 * (hi - lo), math.nan):
        assert math.isnan(force(LAW_CHEB, p, x)) and math.isnan(dforce(LAW_CHEB, p, x))


@pytest.mark.parametrize("name", SMOOTH)
def test_potential_is_the_integral_of_f(name):
    law = preset_law(name)
    f = exact(name)
    for x in (law.alpha, 0.5 * law.w_star, law.w_star, law.beta):
        ref = float(mpmath.quad(f, [0, x]))
        assert abs(float(law.phi(x)) - ref) <= abs(x) * law.representation_error.f + 1e-14 * (
            1 + abs(ref)
        )


@pytest.mark.parametrize(
    "text",
    ["w + 10*w**2 - w**3", "w + 10*w**2 - w**3 - 0.01*w**4", "a*w**3 + b*w**2 + w"],
)
def test_polynomial_texts_keep_the_polynomial_route_bit_for_bit(text):
    consts = {"a": -1, "b": 10} if "a*" in text else None
    law = law_from_expression(text, consts)
    assert type(law) is PolynomialLaw
    plain = text.replace("a*", "-1*").replace("b*", "10*")
    ref = law_from_expression(plain)
    assert law.coeffs == ref.coeffs and np.array_equal(law.params, ref.params)
    assert law.law_id == ref.law_id and law.beta == ref.beta and law.w_star == ref.w_star


def test_polynomial_with_constants_equals_cubic_coefficients():
    law = law_from_expression("a*w**3 + b*w**2 + w", {"a": -1.0, "b": 10.0})
    assert law.coeffs == F.CubicLaw(-1.0, 10.0).as_polynomial().coeffs


def test_with_constants_changes_one_constant():
    law = preset_law("exponential")
    other = law.with_constants(d=40)
    assert other.constants_dict == {"b": 10.0, "c": 1.0, "d": 40.0}
    assert other == law_from_expression(law.text, {"b": 10, "c": 1, "d": 40})
    with pytest.raises(ParameterError, match="q="):
        law.with_constants(q=1)


@pytest.mark.parametrize(
    "text, consts, cause",
    [
        ("log(1 + w)", None, "no softening"),
        ("w + w**2 - sqrt(w)*w**3", None, "fractional power of a negative number"),
        ("w + w**2 - w**3 + log(w + 0.5) - log(0.5)", None, "log of a non-positive"),
        ("w + w**2 - w**3*exp(w) + log(-0.5)*w", None, "log of a non-positive number: log(-1/2)"),
        ("w + w**2 - w**3*exp(w)*sqrt(-2)", None, "sqrt of a negative number"),
        ("w + w**2 - w**3*sqrt(-2)", None, "the constant sqrt(-2) is not a finite real number"),
        ("w + 10*w**2 - w**3*exp(w/50) + 1e-300*exp(1000*w)", None,
         "f' is not finite at w = 0.7"),
        ("w + 1 + w**2 - w**3*exp(w)", None, "f(0) ="),
        ("-w + w**2 - w**3*exp(w)", None, "f'(0) ="),
        ("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3",
         {"c": 0.1, "k": 1, "m": 1, "s": 0.01}, "f'' changes sign 3 times"),
        ("w - w**2*exp(w)", None, "the inflection w* = -0.58578"),
        ("w + b*w**2", {"b": 1}, "no softening"),
        ("w + q*w**2 - w**3*exp(w)", None, "unknown name 'q'"),
        ("w + sin(w)*w**2", None, "'sin' is not allowed"),
        ("w + b*w**2 - w**3*exp(w)", {"b": 1, "z": 2}, "z"),
        ("w + w**w", None, "depends on w"),
        ("w + (w+1)**100 - 1", None, "degree 100"),
        ("w + exp(w)*(w+1)**100 - exp(w)", None, "the exponent 100 of an expression in w"),
        ("w + 9**9**9*w**2*exp(w)", None, "exceeds the float range"),
    ],
)  # fmt: skip
def test_refusals_name_the_reason(text, consts, cause):
    with pytest.raises(ParameterError) as exc:
        law_from_expression(text, consts)
    assert cause in str(exc.value), str(exc.value)


@pytest.mark.parametrize(
    "consts, name",
    [({"b": math.nan}, "b"), ({"b": True}, "b"), ({"exp": 1.0}, "constants"),
     ({"b": "10"}, "b"), ({"1b": 1.0}, "constants")],
)  # fmt: skip
def test_bad_constants_are_refused_naming_them(consts, name):
    with pytest.raises(ParameterError) as exc:
        law_from_expression("w + b*w**2 - w**3*exp(w)", consts)
    assert exc.value.name == name


def test_the_three_failures_name_their_places():
    with pytest.raises(ParameterError) as exc:
        law_from_expression("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3",
                            {"c": 0.1, "k": 1, "m": 1, "s": 0.01})  # fmt: skip
    # the three sign changes of f'' are at 0 and on both sides of m = 1
    places = [float(x) for x in str(exc.value).split("at w ~ ")[1].split(";")[0].split(", ")]
    assert len(places) == 3 and abs(places[0]) < 1e-3 and places[1] < 1 < places[2] + 1e-3


@pytest.mark.parametrize(
    "text, consts",
    [
        ("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 0.3}),  # steep exponential
        ("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3",
         {"c": 0.1, "k": 1, "m": 0.05, "s": 0.01}),  # narrow tanh transition
        ("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 0.02}),  # w* near beta
    ],
)  # fmt: skip
def test_stiff_laws_are_represented_to_their_stored_error(text, consts):
    law = law_from_expression(text, consts)
    assert isinstance(law, SmoothLaw)
    err = law.representation_error
    assert max(err.relative) <= 1e-9
    # the stored error against 30-digit values at points between all Chebyshev nodes
    lo, hi = law.interval
    xs = np.linspace(lo, hi, 397)
    mpmath.mp.dps = 30
    vals = {k: mpmath.mpf(repr(float(v))) for k, v in consts.items()}
    fn = {"text": text}
    for x in xs:
        ref = _mp_eval(fn["text"], vals, mpmath.mpf(float(x)))
        assert abs(float(law.represented(0, x)) - float(ref)) <= err.f
    mpmath.mp.dps = 40


def _mp_eval(text, vals, w):
    if "tanh" in text:
        k, m, s, c = vals["k"], vals["m"], vals["s"], vals["c"]
        return w + k * (mpmath.tanh((w - m) / s) + mpmath.tanh(m / s)) - c * w**3
    return w + vals["b"] * w**2 - vals["c"] * w**3 * mpmath.exp(w / vals["d"])


def test_w_star_near_beta_is_reported_close():
    law = law_from_expression("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 0.02})
    assert (law.beta - law.w_star) / (law.beta - law.alpha) < 0.25


CLASS_REFUSALS = [
    ("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3", {"c": 0.1, "k": 1, "m": 1, "s": 0.01},
     "f'' changes sign 3 times"),
    ("w + w**2/(1 + exp(-(w - 1)/e)) - w**3/100", {"e": 0.05}, "f'' changes sign 5 times"),
    ("w - w**2*exp(w)", None, "the inflection w* = -0.58578"),
    ("log(1 + w)", None, "no softening"),
    ("w + w**2 - w**3 + log(w + 0.5) - log(0.5)", None, "log of a non-positive"),
    ("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3", {"c": 0.1, "k": 1, "m": 0.01, "s": 0.002},
     "too steep to represent"),
]  # fmt: skip


@pytest.mark.parametrize("text, consts, cause", CLASS_REFUSALS)
def test_class_refusals_do_no_extended_precision_work(monkeypatch, text, consts, cause):
    """A law refused by the class check (or as too steep) is refused on float64 scans alone:
    no root is polished at 30 digits and no representation is built (the work that made such
    refusals take 0.3-0.5 s; ≤ 50 ms now, benchmarks/bench_law_smooth.py D)."""
    from fpucore.law import chebyshev, smooth_class

    def forbidden(*a, **k):
        raise AssertionError("extended-precision work before the refusal")

    monkeypatch.setattr(smooth_class, "polish", forbidden)
    monkeypatch.setattr(chebyshev, "build", forbidden)
    with pytest.raises(ParameterError) as exc:
        law_from_expression(text, consts)
    assert cause in str(exc.value), str(exc.value)


def test_an_accepted_law_polishes_its_three_roots_once(monkeypatch):
    from fpucore.law import smooth_class

    calls = []
    real = smooth_class.polish
    monkeypatch.setattr(smooth_class, "polish", lambda *a: calls.append(a) or real(*a))
    law = law_from_expression("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 50})
    assert len(calls) == 3  # alpha, beta, w*
    assert law.alpha_error < 1e-15 and law.beta_error < 1e-14 and law.w_star_error < 1e-14
