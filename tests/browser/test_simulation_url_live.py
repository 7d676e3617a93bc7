"""A simulation link in a fresh browser: ``sim=`` (the Simulation scene's inputs) with ``run=1``
opens the scene with those widgets and runs it; a reload shows the same run (Fig. SWdyn (b)'s
data on a short chain: the initial dip reaches w_B + A = 0 exactly, eq. GaussIC)."""

from __future__ import annotations

import pytest
from browser_harness import query, source, wait_rendered

from app.sim_url import parse_sim

pytestmark = pytest.mark.browser

SIM = "gaussian:L=600,t_end=10.0,guard=bounded,w_B=6.0,A=-6.0,probes=300"


def sim_input(page, label: str) -> str:
    field = page.locator(".scene-simulation .bk-input-group", has_text=label).locator("input")
    return field.first.input_value()


def test_a_simulation_link_runs_the_same_simulation_after_a_reload(page):
    page.goto(f"{page.server}/main?tab=simulation&sim={SIM}&run=1")
    for attempt in range(2):  # the link, then a reload of the page
        text = wait_rendered(page, "simulation", 240.0)
        assert "Gaussian" in text and "run: gaussian" in text, text
        assert float(sim_input(page, "w_B")) == 6.0
        assert float(sim_input(page, "A (Gaussian)")) == -6.0
        assert int(sim_input(page, "L (sites)")) == 600
        first = source(page, "sim-profile-initial")
        assert len(first["y"]) == 600 and min(first["y"]) == 0.0
        q = query(page)
        assert parse_sim(q["sim"]) == parse_sim(SIM) and q.get("run") == "1", q
        if attempt == 0:
            page.reload()
