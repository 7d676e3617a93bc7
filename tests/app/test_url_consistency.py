"""A link's values must fit together, and a refused value is named as it was typed.

References: the paper's closed forms for a = −1, b = 10 (α, β, w* = 10/3; V_SK = 2√65/3 at
w₊ = 1), and the superkink branch through V = 5.2, whose w₊ solves V_SK(w₊) = 5.2 (found here
by bisection on the closed form, independently of the state's tie)."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("panel")

from app.url_state import state_from_url  # noqa: E402
from fpucore import CubicLaw, qc  # noqa: E402

LAW = CubicLaw(-1.0, 10.0)


def w_plus_of_superkink(V: float) -> float:
    lo, hi = LAW.alpha + 1e-9, 1.0  # the lower branch: V_SK grows with w₊ (5.37 at w₊ = 1)
    assert qc.sound_speeds(LAW, lo)[1] < V < qc.sound_speeds(LAW, hi)[1]
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if qc.sound_speeds(LAW, mid)[1] > V else (mid, hi)
    return lo


def test_superkink_link_with_V_alone_sets_w_plus_from_it():
    st, errors = state_from_url({"mode": "superkink", "V": "5.2", "tab": "profiles"})
    assert not errors
    assert st.V == 5.2 and st.w_plus == pytest.approx(w_plus_of_superkink(5.2), abs=1e-9)


def test_superkink_link_with_inconsistent_V_keeps_w_plus_and_says_so():
    st, errors = state_from_url({"mode": "superkink", "w_plus": "1.0", "V": "5.2"})
    assert st.w_plus == 1.0 and st.V == pytest.approx(2 * math.sqrt(65) / 3, rel=1e-12)
    assert len(errors) == 1 and "V = 5.2" in errors[0] and "5.374838499" in errors[0]


def test_w_plus_outside_the_law_range_is_refused_with_the_range():
    st, errors = state_from_url({"w_plus": "99999999999999999999999", "V": "5.1"})
    assert st.w_plus == 1.0 and st.V == 5.1 and st.problem() is None
    (msg,) = errors
    assert "w_plus" in msg and f"{LAW.beta:.10g}" in msg and "w* = 3.333333333" in msg


@pytest.mark.parametrize("raw", ["1e400", "-1e999"])
def test_an_overflowing_value_is_named_as_typed(raw):
    st, errors = state_from_url({"V": raw})
    assert st.V == 5.0
    (msg,) = errors
    assert raw in msg and "inf" not in msg
