"""The Floquet scene in the page: the plot follows N, the sweep, the unit circle and the panel
layout at every window width.
"""

from __future__ import annotations

import time

import pytest
from browser_harness import (
    FAST,
    app_tracebacks,
    check_consistent,
    query,
    run_floquet_sweep,
    settled,
    source,
    status,
    status_text,
)

pytestmark = pytest.mark.browser


def test_floquet_plot_follows_N_and_shows_the_sweep_without_reload(page):
    """N = 200 → three key presses; the plot holds the new 2N multipliers."""
    page.goto(f"{page.server}/main?tab=floquet&N=200&tol=1e-08")
    text, msg, q = settled(page, 240)
    check_consistent(page, text, msg, q)
    handle = page.locator(".w-N .noUi-handle").first
    handle.focus()
    for _ in range(3):
        page.keyboard.press("ArrowRight")
    t_end = time.monotonic() + 60
    while query(page).get("N") != "206" and time.monotonic() < t_end:
        page.wait_for_timeout(100)
    text, msg, q = settled(page, 240)
    assert q["N"] == "206" and "N = 206: 412 multipliers" in text, text
    check_consistent(page, text, msg, q)
    run_floquet_sweep(page, 6)  # the total: 3 velocities on each interval
    assert len(source(page, "floquet-sweep")["x"]) >= 1  # panel (c) without a reload
    # the energy criterion on (c): E_ren is monotone along w₊ = 1, so no mark
    t_end = time.monotonic() + 60
    while "Energy criterion" not in status_text(page, "floquet") and time.monotonic() < t_end:
        page.wait_for_timeout(200)
    assert "no minimum or maximum" in status_text(page, "floquet")
    assert source(page, "floquet-energy-extremum")["x"] == []
    assert not app_tracebacks()


# ----------------------------------------------------------------------- Floquet figures' layout
# Records, per canvas, the box (canvas px) of every text drawn since the canvas was last cleared
# whole (BokehJS clears a plot's canvas before each repaint): the tick labels as drawn.
CANVAS_TEXT_HOOK = """(() => {
  const logs = new WeakMap();
  window.__canvasTexts = (canvas) => logs.get(canvas) || [];
  const P = CanvasRenderingContext2D.prototype, fill = P.fillText, clear = P.clearRect;
  P.clearRect = function (x, y, w, h) {
    if (x <= 0 && y <= 0 && x + w >= this.canvas.width && y + h >= this.canvas.height) {
      logs.set(this.canvas, []);
    }
    return clear.apply(this, arguments);
  };
  P.fillText = function (text, x, y) {
    const m = this.measureText(text), t = this.getTransform();
    const pts = [[-m.actualBoundingBoxLeft, -m.actualBoundingBoxAscent],
                 [m.actualBoundingBoxRight, -m.actualBoundingBoxAscent],
                 [-m.actualBoundingBoxLeft, m.actualBoundingBoxDescent],
                 [m.actualBoundingBoxRight, m.actualBoundingBoxDescent]]
      .map(([u, v]) => [t.a * (x + u) + t.c * (y + v) + t.e, t.b * (x + u) + t.d * (y + v) + t.f]);
    const xs = pts.map(p => p[0]), ys = pts.map(p => p[1]);
    if (!logs.has(this.canvas)) logs.set(this.canvas, []);
    logs.get(this.canvas).push({text: String(text),
      box: [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)]});
    return fill.apply(this, arguments);
  };
})();"""

# The Floquet figures as BokehJS laid them out: per panel letter its element's page box, its
# frame (canvas px), the pixels per unit of x and of y, and the numeric x tick labels drawn
# under the frame (their boxes in CSS px).
JS_FLOQUET_FIGURES = """() => {
  const out = {}, seen = new Set();
  const walk = (v) => {
    if (!v || seen.has(v)) return;
    seen.add(v);
    const t = v.model && v.model.title && v.model.title.text;
    const letter = typeof t === "string" && /^\\(([a-d])\\)/.exec(t);
    if (letter && v.model.visible) {
      const f = v.frame.bbox, r = v.el.getBoundingClientRect(), dpr = window.devicePixelRatio;
      const texts = window.__canvasTexts(v.canvas_view.primary.canvas)
        .map(s => ({text: s.text, box: s.box.map(z => z / dpr)}));
      out[letter[1]] = {
        el: [r.left, r.top, r.right, r.bottom], frame: [f.x0, f.y0, f.x1, f.y1],
        px_per_x: Math.abs(v.frame.x_scale.compute(1) - v.frame.x_scale.compute(0)),
        px_per_y: Math.abs(v.frame.y_scale.compute(1) - v.frame.y_scale.compute(0)),
        xlabels: texts.filter(s => s.box[1] >= f.y1 - 1
          && /^[−-]?[0-9.]+(e[−+-]?[0-9]+)?$/.test(s.text)).sort((p, q) => p.box[0] - q.box[0]),
      };
    }
    for (const c of v.children()) walk(c);
  };
  for (const v of Bokeh.index) walk(v);
  return out;
}"""

#: window widths: wide, the test default (both fit side by side in its 800 px main column), and
#: two where (b) wraps below (a).  (Below ~1100 px, or 760 px with the sidebar closed, one
#: square figure is wider than the main column.)
WINDOW_WIDTHS = (1920, 1500, 1280, 1150)


def floquet_figures_at(page, width: int) -> dict:
    """JS_FLOQUET_FIGURES once the layout at this window width has settled (two equal reads)."""
    page.set_viewport_size({"width": width, "height": 1000})
    t_end = time.monotonic() + 20
    last = None
    while time.monotonic() < t_end:
        page.wait_for_timeout(300)
        now = page.evaluate(JS_FLOQUET_FIGURES)
        if now == last and now.get("a", {}).get("xlabels"):
            return now
        last = now
    raise AssertionError(f"Floquet figures did not settle at width {width}: {last}")


def open_floquet(page, query: str) -> None:
    page.add_init_script(CANVAS_TEXT_HOOK)
    page.goto(f"{page.server}/main?tab=floquet&{query}")
    settled(page, 240)


def test_floquet_unit_circle_is_a_circle_at_every_window_width(page):
    """Panels (a) and (b) draw the complex plane with as many pixels per unit of Re μ as of
    Im μ (the unit circle is round), their frames square, at every width; they never run into
    the status column (narrower than both, (b) goes below (a))."""
    open_floquet(page, f"V=4.5&{FAST}")
    for width in WINDOW_WIDTHS:
        figs = floquet_figures_at(page, width)
        for p in "ab":
            f = figs[p]
            x0, y0, x1, y1 = f["frame"]
            # equal x and y spans (set by the scene) in a square frame: within 0.5 %
            assert abs(f["px_per_x"] / f["px_per_y"] - 1) < 5e-3, (width, p, f)
            assert abs((x1 - x0) - (y1 - y0)) <= 1, (width, p, f["frame"])
            assert f["el"][2] <= page.evaluate("() => innerWidth"), (width, p, f["el"])
        a, b = figs["a"]["el"], figs["b"]["el"]
        assert b[0] >= a[2] - 1 or b[1] >= a[3] - 1, (width, a, b)  # beside or below
        side = status(page, "floquet").bounding_box()
        assert max(a[2], b[2]) <= side["x"] + 1, (width, a, b, side)
    assert not app_tracebacks()


def test_floquet_tick_labels_never_run_together(page):
    """The x tick labels of (a) and (b) as drawn on the canvas: at least two each, every one
    clear of its neighbour by more than a digit's width (8 px at the 11 px tick font).  At
    w₊ = 1, V = 4.5 the zoom (b) spans ~6e-6: labels of 7–8 digits ("0.969312")."""
    open_floquet(page, f"V=4.5&{FAST}")
    for width in WINDOW_WIDTHS:
        figs = floquet_figures_at(page, width)
        for p in "ab":
            labels = figs[p]["xlabels"]
            assert len(labels) >= 2, (width, p, labels)
            for left, right in zip(labels, labels[1:]):
                gap = right["box"][0] - left["box"][2]
                assert gap >= 8, (width, p, left["text"], right["text"], gap)
    assert not app_tracebacks()


def test_floquet_panels_are_in_the_order_a_b_c_d(page):
    """After a sweep all four panels show, top to bottom (a), (b), (c), (d) ((b) beside (a)
    or below it)."""
    open_floquet(page, FAST)
    run_floquet_sweep(page, 3)
    for width in (1500, 1150):
        figs = floquet_figures_at(page, width)
        assert set(figs) == set("abcd"), (width, sorted(figs))
        a, b, c, d = (figs[p]["el"] for p in "abcd")
        assert b[0] >= a[2] - 1 or b[1] >= a[3] - 1, (width, a, b)
        assert max(a[3], b[3]) <= c[1] + 1 and c[3] <= d[1] + 1, (width, a, b, c, d)
    assert not app_tracebacks()
