"""Scene views and the Explorer composition, without a browser.

Each scene is rendered synchronously (``scene.refresh()``); what it shows is checked against
closed forms (the force-law scene's Rayleigh line passes through (w₋, f(w₋)) with w₋ = 17/3 at
w₊ = 1), and invalid input must give a message, never an exception.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("panel")

from app import compute  # noqa: E402
from app.explorer import Explorer  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402
from app.views.report import SceneMessage  # noqa: E402

QC_SCENES = ("force", "phase", "diagram")


def scene(key, **params):
    st = ExplorerState(**params)
    sc = {cls.key: cls for cls in SCENES}[key](st)
    return st, sc


@pytest.mark.parametrize("key", QC_SCENES)
def test_qc_scenes_render_with_error_and_time(key):
    _, sc = scene(key)
    info = sc.refresh()
    assert sc.last_message is None, sc.last_message
    assert info.errors and info.timings
    assert all(np.isfinite(v) and v < 1e-10 for _, v in info.errors)  # closed forms: round-off
    assert "**Error:**" in sc.status.object and "**Time:**" in sc.status.object
    assert sc.plot.object is not None and sc.plot.visible and not sc.alert.visible


def test_force_scene_draws_the_equal_area_construction():
    _, sc = scene("force", w_plus=1.0, V=5.0)
    sc.refresh()
    assert "w₋ = 5.66667" in sc.last_info.shown  # w₋ = 17/3
    assert "V_SK = 5.37484" in sc.last_info.shown  # 2√65/3
    name, buf = sc.download_data()
    text = buf.getvalue()
    assert name.endswith(".csv") and text.startswith("# superkink construction")
    assert "a=-1.0, b=10.0" in text and "fpucore" in text  # the header reproduces the view
    rows = np.loadtxt([ln for ln in text.splitlines() if not ln.startswith("#")][1:], delimiter=",")
    w, f, R = rows.T
    # R is the Rayleigh line through (w₊, f(w₊)) with slope V_SK² (eq. Rline)
    assert np.allclose(R, f[np.argmin(abs(w - 1))] * 0 + (1 + 10 - 1) + 4 * 65 / 9 * (w - 1))


def test_phase_scene_highlights_the_right_orbit():
    st, sc = scene("phase", w_plus=1.0, V=5.0)
    sc.refresh()
    assert sc.last_info.shown.startswith("tensile solitary wave (homoclinic)")
    st.V = 5.45  # above V_SK: compressive (Fig. pplane c)
    sc.refresh()
    assert sc.last_info.shown.startswith("compressive solitary wave")
    st.mode = "superkink"  # V = V_SK: heteroclinic pair (Fig. pplane b)
    sc.refresh()
    assert sc.last_info.shown.startswith("kink/antikink heteroclinic pair")


@pytest.mark.parametrize("key", [cls.key for cls in SCENES])
@pytest.mark.parametrize(
    "params", [{"V": 9.0}, {"w_plus": 10 / 3}, {"a": 2.0}, {"b": 1e-300, "w_plus": 0.0}]
)
def test_invalid_input_shows_a_message_not_a_traceback(key, params):
    st, sc = scene(key)
    st.param.update(**params)
    sc.refresh()
    # a message in the scene: instead of the plot, or above what is still valid to show
    # (force law and existence diagram do not depend on V)
    assert sc.alert.visible and sc.alert.object
    assert "Traceback" not in sc.alert.object
    assert "computation failed" not in sc.alert.object, sc.alert.object
    if sc.last_message is not None:
        assert not sc.plot.visible


def test_out_of_range_V_message_names_the_interval():
    _, sc = scene("phase", V=9.0)
    sc.refresh()
    assert "V=9 is out of range" in sc.last_message
    assert "4.242640687" in sc.last_message and "5.5" in sc.last_message  # (c₊, …, c₋)


def test_only_the_visible_scene_renders_and_hidden_ones_go_stale():
    ex = Explorer()
    for s in ex.scenes:
        s.stale = False
    ex.state.V = 5.1
    force, phase = ex.by_key["force"], ex.by_key["phase"]
    assert force.wait_idle(30) and force.renders == 1
    assert phase.renders == 0 and phase.stale  # hidden: not computed
    ex.tabs.active = 1  # the user opens the phase-plane tab
    assert ex.state.tab == "phase"
    assert phase.wait_idle(30) and phase.renders == 1 and not phase.stale
    assert force.renders == 1


def test_sliders_follow_the_theory():
    ex = Explorer()
    assert ex.V.start == pytest.approx(3 * math.sqrt(2)) and ex.V.end == pytest.approx(5.5)
    ex.state.mode = "superkink"
    assert ex.V.start == pytest.approx(4.78423, abs=1e-5)
    assert ex.V.value == pytest.approx(2 * math.sqrt(65) / 3)
    assert "V_SK = 5.374838499" in ex.ranges.object
    ex.state.V = 99.0  # invalid (e.g. from a URL): widget clipped, message in the sidebar
    assert ex.V.value == ex.V.end
    assert "out of range" in ex.ranges.object


def test_qc_profile_scene_never_solves_the_discrete_problem_when_off(monkeypatch):
    real_run = compute.run

    def boom(lw, req, **kw):  # the road of every job: a worker's is refused
        if not req.local:
            raise AssertionError("discrete solve triggered")
        return real_run(lw, req, **kw)

    monkeypatch.setattr(compute, "run", boom)
    _, sc = scene("profiles")
    sc.show_discrete.value = False
    sc.wait_idle(30)
    sc.refresh()
    assert sc.last_message is None and "QC only" in sc.status.object


def test_discrete_profile_is_overlaid_and_reports_its_errors():
    pytest.importorskip("fpucore.wave")
    _, sc = scene("profiles", N=200, tol=1e-10)
    info = sc.refresh()
    assert sc.last_message is None
    labels = dict(info.errors)
    assert labels["residual"] < 1e-8 and "dropped eq." in labels
    name, buf = sc.download_data()
    assert name == "profile_discrete.csv" and "residual=" in buf.getvalue()


def test_scene_message_is_shown():
    _, sc = scene("force")
    sc.render = lambda info: (_ for _ in ()).throw(SceneMessage("hello"))
    sc.refresh()
    assert sc.alert.visible and sc.alert.object == "hello"


def _run_simulation(sc, kind, **fields):
    sc.kind.value = kind
    for name, value in fields.items():
        getattr(sc, name).value = value
    sc._want_run = True  # what the "Run simulation" button sets
    return sc.refresh()


def test_simulation_scene_runs_the_papers_gaussian_data_and_reports_the_method():
    """The paper's Gaussian w_B = 1, A = 6 starts at w = 7 > β: the scene's default guard
    (bounded) runs it, notes the excursion, and finds the two solitary waves at ±5.2494 (the
    paper's speed, also in test_simulate_paper.py at L = 2400)."""
    _, sc = scene("simulation")
    info = _run_simulation(sc, "gaussian", L=800, t_end=60.0, w_B=1.0, A=6.0)
    assert sc.last_message is None, sc.last_message
    notes = " ".join(info.notes)
    assert "rkn12" in notes and "outside the convex interval" in notes
    speeds = sorted(w.velocity for w in sc._sim[-1].waves if w.kind == "solitary")
    assert speeds and speeds[0] == pytest.approx(-5.2494, abs=2e-3)
    assert speeds[-1] == pytest.approx(5.2494, abs=2e-3)


def test_simulation_scene_convex_guard_refuses_with_the_reason():
    _, sc = scene("simulation")
    sc.guard.value = "convex"
    _run_simulation(sc, "gaussian", L=400, t_end=5.0, w_B=1.0, A=6.0)
    assert sc.last_message and "initial strain max" in sc.last_message
    assert "bounded" in sc.last_message
