"""The law chooser in the browser: the tanh preset, a constant slider moved, and the force-law
scene redrawn with its α, w*, β marks and the represented interval; a screenshot is kept."""

from __future__ import annotations

import os
import time

import pytest
from browser_harness import (
    FAST,
    TIMEOUT_MS,
    app_tracebacks,
    open_app,
    wait_rendered,
    wait_status_change,
    wait_url,
)

from fpucore.law import law_from_expression
from fpucore.law.presets import PRESETS

pytestmark = pytest.mark.browser

JS_MARKS = """() => {
  const doc = Bokeh.documents[Bokeh.documents.length - 1];
  const out = {};
  for (const n of ["w_star", "alpha", "beta"]) {
    const m = doc.get_model_by_name("force-" + n);
    out[n] = m ? m.location : null;
  }
  const box = doc.get_model_by_name("force-represented");
  out.rep = box ? [box.left, box.right, box.visible] : null;
  return out;
}"""


def marks(page) -> dict:
    return page.evaluate(JS_MARKS)


def law_of(q: dict):
    expr, _, rest = q["law"].partition(";")
    consts = {k.strip(): float(v) for k, v in (p.split("=") for p in rest.split(","))}
    return law_from_expression(expr.strip(), consts)


def wait_marks(page, lw, timeout: float = 60.0) -> dict:
    want = {"w_star": lw.w_star, "alpha": lw.alpha, "beta": lw.beta}
    t_end = time.monotonic() + timeout
    while time.monotonic() < t_end:
        got = marks(page)
        if all(got[k] is not None and abs(got[k] - v) < 1e-12 for k, v in want.items()):
            return got
        page.wait_for_timeout(200)
    raise AssertionError(f"marks {marks(page)} never reached {want}")


def test_tanh_preset_and_a_constant_slider_redraw_the_force_law(page):
    open_app(page, FAST)
    tanh = PRESETS["tanh"]
    page.locator(".w-law-preset select").select_option(label=f"tanh: {tanh.description}")
    q = wait_url(page, lambda q: q.get("law", "").startswith(tanh.text), TIMEOUT_MS / 1000)
    assert q["law"] == tanh.text + "; c=0.1, k=1.0, m=1.0, s=0.3", q
    lw = law_of(q)
    text = wait_rendered(page, "force", 120.0)
    t_end = time.monotonic() + 120
    while "represented" not in text and time.monotonic() < t_end:
        page.wait_for_timeout(200)
        text = wait_rendered(page, "force", 120.0)
    assert "represented |f − f_rep|" in text and f"law={q['law']}" in text, text
    got = wait_marks(page, lw)
    assert got["rep"] == [lw.interval[0], lw.interval[1], True], got
    # the width s one slider step up: a new law, built in the law worker, drawn
    before = text
    old = tanh.text + "; c=0.1, k=1.0, m=1.0, s=0.3"
    for _ in range(3):  # a key press while the sidebar syncs is dropped (the editor is muted)
        page.wait_for_timeout(3000)
        page.locator(".w-const-s .noUi-handle").first.focus()
        page.keyboard.press("ArrowRight")
        q = wait_url(page, lambda q: q.get("law", old) != old, 30.0)
        if q.get("law", old) != old:
            break
    assert "s=0.3" in q["law"] and q["law"].startswith(tanh.text), q
    lw2 = law_of(q)
    after = wait_status_change(page, "force", before)
    t_end = time.monotonic() + 120
    while f"law={q['law']}" not in after and time.monotonic() < t_end:
        page.wait_for_timeout(200)
        after = wait_rendered(page, "force", 120.0)
    assert f"law={q['law']}" in after, (q, after)
    got = wait_marks(page, lw2)
    assert lw2.beta != lw.beta, q
    assert got["beta"] != lw.beta and got["rep"][:2] == list(lw2.interval), (got, q)
    page.wait_for_timeout(2000)  # a follow-up render (V moved into the new law's range)
    wait_rendered(page, "force", 120.0)
    shot = os.environ.get("FPU_SCREENSHOT", "/tmp/force_law_tanh.png")
    page.locator(".scene-force").first.screenshot(path=shot)
    assert not app_tracebacks(), app_tracebacks()[-1][-2000:]
