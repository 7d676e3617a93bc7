"""Held curves belong to the state and travel in the URL (``hold=``): a link reproduces them,
a bad entry is refused by name with its valid range (the rest kept), Hold and Clear rewrite the
URL, and a page built from a link recomputes the held curves (closed forms checked)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("panel")

from app.state import (  # noqa: E402
    MAX_HELD,
    ExplorerState,
    HeldWave,
    state_from_url,
    url_query,
)
from app.views.phase_plane import PhasePlaneScene  # noqa: E402
from app.views.profiles import ProfilesScene  # noqa: E402
from fpucore import qc  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402

LAW = CubicLaw(-1.0, 10.0)
# the paper's speeds at w₊ = 1 (captions of Figs. SWs_cubic, SWamp_energy_QCcubic)
C_PLUS, V_SK, C_MINUS = 3 * math.sqrt(2), 2 * math.sqrt(65) / 3, 11 / 2


def profiles(state: ExplorerState) -> ProfilesScene:
    sc = ProfilesScene(state)
    sc.show_discrete.value = False  # QC only: the held curves are closed forms
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    return sc


def test_a_link_round_trip_keeps_every_held_wave():
    st = ExplorerState(w_plus=1.0, V=5.0)
    waves = [
        HeldWave("solitary", 1.0, 5.2),  # at the state's w₊: written as its V alone
        HeldWave("solitary", 6.0, 5.3),  # at another w₊: V@w₊
        HeldWave("superkink", 0.6327161199294542),  # a superkink: sk@w₊
    ]
    st.held = waves
    q = url_query(st)
    assert q["hold"] == "5.2,5.3@6.0,sk@0.6327161199294542"
    again, errors = state_from_url(q)
    assert errors == [] and again.held == waves
    assert url_query(again) == q
    # the short form follows the state's w₊: moved, the URL names each wave's own w₊
    st.w_plus = 1.5
    assert url_query(st)["hold"].startswith("5.2@1.0,5.3@6.0,")


def test_hold_values_are_read_at_the_links_w_plus():
    st, errors = state_from_url({"w_plus": "6.0", "V": "5.0", "hold": "4.0, 5.3 ,5.36"})
    assert errors == []
    assert st.held == [HeldWave("solitary", 6.0, V) for V in (4.0, 5.3, 5.36)]


def test_a_bad_hold_entry_is_refused_by_name_and_the_rest_kept():
    st, errors = state_from_url({"V": "5.1", "N": "300", "hold": "5.0,5.9,abc,sk,5.2,sk@7.5,5.0@x"})
    assert st.V == 5.1 and st.N == 300  # the link's other values are kept
    assert st.held == [HeldWave("solitary", 1.0, 5.0), HeldWave("solitary", 1.0, 5.2)]
    text = "\n".join(errors)
    assert len(errors) == 5, text
    # V = 5.9 beyond c₋ = 11/2: named with both velocity intervals of the paper's w₊ = 1
    want = f"({C_PLUS:.10g}, {V_SK:.10g}) or ({V_SK:.10g}, {C_MINUS:.10g})"
    assert f"hold=5.9 is out of range: valid {want}" in text
    assert "hold='abc' is not valid" in text and "hold='sk' is not valid" in text
    assert "V, V@w_plus or sk@w_plus" in text
    # a superkink needs w₊ in (α, β) = the zeros of f' (eq. cubic_more)
    beta = (10 + math.sqrt(100 + 3)) / 3  # (b + √(b² + 3|a|)) / (3|a|)
    assert "hold=7.5 is out of range: valid (alpha, beta) = (" in text
    assert f"{beta:.10g})" in text
    assert "hold='x' is not valid" in text
    assert all(e.startswith("URL value ignored: ") for e in errors)


def test_more_than_six_held_curves_keep_the_newest_and_say_so():
    Vs = [4.5, 4.6, 4.7, 4.8, 4.9, 5.0, 5.1, 5.2]
    st, errors = state_from_url({"hold": ",".join(map(str, Vs))})
    assert MAX_HELD == 6 and [h.V for h in st.held] == Vs[-6:]
    assert len(errors) == 1 and "at most 6" in errors[0] and "(4.5, 4.6) let go" in errors[0]


def test_holding_a_seventh_curve_lets_the_oldest_go_with_a_note():
    st = ExplorerState()
    for V in (4.5, 4.6, 4.7, 4.8, 4.9, 5.0, 5.1):
        st.hold(HeldWave("solitary", 1.0, V))
    assert [h.V for h in st.held] == [4.6, 4.7, 4.8, 4.9, 5.0, 5.1]
    assert "V = 4.5, w₊ = 1 let go" in st.note
    st.hold(HeldWave("solitary", 1.0, 4.8))  # held again: it moves to the newest
    assert [h.V for h in st.held] == [4.6, 4.7, 4.9, 5.0, 5.1, 4.8]


def test_hold_and_clear_rewrite_the_url():
    st = ExplorerState(w_plus=1.0, V=5.0)
    sc = profiles(st)
    assert "hold" not in url_query(st)
    assert sc.held.hold() and sc.wait_idle()
    st.V = 5.2
    sc.refresh()
    assert sc.held.hold() and sc.wait_idle()
    assert url_query(st)["hold"] == "5.0,5.2"
    again, errors = state_from_url(url_query(st))
    assert not errors and again.held == st.held
    sc.held.clear_btn.clicks += 1
    sc.wait_idle()
    assert st.held == [] and "hold" not in url_query(st)


def test_a_link_with_held_curves_draws_them_recomputed():
    """The page built from ``hold=`` draws each held wave's closed-form profile (eq.
    SWsoln_cubic via fpucore.qc; superkink eq. SKsoln_cubic) and its phase-plane orbit."""
    st, errors = state_from_url(
        {"tab": "profiles", "V": "5.0", "hold": "4.6,5.37,sk@0.6327161199294542"}
    )
    assert not errors
    sc = profiles(st)
    for k, (mode, V) in enumerate([("solitary", 4.6), ("solitary", 5.37), ("superkink", 5.2)]):
        src = sc.held.lines[k][1]
        x, y = np.asarray(src.data["x"]), np.asarray(src.data["y"])
        assert len(x) == 1601 and sc.held.lines[k][0].visible
        if mode == "solitary":
            exact = qc.solitary(LAW, 1.0, V).profile(x)
        else:
            sk = qc.superkink_from_V(LAW, V)
            assert sk.w_plus == pytest.approx(0.6327161199294542, abs=1e-12)
            exact = sk.profile(x)
            # the plateaus: w₊ ahead, w₋ = 20/3 − w₊ behind (equal-area rule of the cubic)
            assert {round(y.min(), 6), round(y.max(), 6)} == {
                round(0.6327161199294542, 6),
                round(20 / 3 - 0.6327161199294542, 6),
            }
        assert np.max(np.abs(y - exact)) < 1e-12
    assert not sc.held.lines[3][0].visible
    code = sc.python_code()
    assert "held.append((qc.solitary(law, 1.0, 4.6), None))" in code
    assert "held.append((qc.superkink_from_w_plus(law, 0.6327161199294542), None))" in code
    # the phase plane draws the same held waves: the homoclinic orbit at V = 4.6 keeps H fixed
    pp = PhasePlaneScene(st)
    pp.refresh()
    assert pp.last_message is None
    orbit = qc.phase.phase_plane(LAW, 1.0, 4.6).orbits[0]
    held = np.asarray(pp.held.lines[0][1].data["x"])
    assert np.array_equal(held[: len(orbit.w)], orbit.w)
    assert [pp.held.lines[k][0].visible for k in range(4)] == [True, True, True, False]


def test_a_held_wave_the_new_law_has_not_is_named_and_kept():
    st, errors = state_from_url({"V": "5.0", "hold": "5.45"})
    assert not errors
    sc = profiles(st)
    assert sc.held.lines[0][0].visible
    st.b = 9.5  # c₋ at w₊ = 1 drops below 5.45 (c₋ = (b + 1)/2): no such solitary wave
    sc.refresh()
    assert not sc.held.lines[0][0].visible
    assert any("held V = 5.45, w₊ = 1: not drawn" in n for n in sc.last_info.notes)
    assert st.held == [HeldWave("solitary", 1.0, 5.45)]  # back to b = 10, it is drawn again
    st.b = 10.0
    sc.refresh()
    assert sc.held.lines[0][0].visible
