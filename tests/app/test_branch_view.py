"""The branch view (Diagrams scene, panel (b)): the family's Floquet sweep draws each wave's
discrete E_ren in its stability class's colour, and a click on a point opens that wave."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")

from bokeh.events import Tap  # noqa: E402

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402
from fpucore import wave  # noqa: E402
from fpucore.floquet import CLASSES  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


@pytest.fixture(scope="module")
def classified():
    sc = BY_KEY["diagram"](ExplorerState(N=128))
    sc.n_discrete.value = 2  # 2 velocities per interval: 4 waves
    sc.classify_btn.clicks += 1  # "Classify stability (Floquet)"
    assert sc.wait_idle(600)
    assert sc.last_message is None, sc.last_message
    return sc


def test_every_classified_wave_is_drawn_in_its_class(classified):
    sc = classified
    sw = sc._branch
    assert sw is not None and len(sw.V) == 4
    drawn = {}
    for c in CLASSES:
        src = sc.r_branch[c][1]
        for V, E in zip(src.data["x"], src.data["y"]):
            drawn[float(V)] = (c, float(E))
    assert sorted(drawn) == sorted(float(v) for v in sw.V)
    for V, E, c in zip(sw.V, sw.energy, sw.classification):
        assert drawn[float(V)] == (c, float(E))
    # E_ren of a drawn point is the discrete wave's own (an independent solve at that V)
    r = wave.solve_solitary(CubicLaw(-1.0, 10.0), 1.0, float(sw.V[0]), N=128, tol=1e-10)
    assert float(sw.energy[0]) == pytest.approx(r.energy, abs=10 * r.energy_error + 1e-9)
    assert "from fpucore.atlas import sweep\nsw = sweep(law, kind='solitary'" in sc.python_code()
    assert "branch view (N = 128)" in sc.status.object


def test_a_click_on_a_point_opens_that_wave_and_elsewhere_nothing(classified):
    sc = classified
    sw = sc._branch
    k = 2
    x, y = float(sw.V[k]), float(sw.energy[k])
    xs, ys = sc.fig_e.x_range, sc.fig_e.y_range
    far = (x, y + 0.2 * (ys.end - ys.start))
    V0 = sc.state.V
    sc._on_branch_tap(Tap(sc.fig_e, x=far[0], y=far[1]))
    assert sc.state.V == V0  # a click away from every point picks nothing
    near = (x + 0.01 * (xs.end - xs.start), y)
    sc._on_branch_tap(Tap(sc.fig_e, x=near[0], y=near[1]))
    assert sc.state.V == x and sc.state.w_plus == 1.0  # that wave is the current one
    assert np.isfinite(sc.state.V)
    # in superkink mode a click opens the solitary wave too (the branch is the solitary family's)
    sc.state.mode = "superkink"
    sc._on_branch_tap(Tap(sc.fig_e, x=near[0], y=near[1]))
    assert sc.state.mode == "solitary" and sc.state.V == x
