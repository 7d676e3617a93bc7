"""fpucore.qc's public functions route piecewise-linear laws to their closed forms (the general
route integrates f″, zero between breakpoints, and returned wrong states); text = object."""

import pytest

from fpucore import ParameterError, qc
from fpucore.law import TrilinearLaw, law_from_expression

LAW = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2)
TEXT = "trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)"


def trilinear_w_minus(wp, w1=0.5, w2=1.5, E1=1.0, E2=4.0, E3=0.2):
    """The trilinear equal-area partner written out by hand (qc.piecewise module docstring)."""
    A, B = E2 - E1, E2 - E3
    return (A * w1 * (w1 - wp) - B * w2 * (w2 - wp)) / (A * (w1 - wp) - B * (w2 - wp))


@pytest.mark.parametrize("wp", [0.3, -1.0, 2.0, 4.0])
def test_public_qc_functions_use_the_closed_forms(wp):
    sk = qc.superkink_from_w_plus(LAW, wp)
    assert sk.w_minus == pytest.approx(trilinear_w_minus(wp), rel=1e-14)
    V2 = (float(LAW.f(sk.w_minus)) - float(LAW.f(wp))) / (sk.w_minus - wp)
    cp, vsk, cm = qc.sound_speeds(LAW, wp)
    assert vsk == pytest.approx(V2**0.5, rel=1e-14) and sk.V == vsk
    assert cp == pytest.approx(float(LAW.df(wp)) ** 0.5, rel=1e-15)
    # c₋: chord slope to the corner at the far end of the hard regime
    corner = 1.5 if wp < 0.5 else 0.5
    c2 = (float(LAW.f(corner)) - float(LAW.f(wp))) / (corner - wp)
    assert cm == pytest.approx(c2**0.5, rel=1e-14)
    assert qc.w_minus_sonic(LAW, wp) == corner
    (lo, mid), (mid2, hi) = qc.solitary_intervals(LAW, wp)
    assert (lo, mid, mid2, hi) == (cp, vsk, vsk, cm)
    for V in (0.5 * (cp + vsk), 0.5 * (vsk + cm)):
        sw = qc.solitary(LAW, wp, V)
        assert sw.converged and sw.amplitude > 0


def test_text_gives_the_same_results_as_the_object():
    law = law_from_expression(TEXT)
    a = qc.solitary(law, 0.3, 1.7).as_dict()
    b = qc.solitary(LAW, 0.3, 1.7).as_dict()
    a.pop("elapsed_s"), b.pop("elapsed_s")
    assert a == b


def test_cli_qc_numbers_for_a_trilinear_law():
    from fpucore.cli.qc import compute

    out = compute(law_from_expression(TEXT), 0.3, 1.7)
    assert out["superkink"]["w_minus"] == pytest.approx(trilinear_w_minus(0.3), rel=1e-14)
    assert out["breakpoints"] == [0.5, 1.5] and out["solitary"]["kind"] == "tensile"


def test_a_state_in_the_hard_regime_is_refused():
    with pytest.raises(ParameterError) as e:
        qc.superkink_from_w_plus(LAW, 1.0)  # inside the hard regime
    assert e.value.name == "w_plus"


def test_slopes_are_the_derivative_of_the_profiles():
    import numpy as np

    xi = np.linspace(-4, 4, 81) + 0.013
    h = 1e-6
    for wave in (qc.solitary(LAW, 0.3, 1.7), qc.solitary(LAW, 0.3, 1.85),
                 qc.superkink_from_w_plus(LAW, 0.3)):  # fmt: skip
        fd = (wave.profile(xi + h) - wave.profile(xi - h)) / (2 * h)
        assert np.max(np.abs(wave.dprofile(xi) - fd)) <= 1e-8


def test_solitary_with_a_single_turning_point():
    """V low in (c₊, V_SK) on a zero-modulus background: Q has one zero beyond w_M's piece
    (w_T is NaN), once an IndexError."""
    import math

    law = TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2)
    sw = qc.solitary(law, 0.2, 0.35)
    assert sw.converged and sw.c_plus == 0.0 and (math.isnan(sw.w_T) or sw.w_T > sw.w_M)


@pytest.mark.parametrize(
    "law",
    [
        LAW,
        TrilinearLaw(0.5, 1.5, 0.2, 4.0, 1.0),
        TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2),
        TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.0),
        TrilinearLaw(0.1, 3.0, 2.0, 2.5, 1.9),
    ],
)
def test_sweep_states_and_velocities_answer_or_refuse(law):
    """Over each superkink range and both velocity intervals: a converged closed-form wave
    whose tails decay (V² > f′(w_B)) and whose amplitude is below the superkink's, or a
    ParameterError — never another exception."""
    import math

    import numpy as np

    from fpucore.qc import piecewise as P

    for branch in ("lower", "upper"):
        lo, hi = P.superkink_w_plus_range(law, branch)
        lo, hi = (max(lo, hi - 6.0), hi) if branch == "lower" else (lo, min(hi, lo + 6.0))
        for wp in np.linspace(lo, hi, 9)[1:-1]:
            if np.any(np.isclose(law._b, wp)):
                continue
            sk = qc.superkink_from_w_plus(law, wp)
            cp, vsk, cm = qc.sound_speeds(law, wp)
            for V in np.concatenate((np.linspace(cp, vsk, 7)[1:-1], np.linspace(vsk, cm, 7)[1:-1])):
                try:
                    sw = qc.solitary(law, wp, V)
                except ParameterError:
                    continue
                assert sw.converged and math.isfinite(sw.energy)
                assert V * V > float(law.df(sw.w_B))
                assert sw.amplitude < sk.amplitude + 1e-12
