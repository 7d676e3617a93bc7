"""Tracked sites on the Simulation scene (Fig. Riemann1 (c)–(e)): a site's history w_k(t) from
the run against the traveling wave fpucore.wave computes at the velocity and background the
tracker measured — two independent computations that must meet at the wave's crest."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("panel")

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402
from app.views.simulation_table import last_to_pass  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


def riemann(L: int, t_end: float, probes: str):
    sc = BY_KEY["simulation"](ExplorerState(N=300))
    sc.kind.value = "riemann"
    sc.L.value, sc.t_end.value, sc.probes.value = L, t_end, probes
    sc._want_run = True  # the "Run simulation" button
    sc.refresh()
    return sc


def test_the_last_wave_to_pass_a_site_is_the_one_compared():
    # the paper's run at t = 300 (positions from its velocities, Riemann jump at n = 1800):
    # site 100 has seen only the superkink; site 200 the superkink, then the left DSW edge;
    # site 3000 the right DSW edge
    sk = SimpleNamespace(kind="superkink", velocity=-5.7209, position=1800 - 5.7209 * 300)
    left = SimpleNamespace(kind="dsw_edge", velocity=-5.6159, position=1800 - 5.6159 * 300)
    right = SimpleNamespace(kind="dsw_edge", velocity=4.6404, position=1800 + 4.6404 * 300)
    waves = [sk, left, right]
    assert last_to_pass(waves, 100, 300.0) is sk
    assert last_to_pass(waves, 200, 300.0) is left
    assert last_to_pass(waves, 3000, 300.0) is right
    assert last_to_pass(waves, 3500, 300.0) is None  # nothing has reached it


def test_a_tracked_site_meets_the_computed_wave_at_its_crest():
    # jump at n = 200; the right DSW edge (V ≈ 4.63 into w = 0) passes site 280 near t = 17
    sc = riemann(400, 20.0, "280")
    assert sc.last_message is None, sc.last_message
    assert sc.fig_probe[0].visible and not sc.fig_probe[1].visible
    assert "(c) site 280: DSW edge V = 4.6" in sc.fig_probe[0].title.text
    t, w = (np.asarray(sc.r_probe[0][1].data[k]) for k in ("x", "y"))
    tw, ww = (np.asarray(sc.r_probe_wave[0][1].data[k]) for k in ("x", "y"))
    assert tw.size > 10, "no wave drawn"
    # the wave solver's crest (its w(0)) and the simulated site's crest: same time, same height
    amp = float(ww.max() - ww.min())
    assert abs(float(t[np.argmax(w)]) - float(tw[np.argmax(ww)])) < 0.05
    assert abs(float(w.max()) - float(ww.max())) < 0.02 * amp
    # ... and the same pulse around it: the site's history at the wave's sample times (ξ = n − Vt)
    # from the front to just past the crest (behind it the DSW's next oscillation follows)
    k = int(np.argmax(ww))
    near = slice(max(k - 3, 0), k + 2)
    assert np.max(np.abs(np.interp(tw[near], t, w) - ww[near])) < 0.1 * amp
    assert "probes=(280,)" in sc.python_code() and "tw0 = wave.solve_solitary(" in sc.python_code()


def test_bad_tracked_sites_are_named():
    sc = riemann(300, 2.0, "100, x")
    assert "tracked sites" in sc.last_message and "100, x" in sc.last_message
    sc = riemann(300, 2.0, "500")  # beyond the chain: fpucore names the argument
    assert sc.last_message and "probes" in sc.last_message
