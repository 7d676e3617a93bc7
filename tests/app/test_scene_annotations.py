"""What the QC scenes mark for a reader: the force law's special points, each named (w₊, w₋,
w₋ˢ, and the Rayleigh line's other intersections w_C — a centre — and w_S — a saddle — of the
phase plane), and the phase plane's orbits through clicked points (pplane-style)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


def scene(key, **params):
    st = ExplorerState(**params)
    return st, BY_KEY[key](st)


def test_force_law_names_its_special_points():
    """At w₊ = 1, V = 5 (a = −1, b = 10): w₋ = 17/3, and the Rayleigh line of slope V² meets f
    again at the roots of a cubic (numpy's companion matrix here): the one with f′ > V² is the
    centre w_C, the one with f′ < V² the saddle w_S."""
    _, sc = scene("force", w_plus=1.0, V=5.0)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    d = sc.r_pts[1].data
    pts = dict(zip(d["label"], d["x"]))
    assert set(pts) == {"w₊", "w₋", "w₋ˢ", "w_C", "w_S"}
    assert pts["w₊"] == 1.0 and pts["w₋"] == pytest.approx(17 / 3, rel=1e-12)
    roots = np.roots([-1.0, 10.0, 1.0 - 25.0, 25.0 - 10.0])  # f(w) − f(1) − 25 (w − 1) = 0
    others = sorted(r.real for r in roots if abs(r.imag) < 1e-9 and abs(r.real - 1.0) > 1e-6)
    assert pts["w_C"] == pytest.approx(others[0], rel=1e-10)
    assert pts["w_S"] == pytest.approx(others[1], rel=1e-10)
    assert all(str(w).strip() for w in d["what"])  # every point says what it is (hover)
    labels = [item.label["value"] for item in sc.fig.legend[0].items]
    assert "special points (hover: values)" in labels


def test_a_click_draws_the_orbit_through_that_point_and_clear_removes_it():
    st, sc = scene("phase", w_plus=1.0, V=5.0)
    sc.refresh()
    assert sc.click(2.0, 0.0) and sc.wait_idle(30)
    sc.refresh()
    src = sc.r_clicked[1].data
    x, y = np.asarray(src["x"], float), np.asarray(src["y"], float)
    # the closed orbit around the centre w_C = 2.2087 through (2, 0)
    assert np.nanmin(x) == pytest.approx(2.0, abs=1e-9) and np.nanmax(x) < 2.5
    assert np.nanmax(y) > 0 > np.nanmin(y)
    assert any(k == "H on clicked orbits" and v < 1e-12 for k, v in sc.last_info.errors)
    assert "orbit_through" in sc.python_code()
    # the orbit follows V; a point outside the window is left out
    assert sc.click(100.0, 0.0)
    st.V = 5.05
    sc.wait_idle(30)
    sc.refresh()
    assert np.nanmin(np.asarray(sc.r_clicked[1].data["x"], float)) == pytest.approx(2.0, abs=1e-9)
    assert len(sc.r_seeds[1].data["x"]) == 1
    sc.clear_btn.clicks += 1  # "Clear orbits"
    sc.wait_idle(30)
    sc.refresh()
    assert len(sc.r_clicked[1].data["x"]) == 0 and sc.clicks == []
