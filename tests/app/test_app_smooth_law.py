"""The explorer with smooth laws: the preset chooser, a slider per named constant, a refused law
keeping the previous one, the URL and "Copy as Python" with constants, the force-law scene's
marks (α, w*, β, the represented interval), without a browser.

References are independent of fpucore's class check: α, w*, β of the tanh preset
f = w + k (tanh((w − m)/s) + tanh(m/s)) − c w³ as roots of its closed-form f′ and f″ (written
out here, solved by SciPy's brentq).
"""

from __future__ import annotations

import math
import time

import param
import pytest
from scipy.optimize import brentq

pytest.importorskip("panel")

from bokeh.document import Document  # noqa: E402

from app import compute  # noqa: E402
from app.explorer import Explorer  # noqa: E402
from app.state import STATE_PARAMS, ExplorerState  # noqa: E402
from app.url_state import parse_url, url_query  # noqa: E402
from app.views.force_law import ForceLawScene  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402
from fpucore.law.presets import PRESETS  # noqa: E402
from fpucore.law.smooth import SmoothLaw  # noqa: E402

TANH = PRESETS["tanh"]
TANH_TEXT = compute.laws.join_law(TANH.text, TANH.constants_dict)


def tanh_marks(c=0.1, k=1.0, m=1.0, s=0.3) -> tuple[float, float, float]:
    """(α, w*, β) of the tanh preset: zeros of f′ = 1 + (k/s) sech²((w−m)/s) − 3c w² on each
    side of 0 and of f″ = −(2k/s²) sech² tanh − 6c w between them (closed forms)."""

    def df(w):
        return 1 + k / s / math.cosh((w - m) / s) ** 2 - 3 * c * w * w

    def ddf(w):
        u = (w - m) / s
        return -2 * k / s**2 * math.tanh(u) / math.cosh(u) ** 2 - 6 * c * w

    alpha = brentq(df, -10.0, 0.0, xtol=1e-15)
    beta = brentq(df, 0.0, 10.0, xtol=1e-15)
    w_star = brentq(ddf, 0.5, beta, xtol=1e-15)
    return alpha, w_star, beta


def settle(ex: Explorer, done, timeout: float = 120.0) -> None:
    """Wait until ``done()`` (the law worker answers in its own thread), then until the sync
    of the answer (in that thread, under the state's lock) has ended."""
    t_end = time.monotonic() + timeout
    while not done() and time.monotonic() < t_end:
        time.sleep(0.05)
    assert done(), ex.ranges.object
    with ex.state.lock:
        pass


def move(slider, value: float) -> None:
    """What a slider drag ends with: value, then value_throttled."""
    slider.value = value
    with param.edit_constant(slider):
        slider.value_throttled = value


def tanh_explorer() -> Explorer:
    ex = Explorer()
    ex.law_editor.preset.value = "tanh"
    settle(ex, lambda: "s" in ex.law_editor.const_sliders and "checking" not in ex.ranges.object)
    return ex


def test_tanh_preset_builds_the_smooth_law_with_a_slider_per_constant():
    ex = tanh_explorer()
    law = ex.law_editor
    assert ex.state.expression == TANH_TEXT
    lw = ex.state.law()
    assert isinstance(lw, SmoothLaw)
    for got, ref in zip((lw.alpha, lw.w_star, lw.beta), tanh_marks()):
        assert got == pytest.approx(ref, abs=1e-12)
    assert list(law.const_sliders) == ["c", "k", "m", "s"]
    assert [sl.value for sl in law.const_sliders.values()] == [0.1, 1.0, 1.0, 0.3]
    assert law.const_box.visible and not law.coeff_box.visible and not law.a.visible
    assert law.preset.value == "tanh" and law.law_text.value == TANH_TEXT
    # the sidebar's ranges follow the tanh law, w₊ moved into them
    assert f"{lw.beta:.5g}" in ex.ranges.object and ex.state.problem() is None
    # back to the paper's cubic: closed forms, a and b sliders
    settle(ex, lambda: True)
    law.preset.value = "cubic"
    assert ex.state.expression == "" and isinstance(ex.state.law(), CubicLaw)
    assert (ex.state.a, ex.state.b) == (-1.0, 10.0) and law.a.visible
    assert not law.const_box.visible


def test_constant_slider_rebuilds_the_law_and_the_force_scene_redraws():
    ex = tanh_explorer()
    law = ex.law_editor
    scene = ex.scene("force")
    scene.refresh()
    y_before = list(scene.r_f[1].data["y"])
    move(law.const_sliders["s"], 0.4)
    settle(ex, lambda: "s=0.4" in ex.state.expression and "checking" not in ex.ranges.object)
    assert ex.state.expression == compute.laws.join_law(
        TANH.text, {**TANH.constants_dict, "s": 0.4}
    )
    lw = ex.state.law()
    for got, ref in zip((lw.alpha, lw.w_star, lw.beta), tanh_marks(s=0.4)):
        assert got == pytest.approx(ref, abs=1e-12)
    assert law.const_sliders["s"].value == 0.4
    scene.refresh()
    assert scene.last_message is None
    assert list(scene.r_f[1].data["y"]) != y_before
    locations = sorted(sp.location for sp in scene.spans)
    assert locations == pytest.approx(sorted(tanh_marks(s=0.4)), abs=1e-12)


def test_a_refused_law_is_named_and_the_previous_law_stays():
    ex = tanh_explorer()
    law = ex.law_editor
    scene = ex.scene("force")
    scene.refresh()
    before = ex.state.expression
    move(law.const_sliders["c"], -0.1)  # f′ > 0 for every w > 0: no softening
    settle(ex, lambda: bool(law.refused) and "checking" not in ex.ranges.object)
    assert "no softening" in law.refused and "c=-0.1" in law.refused
    assert law.refusal.visible and "no softening" in law.refusal.object
    assert ex.state.expression == before and ex.state.problem() is None
    assert "checking" not in ex.ranges.object and "invalid" not in ex.ranges.object
    assert all(s.copy_btn.disabled for s in ex.scenes)
    scene.refresh()
    assert scene.last_message is None and "'c': 0.1" in scene.code.value  # still tanh
    # a typed text outside the class: refused the same way
    law.law_text.value = "log(w)"
    assert law.checking == "log(w)", law.checking
    settle(ex, lambda: "log(w)" in law.refused and "checking" not in ex.ranges.object)
    assert ex.state.expression == before
    # a valid law clears the refusal
    law.preset.value = "cubic"
    assert not law.refusal.visible and law.refused == ""
    assert not any(s.copy_btn.disabled for s in ex.scenes)


def test_url_and_copy_as_python_carry_the_constants():
    st = ExplorerState(
        expression=compute.laws.join_law(TANH.text, {**TANH.constants_dict, "s": 0.4})
    )
    q = url_query(st)
    assert q["law"].endswith("; c=0.1, k=1.0, m=1.0, s=0.4")
    values, errors = parse_url(q)
    assert errors == []
    again = ExplorerState(**values)
    assert all(getattr(again, n) == getattr(st, n) for n in STATE_PARAMS)
    assert again.law().constants == (("c", 0.1), ("k", 1.0), ("m", 1.0), ("s", 0.4))
    sc = ForceLawScene(again)
    sc.panel.get_root(Document())
    sc.refresh()
    want = (
        f"law = fpucore.law_from_expression({TANH.text!r}, "
        "constants={'c': 0.1, 'k': 1.0, 'm': 1.0, 's': 0.4})"
    )
    assert want in sc.code.value
    ns: dict = {}
    exec(sc.code.value.split("sk = ")[0], ns)  # the preamble: imports and the law
    assert (ns["law"].alpha, ns["law"].beta) == (again.law().alpha, again.law().beta)
    # a malformed constant in a link is refused with its reason
    values, errors = parse_url({"law": TANH.text + "; c=0.1, k"})
    assert "law" not in values and "law=" in errors[0] and "name=value" in errors[0]


def test_force_scene_marks_alpha_w_star_beta_and_the_represented_interval():
    st = ExplorerState(expression=TANH_TEXT, w_plus=0.5, V=2.0)
    sc = ForceLawScene(st)
    sc.panel.get_root(Document())
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    lw = st.law()
    alpha, w_star, beta = tanh_marks()
    assert [sp.location for sp in sc.spans] == pytest.approx([w_star, alpha, beta], abs=1e-12)
    assert [lab.text for lab in sc.labels] == ["w*", "α", "β"]
    lo, hi = lw.interval
    assert lo < alpha and beta < hi  # the interval covers the convex one
    assert sc.rep_box.visible and (sc.rep_box.left, sc.rep_box.right) == (lo, hi)
    assert sc.rep_label.visible and "represented" in sc.rep_label.text
    x = sc.r_f[1].data["x"]
    assert (x[0], x[-1]) == (lo, hi)  # f drawn only where it is represented
    status = sc.status.object
    assert "represented |f − f_rep|" in status and "represented" in sc.last_info.shown
    # the data file's header names the law with its constants and its represented interval
    _, buf = sc.download_data()
    head = [ln for ln in buf.getvalue().splitlines() if ln.startswith("#")]
    assert any(f"law={TANH_TEXT!r}" in ln and "|f - f_rep| <=" in ln for ln in head), head
    # the cubic: no represented interval
    st.expression = ""
    sc.refresh()
    assert not sc.rep_box.visible and not sc.rep_label.visible
