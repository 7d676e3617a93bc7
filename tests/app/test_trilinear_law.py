"""The trilinear preset in the explorer, without a browser: its five sliders, the force law drawn
with its corners, bad combinations refused with fpucore's reason (the previous law stays), the
phase plane, and the dynamic scenes' refusals shown as messages (never a failure).

The force law's reference is the trilinear law's closed form, written out here:
f = E1 w (w ≤ w1), E1 w1 + E2 (w − w1) (w1 ≤ w ≤ w2), f(w2) + E3 (w − w2) (w ≥ w2).
"""

from __future__ import annotations

import numpy as np
import param
import pytest

pytest.importorskip("panel")

from app import compute  # noqa: E402
from app.explorer import Explorer  # noqa: E402
from app.law_presets import TRILINEAR_DEFAULTS, preset_text, trilinear_text  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views.untrusted import LiteralAlert  # noqa: E402

TEXT = preset_text("trilinear")


def f_ref(w, w1, w2, E1, E2, E3):
    w = np.asarray(w, float)
    return np.where(w <= w1, E1 * w,
                    np.where(w <= w2, E1 * w1 + E2 * (w - w1), E1 * w1 + E2 * (w2 - w1)
                             + E3 * (w - w2)))  # fmt: skip


def move(slider, value: float) -> None:
    """What a slider drag ends with: value, then value_throttled."""
    slider.value = value
    with param.edit_constant(slider):
        slider.value_throttled = value


@pytest.fixture
def ex():
    compute.laws.trusted_expression_law(TEXT)  # built, as at the server's warm-up: no law worker
    ex = Explorer()
    ex.law_editor.preset.value = "trilinear"
    assert ex.state.expression == TEXT
    return ex


def drawn_force(ex, values):
    """The force scene rendered: its curve and special points against the closed form."""
    sc = ex.active_scene()
    assert sc.wait_idle(120)  # the render a change requested: none still running below
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    x, y = (np.asarray(sc.r_f[1].data[k], float) for k in ("x", "y"))
    np.testing.assert_allclose(y, f_ref(x, **values), rtol=1e-13, atol=1e-13)
    w1, w2 = values["w1"], values["w2"]
    assert w1 in x and w2 in x  # each corner sampled exactly: drawn sharp
    for lo, hi, E in ((x[0], w1, values["E1"]), (w1, w2, values["E2"]), (w2, x[-1], values["E3"])):
        seg = (x >= lo) & (x <= hi)
        np.testing.assert_allclose(np.diff(y[seg]) / np.diff(x[seg]), E, rtol=1e-9)
    pts = sc.r_pts[1].data
    corners = {lab: (float(px), float(py)) for lab, px, py in zip(pts["label"], pts["x"], pts["y"])}
    assert corners["w₁"] == pytest.approx((w1, float(f_ref(w1, **values))), rel=1e-14)
    assert corners["w₂"] == pytest.approx((w2, float(f_ref(w2, **values))), rel=1e-14)
    return sc


def test_the_preset_shows_five_sliders_and_a_slider_redraws_the_force_law(ex):
    ed = ex.law_editor
    assert ed.trilinear.box.visible and not ed.const_box.visible and not ed.coeff_box.visible
    assert {n: s.value for n, s in ed.trilinear.sliders.items()} == TRILINEAR_DEFAULTS
    drawn_force(ex, TRILINEAR_DEFAULTS)
    assert "[w₁, w₂] = [0.5, 1.5]" in ex.ranges.object
    move(ed.trilinear.sliders["w2"], 2.0)
    values = {**TRILINEAR_DEFAULTS, "w2": 2.0}
    assert ex.state.expression == trilinear_text(values)
    assert not ed.refusal.visible
    drawn_force(ex, values)
    assert ed.preset.value == "trilinear"


@pytest.mark.parametrize(
    "name, value, reason",
    [
        ("w1", 2.5, "w2 > w1 = 2.5"),  # w1 >= w2
        ("w2", 0.3, "w2 > w1 = 0.5"),
        ("E2", 0.5, "E2 > max(E1, E3) = 1"),  # E2 <= E1
        ("E1", 4.5, "E2 > max(E1, E3) = 4.5"),
        ("E3", 4.0, "E2 > max(E1, E3) = 4"),  # E2 <= E3
    ],
)
def test_a_bad_slider_combination_is_refused_with_the_reason(ex, name, value, reason):
    ed = ex.law_editor
    move(ed.trilinear.sliders[name], value)
    assert ex.state.expression == TEXT  # the previous law stays
    assert isinstance(ed.refusal, LiteralAlert) and ed.refusal.visible
    shown = ed.refusal.object.replace("&gt;", ">")
    assert reason in shown and "law refused" in shown
    assert ed.refused and reason in ed.refused


def test_a_typed_negative_modulus_is_refused_with_the_reason(ex):
    text = trilinear_text({**TRILINEAR_DEFAULTS, "E3": -0.1})
    with pytest.raises(compute.ParameterError, match="E3"):
        compute.laws.trusted_expression_law(text)
    ex.law_editor.apply(text)
    assert ex.state.expression == TEXT
    assert "negative modulus" in ex.law_editor.refused


def state() -> ExplorerState:
    compute.laws.trusted_expression_law(TEXT)
    st = ExplorerState()
    st.param.update(expression=TEXT)
    return st


def test_the_phase_plane_and_the_diagram_draw_it():
    st = state()
    for key in ("phase", "diagram"):
        sc = Explorer(st).scene(key)
        sc.refresh()
        assert sc.last_message is None, (key, sc.last_message)


@pytest.mark.parametrize("key", ["profiles", "floquet", "simulation"])
def test_the_dynamic_scenes_compute_it_or_say_why(key):
    """Discrete waves, Floquet spectra and simulations of piecewise-linear laws are computed with
    located crossings; where fpucore refuses (a method without event location) the scene shows
    that reason as its message — never a failure."""
    st = state()
    sc = Explorer(st).scene(key)
    if key == "simulation":
        sc.show_scenario("riemann", run=True, L=60, t_end=2.0, w_left=0.25, w_right=0.3)
    sc.refresh()
    msg = sc.last_message
    if msg is not None:
        assert "piecewise-linear" in msg and "computation failed" not in msg, msg
        assert "Traceback" not in msg
        assert sc.alert.visible and "piecewise-linear" in sc.alert.object


def equal_area_superkink(w_plus: float, **values) -> tuple[float, float]:
    """(w₋, V) of the QC superkink from w₊, solved here by a second route: the chord's
    equal-area condition ∫ f dw = ½ (f(w₊) + f(w₋)) (w₋ − w₊), integrated by adaptive
    quadrature split at the corners, then V² = (f(w₋) − f(w₊)) / (w₋ − w₊) (Rayleigh line)."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    def f(w):
        return float(f_ref(w, **values))

    def gap(wm):
        area = quad(f, w_plus, wm, points=[values["w1"], values["w2"]], epsabs=1e-14)[0]
        return area - 0.5 * (f(w_plus) + f(wm)) * (wm - w_plus)

    grid = np.linspace(values["w2"], 20.0, 2000)  # w₋ lies in the third (soft) regime
    g = np.array([gap(x) for x in grid])
    (i,) = np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))[:1]
    wm = brentq(gap, grid[i], grid[i + 1], xtol=1e-15)
    return wm, float(np.sqrt((f(wm) - f(w_plus)) / (wm - w_plus)))


def test_superkink_mode_follows_the_equal_area_superkink_and_computes_it():
    """Superkink mode with the trilinear preset: V is tied to V_SK(w₊) (checked against the
    equal-area construction solved in the test), the profiles scene shows the discrete superkink
    with its exact amplitude |w₋ − w₊|, and the Floquet scene gives its spectrum and a verdict."""
    st = state()
    st.param.update(N=64, w_plus=0.25)
    st.mode = "superkink"
    wm, V = equal_area_superkink(0.25, **TRILINEAR_DEFAULTS)
    assert st.V == pytest.approx(V, rel=1e-11)
    ex = Explorer(st)
    prof = ex.scene("profiles")
    prof.refresh()
    assert prof.wait_idle(600)
    prof.refresh()
    assert prof.last_message is None, prof.last_message
    shown = prof.last_info.shown
    assert shown.startswith("superkink")
    amp = float(shown.split("|w₋ − w₊| = ")[1].split()[0])
    assert amp == pytest.approx(wm - 0.25, rel=1e-5)
    assert "exact by construction" in shown
    flo = ex.scene("floquet")
    flo.refresh()
    assert flo.wait_idle(600)
    flo.refresh()
    assert flo.last_message is None, flo.last_message
    assert "superkink wave" in flo.last_info.shown and "max |μ| = " in flo.last_info.shown
