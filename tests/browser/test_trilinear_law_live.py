"""The trilinear preset in the browser: chosen, its w2 slider moved by a key press, and the
force law redrawn with its corners at the new breakpoints (the browser's copy of the curve and
of the special points), the URL carrying the law's text."""

from __future__ import annotations

import time

import pytest
from browser_harness import (
    FAST,
    TIMEOUT_MS,
    app_tracebacks,
    open_app,
    source,
    wait_rendered,
    wait_url,
)

from app.law_presets import TRILINEAR_DESCRIPTION, trilinear_values
from fpucore.law import law_from_expression

pytestmark = pytest.mark.browser


def wait_corners(page, values: dict, timeout: float = 120.0) -> dict:
    """Wait until the browser draws f with corners at (w1, f(w1)), (w2, f(w2)) of ``values``
    (the closed form f = E1 w, E1 w1 + E2 (w − w1), …)."""
    w1, w2, E1, E2 = (values[k] for k in ("w1", "w2", "E1", "E2"))
    want = {w1: E1 * w1, w2: E1 * w1 + E2 * (w2 - w1)}
    t_end = time.monotonic() + timeout
    curve = pts = None
    while time.monotonic() < t_end:
        curve, pts = source(page, "force-curve"), source(page, "force-special-points")
        if curve and pts and all(
            w in curve["x"] and w in pts["x"]
            and abs(curve["y"][curve["x"].index(w)] - f) <= 1e-12 * max(1.0, abs(f))
            for w, f in want.items()
        ):  # fmt: skip
            return curve
        page.wait_for_timeout(200)
    raise AssertionError(f"corners {want} never drawn: points {pts}")


def test_trilinear_preset_and_its_w2_slider_redraw_the_force_law(page):
    open_app(page, FAST)
    page.locator(".w-law-preset select").select_option(label=f"trilinear: {TRILINEAR_DESCRIPTION}")
    q = wait_url(page, lambda q: q.get("law", "").startswith("trilinear("), TIMEOUT_MS / 1000)
    first = trilinear_values(q.get("law", ""))
    assert first == {"w1": 0.5, "w2": 1.5, "E1": 1.0, "E2": 4.0, "E3": 0.2}, q
    text = wait_rendered(page, "force", 120.0)
    wait_corners(page, first)
    old = q["law"]
    for _ in range(3):  # a key press while the sidebar syncs is dropped (the editor is muted)
        page.wait_for_timeout(2000)
        page.locator(".w-pl-w2 .noUi-handle").first.focus()
        page.keyboard.press("ArrowRight")
        q = wait_url(page, lambda q: q.get("law", old) != old, 30.0)
        if q.get("law", old) != old:
            break
    values = trilinear_values(q.get("law", ""))
    assert values is not None and values["w2"] > first["w2"], q
    assert {k: v for k, v in values.items() if k != "w2"} == {
        k: v for k, v in first.items() if k != "w2"
    }
    law_from_expression(q["law"])  # the URL's text is the law itself
    wait_corners(page, values)
    t_end = time.monotonic() + 60
    while f"w2={values['w2']!r}" not in text and time.monotonic() < t_end:
        page.wait_for_timeout(200)
        text = wait_rendered(page, "force", 60.0)
    assert f"w2={values['w2']!r}" in text, text  # the status line's law is the new one
    assert not app_tracebacks(), app_tracebacks()[-1][-2000:]
