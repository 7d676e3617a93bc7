"""The Simulation scene draws the extremes of the data it summarizes (paper Fig. SWdyn): the
profiles at every site, the space–time image by blocks that keep each block's extreme, the
colour bar over the whole field, and any reduction stated in the figure's title."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("panel")

from app.paper_figures import FIGURE_SCENARIO  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views.simulation import SimulationScene  # noqa: E402
from fpucore import simulate  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402


def gaussian_scene(w_B: float, A: float, L: int, t_end: float) -> SimulationScene:
    sc = SimulationScene(ExplorerState())
    sc.show_scenario("gaussian", run=True, L=L, t_end=t_end, guard="bounded", w_B=w_B, A=A)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    return sc


def drawn(src, col="y"):
    return np.asarray(src.data[col], float)


@pytest.mark.parametrize("w_B, A", [(1.0, 6.0), (6.0, -6.0)])  # Fig. SWdyn (a) and (b)
def test_the_gaussian_figures_draw_the_datas_extremes(w_B, A):
    sc_ = FIGURE_SCENARIO["SWdyn"]
    L, t_end = sc_["L"], 40.0  # the figure's chain; a shorter run (the waves have formed)
    sc = gaussian_scene(w_B, A, L, t_end)
    # the same run straight from fpucore, every site kept
    sim = simulate.gaussian(CubicLaw(-1.0, 10.0), w_B, A, L, t_end, guard="bounded",
                            max_sites_out=L)  # fmt: skip
    z = np.asarray(sim.snapshots)
    # eq. GaussIC: the peak (dip) of the initial data is w_B + A at n = L/2, exactly
    w0 = drawn(sc.r_first[1])
    assert w0.size == L
    peak = w0.max() if A > 0 else w0.min()
    assert peak == pytest.approx(w_B + A, abs=1e-12)
    assert drawn(sc.r_first[1], "x")[np.argmax(np.abs(w0 - w_B))] == L / 2
    # the final profile is the run's final field, site by site
    np.testing.assert_allclose(drawn(sc.r_last[1]), z[-1], rtol=0, atol=1e-9)
    # the image: its extremes are the field's, and so is the colour bar
    img = np.asarray(sc.img_src.data["image"][0], float)
    assert img.shape[1] <= 1000
    assert img.max() == pytest.approx(z.max(), abs=1e-9)
    assert img.min() == pytest.approx(z.min(), abs=1e-9)
    assert (sc.mapper.low, sc.mapper.high) == pytest.approx((z.min(), z.max()), abs=1e-9)
    # ... and it covers the chain (sites 1 … L) with the blocks the title names
    k = math.ceil(L / 500)
    x0, dw = sc.img_src.data["x"][0], sc.img_src.data["dw"][0]
    assert x0 == 0.5 and x0 + dw >= L + 0.5 and dw == img.shape[1] * k / 2
    assert f"each block of {k} sites drawn as its min and max" in sc.fig_img.title.text
    assert "every site" in sc.fig_prof.title.text


def test_a_chain_that_fits_is_drawn_unreduced():
    sc = gaussian_scene(1.0, 6.0, 600, 5.0)
    img = np.asarray(sc.img_src.data["image"][0], float)
    assert img.shape[1] == 600 and "block of" not in sc.fig_img.title.text
    assert drawn(sc.r_first[1]).max() == pytest.approx(7.0, abs=1e-12)


def test_the_notebook_and_the_exported_figure_draw_the_same_field():
    sc = gaussian_scene(1.0, 6.0, 2400, 10.0)
    assert "max_sites_out=2400" in sc.python_code()
    assert "extreme_blocks(z, n, 1000)" in sc.notebook_plot()
    # the notebook's plot cell on the notebook's own run draws the image on screen
    ns: dict = {}
    import matplotlib

    matplotlib.use("Agg")
    code = sc.python_code() + "\n" + sc.notebook_plot()
    exec(compile(code, "notebook", "exec"), ns)  # noqa: S102
    np.testing.assert_allclose(ns["b"].image, sc.img_src.data["image"][0], atol=1e-9)
    svg = sc.export_figure("svg")
    assert b"<svg" in svg[:400] or b"<svg" in svg
