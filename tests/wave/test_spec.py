"""The wave specification (fpucore.wave.Spec) carries its law and what derives from it.

References: the paper's velocity intervals in closed form (eq. V_bounds_cubic: 2/3 c_max² <
V² < c_max²; solitary waves (c₊, V_SK) ∪ (V_SK, c₋), eqs. cplus, cubic_cond2, cminus_cubic) for
f = −w³ + 10w² + w, and converged discrete waves as the truth for the QC-shift predictor.
"""

import math

import numpy as np
import pytest

from fpucore import qc, wave
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)
C_MAX = math.sqrt(1.0 + 100.0 / 3.0)  # f′(w*) at w* = 10/3
V_SK6, CP6, CM6 = 7 * math.sqrt(5) / 3, math.sqrt(13), math.sqrt(29)  # w+ = 6 (paper)


def test_spec_carries_its_law_to_other_velocities_and_to_its_system():
    other = CubicLaw(-1.0, 20.0)
    (a, b), (c, d) = qc.solitary_intervals(other, 1.0)
    sp = wave.spec_of(other, "solitary", 1.0, 0.5 * (a + b))
    moved = sp.at(0.5 * (c + d))
    assert moved.law is other and moved.row == 1.0 and moved.V == 0.5 * (c + d)
    assert moved.interval() == (c, d) and sp.system(64, 8, 12).law is other
    r = wave.solve_superkink(other, 0.5 * sum(qc.superkink_velocity_bounds(other)), N=64)
    assert r.converged and r.law is other


def test_velocity_intervals_are_the_papers():
    sk = wave.superkink_spec(LAW, 5.2, "lower")
    lo, hi = sk.interval()
    assert lo == pytest.approx(math.sqrt(2.0 / 3.0) * C_MAX, rel=1e-14)
    assert hi == pytest.approx(C_MAX, rel=1e-14)
    assert sk.easy_end() == hi  # superkinks are weak and wide at the upper bound
    below, above = wave.solitary_spec(LAW, 6.0, 4.0), wave.solitary_spec(LAW, 6.0, 5.3)
    assert below.intervals() == above.intervals()
    assert np.allclose(below.interval(), (CP6, V_SK6), rtol=1e-14)
    assert np.allclose(above.interval(), (V_SK6, CM6), rtol=1e-14)
    assert below.v_sk == pytest.approx(V_SK6, rel=1e-14)
    # the QC guess is accurate at the sonic end of each interval
    assert below.easy_end() == below.interval()[0] and above.easy_end() == above.interval()[1]
    # the range a too-wide wave's error names is the family's own
    with pytest.raises(ParameterError) as e:
        wave.solitary_spec(LAW, 6.0, CP6 * (1 + 1e-12)).choose_N(None, 1e-12)
    assert e.value.name == "V" and e.value.valid == below.valid_V() and " or " in e.value.valid


def test_neighbour_predictor_beats_the_qc_guess_and_stays_on_its_interval():
    sp0, sp1 = wave.solitary_spec(LAW, 6.0, 5.0), wave.solitary_spec(LAW, 6.0, 5.05)
    r0 = wave.solve_solitary(LAW, 6.0, 5.0)
    r1 = wave.solve_solitary(LAW, 6.0, 5.05, N=r0.N)
    assert r0.converged and r1.converged
    x1 = np.empty(2 * r1.N)
    x1[0::2], x1[1::2] = r1.w, r1.wdot
    pred = sp1.neighbour_predictor((r0, sp0))(r1.N)
    err_pred = np.max(np.abs(pred - x1)[0::2])
    err_qc = np.max(np.abs(sp1.qc_guess(r1.N) - x1)[0::2])
    assert err_pred < 0.1 * err_qc, (err_pred, err_qc)
    # no predictor from a neighbour on the other side of V_SK, nor without one
    above = wave.solitary_spec(LAW, 6.0, 5.3)
    assert above.neighbour_predictor((r0, sp0)) is None
    assert sp1.neighbour_predictor(None) is None
