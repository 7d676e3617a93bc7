"""fpucore.qc.solitary_kind: the kind and the refusals of qc.solitary without its profile.

The reference is qc.solitary itself (the full wave: w_M by its bracketed root, the profile and
E_ren), for every law route (the cubic's closed forms, a polynomial, each smooth preset, the
trilinear law) over both branches and both velocity intervals, near their ends, and at the
refused velocities (V = V_SK, outside the intervals, too close to an end to resolve).
"""

from __future__ import annotations

import pytest

from fpucore import qc
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw, law_from_expression
from fpucore.law.piecewise import TrilinearLaw
from fpucore.law.presets import preset_law

LAWS = {
    "cubic": CubicLaw(),
    "polynomial": law_from_expression("w + 10*w**2 - w**3 - 0.01*w**4"),
    "exponential": preset_law("exponential"),
    "tanh": preset_law("tanh"),
    "rational": preset_law("rational"),
    "trilinear": TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2),
}


def states(law):
    """(w_plus, V) on both branches, in both intervals, at their middles and near their ends."""
    for branch in ("lower", "upper"):
        lo, hi = qc.superkink_w_plus_range(law, branch)
        a = lo if lo > -1e300 else law.w_star - 4.0 * (hi - law.w_star)
        b = hi if hi < 1e300 else law.w_star + 4.0 * (law.w_star - lo)
        for s in (0.2, 0.3, 0.7, 0.8):
            wp = a + s * (b - a)
            try:  # the trilinear law's hard regime (w1, w2) lies inside its branches' ranges
                (cp, vsk), (_, cm) = qc.solitary_intervals(law, wp)
            except ParameterError:
                continue
            for lo_v, hi_v in ((cp, vsk), (vsk, cm)):
                for t in (1e-3, 0.5, 1 - 1e-3):
                    yield wp, lo_v + t * (hi_v - lo_v)


def outcome(fn, *args):
    try:
        return fn(*args)
    except ParameterError as exc:
        return f"refused: {exc}"


@pytest.mark.parametrize("name", LAWS)
def test_kind_is_the_full_waves_kind(name):
    law = LAWS[name]
    seen = set()
    cases = list(states(law))
    assert len(cases) >= 24
    for wp, V in cases:
        want = outcome(lambda *a: qc.solitary(*a).kind, law, wp, V)
        assert qc.solitary_kind(law, wp, V) == want, (wp, V)
        seen.add(want)
    assert seen == {"tensile", "compressive"}  # both kinds exercised


@pytest.mark.parametrize("name", LAWS)
def test_refusals_are_the_full_waves_refusals(name):
    law = LAWS[name]
    lo, hi = qc.superkink_w_plus_range(law, "lower")
    wp = 0.5 * (max(lo, law.w_star - 4.0) + hi)
    cp, vsk, cm = qc.sound_speeds(law, wp)
    for V in (vsk, 0.5 * cp, cm * 1.01, -1.0, float("nan")):
        want = outcome(qc.solitary, law, wp, V)
        assert want.startswith("refused: "), (V, want)
        assert outcome(qc.solitary_kind, law, wp, V) == want


def test_the_near_sonic_state_of_a_tanh_preset_change():
    """The state the explorer lands on after choosing the tanh preset from the cubic's default
    (w₊ = 1 stays, V to the middle of the narrow (c₊, V_SK)): the case whose profiles made that
    law change take 6 s."""
    law = LAWS["tanh"]
    (cp, vsk), _ = qc.solitary_intervals(law, 1.0)
    V = 0.5 * (cp + vsk)
    assert (vsk - cp) / vsk < 1e-3  # near-sonic indeed
    assert qc.solitary_kind(law, 1.0, V) == qc.solitary(law, 1.0, V).kind
