"""One computable range for every law: a polynomial law gets the cubic's scale checks (strain
scale W, c_max², c_max² W³, w*) and bounded coefficients, through the API and on every command.

Before: ``w + 1e308*w**2 - w**3`` or a 1e-320 coefficient raised LinAlgError (numpy.roots of a
companion matrix with inf) on all commands; ``w + 10*w**2 - 1e308*w**3`` was refused as "no
softening" (its β = 0.33·1e-307 exists); ``w + 1e200*w**2 - 1e200*w**3`` ran while the same
cubic ``CubicLaw(-1e200, 1e200)`` is refused; ``fpu qc --w-plus 1e299 --law
"w+(10**300/3)*w**2-w**3"`` printed c+ = inf with exit 0."""

from __future__ import annotations

import math

import pytest

from fpucore.cli import main
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw, PolynomialLaw, law_from_expression

# (text, the coefficient named, words of the reason)
OVERFLOWING = [
    ("w + 1e308*w**2 - w**3", "c_2", "1e-150 <= |c_2| <= 1e+150"),
    ("w + 1e-320*w**2 - w**3", "c_2", "1e-150 <= |c_2| <= 1e+150"),
    ("w + 10*w**2 - 1e-320*w**3", "c_3", "1e-150 <= |c_3| <= 1e+150"),
    ("w + 10*w**2 - 1e308*w**3", "c_3", "1e-150 <= |c_3| <= 1e+150"),
    ("w+1e200*w**2-1e200*w**3", "c_2", "1e-150 <= |c_2| <= 1e+150"),
    ("w+(10**300/3)*w**2-w**3", "c_2", "1e-150 <= |c_2| <= 1e+150"),
]


@pytest.mark.parametrize("text, name, words", OVERFLOWING)
def test_overflowing_polynomial_laws_are_refused_naming_the_coefficient(text, name, words):
    with pytest.raises(ParameterError) as e:
        law_from_expression(text)
    assert e.value.name == name and words in str(e.value), str(e.value)
    assert "no softening" not in str(e.value)


def test_the_cubic_and_its_polynomial_share_one_range():
    """Laws inside the coefficient bounds but outside the scale range are refused by the same
    check as the cubic, for the same reason (c_max² = 1 + b²/(3|a|) = 3.3e59 · 3 > 1e60 ...)."""
    for a, b in [(-1e100, 1e100), (-1.0, 1e31), (-1e-61, 1e-40), (-1.0, 1e-120)]:
        with pytest.raises(ParameterError, match="strain scale W"):
            CubicLaw(a, b)
        with pytest.raises(ParameterError, match="strain scale W") as e:
            PolynomialLaw((1.0, b, a))
        assert e.value.name == "coeffs"
    for a, b in [(-1.0, 10.0), (-1e-50, 1e-20), (-1e50, 1e20), (-3.0, 1e-90)]:
        law, poly = CubicLaw(a, b), PolynomialLaw((1.0, b, a))  # inside: both accepted, equal
        for k in ("alpha", "beta", "w_star", "c_max"):
            assert getattr(poly, k) == pytest.approx(getattr(law, k), rel=1e-12, abs=0), k


def test_a_law_of_degree_four_outside_the_speed_range_is_refused():
    # quartic with c_max² = f'(w*) = 1.7e61 (w* ≈ √(2e40/0.012) = 1.3e21, f' ≈ 2e40 w*): every
    # coefficient is in range, only the shared scale check stops it; 1e35 instead is inside
    # (c_max² = 5.4e53, c_max² W³ = 2e110)
    with pytest.raises(ParameterError, match=r"c_max\^2 = 1.72e\+61"):
        PolynomialLaw((1.0, 1e40, -1.0, -1e-3))
    assert PolynomialLaw((1.0, 1e35, -1.0, -1e-3)).c_max ** 2 == pytest.approx(5.443e53, rel=1e-3)


COMMANDS = [
    ["qc", "--w-plus", "0.5"],
    ["wave", "superkink", "--V", "5"],
    ["wave", "solitary", "--w-plus", "0.5", "--V", "5"],
    ["floquet", "superkink", "--V", "5"],
    ["floquet", "solitary", "--w-plus", "0.5", "--V", "5"],
    ["simulate", "riemann", "--w-left", "0.5", "--w-right", "0", "--L", "10", "--t-end", "1"],
    ["simulate", "wave", "superkink", "--V", "5"],
]


@pytest.mark.parametrize("cmd", COMMANDS, ids=[" ".join(c[:2]) for c in COMMANDS])
@pytest.mark.parametrize("text, name, words", OVERFLOWING[:4])
def test_every_command_refuses_an_overflowing_law_in_one_line(capsys, cmd, text, name, words):
    assert main([*cmd, f"--law={text}"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"fpu: error: {name}=") and words in err, err


def test_atlas_refuses_an_overflowing_law(capsys, tmp_path):
    out = str(tmp_path / "a.zarr")
    assert main(["atlas", "superkink", "--law=w + 1e308*w**2 - w**3", "--out", out]) == 2
    assert capsys.readouterr().err.startswith("fpu: error: c_2=")


def test_no_inf_printed_with_exit_0(capsys):
    """The report's case: refused now (exit 2); and a legal law at a strain far outside its
    convex interval is refused too, so no command prints inf/nan with exit 0 from these."""
    rc = main(["qc", "--w-plus", "1e299", "--law", "w+(10**300/3)*w**2-w**3"])
    out, err = capsys.readouterr()
    assert rc == 2 and "inf" not in out and err.startswith("fpu: error: c_2=")
    rc = main(["qc", "--w-plus", "1e299", "--law", "w + 10*w**2 - w**3"])
    assert rc == 2 and capsys.readouterr().err.startswith("fpu: error: w_plus=")
    # a law inside the range but far from unit scale (c_max = 5e19): every printed number finite
    assert main(["qc", "--w-plus", "1e19", "--V", "5e19", "--law", "w + 1e20*w**2 - w**3"]) == 0
    out = capsys.readouterr().out
    assert "inf" not in out.lower() and "nan" not in out.lower(), out


def test_real_roots_of_far_out_polynomials_stay_finite():
    """Roots so far out that p(x) overflows are kept unverified (error inf), never NaN."""
    from fpucore.law import real_roots

    roots = real_roots([1.0, 0.0, 1e-150])  # 1 + 1e-150 x²: no real root, |x| = 1e75
    assert roots == []
    roots = real_roots([-1.0, 0.0, 0.0, 0.0, 1e-150])  # x⁴ = 1e150: x = ±1e37.5
    assert [x for x, _ in roots] == pytest.approx([-(10**37.5), 10**37.5], rel=1e-12)
    assert all(math.isfinite(x) for x, _ in roots)


def test_the_cubic_and_its_polynomial_accept_the_same_laws():
    """(a, b) log-uniform over |a| in [1e-80, 1e80], b in [1e-160, 1e80] (fixed seed): CubicLaw
    (closed-form α, β, w*) and PolynomialLaw((1, b, a)) (roots by numpy, the shared range) accept
    exactly the same laws — about 40 % of the sample — and refuse the rest by name."""
    import random

    rng = random.Random(1)
    accepted = 0
    for _ in range(600):
        a, b = -(10 ** rng.uniform(-80, 80)), 10 ** rng.uniform(-160, 80)
        try:
            CubicLaw(a, b)
            cubic = True
        except ParameterError:
            cubic = False
        try:
            PolynomialLaw((1.0, b, a))
            poly = True
        except ParameterError as e:
            poly = False
            assert e.name in ("coeffs", "c_2", "c_3", "w_star"), str(e)
        assert cubic == poly, (a, b, cubic, poly)
        accepted += cubic
    assert 150 < accepted < 450
