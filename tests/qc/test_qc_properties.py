"""Property tests over random valid (a, b, w+, V): jump conditions and the mirror symmetry."""

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from fpucore import CubicLaw, qc


@st.composite
def law_wplus_V(draw):
    a = draw(st.floats(-20.0, -0.02))
    b = draw(st.floats(0.1, 60.0))
    law = CubicLaw(a, b)
    t = draw(st.floats(0.02, 0.98))
    w_plus = law.alpha + t * (law.beta - law.alpha)
    assume(abs(w_plus - law.w_star) > 1e-3 * (law.beta - law.alpha))
    (cp, vsk), (_, cm) = qc.solitary_intervals(law, w_plus)
    s = draw(st.floats(0.01, 0.99))
    below = draw(st.booleans())
    V = cp + s * (vsk - cp) if below else vsk + s * (cm - vsk)
    return law, w_plus, V


@settings(max_examples=150, deadline=None)
@given(law_wplus_V())
def test_superkink_jump_conditions(args):
    law, w_plus, _ = args
    sk = qc.superkink_from_w_plus(law, w_plus)
    # Rayleigh line (eq. Rline) and zero driving force / equal areas (eq. zero_G)
    assert sk.rayleigh_residual < 1e-12
    assert sk.driving_force < 1e-11
    assert law.alpha < min(sk.w_plus, sk.w_minus) and max(sk.w_plus, sk.w_minus) < law.beta


@settings(max_examples=150, deadline=None)
@given(law_wplus_V())
def test_solitary_first_integral_and_background(args):
    law, w_plus, V = args
    sw = qc.solitary(law, w_plus, V)
    assert sw.first_integral_residual < 1e-13
    ray = float(law.f(sw.w_B)) - float(law.f(w_plus)) - V * V * (sw.w_B - w_plus)
    assert abs(ray) <= 1e-10 * (abs(float(law.f(sw.w_B))) + V * V * abs(sw.w_B) + 1)
    assert math.isfinite(sw.energy) and sw.amplitude > 0


@settings(max_examples=100, deadline=None)
@given(law_wplus_V())
def test_mirror_symmetry_maps_solutions_to_solutions(args):
    """w -> 2w* - w maps a wave for w+ to the wave for 2w* - w+ with the same V."""
    law, w_plus, V = args
    sw = qc.solitary(law, w_plus, V)
    mw = qc.solitary(law, float(law.mirror(w_plus)), V)
    assert mw.kind != sw.kind
    xi = np.linspace(-5, 5, 21) / sw.gamma
    scale = abs(law.w_star) + sw.amplitude
    assert np.allclose(mw.profile(xi), law.mirror(sw.profile(xi)), rtol=0, atol=1e-9 * scale)
    sk = qc.superkink_from_w_plus(law, w_plus)
    msk = qc.superkink_from_w_plus(law, float(law.mirror(w_plus)))
    assert abs(msk.V - sk.V) <= 1e-12 * sk.V
    assert np.allclose(msk.profile(xi), law.mirror(sk.profile(xi)), rtol=0, atol=1e-9 * scale)
