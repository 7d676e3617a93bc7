"""Where the browser's part of a Paper click goes: every time BokehJS lays out a whole page root
again (its ``invalidate_layout``, hooked in the page), with the model whose change caused it and
the time it took.  A change of a model's visibility, CSS classes or size lays out the whole tab
again, redrawing every figure in it (0.3–1.2 s each beside the Simulation scene's figures on a
loaded machine); text and data changes do not.

Run: ``.venv/bin/python -m benchmarks.bench_layouts [LABEL ...]`` (default: the four
simulation figures).  Prints, per click, the page's wait line and each layout (seconds after
the click, its duration, the model's type, id and CSS classes).
"""

from __future__ import annotations

import sys
import time

from benchmarks.bench_waits import FIGURES, status, wait_line
from benchmarks.served import served_app

#: wraps LayoutDOMView.invalidate_layout; records the outermost call of each layout
HOOK = """
(() => {
  const P = Bokeh.require("models/layouts/layout_dom").LayoutDOMView.prototype;
  window.__layouts = []; let depth = 0;
  const orig = P.invalidate_layout;
  P.invalidate_layout = function() {
    depth++;
    const t0 = performance.now();
    try { return orig.apply(this, arguments); } finally {
      depth--;
      if (depth === 0) {
        const m = this.model;
        window.__layouts.push([t0, performance.now() - t0, m.type, m.id,
                               (m.css_classes || []).join(" ")]);
      }
    }
  };
})();
"""


def run(url: str, labels: list[str]) -> None:
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = p.chromium.launch(
            executable_path="/usr/bin/chromium",
            args=["--headless=new", "--no-sandbox", "--disable-gpu"],
        )
        pg = b.new_page(viewport={"width": 1500, "height": 1000})
        for label in labels:
            pg.goto(url + "/main?tab=paper")
            btn = pg.locator(f".paper-open-{label} button")
            btn.wait_for(timeout=120_000)
            pg.wait_for_timeout(1500)
            pg.evaluate(HOOK)
            t_page = pg.evaluate("performance.now()")
            before = status(pg, "simulation")
            t = time.monotonic()
            btn.click()
            while time.monotonic() < t + 300:
                now = status(pg, "simulation")
                if now != before and "Time:" in now and "computing the rest" not in now:
                    break
                pg.wait_for_timeout(20)
            line = wait_line(pg, "simulation", "", time.monotonic() + 10)
            pg.wait_for_timeout(1000)
            layouts = pg.evaluate("window.__layouts")
            print(f"== Paper → {label}: {line}")
            for t0, d, typ, mid, css in layouts:
                print(f"  {(t0 - t_page) / 1000:7.2f} s {d:7.1f} ms  {typ} {mid} {css[:60]}")
            total = sum(x[1] for x in layouts) / 1000
            print(f"  {len(layouts)} layouts, {total:.2f} s")
        b.close()


def main(argv: list[str] | None = None) -> int:
    labels = list(argv if argv is not None else sys.argv[1:]) or list(FIGURES)
    with served_app() as url:
        run(url, labels)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
