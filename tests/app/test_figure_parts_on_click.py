"""A Paper-tab click opens the whole figure: the parts a scene otherwise computes on a button —
the discrete dots of Figs. SWamp/SWenergy_cubic_DvsQC, the Floquet sweeps of Figs. floquet_SK and
floquet_cubicSW — are computed as part of the click (before, the click drew the QC curves or one
spectrum, and the figure's dots or sweep needed a button the user had to find).  What a view
does not show at all is named in its note (Fig. cubic (a))."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")

from bokeh.document import Document  # noqa: E402

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


def scene_after_click(label: str, key: str, k: int):
    st = ExplorerState()
    sc = BY_KEY[key](st)
    sc.panel.get_root(Document())
    if key == "floquet":
        sc.n_sweep.value = k  # fewer velocities than the default 12: a test's budget
    else:
        sc.n_discrete.value = k
    st.show_figure(label)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    return st, sc


@pytest.mark.slow
@pytest.mark.parametrize("label", ["floquet_cubicSW", "floquet_SK"])
def test_a_floquet_figure_click_runs_its_sweep(label):
    st, sc = scene_after_click(label, "floquet", 3)
    assert sc._sweep_result is not None and np.asarray(sc._sweep_result.V).size == 3
    drawn = sum(len(src.data["x"]) for _, src in sc.r_cls.values())
    assert drawn == 3 or "did not converge" in sc.status.object
    # the user moves on (another N: another family): the figure is left, and the sweep of the
    # new family waits for the button
    st.N = 400
    assert st.figure == ""
    sc.refresh()
    assert sc._sweep_result is None


@pytest.mark.slow
@pytest.mark.parametrize("label", ["SWamp_cubic_DvsQC", "SWenergy_cubic_DvsQC"])
def test_a_discrete_vs_qc_figure_click_adds_the_discrete_dots(label):
    st, sc = scene_after_click(label, "diagram", 2)
    dots = sc.panels["amp"]["dots"][1].data["x"]
    assert len(dots) >= 2, dots  # the figure's discrete dots, without the button
    assert "press 'Add discrete points'" not in sc.status.object


def test_a_click_on_another_figure_computes_no_part():
    st, sc = scene_after_click("SWamp_energy_QCcubic", "diagram", 2)
    assert len(sc.panels["amp"]["dots"][1].data["x"]) == 0
    assert "press 'Add discrete points'" in sc.status.object


def test_the_figure_whose_panel_no_scene_draws_names_it():
    st = ExplorerState()
    st.show_figure("cubic")
    assert "Fig. cubic (a)" in st.note and "no scene" in st.note
