"""The branch view (Diagrams scene, panel (b)): the family's Floquet sweep draws each wave's
discrete E_ren in its stability class's colour, and a click on a point opens that wave."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")

from bokeh.events import Tap  # noqa: E402

from app import compute  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402
from fpucore import floquet, wave  # noqa: E402
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
    assert "\nsw = atlas.sweep(law, kind='solitary'" in sc.python_code()
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


# ---------------------------------------------------------------- the superkink family (d)
A, B = -1.0, 10.0


def sk_amplitude(V: float) -> float:
    """|w₋ − w₊| = 2√((c_max² − V²)/|a|), c_max² = 1 + b²/(3|a|) (eqs. wpm_cubic, cubic_cond2),
    evaluated independently of fpucore."""
    return 2.0 * np.sqrt((1.0 + B * B / (3 * abs(A)) - V * V) / abs(A))


def v_sk(w_plus: float) -> float:
    ws = B / (3 * abs(A))
    return float(np.sqrt(1 + B * B / (3 * abs(A)) - abs(A) * (w_plus - ws) ** 2))


@pytest.fixture(scope="module")
def superkinks():
    """Superkink mode (w₊ of the paper's V = 5.2 example), N = 64, 4 superkinks.  The cache is
    emptied first: another test of the session may have swept the same superkinks, and a cached
    sweep is drawn without the click."""
    compute.CACHE.clear()
    sc = BY_KEY["diagram"](ExplorerState(N=64, mode="superkink", w_plus=0.6327161199294542))
    sc.n_discrete.value = 2  # 2k = 4 velocities over the superkink interval
    sc.refresh()
    assert sc._sk_branch is None and not sc.fig_sk.visible  # nothing computed before the click
    sc.classify_btn.clicks += 1  # "Classify stability (Floquet)"
    assert sc.wait_idle(600)
    assert sc.last_message is None, sc.last_message
    return sc


def test_every_classified_superkink_is_drawn_in_its_class(superkinks):
    sc = superkinks
    sk, amp, branch = sc._sk_branch
    assert branch == "lower" and len(sk.V) == 4 and sc.fig_sk.visible
    assert sc._branch is None  # superkink mode sweeps the superkinks, not the solitary family
    # the velocities cover the paper's superkink interval 4.78423 < V < 5.85947
    assert 4.78423 < min(sk.V) and max(sk.V) < 5.85947
    drawn = {}
    for c in CLASSES:
        src = sc.r_sk[c][1]
        assert sc.r_sk[c][0].visible == (len(src.data["x"]) > 0)
        for V, y in zip(src.data["x"], src.data["y"]):
            drawn[float(V)] = (c, float(y))
    assert sorted(drawn) == sorted(float(v) for v in sk.V)
    for V, c in zip(sk.V, sk.classification):
        cls, y = drawn[float(V)]
        assert cls == c and c in CLASSES
        assert y == pytest.approx(sk_amplitude(float(V)), abs=1e-12)
    # a row's class is the decision of an independent spectrum of that superkink
    r = wave.solve_superkink(CubicLaw(A, B), float(sk.V[-1]), N=64, tol=1e-10)
    fr = floquet.spectrum(r)
    assert fr.classification == sk.classification[-1]
    assert fr.max_modulus == pytest.approx(float(sk.max_modulus[-1]), abs=1e-10)
    assert "kind='superkink'" in sc.python_code()
    assert "superkink branch view (N = 64, 4 V)" in sc.status.object


def test_a_click_on_a_superkink_sets_V_and_w_plus(superkinks):
    sc = superkinks
    sk, amp, _ = sc._sk_branch
    k = 1
    x, y = float(sk.V[k]), float(amp[k])
    xs, ys = sc.fig_sk.x_range, sc.fig_sk.y_range
    V0, w0 = sc.state.V, sc.state.w_plus
    sc._on_sk_tap(Tap(sc.fig_sk, x=x, y=y + 0.2 * (ys.end - ys.start)))
    assert (sc.state.V, sc.state.w_plus) == (V0, w0)  # away from every point: nothing
    sc._on_sk_tap(Tap(sc.fig_sk, x=x + 0.01 * (xs.end - xs.start), y=y))
    st = sc.state
    assert st.mode == "superkink" and st.problem() is None
    assert st.V == pytest.approx(x, abs=1e-12)
    assert v_sk(st.w_plus) == pytest.approx(x, abs=1e-12)  # V = V_SK(w₊), eq. cubic_cond2
    assert st.w_plus < B / (3 * abs(A))  # on the sweep's (lower) branch
