"""Simulations in the URL: every input of the Simulation scene (the kind of initial data, L,
t_end, w^l, w^r, w_B, A, the guard, the tracked sites) is in the link's ``sim=``, ``run=1`` when
its run is on screen; ``fig=`` leaves at the first change; a page built from the link shows the
same run."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")

from app.explorer import Explorer  # noqa: E402
from app.sim_url import format_sim, parse_sim  # noqa: E402
from app.url_state import state_from_url, url_query  # noqa: E402
from fpucore.errors import ParameterError  # noqa: E402


def test_the_sim_value_round_trips_and_bad_values_are_named():
    inputs = dict(kind="riemann", L=3600, t_end=300.0, guard="convex", w_left=4.6,
                  w_right=0.0, probes=(100, 200, 3000))  # fmt: skip
    text = format_sim(**inputs, w_B=1.0, A=6.0)  # the other kinds' data are not written
    assert text == (
        "riemann:L=3600,t_end=300.0,guard=convex,w_left=4.6,w_right=0.0,probes=100;200;3000"
    )
    assert parse_sim(text) == inputs
    g = dict(kind="gaussian", L=2400, t_end=200.0, guard="bounded", w_B=6.0, A=-6.0, probes=())
    assert parse_sim(format_sim(**g, w_left=1.0, w_right=2.0)) == g
    for bad, name in [
        ("wave:L=10", "sim"),
        ("riemann:L=30,t_end=1.0,guard=convex,w_left=4.6,w_right=0.0", "sim L"),
        ("riemann:L=300,t_end=1.0,guard=none,w_left=4.6,w_right=0.0", "sim guard"),
        ("riemann:L=300,t_end=1.0,guard=convex,w_left=4.6", "sim"),  # w_right missing
        ("gaussian:L=300,t_end=1.0,guard=convex,w_B=1.0,A=nan", "sim A"),
    ]:
        with pytest.raises(ParameterError) as exc:
            parse_sim(bad)
        assert exc.value.name == name, (bad, str(exc.value))
    st, errors = state_from_url({"tab": "simulation", "sim": "wave:L=1"})
    assert st.simulation == "" and errors and "sim" in errors[0]


def test_a_change_of_the_swdyn_run_leaves_the_figure_and_the_link_reproduces_it():
    ex = Explorer(lazy=True)
    ex.scene("paper").open("SWdyn")  # (a): w_B = 1, A = 6
    sc = ex.scene("simulation")
    assert sc.wait_idle(300.0) and sc.last_message is None, sc.last_message
    q = url_query(ex.state)
    assert q["fig"] == "SWdyn" and q["run"] == "1"
    assert parse_sim(q["sim"])["A"] == 6.0
    # panel (b): w_B = 6, A = −6 on a shorter run; fig= leaves at the first change
    sc.w_B.value = 6.0
    assert "fig" not in url_query(ex.state) and "run" not in url_query(ex.state)
    sc.A.value, sc.L.value, sc.t_end.value, sc.probes.value = -6.0, 600, 10.0, "300, 350"
    sc._want_run = True  # "Run simulation"
    sc.request()
    assert sc.wait_idle(300.0) and sc.last_message is None, sc.last_message
    q = url_query(ex.state)
    assert q["sim"] == "gaussian:L=600,t_end=10.0,guard=bounded,w_B=6.0,A=-6.0,probes=300;350"
    assert q["run"] == "1" and "fig" not in q
    # a fresh page from the link: the same widgets, the same run, the same drawn data
    st, errors = state_from_url(q)
    assert not errors and st.figure == ""
    ex2 = Explorer(st, lazy=True)
    sc2 = ex2.active_scene()
    sc2.request()  # the page has loaded: the active scene renders
    assert sc2.wait_idle(300.0) and sc2.last_message is None, sc2.last_message
    assert (sc2.kind.value, sc2.w_B.value, sc2.A.value, sc2.L.value, sc2.t_end.value) == (
        "gaussian", 6.0, -6.0, 600, 10.0)  # fmt: skip
    assert sc2.probes.value == "300, 350" and sc2._sim is not None
    assert sc2._sim[0] == sc._sim[0]  # the same request
    np.testing.assert_array_equal(sc2.r_last[1].data["y"], sc.r_last[1].data["y"])
    assert url_query(ex2.state) == q


def test_a_link_without_run_sets_the_inputs_and_waits_for_the_button():
    q = {"tab": "simulation", "sim": "riemann:L=400,t_end=2.0,guard=convex,w_left=4.6,"
         "w_right=0.0"}  # fmt: skip
    st, errors = state_from_url(q)
    assert not errors
    ex = Explorer(st, lazy=True)
    sc = ex.active_scene()
    sc.request()
    assert sc.wait_idle(60.0)
    assert (sc.kind.value, sc.L.value, sc.w_l.value) == ("riemann", 400, 4.6)
    assert sc._sim is None and "press 'Run simulation'" in (sc.last_message or "")
