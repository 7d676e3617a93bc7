"""The Gaussian figure (Fig. SWdyn (a)) in the browser: the drawn profiles, space–time image and
colour bar reach the extremes of the run's data (the initial peak w = 7 of eq. GaussIC was drawn
at ≈ 4.6 when every 3rd site was kept).  The data: the same run straight from fpucore."""

from __future__ import annotations

import numpy as np
import pytest
from browser_harness import source, wait_rendered

pytestmark = pytest.mark.browser

JS_IMAGE = """() => { let out = {};
  for (const d of Bokeh.documents) { for (const m of d.all_models) {
    if (m.name === 'sim-image' && m.data) {
      const z = m.data.image[0]; const a = z.array !== undefined ? z.array : z;
      let lo = Infinity, hi = -Infinity;
      for (let i = 0; i < a.length; i++) { if (a[i] < lo) lo = a[i]; if (a[i] > hi) hi = a[i]; }
      out.img = [lo, hi]; }
    if (m.name === 'sim-colour') { out.bar = [m.low, m.high]; } } }
  return out; }"""


def test_the_swdyn_figure_draws_the_datas_extremes(page):
    from fpucore import simulate
    from fpucore.law import CubicLaw

    page.goto(f"{page.server}/main?fig=SWdyn&tab=simulation")
    text = wait_rendered(page, "simulation", 240.0)
    assert "Gaussian" in text, text
    sim = simulate.gaussian(CubicLaw(-1.0, 10.0), 1.0, 6.0, 2400, 200.0, guard="bounded",
                            max_sites_out=2400)  # fmt: skip
    z = np.asarray(sim.snapshots)
    first, last = source(page, "sim-profile-initial"), source(page, "sim-profile-final")
    assert len(first["y"]) == 2400 and max(first["y"]) == 7.0  # w_B + A at n = L/2, exactly
    assert max(last["y"]) == pytest.approx(z[-1].max(), abs=1e-9)
    assert min(last["y"]) == pytest.approx(z[-1].min(), abs=1e-9)
    drawn = page.evaluate(JS_IMAGE)
    assert drawn["img"] == pytest.approx([z.min(), z.max()], abs=1e-9)
    assert drawn["bar"] == pytest.approx([z.min(), z.max()], abs=1e-9)
