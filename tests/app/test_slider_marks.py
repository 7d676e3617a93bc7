"""V_SK under the V slider and w* under the w₊ slider: each a pane of its own placed at the
value's fraction of the slider's range, moving with the state, the slider models untouched
(a change of a slider's label, stylesheet or styles re-rendered it in the browser, whose
noUiSlider echoed back a value snapped to its step).  Reference values: the cubic's closed forms
w* = −b/(3a) and, from w₊ + w₋ = 2w* (the cubic's superkinks are symmetric about w*),
V_SK² = (f(w₋) − f(w₊)) / (w₋ − w₊)."""

from __future__ import annotations

import math

import pytest

from app.explorer import Explorer
from app.slider_marks import mark_fraction
from app.state import ExplorerState

A, B = -1.0, 10.0
W_STAR = -B / (3 * A)


def f(w: float) -> float:
    return A * w**3 + B * w**2 + w


def v_sk(w_plus: float) -> float:
    w_minus = 2 * W_STAR - w_plus
    return math.sqrt((f(w_minus) - f(w_plus)) / (w_minus - w_plus))


def fraction_of(slider, value: float) -> float:
    return (value - slider.start) / (slider.end - slider.start)


def slider_models(ex: Explorer) -> list:
    return [(s.label, list(s.stylesheets), dict(s.styles)) for s in (ex.V, ex.w_plus)]


def test_marks_sit_at_v_sk_and_w_star_and_follow_w_plus():
    ex = Explorer(ExplorerState(w_plus=1.0, V=5.0))
    assert v_sk(1.0) == pytest.approx(2 * math.sqrt(65) / 3, rel=1e-14)  # the paper's example
    for mark, slider, value in ((ex.V_mark, ex.V, v_sk(1.0)), (ex.w_plus_mark, ex.w_plus, W_STAR)):
        assert mark.pane.visible
        assert mark.fraction == pytest.approx(fraction_of(slider, value), abs=2e-6)
        assert f"{mark.name} = {value:.6g}" in mark.pane.object
    models = slider_models(ex)
    x0 = ex.V_mark.fraction
    ex.state.w_plus = 2.0  # V_SK moves with w₊, and so does its mark
    assert ex.V_mark.value == pytest.approx(v_sk(2.0), rel=1e-10)
    assert ex.V_mark.fraction == pytest.approx(fraction_of(ex.V, v_sk(2.0)), abs=2e-6)
    assert ex.V_mark.fraction != pytest.approx(x0, abs=1e-3)
    assert slider_models(ex) == models  # the sliders themselves never change for a mark


def test_a_change_that_does_not_move_a_mark_leaves_its_pane_alone():
    ex = Explorer(ExplorerState(w_plus=1.0, V=5.0))
    before = ex.V_mark.pane.object
    updates = []
    ex.V_mark.pane.param.watch(lambda e: updates.append(e.name), ["object", "visible"])
    ex.state.N = 200
    ex.state.V = 5.1
    assert updates == [] and ex.V_mark.pane.object == before


def test_no_mark_off_the_track_or_for_an_invalid_law():
    assert mark_fraction(5.0, 4.0, 6.0) == 0.5
    assert mark_fraction(7.0, 4.0, 6.0) is None and mark_fraction(math.nan, 4.0, 6.0) is None
    assert mark_fraction(None, 4.0, 6.0) is None and mark_fraction(5.0, 6.0, 6.0) is None
    ex = Explorer(ExplorerState(w_plus=1.0, V=5.0))
    ex.state.param.update(expression="w**2")  # no hardening-softening law: no V_SK, no w*
    assert not ex.V_mark.pane.visible and not ex.w_plus_mark.pane.visible


def test_a_mark_at_the_same_place_with_a_new_value_is_relabelled():
    """w* is the midpoint of the cubic's w₊ range (α, β), so a change of law leaves its mark at
    the same fraction of the slider: the label must still follow (w* = −b/(3a): 2 for a = −2,
    b = 12; 10/3 for a = −1, b = 10 — a Paper-figure click made exactly this change)."""
    ex = Explorer(ExplorerState(a=-2.0, b=12.0, w_plus=0.5, V=4.0))
    assert "w* = 2<" in ex.w_plus_mark.pane.object
    x0 = ex.w_plus_mark.fraction
    ex.state.param.update(a=-1.0, b=10.0)
    assert ex.w_plus_mark.fraction == pytest.approx(x0, abs=1e-6)  # the same place
    assert f"w* = {10 / 3:.6g}<" in ex.w_plus_mark.pane.object
    assert ex.w_plus_mark.value == pytest.approx(10 / 3, rel=1e-12)
